//! Slice (batch) operations: one interval operation applied element-wise to whole slices.
//!
//! Every function reads one or two input slices and writes into a caller-provided output
//! slice of the same length; mismatched lengths give [`IntervalError::LengthMismatch`]. The
//! results are **bit-for-bit** those of the scalar operations of [`Interval`] (the same
//! bounds, the same signs of zero, the same empty intervals), so a batch call can replace a
//! loop over the scalar operations anywhere.
//!
//! # How the fast paths work
//!
//! For `f64`, [`add`], [`sub`], [`mul`], [`div`], [`sqr`] and [`sqrt`] process the slices
//! in chunks of 16 intervals with a branch-free formulation of the directed rounding that
//! the compiler can vectorise:
//!
//! * each bound is computed to nearest, `r`, together with the exact sign of its rounding
//!   error: the error-free sum of [`crate::float::two_sum`] for sums, the remainder of a
//!   TwoProd for products, `n − q·d` for quotients and `a − s²` for square roots (TwoProd
//!   uses a fused multiply-add where the target has one, and Dekker's splitting product,
//!   exact in the same range, where it does not, so no call to the C library's `fma` is
//!   made);
//! * the step to the neighbouring float, when the error has the wrong sign, is done on the
//!   bit pattern (`bits ± 1`) and chosen with a select rather than a branch;
//! * for products and quotients the case analysis on the signs of the operands is replaced
//!   by selects (quotients) or by the minimum and maximum of the four corner products
//!   (products), which give the same values because directed rounding is monotone;
//! * a lane leaves the fast path when its sum is not finite or, for the other operations,
//!   when a bound is zero, infinite, NaN (empty) or of magnitude outside `[2^-480, 2^500]`
//!   (`[2^-960, 2^1000]` for square roots), so that no error term can underflow and no
//!   result can overflow. After each chunk those lanes, if any, are recomputed by the
//!   scalar operation.
//!
//! For `f32` intervals, and for the remaining functions ([`pown`], [`exp`], [`ln`],
//! [`sin`], [`cos`]), the batch functions are plain loops over the scalar operations: their
//! cost is in the correctly rounded CORE-MATH calls, which a chunked loop does not reduce.

use super::Interval;
use crate::IntervalError;
use crate::float::{Float, two_sum};
use core::any::Any;

/// Number of intervals processed together by the vectorisable kernels.
const CHUNK: usize = 16;

/// One chunk of `f64` intervals.
type Chunk = [Interval<f64>; CHUNK];

/// Lanes of a chunk that left the fast path.
type Lanes = [bool; CHUNK];

/// Smallest bound magnitude accepted by the product, quotient and square-root fast paths.
///
/// With all magnitudes in `[LOW, HIGH]`, products lie in `[2^-960, 2^1000]` and quotients in
/// `[2^-980, 2^980]`: every error term (FMA remainder or Dekker product) is exact, the
/// round-to-nearest result is normal and finite, and stepping it never overflows.
const LOW: f64 = f64::from_bits((1023 - 480) << 52);
/// Largest bound magnitude accepted by the product, quotient and square-root fast paths.
const HIGH: f64 = f64::from_bits((1023 + 500) << 52);
/// Smallest argument of the square-root fast path (its error term `a − s²` is exact).
const SQRT_LOW: f64 = f64::from_bits((1023 - 960) << 52);
/// Largest argument of the square-root fast path (`s² ≤ 2^1000` cannot overflow in
/// Dekker's product).
const SQRT_HIGH: f64 = f64::from_bits((1023 + 1000) << 52);

// ---------------------------------------------------------------------------------------
// Length checks and the generic drivers.
// ---------------------------------------------------------------------------------------

/// `Err(LengthMismatch)` unless `found == expected`.
#[inline]
fn check_len(
    operation: &'static str,
    argument: &'static str,
    expected: usize,
    found: usize,
) -> Result<(), IntervalError> {
    if expected == found {
        Ok(())
    } else {
        Err(IntervalError::LengthMismatch {
            operation,
            argument,
            expected,
            found,
        })
    }
}

