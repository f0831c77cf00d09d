//! Fixed cases of the elementary and trigonometric functions: exact points, domain edges,
//! clamping to the range, poles and the branch cut, checked against known values and MPFR.

use interval_core::Interval;
use rug::Float as Big;
use rug::float::{Constant, Round};
use rug::ops::Pow;

const INF: f64 = f64::INFINITY;
const TINY: f64 = 5e-324;
/// The smallest `f64` above π (`std::f64::consts::PI` is below π).
const PI_UP: f64 = std::f64::consts::PI.next_up();
const PI_DOWN: f64 = std::f64::consts::PI;
const HALF_PI_DOWN: f64 = std::f64::consts::FRAC_PI_2;
const HALF_PI_UP: f64 = std::f64::consts::FRAC_PI_2.next_up();

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

fn pt(a: f64) -> Interval<f64> {
    iv(a, a)
}

fn iv32(a: f32, b: f32) -> Interval<f32> {
    Interval::new(a, b).unwrap()
}

/// Asserts that the MPFR value `v` lies in `x` and that `x` is at most two ulps wide.
fn assert_encloses_tightly(x: Interval<f64>, v: &Big) {
    let (lo, hi) = x.bounds().expect("nonempty");
    assert!(*v >= lo && *v <= hi, "{x:?} misses {v}");
    assert!(hi <= lo.next_up().next_up(), "{x:?} is wider than two ulps");
}

#[test]
fn empty_in_empty_out() {
    let e = Interval::<f64>::EMPTY;
    for f in [
        Interval::exp,
        Interval::exp2,
        Interval::exp10,
        Interval::log,
        Interval::ln,
        Interval::log2,
        Interval::log10,
        Interval::sinh,
        Interval::cosh,
        Interval::tanh,
        Interval::sin,
        Interval::cos,
        Interval::tan,
        Interval::asin,
        Interval::acos,
        Interval::atan,
    ] {
        assert!(f(e).is_empty());
    }
    for n in [-3, -2, -1, 0, 1, 2, 3] {
        assert!(e.pown(n).is_empty());
    }
    assert!(e.pow(pt(1.0)).is_empty() && pt(1.0).pow(e).is_empty());
    assert!(e.atan2(pt(1.0)).is_empty() && pt(1.0).atan2(e).is_empty());
}

#[test]
fn exponentials_exact_points_and_limits() {
    assert_eq!(pt(0.0).exp(), pt(1.0));
    assert_eq!(Interval::<f64>::ENTIRE.exp(), iv(0.0, INF));
    assert_eq!(pt(-1000.0).exp(), iv(0.0, TINY));
    assert_eq!(pt(710.0).exp(), iv(f64::MAX, INF));
    assert_eq!(iv(-3.0, 10.0).exp2(), iv(0.125, 1024.0));
    assert_eq!(pt(-1074.0).exp2(), pt(TINY));
    assert_eq!(pt(-1022.0).exp2(), pt(f64::MIN_POSITIVE));
    assert_eq!(pt(1024.0).exp2(), iv(f64::MAX, INF));
    assert_eq!(iv(0.0, 22.0).exp10(), iv(1.0, 1e22));
    assert_eq!(pt(2.0).exp10(), pt(100.0));
    // 10^23 is not an f64: a one-ulp bracket around it.
    assert_encloses_tightly(pt(23.0).exp10(), &Big::with_val(300, 10).pow(23u32));
    let e = pt(1.0).exp();
    assert_encloses_tightly(e, &Big::with_val(300, 1).exp());
}

#[test]
fn logarithms_exact_points_and_domain() {
    assert_eq!(pt(1.0).log(), pt(0.0));
    assert_eq!(pt(1.0).ln(), pt(0.0));
    assert!(pt(0.0).log().is_empty());
    assert!(iv(-2.0, -1.0).log().is_empty());
    assert!(iv(-2.0, 0.0).log2().is_empty());
    assert_eq!(iv(-1.0, 1.0).log(), iv(-INF, 0.0));
    assert_eq!(iv(0.0, 1.0).log10(), iv(-INF, 0.0));
    assert_eq!(Interval::<f64>::ENTIRE.log(), Interval::ENTIRE);
    assert_eq!(pt(8.0).log2(), pt(3.0));
    assert_eq!(iv(0.125, 1024.0).log2(), iv(-3.0, 10.0));
    assert_eq!(pt(TINY).log2(), pt(-1074.0));
    assert_eq!(pt(1000.0).log10(), pt(3.0));
    assert_eq!(pt(1e22).log10(), pt(22.0));
    assert_eq!(iv(1.0, 1e22).log10(), iv(0.0, 22.0));
    let l = pt(2.0).log();
    assert_encloses_tightly(l, &Big::with_val(300, 2).ln());
}

