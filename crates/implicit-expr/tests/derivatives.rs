//! Derivatives: symbolic (`Context::gradient`) and forward mode (`Grad`) against finite
//! differences, against each other, and against known values; the interval versions of the
//! non-smooth operations; and named hard cases (a tangent double root, a singular point, huge
//! and tiny magnitudes).
//!
//! The environment variable `INTERVAL_CORE_TEST_SCALE` (a positive integer) multiplies the
//! number of cases of the property tests.

use implicit_expr::{
    BinaryOp, Context, Evaluator, Grad, NodeId, RayEvaluator, RayFunction, Tape, UnaryOp,
};
use interval_core::Interval;
use proptest::prelude::*;

mod common;
use common::config;

fn iv(lo: f64, hi: f64) -> Interval<f64> {
    Interval::new(lo, hi).unwrap()
}

/// A box: intervals for `x`, `y`, `z`.
type Box3 = [Interval<f64>; 3];

fn pt(v: f64) -> Interval<f64> {
    iv(v, v)
}

/// `f`, its symbolic gradient and the tapes of both.
struct Compiled {
    f: Tape,
    grad: Tape,
}

fn compile(ctx: &mut Context, f: NodeId) -> Compiled {
    let g = ctx.gradient(f);
    Compiled {
        f: Tape::new(ctx, &[f]).unwrap(),
        grad: Tape::new(ctx, &g).unwrap(),
    }
}

impl Compiled {
    fn value(&self, p: [f64; 3]) -> f64 {
        Evaluator::<f64>::new(&self.f).eval(&p).unwrap()
    }

    /// The symbolic gradient in `f64`.
    fn symbolic(&self, p: [f64; 3]) -> [f64; 3] {
        let mut out = [0.0; 3];
        Evaluator::<f64>::new(&self.grad)
            .eval_outputs(&p, &mut out)
            .unwrap();
        out
    }

    /// The symbolic gradient over a box.
    fn symbolic_box(&self, b: [Interval<f64>; 3]) -> [Interval<f64>; 3] {
        let mut out = [Interval::EMPTY; 3];
        Evaluator::<Interval<f64>>::new(&self.grad)
            .eval_outputs(&b, &mut out)
            .unwrap();
        out
    }

    /// The forward-mode gradient in `f64`.
    fn forward(&self, p: [f64; 3]) -> Grad<f64> {
        Evaluator::<Grad<f64>>::new(&self.f)
            .eval(&Grad::point(p[0], p[1], p[2]))
            .unwrap()
    }

    /// The forward-mode gradient over a box.
    fn forward_box(&self, b: [Interval<f64>; 3]) -> Grad<Interval<f64>> {
        Evaluator::<Grad<Interval<f64>>>::new(&self.f)
            .eval(&Grad::point(b[0], b[1], b[2]))
            .unwrap()
    }
}

// -------------------------------------------------------------------------------------------
// Random smooth expressions
// -------------------------------------------------------------------------------------------

/// A smooth one-argument building block; the ones with a restricted domain are composed so
/// that their argument stays well inside it.
#[derive(Copy, Clone, Debug)]
enum Smooth {
    Neg,
    Sqr,
    Sin,
    Cos,
    Atan,
    /// `exp(sin a)`
    ExpSin,
    /// `sqrt(1 + a²)`
    SqrtPos,
    /// `ln(1 + a²)`
    LnPos,
    /// `log10(2 + sin a)`
    Log10Pos,
    /// `1 / (1 + a²)`
    RecipPos,
    /// `asin(sin(a) / 2)`
    AsinHalf,
    /// `acos(cos(a) / 2)`
    AcosHalf,
    /// `tan(atan(a) / 2)`
    TanHalf,
    /// `(1 + a²)^0.7`, the real power
    PowPos,
}

