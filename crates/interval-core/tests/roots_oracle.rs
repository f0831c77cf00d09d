//! `rootn` and `hypot` of `Interval<f64>` and `Interval<f32>` against MPFR (through `rug`):
//! enclosure of the exact value at random points (MPFR at 400 bits, rounded both ways, compared
//! exactly) and tightness (the bounds equal the directed roundings of the exact extremes:
//! bit for bit for `rootn` with `1 ≤ n ≤ 64` and for `hypot`; within 50 ulps for `n > 64`).

mod common;

use common::{TestFloat, config, interval, interval_pair, point_seeds, points_in, round_mpfr};
use interval_core::Interval;
use proptest::prelude::*;
use rug::Float as Big;
use rug::float::Round;

const PREC: u32 = 400;
const CASES: u32 = 1500;

fn root_big(x: f64, k: u32, round: Round) -> Big {
    let mut b = Big::with_val(PREC, x);
    b.root_round(k, round);
    b
}

fn hypot_big(x: f64, y: f64, round: Round) -> Big {
    let mut b = Big::with_val(PREC, x);
    b.hypot_round(&Big::with_val(PREC, y), round);
    b
}

/// `lo ≤ [down, up] ≤ hi`, exactly.
fn encloses<T: TestFloat>(got: Interval<T>, down: &Big, up: &Big) -> bool {
    !got.is_empty() && *down >= got.inf().to_f64() && *up <= got.sup().to_f64()
}

/// Number of ulps from `a` to `b` (both of `T`, `a ≤ b`), capped.
fn ulps<T: TestFloat>(a: T, b: T) -> u32 {
    let mut n = 0;
    let mut v = a;
    while v < b && n < 1000 {
        v = v.next_up();
        n += 1;
    }
    n
}

fn check_rootn<T: TestFloat>(
    x: Interval<T>,
    n: u32,
    seeds: &[(T, f64)],
) -> Result<(), TestCaseError> {
    let got = x.rootn(n as i32);
    let dom = if n.is_multiple_of(2) {
        x.intersection(Interval::new(T::ZERO, T::INFINITY).unwrap())
    } else {
        x
    };
    let Some((a, b)) = dom.bounds() else {
        prop_assert!(
            got.is_empty(),
            "rootn({x:?}, {n}) = {got:?}, expected empty"
        );
        return Ok(());
    };
    for p in points_in(dom, seeds) {
        let (d, u) = (
            root_big(p.to_f64(), n, Round::Down),
            root_big(p.to_f64(), n, Round::Up),
        );
        prop_assert!(
            encloses(got, &d, &u),
            "rootn({x:?}, {n}) = {got:?} misses the root of {p:?}"
        );
    }
    let lo: T = round_mpfr(&root_big(a.to_f64(), n, Round::Down), true);
    let hi: T = round_mpfr(&root_big(b.to_f64(), n, Round::Up), false);
    if n <= 64 {
        prop_assert!(
            got.inf() == lo && got.sup() == hi,
            "rootn({x:?}, {n}) = {got:?}, tight [{lo:?}, {hi:?}]"
        );
    } else {
        prop_assert!(got.inf() <= lo && got.sup() >= hi);
        prop_assert!(ulps(got.inf(), lo) <= 50 && ulps(hi, got.sup()) <= 50);
    }
    Ok(())
}