/// The chunk as an array of `f64` intervals, when `T` is `f64` (a safe, zero-cost
/// downcast: the type test folds away after monomorphisation).
#[inline(always)]
fn as_f64<T: Float>(c: &[Interval<T>]) -> Option<&Chunk> {
    let arr: &[Interval<T>; CHUNK] = c.try_into().ok()?;
    (arr as &dyn Any).downcast_ref::<Chunk>()
}

/// Mutable version of [`as_f64`].
#[inline(always)]
fn as_f64_mut<T: Float>(c: &mut [Interval<T>]) -> Option<&mut Chunk> {
    let arr: &mut [Interval<T>; CHUNK] = c.try_into().ok()?;
    (arr as &mut dyn Any).downcast_mut::<Chunk>()
}

/// Applies a unary operation: `kernel` on full `f64` chunks (it returns whether any lane
/// left the fast path, marking those lanes), `scalar` on the marked lanes, on the tail and
/// for `f32`.
#[inline(always)]
fn map1<T: Float>(
    operation: &'static str,
    xs: &[Interval<T>],
    out: &mut [Interval<T>],
    kernel: impl Fn(&Chunk, &mut Chunk, &mut Lanes) -> bool,
    scalar: impl Fn(Interval<T>) -> Interval<T>,
) -> Result<(), IntervalError> {
    check_len(operation, "out", xs.len(), out.len())?;
    let mut xc = xs.chunks_exact(CHUNK);
    let mut oc = out.chunks_exact_mut(CHUNK);
    let mut bad = [false; CHUNK];
    for (x, o) in (&mut xc).zip(&mut oc) {
        let fixup = match (as_f64(x), as_f64_mut(o)) {
            (Some(xf), Some(of)) => {
                if kernel(xf, of, &mut bad) {
                    Some(&bad)
                } else {
                    continue;
                }
            }
            _ => None,
        };
        for (i, (xi, oi)) in x.iter().zip(o.iter_mut()).enumerate() {
            if fixup.is_none_or(|b| b[i]) {
                *oi = scalar(*xi);
            }
        }
    }
    for (xi, oi) in xc.remainder().iter().zip(oc.into_remainder()) {
        *oi = scalar(*xi);
    }
    Ok(())
}

