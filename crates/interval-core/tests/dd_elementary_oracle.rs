//! `exp`, `sin`, `cos`, `tan`, `asin`, `acos`, `atan`, `ln`, `log10` and `pow` of
//! double-double intervals against MPFR (`rug`, 400 bits with directed rounding): the exact
//! range inside every enclosure, each bound within the documented accuracy (`2^-90`
//! relative for `exp`, `2^-95` absolute for `sin`/`cos` and the inverse functions, `2^-90`
//! relative (at least absolute) for `tan`, `2^-88` absolute for `ln`/`log10`, `2^-80`
//! relative for `pow`), and the extremes of `sin`/`cos` found inside wider intervals.

use interval_core::{Dd, DdInterval, Interval};
use proptest::prelude::*;
use rug::float::Round;
use rug::{Float, Rational};

const PREC: u32 = 400;

/// The exact value of a double-double as a 400-bit float (exact: 2 × 53 bits).
fn big(x: Dd) -> Float {
    let mut f = Float::with_val(PREC, x.hi());
    f += x.lo();
    f
}

fn q(x: Dd) -> Rational {
    Rational::from_f64(x.hi()).unwrap() + Rational::from_f64(x.lo()).unwrap()
}

/// `f(x)` rounded down and up at 400 bits.
fn bracket(x: Dd, f: fn(&mut Float, Round) -> std::cmp::Ordering) -> (Rational, Rational) {
    let mut d = big(x);
    f(&mut d, Round::Down);
    let mut u = big(x);
    f(&mut u, Round::Up);
    (d.to_rational().unwrap(), u.to_rational().unwrap())
}

fn exp_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.exp_round(r)
}
fn sin_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.sin_round(r)
}
fn cos_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.cos_round(r)
}
fn tan_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.tan_round(r)
}
fn atan_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.atan_round(r)
}
fn asin_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.asin_round(r)
}
fn acos_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.acos_round(r)
}
fn ln_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.ln_round(r)
}
fn log10_r(f: &mut Float, r: Round) -> std::cmp::Ordering {
    f.log10_round(r)
}

/// A positive double-double `e^u`-ish: `m·2^e` with a trailing part.
fn positive() -> impl Strategy<Value = Dd> {
    (1.0..2.0f64, -800..800i32, -0.5..0.5f64).prop_map(|(m, e, frac)| {
        let hi = m * 2f64.powi(e);
        Dd::from_sum(hi, frac * hi * f64::EPSILON).unwrap()
    })
}

/// A double-double of magnitude up to `scale` with a trailing part.
fn dd(scale: f64) -> impl Strategy<Value = Dd> {
    (-1.0..1.0f64, -0.5..0.5f64).prop_map(move |(m, frac)| {
        let hi = m * scale;
        Dd::from_sum(hi, frac * hi.abs() * f64::EPSILON).unwrap()
    })
}

