//! Primary visibility on the adapter against the CPU renderer, pixel by pixel: for a few
//! catalog surfaces, each pixel's beam is classified on the GPU (counter-based bisection in
//! `f32` intervals) and the central ray of the pixel is searched on the CPU in `f64` with
//! Newton + Alefeld-Hansen. A proven GPU miss never meets a proven CPU root; a proven GPU hit
//! is never a proven CPU miss, and its section holds the CPU's proven first root.

use beam_trace::root::{Proof, RootCounters, RootMethod, RootResult, RootSettings};
use beam_trace::screen::PixelRect;
use beam_trace::{BeamEval, Scene};
use gpu_backend::Gpu;
use gpu_backend::beams::{BeamKernel, BeamQuery, GpuClass, KernelSettings};
use interval_core::Interval;

const SIZE: u32 = 40;

#[test]
fn gpu_classes_never_contradict_cpu_roots() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let finder = RootMethod::NewtonAlefeldHansen.finder();
    let settings = RootSettings::default();
    let mut failures = Vec::new();
    for name in [
        "sphere",
        "chubs",
        "orthocircle",
        "kusner-schmitt",
        "mcmullen-k3",
        "blobby",
        "twist",
        "drop",
    ] {
        let scene = Scene::catalog(name, SIZE, SIZE).expect("a catalog scene");
        let geometry = &scene.geometry;
        let bounds = geometry.bounds();
        let kernel = BeamKernel::new(&gpu, geometry.tape(), bounds).expect("the kernel compiles");
        let rects: Vec<PixelRect> = (0..SIZE * SIZE)
            .map(|i| PixelRect {
                x0: i % SIZE,
                y0: i / SIZE,
                x1: i % SIZE + 1,
                y1: i / SIZE + 1,
            })
            .collect();
        // The CPU plan's beam tolerance: 10^-3 of the scene diagonal.
        let gpu_settings = KernelSettings {
            epsilon: (1e-3 * geometry.diagonal()) as f32,
            ..KernelSettings::default()
        };
        let queries: Vec<BeamQuery> = rects
            .iter()
            .map(|r| {
                let beam = scene.camera.beam(
                    f64::from(r.x0),
                    f64::from(r.y0),
                    f64::from(r.x1),
                    f64::from(r.y1),
                );
                let t = beam.t_range(&bounds).map_or(Interval::EMPTY, |t| {
                    t.intersection(Interval::new(0.0, f64::MAX).unwrap())
                });
                BeamQuery { beam, t }
            })
            .collect();
        let gpu_pixels = kernel
            .classify(&gpu, &queries, &gpu_settings)
            .expect("the GPU classifies");
        let mut eval = BeamEval::new(geometry.ray_function());
        let (mut miss, mut hit, mut undecided, mut agree) = (0, 0, 0, 0);
        for (r, px) in rects.iter().zip(&gpu_pixels) {
            let ray = scene
                .camera
                .ray(f64::from(r.x0) + 0.5, f64::from(r.y0) + 0.5);
            let cpu = match ray.beam().t_range(&bounds) {
                Some(t) => {
                    eval.set_ray(&ray);
                    finder.first_root(&mut eval, t, &settings, &mut RootCounters::default())
                }
                None => RootResult::NoRoot,
            };
            let proven_root = match cpu {
                RootResult::Root { t, proof } if proof != Proof::Possible => Some(t),
                _ => None,
            };
            let bad = match px.class {
                GpuClass::Miss => {
                    miss += 1;
                    agree += u32::from(cpu == RootResult::NoRoot);
                    proven_root.is_some()
                }
                GpuClass::Hit { t } => {
                    hit += 1;
                    let holds =
                        proven_root.is_none_or(|c| c.inf() <= t.sup() && t.inf() <= c.sup());
                    agree += u32::from(proven_root.is_some() && holds);
                    cpu == RootResult::NoRoot || !holds
                }
                GpuClass::Undecided { .. } => {
                    undecided += 1;
                    false
                }
            };
            if bad && failures.len() < 10 {
                failures.push(format!(
                    "{name} pixel {r:?}: GPU {:?}, CPU {cpu:?}",
                    px.class
                ));
            }
        }
        eprintln!(
            "{name}: GPU miss {miss}, hit {hit}, undecided {undecided} (inclusion {}); {agree} agree with the CPU's proofs",
            kernel.proves_hits()
        );
        assert!(miss > 0, "{name}: no pixel proven empty");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
