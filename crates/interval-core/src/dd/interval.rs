//! [`DdInterval`]: intervals with double-double bounds, rounded outward.

use core::fmt;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::expansion::Expansion;
use super::number::Dd;
use crate::float::{Float, two_prod, two_sum};
use crate::{Interval, IntervalError};

/// An interval `[lo, hi]` with [`Dd`] bounds (about 106 bits), for queries whose `f64`
/// enclosures are too wide to decide them: large terms that cancel, clusters of close
/// roots.
///
/// # Accuracy
///
/// `+ - *` and `sqr` are double-word algorithms with proven error bounds, widened outward
/// by `2^-101` of their magnitude; `/` and `sqrt` are corrected until an exact residual
/// ([Shewchuk's expansions](super)) puts them on the right side; the lattice operations are
/// exact. Each bound is within `2^-100` (relative) of the exact one, and never on the wrong
/// side (the tests check both against exact rationals). `pown` multiplies these, so its bounds lose a few
/// such units per multiplication. Where a bound is infinite, a divisor holds 0, or a
/// magnitude leaves `[2^-400, 2^400]`, an operation computes in `f64` intervals instead
/// (outward, 1 ulp of `f64`): sound, no tighter than `f64`. `exp`, `sin`, `cos`, `ln`,
/// `log10` and `pow` reduce their argument and sum a Taylor polynomial in these operations
/// (within about `2^-80` to `2^-95`); the other functions (`tan`, the inverse trigonometric
/// functions, …) take the `f64` hull: [`map_f64`](Self::map_f64).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct DdInterval {
    lo: Dd,
    hi: Dd,
}

/// Smallest and largest bound magnitudes of the double-double paths: every product and
/// quotient of two such values, and the error terms of their expansions, stay finite and
/// above the subnormal range.
const LOW: f64 = f64::from_bits((1023 - 400) << 52);
const HIGH: f64 = f64::from_bits((1023 + 400) << 52);

/// Whether the double-double paths take `x` (zero, or a magnitude in `[LOW, HIGH]`).
fn in_range(x: Dd) -> bool {
    let m = x.hi().abs();
    m == 0.0 || (LOW..=HIGH).contains(&m)
}

/// Relative bound used to widen a double-double sum or product: `2^-101`, eight times the
/// proven error bounds of the algorithms below (`3u²` and `4u²`, `u = 2^-53`; Joldes,
/// Muller and Popescu, *Tight and rigorous error bounds for basic building blocks of
/// double-word arithmetic*, ACM TOMS 2017, Algorithms 6 and 12).
const WIDEN: f64 = f64::from_bits((1023 - 101) << 52);

/// The double-double `(h, l)` (an approximation of a value `v` with
/// `|v − (h + l)| ≤ 2^-104 |v|`) moved outward past `v`: down (`up = false`) or up.
fn widened(h: f64, l: f64, up: bool) -> Option<Dd> {
    // The bounds are relative to the exact value: a computed 0 is exact.
    if h == 0.0 && l == 0.0 {
        return Some(Dd::ZERO);
    }
    let e = (h.abs() * WIDEN).next_up();
    let l = if up { l.add_up(e) } else { l.sub_down(e) };
    Dd::from_sum(h, l)
}

/// `a + b` rounded down or up: the accurate double-word sum (Algorithm 6 of the paper
/// above, relative error at most `3u²/(1 − 4u)`), widened by [`WIDEN`].
fn add_bound(a: Dd, b: Dd, up: bool) -> Option<Dd> {
    let (sh, sl) = two_sum(a.hi(), b.hi());
    let (th, tl) = two_sum(a.lo(), b.lo());
    let c = sl + th;
    let (vh, vl) = fast_two_sum(sh, c);
    let w = tl + vl;
    let (zh, zl) = fast_two_sum(vh, w);
    widened(zh, zl, up)
}

/// `a · b` rounded down or up: the double-word product with fused multiply-adds
/// (Algorithm 12 of the paper above, relative error at most `4u²`), widened by [`WIDEN`].
/// The operands' magnitudes are in `[2^-400, 2^400]` (or 0), so no product underflows
/// below the margin.
fn mul_bound(a: Dd, b: Dd, up: bool) -> Option<Dd> {
    let (ch, cl1) = two_prod(a.hi(), b.hi());
    let tl0 = a.lo() * b.lo();
    let tl1 = a.hi().mul_add(b.lo(), tl0);
    let cl2 = a.lo().mul_add(b.hi(), tl1);
    let cl3 = cl1 + cl2;
    let (zh, zl) = fast_two_sum(ch, cl3);
    widened(zh, zl, up)
}