/// Checks that the point enclosure `r` of `f(x)` holds `[down, up]` and is within `tol` of it.
fn check_point(
    what: &str,
    r: DdInterval,
    (down, up): (Rational, Rational),
    tol: &Rational,
) -> Result<(), TestCaseError> {
    let (lo, hi) = r
        .bounds()
        .ok_or_else(|| TestCaseError::fail(format!("{what}: empty")))?;
    let (lo, hi) = (q(lo), q(hi));
    prop_assert!(lo <= down && up <= hi, "{what}: {r} misses the exact value");
    prop_assert!(
        Rational::from(&down - &lo) <= *tol,
        "{what}: lower bound {r} loose"
    );
    prop_assert!(
        Rational::from(&hi - &up) <= *tol,
        "{what}: upper bound {r} loose"
    );
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]

    #[test]
    fn exp_encloses_tightly(x in dd(600.0)) {
        // Below about e^-660 the trailing part of a double-double is subnormal: the f64
        // path answers there (checked for soundness by the interval property below).
        let r = DdInterval::new(x, x).unwrap().exp();
        let exact = bracket(x, exp_r);
        let tol = exact.1.clone() * Rational::from_f64(2f64.powi(-90)).unwrap();
        check_point("exp", r, exact, &tol)?;
    }

    #[test]
    fn sin_and_cos_enclose_tightly(x in dd(1e4)) {
        let p = DdInterval::new(x, x).unwrap();
        let tol = Rational::from_f64(2f64.powi(-95)).unwrap();
        check_point("sin", p.sin(), bracket(x, sin_r), &tol)?;
        check_point("cos", p.cos(), bracket(x, cos_r), &tol)?;
    }

    #[test]
    fn tan_encloses_tightly(x in dd(1e4)) {
        // Relative: tan grows without bound near its poles.
        let exact = bracket(x, tan_r);
        let scale = exact.1.clone().abs().max(Rational::from(1));
        let tol = scale * Rational::from_f64(2f64.powi(-90)).unwrap();
        let r = DdInterval::new(x, x).unwrap().tan();
        prop_assume!(r.to_interval().is_common_interval());
        check_point("tan", r, exact, &tol)?;
    }

    #[test]
    fn inverse_trig_enclose_tightly(x in dd(1.0), big in dd(1e30)) {
        let tol = Rational::from_f64(2f64.powi(-95)).unwrap();
        let p = DdInterval::new(x, x).unwrap();
        check_point("asin", p.asin(), bracket(x, asin_r), &tol)?;
        check_point("acos", p.acos(), bracket(x, acos_r), &tol)?;
        check_point("atan", p.atan(), bracket(x, atan_r), &tol)?;
        let b = DdInterval::new(big, big).unwrap();
        check_point("atan", b.atan(), bracket(big, atan_r), &tol)?;
    }

    #[test]
    fn ln_and_log10_enclose_tightly(x in positive()) {
        let p = DdInterval::new(x, x).unwrap();
        let tol = Rational::from_f64(2f64.powi(-88)).unwrap();
        check_point("ln", p.ln(), bracket(x, ln_r), &tol)?;
        check_point("log10", p.log10(), bracket(x, log10_r), &tol)?;
    }

    #[test]
    fn pow_encloses_the_exact_power(a in positive(), b in -4.0..4.0f64) {
        prop_assume!(a.hi().abs().log2().abs() * b.abs() < 900.0);
        let r = DdInterval::new(a, a).unwrap().pow(DdInterval::point(b));
        // a^b = exp(b ln a), at 400 bits with directed rounding on each side.
        let side = |round: Round| {
            let mut l = big(a);
            l.ln_round(round);
            let mut e = Float::with_val(PREC, &l * b);
            e.exp_round(round);
            e.to_rational().unwrap()
        };
        let (lo, hi) = r.bounds().unwrap();
        // The 400-bit steps are within 2^-390 of exact: far inside the 2^-88 checked here.
        let (d, u) = (side(Round::Down), side(Round::Up));
        let slack = &u * Rational::from_f64(2f64.powi(-380)).unwrap();
        prop_assert!(q(lo) <= Rational::from(&d + &slack) && Rational::from(&u - &slack) <= q(hi), "pow {r}");
        let tol = &u * Rational::from_f64(2f64.powi(-80)).unwrap();
        let (gap_lo, gap_hi) = (&d - q(lo), q(hi) - &u);
        prop_assert!(gap_lo <= tol && gap_hi <= tol, "pow {r} loose");
    }

    #[test]
    fn intervals_hold_the_values_inside(a in dd(700.0), w in 0.0..4.0f64, s in 0.0..=1.0f64) {
        let b = Dd::from_sum(a.hi() + w, a.lo()).unwrap();
        let x = DdInterval::new(a, b).unwrap();
        // A point inside (an f64 between the bounds) and its exact values.
        let p = Dd::from_f64(a.hi() + s * w);
        prop_assume!(q(a) <= q(p) && q(p) <= q(b));
        for (name, f, v) in [
            ("exp", exp_r as fn(&mut Float, Round) -> std::cmp::Ordering, x.exp()),
            ("sin", sin_r, x.sin()),
            ("cos", cos_r, x.cos()),
            ("ln", ln_r, x.ln()),
            ("tan", tan_r, x.tan()),
            ("atan", atan_r, x.atan()),
        ] {
            if name == "ln" && p.signum() <= 0 {
                continue;
            }
            let (d, u) = bracket(p, f);
            let (lo, hi) = v.bounds().unwrap();
            // Infinite bounds (tan over a pole among them) (ln over an interval reaching 0, exp beyond f64) hold anything.
            let below = lo.hi() == f64::NEG_INFINITY || q(lo) <= d;
            let above = hi.hi() == f64::INFINITY || u <= q(hi);
            prop_assert!(below && above, "{name} over {x}: {v} misses the value at {}", p.hi());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]

    #[test]
    fn asin_and_acos_hold_the_values_inside(a in -1.2..1.2f64, w in 0.0..1.0f64, s in 0.0..=1.0f64) {
        let x = DdInterval::from_interval(Interval::new(a, a + w).unwrap());
        let p = a + s * w;
        prop_assume!(p.abs() <= 1.0);
        for (name, f, v) in [
            ("asin", asin_r as fn(&mut Float, Round) -> std::cmp::Ordering, x.asin()),
            ("acos", acos_r, x.acos()),
        ] {
            let (d, u) = bracket(Dd::from_f64(p), f);
            let (lo, hi) = v.bounds().unwrap();
            prop_assert!(q(lo) <= d && u <= q(hi), "{name} over {x}: {v} misses the value at {p}");
        }
    }
}

