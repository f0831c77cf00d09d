//! Hard cases for reliable rendering: tangent rays and double roots, singular lines,
//! features thinner than a pixel, far-away scenes, vanishing gradients, and huge and tiny
//! coefficients.
//!
//! None may panic, and every proven answer must be right:
//!
//! * a root finder's `NoRoot` (with the scene function or through the renderer's regular
//!   grid) only where the ray misses; a `Root` with proof `Unique` or `Exists` only around
//!   the true first root; a `Possible` root or an `Undecided` range never after the true
//!   first root (nothing before it may be skipped);
//! * a Miss screen box only where no ray of the box meets the surface, a Hit box only where
//!   every ray does.
//!
//! The truth comes from the analytic roots of spheres and of polynomials restricted to a
//! line, or, for the other surfaces, from a sign change of the scene function proven with
//! interval evaluations at points of the ray.

use std::collections::BTreeSet;

use beam_trace::beam::forward;
use beam_trace::grid::Grid;
use beam_trace::ray::{Ray, ipoint};
use beam_trace::root::{
    Escalating, Proof, RootCounters, RootFinder, RootMethod, RootResult, RootSettings,
};
use beam_trace::scene::geometry::GeometryEval;
use beam_trace::{Camera, NoProgress, RenderOutput, Scene, render};
use glam::DVec3;

// ---------------------------------------------------------------------------------------
// Root searches and their truth.

/// The reliable root finders.
fn reliable() -> Vec<RootMethod> {
    RootMethod::ALL
        .into_iter()
        .filter(|m| m.finder().is_reliable())
        .collect()
}

/// The first-root search of `method` along `ray`, over the part of the ray (`t ≥ 0`) inside
/// the scene bounds, with the scene function, as the renderer runs it without a grid.
fn solve(scene: &Scene, method: RootMethod, ray: &Ray, settings: &RootSettings) -> RootResult {
    search(
        scene,
        method.finder(),
        ray,
        settings,
        &mut RootCounters::default(),
    )
}

/// The first-root search of `finder` along `ray` over the part of the ray inside the scene
/// bounds, with the scene function, counting into `counters`.
fn search(
    scene: &Scene,
    finder: &dyn RootFinder,
    ray: &Ray,
    settings: &RootSettings,
    counters: &mut RootCounters,
) -> RootResult {
    let Some(t) = ray
        .beam()
        .t_range_within(&scene.geometry.bounds(), forward())
    else {
        return RootResult::NoRoot;
    };
    let mut ev = scene.geometry.evaluator();
    ev.beam.set_ray(ray);
    finder.first_root(&mut ev.beam, t, settings, counters)
}

/// The truth about a ray: it misses, or its first root (`t ≥ 0`) is at the given parameter.
#[derive(Copy, Clone, Debug, PartialEq)]
enum Truth {
    Miss,
    Root(f64),
}

/// What a search proved.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Outcome {
    ProvenHit,
    ProvenMiss,
    Open,
}

fn outcome(r: &RootResult) -> Outcome {
    match r {
        RootResult::NoRoot => Outcome::ProvenMiss,
        RootResult::Root {
            proof: Proof::Unique | Proof::Exists,
            ..
        } => Outcome::ProvenHit,
        _ => Outcome::Open,
    }
}

/// Checks a reliable search's answer against the truth. Reference roots are computed in
/// floating point (to about 1e-15 relative); a margin of 1e-13 relative covers their error.
fn check(what: &str, m: RootMethod, r: &RootResult, truth: Truth) {
    let slack = |t1: f64| 1e-13 * t1.abs();
    match (*r, truth) {
        (RootResult::NoRoot, Truth::Root(t1)) => {
            panic!("{what}: {m} proves no root, but the ray meets the surface at t = {t1}")
        }
        (
            RootResult::Root {
                t,
                proof: p @ (Proof::Unique | Proof::Exists),
            },
            Truth::Miss,
        ) => panic!("{what}: {m} proves a root ({p:?}) in {t:?}, but the ray misses"),
        (
            RootResult::Root {
                t,
                proof: p @ (Proof::Unique | Proof::Exists),
            },
            Truth::Root(t1),
        ) => assert!(
            t.inf() - slack(t1) <= t1 && t1 <= t.sup() + slack(t1),
            "{what}: {m} proves a root ({p:?}) in {t:?}, the first root is {t1}"
        ),
        (
            RootResult::Root {
                t,
                proof: Proof::Possible,
            }
            | RootResult::Undecided { t },
            Truth::Root(t1),
        ) => assert!(
            t.inf() <= t1 + slack(t1),
            "{what}: {m} answers {r:?}, past the first root {t1}"
        ),
        _ => {}
    }
}

/// The first-root search of `method` along `ray` through the regular grid of `grid`, as the
/// renderer runs it.
fn solve_grid(grid: &Grid, method: RootMethod, ray: &Ray, settings: &RootSettings) -> RootResult {
    let mut ev = grid.evaluator();
    let mut counters = RootCounters::default();
    grid.first_root_within(
        &mut ev,
        ray,
        forward(),
        method.finder(),
        settings,
        &mut counters,
    )
}

/// Runs every reliable finder on `ray`, with the scene function and through the renderer's
/// grid, checks each answer against `truth`, checks that no two answers contradict each
/// other (a proven hit and a proven miss), and returns the answers without the grid.
fn check_all(
    scene: &Scene,
    what: &str,
    ray: &Ray,
    truth: Truth,
    settings: &RootSettings,
) -> Vec<(RootMethod, RootResult)> {
    let answers: Vec<(RootMethod, RootResult)> = reliable()
        .into_iter()
        .map(|m| (m, solve(scene, m, ray, settings)))
        .collect();
    let grid = Grid::build(&scene.geometry, scene.settings.grid_resolution.max(1));
    let through_grid: Vec<(RootMethod, RootResult)> = reliable()
        .into_iter()
        .map(|m| (m, solve_grid(&grid, m, ray, settings)))
        .collect();
    for (m, r) in &answers {
        check(what, *m, r, truth);
    }
    for (m, r) in &through_grid {
        check(&format!("{what} (grid)"), *m, r, truth);
    }
    let outcomes: BTreeSet<_> = answers
        .iter()
        .chain(&through_grid)
        .map(|(_, r)| format!("{:?}", outcome(r)))
        .collect();
    assert!(
        !(outcomes.contains("ProvenHit") && outcomes.contains("ProvenMiss")),
        "{what}: the finders contradict each other: {answers:?}, through the grid {through_grid:?}"
    );
    answers
}

/// Checks every reliable finder on a ray that meets the surface at (or within 1e-9 of)
/// `t_on`, whose first root is not known: no proven miss, no answer past `t_on` or past a
/// proven sign change, and each proven root enclosure `t` can hold a zero (the interval
/// value over its points holds 0) with no proven sign change before `t.inf()`.
fn check_through(
    scene: &Scene,
    ev: &mut GeometryEval,
    what: &str,
    ray: &Ray,
    t_on: f64,
    settings: &RootSettings,
) {
    let limit = match sign_change(scene, ev, ray, 1024) {
        Some(tc) => tc.min(t_on + 1e-9),
        None => t_on + 1e-9,
    };
    let start = ray
        .beam()
        .t_range_within(&scene.geometry.bounds(), forward())
        .expect("the ray crosses the bounds")
        .inf();
    for m in reliable() {
        let r = solve(scene, m, ray, settings);
        let t = match r {
            RootResult::NoRoot => panic!("{what}: {m} proves no root"),
            RootResult::Root { t, .. } | RootResult::Undecided { t } => t,
        };
        assert!(
            t.inf() <= limit,
            "{what}: {m} answers {r:?}, past a root at {limit}"
        );
        if outcome(&r) == Outcome::ProvenHit {
            let v = ev.value_box(&ray.beam().points(t));
            assert!(
                v.contains(0.0),
                "{what}: {m} proves {r:?}, where f is {v:?}"
            );
            if let Some(tc) = sign_change_in(ev, ray, start, t.inf(), 1024) {
                assert!(
                    tc >= t.inf(),
                    "{what}: {m} proves {r:?}, a root lies before {tc}"
                );
            }
        }
    }
}

