//! Exact reductions (`sum`, `dot`, `sum_sqr`, `sum_abs`) and interval literals against exact
//! rational arithmetic (`rug::Rational`): every result must be the exact value rounded toward
//! −∞ and toward +∞ (the neighbour test `r ≤ e < next_up(r)`), for `f64` and `f32`, with
//! inputs of every class (signed zeros, subnormals, huge values, cancelling terms).

mod common;

use common::{TestFloat, check_tight, config, finite, is_round_down, is_round_up, rat};
use interval_core::Interval;
use interval_core::interval::reduction;
use proptest::prelude::*;
use rug::ops::Pow;
use rug::{Integer, Rational};

const CASES: u32 = 1500;

fn check_rounded<T: TestFloat>(
    name: &str,
    (down, up): (T, T),
    exact: &Rational,
) -> Result<(), TestCaseError> {
    prop_assert!(
        is_round_down(down, exact),
        "{name}: down {down:?} vs exact {exact}"
    );
    prop_assert!(is_round_up(up, exact), "{name}: up {up:?} vs exact {exact}");
    Ok(())
}

/// Vectors with cancellation: random values followed by the negations of some of them.
fn vector<T: TestFloat>() -> BoxedStrategy<Vec<T>> {
    (
        proptest::collection::vec(finite::<T>(), 0..12),
        proptest::collection::vec(any::<bool>(), 12),
    )
        .prop_map(|(mut v, neg)| {
            let extra: Vec<T> = v
                .iter()
                .zip(&neg)
                .filter(|(_, n)| **n)
                .map(|(x, _)| -*x)
                .collect();
            v.extend(extra);
            v
        })
        .boxed()
}

fn check_reductions<T: TestFloat>(xs: &[T], ys: &[T]) -> Result<(), TestCaseError> {
    let sum: Rational = xs.iter().map(|&x| rat(x)).sum();
    check_rounded("sum", reduction::sum(xs), &sum)?;
    let abs: Rational = xs.iter().map(|&x| rat(x).abs()).sum();
    check_rounded("sum_abs", reduction::sum_abs(xs), &abs)?;
    let sqr: Rational = xs.iter().map(|&x| rat(x) * rat(x)).sum();
    check_rounded("sum_sqr", reduction::sum_sqr(xs), &sqr)?;
    let n = xs.len().min(ys.len());
    let dot: Rational = xs[..n]
        .iter()
        .zip(&ys[..n])
        .map(|(&x, &y)| rat(x) * rat(y))
        .sum();
    check_rounded("dot", reduction::dot(&xs[..n], &ys[..n]).unwrap(), &dot)?;
    prop_assert!(xs.len() == ys.len() || reduction::dot(xs, ys).is_err());
    Ok(())
}

/// A decimal literal: digits, a decimal point position and a power of ten, with its exact
/// value.
fn decimal() -> impl Strategy<Value = (String, Rational)> {
    (
        any::<bool>(),
        proptest::collection::vec(0u8..10, 1..30),
        0usize..30,
        prop_oneof![3 => -30i32..30, 1 => -400i32..400],
    )
        .prop_map(|(neg, digits, point, exp)| {
            let int: String = digits.iter().map(|d| char::from(b'0' + d)).collect();
            let point = point.min(digits.len());
            let text = format!(
                "{}{}.{}e{}",
                if neg { "-" } else { "" },
                &int[..digits.len() - point],
                &int[digits.len() - point..],
                exp
            );
            let m = Integer::from_str_radix(&int, 10).unwrap();
            let k = i64::from(exp) - point as i64;
            let ten = Integer::from(10).pow(k.unsigned_abs() as u32);
            let mut q = if k >= 0 {
                Rational::from(m * ten)
            } else {
                Rational::from((m, ten))
            };
            if neg {
                q = -q;
            }
            (text, q)
        })
}

fn check_literal<T: TestFloat>(text: &str, q: &Rational) -> Result<(), TestCaseError> {
    let x: Interval<T> = Interval::parse(&format!("[{text}]")).unwrap();
    check_tight(x, Some((q.clone(), q.clone())))
}

fn check_pair<T: TestFloat>(
    a: &(String, Rational),
    b: &(String, Rational),
) -> Result<(), TestCaseError> {
    let (lo, hi) = if a.1 <= b.1 { (a, b) } else { (b, a) };
    let x: Interval<T> = format!("[{}, {}]", lo.0, hi.0).parse().unwrap();
    check_tight(x, Some((lo.1.clone(), hi.1.clone())))
}

proptest! {
    #![proptest_config(config(CASES))]

    #[test]
    fn reductions_f64(xs in vector::<f64>(), ys in vector::<f64>()) {
        check_reductions(&xs, &ys)?;
    }

    #[test]
    fn reductions_f32(xs in vector::<f32>(), ys in vector::<f32>()) {
        check_reductions(&xs, &ys)?;
    }

    #[test]
    fn literals_f64((text, q) in decimal()) {
        check_literal::<f64>(&text, &q)?;
    }

    #[test]
    fn literals_f32((text, q) in decimal()) {
        check_literal::<f32>(&text, &q)?;
    }

    #[test]
    fn literal_pairs(a in decimal(), b in decimal()) {
        check_pair::<f64>(&a, &b)?;
        check_pair::<f32>(&a, &b)?;
    }

    #[test]
    fn shortest_round_trip_is_a_point(x in finite::<f64>()) {
        // Rust's shortest round-trip text of a double denotes a decimal within half an ulp of
        // it (rounding to it), so its enclosure is x itself or a one-ulp interval holding x.
        let p: Interval<f64> = format!("[{x:e}]").parse().unwrap();
        prop_assert!(p.contains(x), "[{x:e}] read as {p:?}");
        prop_assert!(p.sup() <= p.inf().next_up());
    }
}
