//! The public proptest strategies (`proptest` feature) and soundness checks: the strategies
//! produce valid values of every class, points lie in their intervals, and the checks accept
//! sound and reject unsound results. Run with
//! `cargo test -p interval-core --features proptest --test strategies`.

#![cfg(feature = "proptest")]

use interval_core::modal::Outer;
use interval_core::testing::strategy::{
    bounded_interval, dec_interval, finite, interval, interval_and_point, modal, point_in,
};
use interval_core::testing::{check_encloses, check_encloses_bracket};
use interval_core::{Float, Interval, Modal};
use proptest::prelude::*;

fn valid<T: Float>(x: Interval<T>) -> bool {
    match x.bounds() {
        None => true,
        Some((lo, hi)) => lo <= hi && lo != T::INFINITY && hi != T::NEG_INFINITY,
    }
}

proptest! {
    #[test]
    fn intervals_are_valid(x in interval::<f64>(), y in interval::<f32>(), b in bounded_interval::<f64>()) {
        prop_assert!(valid(x) && valid(y));
        prop_assert!(b.is_common_interval());
    }

    #[test]
    fn points_lie_inside((x, p) in interval_and_point::<f32>()) {
        prop_assert!(x.contains(p));
    }

    #[test]
    fn point_in_a_given_interval(p in point_in(Interval::new(-1.0, f64::INFINITY).unwrap())) {
        prop_assert!(p >= -1.0 && p.is_finite());
    }

    #[test]
    fn finite_values(v in finite::<f32>()) {
        prop_assert!(v.is_finite());
    }

    #[test]
    fn decorated_and_modal(d in dec_interval::<f64>(), m in modal::<f64, Outer>()) {
        prop_assert!(valid(d.interval()));
        let _: Modal<f64> = m;
    }

    #[test]
    fn sound_results_pass((x, p) in interval_and_point::<f64>()) {
        prop_assert!(check_encloses((x + x) - x, p).is_ok());
        prop_assert!(check_encloses_bracket(x * x, p.mul_down(p), p.mul_up(p)).is_ok());
    }
}

/// The function under test of the README example: an interval extension of x² + x.
fn f(x: Interval<f64>) -> Interval<f64> {
    x.sqr() + x
}

proptest! {
    /// The README's example test, verbatim.
    #[test]
    fn readme_example((x, p) in interval_and_point::<f64>()) {
        // A reference bracket of f(p): p² + p rounded down and up.
        let (lo, hi) = (p.fma_down(p, p), p.fma_up(p, p));
        check_encloses_bracket(f(x), lo, hi).map_err(|e| TestCaseError::fail(e.to_string()))?;
    }
}

#[test]
fn edge_cases_are_drawn() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let (mut empty, mut unbounded, mut subnormal, mut huge) = (false, false, false, false);
    for _ in 0..4000 {
        let x = interval::<f64>().new_tree(&mut runner).unwrap().current();
        empty |= x.is_empty();
        unbounded |= !x.is_empty() && !x.is_common_interval();
        if let Some((lo, hi)) = x.bounds() {
            subnormal |= lo != 0.0 && lo.abs() < f64::MIN_POSITIVE;
            huge |= hi.is_finite() && hi > 1e300;
        }
    }
    assert!(empty && unbounded && subnormal && huge);
}

#[test]
fn unsound_results_fail() {
    let x = Interval::new(1.0, 2.0).unwrap();
    assert!(check_encloses(x, 2.0f64.next_up()).is_err());
    assert!(check_encloses_bracket(x, 1.5, 2.5).is_err());
}
