//! Property tests of soundness on random expression graphs.
//!
//! A strategy builds random graphs through the [`Context`] API: trees (and, through shared
//! arguments, DAGs) over every [`UnaryOp`] (the step functions and their slopes included),
//! every [`BinaryOp`], `pown` with small exponents, the variables `x`, `y`, `z`, one
//! parameter `p`, and constants, exact (`2`) and inexact (`0.1`, `pi`). Each graph is
//! evaluated over random boxes (points, thin, wide, negative, around zero) and at random
//! points inside them.
//!
//! The reference is an oracle that evaluates the same recipe in 200-bit MPFR arithmetic
//! (`rug`) with the real values of the literals (the decimal `0.1`, not the double nearest
//! to it), together with its gradient where the function is differentiable; it runs again at
//! 320 bits and gives no answer where the two runs disagree. Points outside the IEEE 1788
//! domain of some operation are skipped. The checks:
//!
//! * interval values (`f64` and `f32`) contain the oracle's value and the point value at
//!   every point of the box where the function is defined there (the real soundness check:
//!   point arithmetic may round differently from the real value); double-double intervals
//!   contain the oracle's value;
//! * decorations: the plain evaluator's (`eval_decorated`, `eval_continuous`) agree with
//!   the evaluation on `DecInterval`s;
//! * the slice evaluator gives bit-identical results to the one-input evaluator;
//! * a tape pruned from an interval evaluation over a box gives the full tape's point
//!   values in the box, and its interval values over sub-boxes contain the point values;
//! * for proper inputs, `Modal<f64, Outer>` contains the point values, and for inputs of any
//!   modality the inner-rounded result is included in the outer-rounded one;
//! * `Grad<Interval<f64>>` and the interval evaluation of the symbolic gradient contain the
//!   real gradient, the `Grad<f64>` gradient and the symbolic gradient's point value;
//! * for a beam (origin `c`, direction box `D`, parameter interval `T`), the interval
//!   `g(T)` and `g'(T)` contain `g(t)` and `g'(t)` of every ray `d ∈ D` at every `t ∈ T`.
//!
//! Named regression tests at the end of the file hold the minimal cases these properties
//! found: undefined slopes (read as unbounded, `Number::widen_undefined`), the undefined
//! branch of a `min`/`max` derivative, pruning where the formula is partly undefined, and
//! folding `pow` with an integer exponent.
//!
//! The environment variable `INTERVAL_CORE_TEST_SCALE` (a positive integer) multiplies the
//! number of cases.

use implicit_expr::contractor::Contractor;
use implicit_expr::testing::reference;
use implicit_expr::{
    BinaryOp, Choice, Constant, Context, Evaluator, Grad, Node, NodeId, Number, RayEvaluator,
    RayFunction, SliceEvaluator, Tape, UnaryOp,
};
use interval_core::{Dd, DdInterval, DecInterval, Decoration, Inner, Interval, Modal, Outer};
use proptest::prelude::*;
use rug::Float;
use rug::float::Constant as MpfrConstant;
use rug::ops::Pow;

/// Working precision of the oracle, in bits; it runs again at [`PREC_CHECK`] bits, and a
/// value that moves between the two (a cancellation of the rounded `π`, say, or a step
/// function at a rounded jump) is not used.
const PREC: u32 = 200;

/// The precision of the oracle's second run.
const PREC_CHECK: u32 = 320;

thread_local! {
    /// The precision of the oracle run in progress on this thread.
    static PRECISION: std::cell::Cell<u32> = const { std::cell::Cell::new(PREC) };
}

fn prec() -> u32 {
    PRECISION.with(|p| p.get())
}

/// Number of variable slots: `x`, `y`, `z` and the parameter `p`.
const SLOTS: usize = 4;

mod common;
use common::config;

// -------------------------------------------------------------------------------------------
// Random expressions
// -------------------------------------------------------------------------------------------

/// Decimal literals used as constants: exact ones and ones no double represents.
const DECIMALS: [&str; 14] = [
    "0", "0.5", "1", "2", "3", "10", "0.1", "0.3", "1.7", "1e-3", "2.5e-7", "1e10", "1e300",
    "1e-300",
];

/// A leaf of a recipe.
#[derive(Clone, Debug)]
enum Leaf {
    /// Variable slot 0..4 (`x`, `y`, `z`, `p`).
    Var(u32),
    /// A decimal literal.
    Dec(&'static str),
    /// π.
    Pi,
    /// e.
    E,
}

/// An operation of a recipe; arguments select earlier nodes (see [`arg`]).
#[derive(Clone, Debug)]
enum Step {
    Un(UnaryOp, usize),
    Bin(BinaryOp, usize, usize),
    Pown(usize, i32),
}

/// A random expression: leaves, then operations on earlier nodes; the last node is the root.
#[derive(Clone, Debug)]
struct Recipe {
    leaves: Vec<Leaf>,
    steps: Vec<Step>,
}

fn leaf() -> impl Strategy<Value = Leaf> {
    prop_oneof![
        8 => (0u32..SLOTS as u32).prop_map(Leaf::Var),
        3 => prop::sample::select(DECIMALS.to_vec()).prop_map(Leaf::Dec),
        1 => Just(Leaf::Pi),
        1 => Just(Leaf::E),
    ]
}

fn step() -> impl Strategy<Value = Step> {
    prop_oneof![
        4 => (prop::sample::select(UnaryOp::ALL.to_vec()), any::<usize>())
            .prop_map(|(op, a)| Step::Un(op, a)),
        5 => (prop::sample::select(BinaryOp::ALL.to_vec()), any::<usize>(), any::<usize>())
            .prop_map(|(op, a, b)| Step::Bin(op, a, b)),
        1 => (any::<usize>(), -4i32..=5).prop_map(|(a, n)| Step::Pown(a, n)),
    ]
}

fn recipe() -> impl Strategy<Value = Recipe> {
    (
        prop::collection::vec(leaf(), 1..5),
        prop::collection::vec(step(), 1..20),
    )
        .prop_map(|(leaves, steps)| Recipe { leaves, steps })
}

/// The node an argument code `a` selects among `k` earlier nodes: often the last one, else
/// one of the last three (deep expressions), sometimes any (shared subexpressions).
fn arg(a: usize, k: usize) -> usize {
    match a % 10 {
        0..5 => k - 1,
        5..8 => k - 1 - (a / 10) % k.min(3),
        _ => (a / 10) % k,
    }
}

impl Recipe {
    /// The built expression as text.
    fn describe(&self) -> String {
        let (ctx, root) = self.build();
        describe(&ctx, root)
    }

    /// Builds the graph in a fresh context (with `p` declared as slot 3); returns the root.
    fn build(&self) -> (Context, NodeId) {
        let (ctx, nodes) = self.build_nodes();
        (ctx, *nodes.last().unwrap())
    }

    /// For each step, the exponent `n` when it is a `pow` that the graph turned into
    /// `pown(a, n)` (its exponent folded to an exact integer constant).
    fn pown_exponents(&self) -> Vec<Option<i32>> {
        let (ctx, nodes) = self.build_nodes();
        let l = self.leaves.len();
        self.steps
            .iter()
            .enumerate()
            .map(|(i, s)| match *s {
                Step::Bin(BinaryOp::Pow, _, b) => {
                    let b = nodes[arg(b, l + i)];
                    ctx.as_const(b).and_then(|c| c.as_i32())
                }
                _ => None,
            })
            .collect()
    }