const SMOOTH: [Smooth; 14] = [
    Smooth::Neg,
    Smooth::Sqr,
    Smooth::Sin,
    Smooth::Cos,
    Smooth::Atan,
    Smooth::ExpSin,
    Smooth::SqrtPos,
    Smooth::LnPos,
    Smooth::Log10Pos,
    Smooth::RecipPos,
    Smooth::AsinHalf,
    Smooth::AcosHalf,
    Smooth::TanHalf,
    Smooth::PowPos,
];

#[derive(Clone, Debug)]
enum SStep {
    Un(Smooth, usize),
    /// `+`, `-` or `*`
    Bin(BinaryOp, usize, usize),
    /// `a / (1 + b²)`
    DivPos(usize, usize),
    Pown(usize, i32),
}

#[derive(Clone, Debug)]
struct SmoothRecipe {
    /// Leaves: `x`, `y`, `z` and two constants.
    consts: [f64; 2],
    steps: Vec<SStep>,
}

fn smooth_recipe() -> impl Strategy<Value = SmoothRecipe> {
    let step = prop_oneof![
        4 => (prop::sample::select(SMOOTH.to_vec()), any::<usize>())
            .prop_map(|(op, a)| SStep::Un(op, a)),
        4 => (
            prop::sample::select(vec![BinaryOp::Add, BinaryOp::Sub, BinaryOp::Mul]),
            any::<usize>(),
            any::<usize>()
        )
            .prop_map(|(op, a, b)| SStep::Bin(op, a, b)),
        1 => (any::<usize>(), any::<usize>()).prop_map(|(a, b)| SStep::DivPos(a, b)),
        1 => (any::<usize>(), 2i32..=4).prop_map(|(a, n)| SStep::Pown(a, n)),
    ];
    (
        [-2.0..2.0f64, -2.0..2.0f64],
        prop::collection::vec(step, 1..8),
    )
        .prop_map(|(consts, steps)| SmoothRecipe { consts, steps })
}

/// Mostly one of the last three nodes, sometimes any.
fn arg(a: usize, k: usize) -> usize {
    if a % 10 < 7 {
        k - 1 - (a / 10) % k.min(3)
    } else {
        (a / 10) % k
    }
}

impl SmoothRecipe {
    fn build(&self, ctx: &mut Context) -> NodeId {
        let one = ctx.constant(1.0).unwrap();
        let two = ctx.constant(2.0).unwrap();
        let half = ctx.constant(0.5).unwrap();
        let mut nodes = vec![ctx.x(), ctx.y(), ctx.z()];
        for &c in &self.consts {
            nodes.push(ctx.constant(c).unwrap());
        }
        let pos = |ctx: &mut Context, a: NodeId| {
            let s = ctx.sqr(a);
            ctx.add(one, s)
        };
        for s in &self.steps {
            let k = nodes.len();
            let n = match *s {
                SStep::Un(op, a) => {
                    let a = nodes[arg(a, k)];
                    match op {
                        Smooth::Neg => ctx.neg(a),
                        Smooth::Sqr => ctx.sqr(a),
                        Smooth::Sin => ctx.unary(UnaryOp::Sin, a),
                        Smooth::Cos => ctx.unary(UnaryOp::Cos, a),
                        Smooth::Atan => ctx.unary(UnaryOp::Atan, a),
                        Smooth::ExpSin => {
                            let s = ctx.unary(UnaryOp::Sin, a);
                            ctx.unary(UnaryOp::Exp, s)
                        }
                        Smooth::SqrtPos => {
                            let p = pos(ctx, a);
                            ctx.sqrt(p)
                        }
                        Smooth::LnPos => {
                            let p = pos(ctx, a);
                            ctx.unary(UnaryOp::Ln, p)
                        }
                        Smooth::Log10Pos => {
                            let s = ctx.unary(UnaryOp::Sin, a);
                            let p = ctx.add(two, s);
                            ctx.unary(UnaryOp::Log10, p)
                        }
                        Smooth::RecipPos => {
                            let p = pos(ctx, a);
                            ctx.unary(UnaryOp::Recip, p)
                        }
                        Smooth::AsinHalf | Smooth::AcosHalf => {
                            let (inner, outer) = if matches!(op, Smooth::AsinHalf) {
                                (UnaryOp::Sin, UnaryOp::Asin)
                            } else {
                                (UnaryOp::Cos, UnaryOp::Acos)
                            };
                            let s = ctx.unary(inner, a);
                            let h = ctx.mul(half, s);
                            ctx.unary(outer, h)
                        }
                        Smooth::TanHalf => {
                            let t = ctx.unary(UnaryOp::Atan, a);
                            let h = ctx.mul(half, t);
                            ctx.unary(UnaryOp::Tan, h)
                        }
                        Smooth::PowPos => {
                            let p = pos(ctx, a);
                            let e = ctx.constant(0.7).unwrap();
                            ctx.binary(BinaryOp::Pow, p, e)
                        }
                    }
                }
                SStep::Bin(op, a, b) => ctx.binary(op, nodes[arg(a, k)], nodes[arg(b, k)]),
                SStep::DivPos(a, b) => {
                    let p = pos(ctx, nodes[arg(b, k)]);
                    ctx.div(nodes[arg(a, k)], p)
                }
                SStep::Pown(a, n) => ctx.pown(nodes[arg(a, k)], n),
            };
            nodes.push(n);
        }
        *nodes.last().unwrap()
    }
}

