//! The public proptest strategies (feature `proptest`) and the soundness check: random
//! expressions over every operation are sound on random regions in `f64` and `f32` (the
//! example of the crate's README), the options keep their promises, and the formulas
//! read back.
#![cfg(feature = "proptest")]

use implicit_expr::testing::strategy::{
    ExpressionOptions, expression, expression_with, region, region_and_point,
};
use implicit_expr::testing::{CheckError, Verdict, check_sound, check_value_in};
use implicit_expr::{Context, Evaluator, Node, Tape, parse::parse};
use interval_core::Interval;
use proptest::prelude::*;

mod common;
use common::config;

/// Fails on an unsound verdict only; the others (undefined at the point, unresolved) pass.
fn sound<T: interval_core::Float>(
    tape: &Tape,
    region: &[Interval<T>],
    point: &[T],
) -> Result<Verdict, TestCaseError> {
    match check_sound(tape, region, point) {
        Err(e @ CheckError::Unsound { .. }) => Err(TestCaseError::fail(e.to_string())),
        Err(e) => Err(TestCaseError::fail(format!("malformed case: {e}"))),
        Ok(v) => Ok(v),
    }
}

/// The code under test in the README's example: the tape pruned to the region, evaluated
/// over it.
fn my_enclosure(tape: &Tape, region: &[Interval<f64>]) -> Interval<f64> {
    let mut full = Evaluator::<Interval<f64>>::new(tape);
    let pruned = full.pruned(region, &mut Vec::new()).unwrap();
    Evaluator::<Interval<f64>>::new(&pruned)
        .eval(region)
        .unwrap()
}

proptest! {
    #![proptest_config(config(512))]

    /// The README's example.
    #[test]
    fn readme_example(e in expression(), (region, point) in region_and_point::<f64>(3)) {
        let tape = e.tape();
        let value = my_enclosure(&tape, &region);
        if let Err(err @ CheckError::Unsound { .. }) = check_value_in(value, &tape, &point) {
            return Err(TestCaseError::fail(format!("{err} in {e:?}")));
        }
    }

    #[test]
    fn interval_values_are_sound(e in expression(), (region, point) in region_and_point::<f64>(3)) {
        let tape = e.tape();
        sound(&tape, &region, &point)?;
    }

    #[test]
    fn f32_interval_values_are_sound(e in expression(), (region, point) in region_and_point::<f32>(3)) {
        sound(&e.tape(), &region, &point)?;
    }

    /// Total, continuous expressions: the tape says so, and they are defined at every point.
    #[test]
    fn total_expressions_are_defined_everywhere(
        e in expression_with(ExpressionOptions::total_and_continuous()),
        (region, point) in region_and_point::<f64>(3),
    ) {
        let tape = e.tape();
        prop_assert!(tape.is_total_and_continuous(), "{e:?}");
        prop_assert_ne!(sound(&tape, &region, &point)?, Verdict::Undefined, "{:?}", e);
    }

    /// The formula text parses back to an expression with the same interval values where
    /// every constant is a double, and overlapping ones otherwise if the expression is
    /// defined everywhere (a folded inexact constant, `ln(0.1)`, prints as one decimal of
    /// its enclosure, which moves a partial operation's argument at the edge of its domain).
    #[test]
    fn formulas_read_back(e in expression(), r in region::<f64>(3)) {
        let mut ctx = Context::new();
        let again = parse(&mut ctx, &e.formula(), &[]).unwrap();
        let back = Tape::new(&ctx, &[again]).unwrap();
        let a = Evaluator::<Interval<f64>>::new(&e.tape()).eval(&r).unwrap();
        let b = Evaluator::<Interval<f64>>::new(&back).eval(&r).unwrap();
        let exact = e.context().reachable(&[e.root()]).iter().all(|&n| {
            !matches!(e.context().get(n), Node::Const(c) if c.lo() != c.hi())
        });
        if exact {
            prop_assert_eq!(a, b, "{:?}", e);
        } else if e.tape().is_total() {
            prop_assert!(a.is_empty() == b.is_empty() && (a.is_empty() || !a.intersection(b).is_empty()), "{a:?} against {b:?} in {e:?}");
        }
    }
}

/// The check catches an unsound value: an interval value narrowed by a few ulps below the
/// real value at a point, on expressions whose value there is known to lie inside.
#[test]
fn a_narrowed_value_is_caught() {
    let mut runner = proptest::test_runner::TestRunner::new(config(256));
    let caught = std::cell::Cell::new(0);
    runner
        .run(
            &(
                expression_with(ExpressionOptions::total_and_continuous()),
                region_and_point::<f64>(3),
            ),
            |(e, (_, point))| {
                let tape = e.tape();
                let at: Vec<Interval<f64>> = point
                    .iter()
                    .map(|&v| Interval::new(v, v).unwrap())
                    .collect();
                let v = Evaluator::<Interval<f64>>::new(&tape).eval(&at).unwrap();
                if let Some((lo, hi)) = v.bounds()
                    && lo.is_finite()
                    && hi.is_finite()
                    && lo.abs() > 1e-300
                {
                    // Entirely above the value's enclosure: never sound.
                    let wrong =
                        Interval::new(hi.next_up().next_up(), hi.next_up().next_up().next_up());
                    if let Ok(w) = wrong
                        && matches!(
                            check_value_in(w, &tape, &point),
                            Err(CheckError::Unsound { .. })
                        )
                    {
                        caught.set(caught.get() + 1);
                    }
                }
                Ok(())
            },
        )
        .unwrap();
    assert!(caught.get() > 100, "{} of 256", caught.get());
}
