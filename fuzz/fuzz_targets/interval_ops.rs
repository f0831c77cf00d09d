//! Fuzz target: enclosure (soundness) of every interval operation of `interval-core`, for
//! `f64` and `f32`, against exact results from GMP/MPFR (`rug`).
//!
//! Input layout: byte 0 picks the type (bit 0: `f64`/`f32`); then come three intervals
//! `x`, `y`, `z` (two values each, see `Input::value`, made into an interval when the
//! constructor accepts them in either order, otherwise the empty interval), two extra values
//! per interval used as points when they lie inside, and an exponent `n` for `pown`. Missing
//! bytes read as zero. For every operation and every choice of points (finite endpoints, the
//! midpoint, the extra values) the exact value must lie in the result, and every result must
//! be a valid interval; intersection, convex hull and split are checked on the same points.
//! A failed `assert!` is a finding.
//!
//! Exact values: `+ − × ÷`, `fma`, `sqr`, `recip` as rationals; `sqrt` and the elementary
//! functions by MPFR rounded down and up (at any precision ≥ the format's, a bound `lo` of
//! the format satisfies `lo ≤ f(p)` iff `lo ≤ RD(f(p))`, so the check is exact).

#![no_main]

use core::cmp::Ordering;

use interval_core::{Float, Interval};
use libfuzzer_sys::fuzz_target;
use rug::Rational;
use rug::float::Round;
use rug::ops::PowAssignRound;

/// MPFR working precision for the elementary functions.
const PREC: u32 = 128;

/// The two floating-point types, as far as this target needs them.
trait Fl: Float {
    /// Stored fraction bits (52 or 23).
    const FRAC_BITS: u32;
    /// Largest biased exponent of a finite value (2046 or 254).
    const MAX_BIASED: u64;
    /// The value with the given sign, biased exponent and fraction (masked).
    fn compose(negative: bool, biased_exp: u64, frac: u64) -> Self;
    /// The low bits of `w` as a bit pattern.
    fn from_raw(w: u64) -> Self;
    /// The exact value as an MPFR number (`−0` becomes `+0`: points are real numbers).
    fn to_mp(self) -> rug::Float {
        rug::Float::with_val(PREC, rat(self))
    }
}

impl Fl for f64 {
    const FRAC_BITS: u32 = 52;
    const MAX_BIASED: u64 = 2046;
    fn compose(negative: bool, biased_exp: u64, frac: u64) -> Self {
        let bits =
            (u64::from(negative) << 63) | ((biased_exp & 0x7ff) << 52) | (frac & ((1 << 52) - 1));
        f64::from_bits(bits)
    }
    fn from_raw(w: u64) -> Self {
        f64::from_bits(w)
    }
}

impl Fl for f32 {
    const FRAC_BITS: u32 = 23;
    const MAX_BIASED: u64 = 254;
    fn compose(negative: bool, biased_exp: u64, frac: u64) -> Self {
        let bits = (u32::from(negative) << 31)
            | (((biased_exp & 0xff) as u32) << 23)
            | (frac as u32 & ((1 << 23) - 1));
        f32::from_bits(bits)
    }
    fn from_raw(w: u64) -> Self {
        f32::from_bits(w as u32)
    }
}

/// The input bytes, read front to back; reads past the end give zeros.
struct Input<'a> {
    data: &'a [u8],
    pos: usize,
}

impl Input<'_> {
    fn bytes<const N: usize>(&mut self) -> [u8; N] {
        let mut out = [0u8; N];
        for o in out.iter_mut() {
            *o = self.data.get(self.pos).copied().unwrap_or(0);
            self.pos += 1;
        }
        out
    }

    /// A value: a tag byte chooses the class (raw bit pattern, special value, huge
    /// magnitude near overflow, subnormal, tiny normal, short-mantissa value), eight more
    /// bytes its sign and digits. Special classes are hard to hit with raw bit patterns.
    fn value<T: Fl>(&mut self) -> T {
        let [tag]: [u8; 1] = self.bytes();
        let w = u64::from_le_bytes(self.bytes());
        let negative = w >> 63 == 1;
        let e = (w >> T::FRAC_BITS) & 31;
        match tag % 8 {
            0..=2 => T::from_raw(w),
            3 => {
                let specials = [
                    T::ZERO,
                    T::INFINITY,
                    T::MAX,
                    T::MIN_POSITIVE_SUBNORMAL,
                    T::compose(false, 1, 0),
                    T::ONE,
                    T::TWO,
                    T::NAN,
                ];
                let v = specials[(w % 8) as usize];
                if negative { -v } else { v }
            }
            4 => T::compose(negative, T::MAX_BIASED - e, w),
            5 => T::compose(negative, 0, w),
            6 => T::compose(negative, 1 + e, w),
            _ => {
                let m = f64::from(w as u16 as i16);
                let k = i32::from((w >> 16) as u8 as i8) % 40;
                T::from_f64_rn(m * 2f64.powi(k))
            }
        }
    }
}