#[test]
fn hyperbolic_exact_points_and_range() {
    assert_eq!(pt(0.0).sinh(), pt(0.0));
    assert_eq!(pt(0.0).tanh(), pt(0.0));
    assert_eq!(pt(0.0).cosh(), pt(1.0));
    assert_eq!(iv(-1.0, 2.0).cosh().inf(), 1.0);
    assert_eq!(Interval::<f64>::ENTIRE.cosh(), iv(1.0, INF));
    assert_eq!(Interval::<f64>::ENTIRE.tanh(), iv(-1.0, 1.0));
    assert_eq!(Interval::<f64>::ENTIRE.sinh(), Interval::ENTIRE);
    // tanh(1e300) rounds to 1 but is below it: the bound is not pushed above 1.
    assert_eq!(pt(1e300).tanh(), iv(1f64.next_down(), 1.0));
    assert_eq!(pt(1000.0).sinh(), iv(f64::MAX, INF));
    assert_eq!(pt(-1000.0).sinh(), iv(-INF, -f64::MAX));
}

#[test]
fn sine_bounds_at_pi() {
    // sin(π↑) is a tiny negative number, so the lower bound is one ulp below it.
    let s = iv(0.0, PI_UP).sin();
    assert_eq!(s.sup(), 1.0);
    let exact = Big::with_val(300, PI_UP).sin();
    assert!(exact < 0.0 && exact > -3.3e-16);
    assert!(s.inf() <= exact && s.inf() >= exact.to_f64_round(Round::Down).next_down());
    // sin(π↓) is a tiny positive number: the range is exactly [0, 1].
    assert_eq!(iv(0.0, PI_DOWN).sin(), iv(0.0, 1.0));
    assert_eq!(pt(0.0).sin(), pt(0.0));
    assert_eq!(iv(0.0, 2.0).sin(), iv(0.0, 1.0));
    assert_eq!(iv(-2.0, 2.0).sin(), iv(-1.0, 1.0));
    assert_eq!(iv(4.0, 5.0).sin().inf(), -1.0);
    assert_eq!(iv(0.0, 7.0).sin(), iv(-1.0, 1.0));
    assert_eq!(Interval::<f64>::ENTIRE.sin(), iv(-1.0, 1.0));
    assert_eq!(iv(1.0, INF).cos(), iv(-1.0, 1.0));
}

#[test]
fn cosine_extrema_and_zero_endpoints() {
    let c = iv(-1.0, 1.0).cos();
    assert_eq!(c.sup(), 1.0);
    assert_encloses_tightly(pt(1.0).cos(), &Big::with_val(300, 1).cos());
    assert!(c.inf() <= Big::with_val(300, 1).cos() && c.inf() > 0.54);
    assert_eq!(pt(0.0).cos(), pt(1.0));
    // 0 as an endpoint is the maximum itself, not an interior minimum.
    let right = iv(0.0, 1.0).cos();
    assert_eq!(right.sup(), 1.0);
    assert!(right.inf() > 0.54);
    let left = iv(-1.0, 0.0).cos();
    assert_eq!(left.sup(), 1.0);
    assert!(left.inf() > 0.54);
    // π inside: minimum −1.
    assert_eq!(iv(0.0, 4.0).cos().inf(), -1.0);
    assert_eq!(iv(-4.0, 0.0).cos().inf(), -1.0);
    assert_eq!(iv(0.0, 6.0).cos().sup(), 1.0);
    assert_eq!(iv(-1.0, 5.0).cos(), iv(-1.0, 1.0));
    // cos(π↓) rounds to −1: the bound is clamped at −1.
    assert_eq!(iv(3.0, PI_DOWN).cos().inf(), -1.0);
}

#[test]
fn sine_of_a_huge_argument() {
    let s = pt(1e300).sin();
    assert_encloses_tightly(s, &Big::with_val(300, 1e300).sin());
    let c = pt(1e300).cos();
    assert_encloses_tightly(c, &Big::with_val(300, 1e300).cos());
    let t = pt(1e300).tan();
    let exact = Big::with_val(300, 1e300).tan();
    assert!(t.inf() <= exact && exact <= t.sup());
}

#[test]
fn tangent_poles() {
    assert!(iv(1.5, 1.6).tan().is_entire());
    assert!(iv(-1.6, -1.5).tan().is_entire());
    assert!(iv(0.0, 4.0).tan().is_entire());
    assert!(iv(1.0, INF).tan().is_entire());
    assert_eq!(pt(0.0).tan(), pt(0.0));
    let t = iv(-1.0, 1.0).tan();
    let t1 = Big::with_val(300, 1).tan();
    assert!(t.sup() >= t1 && t.sup() <= t1.to_f64_round(Round::Up).next_up());
    assert_eq!(t.inf(), -t.sup());
    // Just below the pole at π/2: finite and huge.
    let near = iv(1.5, HALF_PI_DOWN).tan();
    assert!(near.sup().is_finite() && near.sup() > 1e15);
}