/// Central difference of `f` along `axis` at `p` with step `h`.
fn central(c: &Compiled, p: [f64; 3], axis: usize, h: f64) -> f64 {
    let (mut a, mut b) = (p, p);
    a[axis] += h;
    b[axis] -= h;
    (c.value(a) - c.value(b)) / (a[axis] - b[axis])
}

/// The symbolic gradient of `r` at `p` agrees with central finite differences (two step
/// sizes; points where they disagree with each other by more than a thousandth of the
/// derivative's size, down to 10^-6, are skipped: near a singularity or in a steep or fast
/// oscillating region they have not converged, whatever the function's scale), and forward
/// mode agrees with the symbolic gradient.
fn check_gradient(r: &SmoothRecipe, p: [f64; 3]) -> Result<(), TestCaseError> {
    let mut ctx = Context::new();
    let f = r.build(&mut ctx);
    let c = compile(&mut ctx, f);
    let v = c.value(p);
    prop_assume!(v.is_finite() && v.abs() < 1e6);
    let d = c.symbolic(p);
    let g = c.forward(p);
    prop_assert_eq!(g.v.to_bits(), v.to_bits());
    for (k, (&dk, &gk)) in d.iter().zip(&g.d).enumerate() {
        prop_assert!(dk.is_finite(), "d{k} = {dk} at {p:?}");
        // Forward mode and the symbolic gradient round differently: close, not equal.
        let tol = 1e-9 * (1.0 + dk.abs() + v.abs());
        prop_assert!(
            (gk - dk).abs() <= tol,
            "forward d{k} {gk} vs symbolic {dk} at {p:?}"
        );
        let h = 1e-4;
        let (f1, f2) = (central(&c, p, k, h), central(&c, p, k, h / 2.0));
        let spread = (f1 - f2).abs();
        if spread > 1e-3 * (1e-6 + f2.abs()) {
            continue; // finite differences not converged: too steep to check this way
        }
        let tol = 4.0 * spread + 1e-6 * (1.0 + dk.abs()) + 1e-10 * v.abs() / h;
        prop_assert!(
            (f2 - dk).abs() <= tol,
            "d{k}: symbolic {dk} vs finite difference {f2} (spread {spread}) at {p:?}"
        );
    }
    Ok(())
}