    /// Builds the graph; returns the context and the node of every leaf and step.
    fn build_nodes(&self) -> (Context, Vec<NodeId>) {
        let mut ctx = Context::new();
        ctx.declare_var("p");
        let mut nodes: Vec<NodeId> = Vec::new();
        for l in &self.leaves {
            let n = match l {
                Leaf::Var(3) => ctx.named_var("p"),
                Leaf::Var(i) => ctx.var(implicit_expr::Var(*i)).unwrap(),
                Leaf::Dec(s) => ctx.constant_enclosed(Constant::from_decimal(s).unwrap()),
                Leaf::Pi => ctx.constant_enclosed(Constant::pi()),
                Leaf::E => ctx.constant_enclosed(Constant::e()),
            };
            nodes.push(n);
        }
        for s in &self.steps {
            let k = nodes.len();
            let n = match *s {
                Step::Un(op, a) => ctx.unary(op, nodes[arg(a, k)]),
                Step::Bin(op, a, b) => ctx.binary(op, nodes[arg(a, k)], nodes[arg(b, k)]),
                Step::Pown(a, n) => ctx.pown(nodes[arg(a, k)], n),
            };
            nodes.push(n);
        }
        (ctx, nodes)
    }
}

// -------------------------------------------------------------------------------------------
// The oracle: 200-bit values and gradients of the recipe
// -------------------------------------------------------------------------------------------

/// A real value with its gradient by `x`, `y`, `z` (`None` where not differentiable).
#[derive(Clone, Debug)]
struct Real {
    v: Float,
    d: Option<[Float; 3]>,
    /// Whether the value is constant in a neighbourhood of the point.
    flat: bool,
    /// Whether the gradient exists only because an undefined derivative is multiplied by a
    /// zero: an infinite slope (`sqrt` at 0, `asin`/`acos` at ±1) of a locally constant
    /// argument, a step function's slope of an argument without derivative, or a `min`/`max`
    /// whose other branch has no derivative. The crate's enclosures are empty there: see
    /// `zero_times_undefined_derivative_gives_an_empty_enclosure`.
    zero_times_undefined: bool,
}

impl Real {
    fn constant(v: Float) -> Self {
        Self {
            v,
            d: Some(zero3()),
            flat: true,
            zero_times_undefined: false,
        }
    }
}

fn fl(v: impl Into<f64>) -> Float {
    Float::with_val(prec(), v.into())
}

fn zero3() -> [Float; 3] {
    [fl(0.0), fl(0.0), fl(0.0)]
}

/// `d · s`, component-wise.
fn scale(d: &Option<[Float; 3]>, s: &Float) -> Option<[Float; 3]> {
    d.as_ref()
        .map(|d| [d[0].clone() * s, d[1].clone() * s, d[2].clone() * s])
}

/// `a · da + b · db`.
fn combine(
    da: &Option<[Float; 3]>,
    a: &Float,
    db: &Option<[Float; 3]>,
    b: &Float,
) -> Option<[Float; 3]> {
    let (da, db) = (da.as_ref()?, db.as_ref()?);
    Some(std::array::from_fn(|i| {
        da[i].clone() * a + db[i].clone() * b
    }))
}

/// Whether an oracle value is finite and below 2^4000 in magnitude: far beyond the `f64`
/// range, where checks say nothing more and MPFR's trigonometric argument reduction gets
/// slow.
fn in_range(v: &Float) -> bool {
    v.is_finite() && v.get_exp().is_none_or(|e| e < 4000)
}

/// Whether two oracle runs agree: to a relative 2^-100.
fn agree(a: &Float, b: &Float) -> bool {
    let diff = Float::with_val(PREC_CHECK, a - b).abs();
    diff <= (Float::with_val(PREC_CHECK, b.abs_ref()) >> 100u32)
}

/// The derivative at a kink, jump or infinite slope of a function of `a`: zero when `a`
/// is locally constant, else undefined.
fn kink(a: &Real) -> Option<[Float; 3]> {
    if a.flat { Some(zero3()) } else { None }
}

/// The value and gradient of `op(a)`, or `None` outside the domain (IEEE 1788 domains).
fn real_unary(op: UnaryOp, a: &Real) -> Option<Real> {
    let x = &a.v;
    let one = fl(1.0);
    let mut flat = a.flat;
    let mut singular = false;
    let mut poisoned = false;
    let (v, d) = match op {
        UnaryOp::Neg => (-x.clone(), scale(&a.d, &fl(-1.0))),
        UnaryOp::Abs => {
            let d = match x.cmp0() {
                Some(std::cmp::Ordering::Greater) => a.d.clone(),
                Some(std::cmp::Ordering::Less) => scale(&a.d, &fl(-1.0)),
                _ => kink(a),
            };
            (x.clone().abs(), d)
        }
        UnaryOp::Sqr => (x.clone().square(), scale(&a.d, &(x.clone() * 2u32))),
        UnaryOp::Sqrt => {
            if *x < 0.0 {
                return None;
            }
            let v = x.clone().sqrt();
            let d = if x.is_zero() {
                singular = true;
                kink(a)
            } else {
                scale(&a.d, &(fl(0.5) / &v))
            };
            (v, d)
        }
        UnaryOp::Recip => {
            if x.is_zero() {
                return None;
            }
            let v = x.clone().recip();
            let s = -(v.clone().square());
            (v, scale(&a.d, &s))
        }
        UnaryOp::Exp => {
            let v = x.clone().exp();
            (v.clone(), scale(&a.d, &v))
        }
        UnaryOp::Ln | UnaryOp::Log10 => {
            if *x <= 0.0 {
                return None;
            }
            let (v, s) = if op == UnaryOp::Ln {
                (x.clone().ln(), x.clone().recip())
            } else {
                (x.clone().log10(), (x.clone() * fl(10.0).ln()).recip())
            };
            (v, scale(&a.d, &s))
        }
        UnaryOp::Sin => (x.clone().sin(), scale(&a.d, &x.clone().cos())),
        UnaryOp::Cos => (x.clone().cos(), scale(&a.d, &(-x.clone().sin()))),
        UnaryOp::Tan => {
            let v = x.clone().tan();
            let s = v.clone().square() + 1u32;
            (v, scale(&a.d, &s))
        }
        UnaryOp::Asin | UnaryOp::Acos => {
            if x.clone().abs() > 1.0 {
                return None;
            }
            let v = if op == UnaryOp::Asin {
                x.clone().asin()
            } else {
                x.clone().acos()
            };
            let r = one - x.clone().square();
            let d = if r.is_zero() {
                singular = true;
                kink(a)
            } else {
                let s = r.sqrt().recip();
                let s = if op == UnaryOp::Acos { -s } else { s };
                scale(&a.d, &s)
            };
            (v, d)
        }
        UnaryOp::Atan => {
            let s = (x.clone().square() + 1u32).recip();
            (x.clone().atan(), scale(&a.d, &s))
        }
        UnaryOp::Floor | UnaryOp::Ceil | UnaryOp::Round | UnaryOp::Not => {
            let (v, jump) = match op {
                UnaryOp::Floor => (x.clone().floor(), x.is_integer()),
                UnaryOp::Ceil => (x.clone().ceil(), x.is_integer()),
                UnaryOp::Round => (
                    x.clone().round(),
                    (x.clone().abs().fract() - fl(0.5)).is_zero(),
                ),
                _ => (fl(if x.is_zero() { 1.0 } else { 0.0 }), x.is_zero()),
            };
            if jump {
                (v, kink(a))
            } else {
                flat = true;
                poisoned = a.d.is_none();
                (v, Some(zero3()))
            }
        }
        // The slopes are zero at every point (their interval versions add the jumps).
        UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => {
            return Some(Real {
                zero_times_undefined: a.zero_times_undefined || a.d.is_none(),
                ..Real::constant(fl(0.0))
            });
        }
    };
    // A locally constant result has a zero gradient, whatever the argument's.
    poisoned |= (singular || a.d.is_none()) && flat;
    let d = if flat { Some(zero3()) } else { d };
    in_range(&v).then_some(Real {
        v,
        d,
        flat,
        zero_times_undefined: a.zero_times_undefined || poisoned,
    })
}

/// The value and gradient of `op(a, b)`, or `None` outside the domain.
/// `pown` is `Some(n)` for a `pow` whose exponent the graph holds as the exact integer
/// constant `n` (the graph makes it `pown(a, n)`).
fn real_binary(op: BinaryOp, a: &Real, b: &Real, pown: Option<i32>) -> Option<Real> {
    if let Some(n) = pown.filter(|_| op == BinaryOp::Pow) {
        return real_pown(a, n);
    }
    let (x, y) = (&a.v, &b.v);
    let mut flat = a.flat && b.flat;
    let mut poisoned = false;
    let (v, d) = match op {
        BinaryOp::Add => (x.clone() + y, combine(&a.d, &fl(1.0), &b.d, &fl(1.0))),
        BinaryOp::Sub => (x.clone() - y, combine(&a.d, &fl(1.0), &b.d, &fl(-1.0))),
        BinaryOp::Mul => (x.clone() * y, combine(&a.d, y, &b.d, x)),
        BinaryOp::Div => {
            if y.is_zero() {
                return None;
            }
            let v = x.clone() / y;
            let r = y.clone().recip();
            let d = combine(&a.d, &r, &b.d, &(-(v.clone() * &r)));
            (v, d)
        }
        BinaryOp::Min | BinaryOp::Max => {
            let take_a = if op == BinaryOp::Min { x < y } else { x > y };
            if x == y {
                let d = match (&a.d, &b.d) {
                    (Some(p), Some(q)) if p == q && a.flat == b.flat => Some(p.clone()),
                    _ => None,
                };
                (x.clone(), d)
            } else if take_a {
                flat = a.flat;
                poisoned = a.d.is_some() && b.d.is_none();
                (x.clone(), a.d.clone())
            } else {
                flat = b.flat;
                poisoned = b.d.is_some() && a.d.is_none();
                (y.clone(), b.d.clone())
            }
        }
        BinaryOp::Pow => {
            if x.is_zero() && *y > 0.0 {
                poisoned = true;
                (fl(0.0), None)
            } else if *x > 0.0 {
                let v = x.clone().pow(y);
                let sa = y.clone() * x.clone().pow(y.clone() - 1u32);
                let sb = v.clone() * x.clone().ln();
                (v, combine(&a.d, &sa, &b.d, &sb))
            } else {
                return None;
            }
        }
        // `b` inside the domain; outside it the value is +inf (no object), which a real
        // cannot hold: such points are left to the interval tests of `domain` itself. On
        // the boundary `d = 0` the function jumps, so it has no gradient there.
        BinaryOp::Domain => {
            if *x > 0.0 {
                return None;
            }
            flat = b.flat;
            poisoned = x.is_zero();
            let d = if x.is_zero() { None } else { b.d.clone() };
            (y.clone(), d)
        }
    };
    // A locally constant result has a zero gradient, whatever the arguments'.
    poisoned |= (a.d.is_none() || b.d.is_none()) && flat;
    let d = if flat { Some(zero3()) } else { d };
    in_range(&v).then_some(Real {
        v,
        d,
        flat,
        zero_times_undefined: a.zero_times_undefined || b.zero_times_undefined || poisoned,
    })
}

fn real_pown(a: &Real, n: i32) -> Option<Real> {
    let x = &a.v;
    if n < 0 && x.is_zero() {
        return None;
    }
    // The graph makes `pown(a, n)` for n = 0, 1, 2, -1 the constant 1, `a`, `sqr a` and
    // `recip a`: compute their derivatives the same way, so that cancellations the graph
    // simplifies exactly (`pown(a, -1) - recip(a) = 0`) are exact here too.
    match n {
        0 => return Some(Real::constant(fl(1.0))),
        1 => return Some(a.clone()),
        2 => return real_unary(UnaryOp::Sqr, a),
        -1 => return real_unary(UnaryOp::Recip, a),
        _ => {}
    }
    let v = x.clone().pow(n);
    let s = x.clone().pow(n - 1) * n;
    let d = if a.flat {
        Some(zero3())
    } else {
        scale(&a.d, &s)
    };
    in_range(&v).then_some(Real {
        v,
        d,
        flat: a.flat,
        zero_times_undefined: a.zero_times_undefined || (a.flat && a.d.is_none()),
    })
}

impl Recipe {
    /// The real value and gradient of the root at `inputs` (`x`, `y`, `z`, `p`), or `None`
    /// where some operation is undefined (or overflows even MPFR's exponent range).
    fn oracle(&self, inputs: &[Float; SLOTS]) -> Option<Real> {
        let a = self.oracle_at(inputs, PREC)?;
        let b = self.oracle_at(inputs, PREC_CHECK)?;
        if !agree(&a.v, &b.v) {
            return None;
        }
        let d = match (&a.d, &b.d) {
            (Some(p), Some(q)) if (0..3).all(|k| agree(&p[k], &q[k])) => b.d.clone(),
            _ => None,
        };
        Some(Real {
            d,
            zero_times_undefined: a.zero_times_undefined || b.zero_times_undefined,
            ..b
        })
    }

