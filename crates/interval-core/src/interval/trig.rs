//! Trigonometric functions: `sin`, `cos`, `tan`, `asin`, `acos`, `atan`, `atan2`.
//!
//! # Method
//!
//! Point values come from the correctly rounded CORE-MATH functions (computed in `f64`),
//! widened by one step outward exactly as in the elementary functions (see the `elementary`
//! module), so each bound taken at an endpoint is within one ulp of tight. CORE-MATH reduces
//! its arguments exactly, so `sin(1e300)` is as accurate as `sin(1)`.
//!
//! Interior extrema of `sin` and `cos`, and the poles of `tan`, are located from the *signs*
//! of the correctly rounded derivative at the endpoints, without any argument reduction of
//! our own. Rounding to nearest preserves signs, and neither `cos x` nor `sin x` comes close
//! to underflowing for an `f64` argument `x` (except `sin 0 = 0`), so those signs are the
//! signs of the exact values. With `w` the width rounded up:
//!
//! * `w ≤ π↓` (so the exact width is below π): the interval holds at most one zero of the derivative, and holds one exactly
//!   when the derivative changes sign between the endpoints;
//! * `π↓ < w ≤ 2π↓`: it holds one or two zeros, or none; a sign change means exactly one, equal
//!   signs mean zero or two, and both extrema are then included;
//! * `w > 2π↓`: the whole range `[−1, 1]`.
//!
//! (`π` and `2π` stand for `π↓` and `2π↓` in the tests, so they are decided soundly.) The
//! result is `[−1, 1]` without both extrema inside only when the exact width is within
//! `2·10⁻¹⁵` of `π` or `2π`; then both endpoints lie within `2·10⁻¹⁵` of extrema of opposite
//! sign, their values within `10⁻²⁹` of `±1`, and `[−1, 1]` is still the tight result. So
//! `sin` and `cos` are within one ulp of tight everywhere. For `tan` the same window (width
//! in `(π↓, π)` without a pole) returns `[−∞, +∞]` instead of two huge finite bounds.
//!
//! The enclosures of π used are `π↓ = 3.141592653589793 < π < π↑ = next_up(π↓)`, and
//! `π/2↓ = π↓/2 < π/2 < π/2↑ = next_up(π/2↓)`.

use super::Interval;
use super::elementary::{above, below, increasing, outward, plus_zero};
use crate::float::Float;

/// The largest `f64` below π (`std::f64::consts::PI`).
pub(super) const PI_DOWN: f64 = core::f64::consts::PI;
/// The smallest `f64` above π.
pub(super) const PI_UP: f64 = PI_DOWN.next_up();
/// `2π↓`, exactly twice [`PI_DOWN`], below 2π.
pub(super) const TWO_PI_DOWN: f64 = core::f64::consts::TAU;
/// The largest `f64` below π/2 (`π↓ / 2`).
const HALF_PI_DOWN: f64 = core::f64::consts::FRAC_PI_2;
/// The smallest `f64` above π/2.
const HALF_PI_UP: f64 = HALF_PI_DOWN.next_up();

/// Sign of a value for the extremum test: `+1`, `−1`, or 0 for zero.
#[inline(always)]
fn sign(v: f64) -> i8 {
    if v > 0.0 {
        1
    } else if v < 0.0 {
        -1
    } else {
        0
    }
}

/// Bounds of a periodic function with range `[−1, 1]` over `[a, b]` (finite, `a < b`),
/// from its rounded endpoint bounds `(lo, hi)` and the signs `da`, `db` (nonzero) of its
/// derivative at the endpoints: a sign change `+ → −` means an interior maximum,
/// `− → +` an interior minimum; see the module documentation for the width cases.
#[inline(always)]
fn periodic_extrema(a: f64, b: f64, lo: f64, hi: f64, da: i8, db: i8) -> (f64, f64) {
    let w = b.sub_up(a);
    if w > TWO_PI_DOWN || da == 0 || db == 0 {
        return (-1.0, 1.0);
    }
    if da != db {
        if da > 0 { (lo, 1.0) } else { (-1.0, hi) }
    } else if w > PI_DOWN {
        (-1.0, 1.0)
    } else {
        (lo, hi)
    }
}