#[test]
fn inverse_trigonometric_domains() {
    assert_eq!(iv(-2.0, 2.0).asin(), iv(-HALF_PI_UP, HALF_PI_UP));
    assert!(iv(-2.0, 2.0).asin().inf() <= -Big::with_val(300, Constant::Pi) / 2u32);
    assert_eq!(iv(-2.0, 2.0).acos(), iv(0.0, PI_UP));
    assert!(iv(2.0, 3.0).asin().is_empty());
    assert!(iv(-3.0, -1.5).acos().is_empty());
    assert_eq!(pt(0.0).asin(), pt(0.0));
    assert_eq!(pt(1.0).acos(), pt(0.0));
    assert_eq!(pt(0.0).atan(), pt(0.0));
    assert_eq!(Interval::<f64>::ENTIRE.atan(), iv(-HALF_PI_UP, HALF_PI_UP));
    // The exact values π and π/2 lie between known neighbours: tight.
    assert_eq!(pt(-1.0).acos(), iv(PI_DOWN, PI_UP));
    assert_eq!(pt(1.0).asin(), iv(HALF_PI_DOWN, HALF_PI_UP));
    assert_eq!(pt(-1.0).asin(), iv(-HALF_PI_UP, -HALF_PI_DOWN));
    assert_eq!(iv(1.0, INF).atan().sup(), HALF_PI_UP);
}

#[test]
fn atan2_quadrants_and_branch_cut() {
    let pi = Big::with_val(300, Constant::Pi);
    let q = |y: Interval<f64>, x: Interval<f64>| y.atan2(x);
    // First quadrant: inside (0, π/2).
    let r = q(iv(1.0, 2.0), iv(1.0, 2.0));
    assert!(r.inf() > 0.46 && r.sup() < 1.11);
    // Second, third and fourth quadrants.
    let r = q(iv(1.0, 2.0), iv(-2.0, -1.0));
    assert!(r.inf() > HALF_PI_UP && r.sup() < PI_DOWN);
    let r = q(iv(-2.0, -1.0), iv(-2.0, -1.0));
    assert!(r.inf() > -PI_DOWN && r.sup() < -HALF_PI_UP);
    let r = q(iv(-2.0, -1.0), iv(1.0, 2.0));
    assert!(r.inf() > -HALF_PI_UP && r.sup() < 0.0);
    // Touching the cut from below, or crossing it: [−π, π].
    assert_eq!(q(iv(-1.0, 1.0), iv(-2.0, -1.0)), iv(-PI_UP, PI_UP));
    assert_eq!(q(iv(-1.0, 0.0), iv(-2.0, -1.0)), iv(-PI_UP, PI_UP));
    // On the cut from above: angle π; no signed zeros.
    let r = q(iv(0.0, 1.0), iv(-2.0, -1.0));
    assert_eq!(r.sup(), PI_UP);
    assert_eq!(q(pt(0.0), iv(-2.0, -1.0)), iv(PI_DOWN, PI_UP));
    assert_eq!(q(pt(-0.0), iv(-2.0, -1.0)), iv(PI_DOWN, PI_UP));
    assert_eq!(q(pt(0.0), iv(1.0, 2.0)), pt(0.0));
    // The origin is outside the domain.
    assert!(q(pt(0.0), pt(0.0)).is_empty());
    assert_eq!(q(iv(0.0, 1.0), iv(0.0, 1.0)), iv(0.0, HALF_PI_UP));
    assert_eq!(q(pt(0.0), iv(-1.0, 1.0)), iv(0.0, PI_UP));
    assert_eq!(q(pt(1.0), pt(0.0)), iv(HALF_PI_DOWN, HALF_PI_UP));
    assert_eq!(q(pt(-1.0), iv(0.0, 0.0)), iv(-HALF_PI_UP, -HALF_PI_DOWN));
    assert_eq!(q(iv(1.0, INF), pt(0.0)), iv(HALF_PI_DOWN, HALF_PI_UP));
    assert_eq!(
        q(pt(1.0), iv(-INF, -1.0)),
        iv(2.356_194_490_192_344_6, PI_UP)
    );
    let r = q(pt(1.0), pt(1.0));
    let quarter = Big::with_val(300, &pi / 4u32);
    assert_encloses_tightly(r, &quarter);
    // Unbounded boxes: limits at the corners.
    assert_eq!(q(iv(1.0, INF), iv(1.0, INF)), iv(0.0, HALF_PI_UP));
    assert_eq!(q(Interval::ENTIRE, Interval::ENTIRE), iv(-PI_UP, PI_UP));
}