/// A case the property below once failed: `log10(2 + sin((2z)^8)) / (1 + (2z)^16)` near
/// z = -1.92, a value of about 10^-10 whose sine turns about three times over a step of the
/// finite differences, so that their two estimates (each about 10^-7) agreed to within the
/// old absolute threshold while neither had converged. Such a point is now skipped.
#[test]
fn gradient_check_skips_unconverged_differences() {
    let r = SmoothRecipe {
        consts: [0.0, 0.0],
        steps: vec![
            SStep::Bin(BinaryOp::Add, 2620536392938954877, 7577508800188773620),
            SStep::Pown(4467950634939581337, 2),
            SStep::Pown(11861392808261596170, 4),
            SStep::Un(Smooth::Log10Pos, 1028442488028177990),
            SStep::DivPos(8095688582228070477, 10863072999785569060),
        ],
    };
    check_gradient(&r, [0.0, 0.0, -1.9185585577169417]).unwrap();
}

proptest! {
    #![proptest_config(config(2048))]

    /// See [`check_gradient`].
    #[test]
    fn symbolic_gradient_matches_finite_differences(
        r in smooth_recipe(),
        p in [-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64],
    ) {
        check_gradient(&r, p)?;
    }

    /// The interval gradients over a small box around the point contain the point gradients.
    #[test]
    fn interval_gradients_contain_point_gradients(
        r in smooth_recipe(),
        p in [-2.0..2.0f64, -2.0..2.0f64, -2.0..2.0f64],
        w in 0.0..0.1f64,
    ) {
        let mut ctx = Context::new();
        let f = r.build(&mut ctx);
        let c = compile(&mut ctx, f);
        let b = p.map(|v| iv(v - w, v + w));
        let (sb, fb) = (c.symbolic_box(b), c.forward_box(b));
        let (d, g) = (c.symbolic(p), c.forward(p));
        for k in 0..3 {
            if d[k].is_finite() {
                prop_assert!(sb[k].contains(d[k]), "symbolic d{k} {} not in {:?}", d[k], sb[k]);
            }
            if g.d[k].is_finite() {
                prop_assert!(fb.d[k].contains(g.d[k]), "forward d{k} {} not in {:?}", g.d[k], fb.d[k]);
            }
        }
    }
}

// -------------------------------------------------------------------------------------------
// Each operation at a fixed point
// -------------------------------------------------------------------------------------------

/// Whether `a` and `b` agree to a few ulps.
fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= 4.0 * f64::EPSILON * a.abs().max(b.abs())
}

/// Checks `d/dx f(x)` at `x0` for `f = op(x)`: symbolic and forward mode in `f64` against
/// `expected`, and the interval versions over `[x0, x0]` containing it (within rounding).
fn check_unary(op: UnaryOp, x0: f64, expected: f64) {
    let mut ctx = Context::new();
    let x = ctx.x();
    let f = ctx.unary(op, x);
    let c = compile(&mut ctx, f);
    let p = [x0, 0.0, 0.0];
    let (d, g) = (c.symbolic(p)[0], c.forward(p).d[0]);
    assert!(
        close(d, expected),
        "{op}'({x0}): symbolic {d}, expected {expected}"
    );
    assert!(
        close(g, expected),
        "{op}'({x0}): forward {g}, expected {expected}"
    );
    let b = [pt(x0), pt(0.0), pt(0.0)];
    for (what, e) in [
        ("symbolic", c.symbolic_box(b)[0]),
        ("forward", c.forward_box(b).d[0]),
    ] {
        let (lo, hi) = e.bounds().unwrap();
        let slack = 4.0 * f64::EPSILON * expected.abs();
        assert!(
            lo - slack <= expected && expected <= hi + slack,
            "{op}'({x0}): {what} interval {e:?} misses {expected}"
        );
        assert!(
            hi - lo <= 8.0 * f64::EPSILON * expected.abs().max(1.0),
            "{op}'({x0}): {what} interval {e:?} too wide"
        );
    }
}