/// `[a, b]` or `[b, a]` if the constructor accepts one of them, else the empty interval.
fn make<T: Fl>(a: T, b: T) -> Interval<T> {
    Interval::new(a, b)
        .or_else(|_| Interval::new(b, a))
        .unwrap_or(Interval::EMPTY)
}

/// Points of `x`: finite endpoints, the midpoint, and the extra values that lie inside.
fn points<T: Fl>(x: Interval<T>, extra: [T; 2]) -> Vec<T> {
    let Some((lo, hi)) = x.bounds() else {
        return Vec::new();
    };
    let mut v: Vec<T> = [lo, hi, x.mid()]
        .into_iter()
        .chain(extra)
        .filter(|&p| p.is_finite() && x.contains(p))
        .collect();
    v.dedup_by(|a, b| a == b);
    v
}

fn valid<T: Fl>(x: Interval<T>) -> bool {
    match x.bounds() {
        None => true,
        Some((lo, hi)) => {
            !lo.is_nan() && !hi.is_nan() && lo <= hi && lo != T::INFINITY && hi != T::NEG_INFINITY
        }
    }
}

fn rat<T: Fl>(x: T) -> Rational {
    Rational::from_f64(x.to_f64()).expect("finite")
}

/// `x ∋ v` for a rational `v`, compared exactly.
fn has_rat<T: Fl>(x: Interval<T>, v: &Rational) -> bool {
    let Some((lo, hi)) = x.bounds() else {
        return false;
    };
    let lo_ok = lo == T::NEG_INFINITY || (lo.is_finite() && rat(lo) <= *v);
    let hi_ok = hi == T::INFINITY || (hi.is_finite() && rat(hi) >= *v);
    lo_ok && hi_ok
}

/// `x ∋ f(p)` given `f(p)` rounded down (`d`) and up (`u`) by MPFR.
fn has_mp<T: Fl>(x: Interval<T>, d: &rug::Float, u: &rug::Float) -> bool {
    let Some((lo, hi)) = x.bounds() else {
        return false;
    };
    let lo_ok = d
        .partial_cmp(&lo.to_f64())
        .is_some_and(|o| o != Ordering::Less);
    let hi_ok = u
        .partial_cmp(&hi.to_f64())
        .is_some_and(|o| o != Ordering::Greater);
    lo_ok && hi_ok
}

/// `f(p)` rounded down and up by MPFR.
fn mpfr(
    p: &rug::Float,
    f: impl Fn(&mut rug::Float, Round) -> Ordering,
) -> (rug::Float, rug::Float) {
    let (mut d, mut u) = (p.clone(), p.clone());
    f(&mut d, Round::Down);
    f(&mut u, Round::Up);
    (d, u)
}

fn check_rat<T: Fl>(op: &str, at: &[T], r: Interval<T>, v: &Rational) {
    assert!(valid(r), "{op}{at:?}: invalid result {r:?}");
    assert!(has_rat(r, v), "{op}{at:?}: exact value {v} not in {r:?}");
}

fn check_mp<T: Fl>(op: &str, at: &[T], r: Interval<T>, du: (rug::Float, rug::Float)) {
    assert!(valid(r), "{op}{at:?}: invalid result {r:?}");
    assert!(
        has_mp(r, &du.0, &du.1),
        "{op}{at:?}: exact value in [{}, {}] not in {r:?}",
        du.0,
        du.1
    );
}