#[test]
fn pown_cases() {
    let x = iv(-2.0, 3.0);
    assert_eq!(x.pown(3), iv(-8.0, 27.0));
    assert_eq!(x.pown(2), iv(0.0, 9.0));
    assert_eq!(x.pown(4), iv(0.0, 81.0));
    assert_eq!(x.pown(0), pt(1.0));
    assert_eq!(x.pown(1), x);
    assert_eq!(iv(-1.0, 2.0).pown(-2), iv(0.25, INF));
    assert!(iv(-1.0, 2.0).pown(-1).is_entire());
    assert!(iv(-1.0, 2.0).pown(-3).is_entire());
    assert!(pt(0.0).pown(-2).is_empty());
    assert_eq!(iv(0.0, 2.0).pown(-3), iv(0.125, INF));
    assert_eq!(iv(-2.0, 0.0).pown(-3), iv(-INF, -0.125));
    assert_eq!(iv(-2.0, -1.0).pown(-3), iv(-1.0, -0.125));
    assert_eq!(iv(-2.0, -1.0).pown(-2), iv(0.25, 1.0));
    assert_eq!(pt(0.5).pown(1074), pt(TINY));
    assert_eq!(pt(3.0).pown(33), pt(5_559_060_566_555_523.0));
    assert_eq!(pt(10.0).pown(400), iv(f64::MAX, INF));
    assert_eq!(pt(-10.0).pown(401), iv(-INF, -f64::MAX));
    assert_eq!(pt(10.0).pown(-400), iv(0.0, TINY));
    assert_eq!(Interval::<f64>::ENTIRE.pown(-2), iv(0.0, INF));
    assert_eq!(Interval::<f64>::ENTIRE.pown(3), Interval::ENTIRE);
    // 1.1^100 is not representable: a one-ulp bracket.
    let p = pt(1.1).pown(100);
    let exact = Big::with_val(300, 1.1).pow(100u32);
    assert_encloses_tightly(p, &exact);
}

#[test]
fn pow_cases() {
    assert!(pt(0.0).pow(iv(-1.0, 0.0)).is_empty());
    assert_eq!(pt(0.0).pow(iv(-1.0, 1.0)), pt(0.0));
    assert!(iv(-2.0, -1.0).pow(pt(2.0)).is_empty());
    assert_eq!(iv(0.0, 1.0).pow(pt(-1.0)), iv(1.0, INF));
    assert_eq!(iv(-1.0, 4.0).pow(pt(0.5)), iv(0.0, 2.0));
    assert_eq!(pt(2.0).pow(pt(3.0)), pt(8.0));
    assert_eq!(pt(2.0).pow(pt(-3.0)), pt(0.125));
    assert_eq!(iv(1.0, 3.0).pow(pt(4.0)), iv(1.0, 81.0));
    assert_eq!(pt(1.0).pow(Interval::ENTIRE), pt(1.0));
    assert_eq!(pt(2.0).pow(Interval::ENTIRE), iv(0.0, INF));
    assert_eq!(iv(0.5, 2.0).pow(iv(-1.0, 1.0)), iv(0.5, 2.0));
    assert_eq!(iv(0.0, INF).pow(iv(-2.0, -1.0)), iv(0.0, INF));
    assert_eq!(iv(0.0, 1.0).pow(pt(0.0)), pt(1.0));
    let r = pt(2.0).pow(pt(0.3));
    let exact = Big::with_val(300, 2).pow(&Big::with_val(300, 0.3));
    assert_encloses_tightly(r, &exact);
}

#[test]
fn f32_bounds() {
    assert_eq!(iv32(0.0, 0.0).exp(), iv32(1.0, 1.0));
    assert_eq!(iv32(-3.0, 10.0).exp2(), iv32(0.125, 1024.0));
    assert_eq!(iv32(100.0, 100.0).exp(), iv32(f32::MAX, f32::INFINITY));
    assert_eq!(iv32(-200.0, -200.0).exp(), iv32(0.0, 1e-45));
    assert_eq!(iv32(8.0, 8.0).log2(), iv32(3.0, 3.0));
    assert_eq!(iv32(-1.0, 1.0).log(), iv32(f32::NEG_INFINITY, 0.0));
    assert_eq!(iv32(-1.0, 1.0).cos().sup(), 1.0);
    assert_eq!(iv32(-2.0, 3.0).pown(3), iv32(-8.0, 27.0));
    assert!(iv32(1.5, 1.6).tan().is_entire());
    let e = iv32(1.0, 1.0).exp();
    assert!(e.contains(std::f32::consts::E) && e.sup() == e.inf().next_up());
    // π as f32 (above π): sin is a tiny negative number.
    let s = iv32(0.0, std::f32::consts::PI).sin();
    assert!(s.inf() < 0.0 && s.inf() > -1e-7 && s.sup() == 1.0);
}