/// Bounds of `atan2(y, x)` at one corner (`+0` for zero coordinates, not the origin):
/// exact 0 on the positive x-axis (and at `x = +∞`), the tight enclosures of `π` and `±π/2`
/// on the negative x-axis and the y-axis (and their limits at infinity), otherwise the
/// correctly rounded CORE-MATH `atan2` widened by one step.
fn atan2_corner(y: f64, x: f64) -> (f64, f64) {
    let finite_y = y.is_finite();
    if (y == 0.0 && x > 0.0) || (finite_y && x == f64::INFINITY) {
        (0.0, 0.0)
    } else if (y == 0.0 && x < 0.0) || (finite_y && y >= 0.0 && x == f64::NEG_INFINITY) {
        (PI_DOWN, PI_UP)
    } else if finite_y && x == f64::NEG_INFINITY {
        (-PI_UP, -PI_DOWN)
    } else if (x == 0.0 || (x.is_finite() && !finite_y)) && y > 0.0 {
        (HALF_PI_DOWN, HALF_PI_UP)
    } else if (x == 0.0 || (x.is_finite() && !finite_y)) && y < 0.0 {
        (-HALF_PI_UP, -HALF_PI_DOWN)
    } else {
        let r = core_math::atan2(y, x);
        (below(r, false), above(r, false))
    }
}

impl<T: Float> Interval<T> {
    /// Sine.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound (a bound that is an
    /// interior extremum is exactly `±1`); tight at `x = 0`.
    /// **Why:** the endpoint values come from the correctly rounded CORE-MATH `sincos`
    /// widened by one step; interior extrema (zeros of `cos`) are decided from the exact
    /// signs of the correctly rounded `cos` at the endpoints and the rounded-up width, see
    /// the module documentation. Bounds are clamped to `[−1, 1]`.
    ///
    /// | `self`           | result                          |
    /// |------------------|---------------------------------|
    /// | ∅                | ∅                               |
    /// | unbounded        | `[−1, 1]`                       |
    /// | `[0, 0]`         | `[0, 0]`                        |
    /// | `[0, π↑]`        | `[sin(π↑)↓, 1]` (tiny negative) |
    /// | width ≥ 2π       | `[−1, 1]`                       |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let s = Interval::new(0.0, 2.0)?.sin();
    /// assert_eq!((s.inf(), s.sup()), (0.0, 1.0));
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn sin(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let (a, b) = (self.lo.to_f64(), self.hi.to_f64());
        if !(a.is_finite() && b.is_finite()) {
            return outward(-1.0, 1.0);
        }
        let (sa, ca) = core_math::sincos(a);
        let (sb, cb) = if a == b {
            (sa, ca)
        } else {
            core_math::sincos(b)
        };
        let mut lo = below(sa, a == 0.0).min(below(sb, b == 0.0));
        let mut hi = above(sa, a == 0.0).max(above(sb, b == 0.0));
        if a != b {
            // sin' = cos, never zero at an f64 argument.
            (lo, hi) = periodic_extrema(a, b, lo, hi, sign(ca), sign(cb));
        }
        outward(lo.max(-1.0), hi.min(1.0))
    }