fn check_hypot<T: TestFloat>(
    x: Interval<T>,
    y: Interval<T>,
    sx: &[(T, f64)],
    sy: &[(T, f64)],
) -> Result<(), TestCaseError> {
    let got = x.hypot(y);
    if x.is_empty() || y.is_empty() {
        prop_assert!(got.is_empty());
        return Ok(());
    }
    for p in points_in(x, sx) {
        for q in points_in(y, sy) {
            let (d, u) = (
                hypot_big(p.to_f64(), q.to_f64(), Round::Down),
                hypot_big(p.to_f64(), q.to_f64(), Round::Up),
            );
            prop_assert!(
                encloses(got, &d, &u),
                "hypot({x:?}, {y:?}) = {got:?} at ({p:?}, {q:?})"
            );
        }
    }
    let lo: T = round_mpfr(
        &hypot_big(x.mig().to_f64(), y.mig().to_f64(), Round::Down),
        true,
    );
    let hi: T = round_mpfr(
        &hypot_big(x.mag().to_f64(), y.mag().to_f64(), Round::Up),
        false,
    );
    prop_assert!(
        got.inf() == lo && got.sup() == hi,
        "hypot({x:?}, {y:?}) = {got:?}, tight [{lo:?}, {hi:?}]"
    );
    Ok(())
}

fn root_index() -> impl Strategy<Value = u32> {
    prop_oneof![4 => 1u32..=8, 2 => 9u32..=64, 1 => 65u32..=300]
}

proptest! {
    #![proptest_config(config(CASES))]

    #[test]
    fn rootn_f64(x in interval::<f64>(), n in root_index(), s in point_seeds::<f64>(3)) {
        check_rootn(x, n, &s)?;
    }

    #[test]
    fn rootn_f32(x in interval::<f32>(), n in root_index(), s in point_seeds::<f32>(3)) {
        check_rootn(x, n, &s)?;
    }

    #[test]
    fn hypot_f64((x, y) in interval_pair::<f64>(), sx in point_seeds::<f64>(2), sy in point_seeds::<f64>(2)) {
        check_hypot(x, y, &sx, &sy)?;
    }

    #[test]
    fn hypot_f32((x, y) in interval_pair::<f32>(), sx in point_seeds::<f32>(2), sy in point_seeds::<f32>(2)) {
        check_hypot(x, y, &sx, &sy)?;
    }
}

/// `rootn` with `n < 0` (the reciprocal of the tight root, rounded outward): encloses, and
/// each bound within 2 ulps of the tight one.
fn check_rootn_negative<T: TestFloat>(x: Interval<T>, k: u32) -> Result<(), TestCaseError> {
    let got = x.rootn(-(k as i32));
    let Some((a, b)) = x.bounds() else {
        prop_assert!(got.is_empty());
        return Ok(());
    };
    // Keep to positive boxes, where x^(-1/k) is decreasing and finite.
    if !(a > T::ZERO && b.is_finite()) {
        return Ok(());
    }
    let inv = |v: f64, r: Round| {
        let mut t = root_big(
            v,
            k,
            if r == Round::Down {
                Round::Up
            } else {
                Round::Down
            },
        );
        t.recip_round(r);
        t
    };
    let lo: T = round_mpfr(&inv(b.to_f64(), Round::Down), true);
    let hi: T = round_mpfr(&inv(a.to_f64(), Round::Up), false);
    prop_assert!(
        got.inf() <= lo && got.sup() >= hi,
        "rootn({x:?}, -{k}) = {got:?}"
    );
    prop_assert!(
        ulps(got.inf(), lo) <= 2 && ulps(hi, got.sup()) <= 2,
        "rootn({x:?}, -{k}) = {got:?} vs [{lo:?}, {hi:?}]"
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(CASES))]

    #[test]
    fn rootn_negative_f64(x in interval::<f64>(), k in 1u32..=20) {
        check_rootn_negative(x, k)?;
    }

    #[test]
    fn rootn_negative_f32(x in interval::<f32>(), k in 1u32..=20) {
        check_rootn_negative(x, k)?;
    }
}

#[test]
fn negative_index_encloses() {
    let x = Interval::new(2.0, 8.0).unwrap();
    let r = x.rootn(-3);
    assert!(r.contains(0.5) && r.contains(2f64.powf(-1.0 / 3.0)));
    assert!(r.inf() >= 0.5f64.next_down() && r.sup() <= 0.7937005259840999);
}