#[test]
fn derivative_of_each_unary_operation() {
    use UnaryOp::*;
    let s75 = 0.75f64.sqrt();
    let cases: [(UnaryOp, f64, f64); 24] = [
        (Neg, 0.3, -1.0),
        (Abs, -2.0, -1.0),
        (Abs, 3.0, 1.0),
        (Sqr, 3.0, 6.0),
        (Sqr, -0.5, -1.0),
        (Sqrt, 4.0, 0.25),
        (Recip, 2.0, -0.25),
        (Exp, 1.0, std::f64::consts::E),
        (Exp, 0.0, 1.0),
        (Ln, 2.0, 0.5),
        (Log10, 10.0, 1.0 / (10.0 * std::f64::consts::LN_10)),
        (Sin, 0.0, 1.0),
        (Sin, 0.5, 0.8775825618903728), // cos 0.5
        (Cos, 0.5, -0.479425538604203), // -sin 0.5
        (Tan, 0.0, 1.0),
        (Tan, 0.5, 1.2984464104095248), // 1 + tan² 0.5
        (Asin, 0.5, 1.0 / s75),
        (Acos, 0.5, -1.0 / s75),
        (Atan, 2.0, 0.2),
        (Floor, 0.3, 0.0),
        (Ceil, -1.7, 0.0),
        (Round, 2.2, 0.0),
        (Not, 0.7, 0.0),
        (SlopeFloor, 0.3, 0.0),
    ];
    for (op, x0, expected) in cases {
        check_unary(op, x0, expected);
    }
    check_unary(SlopeRound, 0.3, 0.0);
    check_unary(SlopeNot, 0.3, 0.0);
}

#[test]
fn derivative_of_each_binary_operation() {
    // (formula builder, point, expected ∂/∂x, expected ∂/∂y)
    let cases: [(BinaryOp, [f64; 2], [f64; 2]); 9] = [
        (BinaryOp::Add, [1.0, 2.0], [1.0, 1.0]),
        (BinaryOp::Sub, [1.0, 2.0], [1.0, -1.0]),
        (BinaryOp::Mul, [3.0, -2.0], [-2.0, 3.0]),
        (BinaryOp::Div, [3.0, 2.0], [0.5, -0.75]),
        (BinaryOp::Min, [1.0, 2.0], [1.0, 0.0]),
        (BinaryOp::Min, [3.0, 2.0], [0.0, 1.0]),
        (BinaryOp::Max, [1.0, 2.0], [0.0, 1.0]),
        (BinaryOp::Max, [3.0, 2.0], [1.0, 0.0]),
        // d(x^y) = y x^(y-1) dx + x^y ln x dy at (2, 3): 12, 8 ln 2
        (
            BinaryOp::Pow,
            [2.0, 3.0],
            [12.0, 8.0 * std::f64::consts::LN_2],
        ),
    ];
    for (op, [x0, y0], [ex, ey]) in cases {
        let mut ctx = Context::new();
        let (x, y) = (ctx.x(), ctx.y());
        let f = ctx.binary(op, x, y);
        let c = compile(&mut ctx, f);
        let p = [x0, y0, 0.0];
        let (d, g) = (c.symbolic(p), c.forward(p));
        for (k, e) in [(0, ex), (1, ey)] {
            assert!(
                close(d[k], e),
                "{op} d{k} at {p:?}: symbolic {}, expected {e}",
                d[k]
            );
            assert!(
                close(g.d[k], e),
                "{op} d{k} at {p:?}: forward {}, expected {e}",
                g.d[k]
            );
        }
        let b = p.map(pt);
        let (sb, fb) = (c.symbolic_box(b), c.forward_box(b));
        for (k, e) in [(0, ex), (1, ey)] {
            let slack = 4.0 * f64::EPSILON * e.abs();
            for iv in [sb[k], fb.d[k]] {
                assert!(
                    iv.inf() - slack <= e && e <= iv.sup() + slack,
                    "{op} d{k}: {iv:?} misses {e}"
                );
            }
        }
    }
    // pown: d(x^n) = n x^(n-1).
    for (n, x0, e) in [
        (3, 2.0, 12.0),
        (-2, 2.0, -0.25),
        (5, -1.0, 5.0),
        (4, 0.0, 0.0),
    ] {
        let mut ctx = Context::new();
        let x = ctx.x();
        let f = ctx.pown(x, n);
        let c = compile(&mut ctx, f);
        let p = [x0, 0.0, 0.0];
        assert!(close(c.symbolic(p)[0], e), "pown {n} at {x0}");
        assert!(close(c.forward(p).d[0], e), "pown {n} at {x0}");
        assert!(c.symbolic_box(p.map(pt))[0].contains(e));
        assert!(c.forward_box(p.map(pt)).d[0].contains(e));
    }
}

