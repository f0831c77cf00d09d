//! Constants of the graph: a value for point evaluation and a tight enclosure of the real
//! number it stands for, so that interval evaluation stays sound for literals such as `0.1`
//! or `pi` that no float represents.

use std::hash::{Hash, Hasher};

use interval_core::{Float, Interval};

/// A real constant: `value` is the float used by point evaluators (the literal rounded to
/// nearest), `[lo, hi]` encloses the real number. `lo == hi == value` when it is exact.
#[derive(Copy, Clone, Debug)]
pub struct Constant {
    value: f64,
    lo: f64,
    hi: f64,
}

impl Constant {
    /// The exact constant 0.
    pub const ZERO: Constant = Constant {
        value: 0.0,
        lo: 0.0,
        hi: 0.0,
    };

    /// The exact constant 1.
    pub const ONE: Constant = Constant {
        value: 1.0,
        lo: 1.0,
        hi: 1.0,
    };

    /// An exactly representable constant.
    ///
    /// Returns `None` for NaN or an infinity (the graph holds only finite constants).
    pub fn exact(value: f64) -> Option<Self> {
        let value = plus_zero(value);
        value.is_finite().then_some(Self {
            value,
            lo: value,
            hi: value,
        })
    }

    /// A constant known only by an enclosure `[lo, hi]` and a nearest float `value` inside it.
    ///
    /// Returns `None` unless `lo <= value <= hi` are all finite.
    pub fn enclosed(value: f64, lo: f64, hi: f64) -> Option<Self> {
        let (value, lo, hi) = (plus_zero(value), plus_zero(lo), plus_zero(hi));
        let ok =
            value.is_finite() && lo.is_finite() && hi.is_finite() && lo <= value && value <= hi;
        ok.then_some(Self { value, lo, hi })
    }

    /// π, enclosed by the two doubles around it.
    pub fn pi() -> Self {
        let v = std::f64::consts::PI; // below π
        Self {
            value: v,
            lo: v,
            hi: Float::next_up(v),
        }
    }

    /// Euler's number e, enclosed by the two doubles around it.
    pub fn e() -> Self {
        let v = std::f64::consts::E; // below e
        Self {
            value: v,
            lo: v,
            hi: Float::next_up(v),
        }
    }

    /// The constant a decimal literal denotes (`12`, `0.1`, `1.5e-3`, `.5`, `2.`).
    ///
    /// The value is the literal rounded to nearest. When the literal is not exactly a double,
    /// the enclosure is the pair of doubles around that value. Returns `None` when the text
    /// is not a decimal literal or its value overflows.
    pub fn from_decimal(text: &str) -> Option<Self> {
        let value: f64 = text.parse().ok()?;
        if !value.is_finite() || text.contains(['i', 'I', 'n', 'N']) {
            return None;
        }
        if decimal_is_exact(text, value) {
            return Self::exact(value);
        }
        Some(Self {
            value,
            lo: Float::next_down(value),
            hi: Float::next_up(value),
        })
    }

    /// The float used by point evaluators.
    pub fn value(&self) -> f64 {
        self.value
    }

    /// Lower bound of the real constant.
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// Upper bound of the real constant.
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// Whether the constant is exactly `value`.
    pub fn is_exact(&self) -> bool {
        self.lo == self.hi
    }

    /// Whether the constant is exactly `v`.
    pub fn is(&self, v: f64) -> bool {
        self.is_exact() && self.value == v
    }

    /// The enclosure as an interval.
    pub fn interval(&self) -> Interval<f64> {
        Interval::new_unchecked(self.lo, self.hi)
    }

    /// The exact integer value, when the constant is one and fits an `i32`.
    pub fn as_i32(&self) -> Option<i32> {
        let v = self.value;
        (self.is_exact() && v.fract() == 0.0 && v.abs() <= f64::from(i32::MAX)).then_some(v as i32)
    }
}

/// Zeros are stored as `+0` so that `0` and `-0` are one constant of the graph.
fn plus_zero(x: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x }
}

impl PartialEq for Constant {
    fn eq(&self, other: &Self) -> bool {
        self.value.to_bits() == other.value.to_bits()
            && self.lo.to_bits() == other.lo.to_bits()
            && self.hi.to_bits() == other.hi.to_bits()
    }
}

