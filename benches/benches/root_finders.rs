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
//! each ray is clipped to the box, as in the `root_finders` example of the `examples`
//! package (which prints the same comparison as a table, with counters and an agreement
//! check).

use std::hint::black_box;
use std::time::Duration;

use beam_trace::Camera;
use beam_trace::ray::{BeamEval, IBox, Ray};
use beam_trace::root::{RootCounters, RootMethod, RootSettings};
use beam_trace::scene::{Csg, Geometry, Leaf};
use criterion::{Criterion, Throughput};
use glam::DVec3;
use implicit_expr::{Context, catalog};
use interval_core::Interval;

/// The surfaces of thesis Table 4.1.
const TABLE_4_1: [&str; 8] = [
    "sphere",
    "drop",
    "chubs",
    "crosscap",
    "gumdrop-torus",
    "horned-cube",
    "mcmullen-k3",
    "kusner-schmitt",
];

/// Rays per image side.
const SIZE: u32 = 32;

fn config() -> Criterion {
    Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1))
}

/// The geometry of a catalog surface (parameters bound to their defaults) and the rays of
/// its image that enter its box, each with its parameter range inside the box.
fn workload(name: &str) -> (Geometry, Vec<(Ray, Interval<f64>)>) {
    let s = catalog::get(name).expect("catalog surface");
    let mut ctx = Context::new();
    let f = s.build(&mut ctx).expect("catalog formulas parse");
    let map: Vec<_> = s
        .params
        .iter()
        .map(|&(p, v)| {
            let var = ctx.find_var(p).expect("declared parameter");
            (var, ctx.constant(v).expect("finite parameter"))
        })
        .collect();
    let f = ctx.substitute(f, &map);
    let (ctx, f) = ctx.extract(f);
    let bounds = s.bounding_box();
    let leaf = Leaf {
        name: name.to_string(),
        node: f,
        material: Default::default(),
        bounds,
        clipped: false,
    };
    let geometry = Geometry::new(ctx, vec![leaf], vec![Csg::Leaf(0)]).expect("geometry");
    let lo = DVec3::new(bounds[0].inf(), bounds[1].inf(), bounds[2].inf());
    let hi = DVec3::new(bounds[0].sup(), bounds[1].sup(), bounds[2].sup());
    let center = (lo + hi) * 0.5;
    let fov: f64 = 40.0;
    let distance = (hi - lo).length() * 0.5 / (fov.to_radians() * 0.5).sin();
    let eye = center + DVec3::new(1.0, 0.8, 2.2).normalize() * distance;
    let camera = Camera::new(eye, center, DVec3::Y, fov, SIZE, SIZE).expect("camera");
    let rays = (0..SIZE * SIZE)
        .filter_map(|p| {
            let ray = camera.ray(f64::from(p % SIZE) + 0.5, f64::from(p / SIZE) + 0.5);
            clip(&ray, &bounds).map(|t| (ray, t))
        })
        .collect();
    (geometry, rays)
}

/// The parameter range of `ray` inside the box `b` from `t = 0` on (slab test).
fn clip(ray: &Ray, b: &IBox) -> Option<Interval<f64>> {
    let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for i in 0..3 {
        let (lo, hi) = (b[i].inf(), b[i].sup());
        if d[i] == 0.0 {
            if o[i] < lo || o[i] > hi {
                return None;
            }
            continue;
        }
        let (a, c) = ((lo - o[i]) / d[i], (hi - o[i]) / d[i]);
        t0 = t0.max(a.min(c));
        t1 = t1.min(a.max(c));
    }
    (t0 <= t1).then(|| Interval::new(t0, t1).expect("ordered finite range"))
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