    /// The oracle at `bits` of precision.
    fn oracle_at(&self, inputs: &[Float; SLOTS], bits: u32) -> Option<Real> {
        PRECISION.with(|p| p.set(bits));
        let r = self.oracle_run(inputs);
        PRECISION.with(|p| p.set(PREC));
        r
    }

    fn oracle_run(&self, inputs: &[Float; SLOTS]) -> Option<Real> {
        let mut vals: Vec<Option<Real>> = Vec::new();
        for l in &self.leaves {
            let r = match l {
                Leaf::Var(i) => {
                    let mut d = zero3();
                    if (*i as usize) < 3 {
                        d[*i as usize] = fl(1.0);
                    }
                    Real {
                        v: Float::with_val(prec(), &inputs[*i as usize]),
                        d: Some(d),
                        // The parameter is constant for derivatives by x, y, z.
                        flat: false,
                        zero_times_undefined: false,
                    }
                }
                Leaf::Dec(s) => Real::constant(Float::with_val(prec(), Float::parse(s).unwrap())),
                Leaf::Pi => Real::constant(Float::with_val(prec(), MpfrConstant::Pi)),
                Leaf::E => Real::constant(fl(1.0).exp()),
            };
            vals.push(Some(r));
        }
        let pown = self.pown_exponents();
        for (i, s) in self.steps.iter().enumerate() {
            let k = vals.len();
            let r = match *s {
                Step::Un(op, a) => vals[arg(a, k)].as_ref().and_then(|a| real_unary(op, a)),
                Step::Bin(op, a, b) => match (&vals[arg(a, k)], &vals[arg(b, k)]) {
                    (Some(a), Some(b)) => real_binary(op, a, b, pown[i]),
                    _ => None,
                },
                Step::Pown(a, n) => vals[arg(a, k)].as_ref().and_then(|a| real_pown(a, n)),
            };
            vals.push(r);
        }
        vals.pop().unwrap()
    }
}

/// The expression of `root` as text, for failure messages.
fn describe(ctx: &Context, root: NodeId) -> String {
    let mut text: Vec<String> = vec![String::new(); ctx.len()];
    for id in ctx.reachable(&[root]) {
        text[id.index()] = match *ctx.get(id) {
            Node::Var(v) => ctx.var_names()[v.index()].clone(),
            Node::Const(c) if c.is_exact() => format!("{}", c.value()),
            Node::Const(c) => format!("[{:e}, {:e}]", c.lo(), c.hi()),
            Node::Unary(op, a) => format!("{}({})", op.name(), text[a.index()]),
            Node::Binary(op, a, b) => {
                format!("{}({}, {})", op.name(), text[a.index()], text[b.index()])
            }
            Node::Pown(a, n) => format!("pown({}, {n})", text[a.index()]),
        };
    }
    text[root.index()].clone()
}

// -------------------------------------------------------------------------------------------
// Boxes and points
// -------------------------------------------------------------------------------------------

/// A bound value: small integers (ties, exact results), moderate, large and tiny values.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-3i32..=3).prop_map(f64::from),
        4 => -4.0..4.0f64,
        1 => -1e3..1e3f64,
        1 => -1e-6..1e-6f64,
        1 => prop::sample::select(vec![1e150, -1e150, 1e-150, 0.1, -0.5, 0.25]),
    ]
}

/// A random interval: a point, a thin one (a few ulps), a general one, one around zero, a
/// wide one, or a negative one.
fn interval() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        2 => value().prop_map(|v| (v, v)),
        1 => (value(), 1u32..4).prop_map(|(v, k)| {
            let mut hi = v;
            for _ in 0..k {
                hi = hi.next_up();
            }
            (v, hi)
        }),
        4 => (value(), value()).prop_map(|(a, b)| (a.min(b), a.max(b))),
        2 => (0.0..3.0f64, 0.0..3.0f64).prop_map(|(a, b)| (-a, b)),
        1 => (1.0..1e4f64).prop_map(|w| (-w, w)),
        1 => (0.0..5.0f64, 0.0..5.0f64).prop_map(|(a, b)| (-a.max(b), -a.min(b))),
    ]
}

