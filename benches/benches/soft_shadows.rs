//! Soft-shadow methods side by side on the same scene and image: the whole render of
//! `scenes/soft-shadows.toml` at 64 × 48 (primary visibility is the same work in every
//! run; the soft-shadow pass is what differs), with the stochastic baseline at 16 and 64
//! samples, the beam method and its variants at 7 × 7 sub-beams, and the Minkowski
//! detection with both fine steps.
//!
//! `cargo bench -p benches --bench soft_shadows`; the `soft-shadows` and `accuracy-cost`
//! examples report the per-pass times and the errors.

use std::path::Path;

use beam_trace::scene::AaMode;
use beam_trace::shadow::ShadowSpec;
use beam_trace::{NoProgress, Scene, render};
use criterion::Criterion;

const METHODS: [&str; 8] = [
    "stochastic:16",
    "stochastic:64",
    "stochastic:64:cache",
    "beam:7",
    "beam-all:7",
    "beam-quadtree:7",
    "minkowski:stochastic:64",
    "minkowski:beam:7",
];

fn scene() -> Scene {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/soft-shadows.toml");
    let mut s = Scene::load(&file).expect("the scene loads");
    s.camera = s.camera.resized(64, 48).expect("a valid size");
    // The soft-shadow methods are measured, one sample per Hit pixel.
    s.settings.aa = Some(AaMode::None);
    s
}

fn bench(c: &mut Criterion) {
    let base = scene();
    let mut group = c.benchmark_group("soft_shadows");
    group.sample_size(10);
    for m in METHODS {
        let mut s = base.clone();
        s.settings.shadow_method = m.parse::<ShadowSpec>().expect("a method name");
        group.bench_function(m, |b| {
            b.iter(|| render(&s, &NoProgress).expect("the render succeeds"))
        });
    }
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
