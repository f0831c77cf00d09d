//! Errors of the GPU backend.

/// What can go wrong on the GPU path.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// No adapter: no GPU, and no software driver either.
    #[error("no GPU adapter found ({0}); on Linux install mesa-vulkan-drivers for a software one")]
    NoAdapter(String),
    /// The adapter refused to open a device.
    #[error("the GPU adapter '{adapter}' could not open a device: {message}")]
    Device {
        /// The adapter's name.
        adapter: String,
        /// wgpu's message.
        message: String,
    },
    /// A shader or pipeline was rejected (a bug of this crate or of the generated WGSL).
    #[error("the GPU rejected the {what}: {message}")]
    Validation {
        /// What was being created or run.
        what: String,
        /// wgpu's message.
        message: String,
    },
    /// Reading results back from the GPU failed.
    #[error("reading results back from the GPU failed: {0}")]
    Readback(String),
    /// A formula could not be written as WGSL.
    #[error("the surface cannot run on the GPU: {0}")]
    Expr(#[from] implicit_expr::Error),
    /// The input is too large for one dispatch or buffer.
    #[error("{0}")]
    TooLarge(String),
}