/// The exact `π·k/2` lies inside every enclosure `r` of it (checked at 400 bits).
fn holds_half_pi_times(r: DdInterval, k: i32) {
    let mut down = Float::with_val(PREC, rug::float::Constant::Pi);
    down *= k;
    down /= 2;
    let (lo, hi) = r.bounds().expect("not empty");
    let exact = down.to_rational().unwrap();
    // π is irrational: the 400-bit value is within 2^-398 of it, far inside any gap tested.
    let slack = Rational::from_f64(2f64.powi(-390)).unwrap();
    assert!(
        q(lo) <= Rational::from(&exact - &slack) && Rational::from(&exact + &slack) <= q(hi),
        "{r} misses {k}·π/2"
    );
}

#[test]
fn exact_ends_of_the_inverse_functions_hold_the_irrational_values() {
    let p = |x: f64| DdInterval::point(x);
    holds_half_pi_times(p(1.0).asin(), 1);
    holds_half_pi_times(p(-1.0).asin(), -1);
    holds_half_pi_times(-p(-1.0).asin(), 1);
    holds_half_pi_times(p(-1.0).acos(), 2);
    holds_half_pi_times(p(0.0).acos(), 1);
    holds_half_pi_times(DdInterval::ENTIRE.atan(), 1);
    holds_half_pi_times(DdInterval::ENTIRE.atan(), -1);
    holds_half_pi_times(p(1e300).atan(), 1);
    // ln 10 through log10: log10(10) = 1 exactly, inside.
    assert!(p(10.0).log10().contains(1.0));
}

#[test]
fn extremes_and_special_cases() {
    let iv = |a: f64, b: f64| DdInterval::from_interval(Interval::new(a, b).unwrap());
    // [1, 2] holds π/2: sin reaches 1 exactly; [3, 3.5] holds π: cos reaches −1.
    assert_eq!(iv(1.0, 2.0).sin().to_interval().sup(), 1.0);
    assert_eq!(iv(3.0, 3.5).cos().to_interval().inf(), -1.0);
    // Far arguments and infinite bounds take the f64 path, soundly.
    assert!(iv(1e30, 1e30).sin().to_interval().contains(1e30f64.sin()));
    assert_eq!(DdInterval::ENTIRE.exp().to_interval().inf(), 0.0);
    assert_eq!(
        iv(0.0, 0.0).exp().to_interval(),
        Interval::new(1.0, 1.0).unwrap()
    );
    // tan over a pole is the whole line; atan of the whole line is (−π/2, π/2) enclosed.
    assert_eq!(iv(1.0, 2.0).tan().to_interval(), Interval::ENTIRE);
    let a = DdInterval::ENTIRE.atan().to_interval();
    assert!(
        a.contains(std::f64::consts::FRAC_PI_2) && a.sup() - std::f64::consts::FRAC_PI_2 < 1e-15
    );
    // asin and acos outside [−1, 1] are empty; at its ends, ±π/2, 0 and π.
    assert!(iv(1.5, 2.0).asin().is_empty());
    assert!(
        iv(1.0, 1.0)
            .asin()
            .to_interval()
            .contains(std::f64::consts::FRAC_PI_2)
    );
    assert!(
        iv(-1.0, -1.0)
            .acos()
            .to_interval()
            .contains(std::f64::consts::PI)
    );
    assert_eq!(iv(1.0, 1.0).acos().to_interval().inf(), 0.0);
}
