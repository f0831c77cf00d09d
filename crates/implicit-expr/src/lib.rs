//! # implicit-expr
//!
//! Formulas for implicit surfaces f(x, y, z) = 0 turned into fast, sound inclusion
//! functions: an expression graph ([`Context`]), symbolic derivatives, a compiled register
//! [`Tape`], evaluators for points, intervals, modal intervals and gradients, tape pruning,
//! restriction to rays and beams, modal semantic extensions, and WGSL code generation.
//!
//! ## A tour
//!
//! Parse a formula with a parameter, compile it, and evaluate it on a point and on a box:
//!
//! ```
//! use implicit_expr::{Context, Evaluator, Tape, parse::parse};
//! use interval_core::Interval;
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x^2 + y^2 + z^2 - r^2", &["r"])?;
//! let tape = Tape::new(&ctx, &[f])?;
//!
//! // Inputs are the variable slots: x, y, z, then the parameters.
//! let mut points = Evaluator::<f64>::new(&tape);
//! assert_eq!(points.eval(&[1.0, 2.0, 2.0, 3.0])?, 0.0);
//!
//! let iv = |a, b| Interval::new(a, b).unwrap();
//! let mut boxes = Evaluator::<Interval<f64>>::new(&tape);
//! let r = boxes.eval(&[iv(2.0, 3.0), iv(0.0, 1.0), iv(0.0, 0.0), iv(1.0, 1.0)])?;
//! assert!(r.inf() > 0.0); // proven: no point of this box is on the sphere
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! Errors point at the text:
//!
//! ```
//! use implicit_expr::{Context, parse::parse};
//!
//! let err = parse(&mut Context::new(), "sine(x) + 1", &[]).unwrap_err();
//! assert_eq!(err.to_string(), "unknown function 'sine' at 0..4; did you mean 'sin'?");
//! ```
//!
//! Gradients (for normals and interval Newton), symbolically or in forward mode:
//!
//! ```
//! use implicit_expr::{Context, Evaluator, Grad, Tape, parse::parse};
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x*y + sin(z)", &[])?;
//! let [fx, fy, fz] = ctx.gradient(f);
//! let tape = Tape::new(&ctx, &[f, fx, fy, fz])?; // shares nodes between f and its partials
//! let mut out = [0.0; 4];
//! Evaluator::<f64>::new(&tape).eval_outputs(&[2.0, 3.0, 0.0], &mut out)?;
//! assert_eq!(out, [6.0, 3.0, 2.0, 1.0]);
//!
//! let g = Evaluator::<Grad<f64>>::new(&tape).eval(&Grad::point(2.0, 3.0, 0.0))?;
//! assert_eq!(g.d, [3.0, 2.0, 1.0]);
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! Tape pruning: an interval evaluation over a region records which side each `min`/`max`
//! took, and [`Tape::simplify`] returns the shorter tape that equals the full one there:
//!
//! ```
//! use implicit_expr::{Context, Evaluator, Tape, parse::parse};
//! use interval_core::Interval;
//!
//! let mut ctx = Context::new();
//! // Union of two discs, far apart.
//! let f = parse(&mut ctx, "min(sqrt((x-2)^2 + y^2) - 1, sqrt((x+2)^2 + y^2) - 1)", &[])?;
//! let tape = Tape::new(&ctx, &[f])?;
//! let iv = |a, b| Interval::new(a, b).unwrap();
//! let mut trace = Vec::new();
//! Evaluator::<Interval<f64>>::new(&tape)
//!     .eval_traced(&[iv(1.5, 2.5), iv(-0.5, 0.5), iv(0.0, 0.0)], &mut trace)?;
//! let pruned = tape.simplify(&trace)?;
//! assert!(pruned.len() < tape.len()); // the far disc is gone
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! Rays and beams: `g(t) = f(c + t·d)` and `g'(t)` for the root finders:
//!
//! ```
//! use implicit_expr::{Context, RayEvaluator, RayFunction, parse::parse};
//! use interval_core::Interval;
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x^2 + y^2 + z^2 - 1", &[])?;
//! let ray = RayFunction::new(&ctx, f)?;
//! let p = |v: f64| Interval::new(v, v).unwrap();
//! let mut e = RayEvaluator::<Interval<f64>>::new(&ray, &[])?;
//! e.set_ray([p(0.0), p(0.0), p(-3.0)], [p(0.0), p(0.0), p(1.0)]); // from z = -3 towards +z
//! let (g, dg) = e.g_dg(p(2.0)); // t = 2 is the point (0, 0, -1), on the sphere
//! assert!(g.contains(0.0) && dg.contains(-2.0));
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! Modal semantics (thesis 3.5.2): the theorem that applies is chosen from the formula.
//!
//! ```
//! use implicit_expr::{Context, Theorem, analyze, parse::parse};
//! use interval_core::Modal;
//!
//! let mut ctx = Context::new();
//! let f = parse(&mut ctx, "x*y/(x+y)", &[])?;
//! let args = [Modal::new(2.0, 3.0).unwrap(), Modal::new(4.0, 3.0).unwrap()];
//! let result = analyze(&ctx, f, &args)?;
//! assert!(result.is_optimal());
//! assert_eq!(result.outer().theorem, Theorem::Theorem6);
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! See `docs/numerics.md` of the repository for the numerical model (constants,
//! simplifications, pruning, derivatives of non-smooth operations, modal rounding).

pub mod catalog;
pub mod constant;
pub mod context;
pub mod contractor;
mod deriv;
mod domain;
pub mod error;
pub mod eval;
pub mod jit;
pub mod number;
pub mod op;
pub mod parse;
pub mod print;
pub mod ray;
pub mod semantics;
pub mod tape;
pub mod testing;
pub mod vm;
pub mod wgsl;

pub use constant::Constant;
pub use context::{Context, Node, NodeId, Var};
pub use error::Error;
pub use eval::{Choice, Evaluator, Grad, Number, SliceEvaluator};
pub use op::{BinaryOp, Op, UnaryOp};
pub use ray::{RayEvaluator, RayFunction};
pub use semantics::{SemanticResult, Theorem, analyze};
pub use tape::Tape;
pub use tape::cache::PruneCache;
