//! Phong shading on the GPU: beam-trace's `phong` (thesis eq. 2.6) for many samples at once,
//! each with its point, normal, material and the visible fraction of every light.

pub use beam_trace::backend::ShadeLight;
use beam_trace::scene::Material;
use bytemuck::{Pod, Zeroable};
use glam::DVec3;

use crate::device::Gpu;
use crate::dispatch::Kernel;
use crate::error::GpuError;

const SHADING_KERNEL: &str = include_str!("wgsl/shading.wgsl");

/// The most lights the shading kernel takes.
pub const MAX_LIGHTS: usize = 8;

/// One sample to shade.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadingInput {
    /// The surface point.
    pub point: DVec3,
    /// Its unit normal.
    pub normal: DVec3,
    /// Unit vector to the eye.
    pub to_eye: DVec3,
    /// Its material.
    pub material: Material,
    /// The visible fraction of each light (`MAX_LIGHTS` at most; missing ones are 0).
    pub fractions: [f32; MAX_LIGHTS],
}

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct LightsParams {
    position: [[f32; 4]; MAX_LIGHTS],
    color: [[f32; 4]; MAX_LIGHTS],
    ints: [u32; 4],
    ambient: [f32; 4],
}

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct Sample {
    point: [f32; 4],
    normal: [f32; 4],
    to_eye: [f32; 4],
    material: [f32; 4],
    shininess: [f32; 4],
    fraction: [f32; MAX_LIGHTS],
}

/// The Phong kernel.
#[derive(Debug)]
pub struct ShadingKernel {
    kernel: Kernel,
}

impl ShadingKernel {
    /// Compiles the kernel.
    ///
    /// # Errors
    ///
    /// [`GpuError::Validation`] if the adapter rejects the shader.
    pub fn new(gpu: &Gpu) -> Result<ShadingKernel, GpuError> {
        Ok(ShadingKernel {
            kernel: Kernel::new(gpu, "shading kernel", SHADING_KERNEL.to_string(), &[])?,
        })
    }

    /// The colour of each sample.
    ///
    /// # Errors
    ///
    /// [`GpuError::TooLarge`] with more than [`MAX_LIGHTS`] lights, or a GPU failure.
    pub fn shade(
        &self,
        gpu: &Gpu,
        lights: &[ShadeLight],
        ambient: f32,
        samples: &[ShadingInput],
    ) -> Result<Vec<[f32; 3]>, GpuError> {
        if lights.len() > MAX_LIGHTS {
            return Err(GpuError::TooLarge(format!(
                "{} lights: the GPU shading kernel takes at most {MAX_LIGHTS}",
                lights.len()
            )));
        }
        let v3 = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32, 0.0];
        let mut params = LightsParams::zeroed();
        for (k, l) in lights.iter().enumerate() {
            params.position[k] = v3(l.position);
            params.color[k] = [l.color[0], l.color[1], l.color[2], 0.0];
        }
        params.ambient = [ambient, 0.0, 0.0, 0.0];
        let input: Vec<Sample> = samples
            .iter()
            .map(|s| Sample {
                point: v3(s.point),
                normal: v3(s.normal),
                to_eye: v3(s.to_eye),
                material: [
                    s.material.color[0],
                    s.material.color[1],
                    s.material.color[2],
                    s.material.specular,
                ],
                shininess: [s.material.shininess, 0.0, 0.0, 0.0],
                fraction: s.fractions,
            })
            .collect();
        let out: Vec<[f32; 4]> = self.kernel.map(gpu, &input, |count| {
            let mut p = params;
            p.ints = [lights.len() as u32, count as u32, 0, 0];
            bytemuck::bytes_of(&p).to_vec()
        })?;
        Ok(out.into_iter().map(|c| [c[0], c[1], c[2]]).collect())
    }
}
