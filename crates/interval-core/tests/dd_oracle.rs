//! Double-double intervals against exact rational arithmetic (`rug`): every bound on the
//! right side of the exact range (soundness) and within `2^-100` of it, relative
//! (tightness: the documented accuracy is a few units of `2^-104`), for `+ − ×`, `sqr`,
//! `/`, `sqrt`, `pown`; and the cancellation that `f64` cannot resolve.

use interval_core::{Dd, DdInterval, Interval};
use proptest::prelude::*;
use rug::Rational;

/// The exact value of a double-double.
fn q(x: Dd) -> Rational {
    Rational::from_f64(x.hi()).unwrap() + Rational::from_f64(x.lo()).unwrap()
}

/// A normalised double-double of magnitude `m·2^e` with a trailing part of either sign.
fn dd() -> impl Strategy<Value = Dd> {
    (
        any::<bool>(),
        1.0..2.0f64,
        -40..40i32,
        -0.5..0.5f64,
        prop::bool::weighted(0.1),
    )
        .prop_map(|(neg, m, e, frac, plain)| {
            let hi = if neg { -m } else { m } * 2f64.powi(e);
            let lo = if plain {
                0.0
            } else {
                frac * hi.abs() * f64::EPSILON
            };
            Dd::from_sum(hi, lo).unwrap()
        })
}

fn interval() -> impl Strategy<Value = DdInterval> {
    (dd(), dd()).prop_map(|(a, b)| {
        let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
        DdInterval::new(lo, hi).unwrap()
    })
}

/// Relative tightness allowed per bound.
fn slack(exact: &Rational, bits: i32) -> Rational {
    let tiny = Rational::from_f64(2f64.powi(-900)).unwrap();
    exact.clone().abs() * Rational::from_f64(2f64.powi(-bits)).unwrap() + tiny
}

/// `r` holds `[lo, hi]` (exact) and each bound is within `2^-bits` (relative) of it.
fn check(
    what: &str,
    r: DdInterval,
    lo: &Rational,
    hi: &Rational,
    bits: i32,
) -> Result<(), TestCaseError> {
    let (rl, rh) = r
        .bounds()
        .ok_or_else(|| TestCaseError::fail(format!("{what}: empty")))?;
    let (rl, rh) = (q(rl), q(rh));
    prop_assert!(
        &rl <= lo && hi <= &rh,
        "{what}: {r} does not hold [{}, {}]",
        lo.to_f64(),
        hi.to_f64()
    );
    prop_assert!(
        Rational::from(lo - &rl) <= slack(lo, bits),
        "{what}: lower bound {r} loose"
    );
    prop_assert!(
        Rational::from(&rh - hi) <= slack(hi, bits),
        "{what}: upper bound {r} loose"
    );
    Ok(())
}