/// Fast2Sum (`|a| ≥ |b|` or `a = 0`): `(s, e)` with `s + e = a + b` exactly.
#[inline]
fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// Largest number of corrections of an approximate quotient or square root.
const MAX_CORRECTIONS: usize = 8;

/// `x` moved by about `2^-104 |x|` down (`up = false`) or up.
fn nudge(x: Dd, up: bool) -> Option<Dd> {
    let step = (x.hi().abs() * f64::EPSILON * f64::EPSILON).max(f64::MIN_POSITIVE);
    Dd::from_sum(x.hi(), if up { x.lo() + step } else { x.lo() - step })
}

/// A double-double `q` corrected until `residual(q)` (an exact sum) has the sign `wanted`
/// (`≥ 0` when `true`, `≤ 0` when `false`), moving `q` in direction `up`.
fn correct(
    mut q: Dd,
    up: bool,
    wanted_nonnegative: bool,
    residual: impl Fn(Dd) -> Expansion,
) -> Option<Dd> {
    for _ in 0..MAX_CORRECTIONS {
        let r = residual(q);
        let ok = if wanted_nonnegative {
            r.is_nonnegative(false)
        } else {
            r.is_nonpositive(false)
        };
        if ok {
            return Some(q);
        }
        q = nudge(q, up)?;
    }
    None
}

/// `a / b` rounded down or up (`b ≠ 0`).
fn div_bound(a: Dd, b: Dd, up: bool) -> Option<Dd> {
    let q1 = a.hi() / b.hi();
    let mut e = Expansion::new();
    e.add_dd(a);
    e.add_product(-q1, b.hi());
    e.add_product(-q1, b.lo());
    let q2 = e.round(false)?.hi() / b.hi();
    let q = Dd::from_sum(q1, q2)?;
    // q ≤ a/b ⇔ a − q·b ≥ 0 for b > 0 (≤ 0 for b < 0); the other way round for q ≥ a/b.
    let wanted_nonnegative = (b.signum() > 0) != up;
    correct(q, up, wanted_nonnegative, |q| {
        let mut r = Expansion::new();
        r.add_dd(a);
        r.add_dd_product(-q, b);
        r
    })
}

/// `√a` rounded down or up (`a > 0`).
fn sqrt_bound(a: Dd, up: bool) -> Option<Dd> {
    let s1 = a.hi().sqrt();
    let mut e = Expansion::new();
    e.add_dd(a);
    e.add_product(-s1, s1);
    let s2 = e.round(false)?.hi() / (2.0 * s1);
    let s = Dd::from_sum(s1, s2)?;
    // s ≤ √a ⇔ a − s² ≥ 0.
    correct(s, up, !up, |s| {
        let mut r = Expansion::new();
        r.add_dd(a);
        r.add_dd_product(-s, s);
        r
    })
}

impl DdInterval {
    /// The empty set.
    pub const EMPTY: Self = Self {
        lo: Dd::INFINITY,
        hi: Dd::NEG_INFINITY,
    };
    /// The whole real line.
    pub const ENTIRE: Self = Self {
        lo: Dd::NEG_INFINITY,
        hi: Dd::INFINITY,
    };

    /// `[lo, hi]`; an error when a bound is NaN, `lo > hi`, or `lo = +∞` or `hi = −∞`.
    pub fn new(lo: Dd, hi: Dd) -> Result<Self, IntervalError> {
        let (l, h) = (lo.hi(), hi.hi());
        if l.is_nan() {
            return Err(IntervalError::NanBound { which: "lower" });
        }
        if h.is_nan() {
            return Err(IntervalError::NanBound { which: "upper" });
        }
        if l == f64::INFINITY || h == f64::NEG_INFINITY {
            return Err(IntervalError::InfiniteEndpoint { lo: l, hi: h });
        }
        if lo > hi {
            return Err(IntervalError::Reversed { lo: l, hi: h });
        }
        Ok(Self { lo, hi })
    }

    /// The `f64` interval `x`, exactly.
    pub fn from_interval(x: Interval<f64>) -> Self {
        match x.bounds() {
            Some((lo, hi)) => Self {
                lo: Dd::from_f64(lo),
                hi: Dd::from_f64(hi),
            },
            None => Self::EMPTY,
        }
    }

    /// The point `[x, x]` (empty for NaN, the whole line's end for an infinity is refused:
    /// empty as well).
    pub fn point(x: f64) -> Self {
        if x.is_finite() {
            Self {
                lo: Dd::from_f64(x),
                hi: Dd::from_f64(x),
            }
        } else {
            Self::EMPTY
        }
    }

    /// The smallest `f64` interval holding this one (outward).
    pub fn to_interval(self) -> Interval<f64> {
        if self.is_empty() {
            Interval::EMPTY
        } else {
            Interval::new_unchecked(self.lo.to_f64_down(), self.hi.to_f64_up())
        }
    }

