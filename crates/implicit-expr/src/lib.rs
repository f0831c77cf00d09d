//! # implicit-expr
//!
//! Formulas for implicit surfaces f(x, y, z) = 0 turned into fast, sound inclusion
//! functions: an expression graph ([`Context`]), symbolic derivatives, a compiled register
//! [`Tape`], evaluators for points, intervals, modal intervals and gradients, tape pruning,
//! restriction to rays and beams, modal semantic extensions, and WGSL code generation.

pub mod constant;
pub mod context;
mod deriv;
pub mod error;
pub mod eval;
pub mod op;
pub mod parse;
pub mod print;
pub mod ray;
pub mod semantics;
pub mod tape;
pub mod wgsl;
pub mod vm;

pub use constant::Constant;
pub use context::{Context, Node, NodeId, Var};
pub use error::Error;
pub use eval::{Choice, Evaluator, Grad, Number, SliceEvaluator};
pub use op::{BinaryOp, UnaryOp};
pub use ray::{RayEvaluator, RayFunction};
pub use semantics::{SemanticResult, Theorem, analyze};
pub use tape::Tape;