fn boxes() -> impl Strategy<Value = [(f64, f64); SLOTS]> {
    [interval(), interval(), interval(), interval()]
}

/// A fraction in `[0, 1]`, the ends included often.
fn fraction() -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 1 => Just(1.0), 4 => 0.0..=1.0f64]
}

fn fractions(n: usize) -> impl Strategy<Value = Vec<[f64; SLOTS]>> {
    prop::collection::vec([fraction(), fraction(), fraction(), fraction()], n)
}

/// The point at `u ∈ [0, 1]` of `[lo, hi]`, kept inside.
fn lerp((lo, hi): (f64, f64), u: f64) -> f64 {
    let w = hi - lo;
    let v = if w.is_finite() {
        lo + u * w
    } else {
        lo * (1.0 - u) + hi * u
    };
    v.clamp(lo, hi)
}

fn point(b: &[(f64, f64); SLOTS], u: &[f64; SLOTS]) -> [f64; SLOTS] {
    std::array::from_fn(|i| lerp(b[i], u[i]))
}

fn iv(b: (f64, f64)) -> Interval<f64> {
    Interval::new(b.0, b.1).unwrap()
}

fn inputs_of(p: &[f64; SLOTS]) -> [Float; SLOTS] {
    std::array::from_fn(|i| fl(p[i]))
}

/// Whether the real `v` lies in `x`.
///
/// The oracle rounds too (to 200 bits, where divisions and elementary functions are
/// inexact), so `v` may stand a relative 2^-150 outside an interval that holds the exact
/// value (`3 · (1 - 1/3)` against the exact `[2, 2]`).
fn holds(x: Interval<f64>, v: &Float) -> bool {
    x.bounds()
        .is_some_and(|(lo, hi)| between(&Float::with_val(PREC, lo), &Float::with_val(PREC, hi), v))
}

/// `lo ≤ v ≤ hi` up to [`holds`]' slack of the oracle's rounding.
fn between(lo: &Float, hi: &Float, v: &Float) -> bool {
    let slack = Float::with_val(PREC, v.abs_ref()) >> 150u32;
    Float::with_val(PREC, v + &slack) >= *lo && Float::with_val(PREC, v - &slack) <= *hi
}

/// [`holds`] for `f32` intervals.
fn holds32(x: Interval<f32>, v: &Float) -> bool {
    holds(x.cast::<f64>(), v)
}

/// Whether the point value `p` (not NaN) lies in `x`: finite values as members, infinite
/// ones as the limit of an unbounded side.
fn holds_point(x: Interval<f64>, p: f64) -> bool {
    if p == f64::INFINITY {
        x.sup() == f64::INFINITY
    } else if p == f64::NEG_INFINITY {
        x.inf() == f64::NEG_INFINITY
    } else {
        x.contains(p)
    }
}

fn holds_point32(x: Interval<f32>, p: f32) -> bool {
    if p == f32::INFINITY {
        x.sup() == f32::INFINITY
    } else if p == f32::NEG_INFINITY {
        x.inf() == f32::NEG_INFINITY
    } else {
        x.contains(p)
    }
}

/// Whether, at the point `vars`, some `min`/`max` of the graph has equal arguments or some
/// `abs` a zero argument (in `f64`): there the point derivative takes one branch and an
/// interval evaluation over a degenerate box may take the other.
fn has_tie(ctx: &Context, roots: &[NodeId], vars: &[f64]) -> bool {
    let mut vals = vec![0.0f64; ctx.len()];
    let mut tie = false;
    for id in ctx.reachable(roots) {
        let v = match *ctx.get(id) {
            Node::Var(v) => vars[v.index()],
            Node::Const(c) => c.value(),
            Node::Unary(op, a) => {
                tie |= op == UnaryOp::Abs && vals[a.index()] == 0.0;
                f64::unary(op, vals[a.index()])
            }
            Node::Binary(op, a, b) => {
                let (x, y) = (vals[a.index()], vals[b.index()]);
                tie |= matches!(op, BinaryOp::Min | BinaryOp::Max) && x == y;
                f64::binary(op, x, y)
            }
            Node::Pown(a, n) => f64::pown(vals[a.index()], n),
        };
        vals[id.index()] = v;
    }
    tie
}

/// Whether the point evaluation at `vars` (in `N`: `f64` or `f32`) stays inside the IEEE
/// 1788 domain of every operation. Where it leaves it (`pow(0, 0) = 1`, `1/0 = inf`,
/// `ln 0 = -inf`), typically after an underflow or a rounding moved an argument onto the
/// domain's edge, the point value is one that the interval operations rightly exclude.
fn point_in_domain<N: Number + Into<f64>>(ctx: &Context, root: NodeId, vars: &[N]) -> bool {
    let mut vals: Vec<N> = vec![vars[0]; ctx.len()];
    for id in ctx.reachable(&[root]) {
        let v = match *ctx.get(id) {
            Node::Var(v) => vars[v.index()],
            Node::Const(c) => N::constant(&c),
            Node::Unary(op, a) => {
                let x: f64 = vals[a.index()].into();
                let out = match op {
                    UnaryOp::Recip => x == 0.0,
                    UnaryOp::Ln | UnaryOp::Log10 => x <= 0.0,
                    _ => false,
                };
                if out {
                    return false;
                }
                N::unary(op, vals[a.index()])
            }
            Node::Binary(op, a, b) => {
                let (x, y): (f64, f64) = (vals[a.index()].into(), vals[b.index()].into());
                let out = match op {
                    BinaryOp::Div => y == 0.0,
                    BinaryOp::Pow => x < 0.0 || (x == 0.0 && y <= 0.0),
                    _ => false,
                };
                if out {
                    return false;
                }
                N::binary(op, vals[a.index()], vals[b.index()])
            }
            Node::Pown(a, n) => {
                let x: f64 = vals[a.index()].into();
                if n < 0 && x == 0.0 {
                    return false;
                }
                N::pown(vals[a.index()], n)
            }
        };
        vals[id.index()] = v;
    }
    true
}

fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

