//! Single-precision interval evaluation of the scene function (`Precision::F32`): its
//! enclosures of `g` contain the `f64` values at sample points and the `f64` enclosures,
//! renders in `f32` and `f64` agree, and precision names parse with clear errors.

use std::path::Path;

use beam_trace::ray::ival;
use beam_trace::scene::RenderSettings;
use beam_trace::{Beam, BeamEval, NoProgress, Precision, RayFn, RenderOutput, Scene, render};
use glam::DVec3;
use interval_core::Interval;
use proptest::prelude::*;

/// The scenes whose functions the property tests evaluate: catalog surfaces (polynomials,
/// `exp`, `sin`/`cos`) and a scene of three surfaces, one clipped (`max`, `min`).
fn scenes() -> Vec<Scene> {
    let mut out: Vec<Scene> = ["sphere", "blobby", "twist", "tri-trumpet", "barth-sextic"]
        .into_iter()
        .map(|n| Scene::catalog(n, 8, 8).unwrap_or_else(|e| panic!("{n}: {e}")))
        .collect();
    out.push(soft_shadows_scene(8, 6));
    out
}

fn soft_shadows_scene(width: u32, height: u32) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/soft-shadows.toml");
    let mut scene = Scene::load(&path).unwrap_or_else(|e| panic!("{e}"));
    scene.camera = scene.camera.resized(width, height).unwrap();
    scene
}

/// `b` contains `a` (the empty set is contained in everything).
fn contains(b: Interval<f64>, a: Interval<f64>) -> bool {
    a.is_empty() || (!b.is_empty() && b.inf() <= a.inf() && a.sup() <= b.sup())
}