    /// Whether the interval is empty.
    pub fn is_empty(self) -> bool {
        self.lo.hi() == f64::INFINITY
    }

    /// The bounds, `None` when empty.
    pub fn bounds(self) -> Option<(Dd, Dd)> {
        (!self.is_empty()).then_some((self.lo, self.hi))
    }

    /// Whether the `f64` `x` lies in the interval.
    pub fn contains(self, x: f64) -> bool {
        let x = Dd::from_f64(x);
        !self.is_empty() && self.lo <= x && x <= self.hi
    }

    /// `f` applied to the `f64` hull: the path of the operations without a double-double
    /// form (sound, with the accuracy of the `f64` operation).
    pub fn map_f64(self, f: impl FnOnce(Interval<f64>) -> Interval<f64>) -> Self {
        Self::from_interval(f(self.to_interval()))
    }

    /// `f` applied to the `f64` hulls of `self` and `b`.
    pub fn map2_f64(
        self,
        b: Self,
        f: impl FnOnce(Interval<f64>, Interval<f64>) -> Interval<f64>,
    ) -> Self {
        Self::from_interval(f(self.to_interval(), b.to_interval()))
    }

    /// Whether both bounds are finite and take the double-double paths.
    fn finite_in_range(self) -> bool {
        !self.is_empty()
            && self.lo.is_finite()
            && self.hi.is_finite()
            && in_range(self.lo)
            && in_range(self.hi)
    }

    /// The smallest lower and the largest upper bound of `op` at the four corners
    /// `(x, y)`, `x` a bound of `self` and `y` one of `b` (the range of a product or
    /// quotient, each monotone in both arguments on the region); `None` when a bound is
    /// missing.
    fn corners(self, b: Self, op: fn(Dd, Dd, bool) -> Option<Dd>) -> Option<(Dd, Dd)> {
        let mut out: Option<(Dd, Dd)> = None;
        for (x, y) in [
            (self.lo, b.lo),
            (self.lo, b.hi),
            (self.hi, b.lo),
            (self.hi, b.hi),
        ] {
            let (d, u) = (op(x, y, false)?, op(x, y, true)?);
            out = Some(match out {
                None => (d, u),
                Some((l, h)) => (if d < l { d } else { l }, if u > h { u } else { h }),
            });
        }
        out
    }

    /// `[lo, hi]` from computed bounds, or the `f64` path when one of them is missing.
    fn or_f64(lo: Option<Dd>, hi: Option<Dd>, fallback: impl FnOnce() -> Self) -> Self {
        match (lo, hi) {
            (Some(lo), Some(hi)) => Self { lo, hi },
            _ => fallback(),
        }
    }

    /// `self²` (the exact range: `[0, …]` over an interval holding 0).
    pub fn sqr(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let f64_path = || self.map_f64(Interval::sqr);
        if !self.finite_in_range() {
            return f64_path();
        }
        let (lo, hi) = (self.lo, self.hi);
        let (near, far) = if lo.signum() >= 0 {
            (Some(lo), hi)
        } else if hi.signum() <= 0 {
            (Some(hi), lo)
        } else {
            (None, if hi > -lo { hi } else { lo })
        };
        let low = match near {
            Some(n) => mul_bound(n, n, false),
            None => Some(Dd::ZERO),
        };
        Self::or_f64(low, mul_bound(far, far, true), f64_path)
    }

    /// `1 / self`.
    pub fn recip(self) -> Self {
        Self::point(1.0) / self
    }

    /// `√self` over the non-negative part (empty where there is none).
    pub fn sqrt(self) -> Self {
        if self.is_empty() || self.hi.signum() < 0 {
            return Self::EMPTY;
        }
        let f64_path = || self.map_f64(Interval::sqrt);
        if !self.finite_in_range() {
            return f64_path();
        }
        let root = |x: Dd, up: bool| {
            if x.signum() <= 0 {
                Some(Dd::ZERO)
            } else {
                sqrt_bound(x, up)
            }
        };
        Self::or_f64(root(self.lo, false), root(self.hi, true), f64_path)
    }

    /// `self^n` for an integer `n` (IEEE 1788 `pown`: `x^0 = 1`, negative `n` divides).
    ///
    /// The power is monotone on each sign, so the bounds are powers of single bounds (no
    /// dependency between factors), each computed by squaring and multiplying point
    /// intervals outward.
    pub fn pown(self, n: i32) -> Self {
        if self.is_empty() {
            return self;
        }
        match n {
            0 => Self::point(1.0),
            1 => self,
            _ if n == i32::MIN || !self.finite_in_range() => self.map_f64(|x| x.pown(n)),
            _ if n < 0 => self.pown(-n).recip(),
            _ => {
                let n = n.unsigned_abs();
                let at = |x: Dd| Self { lo: x, hi: x }.power_of_point(n);
                if n % 2 == 1 {
                    Self {
                        lo: at(self.lo).lo,
                        hi: at(self.hi).hi,
                    }
                } else {
                    let a = self.abs();
                    Self {
                        lo: at(a.lo).lo,
                        hi: at(a.hi).hi,
                    }
                }
            }
        }
    }

