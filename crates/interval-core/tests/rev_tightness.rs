//! How far the ends of `sin_rev`, `cos_rev`, `tan_rev`, `pow_rev1` and `pow_rev2` lie from
//! the tight ones, measured against MPFR (`f64`, moderate arguments).
//!
//! The tight lower end of a preimage `{z ∈ x : f(z) ∈ c}` is the float `L` whose gap
//! `[L, L⁺]` holds the preimage's infimum. Ours, `lo ≤ L`, is within `k` ulps when one of the
//! gaps `[lo + j ulps, lo + (j + 1) ulps]`, `j ≤ k`, holds a point of the preimage: MPFR
//! (1400 bits) evaluates `f` at the gap's two floats, and the gap holds a point when either
//! value lies in `c` or the two lie on both sides of a bound of `c` (`f` is monotone on a gap
//! this small away from its extrema, which are excluded: bounds of `c` within `2^-20` of
//! `±1` for `sin` and `cos`: `c` stays within `[-0.999, 0.999]`). The upper end likewise.
//! The test asserts `k = 0`: after shaving in double-double the ends are tight, for
//! arguments within a few periods of 0 (`|x| ≤ 40`; far out, the unshaved ends can lie
//! more than the 16 ulps the shaving walks, and stay valid).

mod common;

use common::config;
use interval_core::Interval;
use proptest::prelude::*;
use rug::Float as Big;
use rug::float::Round;

const PREC: u32 = 1400;
/// The largest distance allowed, in ulps: none, the ends are the tight ones.
const MAX_ULPS: u32 = 0;

type I = Interval<f64>;

/// Where the MPFR bracket `[d, u]` of `f(z)` lies against `c`: -1 below, 1 above, 0 inside
/// or straddling a bound (then a preimage point is at `z` or within the bracket's error).
fn side(c: I, d: &Big, u: &Big) -> i32 {
    if *u < c.inf() {
        -1
    } else if *d > c.sup() {
        1
    } else {
        0
    }
}

/// Whether the gap `[a, b]` (neighbouring floats) holds a point `z` with `f(z) ∈ c`.
fn gap_meets(c: I, a: f64, b: f64, f: &dyn Fn(f64) -> (Big, Big)) -> bool {
    let (sa, sb) = {
        let (da, ua) = f(a);
        let (db, ub) = f(b);
        (side(c, &da, &ua), side(c, &db, &ub))
    };
    sa == 0 || sb == 0 || sa != sb
}

/// The distance in ulps of the ends of `ours` from the tight ones (`None`: not found within
/// `MAX_ULPS + 2`, reported as a failure).
fn distance(ours: I, x: I, c: I, f: &dyn Fn(f64) -> (Big, Big)) -> Option<u32> {
    let Some((lo, hi)) = ours.bounds() else {
        return Some(0);
    };
    let mut worst = 0;
    if lo.is_finite() && lo > x.inf() {
        let mut z = lo;
        let mut k = 0;
        while !gap_meets(c, z, z.next_up(), f) {
            k += 1;
            z = z.next_up();
            if k > MAX_ULPS + 2 || z > hi {
                return None;
            }
        }
        worst = worst.max(k);
    }
    if hi.is_finite() && hi < x.sup() {
        let mut z = hi;
        let mut k = 0;
        while !gap_meets(c, z.next_down(), z, f) {
            k += 1;
            z = z.next_down();
            if k > MAX_ULPS + 2 || z < lo {
                return None;
            }
        }
        worst = worst.max(k);
    }
    Some(worst)
}

fn mpfr(z: f64, g: fn(&mut Big, Round) -> core::cmp::Ordering) -> (Big, Big) {
    let mut d = Big::with_val(PREC, z);
    let mut u = d.clone();
    g(&mut d, Round::Down);
    g(&mut u, Round::Up);
    (d, u)
}

/// `b^e` bracketed (for `b > 0`).
fn mpfr_pow(b: f64, e: f64) -> (Big, Big) {
    let (bb, ee) = (Big::with_val(PREC, b), Big::with_val(PREC, e));
    let mut d = Big::with_val(PREC, &bb);
    let mut u = d.clone();
    use rug::ops::PowAssignRound;
    d.pow_assign_round(&ee, Round::Down);
    u.pow_assign_round(&ee, Round::Up);
    (d, u)
}

fn check(
    name: &str,
    ours: I,
    x: I,
    c: I,
    f: &dyn Fn(f64) -> (Big, Big),
) -> Result<(), TestCaseError> {
    let k = distance(ours, x, c, f);
    prop_assert!(
        k == Some(MAX_ULPS),
        "{name}(c = {c:?}, x = {x:?}) = {ours:?}: an end is {k:?} ulps from tight"
    );
    Ok(())
}

/// A narrow `c` around a value `v`, and a moderate `x`.
fn ordered(a: f64, b: f64) -> I {
    I::new(a.min(b), a.max(b)).unwrap()
}

proptest! {
    #![proptest_config(config(3000))]

    #[test]
    fn trigonometric_reverse_operations_are_tight(
        v in -0.999f64..0.999, w in 0.0f64..0.5, x0 in -20.0f64..20.0, xw in 0.0f64..20.0,
        t in -50.0f64..50.0,
    ) {
        let x = ordered(x0, x0 + xw);
        let c = ordered(v, (v + w).min(0.999));
        check("sin_rev", c.sin_rev_in(x), x, c, &|z| mpfr(z, Big::sin_round))?;
        check("cos_rev", c.cos_rev_in(x), x, c, &|z| mpfr(z, Big::cos_round))?;
        let ct = ordered(t, t + w * 10.0);
        check("tan_rev", ct.tan_rev_in(x), x, ct, &|z| mpfr(z, Big::tan_round))?;
    }

    #[test]
    fn pow_reverse_operations_are_tight(
        b in 0.1f64..5.0, clo in 0.01f64..50.0, cw in 0.0f64..50.0, x0 in 0.0f64..10.0,
        xw in 0.0f64..10.0, a in 0.05f64..8.0,
    ) {
        let c = ordered(clo, clo + cw);
        let x = ordered(x0, x0 + xw);
        let bi = I::new(b, b).unwrap();
        check("pow_rev1", bi.pow_rev1_in(c, x), x, c, &|z| mpfr_pow(z, b))?;
        let ai = I::new(a, a).unwrap();
        let y = ordered(x0 - 5.0, x0 + xw);
        check("pow_rev2", ai.pow_rev2_in(c, y), y, c, &|z| mpfr_pow(a, z))?;
    }
}
