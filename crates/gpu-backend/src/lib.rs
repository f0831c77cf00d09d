//! # gpu-backend
//!
//! A wgpu compute backend for reliable interval rendering of implicit surfaces, with outward rounding emulated in WGSL.
//!
//! This crate is a placeholder in the workspace layout: it holds no functionality yet.
//! See its README for what it will provide.
