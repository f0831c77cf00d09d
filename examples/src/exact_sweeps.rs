//! Seed 003's experiments through the renderer: the `exact` soft-shadow method against
//! stochastic sampling on a scene whose occluders are polygons (the `soft-shadows exact`
//! example).
//!
//! Every render uses the scene's camera at the size asked, one sample per pixel (no
//! anti-aliasing, so that every method shades the same points), and times the soft-shadow
//! pass. The exact method is the reference: on such a scene its fractions are exact up to
//! rounding.
//!
//! * **Equal quality**: `stochastic:N` for each `N`, its RMSE against the exact fractions,
//!   and the samples (and time, at its measured cost per sample) that RMSE `1/255` needs,
//!   from a least-squares fit of `log RMSE` against `log N`.
//! * **Coherence**: the exact method with one tree per query (`exact:D:1`) against its groups.
//! * **Light size**: every area light scaled about its centre.
//! * **Light count**: `k × k` lights in place of every area light, either copies of it
//!   spread on a grid (the paper's experiment: lights of the same size, each casting its
//!   own shadows) or its `k × k` parts (the same total area).
//!
//! Both sweeps compare the exact method with `stochastic:N` at equal time and at equal
//! quality: the RMSE of the `N`-sample fractions against the exact ones, and the time
//! sampling would take to reach RMSE `1/255` at its measured cost per sample, its error
//! falling with `N` as the equal-quality fit found on the scene (stratified samples
//! converge faster than `N^-1/2` in a penumbra; `N^-1/2` where the fit has one run).
//! * **Peak memory**: the largest tree of each run, in nodes and bytes.

use std::fmt::Write as _;
use std::path::Path;

use beam_trace::mesh::Triangle;
use beam_trace::scene::{AaMode, AreaLight, Material, MeshSurface};
use beam_trace::shadow::exact::NODE_BYTES;
use beam_trace::shadow::{Patch, ShadowSpec};
use beam_trace::{Light, RenderOutput, Scene, render};

/// What to run.
#[derive(Clone, Debug)]
pub struct Options {
    /// Image width and height.
    pub size: (u32, u32),
    /// Samples of the stochastic runs of the equal-quality table.
    pub samples: Vec<u32>,
    /// Samples of the stochastic runs of the light sweeps.
    pub sweep_samples: u32,
    /// Multipliers of each light's side (its area grows with the square); none: no light
    /// size table.
    pub light_scales: Vec<f64>,
    /// Lights per side of each area light (`k × k`); none: no light count table.
    pub light_counts: Vec<u32>,
    /// How the lights of the light count table are placed.
    pub light_layout: LightLayout,
    /// Where to write the exact method's render of the scene (PNG), if anywhere.
    pub image: Option<std::path::PathBuf>,
}

/// One render's figures.
struct Run {
    /// Seconds of the soft-shadow pass.
    secs: f64,
    /// Per area light, per pixel, the visible fraction (NaN where nothing is shaded).
    fractions: Vec<Vec<f32>>,
    /// A counter of the soft-shadow pass.
    counters: Vec<(String, u64)>,
    /// Thread seconds of the exact method's phases, summed over the lights.
    phases: Vec<(String, f64)>,
    /// The image.
    image: beam_trace::Image,
}

impl Run {
    fn counter(&self, name: &str) -> u64 {
        self.counters
            .iter()
            .find(|(n, _)| n == name)
            .map_or(0, |(_, v)| *v)
    }

    fn phase_list(&self) -> String {
        let v: Vec<String> = self
            .phases
            .iter()
            .map(|(n, t)| format!("{n} {t:.2}"))
            .collect();
        v.join(", ")
    }
}

