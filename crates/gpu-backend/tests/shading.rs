//! The GPU Phong kernel against beam-trace's `phong` on random samples and lights.

use beam_trace::scene::Material;
use beam_trace::shading::{Incoming, phong};
use glam::DVec3;
use gpu_backend::Gpu;
use gpu_backend::shading::{MAX_LIGHTS, ShadeLight, ShadingInput, ShadingKernel};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

fn unit(rng: &mut StdRng) -> DVec3 {
    DVec3::new(
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
        rng.gen_range(-1.0..1.0),
    )
    .normalize_or(DVec3::Y)
}

#[test]
fn gpu_phong_matches_the_cpu() {
    let Some(gpu) = Gpu::for_tests() else { return };
    let kernel = ShadingKernel::new(&gpu).expect("the kernel compiles");
    let mut rng = StdRng::seed_from_u64(5);
    let lights: Vec<ShadeLight> = (0..3)
        .map(|_| ShadeLight {
            position: unit(&mut rng) * 10.0,
            color: [rng.gen_range(0.0..1.0), rng.gen_range(0.0..1.0), 1.0],
        })
        .collect();
    let samples: Vec<ShadingInput> = (0..2000)
        .map(|_| {
            let mut fractions = [0f32; MAX_LIGHTS];
            for f in fractions.iter_mut().take(lights.len()) {
                *f = rng.gen_range(0.0..=1.0);
            }
            ShadingInput {
                point: unit(&mut rng),
                normal: unit(&mut rng),
                to_eye: unit(&mut rng),
                material: Material {
                    color: [rng.gen_range(0.0..1.0), 0.5, rng.gen_range(0.0..1.0)],
                    specular: rng.gen_range(0.0..1.0),
                    shininess: rng.gen_range(1.0..64.0),
                },
                fractions,
            }
        })
        .collect();
    let colors = kernel
        .shade(&gpu, &lights, 0.1, &samples)
        .expect("the GPU shades");
    for (s, c) in samples.iter().zip(&colors) {
        let incoming: Vec<Incoming> = lights
            .iter()
            .zip(s.fractions)
            .map(|(l, f)| Incoming {
                dir: (l.position - s.point).normalize(),
                color: l.color.map(|c| c * f),
            })
            .collect();
        let cpu = phong(&s.material, 0.1, s.normal, s.to_eye, &incoming);
        for (a, b) in c.iter().zip(cpu) {
            assert!(
                (a - b).abs() <= 1e-3 * (1.0 + b.abs()),
                "GPU {c:?}, CPU {cpu:?}"
            );
        }
    }
}