/// Applies a binary operation; see [`map1`].
#[inline(always)]
fn map2<T: Float>(
    operation: &'static str,
    xs: &[Interval<T>],
    ys: &[Interval<T>],
    out: &mut [Interval<T>],
    kernel: impl Fn(&Chunk, &Chunk, &mut Chunk, &mut Lanes) -> bool,
    scalar: impl Fn(Interval<T>, Interval<T>) -> Interval<T>,
) -> Result<(), IntervalError> {
    check_len(operation, "ys", xs.len(), ys.len())?;
    check_len(operation, "out", xs.len(), out.len())?;
    let mut xc = xs.chunks_exact(CHUNK);
    let mut yc = ys.chunks_exact(CHUNK);
    let mut oc = out.chunks_exact_mut(CHUNK);
    let mut bad = [false; CHUNK];
    for ((x, y), o) in (&mut xc).zip(&mut yc).zip(&mut oc) {
        let fixup = match (as_f64(x), as_f64(y), as_f64_mut(o)) {
            (Some(xf), Some(yf), Some(of)) => {
                if kernel(xf, yf, of, &mut bad) {
                    Some(&bad)
                } else {
                    continue;
                }
            }
            _ => None,
        };
        for (i, ((xi, yi), oi)) in x.iter().zip(y).zip(o.iter_mut()).enumerate() {
            if fixup.is_none_or(|b| b[i]) {
                *oi = scalar(*xi, *yi);
            }
        }
    }
    let tail = xc.remainder().iter().zip(yc.remainder());
    for ((xi, yi), oi) in tail.zip(oc.into_remainder()) {
        *oi = scalar(*xi, *yi);
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------
// Branch-free directed rounding of f64 results.
// ---------------------------------------------------------------------------------------

/// `r` stepped one ulp toward −∞ when `err < 0`, for finite `r` that is nonzero whenever
/// `err ≠ 0` (then `f64::next_down(r)` is `bits − 1` for positive and `bits + 1` for
/// negative `r`, which is what is computed, without branches).
#[inline(always)]
fn down(r: f64, err: f64) -> f64 {
    let bits = r.to_bits();
    let stepped = if r > 0.0 {
        bits.wrapping_sub(1)
    } else {
        bits.wrapping_add(1)
    };
    f64::from_bits(if err < 0.0 { stepped } else { bits })
}

/// `r` stepped one ulp toward +∞ when `err > 0`; see [`down`].
#[inline(always)]
fn up(r: f64, err: f64) -> f64 {
    let bits = r.to_bits();
    let stepped = if r > 0.0 {
        bits.wrapping_add(1)
    } else {
        bits.wrapping_sub(1)
    };
    f64::from_bits(if err > 0.0 { stepped } else { bits })
}

/// `a · b` rounded to nearest and its exact error (exact for the operands of the fast
/// paths: the product is at least `2^-961` in magnitude and finite).
#[cfg(any(target_feature = "fma", target_arch = "aarch64"))]
#[inline(always)]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `a · b` rounded to nearest and its exact error, for the operands of the fast paths.
///
/// Without a hardware FMA, `f64::mul_add` is a library call; Dekker's product with
/// Veltkamp's splitting is exact when no splitting overflows (`|a|, |b| ≤ 2^996`) and the
/// exponents of `a` and `b` sum to at least `−970` (then no partial product loses bits to
/// underflow). The fast paths call it with `|a|, |b| ∈ [2^-480, 2^500]` (products), with
/// `q ∈ [2^-980, 2^980]` and `|q·d| ≥ 2^-481` (quotient remainders) and with
/// `s ∈ [2^-480, 2^500]` (square-root remainders).
#[cfg(not(any(target_feature = "fma", target_arch = "aarch64")))]
#[inline(always)]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    #[inline(always)]
    fn split(x: f64) -> (f64, f64) {
        let c = 134_217_729.0 * x; // 2^27 + 1
        let hi = c - (c - x);
        (hi, x - hi)
    }
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    let e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    (p, e)
}

/// `n − q·d` (or a value of the same sign), for `q = RN(n/d)` or `q = RN(√n) = d` in the
/// fast-path ranges: `q·d` is within a factor 2 of `n`, so `n − RN(q·d)` is exact
/// (Sterbenz) and the difference of two exact terms has the sign of the exact remainder.
#[inline(always)]
fn remainder(n: f64, q: f64, d: f64) -> f64 {
    let (p, e) = two_prod(q, d);
    (n - p) - e
}

/// True when `|x| ∈ [LOW, HIGH]` (false for zero, infinities, NaN and tiny values).
#[inline(always)]
fn in_range(x: f64) -> bool {
    (LOW..=HIGH).contains(&x.abs())
}

/// `min` for values that are not NaN and not both zero (so the result is unambiguous).
#[inline(always)]
fn fmin(a: f64, b: f64) -> f64 {
    if a < b { a } else { b }
}

/// `max` for values that are not NaN and not both zero.
#[inline(always)]
fn fmax(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

// ---------------------------------------------------------------------------------------
// f64 kernels. Each returns true if some lane left the fast path (marked in `bad`).
// ---------------------------------------------------------------------------------------

/// `[xl + yl, xh + yh]` for one chunk. The fast path needs only finite sums: then the
/// operands are finite, the error-free sum of [`two_sum`] (Fast2Sum after ordering by
/// magnitude, whose intermediate cannot overflow) is exact, and a nonzero error implies a
/// nonzero sum (a nonzero exact sum is at least the smallest subnormal).
#[inline(always)]
fn add_kernel(x: &Chunk, y: &Chunk, out: &mut Chunk, bad: &mut Lanes, negate_y: bool) -> bool {
    let mut any = false;
    for i in 0..CHUNK {
        let (xl, xh) = (x[i].lo, x[i].hi);
        // Subtraction is addition of `−y = [−yh, −yl]`.
        let (yl, yh) = if negate_y {
            (-y[i].hi, -y[i].lo)
        } else {
            (y[i].lo, y[i].hi)
        };
        let (sl, el) = two_sum(xl, yl);
        let (sh, eh) = two_sum(xh, yh);
        out[i] = Interval {
            lo: down(sl, el),
            hi: up(sh, eh),
        };
        let b = !((sl.abs() <= f64::MAX) & (sh.abs() <= f64::MAX));
        bad[i] = b;
        any |= b;
    }
    any
}

/// `x · y` for one chunk: the minimum (maximum) of the four corner products rounded down
/// (up). With all bounds nonzero the products are nonzero, so equal values have equal bits,
/// and by monotonicity of directed rounding the extremes are the bounds picked by the sign
/// tables of the scalar operation.
#[inline(always)]
fn mul_kernel(x: &Chunk, y: &Chunk, out: &mut Chunk, bad: &mut Lanes) -> bool {
    let mut any = false;
    for i in 0..CHUNK {
        let (a, b, c, d) = (x[i].lo, x[i].hi, y[i].lo, y[i].hi);
        let (p1, e1) = two_prod(a, c);
        let (p2, e2) = two_prod(a, d);
        let (p3, e3) = two_prod(b, c);
        let (p4, e4) = two_prod(b, d);
        let lo = fmin(
            fmin(down(p1, e1), down(p2, e2)),
            fmin(down(p3, e3), down(p4, e4)),
        );
        let hi = fmax(fmax(up(p1, e1), up(p2, e2)), fmax(up(p3, e3), up(p4, e4)));
        out[i] = Interval { lo, hi };
        let ok = in_range(a) & in_range(b) & in_range(c) & in_range(d);
        bad[i] = !ok;
        any |= !ok;
    }
    any
}

/// `x / y` for one chunk with `0 ∉ y`: the lower bound is `n / d` rounded down with
/// `n = xl` (y > 0) or `xh` (y < 0) and `d = yh` if `n ≥ 0` else `yl`; the upper bound is
/// `m / e` rounded up with `m` the other bound of `x` and `e = yl` if `m ≥ 0` else `yh`.
/// These are the entries of the scalar sign table.
#[inline(always)]
fn div_kernel(x: &Chunk, y: &Chunk, out: &mut Chunk, bad: &mut Lanes) -> bool {
    let mut any = false;
    for i in 0..CHUNK {
        let (a, b, c, d) = (x[i].lo, x[i].hi, y[i].lo, y[i].hi);
        let ypos = c > 0.0;
        let (nl, nh) = if ypos { (a, b) } else { (b, a) };
        let dl = if nl >= 0.0 { d } else { c };
        let dh = if nh >= 0.0 { c } else { d };
        let ql = nl / dl;
        let qh = nh / dh;
        let rl = remainder(nl, ql, dl);
        let rh = remainder(nh, qh, dh);
        // The error of q is r / d: flip the sign of r for negative divisors.
        let (rl, rh) = if ypos { (rl, rh) } else { (-rl, -rh) };
        out[i] = Interval {
            lo: down(ql, rl),
            hi: up(qh, rh),
        };
        let ok = in_range(a) & in_range(b) & in_range(c) & in_range(d) & (ypos | (d < 0.0));
        bad[i] = !ok;
        any |= !ok;
    }
    any
}

/// `x²` for one chunk (nonzero bounds: the sign classes are strict).
#[inline(always)]
fn sqr_kernel(x: &Chunk, out: &mut Chunk, bad: &mut Lanes) -> bool {
    let mut any = false;
    for i in 0..CHUNK {
        let (a, b) = (x[i].lo, x[i].hi);
        let (pa, ea) = two_prod(a, a);
        let (pb, eb) = two_prod(b, b);
        let (la, ua) = (down(pa, ea), up(pa, ea));
        let (lb, ub) = (down(pb, eb), up(pb, eb));
        let (lo, hi) = if a > 0.0 {
            (la, ub)
        } else if b < 0.0 {
            (lb, ua)
        } else {
            (0.0, fmax(ua, ub))
        };
        out[i] = Interval { lo, hi };
        let ok = in_range(a) & in_range(b);
        bad[i] = !ok;
        any |= !ok;
    }
    any
}

/// `√x` for one chunk. Fast lanes: `xh ∈ [2^-960, 2^1000]` and either `xl ≤ 0` (lower bound
/// `+0`, as the scalar operation gives) or `xl ≥ 2^-960`.
#[inline(always)]
fn sqrt_kernel(x: &Chunk, out: &mut Chunk, bad: &mut Lanes) -> bool {
    let mut any = false;
    for i in 0..CHUNK {
        let (a, b) = (x[i].lo, x[i].hi);
        let a_pos = a > 0.0;
        let a1 = if a_pos { a } else { 1.0 };
        let sa = a1.sqrt();
        let sb = b.sqrt();
        let ra = remainder(a1, sa, sa);
        let rb = remainder(b, sb, sb);
        let lo = if a_pos { down(sa, ra) } else { 0.0 };
        out[i] = Interval { lo, hi: up(sb, rb) };
        let ok = (SQRT_LOW..=SQRT_HIGH).contains(&b) & (!a_pos | (a >= SQRT_LOW));
        bad[i] = !ok;
        any |= !ok;
    }
    any
}

// ---------------------------------------------------------------------------------------
// Public operations.
// ---------------------------------------------------------------------------------------

/// `out[i] = xs[i] + ys[i]` (tight, bit-identical to [`Interval::add`]).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `ys` or `out` is not as long as `xs`; `out` is
/// then left untouched.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(1.0, 2.0)?, Interval::new(-1.0, 0.5)?];
/// let ys = [Interval::new(0.1, 0.1)?, Interval::EMPTY];
/// let mut out = [Interval::EMPTY; 2];
/// batch::add(&xs, &ys, &mut out)?;
/// assert_eq!(out[0], xs[0] + ys[0]);
/// assert!(out[1].is_empty());
/// assert!(batch::add(&xs, &ys[..1], &mut out).is_err());
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn add<T: Float>(
    xs: &[Interval<T>],
    ys: &[Interval<T>],
    out: &mut [Interval<T>],
) -> Result<(), IntervalError> {
    map2(
        "batch::add",
        xs,
        ys,
        out,
        |x, y, o, b| add_kernel(x, y, o, b, false),
        Interval::add,
    )
}

/// `out[i] = xs[i] − ys[i]` (tight, bit-identical to [`Interval::sub`]).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `ys` or `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(1.0, 2.0)?];
/// let ys = [Interval::new(0.5, 3.0)?];
/// let mut out = [Interval::EMPTY];
/// batch::sub(&xs, &ys, &mut out)?;
/// assert_eq!(out[0], Interval::new(-2.0, 1.5)?);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn sub<T: Float>(
    xs: &[Interval<T>],
    ys: &[Interval<T>],
    out: &mut [Interval<T>],
) -> Result<(), IntervalError> {
    map2(
        "batch::sub",
        xs,
        ys,
        out,
        |x, y, o, b| add_kernel(x, y, o, b, true),
        Interval::sub,
    )
}

/// `out[i] = xs[i] · ys[i]` (tight, bit-identical to [`Interval::mul`]).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `ys` or `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = vec![Interval::new(-1.0, 2.0)?; 100];
/// let ys = vec![Interval::new(-3.0, 0.1)?; 100];
/// let mut out = vec![Interval::EMPTY; 100];
/// batch::mul(&xs, &ys, &mut out)?;
/// assert!(out.iter().all(|z| *z == xs[0] * ys[0]));
/// assert_eq!(out[0].inf(), -6.0);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn mul<T: Float>(
    xs: &[Interval<T>],
    ys: &[Interval<T>],
    out: &mut [Interval<T>],
) -> Result<(), IntervalError> {
    map2("batch::mul", xs, ys, out, mul_kernel, Interval::mul)
}