fn binary<T: Fl>(x: Interval<T>, y: Interval<T>, px: &[T], py: &[T]) {
    let (sum, diff, prod, quot) = (x + y, x - y, x * y, x / y);
    let (mn, mx) = (x.min(y), x.max(y));
    let (q1, q2) = y.mul_rev_to_pair(x);
    let pw = x.pow(y);
    let at2 = x.atan2(y);
    for &p in px {
        for &q in py {
            let at = [p, q];
            let (rp, rq) = (rat(p), rat(q));
            check_rat("add", &at, sum, &Rational::from(&rp + &rq));
            check_rat("sub", &at, diff, &Rational::from(&rp - &rq));
            check_rat("mul", &at, prod, &Rational::from(&rp * &rq));
            check_rat("min", &at, mn, &rp.clone().min(rq.clone()));
            check_rat("max", &at, mx, &rp.clone().max(rq.clone()));
            if q != T::ZERO {
                let v = Rational::from(&rp / &rq);
                check_rat("div", &at, quot, &v);
                assert!(
                    has_rat(q1, &v) || has_rat(q2, &v),
                    "mul_rev_to_pair{at:?}: {v} not in ({q1:?}, {q2:?})"
                );
            }
            // pow over {p > 0} ∪ {p = 0, q > 0}.
            if p > T::ZERO || (p == T::ZERO && q > T::ZERO) {
                let (mp, mq) = (p.to_mp(), q.to_mp());
                check_mp("pow", &at, pw, mpfr(&mp, |v, r| v.pow_assign_round(&mq, r)));
            }
            // atan2(p, q) = angle of the point (q, p), with the set-based +0.
            if !(p == T::ZERO && q == T::ZERO) {
                let (mp, mq) = (p.to_mp(), q.to_mp());
                check_mp("atan2", &at, at2, mpfr(&mp, |v, r| v.atan2_round(&mq, r)));
            }
        }
    }
    for r in [sum, diff, prod, quot, mn, mx, q1, q2, pw, at2] {
        assert!(valid(r), "invalid result {r:?} for x = {x:?}, y = {y:?}");
    }
    if !q2.is_empty() {
        assert!(
            q1.precedes(q2),
            "mul_rev_to_pair pieces out of order: {q1:?}, {q2:?}"
        );
    }
}

/// Set operations: every point of `x` or `y` lies in the hull, points of both in the
/// intersection, and each point of `x` in one of the pieces of `x.split(at)`.
fn set_ops<T: Fl>(x: Interval<T>, y: Interval<T>, px: &[T], py: &[T], at: T) {
    let (inter, hull) = (x.intersection(y), x.convex_hull(y));
    let (left, right) = x.split(at);
    for r in [inter, hull, left, right] {
        assert!(
            valid(r),
            "invalid set-operation result {r:?} for {x:?}, {y:?}, at {at:?}"
        );
    }
    for (&p, other) in px.iter().map(|p| (p, y)).chain(py.iter().map(|p| (p, x))) {
        assert!(hull.contains(p), "convex_hull({x:?}, {y:?}) misses {p:?}");
        assert_eq!(
            inter.contains(p),
            other.contains(p),
            "intersection({x:?}, {y:?}) at {p:?}"
        );
    }
    for &p in px {
        assert!(
            left.contains(p) || right.contains(p),
            "split({x:?}, {at:?}) misses {p:?}"
        );
        if !at.is_nan() {
            assert_eq!(left.contains(p), p <= at, "split({x:?}, {at:?}).0 at {p:?}");
            assert_eq!(
                right.contains(p),
                p >= at,
                "split({x:?}, {at:?}).1 at {p:?}"
            );
        }
    }
}

fn ternary<T: Fl>(x: Interval<T>, y: Interval<T>, z: Interval<T>, pts: [&[T]; 3]) {
    let r = x.fma(y, z);
    assert!(valid(r), "fma({x:?}, {y:?}, {z:?}): invalid result {r:?}");
    for &p in pts[0] {
        for &q in pts[1] {
            for &s in pts[2] {
                let v = rat(p) * rat(q) + rat(s);
                check_rat("fma", &[p, q, s], r, &v);
            }
        }
    }
}