fn run(scene: &Scene, method: &str) -> Result<Run, String> {
    let mut s = scene.clone();
    s.settings.shadow_method = method.parse()?;
    eprintln!("  {method} ...");
    let out: RenderOutput =
        render(&s, &crate::pass_bars::PassBars::new(false)).map_err(|e| e.to_string())?;
    let pass = out
        .stats
        .pass("soft-shadows")
        .ok_or("the render has no soft-shadow pass")?;
    let mut phases: Vec<(String, f64)> = Vec::new();
    for light in &out.stats.lights {
        for (name, t) in &light.phases {
            match phases.iter_mut().find(|(n, _)| n == name) {
                Some((_, sum)) => *sum += t.as_secs_f64(),
                None => phases.push((name.clone(), t.as_secs_f64())),
            }
        }
    }
    let fractions = out.shadows.map(|m| m.fractions).unwrap_or_default();
    eprintln!("  {method}: {:.3} s", pass.time.as_secs_f64());
    Ok(Run {
        secs: pass.time.as_secs_f64(),
        fractions,
        counters: pass.counters.clone(),
        phases,
        image: out.image,
    })
}

/// RMSE and largest error of `a` against `b` over the pixels both shade, every light.
fn errors(a: &Run, b: &Run) -> (f64, f64) {
    let (mut sq, mut worst, mut n) = (0.0, 0.0f64, 0usize);
    for (fa, fb) in a.fractions.iter().zip(&b.fractions) {
        for (&x, &y) in fa.iter().zip(fb) {
            if x.is_nan() || y.is_nan() {
                continue;
            }
            let d = f64::from(x) - f64::from(y);
            sq += d * d;
            worst = worst.max(d.abs());
            n += 1;
        }
    }
    ((sq / n.max(1) as f64).sqrt(), worst)
}

/// The scene with every area light's patch changed by `f`, each into as many patches as
/// it returns (the light's power shared among them).
fn with_lights(scene: &Scene, f: impl Fn(&Patch) -> Vec<Patch>) -> Scene {
    let mut s = scene.clone();
    s.lights = scene
        .lights
        .iter()
        .flat_map(|l| match l {
            Light::Area(a) => {
                let parts = f(&a.patch);
                let share = 1.0 / parts.len() as f32;
                parts
                    .into_iter()
                    .map(|patch| {
                        Light::Area(AreaLight {
                            patch,
                            color: a.color.map(|c| c * share),
                        })
                    })
                    .collect()
            }
            other => vec![*other],
        })
        .collect();
    s
}

/// The patch scaled by `k` about its centre.
fn scaled(p: &Patch, k: f64) -> Patch {
    let (edge_u, edge_v) = (p.edge_u * k, p.edge_v * k);
    Patch {
        corner: p.center() - 0.5 * (edge_u + edge_v),
        edge_u,
        edge_v,
    }
}

/// Where the `k × k` lights of the light count table come from.
#[derive(Copy, Clone, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum LightLayout {
    /// Copies of each light, of its size, on a grid along its edges twice its larger side
    /// apart, centred on it (the paper's experiment: lights of the same size, each casting
    /// its own shadows).
    Spread,
    /// Each light cut into `k × k` parts of the same total area.
    Tiled,
}

impl LightLayout {
    /// The lights in place of `p`.
    fn lights(self, p: &Patch, k: u32) -> Vec<Patch> {
        match self {
            LightLayout::Spread => spread(p, k),
            LightLayout::Tiled => tiled(p, k),
        }
    }

    /// What the table says of the lights.
    fn describe(self) -> &'static str {
        match self {
            LightLayout::Spread => {
                "copies of each light on a grid twice its side apart, the power shared"
            }
            LightLayout::Tiled => "each light cut into `k × k` lights, the same area and power",
        }
    }
}

/// `k × k` copies of the patch on a grid along its edges, their centres twice its larger
/// side apart, the grid centred on it.
fn spread(p: &Patch, k: u32) -> Vec<Patch> {
    let side = p.edge_u.length().max(p.edge_v.length());
    let (u, v) = (
        p.edge_u.normalize_or_zero() * 2.0 * side,
        p.edge_v.normalize_or_zero() * 2.0 * side,
    );
    let mid = 0.5 * f64::from(k - 1);
    let mut out = Vec::new();
    for i in 0..k {
        for j in 0..k {
            let shift = (f64::from(i) - mid) * u + (f64::from(j) - mid) * v;
            out.push(Patch {
                corner: p.corner + shift,
                edge_u: p.edge_u,
                edge_v: p.edge_v,
            });
        }
    }
    out
}