/// `out[i] = xs[i] / ys[i]` (tight, bit-identical to [`Interval::div`], including the
/// hull semantics when `ys[i]` contains zero).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `ys` or `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs: [Interval; 2] = [Interval::new(1.0, 1.0)?, Interval::new(1.0, 2.0)?];
/// let ys = [Interval::new(3.0, 3.0)?, Interval::new(0.0, 4.0)?];
/// let mut out = [Interval::EMPTY; 2];
/// batch::div(&xs, &ys, &mut out)?;
/// assert_eq!(out[0].sup(), out[0].inf().next_up()); // 1/3, one ulp wide
/// assert_eq!(out[1], Interval::new(0.25, f64::INFINITY)?);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn div<T: Float>(
    xs: &[Interval<T>],
    ys: &[Interval<T>],
    out: &mut [Interval<T>],
) -> Result<(), IntervalError> {
    map2("batch::div", xs, ys, out, div_kernel, Interval::div)
}

/// `out[i] = xs[i]²` (tight, bit-identical to [`Interval::sqr`]).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(-1.0, 2.0)?, Interval::new(-3.0, -2.0)?];
/// let mut out = [Interval::EMPTY; 2];
/// batch::sqr(&xs, &mut out)?;
/// assert_eq!(out, [Interval::new(0.0, 4.0)?, Interval::new(4.0, 9.0)?]);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn sqr<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    map1("batch::sqr", xs, out, sqr_kernel, Interval::sqr)
}

