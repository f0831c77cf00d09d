//! Reading intervals from text (IEEE 1788 §12.11 interval literals, the bare-interval part):
//! `"[0.1, 2]"`, `"[1.5]"` (a point), `"[empty]"`, `"[entire]"`, `"[-inf, 3]"`, `"[, 3]"`
//! (an omitted bound is infinite).
//!
//! Decimal bounds are rounded **outward**: the lower bound is the largest value of `T` not
//! above the decimal number, the upper the smallest not below it, so `"[0.1]"` gives the
//! two floats around 1/10 and `"[0.5]"` the point 0.5. The conversion is correct in both
//! directions: the standard library's correctly rounded `f64` parse gives a candidate within
//! one ulp (for `f32`, within one `f32` ulp after the second rounding), and the candidate and
//! its neighbours are then placed against the decimal number by an **exact** comparison
//! (`c · 10^k` against the integer of the digits, in exact dyadic arithmetic), stepping
//! outward only when needed. Errors name the problem and its byte offset; nothing panics.

use super::Interval;
use crate::IntervalError;
use crate::float::Float;
use crate::float::big::BigUint;
use crate::float::dyadic::Dyadic;
use core::cmp::Ordering;
use core::str::FromStr;

/// A parsed decimal number `±digits · 10^exp`, or an infinity.
enum Decimal {
    /// `±∞`.
    Infinite(bool),
    /// `(negative, digits, power of ten)`.
    Finite(bool, BigUint, i64),
}

fn err(position: usize, reason: &'static str) -> IntervalError {
    IntervalError::Parse { position, reason }
}

/// Reads a decimal number (`[+-] digits [. digits] [(e|E) [+-] digits]`, or `inf`,
/// `infinity` with an optional sign); `at` is the text's offset for messages.
fn read_decimal(text: &str, at: usize) -> Result<Decimal, IntervalError> {
    let t = text.trim();
    let at = at + (text.len() - text.trim_start().len());
    let (neg, body) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let lower = body.to_ascii_lowercase();
    if lower == "inf" || lower == "infinity" {
        return Ok(Decimal::Infinite(neg));
    }
    let (mantissa, exponent) = match body.find(['e', 'E']) {
        Some(i) => (&body[..i], Some(&body[i + 1..])),
        None => (body, None),
    };
    let mut digits = BigUint::zero();
    let mut exp: i64 = 0;
    let mut seen_digit = false;
    let mut seen_point = false;
    for (i, ch) in mantissa.char_indices() {
        match ch {
            '0'..='9' => {
                seen_digit = true;
                digits = digits
                    .mul_small(10)
                    .add(&BigUint::from_u64(u64::from(ch as u32 - '0' as u32)));
                if seen_point {
                    exp -= 1;
                }
            }
            '.' if !seen_point => seen_point = true,
            _ => {
                let offset = at + (t.len() - body.len()) + i;
                return Err(err(offset, "unexpected character in a number"));
            }
        }
    }
    if !seen_digit {
        return Err(err(at, "expected a number"));
    }
    if let Some(e) = exponent {
        let k: i64 = e.parse().map_err(|_| {
            err(
                at + (t.len() - body.len()) + mantissa.len() + 1,
                "bad exponent",
            )
        })?;
        exp = exp.saturating_add(k);
    }
    Ok(Decimal::Finite(neg, digits, exp))
}

/// The exact order of the finite float `c` against `±digits · 10^exp`.
fn cmp_decimal(c: f64, neg: bool, digits: &BigUint, exp: i64) -> Ordering {
    let d = Dyadic::from_parts(neg, digits.clone(), 0);
    let ten_k = |k: u64| Dyadic::from_parts(false, BigUint::from_u64(5).pow(k), k as i64);
    if exp >= 0 {
        Dyadic::of(c).cmp(&d.mul(&ten_k(exp as u64)))
    } else {
        Dyadic::of(c).mul(&ten_k(exp.unsigned_abs())).cmp(&d)
    }
}

/// The tightest bounds `(lo, hi)` in `T` of the decimal number `text` (already validated as
/// `Decimal::Finite`).
fn enclose<T: Float>(text: &str, neg: bool, digits: &BigUint, exp: i64) -> (T, T) {
    if digits.is_zero() {
        return (T::ZERO, T::ZERO);
    }
    let nearest: f64 = text.trim().parse().unwrap_or(f64::NAN);
    let sign = |x: T| if neg { -x } else { x };
    // Out of the f64 range: the parse rounded to 0 or ∞; the decimal lies strictly
    // between 0 and the smallest subnormal, or beyond MAX (f64's, hence T's too).
    if nearest == 0.0 {
        let (a, b) = (T::ZERO, T::MIN_POSITIVE_SUBNORMAL);
        return if neg { (-b, -a) } else { (a, b) };
    }
    if nearest.is_infinite() || nearest.is_nan() {
        let (a, b) = (T::MAX, T::INFINITY);
        return if neg { (-b, -a) } else { (a, b) };
    }
    // Work with the magnitude, then restore the sign.
    let mut c = T::from_f64_rn(nearest.abs());
    let vs = |c: T| {
        if c == T::INFINITY {
            Ordering::Greater
        } else {
            cmp_decimal(c.to_f64(), false, digits, exp)
        }
    };
    while vs(c) == Ordering::Greater {
        c = c.next_down();
    }
    while vs(c.next_up()) != Ordering::Greater {
        c = c.next_up();
    }
    let (lo, hi) = if vs(c) == Ordering::Equal {
        (c, c)
    } else {
        (c, c.next_up())
    };
    if neg { (sign(hi), sign(lo)) } else { (lo, hi) }
}

