//! The compiled code against the interpreter (the same bounds, choices and flags, or a
//! fallback) and against a double-double reference at points of the region (enclosure).

use std::sync::atomic::{AtomicUsize, Ordering};

use interval_core::{Decoration, Interval};
use proptest::prelude::*;
use proptest::strategy::ValueTree;

use super::{Code, MAX_OUTPUTS, MAX_VARS};
use crate::constant::Constant;
use crate::context::{Context, NodeId, Var};
use crate::eval::Evaluator;
use crate::number::Choice;
use crate::op::{BinaryOp, UnaryOp};
use crate::tape::Tape;
use crate::testing::check_value_in;

const UNARY: [UnaryOp; 5] = [
    UnaryOp::Neg,
    UnaryOp::Abs,
    UnaryOp::Sqr,
    UnaryOp::Sqrt,
    UnaryOp::Not,
];
const BINARY: [BinaryOp; 5] = [
    BinaryOp::Add,
    BinaryOp::Sub,
    BinaryOp::Mul,
    BinaryOp::Min,
    BinaryOp::Max,
];
const DECIMALS: [&str; 8] = ["0", "0.5", "1", "2", "0.1", "0.3", "1e-3", "1e300"];

/// A recipe: leaves (a variable or a constant), then steps on earlier nodes.
#[derive(Clone, Debug)]
enum Step {
    Unary(usize, usize),
    Binary(usize, usize, usize),
}

fn build(leaves: &[(bool, usize)], steps: &[Step]) -> (Context, NodeId) {
    let mut ctx = Context::new();
    let mut nodes = Vec::new();
    for &(var, i) in leaves {
        nodes.push(if var {
            ctx.var(Var((i % 3) as u32)).expect("x, y, z")
        } else {
            ctx.constant_enclosed(Constant::from_decimal(DECIMALS[i % 8]).expect("a literal"))
        });
    }
    for s in steps {
        let k = nodes.len();
        let n = match *s {
            Step::Unary(op, a) => ctx.unary(UNARY[op % 5], nodes[k - 1 - a % k.min(3)]),
            Step::Binary(op, a, b) => ctx.binary(
                BINARY[op % 5],
                nodes[k - 1 - a % k.min(3)],
                nodes[(b / 3) % k],
            ),
        };
        nodes.push(n);
    }
    let root = *nodes.last().expect("a leaf");
    (ctx, root)
}

fn expression() -> impl Strategy<Value = (Context, NodeId)> {
    let step = prop_oneof![
        2 => (0..5usize, 0..3usize).prop_map(|(op, a)| Step::Unary(op, a)),
        3 => (0..5usize, 0..3usize, 0..64usize).prop_map(|(op, a, b)| Step::Binary(op, a, b)),
    ];
    (
        prop::collection::vec((prop::bool::weighted(0.7), 0..8usize), 1..5),
        prop::collection::vec(step, 1..24),
    )
        .prop_map(|(leaves, steps)| build(&leaves, &steps))
}

/// A bound: moderate, integer, tiny, subnormal, huge or infinite.
fn bound() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -4.0..4.0f64,
        2 => (-4i32..=4).prop_map(f64::from),
        1 => -1e-300..1e-300f64,
        1 => (-4i64..4).prop_map(|k| k as f64 * 5e-324),
        1 => -1e300..1e300f64,
        1 => prop::sample::select(vec![f64::INFINITY, f64::NEG_INFINITY, f64::MAX, 0.0, -0.0]),
    ]
}

fn interval() -> impl Strategy<Value = Interval<f64>> {
    prop_oneof![
        4 => (bound(), bound()).prop_filter_map("a bounded-or-not nonempty interval", |(a, b)| {
            let (lo, hi) = (a.min(b), a.max(b));
            (lo < f64::INFINITY && hi > f64::NEG_INFINITY).then(|| Interval::new_unchecked(lo, hi))
        }),
        1 => (-4.0..4.0f64).prop_map(|v| Interval::new_unchecked(v, v)),
        1 => Just(Interval::EMPTY),
    ]
}