/// `out[i] = √xs[i]` (tight, bit-identical to [`Interval::sqrt`]).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(2.0, 4.0)?, Interval::new(-1.0, 9.0)?, Interval::new(-2.0, -1.0)?];
/// let mut out = [Interval::EMPTY; 3];
/// batch::sqrt(&xs, &mut out)?;
/// assert_eq!(out[0].sup(), 2.0);
/// assert!(out[0].contains(std::f64::consts::SQRT_2));
/// assert_eq!(out[1], Interval::new(0.0, 3.0)?);
/// assert!(out[2].is_empty());
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn sqrt<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    map1("batch::sqrt", xs, out, sqrt_kernel, Interval::sqrt)
}

/// Applies a scalar operation element by element (no fast path).
#[inline(always)]
fn each<T: Float>(
    operation: &'static str,
    xs: &[Interval<T>],
    out: &mut [Interval<T>],
    f: impl Fn(Interval<T>) -> Interval<T>,
) -> Result<(), IntervalError> {
    check_len(operation, "out", xs.len(), out.len())?;
    for (x, o) in xs.iter().zip(out) {
        *o = f(*x);
    }
    Ok(())
}

/// `out[i] = xs[i]ⁿ` (same as [`Interval::pown`]; a loop over the scalar operation).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(-2.0, 3.0)?, Interval::new(0.5, 1.0)?];
/// let mut out = [Interval::EMPTY; 2];
/// batch::pown(&xs, 3, &mut out)?;
/// assert_eq!(out, [Interval::new(-8.0, 27.0)?, Interval::new(0.125, 1.0)?]);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn pown<T: Float>(
    xs: &[Interval<T>],
    n: i32,
    out: &mut [Interval<T>],
) -> Result<(), IntervalError> {
    each("batch::pown", xs, out, |x| x.pown(n))
}