fn unary<T: Fl>(x: Interval<T>, px: &[T], n: i32) {
    type F = fn(&mut rug::Float, Round) -> Ordering;
    type Domain = fn(f64) -> bool;
    let funcs: [(&str, Interval<T>, F, Domain); 17] = [
        ("sqrt", x.sqrt(), |v, r| v.sqrt_round(r), |p| p >= 0.0),
        ("exp", x.exp(), |v, r| v.exp_round(r), |_| true),
        ("exp2", x.exp2(), |v, r| v.exp2_round(r), |_| true),
        ("exp10", x.exp10(), |v, r| v.exp10_round(r), |_| true),
        ("log", x.log(), |v, r| v.ln_round(r), |p| p > 0.0),
        ("log2", x.log2(), |v, r| v.log2_round(r), |p| p > 0.0),
        ("log10", x.log10(), |v, r| v.log10_round(r), |p| p > 0.0),
        ("sinh", x.sinh(), |v, r| v.sinh_round(r), |_| true),
        ("cosh", x.cosh(), |v, r| v.cosh_round(r), |_| true),
        ("tanh", x.tanh(), |v, r| v.tanh_round(r), |_| true),
        ("sin", x.sin(), |v, r| v.sin_round(r), |_| true),
        ("cos", x.cos(), |v, r| v.cos_round(r), |_| true),
        ("tan", x.tan(), |v, r| v.tan_round(r), |_| true),
        (
            "asin",
            x.asin(),
            |v, r| v.asin_round(r),
            |p| (-1.0..=1.0).contains(&p),
        ),
        (
            "acos",
            x.acos(),
            |v, r| v.acos_round(r),
            |p| (-1.0..=1.0).contains(&p),
        ),
        ("atan", x.atan(), |v, r| v.atan_round(r), |_| true),
        ("ln", x.ln(), |v, r| v.ln_round(r), |p| p > 0.0),
    ];
    let (neg, abs, sqr, recip) = (-x, x.abs(), x.sqr(), x.recip());
    let pown = x.pown(n);
    for (name, r, _, _) in &funcs {
        assert!(valid(*r), "{name}({x:?}): invalid result {r:?}");
    }
    for &p in px {
        let rp = rat(p);
        check_rat("neg", &[p], neg, &Rational::from(-&rp));
        check_rat("abs", &[p], abs, &Rational::from(rp.abs_ref()));
        check_rat("sqr", &[p], sqr, &Rational::from(rp.square_ref()));
        if p != T::ZERO {
            check_rat("recip", &[p], recip, &Rational::from(rp.recip_ref()));
        }
        let mp = p.to_mp();
        if n >= 0 || p != T::ZERO {
            check_mp(
                "pown",
                &[p],
                pown,
                mpfr(&mp, |v, r| v.pow_assign_round(n, r)),
            );
        }
        for (name, r, f, domain) in &funcs {
            if domain(p.to_f64()) {
                check_mp(name, &[p], *r, mpfr(&mp, f));
            }
        }
    }
}

fn run<T: Fl>(inp: &mut Input<'_>) {
    let (a, b, c, d, e, f) = (
        inp.value::<T>(),
        inp.value::<T>(),
        inp.value::<T>(),
        inp.value::<T>(),
        inp.value::<T>(),
        inp.value::<T>(),
    );
    let (x, y, z) = (make(a, b), make(c, d), make(e, f));
    let mut extra = || [inp.value::<T>(), inp.value::<T>()];
    let (ex, ey, ez) = (extra(), extra(), extra());
    let [n0, n1]: [u8; 2] = inp.bytes();
    // Exponents mostly small, sometimes large (|n| up to 32767).
    let n = i32::from(i16::from_le_bytes([n0, n1]));
    let n = if n.unsigned_abs() > 4096 { n } else { n % 40 };
    let (px, py, pz) = (points(x, ex), points(y, ey), points(z, ez));
    binary(x, y, &px, &py);
    binary(y, x, &py, &px);
    set_ops(x, y, &px, &py, ey[0]);
    ternary(x, y, z, [&px, &py, &pz]);
    unary(x, &px, n);
}

fuzz_target!(|data: &[u8]| {
    let Some(&mode) = data.first() else {
        return;
    };
    let mut inp = Input { data, pos: 1 };
    if mode & 1 == 0 {
        run::<f64>(&mut inp);
    } else {
        run::<f32>(&mut inp);
    }
});
