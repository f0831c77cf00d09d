//! Every catalog surface's interval function, generated as WGSL by implicit-expr and run on
//! the adapter with the interval library: over random boxes of every size inside the
//! surface's bounds, the GPU's enclosure contains the function's `f64` values at the box's
//! corners, centre and random points. Skipped without an adapter (failed under `CI`), as the
//! library tests are.

use beam_trace::Scene;
use gpu_backend::Gpu;
use gpu_backend::surface::{IBox, SurfaceKernel};
use implicit_expr::catalog;
use interval_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// A random box inside `bounds`, of a random size from `10^-5` of the bounds to all of them.
fn random_box(rng: &mut StdRng, bounds: &IBox) -> IBox {
    let scale = 10f64.powf(rng.gen_range(-5.0..0.0));
    std::array::from_fn(|k| {
        let (lo, hi) = bounds[k].bounds().expect("bounded");
        let w = (hi - lo) * scale;
        let a = rng.gen_range(lo..=hi - w);
        Interval::new(a, a + w).expect("ordered")
    })
}

/// Points of `b`: its corners, its centre and a few random ones.
fn points(rng: &mut StdRng, b: &IBox) -> Vec<[f64; 3]> {
    let mut out: Vec<[f64; 3]> = (0..8)
        .map(|c| {
            std::array::from_fn(|k| {
                if c >> k & 1 == 0 {
                    b[k].inf()
                } else {
                    b[k].sup()
                }
            })
        })
        .collect();
    out.push(std::array::from_fn(|k| b[k].mid()));
    for _ in 0..4 {
        out.push(std::array::from_fn(|k| {
            rng.gen_range(b[k].inf()..=b[k].sup())
        }));
    }
    out
}

#[test]
fn generated_surfaces_enclose_their_point_values() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let mut failures = Vec::new();
    for (s, name) in catalog::names().enumerate() {
        let scene = Scene::catalog(name, 8, 8).expect("a catalog scene");
        let geometry = &scene.geometry;
        let kernel =
            SurfaceKernel::new(&gpu, geometry.tape()).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut rng = StdRng::seed_from_u64(s as u64);
        let boxes: Vec<IBox> = (0..4000)
            .map(|_| random_box(&mut rng, &geometry.bounds()))
            .collect();
        let enclosures = kernel.eval(&gpu, &boxes).expect("the GPU evaluates");
        let (mut checked, mut bad) = (0, 0);
        for (b, e) in boxes.iter().zip(&enclosures) {
            for p in points(&mut rng, b) {
                let v = geometry
                    .context()
                    .eval::<f64>(geometry.root(), &p)
                    .expect("a point value");
                if !v.is_finite() {
                    continue;
                }
                checked += 1;
                if !e.contains(v) {
                    bad += 1;
                    if failures.len() < 10 {
                        failures.push(format!("{name}: f{p:?} = {v} not in {e:?} over {b:?}"));
                    }
                }
            }
        }
        eprintln!("{name}: {checked} point values, {bad} outside the GPU enclosures");
        assert!(checked > 10_000, "{name}: only {checked} finite values");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