/// `out[i] = exp(xs[i])` (same as [`Interval::exp`]; a loop over the scalar operation).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(0.0, 1.0)?];
/// let mut out = [Interval::EMPTY];
/// batch::exp(&xs, &mut out)?;
/// assert_eq!(out[0].inf(), 1.0);
/// assert!(out[0].contains(std::f64::consts::E));
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn exp<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    each("batch::exp", xs, out, Interval::exp)
}

/// `out[i] = ln(xs[i])` (same as [`Interval::ln`]; a loop over the scalar operation).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(1.0, std::f64::consts::E)?];
/// let mut out = [Interval::EMPTY];
/// batch::ln(&xs, &mut out)?;
/// assert!(out[0].contains(0.0) && out[0].contains(1.0));
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn ln<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    each("batch::ln", xs, out, Interval::ln)
}

/// `out[i] = sin(xs[i])` (same as [`Interval::sin`]; a loop over the scalar operation).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(0.0, 2.0)?, Interval::new(-10.0, 10.0)?];
/// let mut out = [Interval::EMPTY; 2];
/// batch::sin(&xs, &mut out)?;
/// assert_eq!((out[0].inf(), out[0].sup()), (0.0, 1.0));
/// assert_eq!((out[1].inf(), out[1].sup()), (-1.0, 1.0));
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn sin<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    each("batch::sin", xs, out, Interval::sin)
}

