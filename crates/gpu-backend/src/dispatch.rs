//! Running a one-dimensional compute kernel over an array: the buffers, the bind group, the
//! dispatch and the read-back that every kernel of the backend shares.

use bytemuck::Pod;
use wgpu::util::DeviceExt;

use crate::device::Gpu;
use crate::error::GpuError;

/// A compiled kernel with the bindings `0` (a uniform), `1` (the input array, read-only) and
/// `2` (the output array), one invocation per element, workgroups of [`WORKGROUP`].
#[derive(Debug)]
pub(crate) struct Kernel {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    label: &'static str,
}

/// Invocations per workgroup (the kernels declare `@workgroup_size(64)`).
pub(crate) const WORKGROUP: u32 = 64;

/// Elements per dispatch: at most 65 535 workgroups along one dimension.
const MAX_DISPATCH: usize = 65_535 * WORKGROUP as usize;

/// The most elements of `bytes_per_element` (the larger of an input and an output element)
/// one dispatch of `gpu` can take: the dispatch limit and the adapter's largest storage
/// binding.
fn max_elements(gpu: &Gpu, bytes_per_element: usize) -> usize {
    let binding = gpu.device.limits().max_storage_buffer_binding_size as usize;
    MAX_DISPATCH.min(binding / bytes_per_element.max(1)).max(1)
}

impl Kernel {
    /// Compiles `source` (entry point `main`) with the pipeline constants `constants`.
    pub(crate) fn new(
        gpu: &Gpu,
        label: &'static str,
        source: String,
        constants: &[(&str, f64)],
    ) -> Result<Kernel, GpuError> {
        let module = gpu.checked(label, || {
            gpu.device
                .create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                })
        })?;
        let pipeline = gpu.checked(label, || {
            gpu.device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(label),
                    layout: None,
                    module: &module,
                    entry_point: Some("main"),
                    compilation_options: wgpu::PipelineCompilationOptions {
                        constants,
                        ..Default::default()
                    },
                    cache: None,
                })
        })?;
        let layout = pipeline.get_bind_group_layout(0);
        Ok(Kernel {
            pipeline,
            layout,
            label,
        })
    }

    /// Runs the kernel on every element of `inputs`, in as many dispatches as the adapter's
    /// limits need: `uniform(n)` gives the parameter bytes of a dispatch of `n` elements
    /// (the kernels read their element count from them). One output per input, in order.
    pub(crate) fn map<I: Pod, O: Pod>(
        &self,
        gpu: &Gpu,
        inputs: &[I],
        uniform: impl Fn(usize) -> Vec<u8>,
    ) -> Result<Vec<O>, GpuError> {
        let size = std::mem::size_of::<I>().max(std::mem::size_of::<O>());
        let mut out = Vec::with_capacity(inputs.len());
        for chunk in inputs.chunks(max_elements(gpu, size)) {
            let bytes = self.run(
                gpu,
                &uniform(chunk.len()),
                bytemuck::cast_slice(chunk),
                chunk.len(),
                std::mem::size_of::<O>(),
            )?;
            out.extend(bytemuck::pod_collect_to_vec::<u8, O>(&bytes));
        }
        Ok(out)
    }

    /// Runs the kernel on `count` elements (`input` holds them, `uniform` the parameters)
    /// and reads back `count * out_size` bytes of output.
    fn run(
        &self,
        gpu: &Gpu,
        uniform: &[u8],
        input: &[u8],
        count: usize,
        out_size: usize,
    ) -> Result<Vec<u8>, GpuError> {
        if count == 0 {
            return Ok(Vec::new());
        }
        let most = max_elements(gpu, out_size.max(input.len() / count));
        if count > most {
            return Err(GpuError::TooLarge(format!(
                "{}: {count} elements in one dispatch, at most {most}",
                self.label
            )));
        }
        let device = &gpu.device;
        let bytes = (count * out_size) as u64;
        let (encoder, readback) = gpu.checked(self.label, || {
            let uniform = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("parameters"),
                contents: uniform,
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("inputs"),
                contents: input,
                usage: wgpu::BufferUsages::STORAGE,
            });
            let output = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("outputs"),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let readback = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("read-back"),
                size: bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(self.label),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: input.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: output.as_entire_binding(),
                    },
                ],
            });
            let mut encoder = device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_compute_pass(&Default::default());
                pass.set_pipeline(&self.pipeline);
                pass.set_bind_group(0, &bind, &[]);
                pass.dispatch_workgroups((count as u32).div_ceil(WORKGROUP), 1, 1);
            }
            encoder.copy_buffer_to_buffer(&output, 0, &readback, 0, bytes);
            (encoder, readback)
        })?;
        gpu.queue.submit([encoder.finish()]);
        read_back(gpu, &readback)
    }
}

/// Maps `buffer` and copies its bytes out.
fn read_back(gpu: &Gpu, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
    let slice = buffer.slice(..);
    let (tx, rx) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |r| {
        let _ = tx.send(r);
    });
    gpu.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    rx.recv()
        .map_err(|e| GpuError::Readback(e.to_string()))?
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let data = slice
        .get_mapped_range()
        .map_err(|e| GpuError::Readback(e.to_string()))?;
    let out = data.to_vec();
    drop(data);
    buffer.unmap();
    Ok(out)
}
