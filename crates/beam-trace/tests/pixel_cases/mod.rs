//! The pixel cases, shared by every backend's test suite (beam-trace's `tests/pixels.rs`
//! for the CPU, gpu-backend's for the GPU): a feature the beams see is never lost in the
//! default primary mode (with its default anti-aliasing, and without any), and each pixel's
//! coverage bounds contain its true coverage
//! (computed analytically for thin cylinders and a sphere smaller than a pixel, by dense
//! point sampling for the drop's neck). Each case takes the renderer to test.

use beam_trace::scene::{AaMode, PrimaryMode};
use beam_trace::{Camera, Coverage, RenderOutput, Scene};
use glam::{DVec2, DVec3};

/// A renderer under test.
pub type Render<'a> = &'a dyn Fn(&Scene) -> RenderOutput;

/// The `#[test]` functions of every case, each run by `$with`, a function that takes a case
/// (`fn(Render<'_>)`) and runs it with the backend under test.
macro_rules! pixel_tests {
    ($with:path) => {
        pixel_tests!(
            $with:
            wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross,
            point_rays_lose_the_wire_the_beams_keep,
            two_wires_crossing_inside_a_pixel_both_appear,
            a_sphere_smaller_than_a_pixel_has_its_coverage_bounded,
            the_drops_neck_is_kept_wherever_dense_rays_see_it,
            rays_at_the_depth_limit_estimate_an_edges_share,
            a_hard_shadows_edge_is_anti_aliased
        );
    };
    ($with:path: $($case:ident),+) => {
        $(
            #[test]
            fn $case() {
                $with(pixel_cases::$case);
            }
        )+
    };
}

const W: u32 = 32;
const H: u32 = 24;
const EYE_Z: f64 = 10.0;
const FOV: f64 = 20.0;