/// `out[i] = cos(xs[i])` (same as [`Interval::cos`]; a loop over the scalar operation).
///
/// # Errors
/// [`IntervalError::LengthMismatch`] if `out` is not as long as `xs`.
///
/// ```
/// use interval_core::{Interval, interval::batch};
/// let xs = [Interval::new(-1.0, 1.0)?];
/// let mut out = [Interval::EMPTY];
/// batch::cos(&xs, &mut out)?;
/// assert_eq!(out[0].sup(), 1.0);
/// # Ok::<(), interval_core::IntervalError>(())
/// ```
pub fn cos<T: Float>(xs: &[Interval<T>], out: &mut [Interval<T>]) -> Result<(), IntervalError> {
    each("batch::cos", xs, out, Interval::cos)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn same<T: Float>(a: Interval<T>, b: Interval<T>) -> bool {
        a.lo.to_f64().to_bits() == b.lo.to_f64().to_bits()
            && a.hi.to_f64().to_bits() == b.hi.to_f64().to_bits()
    }

    #[test]
    fn length_mismatch_is_an_error() {
        let xs = [Interval::<f64>::ONE; 3];
        let mut out = [Interval::EMPTY; 3];
        assert_eq!(
            add(&xs, &xs[..2], &mut out),
            Err(IntervalError::LengthMismatch {
                operation: "batch::add",
                argument: "ys",
                expected: 3,
                found: 2
            })
        );
        assert_eq!(
            sqrt(&xs, &mut out[..1]),
            Err(IntervalError::LengthMismatch {
                operation: "batch::sqrt",
                argument: "out",
                expected: 3,
                found: 1
            })
        );
    }

    #[test]
    fn batch_matches_scalar_smoke() {
        let xs: Vec<Interval<f64>> = (0..37)
            .map(|i| Interval::new(i as f64 * 0.1 - 1.3, i as f64 * 0.3 + 0.7).unwrap())
            .collect();
        let ys: Vec<Interval<f64>> = xs.iter().rev().copied().collect();
        let mut out = vec![Interval::EMPTY; xs.len()];
        mul(&xs, &ys, &mut out).unwrap();
        for i in 0..xs.len() {
            assert!(same(out[i], xs[i] * ys[i]), "{i}");
        }
    }
}