impl Eq for Constant {}

impl Hash for Constant {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.value.to_bits().hash(state);
        self.lo.to_bits().hash(state);
        self.hi.to_bits().hash(state);
    }
}

/// Whether the decimal literal `text` equals the double `value` (its nearest double) exactly.
///
/// Writes the literal as `d · 10^k` with an integer `d` and checks `d · 10^k = value` with
/// exact integer and power-of-two arithmetic. Answers `false` when the digits do not fit the
/// check (a safe answer: the constant then gets a one-ulp enclosure).
fn decimal_is_exact(text: &str, value: f64) -> bool {
    let text = text.strip_prefix(['+', '-']).unwrap_or(text);
    let value = value.abs();
    let (mantissa, exp_part) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], &text[i + 1..]),
        None => (text, ""),
    };
    let exp10: i64 = if exp_part.is_empty() {
        0
    } else {
        match exp_part.parse() {
            Ok(e) => e,
            Err(_) => return false,
        }
    };
    let (int_part, frac_part) = match mantissa.find('.') {
        Some(i) => (&mantissa[..i], &mantissa[i + 1..]),
        None => (mantissa, ""),
    };
    let mut digits: String = int_part.chars().chain(frac_part.chars()).collect();
    let mut k = exp10 - frac_part.len() as i64;
    let trimmed = digits.trim_start_matches('0').to_string();
    digits = trimmed;
    if digits.is_empty() {
        return value == 0.0;
    }
    while digits.ends_with('0') {
        digits.pop();
        k += 1;
    }
    if digits.len() > 38 {
        return false;
    }
    let Ok(mut d) = digits.parse::<u128>() else {
        return false;
    };
    // d · 10^k = d · 5^k · 2^k; fold the power of five into d (multiply or divide exactly).
    if k >= 0 {
        for _ in 0..k {
            match d.checked_mul(5) {
                Some(v) => d = v,
                None => return false,
            }
        }
    } else {
        for _ in 0..(-k) {
            if d % 5 != 0 {
                return false;
            }
            d /= 5;
        }
    }
    // Now the literal is d · 2^k; d must be a double exactly.
    let odd = d >> d.trailing_zeros();
    if odd >= (1u128 << 53) {
        return false;
    }
    let df = d as f64; // exact: odd part below 2^53, value below 2^128
    if k.abs() > 1100 {
        return false;
    }
    // value · 2^-k == d, where scaling by a power of two is exact unless it under/overflows
    // (which a mismatch then reveals).
    let mut v = value;
    let mut e = -k;
    while e != 0 {
        let step = e.clamp(-1000, 1000);
        v *= 2f64.powi(step as i32);
        e -= step;
    }
    v == df
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_literals() {
        for s in [
            "0", "-0.5", "+2", "-0", "0.0", "1", "1.5", "0.25", "2.", ".5", "1e3", "1.25e-1",
            "3e10", "0.0625",
        ] {
            let c = Constant::from_decimal(s).unwrap();
            assert!(c.is_exact(), "{s}");
        }
    }

    #[test]
    fn inexact_literals_are_enclosed() {
        for s in [
            "0.1",
            "0.3",
            "1e-5",
            "3.14159",
            "1e23",
            "123456789012345678901234567890",
        ] {
            let c = Constant::from_decimal(s).unwrap();
            assert!(!c.is_exact(), "{s}");
            assert!(c.lo() < c.value() && c.value() < c.hi(), "{s}");
        }
    }

    #[test]
    fn pi_and_e_enclosed() {
        let p = Constant::pi();
        assert!(p.lo() < p.hi());
        assert!(p.interval().contains(std::f64::consts::PI));
        let e = Constant::e();
        assert!(e.interval().contains(std::f64::consts::E));
    }

    #[test]
    fn bad_literals() {
        assert!(Constant::from_decimal("inf").is_none());
        assert!(Constant::from_decimal("nan").is_none());
        assert!(Constant::from_decimal("1e400").is_none());
        assert!(Constant::from_decimal("abc").is_none());
    }
}