// -------------------------------------------------------------------------------------------
// Non-smooth operations over intervals
// -------------------------------------------------------------------------------------------

/// Where the interval evaluation cannot decide which argument `min`/`max` takes (or the sign
/// of the argument of `abs`), the derivative encloses the hull of the branches' derivatives;
/// where it can, it is the taken branch's.
#[test]
fn min_max_abs_derivatives_are_the_hull_where_undecided() {
    let cases: [(&str, Box3, Box3); 8] = [
        // undecided: x ∈ [0, 2], y ∈ [1, 3]
        (
            "min",
            [iv(0.0, 2.0), iv(1.0, 3.0), pt(0.0)],
            [iv(0.0, 1.0), iv(0.0, 1.0), pt(0.0)],
        ),
        (
            "max",
            [iv(0.0, 2.0), iv(1.0, 3.0), pt(0.0)],
            [iv(0.0, 1.0), iv(0.0, 1.0), pt(0.0)],
        ),
        // decided: x ∈ [0, 1] below y ∈ [2, 3]
        (
            "min",
            [iv(0.0, 1.0), iv(2.0, 3.0), pt(0.0)],
            [pt(1.0), pt(0.0), pt(0.0)],
        ),
        (
            "max",
            [iv(0.0, 1.0), iv(2.0, 3.0), pt(0.0)],
            [pt(0.0), pt(1.0), pt(0.0)],
        ),
        // touching: x ∈ [0, 1], y ∈ [1, 2]: min = x, max = y everywhere
        (
            "min",
            [iv(0.0, 1.0), iv(1.0, 2.0), pt(0.0)],
            [pt(1.0), pt(0.0), pt(0.0)],
        ),
        (
            "max",
            [iv(0.0, 1.0), iv(1.0, 2.0), pt(0.0)],
            [pt(0.0), pt(1.0), pt(0.0)],
        ),
        // abs across 0, and on one side
        (
            "abs",
            [iv(-1.0, 2.0), pt(0.0), pt(0.0)],
            [iv(-1.0, 1.0), pt(0.0), pt(0.0)],
        ),
        (
            "abs",
            [iv(-3.0, -1.0), pt(0.0), pt(0.0)],
            [pt(-1.0), pt(0.0), pt(0.0)],
        ),
    ];
    for (op, b, expected) in cases {
        let mut ctx = Context::new();
        let (x, y) = (ctx.x(), ctx.y());
        let f = match op {
            "min" => ctx.min(x, y),
            "max" => ctx.max(x, y),
            _ => ctx.unary(UnaryOp::Abs, x),
        };
        let c = compile(&mut ctx, f);
        let fb = c.forward_box(b);
        let sb = c.symbolic_box(b);
        for k in 0..3 {
            // Forward mode gives exactly the hull; the symbolic form `db + (da - db)·H`
            // encloses it (equal here, with exact arithmetic on small integers).
            assert_eq!(fb.d[k], expected[k], "{op} forward d{k} over {b:?}");
            assert_eq!(sb[k], expected[k], "{op} symbolic d{k} over {b:?}");
        }
    }
    // The hull of branch derivatives of different sizes: min(2x, -3x) over x ∈ [-1, 1]
    // has branch derivatives 2 and -3.
    let mut ctx = Context::new();
    let x = ctx.x();
    let (two, m3) = (ctx.constant(2.0).unwrap(), ctx.constant(-3.0).unwrap());
    let (a, b) = (ctx.mul(two, x), ctx.mul(m3, x));
    let f = ctx.min(a, b);
    let c = compile(&mut ctx, f);
    let bx = [iv(-1.0, 1.0), pt(0.0), pt(0.0)];
    assert_eq!(c.forward_box(bx).d[0], iv(-3.0, 2.0));
    // Symbolically: -3 + (2 - (-3))·[0, 1], exact.
    assert_eq!(c.symbolic_box(bx)[0], iv(-3.0, 2.0));
}

