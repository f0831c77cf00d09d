//! The headless GPU device: whatever adapter wgpu finds (Vulkan, Metal, DX12, GL), software
//! drivers included, with every failure an error rather than a panic.

use std::sync::Arc;

use crate::error::GpuError;

/// A GPU device and its queue, headless (no window, no surface).
#[derive(Debug)]
pub struct Gpu {
    pub(crate) device: wgpu::Device,
    pub(crate) queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
}

impl Gpu {
    /// Opens the first adapter wgpu finds, preferring a high-performance one and falling
    /// back to a software adapter (such as Mesa's lavapipe).
    ///
    /// # Errors
    ///
    /// [`GpuError::NoAdapter`] when there is none (its message says how to install a
    /// software driver), [`GpuError::Device`] when the adapter cannot open a device.
    pub fn new() -> Result<Gpu, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let hardware = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            ..Default::default()
        };
        let adapter = match pollster::block_on(instance.request_adapter(&hardware)) {
            Ok(a) => a,
            Err(first) => {
                let software = wgpu::RequestAdapterOptions {
                    force_fallback_adapter: true,
                    ..hardware
                };
                pollster::block_on(instance.request_adapter(&software))
                    .map_err(|_| GpuError::NoAdapter(first.to_string()))?
            }
        };
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("gpu-backend"),
            required_limits: wgpu::Limits::downlevel_defaults().using_resolution(adapter.limits()),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device {
            adapter: info.name.clone(),
            message: e.to_string(),
        })?;
        // Errors are caught by error scopes around each step; anything else is reported
        // instead of aborting the process.
        device.on_uncaptured_error(Arc::new(|e: wgpu::Error| {
            eprintln!("gpu-backend: uncaptured GPU error: {e}");
        }));
        Ok(Gpu {
            device,
            queue,
            info,
        })
    }

    /// The adapter for a test suite: `Some` when there is one. Without one, the reason is
    /// printed and the tests are to be skipped (`None`), except where the `CI` environment
    /// variable is set, where a missing adapter is a failure (a panic) rather than a silent
    /// skip.
    pub fn for_tests() -> Option<Gpu> {
        match Gpu::new() {
            Ok(g) => {
                eprintln!("adapter: {}", g.name());
                Some(g)
            }
            Err(e) if std::env::var_os("CI").is_some() => {
                panic!("CI must run the GPU tests, but: {e}")
            }
            Err(e) => {
                eprintln!("skipping the GPU tests: {e}");
                None
            }
        }
    }

    /// The adapter's name, driver and backend, e.g.
    /// `llvmpipe (LLVM 15.0.6, 256 bits) (Vulkan, Cpu, Mesa 22.3.6)`.
    pub fn name(&self) -> String {
        let i = &self.info;
        let driver = [i.driver.as_str(), i.driver_info.as_str()]
            .iter()
            .filter(|s| !s.is_empty())
            .copied()
            .collect::<Vec<_>>()
            .join(" ");
        format!(
            "{} ({:?}, {:?}, {driver})",
            i.name, i.backend, i.device_type
        )
    }

    /// What wgpu reports about the adapter.
    pub fn info(&self) -> &wgpu::AdapterInfo {
        &self.info
    }

    /// Whether the adapter is a software rasteriser (such as lavapipe).
    pub fn is_software(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }

    /// Runs `f`, turning any validation error it causes into [`GpuError::Validation`]
    /// about `what`.
    pub(crate) fn checked<T>(&self, what: &str, f: impl FnOnce() -> T) -> Result<T, GpuError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        match pollster::block_on(scope.pop()) {
            None => Ok(value),
            Some(e) => Err(GpuError::Validation {
                what: what.to_string(),
                message: e.to_string(),
            }),
        }
    }
}