fn same_bits32(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

/// The same interval from two evaluators: bounds equal bit for bit, except that a zero
/// bound may carry either sign. The one-input evaluator multiplies by IEEE 1788's sign
/// cases ([`Interval::mul_sign_cases`]) and the slice evaluator by the corner products
/// ([`Interval::mul`]): the same interval, whose zero bounds may differ in sign (a product
/// that underflows to `-0` rounded up in one, `+0` in the other).
fn same_set(a: Interval<f64>, b: Interval<f64>) -> bool {
    let same = |x: f64, y: f64| same_bits(x, y) || (x == 0.0 && y == 0.0);
    match (a.bounds(), b.bounds()) {
        (None, None) => true,
        (Some((a0, a1)), Some((b0, b1))) => same(a0, b0) && same(a1, b1),
        _ => false,
    }
}

fn same_interval(a: Interval<f64>, b: Interval<f64>) -> bool {
    match (a.bounds(), b.bounds()) {
        (None, None) => true,
        (Some((a0, a1)), Some((b0, b1))) => same_bits(a0, b0) && same_bits(a1, b1),
        _ => false,
    }
}

// -------------------------------------------------------------------------------------------
// Properties
// -------------------------------------------------------------------------------------------

/// `Interval<f64>` contains the real value and the `f64` value at points of the box.
fn check_interval_f64_contains_real_and_point_values(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let x: Vec<Interval<f64>> = b.iter().map(|&b| iv(b)).collect();
    let fx = Evaluator::<Interval<f64>>::new(&tape).eval(&x).unwrap();
    let mut pe = Evaluator::<f64>::new(&tape);
    for u in us {
        let p = point(b, u);
        let Some(real) = r.oracle(&inputs_of(&p)) else {
            continue;
        };
        prop_assert!(holds(fx, &real.v), "real {} not in {fx:?} at {p:?}", real.v);
        let pv = pe.eval(&p).unwrap();
        if !pv.is_nan() && point_in_domain(&ctx, root, &p) {
            prop_assert!(holds_point(fx, pv), "f64 {pv} not in {fx:?} at {p:?}");
        }
    }
    Ok(())
}

/// Decorations: the plain evaluator's decoration (`eval_decorated`) is the decorated
/// evaluator's, with bit-identical interval parts, in `f64` and `f32`; `eval_continuous`
/// says "at least `dac`" exactly when the decoration does, `eval_traced_defined` "at least
/// `def`" exactly when it does (with the choices of `eval_traced`); a decoration of `def`
/// or better comes with a nonempty value. (The rules of each operation are tested in interval-core,
/// `tests/decorated_rules.rs`.)
fn check_decorations(b: &[(f64, f64); SLOTS], r: &Recipe) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let x: Vec<Interval<f64>> = b.iter().map(|&b| iv(b)).collect();
    let (fx, dec) = Evaluator::<Interval<f64>>::new(&tape)
        .eval_decorated(&x)
        .unwrap();
    let xd: Vec<DecInterval<f64>> = x.iter().map(|&x| DecInterval::new(x)).collect();
    let fd = Evaluator::<DecInterval<f64>>::new(&tape).eval(&xd).unwrap();
    prop_assert!(same_interval(fx, fd.interval()), "{fx:?} against {fd}");
    prop_assert_eq!(dec, fd.decoration(), "plain against decorated, {}", fd);
    prop_assert!(
        dec < Decoration::Def || !fx.is_empty(),
        "{dec} on the empty set"
    );
    let (fc, continuous) = Evaluator::<Interval<f64>>::new(&tape)
        .eval_continuous(&x)
        .unwrap();
    prop_assert!(same_interval(fx, fc));
    prop_assert_eq!(continuous, dec >= Decoration::Dac, "decoration {}", dec);
    let mut trace = Vec::new();
    let mut traced = Evaluator::<Interval<f64>>::new(&tape);
    let (ft, defined) = traced.eval_traced_defined(&x, &mut trace).unwrap();
    prop_assert!(same_interval(fx, ft));
    prop_assert_eq!(defined, dec >= Decoration::Def, "decoration {}", dec);
    let mut plain_trace = Vec::new();
    traced.eval_traced(&x, &mut plain_trace).unwrap();
    prop_assert_eq!(&trace, &plain_trace);
    let x32: Vec<Interval<f32>> = x.iter().map(|&x| x.cast()).collect();
    let (f32x, dec32) = Evaluator::<Interval<f32>>::new(&tape)
        .eval_decorated(&x32)
        .unwrap();
    let xd32: Vec<DecInterval<f32>> = x32.iter().map(|&x| DecInterval::new(x)).collect();
    let fd32 = Evaluator::<DecInterval<f32>>::new(&tape)
        .eval(&xd32)
        .unwrap();
    prop_assert_eq!(f32x, fd32.interval());
    prop_assert_eq!(
        dec32,
        fd32.decoration(),
        "f32: plain against decorated, {}",
        fd32
    );
    Ok(())
}

/// HC4-revise keeps every point of the box whose value lies in the target: the target is
/// the double-double enclosure of the value at a point of the box (widened by `widen`
/// times its magnitude), and the point must survive the contraction wherever the formula is
/// proven defined there. The contracted box lies in the box.
fn check_contractor_keeps_solutions(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
    widen: f64,
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let mut hc4 = Contractor::<f64>::new(&ctx, root);
    let x: Vec<Interval<f64>> = b.iter().map(|&b| iv(b)).collect();
    for u in us {
        let p = point(b, u);
        let (v, dec) = reference(&tape, &p).unwrap();
        let Some((lo, hi)) = v.bounds() else {
            continue;
        };
        if dec < Decoration::Def {
            continue;
        }
        let (lo, hi) = (lo.to_f64_down(), hi.to_f64_up());
        let pad = widen * lo.abs().max(hi.abs());
        let target = Interval::new((lo - pad).min(lo), (hi + pad).max(hi)).unwrap();
        let mut c = x.clone();
        let kept = hc4.contract(&mut c, target);
        prop_assert!(
            kept,
            "every point removed, but {p:?} has its value in {target:?}"
        );
        for (k, (ck, xk)) in c.iter().zip(&x).enumerate() {
            prop_assert!(
                ck.contains(p[k]),
                "{p:?} removed: slot {k} contracted to {ck:?}"
            );
            prop_assert!(ck.subset(*xk), "slot {k} grew to {ck:?}");
        }
    }
    Ok(())
}

/// `Interval<f32>` contains the real value and the `f32` value at points of the box.
fn check_interval_f32_contains_real_and_point_values(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let x: Vec<Interval<f32>> = b.iter().map(|&b| iv(b).cast::<f32>()).collect();
    let fx = Evaluator::<Interval<f32>>::new(&tape).eval(&x).unwrap();
    let mut pe = Evaluator::<f32>::new(&tape);
    for u in us {
        let p: [f32; SLOTS] = std::array::from_fn(|i| {
            let v = lerp(b[i], u[i]) as f32;
            v.clamp(x[i].inf(), x[i].sup())
        });
        if p.iter().any(|v| !v.is_finite()) {
            continue; // a bound beyond the f32 range
        }
        let inputs: [Float; SLOTS] = std::array::from_fn(|i| fl(p[i]));
        let Some(real) = r.oracle(&inputs) else {
            continue;
        };
        prop_assert!(
            holds32(fx, &real.v),
            "real {} not in {fx:?} at {p:?}",
            real.v
        );
        let pv = pe.eval(&p).unwrap();
        if !pv.is_nan() && point_in_domain(&ctx, root, &p) {
            prop_assert!(holds_point32(fx, pv), "f32 {pv} not in {fx:?} at {p:?}");
        }
    }
    Ok(())
}

/// Whether the real `v` lies in the double-double interval `x` (with [`holds`]' slack).
fn holds_dd(x: DdInterval, v: &Float) -> bool {
    let exact = |d: Dd| Float::with_val(PREC, d.hi()) + d.lo();
    x.bounds()
        .is_some_and(|(lo, hi)| between(&exact(lo), &exact(hi), v))
}

/// `DdInterval` contains the real value at points of the box.
fn check_interval_dd_contains_real_values(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let x: Vec<DdInterval> = b
        .iter()
        .map(|&b| DdInterval::from_interval(iv(b)))
        .collect();
    let fx = Evaluator::<DdInterval>::new(&tape).eval(&x).unwrap();
    for u in us {
        let p = point(b, u);
        let Some(real) = r.oracle(&inputs_of(&p)) else {
            continue;
        };
        prop_assert!(
            holds_dd(fx, &real.v),
            "real {} not in {fx} at {p:?}",
            real.v
        );
    }
    Ok(())
}

/// The slice evaluator agrees bit for bit with the one-input evaluator (`f64`, `f32`;
/// `Interval<f64>` up to the sign of a zero bound, see [`same_set`]), across more inputs
/// than one chunk.
fn check_slice_evaluator_is_bit_identical(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
    ws: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let pts: Vec<[f64; SLOTS]> = us.iter().map(|u| point(b, u)).collect();
    let cols: Vec<Vec<f64>> = (0..SLOTS)
        .map(|s| pts.iter().map(|p| p[s]).collect())
        .collect();
    let slices: Vec<&[f64]> = cols.iter().map(|c| c.as_slice()).collect();
    let mut out = vec![0.0; pts.len()];
    SliceEvaluator::<f64>::new(&tape)
        .eval(&slices, &mut out)
        .unwrap();
    let mut e = Evaluator::<f64>::new(&tape);
    for (p, o) in pts.iter().zip(&out) {
        let v = e.eval(p).unwrap();
        prop_assert!(same_bits(v, *o), "f64 slice {o} vs {v} at {p:?}");
    }

    let cols32: Vec<Vec<f32>> = cols
        .iter()
        .map(|c| c.iter().map(|&v| v as f32).collect())
        .collect();
    let slices32: Vec<&[f32]> = cols32.iter().map(|c| c.as_slice()).collect();
    let mut out32 = vec![0.0f32; pts.len()];
    SliceEvaluator::<f32>::new(&tape)
        .eval(&slices32, &mut out32)
        .unwrap();
    let mut e32 = Evaluator::<f32>::new(&tape);
    for (i, o) in out32.iter().enumerate() {
        let p: Vec<f32> = cols32.iter().map(|c| c[i]).collect();
        let v = e32.eval(&p).unwrap();
        prop_assert!(same_bits32(v, *o), "f32 slice {o} vs {v} at {p:?}");
    }

    // Sub-boxes between two random points of the box.
    let subs: Vec<[Interval<f64>; SLOTS]> = us
        .iter()
        .zip(ws)
        .map(|(u, w)| {
            let (p, q) = (point(b, u), point(b, w));
            std::array::from_fn(|s| iv((p[s].min(q[s]), p[s].max(q[s]))))
        })
        .collect();
    let icols: Vec<Vec<Interval<f64>>> = (0..SLOTS)
        .map(|s| subs.iter().map(|x| x[s]).collect())
        .collect();
    let islices: Vec<&[Interval<f64>]> = icols.iter().map(|c| c.as_slice()).collect();
    let mut iout = vec![Interval::EMPTY; subs.len()];
    SliceEvaluator::<Interval<f64>>::new(&tape)
        .eval(&islices, &mut iout)
        .unwrap();
    let mut ie = Evaluator::<Interval<f64>>::new(&tape);
    for (x, o) in subs.iter().zip(&iout) {
        let v = ie.eval(x).unwrap();
        prop_assert!(same_set(v, *o), "interval slice {o:?} vs {v:?} on {x:?}");
    }
    Ok(())
}