    /// Cosine.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound (a bound that is an
    /// interior extremum is exactly `±1`); tight at `x = 0` (`cos 0 = 1`).
    /// **Why:** as for [`Interval::sin`], with `cos' = −sin`: `sin a < 0 < sin b` means an
    /// interior maximum, `sin a > 0 > sin b` an interior minimum. `sin` vanishes at an `f64`
    /// argument only at 0; an endpoint at 0 is itself the critical point, and the test uses
    /// the sign of `sin` just inside the interval (`+` right of 0, `−` left of 0).
    ///
    /// | `self`           | result         |
    /// |------------------|----------------|
    /// | ∅                | ∅              |
    /// | unbounded        | `[−1, 1]`      |
    /// | `[0, 0]`         | `[1, 1]`       |
    /// | `[−1, 1]`        | `[cos(1)↓, 1]` |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let c = Interval::new(-1.0, 1.0)?.cos();
    /// assert_eq!(c.sup(), 1.0);
    /// assert!(c.contains(1f64.cos()) && c.inf() > 0.54);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    // `sin` and `cos` keep separate bodies: a shared helper parameterised by the function
    // measured about 2 ns slower per call on the benchmark workload.
    pub fn cos(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let (a, b) = (self.lo.to_f64(), self.hi.to_f64());
        if !(a.is_finite() && b.is_finite()) {
            return outward(-1.0, 1.0);
        }
        let (sa, ca) = core_math::sincos(a);
        let (sb, cb) = if a == b {
            (sa, ca)
        } else {
            core_math::sincos(b)
        };
        let mut lo = below(ca, a == 0.0).min(below(cb, b == 0.0));
        let mut hi = above(ca, a == 0.0).max(above(cb, b == 0.0));
        if a != b {
            // cos' = −sin; just right of 0 sin > 0, just left of it sin < 0.
            let da = if a == 0.0 { -1 } else { -sign(sa) };
            let db = if b == 0.0 { 1 } else { -sign(sb) };
            (lo, hi) = periodic_extrema(a, b, lo, hi, da, db);
        }
        outward(lo.max(-1.0), hi.min(1.0))
    }

    /// Tangent, over the set minus the poles `π/2 + kπ` (which no `f64` hits).
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`; `ENTIRE`
    /// when the interval contains a pole. The one exception to the ulp bound: a width in the
    /// window `(π↓, π)` without a pole (both endpoints then within `10⁻¹⁵` of poles) gives
    /// `[−∞, +∞]` rather than two finite bounds of magnitude above `10¹⁵` (valid, not tight).
    /// **Why:** endpoint values from the correctly rounded CORE-MATH `tan`, widened by one
    /// step; `tan` is increasing between poles, and with the width below π the interval
    /// contains a pole exactly when the correctly rounded `cos` changes sign.
    ///
    /// | `self`          | result        |
    /// |-----------------|---------------|
    /// | ∅               | ∅             |
    /// | unbounded       | `[−∞, +∞]`    |
    /// | `[0, 0]`        | `[0, 0]`      |
    /// | `[1.5, 1.6]`    | `[−∞, +∞]`    |
    /// | width > π↓      | `[−∞, +∞]`    |
    ///
    /// ```
    /// use interval_core::Interval;
    /// assert!(Interval::new(1.5, 1.6)?.tan().is_entire());
    /// assert!(Interval::new(-1.0, 1.0)?.tan().contains(1.5574077246549023));
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn tan(self) -> Self {
        if self.is_empty() {
            return self;
        }
        let (a, b) = (self.lo.to_f64(), self.hi.to_f64());
        if !(a.is_finite() && b.is_finite()) || b.sub_up(a) > PI_DOWN {
            return Self::ENTIRE;
        }
        if a != b && sign(core_math::cos(a)) != sign(core_math::cos(b)) {
            return Self::ENTIRE;
        }
        let ta = core_math::tan(a);
        let tb = if a == b { ta } else { core_math::tan(b) };
        outward(below(ta, a == 0.0), above(tb, b == 0.0))
    }

