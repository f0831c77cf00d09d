//! # beam-trace
//!
//! Reliable CPU ray and beam tracing of implicit surfaces with interval arithmetic.
//!
//! This crate is a placeholder in the workspace layout: it holds no functionality yet.
//! See its README for what it will provide.