/// The first root (`t ≥ 0`) of `ray` on the sphere of `centre` and `radius` (the origin
/// outside it), computed with the cancellation-free quadratic formula.
fn sphere_truth(ray: &Ray, centre: DVec3, radius: f64) -> Truth {
    let o = ray.origin - centre;
    let d = ray.dir;
    let a = d.dot(d);
    let b = o.dot(d);
    let c = o.dot(o) - radius * radius;
    assert!(c > 0.0, "the origin must lie outside the sphere");
    let disc = b * b - a * c;
    if disc < 0.0 || b >= 0.0 {
        return Truth::Miss;
    }
    // Both roots are positive; the first is c / q with q = −b + √disc.
    let q = -b + disc.sqrt();
    Truth::Root(c / q)
}

/// The first proven sign change of the scene function along `ray` for `t ∈ [lo, hi]`:
/// interval evaluations at `n + 1` points of the ray (each enclosing the exact point) with
/// opposite strict signs, or a proven zero. `Some(t)`: the ray meets the surface at or
/// before `t`.
fn sign_change_in(ev: &mut GeometryEval, ray: &Ray, lo: f64, hi: f64, n: usize) -> Option<f64> {
    let beam = ray.beam();
    let mut seen = [false, false];
    for i in 0..=n {
        let ti = lo + (hi - lo) * (i as f64 / n as f64);
        let v = ev.value_box(&beam.points(ipoint(ti)));
        if v.is_empty() {
            continue;
        }
        if v.inf() > 0.0 {
            seen[0] = true;
        } else if v.sup() < 0.0 {
            seen[1] = true;
        } else if v.inf() == 0.0 && v.sup() == 0.0 {
            return Some(ti);
        }
        if seen[0] && seen[1] {
            return Some(ti);
        }
    }
    None
}

/// [`sign_change_in`] over the part of the ray (`t ≥ 0`) inside the scene bounds.
fn sign_change(scene: &Scene, ev: &mut GeometryEval, ray: &Ray, n: usize) -> Option<f64> {
    let t = ray
        .beam()
        .t_range_within(&scene.geometry.bounds(), forward())?;
    sign_change_in(ev, ray, t.inf(), t.sup(), n)
}

// ---------------------------------------------------------------------------------------
// Renders and their checks.

