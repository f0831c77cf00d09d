//! `overlap` against the defining conditions of IEEE 1788 Table 10.7 (exactly one state holds
//! for every pair), and the integer functions against their point values: for random
//! intervals of every kind (`f64` and `f32`), the result is exact — its bounds are the
//! function at the bounds, and every point's value lies inside.

mod common;

use common::{TestFloat, config, interval, point_seeds, points_in};
use interval_core::Interval;
use interval_core::Overlap;
use proptest::prelude::*;

/// The states whose defining conditions hold for `x`, `y`.
fn states<T: TestFloat>(x: Interval<T>, y: Interval<T>) -> Vec<Overlap> {
    use Overlap::*;
    let (Some((a, b)), Some((c, d))) = (x.bounds(), y.bounds()) else {
        return vec![match (x.is_empty(), y.is_empty()) {
            (true, true) => BothEmpty,
            (true, false) => FirstEmpty,
            _ => SecondEmpty,
        }];
    };
    let conditions = [
        (Before, b < c),
        (Meets, a < b && b == c && c < d),
        (Overlaps, a < c && c < b && b < d),
        (Starts, a == c && b < d),
        (ContainedBy, c < a && b < d),
        (Finishes, c < a && b == d),
        (Equals, a == c && b == d),
        (FinishedBy, a < c && b == d),
        (Contains, a < c && d < b),
        (StartedBy, a == c && d < b),
        (OverlappedBy, c < a && a < d && d < b),
        (MetBy, c < d && a == d && a < b),
        (After, d < a),
    ];
    conditions
        .iter()
        .filter(|(_, c)| *c)
        .map(|(s, _)| *s)
        .collect()
}

fn check_overlap<T: TestFloat>(x: Interval<T>, y: Interval<T>) -> Result<(), TestCaseError> {
    let holds = states(x, y);
    prop_assert_eq!(holds.len(), 1, "{:?} {:?}: states {:?}", x, y, holds);
    prop_assert_eq!(x.overlap(y), holds[0]);
    Ok(())
}

/// An integer function: its name, the interval version and the point version.
type IntegerFn<T> = (&'static str, fn(Interval<T>) -> Interval<T>, fn(f64) -> f64);

fn check_integer<T: TestFloat>(x: Interval<T>, seeds: &[(T, f64)]) -> Result<(), TestCaseError> {
    let fns: [IntegerFn<T>; 6] = [
        ("floor", Interval::floor, f64::floor),
        ("ceil", Interval::ceil, f64::ceil),
        ("trunc", Interval::trunc, f64::trunc),
        (
            "round_ties_to_even",
            Interval::round_ties_to_even,
            f64::round_ties_even,
        ),
        (
            "round_ties_to_away",
            Interval::round_ties_to_away,
            f64::round,
        ),
        ("sign", Interval::sign, |v: f64| {
            if v == 0.0 { 0.0 } else { v.signum() }
        }),
    ];
    for (name, f, point) in fns {
        let got = f(x);
        let Some((lo, hi)) = x.bounds() else {
            prop_assert!(got.is_empty());
            continue;
        };
        let at = |v: T| T::from_f64_rn(point(v.to_f64()));
        let want_lo = if lo.is_finite() {
            at(lo)
        } else if name == "sign" {
            -T::ONE
        } else {
            lo
        };
        let want_hi = if hi.is_finite() {
            at(hi)
        } else if name == "sign" {
            T::ONE
        } else {
            hi
        };
        prop_assert!(
            got.inf() == want_lo && got.sup() == want_hi,
            "{name}({x:?}) = {got:?}"
        );
        for p in points_in(x, seeds) {
            prop_assert!(got.contains(at(p)), "{name}({x:?}) = {got:?} misses {p:?}");
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(2000))]

    #[test]
    fn overlap_f64(x in interval::<f64>(), y in interval::<f64>()) {
        check_overlap(x, y)?;
    }

    #[test]
    fn overlap_shared_bounds(a in -3i32..3, b in -3i32..3, c in -3i32..3, d in -3i32..3) {
        // Small integers make equal bounds (meets, starts, finishes, ...) frequent.
        let iv = |p: i32, q: i32| Interval::new(f64::from(p.min(q)), f64::from(p.max(q))).unwrap();
        check_overlap(iv(a, b), iv(c, d))?;
    }

    #[test]
    fn overlap_f32(x in interval::<f32>(), y in interval::<f32>()) {
        check_overlap(x, y)?;
    }

    #[test]
    fn integer_functions_f64(x in interval::<f64>(), s in point_seeds::<f64>(4)) {
        check_integer(x, &s)?;
    }

    #[test]
    fn integer_functions_f32(x in interval::<f32>(), s in point_seeds::<f32>(4)) {
        check_integer(x, &s)?;
    }
}