    /// Arcsine over `self ∩ [−1, 1]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0` and at
    /// `x = ±1` (`±π/2`, whose neighbours `π/2↓ < π/2 < π/2↑` are known); the bounds never
    /// leave `[−π/2↑, π/2↑]`.
    /// **Why:** CORE-MATH `asin` is correctly rounded, so one outward step encloses;
    /// increasing.
    ///
    /// | `self`        | result                    |
    /// |---------------|---------------------------|
    /// | ∅, `[2, 3]`   | ∅                         |
    /// | `[−2, 2]`     | `[−π/2↑, π/2↑]` ⊇ `[−π/2, π/2]` |
    /// | `[0, 0]`      | `[0, 0]`                  |
    /// | `[1, 1]`      | `[π/2↓, π/2↑]`            |
    pub fn asin(self) -> Self {
        if self.is_empty() || self.hi < -T::ONE || self.lo > T::ONE {
            return Self::EMPTY;
        }
        let a = self.lo.max_nan(-T::ONE).to_f64();
        let b = self.hi.min_nan(T::ONE).to_f64();
        let ra = core_math::asin(a);
        let rb = if a == b { ra } else { core_math::asin(b) };
        // asin(±1) = ±π/2, whose position between its neighbours is known.
        let lo = if a == 1.0 {
            HALF_PI_DOWN
        } else {
            below(ra, a == 0.0)
        };
        let hi = if b == -1.0 {
            -HALF_PI_DOWN
        } else {
            above(rb, b == 0.0)
        };
        outward(lo.max(-HALF_PI_UP), hi.min(HALF_PI_UP))
    }

    /// Arccosine over `self ∩ [−1, 1]`.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 1`
    /// (`acos 1 = 0`) and `x = −1` (`π`, enclosed by `[π↓, π↑]`); the bounds never leave
    /// `[0, π↑]`.
    /// **Why:** CORE-MATH `acos` is correctly rounded, so one outward step encloses;
    /// decreasing.
    ///
    /// | `self`        | result        |
    /// |---------------|---------------|
    /// | ∅, `[2, 3]`   | ∅             |
    /// | `[−2, 2]`     | `[0, π↑]`     |
    /// | `[1, 1]`      | `[0, 0]`      |
    /// | `[−1, −1]`    | `[π↓, π↑]`    |
    pub fn acos(self) -> Self {
        if self.is_empty() || self.hi < -T::ONE || self.lo > T::ONE {
            return Self::EMPTY;
        }
        let a = self.lo.max_nan(-T::ONE).to_f64();
        let b = self.hi.min_nan(T::ONE).to_f64();
        let rb = core_math::acos(b);
        let ra = if a == b { rb } else { core_math::acos(a) };
        // acos(−1) = π, whose position between its neighbours is known.
        let lo = if b == -1.0 {
            PI_DOWN
        } else {
            below(rb, b == 1.0)
        };
        outward(lo.max(0.0), above(ra, a == 1.0).min(PI_UP))
    }

    /// Arctangent.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at `x = 0`; the
    /// bounds never leave `[−π/2↑, π/2↑]`.
    /// **Why:** CORE-MATH `atan` is correctly rounded, so one outward step encloses;
    /// increasing, with the limits `±π/2` at `±∞`.
    ///
    /// | `self`        | result            |
    /// |---------------|-------------------|
    /// | ∅             | ∅                 |
    /// | `[−∞, +∞]`    | `[−π/2↑, π/2↑]`   |
    /// | `[0, 0]`      | `[0, 0]`          |
    pub fn atan(self) -> Self {
        if self.is_empty() {
            return self;
        }
        increasing(
            self.lo,
            self.hi,
            core_math::atan,
            |x| x == 0.0,
            -HALF_PI_UP,
            HALF_PI_UP,
        )
    }