// -------------------------------------------------------------------------------------------
// Hard cases
// -------------------------------------------------------------------------------------------

/// `f = (x - 1)²` touches zero at `x = 1` without crossing it: the derivative is exactly 0
/// there and its enclosure over a box around the root holds 0 and is tight (interval Newton
/// cannot exclude such a root, and must not).
#[test]
fn tangent_double_root() {
    let mut ctx = Context::new();
    let x = ctx.x();
    let one = ctx.constant(1.0).unwrap();
    let s = ctx.sub(x, one);
    let f = ctx.sqr(s);
    let c = compile(&mut ctx, f);
    assert_eq!(c.value([1.0, 0.0, 0.0]), 0.0);
    assert_eq!(c.symbolic([1.0, 0.0, 0.0])[0], 0.0);
    assert_eq!(c.forward([1.0, 0.0, 0.0]).d[0], 0.0);
    for eps in [1e-1, 1e-8, 1e-300] {
        let b = [iv(1.0 - eps, 1.0 + eps), pt(0.0), pt(0.0)];
        let (sb, fb) = (c.symbolic_box(b)[0], c.forward_box(b).d[0]);
        for e in [sb, fb] {
            assert!(e.contains(0.0), "{e:?}");
            // 2(x - 1) over the box: the subtractions are exact (Sterbenz), so the
            // enclosure is exactly [2(lo - 1), 2(hi - 1)].
            let (lo, hi) = (b[0].inf(), b[0].sup());
            assert_eq!(e, iv(2.0 * (lo - 1.0), 2.0 * (hi - 1.0)), "ε = {eps}");
        }
        let fv = Evaluator::<Interval<f64>>::new(&c.f).eval(&b).unwrap();
        assert_eq!(fv.inf(), 0.0, "{fv:?}");
    }
    // Along a ray through the root: g(t) = (t - 1)², g'(1) = 0.
    let rf = RayFunction::new(&ctx, f).unwrap();
    let mut ray = RayEvaluator::<f64>::new(&rf, &[]).unwrap();
    ray.set_ray([0.0; 3], [1.0, 0.0, 0.0]);
    assert_eq!(ray.g_dg(1.0), (0.0, 0.0));
    let mut beam = RayEvaluator::<Interval<f64>>::new(&rf, &[]).unwrap();
    beam.set_ray([pt(0.0); 3], [pt(1.0), pt(0.0), pt(0.0)]);
    let (g, dg) = beam.g_dg(iv(0.5, 1.5));
    assert!(g.contains(0.0) && dg.contains(0.0));
    assert_eq!(dg, iv(-1.0, 1.0));
}