/// Cases in which the compiled code answered (not a fallback), across the property test.
static ANSWERED: AtomicUsize = AtomicUsize::new(0);

fn pairs(vars: &[Interval<f64>]) -> [[f64; 2]; MAX_VARS] {
    let mut xs = [[0.0; 2]; MAX_VARS];
    for (x, v) in xs.iter_mut().zip(vars) {
        *x = v.bounds().map_or([f64::NAN; 2], |(lo, hi)| [lo, hi]);
    }
    xs
}

fn same(a: Interval<f64>, b: [f64; 2]) -> bool {
    match a.bounds() {
        Some((lo, hi)) => lo == b[0] && hi == b[1],
        None => b[0].is_nan() && b[1].is_nan(),
    }
}

/// Checks the compiled code of `tape` at `vars` against a fresh interpreter (a fresh tape
/// is below the count at which evaluators switch to its code). Returns whether it answered.
fn check(tape: &Tape, vars: &[Interval<f64>]) -> Result<bool, TestCaseError> {
    let mut ev = Evaluator::<Interval<f64>>::new(tape);
    let want = ev.eval(vars).unwrap();
    if vars.iter().any(|v| v.is_empty()) {
        // A code is run on nonempty variables only: an evaluator (whatever it has compiled)
        // answers an empty one with the interpreter.
        tape.expect_reuse();
        let mut compiled = Evaluator::<Interval<f64>>::new(tape);
        let got = compiled.eval(vars).unwrap();
        prop_assert!(got.is_empty() == want.is_empty() && (got.is_empty() || got == want));
        return Ok(false);
    }
    let mut want_trace = Vec::new();
    ev.eval_traced(vars, &mut want_trace).unwrap();
    let (_, continuous) = ev.eval_continuous(vars).unwrap();

    let plain = Code::compile(tape, false).expect("supported operations compile");
    let traced = Code::compile(tape, true).expect("supported operations compile");
    let xs = pairs(vars);
    let mut bytes = vec![9u8; tape.choice_count()];
    let (mut v, mut w) = ([[0.0; 2]; MAX_OUTPUTS], [[0.0; 2]; MAX_OUTPUTS]);
    let a = plain.run(&xs, &mut [], &mut v);
    let b = traced.run(&xs, &mut bytes, &mut w);
    prop_assert_eq!(a.is_some(), b.is_some());
    let (Some(flags), Some(_)) = (a, b) else {
        return Ok(false);
    };
    let (v, w) = (v[0], w[0]);
    prop_assert!(same(want, v), "interpreter {want:?}, compiled {v:?}");
    prop_assert!(same(want, w), "interpreter {want:?}, compiled traced {w:?}");
    let value = Interval::new_unchecked(v[0], v[1]);
    prop_assert_eq!(
        continuous,
        !flags.partial
            && !flags.jump
            && crate::number::Number::value_decoration(value) >= Decoration::Dac
    );
    if !flags.partial {
        let mut trace = Vec::new();
        super::choices_into(&bytes, &mut trace);
        prop_assert_eq!(&trace, &want_trace);
    } else {
        prop_assert!(want_trace.iter().all(|&c| c == Choice::Both));
    }
    // Enclosure at the corners and the centre of a bounded region.
    if vars.iter().all(|x| x.is_common_interval()) {
        let corner = |k: usize| -> Vec<f64> {
            vars.iter()
                .enumerate()
                .map(|(i, x)| if k >> i & 1 == 0 { x.inf() } else { x.sup() })
                .collect()
        };
        let mid: Vec<f64> = vars.iter().map(|x| x.mid()).collect();
        for p in (0..8).map(corner).chain([mid]) {
            check_value_in(value, tape, &p).map_err(|e| TestCaseError::fail(e.to_string()))?;
        }
    }
    Ok(true)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn compiled_equals_the_interpreter(
        (ctx, root) in expression(),
        vars in prop::collection::vec(interval(), 3),
    ) {
        let tape = Tape::new(&ctx, &[root]).unwrap();
        if check(&tape, &vars)? {
            ANSWERED.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// The property test is not vacuous: most of its cases are answered by the compiled code
/// (run after it in the same binary when the tests run in one thread; on its own it runs
/// its own cases).
#[test]
fn most_random_cases_are_compiled() {
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let strategy = (expression(), prop::collection::vec(interval(), 3));
    let (mut answered, mut total) = (0, 0);
    for _ in 0..500 {
        let ((ctx, root), vars) = strategy.new_tree(&mut runner).unwrap().current();
        let tape = Tape::new(&ctx, &[root]).unwrap();
        total += 1;
        if check(&tape, &vars).unwrap() {
            answered += 1;
        }
    }
    assert!(answered * 2 > total, "{answered} of {total} answered");
}

fn tape_of(formula: &str) -> Tape {
    let mut ctx = Context::new();
    let f = crate::parse::parse(&mut ctx, formula, &[]).unwrap();
    Tape::new(&ctx, &[f]).unwrap()
}

fn iv(lo: f64, hi: f64) -> Interval<f64> {
    Interval::new(lo, hi).unwrap()
}

fn run(formula: &str, vars: &[Interval<f64>]) -> Option<(Interval<f64>, bool)> {
    let tape = tape_of(formula);
    let code = Code::compile(&tape, false).unwrap();
    let mut out = [[0.0; 2]; MAX_OUTPUTS];
    let flags = code.run(&pairs(vars), &mut [], &mut out)?;
    Some((Interval::new_unchecked(out[0][0], out[0][1]), flags.partial))
}

#[test]
fn fixed_cases() {
    let x = |lo, hi| [iv(lo, hi), iv(0.0, 0.0), iv(0.0, 0.0)];
    // Tight sums and roots: one ulp wide where the result is inexact.
    let (v, _) = run("x + 0.2", &x(0.1, 0.1)).unwrap();
    let two =
        <Interval<f64> as crate::number::Number>::constant(&Constant::from_decimal("0.2").unwrap());
    assert_eq!(v, iv(0.1, 0.1) + two);
    let (v, partial) = run("sqrt(x)", &x(2.0, 2.0)).unwrap();
    assert_eq!(v.sup(), v.inf().next_up());
    assert!(v.contains(std::f64::consts::SQRT_2) && !partial);
    let (v, partial) = run("sqrt(x)", &x(-1.0, 4.0)).unwrap();
    assert_eq!((v, partial), (iv(0.0, 2.0), true));
    // A root of a negative interval, 0 · ∞: the interpreter decides.
    assert!(run("sqrt(x)", &x(-2.0, -1.0)).is_none());
    assert!(
        run(
            "x * y",
            &[iv(0.0, 0.0), iv(1.0, f64::INFINITY), iv(0.0, 0.0)]
        )
        .is_none()
    );
    // The same where a `min`, `max` or absolute value would drop the NaN, traced or not.
    let unbounded = [iv(0.0, 1.0), iv(1.0, f64::INFINITY), iv(0.0, 0.0)];
    for formula in ["min(sqrt(x), 1)", "max(sqrt(x), 1) + y"] {
        assert!(run(formula, &x(-2.0, -1.0)).is_none(), "{formula}");
        let code = Code::compile(&tape_of(formula), true).unwrap();
        let mut out = [[0.0; 2]; MAX_OUTPUTS];
        let mut bytes = vec![0u8; 1];
        assert!(
            code.run(&pairs(&x(-2.0, -1.0)), &mut bytes, &mut out)
                .is_none()
        );
    }
    assert!(run("max(x * y, 2)", &unbounded).is_none());
    assert!(run("min(abs(x * y), 2)", &unbounded).is_none());
    // An empty variable never reaches a code: the evaluator of a tape compiled at once
    // answers with the interpreter.
    let tape = tape_of("max(abs(x), 1)");
    tape.expect_reuse();
    let mut ev = Evaluator::<Interval<f64>>::new(&tape);
    let empty = [Interval::EMPTY, iv(0.0, 0.0), iv(0.0, 0.0)];
    assert!(ev.eval(&empty).unwrap().is_empty());
    assert_eq!(ev.eval(&x(-2.0, 0.5)).unwrap(), iv(1.0, 2.0));
    // Squares and absolute values across 0; products by sign.
    assert_eq!(run("sqr(x)", &x(-3.0, 2.0)).unwrap().0, iv(0.0, 9.0));
    assert_eq!(run("abs(x)", &x(-3.0, 2.0)).unwrap().0, iv(0.0, 3.0));
    assert_eq!(run("abs(x)", &x(-3.0, -2.0)).unwrap().0, iv(2.0, 3.0));
    let xy = [iv(-2.0, 3.0), iv(-5.0, 4.0), iv(0.0, 0.0)];
    assert_eq!(run("x * y", &xy).unwrap().0, iv(-15.0, 12.0));
    assert_eq!(run("x - y", &xy).unwrap().0, iv(-6.0, 8.0));
    assert_eq!(run("min(x, y)", &xy).unwrap().0, iv(-5.0, 3.0));
    assert_eq!(run("max(x, y)", &xy).unwrap().0, iv(-2.0, 4.0));
    // `not`: 1 at 0 only; a jump where 0 is inside.
    assert_eq!(run("not(x)", &x(0.0, 0.0)).unwrap().0, iv(1.0, 1.0));
    assert_eq!(run("not(x)", &x(-1.0, 2.0)).unwrap().0, iv(0.0, 1.0));
    assert_eq!(run("not(x)", &x(1.0, 2.0)).unwrap().0, iv(0.0, 0.0));
    let jump = tape_of("not(x)");
    let code = Code::compile(&jump, false).unwrap();
    let mut out = [[0.0; 2]; MAX_OUTPUTS];
    let flags = code.run(&pairs(&x(-1.0, 2.0)), &mut [], &mut out).unwrap();
    assert!(flags.jump && !flags.partial);
    let flags = code.run(&pairs(&x(0.0, 0.0)), &mut [], &mut out).unwrap();
    assert!(!flags.jump);
    // Overflow rounds outward.
    let (v, _) = run("x + x", &x(f64::MAX, f64::MAX)).unwrap();
    assert_eq!(v, Interval::new_unchecked(f64::MAX, f64::INFINITY));
}

#[test]
fn choices_are_recorded() {
    let tape = tape_of("max(min(x, y), z)");
    let code = Code::compile(&tape, true).unwrap();
    let vars = [iv(0.0, 1.0), iv(2.0, 3.0), iv(5.0, 6.0)];
    let mut bytes = vec![9; tape.choice_count()];
    code.run(&pairs(&vars), &mut bytes, &mut [[0.0; 2]; MAX_OUTPUTS])
        .unwrap();
    let mut trace = Vec::new();
    super::choices_into(&bytes, &mut trace);
    assert_eq!(trace, [Choice::Left, Choice::Right]);
}

#[test]
fn rounding_mode_is_restored() {
    let tape = tape_of("x + y");
    let code = Code::compile(&tape, false).unwrap();
    code.run(
        &pairs(&[iv(0.1, 0.2), iv(0.3, 0.4), iv(0.0, 0.0)]),
        &mut [],
        &mut [[0.0; 2]; MAX_OUTPUTS],
    )
    .unwrap();
    // Under upward rounding the sum would be the next double above 1.
    let one = std::hint::black_box(1.0f64);
    assert_eq!(one + std::hint::black_box(1e-17), 1.0);
}

#[test]
fn evaluators_switch_to_the_code_with_the_same_results() {
    let tape = tape_of("max(sqrt(sqr(x) + sqr(y)) - 1, abs(z) - 0.5) * 0.3");
    let vars = [iv(-0.5, 0.7), iv(0.2, 0.9), iv(-0.1, 0.4)];
    let mut ev = Evaluator::<Interval<f64>>::new(&tape);
    let first = ev.eval(&vars).unwrap();
    let mut first_trace = Vec::new();
    ev.eval_traced(&vars, &mut first_trace).unwrap();
    for _ in 0..3 * super::COMPILE_AFTER {
        assert_eq!(ev.eval(&vars).unwrap(), first);
        let mut trace = Vec::new();
        assert_eq!(ev.eval_traced(&vars, &mut trace).unwrap(), first);
        assert_eq!(trace, first_trace);
    }
    assert!(tape.code(false).is_some() && tape.code(true).is_some());
}

/// A tape equal to one compiled before, made on its own (another `Arc`), takes the shared
/// code at its first evaluation, with the interpreter's results; a tape of another formula
/// does not.
#[test]
fn an_equal_tape_takes_the_shared_code_at_once() {
    let text = "min(sqrt(sqr(x - 0.25) + sqr(y)) - 0.75, z + 0.125) * 0.5";
    let vars = [iv(-0.5, 0.25), iv(0.5, 0.625), iv(-0.25, 0.5)];
    let first = tape_of(text);
    let mut ev = Evaluator::<Interval<f64>>::new(&first);
    for _ in 0..=super::COMPILE_AFTER {
        ev.eval(&vars).unwrap();
    }
    assert!(
        first.code(false).is_some(),
        "compiled after its evaluations"
    );
    let again = tape_of(text);
    assert!(!again.ptr_eq(&first) && again == first);
    // (Asking for the code counts an evaluation: it is asked after the first one.)
    let mut ev = Evaluator::<Interval<f64>>::new(&again);
    let value = ev.eval(&vars).unwrap();
    assert!(
        again.code(false).is_some(),
        "the shared code at the first evaluation"
    );
    assert_eq!(
        value,
        Evaluator::<Interval<f64>>::new(&first).eval(&vars).unwrap()
    );
    let other = tape_of("min(sqrt(sqr(x - 0.25) + sqr(y)) - 0.75, z + 0.25) * 0.5");
    Evaluator::<Interval<f64>>::new(&other).eval(&vars).unwrap();
    assert!(
        other.code(false).is_none(),
        "another formula is counted as before"
    );
}

/// A tape said to be reused is compiled at its first evaluation, plain and traced, with
/// the interpreter's results and choices; one not said to be is interpreted first.
#[test]
fn a_tape_expected_to_be_reused_is_compiled_at_once() {
    // Formulas of this test only, so that no other test's code is shared with them.
    let text = "max(min(sqrt(sqr(x) + sqr(y)) - 0.625, z - 0.375), 0.125 - z) * 0.75";
    let vars = [iv(-0.5, 0.25), iv(0.125, 0.5), iv(0.5, 0.75)];
    // The interpreter's results: a tape of the formula evaluated twice is not compiled.
    let interpreted = tape_of(text);
    let mut ev = Evaluator::<Interval<f64>>::new(&interpreted);
    let want = ev.eval(&vars).unwrap();
    let mut want_trace = Vec::new();
    ev.eval_traced(&vars, &mut want_trace).unwrap();
    assert!(interpreted.code(false).is_none() && interpreted.code(true).is_none());
    assert!(want_trace.contains(&Choice::Left) || want_trace.contains(&Choice::Right));

    let hot = tape_of(text);
    hot.expect_reuse();
    let mut ev = Evaluator::<Interval<f64>>::new(&hot);
    assert_eq!(ev.eval(&vars).unwrap(), want);
    assert!(
        hot.code(false).is_some(),
        "compiled at the first evaluation"
    );
    let mut trace = Vec::new();
    assert_eq!(ev.eval_traced(&vars, &mut trace).unwrap(), want);
    assert!(hot.code(true).is_some(), "the traced code too");
    assert_eq!(trace, want_trace);

    let cold = tape_of("max(min(sqrt(sqr(x) + sqr(y)) - 0.625, z - 0.375), 0.125 - z) * 0.25");
    Evaluator::<Interval<f64>>::new(&cold).eval(&vars).unwrap();
    assert!(cold.code(false).is_none(), "interpreted first");
}

/// Once a tape has traced code, its plain evaluations run that code (no second code is
/// compiled for the tape), with the interpreter's values and flags: plain, continuity-
/// checked and all-outputs evaluations, over boxes where the formula is defined and
/// where a square root's argument reaches below 0.
#[test]
fn traced_code_serves_plain_evaluations() {
    // Formulas of this test only, so that no other test's code is shared with them.
    let text = "min(sqrt(x * y + 0.375) - 0.625, max(z - 0.875, sqr(x) - 0.25))";
    let boxes = [
        [iv(0.25, 0.5), iv(0.5, 1.0), iv(-0.5, 0.25)],
        [iv(-1.0, 0.5), iv(0.5, 1.5), iv(0.0, 1.0)],
        [iv(-2.0, -1.5), iv(1.0, 2.0), iv(-1.0, 1.0)],
    ];
    let hot = tape_of(text);
    hot.expect_reuse();
    let mut ev = Evaluator::<Interval<f64>>::new(&hot);
    let mut trace = Vec::new();
    ev.eval_traced(&boxes[0], &mut trace).unwrap();
    assert_eq!(hot.code_kinds(), (false, true), "traced code first");
    for vars in &boxes {
        // The interpreter's: a tape of its own per box, evaluated fewer times than
        // compiling takes.
        let interpreted = tape_of(text);
        let mut want = Evaluator::<Interval<f64>>::new(&interpreted);
        assert_eq!(ev.eval(vars).unwrap(), want.eval(vars).unwrap());
        assert_eq!(
            ev.eval_continuous(vars).unwrap(),
            want.eval_continuous(vars).unwrap()
        );
        let (mut got, mut expected) = ([Interval::EMPTY; 1], [Interval::EMPTY; 1]);
        ev.eval_outputs(vars, &mut got).unwrap();
        want.eval_outputs(vars, &mut expected).unwrap();
        assert_eq!(got, expected);
        assert_eq!(interpreted.code_kinds(), (false, false), "interpreted");
    }
    assert_eq!(hot.code_kinds(), (false, true), "no plain code compiled");
}

/// A tape of several outputs (a formula and its gradient): every output compiled, each
/// the interpreter's, through `eval_outputs` once the tape is compiled.
#[test]
fn every_output_is_compiled() {
    let mut ctx = Context::new();
    let f = crate::parse::parse(&mut ctx, "max(x*y - z, sqr(x) + sqr(y) - 1)", &[]).unwrap();
    let [fx, fy, fz] = ctx.gradient(f);
    let tape = Tape::new(&ctx, &[f, fx, fy, fz]).unwrap();
    let vars = [iv(0.5, 0.75), iv(-0.25, 0.5), iv(0.1, 0.2)];
    let mut ev = Evaluator::<Interval<f64>>::new(&tape);
    let mut first = [Interval::EMPTY; 4];
    ev.eval_outputs(&vars, &mut first).unwrap();
    let code = Code::compile(&tape, false).expect("supported operations");
    let mut out = [[0.0; 2]; MAX_OUTPUTS];
    code.run(&pairs(&vars), &mut [], &mut out).unwrap();
    for (want, got) in first.iter().zip(out) {
        assert!(same(*want, got), "{want:?} against {got:?}");
    }
    for _ in 0..3 * super::COMPILE_AFTER {
        let mut again = [Interval::EMPTY; 4];
        ev.eval_outputs(&vars, &mut again).unwrap();
        for (a, b) in again.iter().zip(&first) {
            assert!(a.inf() == b.inf() && a.sup() == b.sup());
        }
    }
    assert!(tape.code(false).is_some());
}

#[test]
fn unsupported_operations_are_not_compiled() {
    assert!(Code::compile(&tape_of("sin(x)"), false).is_none());
    assert!(Code::compile(&tape_of("x / y"), true).is_none());
}

#[test]
fn this_machine_honours_the_rounding_mode() {
    assert!(super::rounding_honoured());
}