/// A tape pruned by an interval evaluation over a box equals the full tape at the points
/// of the box, and its interval values over sub-boxes contain the point and real values.
fn check_pruned_tape_agrees_inside_its_box(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
    ws: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let x: Vec<Interval<f64>> = b.iter().map(|&b| iv(b)).collect();
    let mut trace = Vec::new();
    Evaluator::<Interval<f64>>::new(&tape)
        .eval_traced(&x, &mut trace)
        .unwrap();
    prop_assert_eq!(trace.len(), tape.choice_count());
    let pruned = tape.simplify(&trace).unwrap();
    prop_assert!(pruned.len() <= tape.len());
    if trace.iter().all(|&c| c == Choice::Both) {
        prop_assert!(pruned.ptr_eq(&tape));
    }
    let (mut full, mut short) = (Evaluator::<f64>::new(&tape), Evaluator::<f64>::new(&pruned));
    let mut short_iv = Evaluator::<Interval<f64>>::new(&pruned);
    for (u, w) in us.iter().zip(ws) {
        let p = point(b, u);
        // Outside the domain the two may differ: see
        // `pruning_defines_what_the_full_tape_leaves_undefined`.
        let Some(real) = r.oracle(&inputs_of(&p)) else {
            continue;
        };
        let v = full.eval(&p).unwrap();
        if v.is_nan() || !point_in_domain(&ctx, root, &p) {
            continue; // an overflow or underflow on the way
        }
        let s = short.eval(&p).unwrap();
        // Equal up to the sign of a zero: where `min(-0, 0)` is decided, the pruned tape
        // returns the argument taken, the full tape whichever zero `f64::min` returns.
        prop_assert!(same_bits(v, s) || v == s, "pruned {s} vs full {v} at {p:?}");
        let q = point(b, w);
        let sub: Vec<Interval<f64>> = (0..SLOTS)
            .map(|i| iv((p[i].min(q[i]), p[i].max(q[i]))))
            .collect();
        let fs = short_iv.eval(&sub).unwrap();
        prop_assert!(holds(fs, &real.v), "real {} not in pruned {fs:?}", real.v);
        prop_assert!(
            holds_point(fs, s),
            "pruned point {s} not in {fs:?} on {sub:?}"
        );
    }
    Ok(())
}

/// For proper inputs, the outer-rounded modal result contains the point and real values;
/// for inputs of any modality, inner rounding is included in outer rounding.
fn check_modal_outer_contains_points_and_inner_is_included(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
    flips: [bool; SLOTS],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let proper: Vec<Modal<f64, Outer>> = b
        .iter()
        .map(|&(lo, hi)| Modal::proper(lo, hi).unwrap())
        .collect();
    let out = Evaluator::<Modal<f64, Outer>>::new(&tape)
        .eval(&proper)
        .unwrap();
    prop_assert!(!out.first().is_nan() && !out.second().is_nan(), "{out:?}");
    let mut pe = Evaluator::<f64>::new(&tape);
    for u in us {
        let p = point(b, u);
        let Some(real) = r.oracle(&inputs_of(&p)) else {
            continue;
        };
        prop_assert!(
            out.first() <= out.second(),
            "improper {out:?} from proper inputs"
        );
        let as_iv = Interval::new(out.first(), out.second()).unwrap();
        prop_assert!(holds(as_iv, &real.v), "real {} not in Out {out:?}", real.v);
        let pv = pe.eval(&p).unwrap();
        if !pv.is_nan() && point_in_domain(&ctx, root, &p) {
            prop_assert!(holds_point(as_iv, pv), "f64 {pv} not in Out {out:?}");
        }
    }
    // Random modalities: Inn(fR(X)) ⊆ Out(fR(X)).
    let mixed: Vec<(f64, f64)> = b
        .iter()
        .zip(flips)
        .map(|(&(lo, hi), f)| if f { (hi, lo) } else { (lo, hi) })
        .collect();
    let xo: Vec<Modal<f64, Outer>> = mixed
        .iter()
        .map(|&(a, c)| Modal::new(a, c).unwrap())
        .collect();
    let xi: Vec<Modal<f64, Inner>> = mixed
        .iter()
        .map(|&(a, c)| Modal::new(a, c).unwrap())
        .collect();
    let o = Evaluator::<Modal<f64, Outer>>::new(&tape)
        .eval(&xo)
        .unwrap();
    let i = Evaluator::<Modal<f64, Inner>>::new(&tape)
        .eval(&xi)
        .unwrap();
    prop_assert!(!i.first().is_nan() && !i.second().is_nan(), "{i:?}");
    prop_assert!(
        i.with_rounding::<Outer>().subset(o),
        "Inn {i:?} not included in Out {o:?} for {mixed:?}"
    );
    Ok(())
}

/// `Grad<Interval<f64>>` and the symbolic gradient over the box contain the real gradient,
/// the `Grad<f64>` gradient and the symbolic gradient's point value.
fn check_gradient_enclosures_contain_point_gradients(
    r: &Recipe,
    b: &[(f64, f64); SLOTS],
    us: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (mut ctx, root) = r.build();
    let tape = Tape::new(&ctx, &[root]).unwrap();
    let grad = ctx.gradient(root);
    let gtape = Tape::new(&ctx, &grad).unwrap();
    let x: Vec<Interval<f64>> = b.iter().map(|&b| iv(b)).collect();
    let mut gx = Grad::point(x[0], x[1], x[2]).to_vec();
    gx.push(Grad::constant_value(x[3]));
    let gi = Evaluator::<Grad<Interval<f64>>>::new(&tape)
        .eval(&gx)
        .unwrap();
    let mut si = [Interval::EMPTY; 3];
    Evaluator::<Interval<f64>>::new(&gtape)
        .eval_outputs(&x, &mut si)
        .unwrap();
    let mut gp = Evaluator::<Grad<f64>>::new(&tape);
    let mut sp = Evaluator::<f64>::new(&gtape);
    for u in us {
        let p = point(b, u);
        let Some(real) = r.oracle(&inputs_of(&p)) else {
            continue;
        };
        prop_assert!(holds(gi.v, &real.v), "real {} not in {:?}", real.v, gi.v);
        // Where a slope is undefined (`sqrt` at 0) the symbolic derivative is empty and reads
        // as unbounded (`Number::widen_undefined`, docs/numerics.md); forward mode widens it.
        if let Some(d) = real.d.as_ref() {
            for k in 0..3 {
                prop_assert!(
                    holds(gi.d[k], &d[k]),
                    "real d{k} {} not in Grad {:?}",
                    d[k],
                    gi.d[k]
                );
                prop_assert!(
                    holds(si[k].widen_undefined(), &d[k]),
                    "real d{k} {} not in symbolic {:?}",
                    d[k],
                    si[k]
                );
            }
        }
        let mut g = Grad::point(p[0], p[1], p[2]).to_vec();
        g.push(Grad::constant_value(p[3]));
        let g = gp.eval(&g).unwrap();
        let mut s = [0.0; 3];
        sp.eval_outputs(&p, &mut s).unwrap();
        // A NaN value (an overflow on the way) leaves the point derivative meaningless.
        let tie = has_tie(&ctx, &[root], &p) || g.v.is_nan();
        let regular = real.d.is_some() && !real.zero_times_undefined && !tie;
        for k in 0..3 {
            if s[k].is_finite() && point_in_domain(&ctx, grad[k], &p) {
                prop_assert!(
                    holds_point(si[k], s[k]),
                    "symbolic d{k} {} not in {:?}",
                    s[k],
                    si[k]
                );
            }
            if g.d[k].is_finite() && regular {
                prop_assert!(
                    holds_point(gi.d[k], g.d[k]),
                    "Grad d{k} {} not in {:?}",
                    g.d[k],
                    gi.d[k]
                );
                prop_assert!(
                    holds_point(si[k], g.d[k]),
                    "Grad d{k} {} not in symbolic {:?}",
                    g.d[k],
                    si[k]
                );
            }
        }
    }
    Ok(())
}