/// `f = sqrt(x)` has an unbounded derivative at 0: the enclosures over boxes reaching 0 are
/// unbounded above, and tiny boxes next to 0 give huge lower bounds.
#[test]
fn singular_point_has_an_unbounded_derivative() {
    let mut ctx = Context::new();
    let x = ctx.x();
    let f = ctx.sqrt(x);
    let c = compile(&mut ctx, f);
    assert_eq!(c.forward([0.0; 3]).d[0], f64::INFINITY);
    assert_eq!(c.symbolic([0.0; 3])[0], f64::INFINITY);
    let b = [iv(0.0, 1.0), pt(0.0), pt(0.0)];
    for e in [c.symbolic_box(b)[0], c.forward_box(b).d[0]] {
        assert_eq!(e.sup(), f64::INFINITY, "{e:?}");
        assert!(e.inf() <= 0.5 && e.inf() > 0.49, "{e:?}");
    }
    let b = [iv(1e-300, 2e-300), pt(0.0), pt(0.0)];
    for e in [c.symbolic_box(b)[0], c.forward_box(b).d[0]] {
        // 0.5 / sqrt(2e-300) ≈ 3.5e149
        assert!(e.inf() > 3e149 && e.sup() < 6e149, "{e:?}");
    }
    // Away from the singularity the derivative is ordinary: 1/(2·sqrt 4) = 0.25.
    assert_eq!(c.symbolic([4.0, 0.0, 0.0])[0], 0.25);
}

/// Derivatives of `1e300·x` and `1e-300·x` keep their magnitude; overflow of the value or of
/// the derivative gives unbounded enclosures, never wrong finite ones.
#[test]
fn huge_and_tiny_magnitudes() {
    for k in [1e300, 1e-300] {
        let mut ctx = Context::new();
        let x = ctx.x();
        let kc = ctx.constant(k).unwrap();
        let f = ctx.mul(kc, x);
        let c = compile(&mut ctx, f);
        assert_eq!(c.symbolic([2.0, 0.0, 0.0])[0], k);
        assert_eq!(c.forward([2.0, 0.0, 0.0]).d[0], k);
        let b = [iv(1.0, 2.0), pt(0.0), pt(0.0)];
        assert_eq!(c.symbolic_box(b)[0], pt(k));
        assert_eq!(c.forward_box(b).d[0], pt(k));
        // Values: 1e300 · 1e10 overflows, 1e-300 · 1e-20 is subnormal.
        let far = [iv(1e10, 1e10), pt(0.0), pt(0.0)];
        let v = Evaluator::<Interval<f64>>::new(&c.f).eval(&far).unwrap();
        if k > 1.0 {
            assert_eq!(v.sup(), f64::INFINITY);
            assert_eq!(v.inf(), f64::MAX);
        } else {
            assert!(v.contains(1e-290));
        }
        let near = [pt(1e-20), pt(0.0), pt(0.0)];
        let v = Evaluator::<Interval<f64>>::new(&c.f).eval(&near).unwrap();
        if k < 1.0 {
            // 1e-320 is subnormal: the enclosure holds the real product.
            assert!(
                v.inf() <= 1e-320 && 1e-320 <= v.sup() && v.inf() > 0.0,
                "{v:?}"
            );
        }
    }
    // (1e300·x)² has derivative 2e600·x: it overflows to an unbounded enclosure.
    let mut ctx = Context::new();
    let x = ctx.x();
    let kc = ctx.constant(1e300).unwrap();
    let m = ctx.mul(kc, x);
    let f = ctx.sqr(m);
    let c = compile(&mut ctx, f);
    let b = [iv(1.0, 2.0), pt(0.0), pt(0.0)];
    for e in [c.symbolic_box(b)[0], c.forward_box(b).d[0]] {
        assert_eq!(e.sup(), f64::INFINITY, "{e:?}");
    }
    assert_eq!(c.forward([1.0, 0.0, 0.0]).d[0], f64::INFINITY);
    // Tiny: (1e-300·x)² underflows to 0; its derivative 2e-600·x to 0 as well, enclosed.
    let mut ctx = Context::new();
    let x = ctx.x();
    let kc = ctx.constant(1e-300).unwrap();
    let m = ctx.mul(kc, x);
    let f = ctx.sqr(m);
    let c = compile(&mut ctx, f);
    for e in [c.symbolic_box(b)[0], c.forward_box(b).d[0]] {
        assert!(e.contains(0.0) && e.inf() >= 0.0 && e.sup() > 0.0, "{e:?}");
    }
}