/// Reads one bound; an omitted bound is `default` (an infinity).
fn read_bound<T: Float>(text: &str, at: usize, default: T) -> Result<(T, T), IntervalError> {
    if text.trim().is_empty() {
        return Ok((default, default));
    }
    match read_decimal(text, at)? {
        Decimal::Infinite(neg) => {
            let v = if neg { T::NEG_INFINITY } else { T::INFINITY };
            Ok((v, v))
        }
        Decimal::Finite(neg, digits, exp) => Ok(enclose(text, neg, &digits, exp)),
    }
}

impl<T: Float> Interval<T> {
    /// Reads an interval literal, rounding decimal bounds outward (see the module
    /// documentation): `"[0.1, 2]"`, `"[1.5]"`, `"[empty]"`, `"[entire]"`, `"[-inf, 3]"`,
    /// `"[, 3]"`. Also available as [`str::parse`] through [`FromStr`].
    ///
    /// # Errors
    /// [`IntervalError::Parse`] with the byte offset and the problem for malformed text;
    /// [`IntervalError::Reversed`] or [`IntervalError::InfiniteEndpoint`] for bounds that
    /// make no interval (`"[2, 1]"`, `"[inf, inf]"`).
    ///
    /// ```
    /// use interval_core::Interval;
    /// let x: Interval<f64> = Interval::parse("[0.1, 2]")?;
    /// assert!(x.inf() < 0.1 && x.inf().next_up() == 0.1 && x.sup() == 2.0);
    /// assert_eq!("[1.5]".parse::<Interval<f32>>()?, Interval::point(1.5)?);
    /// assert!(Interval::<f64>::parse("[empty]")?.is_empty());
    /// assert!(Interval::<f64>::parse("[1, x]").is_err());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn parse(text: &str) -> Result<Self, IntervalError> {
        let start = text.len() - text.trim_start().len();
        let t = text.trim();
        let inner = t
            .strip_prefix('[')
            .ok_or_else(|| err(start, "expected '['"))?
            .strip_suffix(']')
            .ok_or_else(|| err(start + t.len(), "expected ']' at the end"))?;
        let at = start + 1;
        let word = inner.trim().to_ascii_lowercase();
        // `[ ]` (nothing between the brackets) is the empty set, as `[empty]`.
        if word == "empty" || word.is_empty() {
            return Ok(Self::EMPTY);
        }
        if word == "entire" {
            return Ok(Self::ENTIRE);
        }
        let (lo, hi) = match inner.find(',') {
            None => read_bound(inner, at, T::ZERO)?,
            Some(i) => {
                let (l, _) = read_bound(&inner[..i], at, T::NEG_INFINITY)?;
                let (_, h) = read_bound(&inner[i + 1..], at + i + 1, T::INFINITY)?;
                (l, h)
            }
        };
        Self::new(lo, hi)
    }
}

impl<T: Float> FromStr for Interval<T> {
    type Err = IntervalError;
    /// [`Interval::parse`].
    fn from_str(s: &str) -> Result<Self, IntervalError> {
        Self::parse(s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Interval<f64> {
        Interval::parse(s).unwrap()
    }

    #[test]
    fn literals() {
        let inf = f64::INFINITY;
        assert_eq!(
            p("[0.1, 2]"),
            Interval::new(0.1f64.next_down(), 2.0).unwrap()
        );
        assert_eq!(p("[0.1]"), Interval::new(0.1f64.next_down(), 0.1).unwrap());
        assert_eq!(
            p(" [ -0.1 ] "),
            Interval::new(-0.1, -0.1f64.next_down()).unwrap()
        );
        assert_eq!(p("[1.5]"), Interval::new(1.5, 1.5).unwrap());
        assert!(p("[empty]").is_empty() && p("[ Entire ]").is_entire());
        assert_eq!(p("[-inf, 3]"), Interval::new(-inf, 3.0).unwrap());
        assert_eq!(p("[, 3]"), Interval::new(-inf, 3.0).unwrap());
        assert_eq!(p("[3,]"), Interval::new(3.0, inf).unwrap());
        assert_eq!(
            p("[1e400]"),
            Interval::new(f64::MAX, inf).unwrap_or(Interval::EMPTY)
        );
        assert_eq!(p("[1e-400]"), Interval::new(0.0, 5e-324).unwrap());
        assert_eq!(p("[-0]"), Interval::new(0.0, 0.0).unwrap());
        assert_eq!(p("[2.5e-324]"), Interval::new(0.0, 5e-324).unwrap());
        assert_eq!(p("[4.9406564584124654e-324]").sup(), 5e-324);
        let third: Interval<f32> = "[0.333333333333333333333333]".parse().unwrap();
        assert_eq!(third.sup(), third.inf().next_up());
        assert!(third.contains(1.0 / 3.0) || third.inf() < 1.0 / 3.0);
    }

    #[test]
    fn errors_name_the_problem() {
        let e = |s: &str| Interval::<f64>::parse(s).unwrap_err();
        assert!(matches!(
            e("1, 2"),
            IntervalError::Parse { position: 0, .. }
        ));
        assert!(matches!(e("[1, 2"), IntervalError::Parse { .. }));
        assert!(matches!(
            e("[1, x]"),
            IntervalError::Parse { position: 4, .. }
        ));
        assert!(p("[]").is_empty() && p("[ ]").is_empty());
        assert!(matches!(e("[1e]"), IntervalError::Parse { .. }));
        assert!(matches!(e("[2, 1]"), IntervalError::Reversed { .. }));
        assert!(matches!(e("[inf]"), IntervalError::InfiniteEndpoint { .. }));
        assert!(matches!(e("[nan]"), IntervalError::Parse { .. }));
    }
}
