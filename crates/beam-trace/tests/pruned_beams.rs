//! Screen boxes searched with pruned tapes keep their proofs: on a model whose formula is
//! long enough to be pruned per beam and per range (a `min`/`max` tree of many primitives,
//! as a `.vm` model is), the central ray of every pixel of a box proven Miss meets
//! nothing, and that of every pixel of a box proven Hit meets the model, as per-pixel rays
//! searched with the whole function find.

use beam_trace::beam::BoxClass;
use beam_trace::{NoProgress, RenderOutput, Scene, render};

/// SplitMix64: a seeded generator for the primitives' placement.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// One formula: the union (`min`) of `n` primitives in `[-1, 1]³`: spheres, boxes
/// (`max` of slabs) and boxes with a spherical bite (`max(box, -sphere)`).
fn model(n: usize, seed: u64) -> String {
    let mut rng = Rng(seed);
    let mut parts = Vec::new();
    for i in 0..n {
        let (a, b, c) = (
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
            rng.range(-0.8, 0.8),
        );
        let r = rng.range(0.08, 0.25);
        let sphere = |a: f64, b: f64, c: f64, r: f64| {
            format!("(sqrt((x - {a:.4})^2 + (y - {b:.4})^2 + (z - {c:.4})^2) - {r:.4})")
        };
        let cube = format!(
            "max(abs(x - {a:.4}) - {r:.4}, abs(y - {b:.4}) - {:.4}, abs(z - {c:.4}) - {r:.4})",
            1.5 * r
        );
        parts.push(match i % 3 {
            0 => sphere(a, b, c, r),
            1 => cube,
            _ => format!("max({cube}, -{})", sphere(a + r, b + r, c, 0.7 * r)),
        });
    }
    // A balanced tree of `min`, as the model generators write it.
    while parts.len() > 1 {
        parts = parts
            .chunks(2)
            .map(|p| match p {
                [a, b] => format!("min({a}, {b})"),
                [a] => a.clone(),
                _ => unreachable!(),
            })
            .collect();
    }
    parts.pop().unwrap()
}

fn render_model(formula: &str, size: u32, settings: &str) -> RenderOutput {
    let text = format!(
        r#"
background = [0.0, 0.0, 0.0]

[camera]
eye = [0.6, 0.9, 3.2]
look_at = [0.0, 0.0, 0.0]
fov = 45.0
width = {size}
height = {size}

[[surfaces]]
name = "model"
formula = "{formula}"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
clip = true
material = {{ color = [1.0, 1.0, 1.0] }}

[render]
{settings}
"#
    );
    let scene = Scene::from_toml(&text, "model.toml", None).unwrap_or_else(|e| panic!("{e}"));
    render(&scene, &NoProgress).unwrap()
}

/// Renders the model with screen boxes (`settings`) and with per-pixel rays, and checks
/// every proven box class against the per-pixel central ray's result.
fn check_box_classes(settings: &str) {
    let formula = model(48, 7);
    assert!(formula.len() > 4000, "a long formula");
    let size = 64;
    let boxes = render_model(
        &formula,
        size,
        &format!("primary = \"screen-rays\"\nrays_per_undecided = 1\n{settings}"),
    );
    let rays = render_model(&formula, size, "primary = \"per-pixel\"\ngrid = 0");
    let (mut miss, mut hit) = (0, 0);
    for (p, class) in boxes.box_classes().iter().enumerate() {
        // White where the pixel's ray meets the model (no light: the material's colour),
        // black where it does not.
        let seen = rays.image.pixels[p][0] > 0.5;
        match class {
            Some(BoxClass::Miss) => {
                miss += 1;
                assert!(
                    !seen,
                    "pixel {p}: its box is proven Miss, its ray meets the model"
                );
            }
            Some(BoxClass::Hit { .. }) => {
                hit += 1;
                assert!(
                    seen,
                    "pixel {p}: its box is proven Hit, its ray has no root"
                );
            }
            _ => {}
        }
    }
    assert!(miss > 100 && hit > 100, "{miss} Miss and {hit} Hit pixels");
}

#[test]
fn pruned_screen_boxes_keep_their_proofs_without_a_grid() {
    check_box_classes("grid = 0");
}

#[test]
fn pruned_screen_boxes_keep_their_proofs_with_the_grid() {
    check_box_classes("");
}