fn corners(
    a: DdInterval,
    b: DdInterval,
    f: impl Fn(&Rational, &Rational) -> Rational,
) -> (Rational, Rational) {
    let (a0, a1) = a.bounds().unwrap();
    let (b0, b1) = b.bounds().unwrap();
    let v: Vec<Rational> = [(a0, b0), (a0, b1), (a1, b0), (a1, b1)]
        .iter()
        .map(|(x, y)| f(&q(*x), &q(*y)))
        .collect();
    let lo = v.iter().min().unwrap().clone();
    let hi = v.iter().max().unwrap().clone();
    (lo, hi)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn add_sub_mul_enclose_tightly(a in interval(), b in interval()) {
        let (lo, hi) = corners(a, b, |x, y| Rational::from(x + y));
        check("add", a + b, &lo, &hi, 100)?;
        let (lo, hi) = corners(a, b, |x, y| Rational::from(x - y));
        check("sub", a - b, &lo, &hi, 100)?;
        let (lo, hi) = corners(a, b, |x, y| Rational::from(x * y));
        check("mul", a * b, &lo, &hi, 100)?;
    }

    #[test]
    fn div_encloses_tightly(a in interval(), b in (dd(), dd()), negative in any::<bool>()) {
        // A divisor of one sign: between |b.0| and |b.1|, or their negatives.
        let abs = |x: Dd| if x.signum() < 0 { -x } else { x };
        let (p, r) = (abs(b.0), abs(b.1));
        let b = DdInterval::new(if p <= r { p } else { r }, if p <= r { r } else { p }).unwrap();
        let b = if negative { -b } else { b };
        let (b0, b1) = b.bounds().unwrap();
        prop_assume!(b0.signum() > 0 || b1.signum() < 0);
        let (lo, hi) = corners(a, b, |x, y| Rational::from(x / y));
        check("div", a / b, &lo, &hi, 100)?;
    }

    #[test]
    fn sqr_and_pown_enclose_tightly(a in interval(), n in -5..8i32) {
        let (a0, a1) = a.bounds().unwrap();
        let (x0, x1) = (q(a0), q(a1));
        let zero = Rational::new();
        let (lo, hi) = if x0 >= zero || x1 <= zero {
            let (p, r) = (Rational::from(&x0 * &x0), Rational::from(&x1 * &x1));
            if p <= r { (p, r) } else { (r, p) }
        } else {
            (zero.clone(), Rational::from(&x0 * &x0).max(Rational::from(&x1 * &x1)))
        };
        check("sqr", a.sqr(), &lo, &hi, 100)?;
        prop_assume!(n >= 0 || x0 > zero || x1 < zero);
        let pow = |x: &Rational| -> Rational {
            let p = Rational::from(rug::ops::Pow::pow(x, n.unsigned_abs()));
            if n < 0 { p.recip() } else { p }
        };
        let mut vals = vec![pow(&x0), pow(&x1)];
        if x0 < zero && x1 > zero {
            vals.push(pow(&zero));
        }
        let lo = vals.iter().min().unwrap().clone();
        let hi = vals.iter().max().unwrap().clone();
        // Each multiplication of pown adds a few units of 2^-104.
        check(&format!("pown {n}"), a.pown(n), &lo, &hi, 96)?;
    }

    #[test]
    fn sqrt_encloses_tightly(a in interval(), whole in any::<bool>()) {
        // Mostly non-negative arguments (|a|), sometimes one reaching below 0.
        let a = if whole { a } else { a.abs() };
        let (a0, a1) = a.bounds().unwrap();
        prop_assume!(a1.signum() > 0);
        let r = a.sqrt();
        let (r0, r1) = r.bounds().unwrap();
        let (s0, s1) = (q(r0), q(r1));
        let (x0, x1) = (q(a0).max(Rational::new()), q(a1));
        // s0 ≤ √x0 and s1 ≥ √x1, each within 2^-100 relative.
        prop_assert!(Rational::from(&s0 * &s0) <= x0 && s0 >= Rational::new(), "sqrt lower {r}");
        prop_assert!(Rational::from(&s1 * &s1) >= x1, "sqrt upper {r}");
        let grow = Rational::from(1) + Rational::from_f64(2f64.powi(-100)).unwrap();
        let shrink = Rational::from(1) - Rational::from_f64(2f64.powi(-100)).unwrap();
        let up0 = Rational::from(&s0 * &grow);
        prop_assert!(x0 == Rational::new() || Rational::from(&up0 * &up0) > x0, "sqrt lower {r} loose");
        let down1 = Rational::from(&s1 * &shrink);
        prop_assert!(Rational::from(&down1 * &down1) < x1, "sqrt upper {r} loose");
    }

    #[test]
    fn conversion_to_f64_is_outward(a in interval()) {
        let (a0, a1) = a.bounds().unwrap();
        let i = a.to_interval();
        prop_assert!(Rational::from_f64(i.inf()).unwrap() <= q(a0));
        prop_assert!(Rational::from_f64(i.sup()).unwrap() >= q(a1));
        prop_assert!(i.inf() == a0.to_f64_down() && i.sup() == a1.to_f64_up());
    }
}

#[test]
fn large_terms_that_cancel_are_resolved() {
    // (x + 1e6)² − 2e6·x − 1e12 = x² exactly; f64 intervals lose everything below about
    // 1e-4 to the rounding of the 1e12 terms, double-doubles keep x² to about 1e-17.
    for x in [0.1, 0.7, 1.0 / 3.0, 2.9] {
        let xi = Interval::new(x, x).unwrap();
        let c = |v: f64| Interval::new(v, v).unwrap();
        let plain = (xi + c(1e6)).sqr() - c(2e6) * xi - c(1e12);
        let d = DdInterval::from_interval(xi);
        let k = |v: f64| DdInterval::point(v);
        let dd = (d + k(1e6)).sqr() - k(2e6) * d - k(1e12);
        let exact = Rational::from_f64(x).unwrap().square();
        let (lo, hi) = dd.bounds().unwrap();
        assert!(q(lo) <= exact && exact <= q(hi), "{x}: {dd}");
        let width = (q(hi) - q(lo)).to_f64();
        assert!(width < 1e-17, "{x}: double-double width {width:e}");
        assert!(plain.wid() > 1e-6, "{x}: f64 width {:e}", plain.wid());
    }
}

#[test]
fn special_cases_take_the_f64_path_soundly() {
    let e = DdInterval::ENTIRE;
    let one = DdInterval::point(1.0);
    assert_eq!((one + e).to_interval(), Interval::ENTIRE);
    let around_zero = DdInterval::from_interval(Interval::new(-1.0, 2.0).unwrap());
    assert_eq!((one / around_zero).to_interval(), Interval::ENTIRE);
    assert!(
        DdInterval::from_interval(Interval::new(-2.0, -1.0).unwrap())
            .sqrt()
            .is_empty()
    );
    let huge = DdInterval::point(1e300);
    let p = (huge * huge).to_interval();
    assert!(p.sup() == f64::INFINITY && p.inf() == f64::MAX);
    assert!((DdInterval::EMPTY + one).is_empty());
    // Infinite bounds: powers take the f64 path, and keep their values.
    let half_line = DdInterval::from_interval(Interval::new(f64::NEG_INFINITY, 2.0).unwrap());
    let cube = half_line.pown(3).to_interval();
    assert!(
        cube.inf() == f64::NEG_INFINITY && cube.sup() == 8.0,
        "{cube:?}"
    );
    assert_eq!(half_line.pown(2).to_interval().sup(), f64::INFINITY);
}