    /// `x^n` for a point interval `x = self` and `n ≥ 1`, by squaring and multiplying.
    fn power_of_point(self, n: u32) -> Self {
        let mut result = None::<Self>;
        let mut base = self;
        let mut k = n;
        while k > 0 {
            if k & 1 == 1 {
                result = Some(result.map_or(base, |r| r * base));
            }
            k >>= 1;
            if k > 0 {
                base = base.sqr();
            }
        }
        result.unwrap_or(Self::point(1.0))
    }

    /// `|self|`.
    pub fn abs(self) -> Self {
        if self.is_empty() || self.lo.signum() >= 0 {
            self
        } else if self.hi.signum() <= 0 {
            -self
        } else {
            let m = if self.hi > -self.lo {
                self.hi
            } else {
                -self.lo
            };
            Self {
                lo: Dd::ZERO,
                hi: m,
            }
        }
    }

    /// `min(self, b)` (exact).
    pub fn min(self, b: Self) -> Self {
        if self.is_empty() || b.is_empty() {
            return Self::EMPTY;
        }
        let pick = |x: Dd, y: Dd| if y < x { y } else { x };
        Self {
            lo: pick(self.lo, b.lo),
            hi: pick(self.hi, b.hi),
        }
    }

    /// `max(self, b)` (exact).
    pub fn max(self, b: Self) -> Self {
        if self.is_empty() || b.is_empty() {
            return Self::EMPTY;
        }
        let pick = |x: Dd, y: Dd| if y > x { y } else { x };
        Self {
            lo: pick(self.lo, b.lo),
            hi: pick(self.hi, b.hi),
        }
    }

    /// The convex hull of both.
    pub fn convex_hull(self, b: Self) -> Self {
        if self.is_empty() {
            return b;
        }
        if b.is_empty() {
            return self;
        }
        Self {
            lo: if b.lo < self.lo { b.lo } else { self.lo },
            hi: if b.hi > self.hi { b.hi } else { self.hi },
        }
    }
}

impl Neg for DdInterval {
    type Output = Self;

    /// `-self`.
    fn neg(self) -> Self {
        if self.is_empty() {
            return self;
        }
        Self {
            lo: -self.hi,
            hi: -self.lo,
        }
    }
}

impl Add for DdInterval {
    type Output = Self;

    /// `self + b`.
    fn add(self, b: Self) -> Self {
        if self.is_empty() || b.is_empty() {
            return Self::EMPTY;
        }
        if !(self.finite_in_range() && b.finite_in_range()) {
            return self.map2_f64(b, |x, y| x + y);
        }
        Self::or_f64(
            add_bound(self.lo, b.lo, false),
            add_bound(self.hi, b.hi, true),
            || self.map2_f64(b, |x, y| x + y),
        )
    }
}

impl Sub for DdInterval {
    type Output = Self;

    /// `self − b`.
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Mul for DdInterval {
    type Output = Self;

    /// `self · b`.
    fn mul(self, b: Self) -> Self {
        if self.is_empty() || b.is_empty() {
            return Self::EMPTY;
        }
        let f64_path = || self.map2_f64(b, |x, y| x * y);
        if !(self.finite_in_range() && b.finite_in_range()) {
            return f64_path();
        }
        let (lo, hi) = self.corners(b, mul_bound).unzip();
        Self::or_f64(lo, hi, f64_path)
    }
}

impl Div for DdInterval {
    type Output = Self;

    /// `self / b` (IEEE 1788's set-based quotient; a divisor holding 0 takes the `f64` path).
    fn div(self, b: Self) -> Self {
        if self.is_empty() || b.is_empty() {
            return Self::EMPTY;
        }
        let f64_path = || self.map2_f64(b, |x, y| x / y);
        let divisor_signed = b.lo.signum() > 0 || b.hi.signum() < 0;
        if !(self.finite_in_range() && b.finite_in_range() && divisor_signed) {
            return f64_path();
        }
        let (lo, hi) = self.corners(b, div_bound).unzip();
        Self::or_f64(lo, hi, f64_path)
    }
}

impl fmt::Display for DdInterval {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.bounds() {
            Some((lo, hi)) => write!(f, "[{lo}, {hi}]"),
            None => f.write_str("[empty]"),
        }
    }
}