/// A beam around the ray `origin + t · dir`: boxes of half-widths `ho` and `hd`.
fn beam(origin: DVec3, dir: DVec3, ho: f64, hd: f64) -> Beam {
    let b = |c: DVec3, h: f64| [0, 1, 2].map(|i| ival(c[i] - h, c[i] + h));
    Beam {
        origin: b(origin, ho),
        dir: b(dir, hd),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// For random rays and thin beams and random parameter intervals `T`, the `f32`
    /// enclosures of `g` (from `g`, `g_dg` and `g_checked`) contain the `f64` values of `g`
    /// at sample parameters in `T` (central ray), and the `f64` enclosures.
    #[test]
    fn f32_enclosures_contain_f64_values_and_enclosures(
        o in prop::array::uniform3(-3.0f64..3.0),
        d in prop::array::uniform3(-1.0f64..1.0),
        t0 in 0.0f64..6.0,
        log_w in -9.0f64..0.5,
        ho in prop_oneof![Just(0.0), 0.0f64..0.05],
        hd in prop_oneof![Just(0.0), 0.0f64..0.05],
    ) {
        let dir = DVec3::from_array(d);
        prop_assume!(dir.length() > 1e-3);
        let b = beam(DVec3::from_array(o), dir, ho, hd);
        let t = ival(t0, t0 + 10f64.powf(log_w));
        for scene in scenes() {
            let f = scene.geometry.ray_function();
            let mut e64 = BeamEval::new(f);
            // Set the beam before the precision: the beam must carry over.
            let mut e32 = BeamEval::new(f);
            e32.set_beam(&b);
            e32.set_precision(Precision::F32);
            prop_assert_eq!(e32.precision(), Precision::F32);
            e64.set_beam(&b);

            let g32 = e32.g(t);
            let (g32b, dg32) = e32.g_dg(t);
            let (g32c, _) = e32.g_checked(t);
            let g64 = e64.g(t);
            let (_, dg64) = e64.g_dg(t);
            let name = &scene.name;
            for k in 0..=16 {
                let s = (t.inf() + t.wid() * f64::from(k) / 16.0).min(t.sup());
                let v = e64.g_point(s);
                if v.is_finite() {
                    for (what, e) in [("g", g32), ("g_dg", g32b), ("g_checked", g32c)] {
                        prop_assert!(
                            !e.is_empty() && e.inf() <= v && v <= e.sup(),
                            "{}: f32 {} over {:?} = {:?} misses g({}) = {}", name, what, t, e, s, v
                        );
                    }
                }
            }
            // Outward rounding of the inputs and of every operation: the f32 enclosure is
            // an f64 interval containing the range over a larger box, so it contains the
            // tightest f64 enclosure of the same operations.
            if g64.inf().is_finite() && g64.sup().is_finite() {
                prop_assert!(contains(g32, g64), "{}: g over {:?}: f32 {:?} ⊉ f64 {:?}", name, t, g32, g64);
            }
            if dg64.inf().is_finite() && dg64.sup().is_finite() {
                prop_assert!(contains(dg32, dg64), "{}: g' over {:?}: f32 {:?} ⊉ f64 {:?}", name, t, dg32, dg64);
            }
        }
    }
}

/// A single ray at a point parameter: the f32 enclosure is at least as wide as the f64 one
/// and both contain the point value.
#[test]
fn f32_is_wider_on_a_ray() {
    let scene = Scene::catalog("sphere", 8, 8).unwrap();
    let f = scene.geometry.ray_function();
    let mut e64 = BeamEval::new(f);
    let mut e32 = BeamEval::with_precision(f, Precision::F32);
    let b = beam(
        DVec3::new(0.1, 0.2, 4.0),
        DVec3::new(0.01, -0.03, -1.0),
        0.0,
        0.0,
    );
    e64.set_beam(&b);
    e32.set_beam(&b);
    let t = ival(3.1, 3.1);
    let (a, w) = (e64.g(t), e32.g(t));
    assert!(contains(w, a), "{w:?} ⊉ {a:?}");
    assert!(
        w.wid() > a.wid(),
        "f32 {w:?} should be wider than f64 {a:?}"
    );
    let v = e64.g_point(3.1);
    assert!(w.inf() <= v && v <= w.sup());
    // Back to f64: the same enclosure as a fresh f64 evaluator.
    e32.set_precision(Precision::F64);
    assert_eq!(e32.g(t), a);
}

fn render_with(precision: Precision) -> RenderOutput {
    let mut scene = soft_shadows_scene(48, 36);
    scene.settings.precision = precision;
    render(&scene, &NoProgress).expect("the render succeeds")
}

/// The soft-shadow scene rendered with f32 and f64 interval evaluation: the images agree on
/// almost every pixel, and the f32 render ran its passes in f32.
#[test]
fn f32_and_f64_renders_agree() {
    let a = render_with(Precision::F64);
    let b = render_with(Precision::F32);
    assert_eq!(a.plan.precision, Precision::F64);
    assert_eq!(b.plan.precision, Precision::F32);
    assert!(
        b.plan.to_string().contains("precision     f32"),
        "{}",
        b.plan
    );
    for name in ["pixel-beams", "soft-shadows"] {
        let p = b.stats.pass(name).unwrap();
        assert!(p.ran && p.total_work() > 0, "{name}:\n{}", b.stats);
    }
    // The f32 enclosures are wider, so the searches do different work.
    let work = |o: &RenderOutput| {
        ["screen-boxes", "pixel-beams", "soft-shadows"]
            .map(|n| o.stats.pass(n).unwrap().total_work())
    };
    assert_ne!(
        work(&a),
        work(&b),
        "f32 and f64 renders counted the same work"
    );

    let (w, h) = (a.image.width, a.image.height);
    assert_eq!((w, h), (48, 36));
    let mut close = 0;
    for y in 0..h {
        for x in 0..w {
            let (p, q) = (a.image.get(x, y), b.image.get(x, y));
            if (0..3).all(|c| (p[c] - q[c]).abs() <= 0.05) {
                close += 1;
            }
        }
    }
    let total = w * h;
    assert!(
        f64::from(close) >= 0.95 * f64::from(total),
        "only {close} of {total} pixels agree within 0.05"
    );
}

#[test]
fn precision_names_parse_and_print() {
    for p in [Precision::F64, Precision::F32] {
        assert_eq!(p.to_string().parse::<Precision>(), Ok(p));
    }
    assert_eq!("f32".parse::<Precision>(), Ok(Precision::F32));
    assert_eq!(Precision::default(), Precision::F64);
    for bad in ["f16", "F32", "", "double", "f32 "] {
        let err = bad.parse::<Precision>().unwrap_err();
        assert!(
            err.contains(&format!("unknown precision '{bad}'"))
                && err.contains("f64")
                && err.contains("f32"),
            "{bad:?}: {err}"
        );
    }
}

#[test]
fn precision_in_scene_files_and_settings() {
    let text = "[camera]\nwidth = 8\nheight = 8\n[[surfaces]]\ncatalog = \"sphere\"\n[render]\nprecision = \"f32\"\n";
    let scene = Scene::from_toml(text, "p.toml", None).unwrap();
    assert_eq!(scene.settings.precision, Precision::F32);
    let json = serde_json::to_string(&scene.settings).unwrap();
    assert!(json.contains(r#""precision":"f32""#), "{json}");
    assert_eq!(RenderSettings::default().precision, Precision::F64);

    let bad = text.replace("\"f32\"", "\"half\"");
    let err = Scene::from_toml(&bad, "p.toml", None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("render.precision") && err.contains("unknown precision 'half'"),
        "{err}"
    );
}