/// A scene of `surfaces` (TOML `[[surfaces]]` tables) seen from `(0, 0, 10)` towards the
/// origin, no lights (a hit pixel shows its material's colour), black background.
fn scene(surfaces: &str, render_settings: &str) -> Scene {
    let text = format!(
        r#"
background = [0.0, 0.0, 0.0]

[camera]
eye = [0.0, 0.0, {EYE_Z}]
look_at = [0.0, 0.0, 0.0]
fov = {FOV}
width = {W}
height = {H}

{surfaces}

[render]
{render_settings}
"#
    );
    Scene::from_toml(&text, "pixels.toml", None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// Where the ray through the continuous pixel position `(px, py)` meets the plane `z = 0`.
fn on_plane(cam: &Camera, px: f64, py: f64) -> DVec2 {
    let r = cam.ray(px, py);
    let t = -r.origin.z / r.dir.z;
    let p = r.at(t);
    DVec2::new(p.x, p.y)
}

/// The world size of a pixel on the plane `z = 0`.
fn pixel_size(cam: &Camera) -> f64 {
    on_plane(cam, 1.0, 0.0).distance(on_plane(cam, 0.0, 0.0))
}

/// The signed distances, in pixels, of a pixel's corners on `z = 0` from the line through
/// `c` along `d` (unit).
fn corner_distances(cam: &Camera, x: u32, y: u32, c: DVec2, d: DVec2) -> [f64; 4] {
    let n = DVec2::new(-d.y, d.x);
    let s = pixel_size(cam);
    let (x, y) = (f64::from(x), f64::from(y));
    [(x, y), (x + 1.0, y), (x, y + 1.0), (x + 1.0, y + 1.0)]
        .map(|(px, py)| (on_plane(cam, px, py) - c).dot(n) / s)
}

/// The coverage bounds are bounds: `0 <= proven <= truth <= possible <= 1`.
fn assert_bounds(cov: &Coverage, truth: f64, tolerance: f64, what: &str) {
    assert!(
        0.0 <= cov.proven && cov.proven <= cov.possible && cov.possible <= 1.0,
        "{what}: {cov:?} out of order"
    );
    assert!(
        f64::from(cov.proven) <= truth + tolerance && truth - tolerance <= f64::from(cov.possible),
        "{what}: true coverage {truth} outside {cov:?}"
    );
}

/// A cylinder of radius `r` along the direction at `angle` degrees in the plane `z = 0`,
/// through `c`, in the colour `color`.
fn wire(name: &str, r: f64, angle: f64, c: DVec2, color: [f32; 3]) -> String {
    format!(
        r#"
[[surfaces]]
name = "{name}"
formula = "y^2 + z^2 - r^2"
params = {{ r = {r:e} }}
bounds = [[-4.0, -0.001, -0.001], [4.0, 0.001, 0.001]]
transform = {{ rotate = [0.0, 0.0, {angle}], translate = [{}, {}, 0.0] }}
material = {{ color = [{}, {}, {}] }}
"#,
        c.x, c.y, color[0], color[1], color[2]
    )
}

fn camera() -> Camera {
    Camera::new(
        DVec3::new(0.0, 0.0, EYE_Z),
        DVec3::ZERO,
        DVec3::Y,
        FOV,
        W,
        H,
    )
    .expect("a valid camera")
}

/// The pixels a line through `c` along the direction at `angle` degrees crosses clearly
/// (corners on both sides by more than `margin` pixels), and those it clearly misses
/// (every corner further than `margin`).
fn crossed_and_missed(angle: f64, c: DVec2, margin: f64) -> (Vec<usize>, Vec<usize>) {
    let cam = camera();
    let d = DVec2::new(angle.to_radians().cos(), angle.to_radians().sin());
    let (mut crossed, mut missed) = (Vec::new(), Vec::new());
    for y in 0..H {
        for x in 0..W {
            let s = corner_distances(&cam, x, y, c, d);
            let (lo, hi) = s
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            let i = (y * W + x) as usize;
            if lo < -margin && hi > margin {
                crossed.push(i);
            } else if lo > margin || hi < -margin {
                missed.push(i);
            }
        }
    }
    (crossed, missed)
}

/// Wires of radius 1e-6 of a pixel at several angles over an empty background.
pub fn wires_of_a_millionth_of_a_pixel_appear_in_every_pixel_they_cross(run: Render<'_>) {
    let cam = camera();
    let r = 1e-6 * pixel_size(&cam);
    // Off the pixel grid's lines, so that no pixel edge lies along a wire.
    let c = on_plane(&cam, 16.37, 12.21);
    for angle in [0.0, 17.0, 45.0, 72.0, 90.0, 133.0] {
        let s = scene(&wire("wire", r, angle, c, [1.0, 0.0, 0.0]), "");
        assert_eq!(
            s.settings.primary,
            PrimaryMode::ScreenBoxes,
            "the default mode"
        );
        let out = run(&s);
        let (crossed, missed) = crossed_and_missed(angle, c, 1e-3);
        assert!(crossed.len() >= 24, "{angle}°: the wire crosses the view");
        for &i in &crossed {
            assert!(
                out.image.pixels[i][0] > 0.0,
                "{angle}°: pixel {i} crossed by the wire does not show it"
            );
            // A share of at most 2r · (the pixel's diagonal) / (its area) is covered.
            let truth = 2e-6 * std::f64::consts::SQRT_2;
            assert_bounds(
                &out.coverage[i],
                truth,
                1e-6,
                &format!("{angle}° pixel {i}"),
            );
            assert!(out.coverage[i].possible > 0.0);
        }
        for &i in &missed {
            assert_bounds(&out.coverage[i], 0.0, 0.0, &format!("{angle}° pixel {i}"));
        }
    }
}

/// The thesis's point rays per Undecided pixel lose the wire the beams keep.
pub fn point_rays_lose_the_wire_the_beams_keep(run: Render<'_>) {
    // The thesis's fixed rays per Undecided pixel: a wire between the rays is lost.
    let cam = camera();
    let r = 1e-6 * pixel_size(&cam);
    let c = on_plane(&cam, 16.37, 12.21);
    let mut s = scene(&wire("wire", r, 17.0, c, [1.0, 0.0, 0.0]), "");
    s.settings.primary = PrimaryMode::ScreenRays;
    let rays = run(&s);
    let (crossed, _) = crossed_and_missed(17.0, c, 1e-3);
    let shown = crossed
        .iter()
        .filter(|&&i| rays.image.pixels[i][0] > 0.0)
        .count();
    assert!(
        shown < crossed.len() / 2,
        "9 point rays see the wire in {shown} of {} pixels",
        crossed.len()
    );
}

/// Two wires crossing inside one pixel: each shows in every pixel it crosses.
pub fn two_wires_crossing_inside_a_pixel_both_appear(run: Render<'_>) {
    let cam = camera();
    let r = 1e-6 * pixel_size(&cam);
    let c = on_plane(&cam, 16.41, 12.58);
    let surfaces = format!(
        "{}{}",
        wire("red", r, 20.0, c, [1.0, 0.0, 0.0]),
        wire("green", r, 110.0, c, [0.0, 1.0, 0.0])
    );
    let s = scene(&surfaces, "undecided_depth = 2");
    let out = run(&s);
    for (angle, channel) in [(20.0, 0), (110.0, 1)] {
        let (crossed, _) = crossed_and_missed(angle, c, 1e-3);
        for &i in &crossed {
            assert!(
                out.image.pixels[i][channel] > 0.0,
                "pixel {i} crossed by the wire at {angle}° does not show it"
            );
        }
    }
    // The pixel where they cross shows both.
    let i = (12 * W + 16) as usize;
    assert!(out.image.pixels[i][0] > 0.0 && out.image.pixels[i][1] > 0.0);
}

/// A sphere smaller than a pixel: shown, with bounds around its analytic coverage.
pub fn a_sphere_smaller_than_a_pixel_has_its_coverage_bounded(run: Render<'_>) {
    let cam = camera();
    let centre = on_plane(&cam, 16.5, 12.5);
    let radius = 0.3 * pixel_size(&cam);
    let surfaces = format!(
        r#"
[[surfaces]]
name = "grain"
formula = "x^2 + y^2 + z^2 - r^2"
params = {{ r = {radius:e} }}
bounds = [[{x0}, {y0}, {z0}], [{x1}, {y1}, {z1}]]
transform = {{ translate = [{cx}, {cy}, 0.0] }}
material = {{ color = [1.0, 1.0, 1.0] }}
"#,
        x0 = -radius,
        y0 = -radius,
        z0 = -radius,
        x1 = radius,
        y1 = radius,
        z1 = radius,
        cx = centre.x,
        cy = centre.y,
    );
    // The cone of rays from the eye touching the sphere has half-angle asin(R / d); its
    // disc on the image plane (unit distance) has radius tan(asin(R / d)), in pixels divided
    // by the pixel's size there. Off the axis by half a pixel at distance 10, the disc is an
    // ellipse within 1e-5 of that circle.
    let d = DVec3::new(centre.x, centre.y, 0.0).distance(DVec3::new(0.0, 0.0, EYE_Z));
    let rho = (radius / d).asin().tan() / (2.0 * (0.5 * FOV.to_radians()).tan() / f64::from(H));
    let truth = std::f64::consts::PI * rho * rho;
    for depth in [0, 1, 4] {
        let s = scene(&surfaces, &format!("undecided_depth = {depth}"));
        let out = run(&s);
        let i = (12 * W + 16) as usize;
        assert!(
            out.image.pixels[i][0] > 0.0,
            "depth {depth}: the grain is shown"
        );
        assert_bounds(&out.coverage[i], truth, 1e-4, &format!("depth {depth}"));
        if depth == 4 {
            // Deep enough for informative bounds: parts inside the disc proven covered,
            // parts outside it proven missed.
            let c = out.coverage[i];
            assert!(c.proven > 0.05 && c.possible < 0.8, "{c:?} around {truth}");
        }
        for (k, cov) in out.coverage.iter().enumerate() {
            if k != i {
                assert_bounds(cov, 0.0, 0.0, &format!("depth {depth} pixel {k}"));
            }
        }
    }
}

/// The drop's neck: kept wherever 64 point rays per pixel see it.
pub fn the_drops_neck_is_kept_wherever_dense_rays_see_it(run: Render<'_>) {
    let size = 32;
    let mut ours = Scene::catalog("drop", size, size).expect("a catalog surface");
    // No lights: a pixel's colour is its material's colour times the share of its samples
    // that hit, so 64 point rays per pixel measure its coverage.
    ours.lights.clear();
    ours.background = [0.0; 3];
    let colour = ours.geometry.leaves()[0].material.color[0];
    let mut dense = ours.clone();
    dense.settings.aa = Some(AaMode::Supersample(8));
    let ours = run(&ours);
    let dense = run(&dense);
    let mut seen = 0;
    for i in 0..(size * size) as usize {
        let share = f64::from(dense.image.pixels[i][0] / colour);
        let cov = ours.coverage[i];
        assert!(cov.proven <= cov.possible, "pixel {i}: {cov:?}");
        if share > 0.0 {
            seen += 1;
            assert!(
                cov.possible > 0.0,
                "pixel {i} seen by point rays, proven missed"
            );
            assert!(
                ours.image.pixels[i][0] > 0.0,
                "pixel {i} seen by point rays is lost"
            );
        }
        if cov.proven >= 1.0 {
            assert!(
                (share - 1.0).abs() < 1e-5,
                "pixel {i} proven covered: {share}"
            );
        }
    }
    assert!(seen > 0);
}

/// A bar a few pixels wide crossing the view at an angle, with interval anti-aliasing to
/// depth 2: where its parts at the limit are undecided, `M × M` stratified rays estimate
/// the share of each that the bar covers. Over the bar's edge pixels the image (white on
/// black, unlit: a pixel's value is the bar's share of its samples) comes closer to the
/// true coverage with 4 × 4 rays than with the central ray alone, and every pixel's
/// coverage bounds hold.
pub fn rays_at_the_depth_limit_estimate_an_edges_share(run: Render<'_>) {
    let cam = camera();
    let ps = pixel_size(&cam);
    let (angle, r) = (23.0f64, 2.3 * ps);
    let c = on_plane(&cam, 15.8, 12.3);
    let surfaces = format!(
        r#"
[[surfaces]]
name = "bar"
formula = "y^2 + z^2 - r^2"
params = {{ r = {r:e} }}
bounds = [[-4.0, {lo}, {lo}], [4.0, {hi}, {hi}]]
transform = {{ rotate = [0.0, 0.0, {angle}], translate = [{cx}, {cy}, 0.0] }}
material = {{ color = [1.0, 1.0, 1.0] }}
"#,
        lo = -1.5 * r,
        hi = 1.5 * r,
        cx = c.x,
        cy = c.y,
    );
    // The true coverage of each pixel by the bar's silhouette on `z = 0` (within 1e-3 of a
    // strip of half-width r there, seen from 10 away), by 64 × 64 points per pixel.
    let d = DVec2::new(angle.to_radians().cos(), angle.to_radians().sin());
    let n = DVec2::new(-d.y, d.x);
    let k = 64;
    let truth: Vec<f64> = (0..W * H)
        .map(|i| {
            let (x, y) = (f64::from(i % W), f64::from(i / W));
            let inside = (0..k * k)
                .filter(|j| {
                    let (u, v) = ((j % k) as f64 + 0.5, (j / k) as f64 + 0.5);
                    let p = on_plane(&cam, x + u / k as f64, y + v / k as f64);
                    (p - c).dot(n).abs() <= r
                })
                .count();
            inside as f64 / (k * k) as f64
        })
        .collect();
    let edge: Vec<usize> = (0..truth.len())
        .filter(|&i| truth[i] > 0.02 && truth[i] < 0.98)
        .collect();
    assert!(edge.len() >= 40, "{} edge pixels", edge.len());
    let rms = |m: u32| {
        let s = scene(&surfaces, &format!("aa = \"iaa:2:0.05:{m}\""));
        let out = run(&s);
        for (i, cov) in out.coverage.iter().enumerate() {
            assert_bounds(cov, truth[i], 2e-3, &format!("{m} rays, pixel {i}"));
        }
        let sum: f64 = edge
            .iter()
            .map(|&i| (f64::from(out.image.pixels[i][0]) - truth[i]).powi(2))
            .sum();
        (sum / edge.len() as f64).sqrt()
    };
    let (one, sixteen) = (rms(1), rms(4));
    eprintln!("edge RMS error: {one:.4} with the central ray, {sixteen:.4} with 4 x 4 rays");
    assert!(
        sixteen < 0.4 * one && sixteen < 0.006,
        "edge RMS error {sixteen} with 4 x 4 rays against {one} with the central ray"
    );
}

/// A floor lit by a point light, part of it in the shadow of a thin slab out of view whose
/// straight edge runs at an angle: the shadow's edge crosses the floor's pixels, each of which the
/// primary beams prove to hit the floor alone, and where the shading hardly varies. With
/// interval anti-aliasing each region shaded once must have its shadow proven the same all
/// over it, so the edge pixels are split and come close to a reference of 16 × 16 rays per
/// pixel, where a region shaded with one shadow query per light would be all lit or all
/// dark: the RMS error over the edge pixels falls well below that of the render without
/// anti-aliasing, and every pixel's coverage bounds hold (the floor covers every pixel).
pub fn a_hard_shadows_edge_is_anti_aliased(run: Render<'_>) {
    let surfaces = r#"
[[surfaces]]
name = "floor"
formula = "z"
bounds = [[-3.0, -3.0, -0.5], [3.0, 3.0, 0.5]]
material = { color = [0.9, 0.9, 0.9], specular = 0.0 }

[[surfaces]]
name = "slab"
formula = "max(abs(z - 5) - 0.02, x + 0.4 * y + 4.85)"
bounds = [[-20.0, -10.0, 4.9], [20.0, 10.0, 5.1]]
material = { color = [0.2, 0.2, 0.8], specular = 0.0 }

[[lights]]
type = "point"
position = [-10.0, 0.0, 10.0]
intensity = 1.0
"#;
    let render = |aa: &str| run(&scene(surfaces, &format!("aa = \"{aa}\"")));
    let reference = render("ss:16");
    let plain = render("none");
    let iaa = render("iaa:3:0.05:2");
    let value = |out: &RenderOutput, i: usize| f64::from(out.image.pixels[i][0]);
    // The edge pixels: neither the lit nor the shadowed floor's value in the reference.
    let (lo, hi) = reference
        .image
        .pixels
        .iter()
        .map(|p| f64::from(p[0]))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    let edge: Vec<usize> = (0..reference.image.pixels.len())
        .filter(|&i| {
            let v = value(&reference, i);
            v > lo + 0.05 * (hi - lo) && v < hi - 0.05 * (hi - lo)
        })
        .collect();
    assert!(edge.len() >= 10, "{} edge pixels", edge.len());
    let rms = |out: &RenderOutput| {
        let sum: f64 = edge
            .iter()
            .map(|&i| (value(out, i) - value(&reference, i)).powi(2))
            .sum();
        (sum / edge.len() as f64).sqrt()
    };
    for (i, cov) in iaa.coverage.iter().enumerate() {
        assert_bounds(cov, 1.0, 0.0, &format!("pixel {i}"));
    }
    let (without, with) = (rms(&plain), rms(&iaa));
    eprintln!(
        "{} shadow-edge pixels, RMS error {without:.4} without anti-aliasing, {with:.4} with iaa:3",
        edge.len()
    );
    assert!(
        with < 0.25 * without,
        "shadow-edge RMS error {with} with iaa:3 against {without} without anti-aliasing"
    );
}