    /// The angle of the point `(x, y)` (IEEE 1788 `atan2(y, x)`, with `self = y`), in
    /// `(−π, π]`, over the box `y × x` minus the origin.
    ///
    /// **Accuracy:** each bound within 1 ulp of the tight bound; tight at the angles 0
    /// (corners `y = 0 < x`, and `x = +∞` with finite `y`), `π` (`y = 0 > x`, `x = −∞`) and
    /// `±π/2` (`x = 0`, `y = ±∞`), whose enclosures `[π↓, π↑]`, `[π/2↓, π/2↑]` are known;
    /// the bounds never leave `[−π↑, π↑]`.
    /// **Why:** a box that does not meet the branch cut from below is convex and the angle is
    /// continuous on it (the origin excluded), so its range is spanned by the angles of its
    /// corners (the limits at infinite corners being the IEEE `atan2` special values); each
    /// is the correctly rounded CORE-MATH `atan2` widened by one step. Set-based intervals
    /// have no signed zeros: a zero bound is `+0`, so `y = 0, x < 0` has angle π.
    ///
    /// | `y` (`self`)             | `x`          | result                |
    /// |--------------------------|--------------|-----------------------|
    /// | ∅                        | any          | ∅                     |
    /// | any                      | ∅            | ∅                     |
    /// | `[0, 0]`                 | `[0, 0]`     | ∅                     |
    /// | `y.inf < 0 ≤ y.sup`      | `x.inf < 0`  | `[−π↑, π↑]`           |
    /// | `[0, 0]`                 | `[−1, 1]`    | `[0, π↑]`             |
    /// | `[0, 0]`                 | `[−2, −1]`   | `[π↓, π↑]`            |
    /// | `[1, 1]`                 | `[0, 0]`     | `[π/2↓, π/2↑]`        |
    /// | `[1, 1]`                 | `[1, 1]`     | `[π/4↓, π/4↑]`        |
    ///
    /// ```
    /// use interval_core::Interval;
    /// let y = Interval::new(0.0, 1.0)?;
    /// let x = Interval::new(1.0, 2.0)?;
    /// let t = y.atan2(x);
    /// assert_eq!(t.inf(), 0.0);
    /// assert!(t.contains(std::f64::consts::FRAC_PI_4));
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn atan2(self, x: Self) -> Self {
        let y = self;
        if y.is_empty() || x.is_empty() {
            return Self::EMPTY;
        }
        let (yl, yh) = (plus_zero(y.lo.to_f64()), plus_zero(y.hi.to_f64()));
        let (xl, xh) = (plus_zero(x.lo.to_f64()), plus_zero(x.hi.to_f64()));
        if yl == 0.0 && yh == 0.0 && xl == 0.0 && xh == 0.0 {
            return Self::EMPTY;
        }
        if xl < 0.0 && yl < 0.0 && yh >= 0.0 {
            return outward(-PI_UP, PI_UP);
        }
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let ys: &[f64] = if yl == yh { &[yl] } else { &[yl, yh] };
        let xs: &[f64] = if xl == xh { &[xl] } else { &[xl, xh] };
        for &yc in ys {
            for &xc in xs {
                if yc == 0.0 && xc == 0.0 {
                    continue;
                }
                let (l, h) = atan2_corner(yc, xc);
                lo = lo.min(l);
                hi = hi.max(h);
            }
        }
        // Range facts: y ≥ 0 gives angles in [0, π]; y < 0 (or y ≤ 0 with x ≥ 0) in
        // [−π, 0]; x ≥ 0 in [−π/2, π/2].
        let (mut min, mut max) = (-PI_UP, PI_UP);
        if yl >= 0.0 {
            min = 0.0;
        }
        if yh < 0.0 || (yh == 0.0 && xl >= 0.0) {
            max = 0.0;
        }
        if xl >= 0.0 {
            min = min.max(-HALF_PI_UP);
            max = max.min(HALF_PI_UP);
        }
        outward(lo.max(min), hi.min(max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pi_enclosures() {
        assert_eq!(PI_DOWN, core::f64::consts::PI);
        assert_eq!(PI_UP, PI_DOWN.next_up());
        assert_eq!(TWO_PI_DOWN, 2.0 * PI_DOWN);
        assert_eq!(HALF_PI_DOWN, PI_DOWN / 2.0);
        assert_eq!(HALF_PI_UP, HALF_PI_DOWN.next_up());
        // sin(π↓) > 0 and sin(π↑) < 0 put π strictly between them.
        assert!(core_math::sin(PI_DOWN) > 0.0 && core_math::sin(PI_UP) < 0.0);
        // cos(π/2↓) > 0 > cos(π/2↑).
        assert!(core_math::cos(PI_DOWN / 2.0) > 0.0 && core_math::cos(HALF_PI_UP) < 0.0);
    }
}
