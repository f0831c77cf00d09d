//! Criterion benchmarks of the root finders of `beam-trace` (thesis Table 4.1): for each
//! surface of the table, every method casts the same 32 × 32 primary rays, one thread.
//!
//! ```text
//! cargo bench -p benches --bench root_finders
//! cargo bench -p benches --bench root_finders -- root_finders/sphere   # one surface
//! ROOT_BENCH_SURFACES=all cargo bench -p benches --bench root_finders  # every catalog surface
//! ```
//!
//! Groups are named `root_finders/<surface>`, functions by the method's name
//! (`bisection`, `mitchell`, ..., and the unreliable baselines `point-sampling` and
//! `sphere-tracing`); the throughput is one ray per element. The camera looks at the
//! surface's bounding box from the direction `(1, 0.8, 2.2)` with a 40° field of view, and
//! each ray is clipped to the box (`examples::catalog_view`, shared with the `root-finders`
//! example, which prints the same comparison as a table, with counters and an agreement
//! check).

use std::hint::black_box;
use std::time::Duration;

use beam_trace::Geometry;
use beam_trace::ray::{BeamEval, Ray};
use beam_trace::root::{RootCounters, RootMethod, RootSettings};
use criterion::{Criterion, Throughput};
use examples::catalog_view::{CatalogView, TABLE_4_1};
use implicit_expr::catalog;
use interval_core::Interval;

/// Rays per image side.
const SIZE: u32 = 32;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
}

/// The geometry of a catalog surface and the rays of its image that enter its box, each
/// with its parameter range inside the box.
fn workload(name: &str) -> (Geometry, Vec<(Ray, Interval<f64>)>) {
    let view = CatalogView::new(name, SIZE).expect("catalog surface");
    let rays = (0..SIZE * SIZE)
        .filter_map(|p| match view.ray(p % SIZE, p / SIZE) {
            (ray, Some(t)) => Some((ray, t)),
            (_, None) => None,
        })
        .collect();
    (view.geometry, rays)
}

fn root_finders(c: &mut Criterion) {
    let names: Vec<&str> = match std::env::var("ROOT_BENCH_SURFACES").as_deref() {
        Ok("all") => catalog::names().collect(),
        _ => TABLE_4_1.to_vec(),
    };
    let settings = RootSettings::default();
    for name in names {
        let (geometry, rays) = workload(name);
        let mut ev = BeamEval::new(geometry.ray_function());
        let mut g = c.benchmark_group(format!("root_finders/{name}"));
        g.throughput(Throughput::Elements(u64::from(SIZE * SIZE)));
        for m in RootMethod::ALL {
            let finder = m.finder();
            g.bench_function(m.name(), |b| {
                b.iter(|| {
                    let mut counters = RootCounters::default();
                    let mut hits = 0u32;
                    for (ray, t) in &rays {
                        ev.set_ray(ray);
                        let r = finder.first_root(&mut ev, *t, &settings, &mut counters);
                        hits += u32::from(r.root().is_some());
                    }
                    black_box((hits, counters))
                })
            });
        }
        g.finish();
    }
}

fn main() {
    let mut c = config().configure_from_args();
    root_finders(&mut c);
    c.final_summary();
}