/// The patch cut into `k × k` equal patches.
fn tiled(p: &Patch, k: u32) -> Vec<Patch> {
    let step = 1.0 / f64::from(k);
    let mut out = Vec::new();
    for i in 0..k {
        for j in 0..k {
            let (u, v) = (f64::from(i) * step, f64::from(j) * step);
            out.push(p.part(u, u + step, v, v + step));
        }
    }
    out
}

/// Least-squares `log RMSE = a + b log N` through the runs: `(a, b)`, where there are two
/// runs or more with an error.
fn fit(points: &[(u32, f64)]) -> Option<(f64, f64)> {
    let pts: Vec<(f64, f64)> = points
        .iter()
        .filter(|(_, e)| *e > 0.0)
        .map(|&(n, e)| (f64::from(n).ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let m = pts.len() as f64;
    let (sx, sy) = pts
        .iter()
        .fold((0.0, 0.0), |(sx, sy), (x, y)| (sx + x, sy + y));
    let (mx, my) = (sx / m, sy / m);
    let sxy: f64 = pts.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = pts.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    let b = sxy / sxx;
    Some((my - b * mx, b))
}

/// The `N` where the fit of [`fit`] through the runs reaches `target`, where it falls.
fn samples_for(points: &[(u32, f64)], target: f64) -> Option<f64> {
    let (a, b) = fit(points)?;
    (b < 0.0).then(|| ((target.ln() - a) / b).exp())
}

/// The generated stand-ins for the paper's models.
#[derive(Copy, Clone, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum StandIn {
    /// A lumpy ball and a canopy of leaves ([`crate::polygon_scene::lumpy_ball_and_canopy`]):
    /// curved, every triangle its own face.
    Canopy,
    /// A furnished hall ([`crate::polygon_scene::furnished_hall`]): planar faces, each
    /// triangulated, many small parts.
    Hall,
}

/// The stand-in `kind` of about `triangles` triangles from `seed` on an implicit floor
/// `y = 0`, under a square light of side 1 at height 4 above the origin, seen from above
/// and to the side.
///
/// # Errors
/// None in practice: the base scene is fixed text.
pub fn generated_scene(kind: StandIn, triangles: usize, seed: u64) -> Result<Scene, String> {
    // The meshes, and the view: the canopy's from above and to the side, the hall's with
    // its floor just wider than the furniture, which fills the picture.
    let (meshes, (eye, look_y, floor)) = match kind {
        StandIn::Canopy => {
            let (ball, leaves) = crate::polygon_scene::lumpy_ball_and_canopy(triangles, seed);
            (
                vec![
                    ("ball", ball, [0.85, 0.45, 0.25]),
                    ("canopy", leaves, [0.3, 0.6, 0.3]),
                ],
                ((3.6, 5.4), 0.7, 4.0),
            )
        }
        StandIn::Hall => {
            let (furniture, half) = crate::polygon_scene::furnished_hall(triangles, seed);
            (
                vec![("furniture", furniture, [0.7, 0.55, 0.4])],
                ((1.5 * half + 1.0, 2.1 * half + 1.5), 0.0, half + 1.0),
            )
        }
    };
    let text = format!(
        r#"
        background = [0.08, 0.09, 0.12]
        ambient = 0.12
        [camera]
        eye = [0.0, {ey}, {ez}]
        look_at = [0.0, {ly}, 0.0]
        up = [0.0, 1.0, 0.0]
        fov = 45.0
        [[surfaces]]
        name = "floor"
        formula = "y"
        bounds = [[-{f}, -0.5, -{f}], [{f}, 0.0, {f}]]
        clip = true
        material = {{ color = [0.75, 0.75, 0.72], specular = 0.05, shininess = 8.0 }}
        [[lights]]
        type = "area"
        center = [0.0, 4.0, 0.0]
        size = 1.0
        normal = "y"
    "#,
        ey = eye.0,
        ez = eye.1,
        ly = look_y,
        f = floor,
    );
    let mut scene = Scene::from_toml(&text, "generated.toml", None).map_err(|e| e.to_string())?;
    scene.meshes = meshes
        .into_iter()
        .map(|(name, tris, color)| MeshSurface {
            name: name.into(),
            triangles: tris
                .into_iter()
                .map(|[a, b, c]| Triangle::new(a, b, c))
                .filter(|t| !t.is_degenerate())
                .collect(),
            material: Material {
                color,
                ..Material::default()
            },
        })
        .collect();
    Ok(scene)
}

/// The experiments on the scene file `path` (or the generated scene of
/// [`generated_scene`] with `generate = Some((kind, triangles, seed))`), as a markdown
/// report.
///
/// # Errors
/// A scene that cannot be read or rendered, or a method the spec parser refuses.
pub fn report(
    path: &Path,
    generate: Option<(StandIn, usize, u64)>,
    o: &Options,
) -> Result<String, String> {
    let (mut scene, name) = match generate {
        Some((kind, n, seed)) => (
            generated_scene(kind, n, seed)?,
            match kind {
                StandIn::Canopy => {
                    format!("a lumpy ball and canopy of about {n} triangles (seed {seed})")
                }
                StandIn::Hall => format!("a furnished hall of about {n} triangles (seed {seed})"),
            },
        ),
        None => (
            Scene::load(path).map_err(|e| e.to_string())?,
            format!("`{}`", path.display()),
        ),
    };
    scene.camera = scene
        .camera
        .resized(o.size.0, o.size.1)
        .map_err(|e| e.to_string())?;
    scene.settings.aa = Some(AaMode::None);
    let triangles: usize = scene.meshes.iter().map(|m| m.triangles.len()).sum();
    let lights = scene
        .lights
        .iter()
        .filter(|l| l.as_area().is_some())
        .count();
    let mut md = String::new();
    let _ = writeln!(
        md,
        "{name}: {triangles} triangles, {lights} area light(s), {} × {}, one sample per pixel, \
         {} thread(s); times are the soft-shadow pass's.\n",
        o.size.0,
        o.size.1,
        rayon::current_num_threads()
    );
    let exact = run(&scene, "exact")?;
    if let Some(path) = &o.image {
        exact.image.write_png(path).map_err(|e| e.to_string())?;
        eprintln!("wrote {}", path.display());
    }
    let single = run(
        &scene,
        &format!("exact:{}:1", ShadowSpec::DEFAULT_EXACT_DEPTH),
    )?;
    let triangles_only = run(
        &scene,
        &format!(
            "exact:{}:{}:triangles",
            ShadowSpec::DEFAULT_EXACT_DEPTH,
            ShadowSpec::MAX_EXACT_GROUP
        ),
    )?;
    let _ = writeln!(
        md,
        "**The exact method, its coherence and its faces**\n\n| method | time (s) | occluders \
         (faces / triangles) | BSP nodes | peak nodes | peak memory (MB) | thread s per phase |\n\
         |---|---:|---:|---:|---:|---:|---|"
    );
    for (name, r) in [
        ("`exact` (groups, faces)", &exact),
        ("`exact:D:1` (a tree per query)", &single),
        (
            "`exact:D:G:triangles` (triangles, not faces)",
            &triangles_only,
        ),
    ] {
        let peak = r.counter("bsp_peak_nodes");
        let _ = writeln!(
            md,
            "| {name} | {:.3} | {} / {} | {} | {peak} | {:.2} | {} |",
            r.secs,
            r.counter("shaft_faces"),
            r.counter("shaft_triangles"),
            r.counter("bsp_nodes"),
            (peak as usize * NODE_BYTES) as f64 / 1e6,
            r.phase_list()
        );
    }
    let _ = writeln!(
        md,
        "\nWithout coherence the method takes {:.2} times as long (the paper: 16 to 48 times); \
         with the triangles as occluders instead of the faces, {:.2} times.\n",
        single.secs / exact.secs,
        triangles_only.secs / exact.secs
    );
    let _ = writeln!(
        md,
        "**Equal quality** (RMSE against the exact fractions)\n\n| method | time (s) | × exact | \
         RMSE | largest error |\n|---|---:|---:|---:|---:|"
    );
    let mut fit_points = Vec::new();
    let mut per_sample = 0.0;
    for &n in &o.samples {
        let r = run(&scene, &format!("stochastic:{n}"))?;
        let (rmse, worst) = errors(&r, &exact);
        eprintln!("    RMSE {rmse:.5}, largest error {worst:.3}");
        fit_points.push((n, rmse));
        per_sample = r.secs / f64::from(n);
        let _ = writeln!(
            md,
            "| `stochastic:{n}` | {:.3} | {:.2} | {rmse:.5} | {worst:.3} |",
            r.secs,
            r.secs / exact.secs
        );
    }
    match samples_for(&fit_points, 1.0 / 255.0) {
        Some(n) => {
            let _ = writeln!(
                md,
                "\nRMSE 1/255 needs about {n:.0} samples (fit of log RMSE against log N), about \
                 {:.2} s at the largest run's cost per sample: {:.2} times the exact method's \
                 time (the paper: about 7.6 times at equal quality).\n",
                n * per_sample,
                n * per_sample / exact.secs
            );
        }
        None => {
            let _ = writeln!(md, "\n(The runs do not fit a falling RMSE.)\n");
        }
    }
    // How the sweeps' sampling error falls with the samples: the fit's slope.
    let slope = fit(&fit_points)
        .map(|(_, b)| b)
        .filter(|b| *b < 0.0)
        .unwrap_or(-0.5);
    if !o.light_scales.is_empty() || !o.light_counts.is_empty() {
        let _ = writeln!(
            md,
            "In the sweeps, sampling's error is taken to fall as `N^{slope:.2}` for the samples \
             RMSE 1/255 needs.\n"
        );
    }
    if !o.light_scales.is_empty() {
        light_size(&mut md, &scene, o, slope)?;
    }
    if !o.light_counts.is_empty() {
        light_count(&mut md, &scene, lights, o, slope)?;
    }
    Ok(md)
}

/// The light size table: every light scaled by each of `o.light_scales`.
/// `slope`: how the sampling error falls with the samples (`RMSE ∝ N^slope`).
fn light_size(md: &mut String, scene: &Scene, o: &Options, slope: f64) -> Result<(), String> {
    let _ = writeln!(
        md,
        "**Light size** (each light's side times `k`, its area times `k²`)\n\n| k | area | exact \
         (s) | BSP nodes | peak nodes | {} |\n|---:|---:|---:|---:|---:|{}",
        Versus::header(o.sweep_samples),
        Versus::RULE
    );
    for &k in &o.light_scales {
        let s = with_lights(scene, |p| vec![scaled(p, k)]);
        let e = run(&s, "exact")?;
        let versus = Versus::of(&e, &s, o.sweep_samples, slope)?;
        let _ = writeln!(
            md,
            "| {k} | {:.0}× | {:.3} | {} | {} | {versus} |",
            k * k,
            e.secs,
            e.counter("bsp_nodes"),
            e.counter("bsp_peak_nodes"),
        );
    }
    Ok(())
}

/// The light count table: `k × k` lights in place of each of the scene's `lights` area
/// lights for each of `o.light_counts`, placed as `o.light_layout` says; `slope` as for
/// [`light_size`].
fn light_count(
    md: &mut String,
    scene: &Scene,
    lights: usize,
    o: &Options,
    slope: f64,
) -> Result<(), String> {
    let _ = writeln!(
        md,
        "\n**Light count** ({})\n\n| lights | exact (s) | BSP nodes | peak nodes | {} |\n\
         |---:|---:|---:|---:|{}",
        o.light_layout.describe(),
        Versus::header(o.sweep_samples),
        Versus::RULE
    );
    for &k in &o.light_counts {
        let s = with_lights(scene, |p| o.light_layout.lights(p, k));
        let e = run(&s, "exact")?;
        let versus = Versus::of(&e, &s, o.sweep_samples, slope)?;
        let _ = writeln!(
            md,
            "| {} | {:.3} | {} | {} | {versus} |",
            k * k * lights as u32,
            e.secs,
            e.counter("bsp_nodes"),
            e.counter("bsp_peak_nodes"),
        );
    }
    Ok(())
}

/// A sweep row's comparison with sampling: `stochastic:N`'s time and RMSE against the
/// exact run, and the time RMSE `1/255` would take it (its error falling as `N^slope`, at
/// its cost per sample), each over the exact method's time.
struct Versus {
    samples: u32,
    secs: f64,
    exact_secs: f64,
    rmse: f64,
    slope: f64,
}

impl Versus {
    const RULE: &'static str = "---:|---:|---:|---:|---:|";

    /// The columns' heads, for `samples` samples.
    fn header(samples: u32) -> String {
        format!(
            "`stochastic:{samples}` (s) | stochastic / exact | its RMSE | RMSE 1/255: samples \
             | RMSE 1/255: sampling / exact"
        )
    }

    /// `stochastic:samples` on `scene`, against its exact run `exact`, its error taken to
    /// fall as `N^slope`.
    fn of(exact: &Run, scene: &Scene, samples: u32, slope: f64) -> Result<Versus, String> {
        let r = run(scene, &format!("stochastic:{samples}"))?;
        Ok(Versus {
            samples,
            secs: r.secs,
            exact_secs: exact.secs,
            rmse: errors(&r, exact).0,
            slope,
        })
    }

    /// The samples that RMSE `1/255` needs.
    fn equal_quality_samples(&self) -> f64 {
        f64::from(self.samples) * (self.rmse * 255.0).powf(-1.0 / self.slope)
    }
}

impl std::fmt::Display for Versus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let n = self.equal_quality_samples();
        let per_sample = self.secs / f64::from(self.samples);
        write!(
            f,
            "{:.3} | {:.2} | {:.5} | {n:.0} | {:.2}",
            self.secs,
            self.secs / self.exact_secs,
            self.rmse,
            n * per_sample / self.exact_secs
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fit_finds_the_samples_of_a_power_law() {
        // RMSE = 0.5 / sqrt(N): 1/255 at N = (127.5)².
        let pts: Vec<(u32, f64)> = [16, 64, 256]
            .iter()
            .map(|&n| (n, 0.5 / f64::from(n).sqrt()))
            .collect();
        let n = samples_for(&pts, 1.0 / 255.0).unwrap();
        assert!((n - 127.5 * 127.5).abs() < 1e-6 * n, "{n}");
        assert!(samples_for(&pts[..1], 0.01).is_none());
    }

    #[test]
    fn tiles_and_scales_keep_the_light_where_it_was() {
        let p = Patch::square(glam::DVec3::new(1.0, 3.0, -2.0), 2.0, 1);
        let parts = tiled(&p, 3);
        assert_eq!(parts.len(), 9);
        let area: f64 = parts.iter().map(Patch::area).sum();
        assert!((area - p.area()).abs() < 1e-12);
        let big = scaled(&p, 10.0);
        assert!((big.area() - 100.0 * p.area()).abs() < 1e-9);
        assert!((big.center() - p.center()).length() < 1e-12);
    }

    #[test]
    fn spread_lights_keep_their_size_on_a_grid_around_the_light() {
        let p = Patch::square(glam::DVec3::new(1.0, 3.0, -2.0), 2.0, 1);
        let copies = spread(&p, 3);
        assert_eq!(copies.len(), 9);
        for c in &copies {
            assert!((c.area() - p.area()).abs() < 1e-12);
        }
        let mean = copies
            .iter()
            .fold(glam::DVec3::ZERO, |m, c| m + c.center() / 9.0);
        assert!((mean - p.center()).length() < 1e-12);
        // Neighbours twice the side apart: they do not overlap.
        let gap = (copies[1].center() - copies[0].center()).length();
        assert!((gap - 4.0).abs() < 1e-12, "{gap}");
        assert_eq!(spread(&p, 1), vec![p]);
    }

    #[test]
    fn equal_quality_scales_the_samples_by_the_squared_error() {
        let v = Versus {
            samples: 4,
            secs: 2.0,
            exact_secs: 1.0,
            rmse: 2.0 / 255.0,
            slope: -0.5,
        };
        // Twice the target error: four times the samples, 16 in 8 s.
        assert!((v.equal_quality_samples() - 16.0).abs() < 1e-9);
        assert!(v.to_string().ends_with("| 16 | 8.00"), "{v}");
        // Falling as `N^-1`: twice the samples.
        let fast = Versus { slope: -1.0, ..v };
        assert!((fast.equal_quality_samples() - 8.0).abs() < 1e-9);
    }
}