/// Over a beam (origin `c`, directions `D`, parameters `T`), `g(T)` and `g'(T)` contain
/// `g(t)` and `g'(t)` of every ray `d ∈ D` at every `t ∈ T`, real and `f64`.
fn check_beam_g_and_dg_contain_ray_values(
    r: &Recipe,
    c: [f64; 3],
    dir: [(f64, f64); 3],
    tb: (f64, f64),
    pb: (f64, f64),
    us: &[[f64; SLOTS]],
    vs: &[[f64; SLOTS]],
) -> Result<(), TestCaseError> {
    let (ctx, root) = r.build();
    let rf = RayFunction::new(&ctx, root).unwrap();
    prop_assert_eq!(rf.params().len(), 1);
    let pi = iv(pb);
    let mut beam = RayEvaluator::<Interval<f64>>::new(&rf, &[pi]).unwrap();
    let ci: [Interval<f64>; 3] = std::array::from_fn(|i| iv((c[i], c[i])));
    beam.set_ray(ci, std::array::from_fn(|i| iv(dir[i])));
    let (g, dg) = beam.g_dg(iv(tb));
    let g_only = beam.g(iv(tb));
    prop_assert!(same_interval(g, g_only), "g {g:?} vs g of g_dg {g_only:?}");
    for (u, v) in us.iter().zip(vs) {
        let d: [f64; 3] = std::array::from_fn(|i| lerp(dir[i], u[i]));
        let t = lerp(tb, u[3]);
        let pv = lerp(pb, v[0]);
        // The real ray point c + t·d and the real g, g' there.
        // Exact: 2200 bits hold any sum of a double and a product of two doubles.
        let exact = |v: f64| Float::with_val(2200, v);
        let at: [Float; SLOTS] = std::array::from_fn(|i| {
            if i < 3 {
                exact(c[i]) + exact(t) * d[i]
            } else {
                exact(pv)
            }
        });
        let Some(real) = r.oracle(&at) else { continue };
        let mut ray = RayEvaluator::<f64>::new(&rf, &[pv]).unwrap();
        ray.set_ray(c, d);
        let (gp, dgp) = ray.g_dg(t);
        let (rctx, [groot, dgroot]) = rf.graph();
        let ray_vars = [c[0], c[1], c[2], t, d[0], d[1], d[2], pv];
        if !gp.is_nan() && point_in_domain(rctx, groot, &ray_vars) {
            prop_assert!(holds_point(g, gp), "f64 g {gp} not in {g:?}");
        }
        let regular = real.d.is_some() && !real.zero_times_undefined;
        if !dgp.is_nan() && regular && point_in_domain(rctx, dgroot, &ray_vars) {
            prop_assert!(holds_point(dg, dgp), "f64 g' {dgp} not in {dg:?}");
        }
        prop_assert!(holds(g, &real.v), "real g {} not in {g:?}", real.v);
        if let Some(gr) = real.d.as_ref() {
            let mut dot = fl(0.0);
            for i in 0..3 {
                dot += gr[i].clone() * d[i];
            }
            prop_assert!(holds(dg, &dot), "real g' {dot} not in {dg:?}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(2048))]

    #[test]
    fn interval_f64_contains_real_and_point_values(
        r in recipe(),
        b in boxes(),
        us in fractions(4),
    ) {
        let res = check_interval_f64_contains_real_and_point_values(&r, &b, &us);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn interval_dd_contains_real_values(
        r in recipe(),
        b in boxes(),
        us in fractions(4),
    ) {
        let res = check_interval_dd_contains_real_values(&r, &b, &us);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn interval_f32_contains_real_and_point_values(
        r in recipe(),
        b in boxes(),
        us in fractions(4),
    ) {
        let res = check_interval_f32_contains_real_and_point_values(&r, &b, &us);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn contractor_keeps_solutions(
        r in recipe(),
        b in boxes(),
        us in fractions(4),
        widen in prop_oneof![Just(0.0), 0.0..1.0f64],
    ) {
        let res = check_contractor_keeps_solutions(&r, &b, &us, widen);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn decorations_agree(r in recipe(), b in boxes()) {
        let res = check_decorations(&b, &r);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn slice_evaluator_is_bit_identical(
        r in recipe(),
        b in boxes(),
        us in fractions(70),
        ws in fractions(70),
    ) {
        let res = check_slice_evaluator_is_bit_identical(&r, &b, &us, &ws);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn pruned_tape_agrees_inside_its_box(
        r in recipe(),
        b in boxes(),
        us in fractions(6),
        ws in fractions(6),
    ) {
        let res = check_pruned_tape_agrees_inside_its_box(&r, &b, &us, &ws);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn modal_outer_contains_points_and_inner_is_included(
        r in recipe(),
        b in boxes(),
        us in fractions(3),
        flips in [any::<bool>(); SLOTS],
    ) {
        let res = check_modal_outer_contains_points_and_inner_is_included(&r, &b, &us, flips);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn gradient_enclosures_contain_point_gradients(
        r in recipe(),
        b in boxes(),
        us in fractions(4),
    ) {
        let res = check_gradient_enclosures_contain_point_gradients(&r, &b, &us);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }

    #[test]
    fn beam_g_and_dg_contain_ray_values(
        r in recipe(),
        c in [value(), value(), value()],
        dir in [interval(), interval(), interval()],
        tb in interval(),
        pb in interval(),
        us in fractions(4),
        vs in fractions(4),
    ) {
        let res = check_beam_g_and_dg_contain_ray_values(&r, c, dir, tb, pb, &us, &vs);
        res.map_err(|e| TestCaseError::fail(format!("{e} in {}", r.describe())))?;
    }
}

// -------------------------------------------------------------------------------------------
// Fixed cases
// -------------------------------------------------------------------------------------------

fn point_iv(v: f64) -> Interval<f64> {
    Interval::new(v, v).unwrap()
}

/// `f = x^(y·y)` at `x = 0`, `y = 1e-200`: the real value is `0^(1e-400) = 0` and the interval
/// over the point box is `[0, 0]`; `y·y` underflows to `0` in `f64`, and the point `pow`
/// must then not answer C's `pow(0, 0) = 1`, a value outside the interval of a box that
/// holds the point: it follows the IEEE 1788 domain (NaN for `0^0`).
#[test]
fn point_pow_of_an_underflowed_exponent_stays_in_the_interval() {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, "pow(x, y*y)", &[]).unwrap();
    let tape = Tape::new(&ctx, &[f]).unwrap();
    let p = [0.0, 1e-200, 0.0];
    let v = Evaluator::<f64>::new(&tape).eval(&p).unwrap();
    let x = Evaluator::<Interval<f64>>::new(&tape)
        .eval(&p.map(point_iv))
        .unwrap();
    assert_eq!(x, Interval::ZERO);
    assert!(v.is_nan() || x.contains(v), "point value {v} outside {x:?}");
}

/// A product that underflows: the one-input evaluator (sign cases) and the slice evaluator
/// (corner products) give the same interval, whose zero upper bound carries a different
/// sign in each (the case the property test `slice_evaluator_is_bit_identical` found).
#[test]
fn underflowing_product_is_the_same_interval_in_slices() {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, "-(1e-300*z) * ((1e-300*z) * -(1e-300*z))", &[])
        .unwrap();
    let tape = Tape::new(&ctx, &[f]).unwrap();
    let x = [0.0, 0.0, -1.0].map(point_iv);
    let one = Evaluator::<Interval<f64>>::new(&tape).eval(&x).unwrap();
    let cols: Vec<Vec<Interval<f64>>> = x.iter().map(|v| vec![*v; 3]).collect();
    let slices: Vec<&[Interval<f64>]> = cols.iter().map(|c| c.as_slice()).collect();
    let mut out = vec![Interval::EMPTY; 3];
    SliceEvaluator::<Interval<f64>>::new(&tape)
        .eval(&slices, &mut out)
        .unwrap();
    for o in out {
        assert!(same_set(one, o), "{one:?} against {o:?}");
        assert!(o.contains(0.0) && o.inf() < 0.0, "encloses -1e-900: {o:?}");
    }
}

// -------------------------------------------------------------------------------------------
// Known failures (minimal cases), ignored until fixed
// -------------------------------------------------------------------------------------------

/// `f = sqrt(max(x, 0))` is `0` on `x ∈ [-2, -1]`, so its derivative there is `0`. The chain
/// rule multiplies the slope of `sqrt` at `[0, 0]` (`0.5 / 0`: empty) by the derivative of
/// `max(x, 0)` (`[0, 0]`), and the empty set times anything is empty. Forward mode replaces
/// an undefined slope of a defined argument by `[-inf, inf]` (so `[-inf, inf] · 0 = 0`); the
/// symbolic gradient gives the empty set, which `Number::widen_undefined` reads as unbounded
/// (docs/numerics.md), and `g'` of a beam is widened so. The same holds for `asin`/`acos`
/// at `±1`, for `pow(0, y)` (`ln 0`), and for the slopes of the step functions.
#[test]
fn undefined_slopes_read_as_unbounded() {
    let mut ctx = Context::new();
    let (x, zero) = (ctx.x(), ctx.constant(0.0).unwrap());
    let m = ctx.max(x, zero);
    let f = ctx.sqrt(m);
    let tape = Tape::new(&ctx, &[f]).unwrap();
    let bx = Interval::new(-2.0, -1.0).unwrap();
    let g = Evaluator::<Grad<Interval<f64>>>::new(&tape)
        .eval(&Grad::point(bx, point_iv(0.0), point_iv(0.0)))
        .unwrap();
    assert_eq!(g.v, Interval::ZERO);
    assert!(g.d[0].contains(0.0), "Grad: {:?}", g.d[0]);

    let [fx, _, _] = ctx.gradient(f);
    let dtape = Tape::new(&ctx, &[fx]).unwrap();
    let d = Evaluator::<Interval<f64>>::new(&dtape)
        .eval(&[bx, point_iv(0.0), point_iv(0.0)])
        .unwrap();
    assert!(d.is_empty() || d.contains(0.0), "symbolic: {d:?}");
    assert!(d.widen_undefined().contains(0.0), "symbolic: {d:?}");

    let rf = RayFunction::new(&ctx, f).unwrap();
    let mut beam = RayEvaluator::<Interval<f64>>::new(&rf, &[]).unwrap();
    beam.set_ray(
        [point_iv(-2.0), point_iv(0.0), point_iv(0.0)],
        [point_iv(1.0); 3],
    );
    let (gv, dg) = beam.g_dg(Interval::new(0.0, 1.0).unwrap());
    assert_eq!(gv, Interval::ZERO);
    assert!(dg.contains(0.0), "g': {dg:?}");
}

/// The symbolic derivative of `min(a, b)` is `db + (da - db)·H`: where `a < b` is decided
/// (`H = 1`) an undefined `db` still poisons it. `f = min(x, 1 + 0^y)` is `x` on
/// `x ∈ [-1, 0]`, `y ∈ [1, 2]` (where `0^y = 0`), so `∂f/∂y = 0`; forward mode (`Grad`)
/// selects the branch and gets `0`; the symbolic gradient gets the empty set, which reads as
/// unbounded (`Number::widen_undefined`): sound, if loose.
#[test]
fn untaken_branch_with_undefined_derivative_reads_as_unbounded() {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, "min(x, 1 + 0^y)", &[]).unwrap();
    let tape = Tape::new(&ctx, &[f]).unwrap();
    let (bx, by) = (
        Interval::new(-1.0, 0.0).unwrap(),
        Interval::new(1.0, 2.0).unwrap(),
    );
    let g = Evaluator::<Grad<Interval<f64>>>::new(&tape)
        .eval(&Grad::point(bx, by, point_iv(0.0)))
        .unwrap();
    assert_eq!(g.d[1], Interval::ZERO);
    let [_, fy, _] = ctx.gradient(f);
    let dtape = Tape::new(&ctx, &[fy]).unwrap();
    let d = Evaluator::<Interval<f64>>::new(&dtape)
        .eval(&[bx, by, point_iv(0.0)])
        .unwrap();
    assert!(d.widen_undefined().contains(0.0), "symbolic: {d:?}");
}

/// `f = min(x, 5 + sqrt(y))` over `x ∈ [0, 1]`, `y ∈ [-1, 1]`: the interval evaluation
/// decides `min = x` (`sqrt([-1, 1]) = [0, 1]`), and the pruned tape is `x`. At `y = -0.5`
/// the full tape is undefined (NaN; the empty set over `y ∈ [-1, -0.5]`): a pruned tape `x`
/// would draw the plane `x = 0` where the formula has no surface. The traced evaluation
/// sees that `sqrt` is undefined on part of its argument and records no choice, so nothing
/// is pruned.
#[test]
fn pruning_keeps_the_full_tape_where_it_is_partly_undefined() {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, "min(x, 5 + sqrt(y))", &[]).unwrap();
    let tape = Tape::new(&ctx, &[f]).unwrap();
    let region = [
        Interval::new(0.0, 1.0).unwrap(),
        Interval::new(-1.0, 1.0).unwrap(),
        point_iv(0.0),
    ];
    let mut trace = Vec::new();
    Evaluator::<Interval<f64>>::new(&tape)
        .eval_traced(&region, &mut trace)
        .unwrap();
    let pruned = tape.simplify(&trace).unwrap();
    let p = [0.5, -0.5, 0.0];
    let full = Evaluator::<f64>::new(&tape).eval(&p).unwrap();
    let short = Evaluator::<f64>::new(&pruned).eval(&p).unwrap();
    assert!(full.is_nan());
    assert!(
        short.is_nan(),
        "pruned tape gives {short} where the formula is undefined"
    );
    let sub = [
        Interval::new(0.0, 1.0).unwrap(),
        Interval::new(-1.0, -0.5).unwrap(),
        point_iv(0.0),
    ];
    let full = Evaluator::<Interval<f64>>::new(&tape).eval(&sub).unwrap();
    let short = Evaluator::<Interval<f64>>::new(&pruned).eval(&sub).unwrap();
    assert!(full.is_empty());
    assert!(
        short.is_empty(),
        "pruned tape gives {short:?} on an undefined sub-box"
    );
}

/// `pow(a, n)` with an exact integer `n` is `pown(a, n)`, whose domain includes negative
/// bases; folding it with the real-exponent `pow` (domain `a >= 0`) would clip a base whose
/// enclosure straddles 0: here the base is the real `0.1 + 0.2 - 0.30000000000000001 =
/// -1e-17`, and the folded `pow(base, 3)` must contain `-1e-51`.
#[test]
fn folding_pow_with_an_integer_exponent_uses_pown() {
    let mut ctx = Context::new();
    let base =
        implicit_expr::parse::parse(&mut ctx, "0.1 + 0.2 - 0.30000000000000001", &[]).unwrap();
    let c = ctx.as_const(base).unwrap();
    assert!(c.lo() < 0.0 && c.hi() > 0.0, "{c:?}");
    let three = ctx.constant(3.0).unwrap();
    let p = ctx.binary(BinaryOp::Pow, base, three);
    let q = ctx.pown(base, 3);
    let (p, q) = (ctx.as_const(p).unwrap(), ctx.as_const(q).unwrap());
    assert!(q.lo() <= -1e-51, "pown fold {q:?}");
    assert!(
        p.lo() <= -1e-51,
        "pow fold {p:?} misses the real value -1e-51 (pown fold {q:?})"
    );
}