fn scene_from(text: &str) -> Scene {
    Scene::from_toml(text, "test.toml", None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

fn run(scene: &Scene) -> RenderOutput {
    render(scene, &NoProgress).expect("the render succeeds")
}

/// Rays through the corners, edge middles and centre of pixel `(x, y)`: all of them lie in
/// the beam of any screen box that holds the pixel.
fn pixel_rays(cam: &Camera, x: u32, y: u32) -> Vec<Ray> {
    let (fx, fy) = (f64::from(x), f64::from(y));
    let mut out = Vec::new();
    for oy in [0.0, 0.5, 1.0] {
        for ox in [0.0, 0.5, 1.0] {
            out.push(cam.ray(fx + ox, fy + oy));
        }
    }
    out
}

/// The class of a pixel of the classification image (base colour or darkened outline).
fn class_at(out: &RenderOutput, x: u32, y: u32) -> &'static str {
    let c = out.classification().get(x, y);
    let is = |base: [f32; 3]| c == base || c == base.map(|v| v * 0.6);
    if is([0.1, 0.25, 0.8]) {
        "miss"
    } else if is([0.85, 0.15, 0.1]) {
        "hit"
    } else if is([0.95, 0.85, 0.1]) {
        "undecided"
    } else {
        "none"
    }
}

/// Every proven class of the screen boxes is right: no ray through a Miss pixel has a
/// proven root (`hits` decides whether a ray meets the surface), every ray through a Hit
/// pixel meets the surface (`hits` returns `Some(true)`, or `None` where it cannot tell).
fn check_classes(
    what: &str,
    scene: &Scene,
    out: &RenderOutput,
    mut hits: impl FnMut(&Ray) -> Option<bool>,
) {
    let cam = &scene.camera;
    for y in 0..cam.height() {
        for x in 0..cam.width() {
            let class = class_at(out, x, y);
            for ray in pixel_rays(cam, x, y) {
                match (class, hits(&ray)) {
                    ("miss", Some(true)) => {
                        panic!("{what}: pixel ({x}, {y}) is a proven miss, but {ray:?} hits")
                    }
                    ("hit", Some(false)) => {
                        panic!("{what}: pixel ({x}, {y}) is a proven hit, but {ray:?} misses")
                    }
                    _ => {}
                }
            }
        }
    }
}

/// Miss pixels checked by sign changes along their rays (a sign change proves a hit;
/// no sign change proves nothing). Returns how many of the rays tried have a proven root,
/// so that callers can check that the test is not empty.
fn check_miss_pixels_by_sampling(what: &str, scene: &Scene, out: &RenderOutput) -> usize {
    let mut ev = scene.geometry.evaluator();
    let mut roots = 0;
    check_classes(what, scene, out, |ray| {
        let hit = sign_change(scene, &mut ev, ray, 256).is_some();
        roots += usize::from(hit);
        hit.then_some(true)
    });
    roots
}

fn sphere_hits(centre: DVec3, radius: f64) -> impl Fn(&Ray) -> Option<bool> {
    move |ray| Some(sphere_truth(ray, centre, radius) != Truth::Miss)
}

/// The pixels of the image that are not the background colour.
fn foreground(scene: &Scene, out: &RenderOutput) -> BTreeSet<(u32, u32)> {
    let mut s = BTreeSet::new();
    for y in 0..out.image.height {
        for x in 0..out.image.width {
            if out.image.get(x, y) != scene.background {
                s.insert((x, y));
            }
        }
    }
    s
}

fn assert_finite(what: &str, out: &RenderOutput) {
    assert!(
        out.image.pixels.iter().flatten().all(|c| c.is_finite()),
        "{what}: the image has a non-finite channel"
    );
}

// ---------------------------------------------------------------------------------------
// 1. Tangent rays.

fn unit_sphere() -> Scene {
    scene_from(
        r#"
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
width = 16
height = 16
[[surfaces]]
catalog = "sphere"
"#,
    )
}

#[test]
fn tangent_ray_to_sphere_double_root() {
    let scene = unit_sphere();
    let s = RootSettings::default();
    // Touches the sphere at (1, 0, 0): g(t) = (t − 5)², a double root at t = 5. Then the
    // same in the other direction, along other axes, obliquely (touching at t = 4), and
    // with roots that are not floats (t = 5/3, 4/3): no evaluation at a float is exactly 0.
    let tangents = [
        (DVec3::new(1.0, 0.0, -5.0), DVec3::new(0.0, 0.0, 1.0), 5.0),
        (DVec3::new(1.0, 0.0, 5.0), DVec3::new(0.0, 0.0, -1.0), 5.0),
        (DVec3::new(0.0, -4.0, 1.0), DVec3::new(0.0, 2.0, 0.0), 2.0),
        (DVec3::new(-3.0, -1.0, 0.0), DVec3::new(0.5, 0.0, 0.0), 6.0),
        (
            DVec3::new(1.0, -1.5, -2.0),
            DVec3::new(0.0, 0.375, 0.5),
            4.0,
        ),
        (
            DVec3::new(1.0, 0.0, -5.0),
            DVec3::new(0.0, 0.0, 3.0),
            5.0 / 3.0,
        ),
        (
            DVec3::new(-4.0, 0.0, -1.0),
            DVec3::new(3.0, 0.0, 0.0),
            4.0 / 3.0,
        ),
    ];
    for (o, d, t1) in tangents {
        let ray = Ray { origin: o, dir: d };
        let what = format!("tangent from {o} along {d}");
        assert_eq!(
            sphere_truth(&ray, DVec3::ZERO, 1.0),
            Truth::Root(t1),
            "{what}"
        );
        // Never a miss; proven roots hold t1 (checked by check_all).
        for (m, r) in check_all(&scene, &what, &ray, Truth::Root(t1), &s) {
            match r {
                // A possible root: g ≥ 0 is below the rounding of `1 + z² − 1` only within
                // about 3e-8 of the root here, and nothing before the root may be skipped.
                RootResult::Root {
                    t,
                    proof: Proof::Possible,
                } => assert!(t.inf() <= t1 && t.sup() >= t1 - 1e-7, "{what}: {m}: {r:?}"),
                RootResult::Undecided { t } => assert!(t.contains(t1), "{what}: {m}: {r:?}"),
                _ => {}
            }
        }
    }

    // Missing by 1e-9: no root, so no proof of one may appear.
    let near = Ray {
        origin: DVec3::new(1.0 + 1e-9, 0.0, -5.0),
        dir: DVec3::new(0.0, 0.0, 1.0),
    };
    assert_eq!(sphere_truth(&near, DVec3::ZERO, 1.0), Truth::Miss);
    check_all(&scene, "miss by 1e-9", &near, Truth::Miss, &s);

    // Missing by 1e-3: every reliable finder proves the miss.
    let miss = Ray {
        origin: DVec3::new(1.001, 0.0, -5.0),
        dir: DVec3::new(0.0, 0.0, 1.0),
    };
    for (m, r) in check_all(&scene, "miss by 1e-3", &miss, Truth::Miss, &s) {
        assert_eq!(r, RootResult::NoRoot, "{m}");
    }
}

// ---------------------------------------------------------------------------------------
// 2. Singular lines.

/// The polynomial of a catalog surface, without clipping, in a box large enough for the
/// rays below.
fn unclipped(formula: &str) -> Scene {
    scene_from(&format!(
        r#"
[camera]
eye = [0.0, 0.0, 5.0]
look_at = [0.0, 0.0, 0.0]
width = 16
height = 16
[[surfaces]]
formula = "{formula}"
bounds = [[-3.0, -3.0, -3.0], [3.0, 3.0, 3.0]]
"#
    ))
}

#[test]
fn crosscap_and_steiner_singular_lines() {
    let s = RootSettings::default();
    let ray = |o: [f64; 3], d: [f64; 3]| Ray {
        origin: DVec3::from(o),
        dir: DVec3::from(d),
    };

    // Steiner's Roman surface x²y² + y²z² + z²x² − xyz: the coordinate axes are double lines
    // for |coordinate| < 1/2 (two sheets cross there) and lie on the zero set everywhere.
    let formula = implicit_expr::catalog::get("steiner").unwrap().formula;
    let steiner = unclipped(formula);
    let cases = [
        // Through (0.25, 0, 0) along (0, 1, 1): g = s²(s² − 1/8) with s = t − 1; a simple
        // root at s = −√(1/8) first, then the double line at s = 0.
        (
            "steiner: crossing the x axis",
            ray([0.25, -1.0, -1.0], [0.0, 1.0, 1.0]),
            Truth::Root(1.0 - 0.125f64.sqrt()),
        ),
        // Along (0, 1, −1): g = s²(s² + 3/8), touching the double line only.
        (
            "steiner: touching the x axis",
            ray([0.25, -1.0, 1.0], [0.0, 1.0, -1.0]),
            Truth::Root(1.0),
        ),
        // Along the x axis: g ≡ 0, the first root is where the search starts.
        (
            "steiner: along the x axis",
            ray([-2.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            Truth::Root(0.0),
        ),
        // Parallel to the z axis at distance 1e-3 (x = y = 1e-3): g = e²(2z² − z + e²),
        // first root at z = (1 − √(1 − 8e²)) / 4 ≈ 1e-6.
        (
            "steiner: beside the z axis",
            ray([1e-3, 1e-3, -2.0], [0.0, 0.0, 1.0]),
            Truth::Root(2.0 + 2.0 * 1e-6 / (1.0 + (1.0 - 8e-6f64).sqrt())),
        ),
        // Crossing the y axis at y = 0.4 along (1, 0, 1): g = s²(s² − 0.08) with
        // s = t − 1, first root at s = −√0.08.
        (
            "steiner: crossing the y axis",
            ray([-1.0, 0.4, -1.0], [1.0, 0.0, 1.0]),
            Truth::Root(1.0 - 0.08f64.sqrt()),
        ),
    ];
    for (what, r, truth) in cases {
        check_all(&steiner, what, &r, truth, &s);
    }

    // The cross-cap 4x²(x² + y² + z² + z) + y²(y² + z² − 1): the z axis lies on the zero
    // set; for 0 < z < 1 it is the double line where the surface crosses itself.
    let formula = implicit_expr::catalog::get("crosscap").unwrap().formula;
    let crosscap = unclipped(formula);
    let cases = [
        // Through (0, 0, 0.5) along (1/4, 1, 0): g = s²(81/64 s² − 9/16), s = t − 1; a
        // simple root at s = −2/3, then the double line at s = 0.
        (
            "crosscap: crossing the double line",
            ray([-0.25, -1.0, 0.5], [0.25, 1.0, 0.0]),
            Truth::Root(1.0 / 3.0),
        ),
        // Along x through (0, 0, 0.5): g = 4x²(x² + 3/4), touching the double line only.
        (
            "crosscap: touching the double line",
            ray([-1.0, 0.0, 0.5], [1.0, 0.0, 0.0]),
            Truth::Root(1.0),
        ),
        // Along the z axis: g ≡ 0.
        (
            "crosscap: along the z axis",
            ray([0.0, 0.0, -2.0], [0.0, 0.0, 1.0]),
            Truth::Root(0.0),
        ),
        // Along x through (0, 0, −0.5), where the z axis is an isolated line inside the
        // solid: g = 4x²(x² − 1/4), first root at x = −1/2.
        (
            "crosscap: across the isolated line",
            ray([-1.0, 0.0, -0.5], [1.0, 0.0, 0.0]),
            Truth::Root(0.5),
        ),
        // In the plane x = 0 along y at z = 0.5: g = y²(y² − 3/4), the double line at
        // y = 0 between two simple roots; from y = −2 the first is y = −√0.75.
        (
            "crosscap: in the plane x = 0",
            ray([0.0, -2.0, 0.5], [0.0, 1.0, 0.0]),
            Truth::Root(2.0 - 0.75f64.sqrt()),
        ),
    ];
    for (what, r, truth) in cases {
        check_all(&crosscap, what, &r, truth, &s);
    }

    // A fan of rays through points of the double lines, whose first roots are not known
    // in closed form: no finder proves a miss or skips the line, and every proven root is
    // a point where the function can vanish with no proven sign change before it.
    for (scene, name, p) in [
        (&steiner, "steiner", DVec3::new(0.3, 0.0, 0.0)),
        (&crosscap, "crosscap", DVec3::new(0.0, 0.0, 0.4)),
    ] {
        let mut ev = scene.geometry.evaluator();
        for i in 0..12 {
            let a = f64::from(i) * 0.27;
            let d = DVec3::new(a.cos() * 0.3, a.sin(), (2.0 * a).cos());
            let r = Ray {
                origin: p - 2.0 * d,
                dir: d,
            };
            let what = format!("{name} fan {i}");
            check_through(scene, &mut ev, &what, &r, 2.0, &s);
        }
    }

    // Whole renders of the catalog scenes (clipped): no panic, sound classes.
    for name in ["crosscap", "steiner"] {
        let scene = Scene::catalog(name, 32, 32).unwrap();
        let out = run(&scene);
        assert_finite(name, &out);
        let fg = foreground(&scene, &out).len();
        assert!(fg > 50 && fg < 32 * 32, "{name}: {fg} foreground pixels");
        let roots = check_miss_pixels_by_sampling(name, &scene, &out);
        assert!(roots > 100, "{name}: only {roots} rays with a proven root");
        let mut iaa = scene.clone();
        iaa.settings.aa = Some("iaa".parse().unwrap());
        let out_iaa = run(&iaa);
        assert_finite(name, &out_iaa);
        // IAA loses nothing that 1 ray per pixel finds.
        let fg_iaa = foreground(&iaa, &out_iaa);
        let mut pp = scene.clone();
        pp.settings.primary = "per-pixel".parse().unwrap();
        pp.settings.rays_per_pixel = 1;
        let fg_pp = foreground(&pp, &run(&pp));
        assert!(fg_pp.is_subset(&fg_iaa), "{name}: {fg_pp:?} vs {fg_iaa:?}");
    }
}

// ---------------------------------------------------------------------------------------
// 3. Features thinner than a pixel.

/// The scene `text` with `render` as the body of its `[render]` table.
fn with_render(text: &str, render: &str) -> Scene {
    scene_from(&format!("{text}\n[render]\n{render}\n"))
}

#[test]
fn thin_cylinder_found_by_beams_missed_by_point_sampling() {
    // The camera looks down −x at the z axis; image x runs along world y, image y along −z.
    let eye = DVec3::new(5.0, 0.0, 0.0);
    let cam = Camera::new(eye, DVec3::ZERO, DVec3::Z, 40.0, 32, 32).unwrap();
    // World y of the pixel position px at the plane x = 0.
    let y_at = |px: f64| {
        let r = cam.ray(px, 16.0);
        r.at(-r.origin.x / r.dir.x).y
    };
    let pixel = y_at(17.0) - y_at(16.0);
    assert!((pixel - 0.1137).abs() < 1e-3, "{pixel}");
    // The axis 0.3 pixel into column 16 (pixel centres are 0.2 pixel away), the radius
    // 1e-4 of a pixel: rows 8 to 23 see it whole (z from −1 to 1).
    let c = y_at(16.3);
    let r = 1e-4 * pixel;
    let h = 1e-3;
    let text = format!(
        r#"
background = [0.0, 0.0, 0.0]
[camera]
eye = [5.0, 0.0, 0.0]
look_at = [0.0, 0.0, 0.0]
up = [0.0, 0.0, 1.0]
fov = 40.0
width = 32
height = 32
[[surfaces]]
name = "wire"
formula = "x^2 + (y - c)^2 - r^2"
params = {{ c = {c:e}, r = {r:e} }}
bounds = [[{mh:e}, {lo:e}, -1.0], [{h:e}, {hi:e}, 1.0]]
clip = true
material = {{ color = [1.0, 1.0, 1.0] }}
"#,
        mh = -h,
        lo = c - h,
        hi = c + h,
    );
    let wire: BTreeSet<(u32, u32)> = (8..=23).map(|y| (16, y)).collect();

    // IAA: the pixel's beam cannot be rejected, the wire is kept.
    let scene = with_render(&text, "aa = \"iaa\"");
    let out = run(&scene);
    assert_finite("iaa", &out);
    let fg = foreground(&scene, &out);
    assert!(
        wire.is_subset(&fg),
        "IAA loses the wire: {:?}",
        wire.difference(&fg).collect::<Vec<_>>()
    );
    // ... including the rows it crosses in part (z = ±1 at rows 7.2 and 24.8), and puts
    // it nowhere else but next to it.
    assert!(fg.contains(&(16, 7)) && fg.contains(&(16, 24)), "{fg:?}");
    assert!(
        fg.iter()
            .all(|&(x, y)| (15..=17).contains(&x) && (6..=25).contains(&y)),
        "IAA draws pixels away from the wire: {fg:?}"
    );

    // One ray per pixel, through the pixel centre: the wire is lost.
    for finder in ["newton-alefeld-hansen", "point-sampling"] {
        let scene = with_render(
            &text,
            &format!("primary = \"per-pixel\"\nrays_per_pixel = 1\nroot_finder = \"{finder}\""),
        );
        let out = run(&scene);
        assert_finite(finder, &out);
        let fg = foreground(&scene, &out);
        assert!(
            fg.is_empty(),
            "{finder}: point sampling was expected to miss the wire: {fg:?}"
        );
    }

    // Screen boxes: no box over the wire may be a proven miss.
    let scene = with_render(&text, "");
    let out = run(&scene);
    for &(x, y) in &wire {
        assert_ne!(class_at(&out, x, y), "miss", "pixel ({x}, {y})");
    }
    // Nor a proven hit: most rays of the pixel miss the wire.
    for &(x, y) in &wire {
        assert_ne!(class_at(&out, x, y), "hit", "pixel ({x}, {y})");
    }
    check_miss_pixels_by_sampling("wire", &scene, &out);
    // A ray through the wire: every reliable finder finds it.
    let through = Ray {
        origin: eye,
        dir: DVec3::new(0.0, c, 0.2) - eye,
    };
    let s = RootSettings::default();
    // The exact first root of this ray: x² + (y − c)² = r² with x = 5 − 5t, y = ct.
    let truth = {
        // (5 − 5t)² + c²(t − 1)² = r²: (t − 1)²(25 + c²) = r².
        let t1 = 1.0 - r / (25.0 + c * c).sqrt();
        Truth::Root(t1)
    };
    check_all(&scene, "ray through the wire", &through, truth, &s);
}

#[test]
fn drop_thin_neck() {
    // Looking down −z at the neck of the drop at the origin (the x axis horizontal, on the
    // boundary between rows 15 and 16); 0.8 units across 32 pixels.
    let fov = 2.0 * (0.4f64 / 3.0).atan().to_degrees();
    let text = format!(
        r#"
[camera]
eye = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov = {fov}
width = 32
height = 32
[[surfaces]]
catalog = "drop"
"#
    );
    let iaa_scene = with_render(&text, "aa = \"iaa\"");
    let iaa = run(&iaa_scene);
    assert_finite("iaa", &iaa);
    let fg_iaa = foreground(&iaa_scene, &iaa);
    // Every pixel of the two rows along the axis holds part of the surface.
    for y in [15, 16] {
        for x in 0..32 {
            assert!(fg_iaa.contains(&(x, y)), "IAA loses pixel ({x}, {y})");
        }
    }

    let pp_scene = with_render(&text, "primary = \"per-pixel\"\nrays_per_pixel = 1");
    let pp = run(&pp_scene);
    assert_finite("per-pixel", &pp);
    let fg_pp = foreground(&pp_scene, &pp);
    assert!(
        fg_pp.is_subset(&fg_iaa),
        "point sampling finds pixels IAA loses: {:?}",
        fg_pp.difference(&fg_iaa).collect::<Vec<_>>()
    );
    assert!(
        fg_iaa.len() > fg_pp.len(),
        "IAA {} pixels, point sampling {}",
        fg_iaa.len(),
        fg_pp.len()
    );
    // Point sampling loses the neck itself: a run of pixels on the axis rows.
    let lost: Vec<_> = (0..32).filter(|&x| !fg_pp.contains(&(x, 15))).collect();
    assert!(lost.len() >= 4, "lost on row 15: {lost:?}");

    // Screen boxes: proven misses are misses.
    let sb_scene = with_render(&text, "");
    let sb = run(&sb_scene);
    let roots = check_miss_pixels_by_sampling("drop", &sb_scene, &sb);
    assert!(roots > 100, "drop: only {roots} rays with a proven root");
    for y in [15, 16] {
        for x in 0..32 {
            assert_ne!(class_at(&sb, x, y), "miss", "pixel ({x}, {y})");
        }
    }
}

// ---------------------------------------------------------------------------------------
// 4. Far from the origin.

fn sphere_scene(offset: DVec3, size: u32) -> String {
    let c = offset;
    format!(
        r#"
background = [0.0, 0.0, 0.0]
[camera]
eye = [{ex:?}, {ey:?}, {ez:?}]
look_at = [{cx:?}, {cy:?}, {cz:?}]
fov = 40.0
width = {size}
height = {size}
[[surfaces]]
name = "ball"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
transform = {{ translate = [{cx:?}, {cy:?}, {cz:?}] }}
[[lights]]
type = "point"
position = [{lx:?}, {ly:?}, {lz:?}]
"#,
        ex = c.x + 0.5,
        ey = c.y + 1.0,
        ez = c.z + 5.0,
        cx = c.x,
        cy = c.y,
        cz = c.z,
        lx = c.x - 3.0,
        ly = c.y + 4.0,
        lz = c.z + 5.0,
    )
}

/// Pixels whose rays (corners, edge middles, centre, and the stratified rays of
/// undecided pixels) do not all agree on hit or miss of the sphere.
fn silhouette(cam: &Camera, centre: DVec3) -> BTreeSet<(u32, u32)> {
    let mut s = BTreeSet::new();
    for y in 0..cam.height() {
        for x in 0..cam.width() {
            let mut rays = pixel_rays(cam, x, y);
            for oy in [1.0 / 6.0, 0.5, 5.0 / 6.0] {
                for ox in [1.0 / 6.0, 0.5, 5.0 / 6.0] {
                    rays.push(cam.ray(f64::from(x) + ox, f64::from(y) + oy));
                }
            }
            let hits: BTreeSet<bool> = rays
                .iter()
                .map(|r| sphere_truth(r, centre, 1.0) != Truth::Miss)
                .collect();
            if hits.len() > 1 {
                s.insert((x, y));
            }
        }
    }
    s
}

#[test]
fn scene_translated_by_1e6() {
    let offset = DVec3::splat(1e6);
    let near = scene_from(&sphere_scene(DVec3::ZERO, 32));
    let far = scene_from(&sphere_scene(offset, 32));
    let out_near = run(&near);
    let out_far = run(&far);
    assert_finite("far", &out_far);
    check_classes("near", &near, &out_near, sphere_hits(DVec3::ZERO, 1.0));
    check_classes("far", &far, &out_far, sphere_hits(offset, 1.0));

    let fg_near = foreground(&near, &out_near);
    let fg_far = foreground(&far, &out_far);
    let edge = silhouette(&near.camera, DVec3::ZERO);
    let differ: BTreeSet<_> = fg_near.symmetric_difference(&fg_far).copied().collect();
    assert!(
        differ.is_subset(&edge),
        "pixels away from the silhouette differ: {:?}",
        differ.difference(&edge).collect::<Vec<_>>()
    );
    assert!(
        differ.len() * 50 <= edge.len(),
        "{} of {} silhouette pixels differ",
        differ.len(),
        edge.len()
    );
    assert!(fg_near.len() > 100, "{}", fg_near.len());

    // The same with interval anti-aliasing.
    let mut near_iaa = near.clone();
    near_iaa.settings.aa = Some("iaa".parse().unwrap());
    let mut far_iaa = far.clone();
    far_iaa.settings.aa = Some("iaa".parse().unwrap());
    let a = foreground(&near_iaa, &run(&near_iaa));
    let b = foreground(&far_iaa, &run(&far_iaa));
    let differ: BTreeSet<_> = a.symmetric_difference(&b).copied().collect();
    assert!(differ.is_subset(&edge), "IAA: {differ:?}");
    assert!(differ.len() * 50 <= edge.len(), "IAA: {differ:?}");

    // Root enclosures along pixel rays contain the analytic roots, near and far.
    let s = RootSettings::default();
    for (scene, centre) in [(&near, DVec3::ZERO), (&far, offset)] {
        let cam = &scene.camera;
        for y in (0..32).step_by(3) {
            for x in (0..32).step_by(3) {
                let ray = cam.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let truth = sphere_truth(&ray, centre, 1.0);
                let what = format!("pixel ({x}, {y}) at {centre}");
                let answers = check_all(scene, &what, &ray, truth, &s);
                // Far from the silhouette every finder decides.
                if !edge.contains(&(x, y)) {
                    for (m, r) in answers {
                        let want = if truth == Truth::Miss {
                            Outcome::ProvenMiss
                        } else {
                            Outcome::ProvenHit
                        };
                        assert_eq!(outcome(&r), want, "{what}: {m} {r:?}");
                    }
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// 5. Vanishing gradients.

fn formula_scene(formula: &str, bound: f64, eye_z: f64, size: u32, render: &str) -> Scene {
    scene_from(&format!(
        r#"
background = [0.0, 0.0, 0.0]
[camera]
eye = [0.0, 0.0, {eye_z:?}]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = {size}
height = {size}
[[surfaces]]
formula = "{formula}"
bounds = [[{m:?}, {m:?}, {m:?}], [{b:?}, {b:?}, {b:?}]]
[[lights]]
type = "point"
position = [{l:?}, {l:?}, {eye_z:?}]
[render]
{render}
"#,
        m = -bound,
        b = bound,
        l = 0.6 * eye_z,
    ))
}

/// Rays from `(0, 0, 5·scale)` towards the points `(0.3 i, 0.3 j, 0)·scale`: their distances
/// from the centre stay at least 4% away from the radius `scale`.
fn ray_fan(scale: f64) -> Vec<Ray> {
    let origin = DVec3::new(0.0, 0.0, 5.0 * scale);
    let mut out = Vec::new();
    for j in -4..=4 {
        for i in -4..=4 {
            let target = DVec3::new(0.3 * f64::from(i), 0.3 * f64::from(j), 0.0) * scale;
            out.push(Ray {
                origin,
                dir: target - origin,
            });
        }
    }
    out
}

#[test]
fn near_zero_gradient() {
    let s = RootSettings::default();
    // (|p|² − 1)³: a triple root on the unit sphere, the gradient vanishes on the surface.
    let cube = formula_scene("(x^2 + y^2 + z^2 - 1)^3", 1.25, 5.0, 32, "");
    // (|p|² − 1)² − 1e-12: two shells |p|² = 1 ± 1e-6, the gradient about 4e-6 there.
    let eps = 1e-12f64.sqrt();
    let square = formula_scene("(x^2 + y^2 + z^2 - 1)^2 - 1e-12", 1.25, 5.0, 32, "");
    let outer = (1.0 + eps).sqrt();
    for ray in ray_fan(1.0) {
        let what = format!("cube, dir {}", ray.dir);
        check_all(&cube, &what, &ray, sphere_truth(&ray, DVec3::ZERO, 1.0), &s);
        let what = format!("square, dir {}", ray.dir);
        let truth = sphere_truth(&ray, DVec3::ZERO, outer);
        for (m, r) in check_all(&square, &what, &ray, truth, &s) {
            // Proven hits reach into the shell between the two spheres: |p|² − 1 goes
            // down monotonically across the enclosure (the ray enters the ball), from at
            // least −1e-6 to at most 1e-6.
            if let (Outcome::ProvenHit, Some(t)) = (outcome(&r), r.root()) {
                let q = |t: f64| ray.at(t).length_squared() - 1.0;
                let (first, last) = (q(t.inf()), q(t.sup()));
                assert!(
                    first >= -eps && last <= eps && first >= last,
                    "{what}: {m} {r:?}: |p|² − 1 from {first} to {last}"
                );
            }
        }
    }
    // A ray just inside the outer shell but outside the unit sphere hits; one just outside
    // the outer shell misses.
    let graze = |d: f64| Ray {
        origin: DVec3::new(d, 0.0, -5.0),
        dir: DVec3::Z,
    };
    let inside = graze(1.0 + 0.25 * eps);
    check_all(
        &square,
        "inside the shell",
        &inside,
        sphere_truth(&inside, DVec3::ZERO, outer),
        &s,
    );
    let outside = graze(1.0 + 2.0 * eps);
    assert_eq!(sphere_truth(&outside, DVec3::ZERO, outer), Truth::Miss);
    check_all(&square, "outside the shell", &outside, Truth::Miss, &s);

    // Renders: no panic, normals counted (degenerate ones included), sound classes.
    for (name, scene) in [("cube", &cube), ("square", &square)] {
        let out = run(scene);
        assert_finite(name, &out);
        let normals = out.stats.pass("normals").unwrap();
        assert!(normals.ran);
        assert!(normals.counter("normals") > 0, "{name}: {}", out.stats);
        assert!(
            normals.counter("degenerate") <= normals.counter("normals"),
            "{name}: {}",
            out.stats
        );
        // Rays through the sphere of radius 1 − 1e-3 hit, rays past 1 + 1e-3 miss; between
        // them the check says nothing.
        check_classes(name, scene, &out, |r| {
            let inner = sphere_truth(r, DVec3::ZERO, 1.0 - 1e-3) != Truth::Miss;
            let outer = sphere_truth(r, DVec3::ZERO, 1.0 + 1e-3) != Truth::Miss;
            match (inner, outer) {
                (true, _) => Some(true),
                (false, false) => Some(false),
                (false, true) => None,
            }
        });
        let fg = foreground(scene, &out).len();
        assert!(fg > 100, "{name}: {fg} foreground pixels");
    }

    // A function that is zero, with a zero gradient, on a whole region: min(|p|² − 1, 0)
    // vanishes everywhere outside the ball, so every ray's first root is where it enters
    // the scene bounds, and the shading points there get a degenerate normal; the render
    // goes on.
    let flat = formula_scene("min(x^2 + y^2 + z^2 - 1, 0)", 1.25, 5.0, 16, "");
    let out = run(&flat);
    assert_finite("flat", &out);
    let normals = out.stats.pass("normals").unwrap();
    assert!(normals.counter("normals") > 0, "{}", out.stats);
    assert!(normals.counter("degenerate") > 0, "{}", out.stats);
}

// ---------------------------------------------------------------------------------------
// 6. Huge and tiny coefficients.

#[test]
fn huge_and_tiny_coefficients() {
    let unit = formula_scene("x^2 + y^2 + z^2 - 1", 1.25, 5.0, 16, "");
    let huge = formula_scene("1e150*(x^2 + y^2 + z^2 - 1)", 1.25, 5.0, 16, "");
    let tiny = formula_scene("1e-150*(x^2 + y^2 + z^2 - 1)", 1.25, 5.0, 16, "");
    // A sphere of radius 1e-8 seen from 5e-8. The epsilons of the searches are absolute
    // widths of the ray parameter: they scale with the scene.
    let small = formula_scene(
        "x^2 + y^2 + z^2 - 1e-16",
        1.25e-8,
        5e-8,
        16,
        "epsilon = 1e-14",
    );
    let default_eps = RootSettings::default();
    let small_eps = RootSettings {
        epsilon: 1e-14,
        ..default_eps
    };

    let classes = |name: &str, scene: &Scene, scale: f64, settings: &RootSettings| {
        ray_fan(scale)
            .iter()
            .enumerate()
            .map(|(i, ray)| {
                let truth = sphere_truth(ray, DVec3::ZERO, scale);
                let what = format!("{name} ray {i}");
                check_all(scene, &what, ray, truth, settings)
                    .iter()
                    .map(|(_, r)| outcome(r))
                    .collect::<Vec<Outcome>>()
            })
            .collect::<Vec<_>>()
    };
    let reference = classes("unit", &unit, 1.0, &default_eps);
    // Every ray of the fan is decided on the unit sphere.
    for (i, c) in reference.iter().enumerate() {
        assert!(!c.contains(&Outcome::Open), "unit ray {i}: {c:?}");
    }
    assert_eq!(
        classes("1e150", &huge, 1.0, &default_eps),
        reference,
        "1e150"
    );
    assert_eq!(
        classes("1e-150", &tiny, 1.0, &default_eps),
        reference,
        "1e-150"
    );
    assert_eq!(
        classes("radius 1e-8", &small, 1e-8, &small_eps),
        reference,
        "radius 1e-8"
    );
    // With the default epsilon the small sphere is below the resolution of the searches:
    // answers may stay open, but no proof may be wrong.
    for (i, ray) in ray_fan(1e-8).iter().enumerate() {
        let truth = sphere_truth(ray, DVec3::ZERO, 1e-8);
        check_all(
            &small,
            &format!("small ray {i}, default epsilon"),
            ray,
            truth,
            &default_eps,
        );
    }

    // Renders: the same pixels are background, and the proven classes are right.
    let out_unit = run(&unit);
    let fg_unit = foreground(&unit, &out_unit);
    let edge = silhouette(&unit.camera, DVec3::ZERO);
    let mut unit_iaa = unit.clone();
    unit_iaa.settings.aa = Some("iaa".parse().unwrap());
    let fg_iaa = foreground(&unit_iaa, &run(&unit_iaa));
    // Pixels with a ray through the sphere (all of whose rays hit, or on the silhouette).
    let fg_inside: BTreeSet<_> = fg_unit.union(&edge).copied().collect();
    for (name, scene, scale) in [
        ("unit", &unit, 1.0),
        ("1e150", &huge, 1.0),
        ("1e-150", &tiny, 1.0),
        ("radius 1e-8", &small, 1e-8),
    ] {
        let out = run(scene);
        assert_finite(name, &out);
        check_classes(name, scene, &out, sphere_hits(DVec3::ZERO, scale));
        let fg = foreground(scene, &out);
        let differ: BTreeSet<_> = fg.symmetric_difference(&fg_unit).copied().collect();
        assert!(
            differ.is_subset(&edge),
            "{name}: pixels away from the silhouette differ: {:?}",
            differ.difference(&edge).collect::<Vec<_>>()
        );
        // Interval anti-aliasing: the shading-variation estimator sees gradients of 1e150
        // and 1e-150.
        let mut iaa = scene.clone();
        iaa.settings.aa = Some("iaa".parse().unwrap());
        let out = run(&iaa);
        assert_finite(name, &out);
        let fg = foreground(&iaa, &out);
        let differ: BTreeSet<_> = fg.symmetric_difference(&fg_iaa).copied().collect();
        assert!(
            differ.is_subset(&edge),
            "{name}, IAA: pixels away from the silhouette differ: {:?}",
            differ.difference(&edge).collect::<Vec<_>>()
        );
        // Every pixel that sees the sphere somewhere is drawn.
        assert!(fg_inside.is_subset(&fg), "{name}, IAA: {fg:?}");
    }
}

// ---------------------------------------------------------------------------------------
// 7. Surfaces that leave their bounds.

/// Unclipped formula surfaces reaching outside the scene bounds: rays search only inside
/// the bounds, so a proven Hit box must place every ray's root there. Each ray through a
/// Hit pixel is searched by interval bisection inside the bounds (every reliable finder
/// agrees); it must find a root, and a Miss pixel's ray must not.
#[test]
fn hit_boxes_keep_their_roots_inside_the_bounds() {
    for (formula, eye) in [
        ("1/(x - 0.3) + y", [0.0, 0.5, 5.0]),
        ("tan(x*2) - y - z", [0.2, 0.5, 5.0]),
        ("abs(x)+abs(y)-abs(z)+0.2", [0.3, 0.5, 5.0]),
    ] {
        let scene = scene_from(&format!(
            r#"
[camera]
eye = {eye:?}
look_at = [0.0, 0.0, 0.0]
fov = 50.0
width = 40
height = 30
[[surfaces]]
formula = "{formula}"
bounds = [[-2.0, -2.0, -2.0], [2.0, 2.0, 2.0]]
"#
        ));
        let out = run(&scene);
        let settings = RootSettings::default();
        let mut hits = 0;
        check_classes(formula, &scene, &out, |ray| {
            let r = solve(&scene, RootMethod::Bisection, ray, &settings);
            match r {
                RootResult::NoRoot => Some(false),
                RootResult::Root {
                    proof: Proof::Unique | Proof::Exists,
                    ..
                } => {
                    hits += 1;
                    Some(true)
                }
                _ => None,
            }
        });
        assert!(hits > 0, "{formula}: no proven hit to check");
    }
}

// ---------------------------------------------------------------------------------------
// 8. Objects with partial domains.
//
// Where an object's formula is undefined, the object is absent (docs/renderer.md): the
// other objects are seen there, a difference removes nothing there, and the boundary of
// the domain is not a surface.

/// A scene of the given `[[surfaces]]` and `[[csg]]` tables, seen from `(0, 0, 5)`.
fn domain_scene(tables: &str) -> Scene {
    scene_from(&format!(
        r#"
background = [0.0, 0.0, 0.0]
[camera]
eye = [0.0, 0.5, 5.0]
look_at = [0.0, 0.0, 0.0]
fov = 40.0
width = 40
height = 30
[[lights]]
type = "point"
position = [2.0, 4.0, 5.0]
{tables}
"#
    ))
}

/// Every reliable finder, with the scene function and through the grid, proves that `ray`
/// meets no surface: where the ray crosses a domain boundary the jump is no root, not even
/// a possible one.
fn assert_no_root(scene: &Scene, what: &str, ray: &Ray) {
    let s = RootSettings::default();
    for (m, r) in check_all(scene, what, ray, Truth::Miss, &s) {
        assert_eq!(r, RootResult::NoRoot, "{what}: {m}");
    }
}

/// Every reliable finder proves the first root of `ray` at `t1` (up to the root-finder
/// tolerance).
fn assert_proven_root(scene: &Scene, what: &str, ray: &Ray, t1: f64) {
    let s = RootSettings::default();
    for (m, r) in check_all(scene, what, ray, Truth::Root(t1), &s) {
        assert_eq!(outcome(&r), Outcome::ProvenHit, "{what}: {m}: {r:?}");
    }
}

fn ray(origin: [f64; 3], dir: [f64; 3]) -> Ray {
    Ray {
        origin: DVec3::from(origin),
        dir: DVec3::from(dir),
    }
}

const FLOOR: &str = r#"
[[surfaces]]
name = "floor"
formula = "y + 1"
bounds = [[-3.0, -1.25, -3.0], [3.0, -1.0, 3.0]]
clip = true
material = { color = [0.7, 0.7, 0.68] }
"#;

#[test]
fn floor_with_an_object_undefined_everywhere_renders_as_the_floor_alone() {
    // `sqrt(-1 - x² - z²)` is nowhere defined: as a set-based interval it is empty, and
    // `min(floor, empty)` used to hide the floor wherever the ghost's box reached.
    let ghost = r#"
[[surfaces]]
name = "ghost"
formula = "sqrt(-1 - x^2 - z^2) + y"
bounds = [[-1.0, -1.25, -1.0], [1.0, -1.0, 1.0]]
material = { color = [1.0, 0.0, 0.0] }
"#;
    let alone = run(&domain_scene(FLOOR));
    let with_ghost = run(&domain_scene(&format!("{FLOOR}{ghost}")));
    assert!(
        alone.image.pixels.iter().any(|p| p[0] > 0.1),
        "the floor is in view"
    );
    assert_eq!(alone.image.pixels, with_ghost.image.pixels);
    assert_eq!(alone.box_classes(), with_ghost.box_classes());
}

#[test]
fn sqrt_surface_next_to_a_sphere() {
    // `z - sqrt(x)` is defined for x ≥ 0 only; the ball lies where it is not.
    let scene = domain_scene(
        r#"
[[surfaces]]
name = "root"
formula = "z - sqrt(x)"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
[[surfaces]]
name = "ball"
formula = "(x + 0.6)^2 + y^2 + z^2 - 0.09"
bounds = [[-0.9, -0.3, -0.3], [-0.3, 0.3, 0.3]]
"#,
    );
    // The ball is seen, and its hits are proven.
    assert_proven_root(
        &scene,
        "to the ball",
        &ray([-0.6, 0.0, 5.0], [0.0, 0.0, -1.0]),
        4.7,
    );
    // The surface itself: 0.5 − √x = 0 at x = 0.25.
    assert_proven_root(
        &scene,
        "to the root",
        &ray([2.0, 0.0, 0.5], [-1.0, 0.0, 0.0]),
        1.75,
    );
    // Inside the solid (z < √x) across the boundary x = 0 into the undefined half, and back:
    // a jump between −0.5 and the absent object, which is not a surface.
    assert_no_root(
        &scene,
        "out of the domain",
        &ray([2.0, 0.0, -0.5], [-1.0, 0.0, 0.0]),
    );
    assert_no_root(
        &scene,
        "into the domain",
        &ray([-2.0, 0.0, -0.5], [1.0, 0.0, 0.0]),
    );

    // Every pixel whose rays all meet the ball shows it (before, the root's empty value
    // over x < 0 hid it).
    let out = run(&scene);
    let cam = &scene.camera;
    let centre = DVec3::new(-0.6, 0.0, 0.0);
    let mut on_ball = 0;
    for y in 0..cam.height() {
        for x in 0..cam.width() {
            let rays = pixel_rays(cam, x, y);
            if rays
                .iter()
                .all(|r| matches!(sphere_truth(r, centre, 0.3), Truth::Root(_)))
            {
                on_ball += 1;
                let c = out.image.get(x, y);
                assert!(
                    c.iter().any(|&v| v > 0.05),
                    "pixel ({x}, {y}) shows the ball: {c:?}"
                );
            }
        }
    }
    assert!(on_ball > 4, "the ball covers {on_ball} pixels");
}

#[test]
fn ln_and_asin_domains() {
    let ln = domain_scene(
        r#"
[[surfaces]]
formula = "ln(x) + 2 - y"
bounds = [[-3.0, -3.0, -3.0], [3.0, 3.0, 3.0]]
"#,
    );
    // ln(x) + 2 − y = 0 at y = 0: x = e⁻².
    let t = 4.0 - (-2.0_f64).exp();
    assert_proven_root(
        &ln,
        "ln: to the surface",
        &ray([4.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        t,
    );
    // From inside the solid (ln x < y − 2) out through x = 0, where ln x → −∞.
    assert_no_root(
        &ln,
        "ln: out of the domain",
        &ray([1.0, 2.9, 0.0], [-1.0, 0.0, 0.0]),
    );

    let asin = domain_scene(
        r#"
[[surfaces]]
formula = "z - asin(x)"
bounds = [[-2.0, -2.0, -2.0], [2.0, 2.0, 2.0]]
"#,
    );
    let t = 0.5_f64.sin();
    assert_proven_root(
        &asin,
        "asin: to the surface",
        &ray([0.0, 0.0, 0.5], [1.0, 0.0, 0.0]),
        t,
    );
    // z = −1.9 lies below asin(x) ≥ −π/2 for every |x| ≤ 1: inside the solid up to |x| = 1.
    for dir in [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0]] {
        let what = format!("asin: out of the domain along {dir:?}");
        assert_no_root(&asin, &what, &ray([0.0, 0.0, -1.9], dir));
    }
}

#[test]
fn csg_difference_with_a_partial_domain_object() {
    // The hole `√x + y² + z² < 0.5` exists for x ≥ 0 only: where it is undefined the cube
    // keeps its front face (before, `max(cube, −empty)` erased the cube there).
    let scene = domain_scene(
        r#"
[[surfaces]]
name = "cube"
formula = "max(abs(x), abs(y), abs(z)) - 0.8"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
[[surfaces]]
name = "hole"
formula = "sqrt(x) + y^2 + z^2 - 0.5"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
[[csg]]
name = "holed"
op = "difference"
children = ["cube", "hole"]
"#,
    );
    for x in [-0.4, 0.1, 0.5] {
        let what = format!("to the cube's face at x = {x}");
        assert_proven_root(&scene, &what, &ray([x, 0.0, 5.0], [0.0, 0.0, -1.0]), 4.2);
    }
    // The hole is a cavity inside the cube (on y = z = 0 it spans 0 <= x < 0.25): the side
    // faces are there, and from inside the solid its curved wall at x = 0.25 is a root.
    assert_proven_root(
        &scene,
        "left face",
        &ray([-2.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        1.2,
    );
    assert_proven_root(
        &scene,
        "right face",
        &ray([2.0, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        1.2,
    );
    assert_proven_root(
        &scene,
        "cavity wall",
        &ray([0.5, 0.0, 0.0], [-1.0, 0.0, 0.0]),
        0.25,
    );
}

// ---------------------------------------------------------------------------------------
// 9. Large terms that cancel, and clusters of close roots: precision escalation.
//
// `f64` rounding of large terms leaves enclosures no bisection can narrow; a search that
// ends open for that reason runs again in double-double (`root::Escalating`).

/// The first root of `ray` with `method` escalating as the renderer does, and the counters.
fn solve_escalating(
    scene: &Scene,
    method: RootMethod,
    ray: &Ray,
    settings: &RootSettings,
) -> (RootResult, RootCounters) {
    let mut counters = RootCounters::default();
    let finder = Escalating::new(method.finder());
    let r = search(scene, &finder, ray, settings, &mut counters);
    (r, counters)
}

/// The finders with interval Newton steps. The others bisect: over a piece of width `w` the
/// natural extension of these formulas is about `2K·w` wide (the dependency between the
/// large terms, which no precision removes), so their final pieces stay open far from the
/// root whatever the precision; they are checked for soundness only.
const NEWTON_FINDERS: [RootMethod; 4] = [
    RootMethod::Newton,
    RootMethod::NewtonAlefeldHansen,
    RootMethod::NewtonHc4,
    RootMethod::MrfroNewton,
];

/// Unit spheres written with terms of size `K` that cancel exactly, for `K` from 1e4 to
/// 1e12 (every constant is a double, so the formulas are exactly the unit sphere).
const CANCELLING: [&str; 8] = [
    "(x + 1e4)^2 - 2e4*x - 1e8 + y^2 + z^2 - 1",
    "(x + 1e6)^2 - 2e6*x - 1e12 + y^2 + z^2 - 1",
    "(x + 1e11)^2 - 2e11*x - 1e22 + y^2 + z^2 - 1",
    "((x + 1e4) - 1e4)^2 + y^2 + z^2 - 1",
    "((x + 1e8) - 1e8)^2 + y^2 + z^2 - 1",
    "((x + 1e12) - 1e12)^2 + y^2 + z^2 - 1",
    "(x + 1e6)*(x - 1e6) + 1e12 + y^2 + z^2 - 1",
    "(x + 1e11)*(x - 1e11) + 1e22 + y^2 + z^2 - 1",
];

#[test]
fn cancellation_at_several_scales_is_decided_by_escalation() {
    let s = RootSettings::default();
    let fan = ray_fan(1.0);
    for formula in std::iter::once("x^2 + y^2 + z^2 - 1").chain(CANCELLING) {
        let scene = formula_scene(formula, 1.25, 5.0, 16, "");
        let mut escalated = 0;
        for (i, ray) in fan.iter().enumerate() {
            let truth = sphere_truth(ray, DVec3::ZERO, 1.0);
            let want = match truth {
                Truth::Miss => Outcome::ProvenMiss,
                Truth::Root(_) => Outcome::ProvenHit,
            };
            for m in NEWTON_FINDERS {
                let what = format!("{formula}: ray {i}");
                let (r, c) = solve_escalating(&scene, m, ray, &s);
                check(&what, m, &r, truth);
                assert_eq!(outcome(&r), want, "{what}: {m}: {r:?}");
                assert_eq!(c.escalated, c.escalated_resolved, "{what}: {m}");
                escalated += c.escalated;
            }
        }
        eprintln!("{formula}: {escalated} searches escalated");
        if formula == "x^2 + y^2 + z^2 - 1" {
            assert_eq!(escalated, 0, "the plain sphere needs no escalation");
        }
        if formula.contains("1e11") {
            // The f64 enclosure of `g` at one point is about 1e6 wide (the ulp of 1e22):
            // nothing is decided in f64. Smaller terms are decided by the mean-value form
            // and the look-around in f64 already, and do not escalate.
            assert!(
                escalated > 0,
                "{formula}: rounding should have forced escalation"
            );
        }
    }
}

#[test]
fn cancellation_renders_as_the_plain_sphere() {
    // Screen rays at every pixel: hits proven, and the image equal to the plain formula's
    // up to the shading of points placed within the root-finder tolerance.
    let render_of = |formula: &str| {
        run(&formula_scene(
            formula,
            1.25,
            5.0,
            24,
            "primary = \"screen-rays\"\nrays_per_undecided = 1",
        ))
    };
    let plain = render_of("x^2 + y^2 + z^2 - 1");
    let hits = plain.stats.pass("primary-rays").unwrap().counter("hits");
    assert!(hits > 0);
    for formula in [CANCELLING[1], CANCELLING[5], CANCELLING[7]] {
        let out = render_of(formula);
        let rays = out.stats.pass("primary-rays").unwrap();
        assert_eq!(rays.counter("hits"), hits, "{formula}");
        assert_eq!(
            rays.counter("proven_unique"),
            hits,
            "{formula}: every hit proven"
        );
        assert_eq!(
            rays.counter("escalated"),
            rays.counter("escalated_resolved")
        );
        let differ = out
            .image
            .pixels
            .iter()
            .zip(&plain.image.pixels)
            .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| (x - y).abs() > 1e-3))
            .count();
        assert_eq!(
            differ, 0,
            "{formula}: {differ} pixels differ from the plain sphere"
        );
    }
}

#[test]
fn a_cluster_of_close_roots_is_separated_by_escalation() {
    // Two planes 2^-30 apart, written expanded: z² − (0.5 + 2^-30)·z + 0.0625 + 2^-32
    // = (z − 0.25)·(z − 0.25 − 2^-30). Between them g is about −2^-62, far below the f64
    // rounding of its terms (about 1e-17): only double-double proves the sign change.
    let scene = formula_scene(
        "z^2 - (0.5 + 2^-30)*z + 0.0625 + 2^-32 + 0*x",
        1.25,
        5.0,
        16,
        "",
    );
    let s = RootSettings {
        epsilon: 1e-11,
        ..RootSettings::default()
    };
    let b = 0.25 + 2f64.powi(-30);
    for (x, y) in [(0.0, 0.0), (0.3, -0.2), (-0.7, 0.5)] {
        let ray = Ray {
            origin: DVec3::new(x, y, 5.0),
            dir: DVec3::new(0.0, 0.0, -1.0),
        };
        for m in reliable() {
            let what = format!("cluster at ({x}, {y})");
            let (r, c) = solve_escalating(&scene, m, &ray, &s);
            check(&what, m, &r, Truth::Root(5.0 - b));
            if !NEWTON_FINDERS.contains(&m) {
                continue;
            }
            assert_eq!(outcome(&r), Outcome::ProvenHit, "{what}: {m}: {r:?}");
            assert!(c.escalated > 0, "{what}: {m} needed no escalation");
            let plain = RootSettings {
                escalate: false,
                ..s
            };
            let (open, _) = solve_escalating(&scene, m, &ray, &plain);
            assert_ne!(
                outcome(&open),
                Outcome::ProvenHit,
                "{what}: {m} proved it in f64"
            );
        }
    }
}

#[test]
fn cancelling_beams_are_decided_by_escalation() {
    // Screen boxes and pixel beams (the default primary mode): over a beam the natural
    // extension of the large terms is as wide as they vary (about 4K times the beam's
    // width) in any precision; escalated beams use the double-double centred form, so the
    // boxes are classed as the plain sphere's are. Every proven class is right.
    let render_of = |formula: &str| run(&formula_scene(formula, 1.25, 5.0, 32, ""));
    let plain = render_of("x^2 + y^2 + z^2 - 1");
    let boxes = plain.stats.pass("screen-boxes").unwrap();
    assert_eq!(boxes.counter("escalated"), 0, "the plain sphere's beams");
    let plain_undecided = boxes.counter("undecided_pixels");
    for formula in CANCELLING {
        let scene = formula_scene(formula, 1.25, 5.0, 32, "");
        let out = run(&scene);
        check_classes(formula, &scene, &out, sphere_hits(DVec3::ZERO, 1.0));
        let b = out.stats.pass("screen-boxes").unwrap();
        let undecided = b.counter("undecided_pixels");
        eprintln!(
            "{formula}: undecided pixels {undecided} (plain {plain_undecided}), beams escalated {} resolved {}",
            b.counter("escalated"),
            b.counter("escalated_resolved")
        );
        assert!(
            undecided <= 2 * plain_undecided,
            "{formula}: {undecided} undecided pixels against the plain sphere's {plain_undecided}"
        );
        if formula.contains("1e11") {
            assert!(b.counter("escalated_resolved") > 0, "{formula}");
        }
        let differ = out
            .image
            .pixels
            .iter()
            .zip(&plain.image.pixels)
            .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| (x - y).abs() > 0.02))
            .count();
        eprintln!("{formula}: {differ} pixels differ by more than 0.02");
    }
}

#[test]
fn escalated_beams_class_random_cancelling_ellipsoids_soundly() {
    // Ellipsoids with random centres and radii, each coordinate written with its own large
    // terms that cancel, `((x − c) + K)² − 2K(x − c) − K²` for K from 1e3 to 1e12: the
    // screen boxes and pixel beams of the default mode escalate, and every class they prove
    // is checked against the exact ellipsoid (a grazing ray, whose answer rounding could
    // change, proves nothing either way).
    let mut state = 0x5851_f42d_4c95_7f2d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut escalated = 0;
    for case in 0..6 {
        let c: [f64; 3] = std::array::from_fn(|_| 0.6 * next() - 0.3);
        let r: [f64; 3] = std::array::from_fn(|_| 0.5 + 0.4 * next());
        let k: [f64; 3] = std::array::from_fn(|_| 10f64.powi(3 + (9.0 * next()) as i32));
        let terms: Vec<String> = ["x", "y", "z"]
            .iter()
            .enumerate()
            .map(|(i, v)| {
                let (ci, ki, ri) = (c[i], k[i], r[i]);
                format!(
                    "(({v} - ({ci:e}) + {ki:e})^2 - 2*{ki:e}*({v} - ({ci:e})) - {ksq:e}) / {rsq:e}",
                    ksq = ki * ki,
                    rsq = ri * ri
                )
            })
            .collect();
        let formula = format!("{} - 1", terms.join(" + "));
        let scene = formula_scene(&formula, 1.25, 5.0, 24, "");
        let out = run(&scene);
        let truth = |ray: &Ray| {
            // The ray in the ellipsoid's unit-sphere coordinates.
            let o = DVec3::from_array(std::array::from_fn(|i| (ray.origin[i] - c[i]) / r[i]));
            let d = DVec3::from_array(std::array::from_fn(|i| ray.dir[i] / r[i]));
            let (a, b, cc) = (d.dot(d), o.dot(d), o.dot(o) - 1.0);
            let disc = b * b - a * cc;
            if disc.abs() <= 1e-9 * b * b {
                None
            } else {
                Some(disc > 0.0 && b < 0.0)
            }
        };
        check_classes(&formula, &scene, &out, truth);
        let boxes = out.stats.pass("screen-boxes").unwrap();
        assert!(boxes.counter("hit_pixels") > 0, "case {case}: {formula}");
        escalated += boxes.counter("escalated_resolved");
    }
    // The K ≥ 1e6 terms keep f64 beams open: some escalations must have decided them.
    assert!(escalated > 0);
}
