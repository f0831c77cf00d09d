//! # implicit-expr
//!
//! Formulas for implicit surfaces f(x, y, z) = 0 turned into inclusion functions: expression graph, symbolic derivatives, compiled register tape, evaluators for points, intervals, modal intervals and gradients, and WGSL code generation.
//!
//! This crate is a placeholder in the workspace layout: it holds no functionality yet.
//! See its README for what it will provide.
