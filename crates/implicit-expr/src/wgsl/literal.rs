//! `f32` values written as WGSL text that denotes exactly that value, and the outward
//! rounding of `f64` enclosures to `f32` ones.

use interval_core::Float;

/// The most significant digits a decimal literal may have; values that need more are written
/// as bit patterns.
const MAX_DIGITS: usize = 12;

/// A WGSL expression of type `f32` whose value is exactly `v`.
///
/// Values whose exact decimal expansion is short (`0.5`, `3`, `-1.25`, `1024`) are written
/// as decimal literals with the `f` suffix (`0.5f`); every other value as a hexadecimal
/// float literal, whose digits are the value's bits (`0x1.99999ap-4f` for the `f32`
/// nearest 0.1). Both denote the value exactly: WGSL lets an implementation round a literal
/// that is not exactly representable to either neighbour, so only exactly representable
/// numbers are ever written. Both are literals, so the result is a constant expression
/// (usable in `const` declarations). Both zeros are written `0.0f`.
///
/// Returns `None` for NaN and the infinities, which WGSL cannot write (a constant expression
/// that evaluates to one is a shader-creation error).
pub fn f32_literal(v: f32) -> Option<String> {
    if !v.is_finite() {
        return None;
    }
    if v == 0.0 {
        return Some("0.0f".into());
    }
    Some(match exact_decimal(v) {
        Some(text) => text,
        None => hex_float(v),
    })
}

/// The hexadecimal float literal `±0x1.<hex digits>p<exponent>f` of a finite nonzero `v`.
fn hex_float(v: f32) -> String {
    let (negative, mut m, mut e) = parts(v);
    while m & 1 == 0 {
        m >>= 1;
        e += 1;
    }
    // v = ±m · 2^e with m odd; written as 1.f · 2^(e + bits - 1).
    let bits = 128 - m.leading_zeros() as i32;
    let exponent = e + bits - 1;
    let fraction_bits = bits - 1;
    let sign = if negative { "-" } else { "" };
    if fraction_bits == 0 {
        return format!("{sign}0x1p{exponent}f");
    }
    let digits = (fraction_bits + 3) / 4;
    let fraction = (m & ((1u128 << fraction_bits) - 1)) << (4 * digits - fraction_bits);
    format!(
        "{sign}0x1.{fraction:0width$x}p{exponent}f",
        width = digits as usize
    )
}

/// `v = ±m · 2^e` for a finite `v`, with the integer `m` of its bits.
fn parts(v: f32) -> (bool, u128, i32) {
    let bits = v.to_bits();
    let negative = bits >> 31 == 1;
    let biased = ((bits >> 23) & 0xff) as i32;
    let fraction = bits & 0x7f_ffff;
    if biased == 0 {
        (negative, u128::from(fraction), -149)
    } else {
        (negative, u128::from(fraction | 0x80_0000), biased - 150)
    }
}

/// The exact decimal expansion of a finite nonzero `v` with the `f` suffix, when it has at
/// most [`MAX_DIGITS`] significant digits.
fn exact_decimal(v: f32) -> Option<String> {
    // v = ±m · 2^e with an integer m.
    let (negative, mut m, mut e) = parts(v);
    if m == 0 {
        return None;
    }
    while m & 1 == 0 {
        m >>= 1;
        e += 1;
    }
    let (int_part, frac_part) = if e >= 0 {
        // m < 2^24 and e <= 104: the integer m · 2^e fits a u128.
        ((m << e).to_string(), String::new())
    } else {
        // m · 2^-k = m · 5^k / 10^k, exactly; the last digit is 5 (m and 5^k are odd), so
        // the expansion has exactly k digits after the point.
        let k = (-e) as u32;
        let power = 5u128.checked_pow(k)?;
        let digits = m.checked_mul(power)?.to_string();
        let k = k as usize;
        let padded = if digits.len() <= k {
            format!("{}{digits}", "0".repeat(k + 1 - digits.len()))
        } else {
            digits
        };
        let split = padded.len() - k;
        (padded[..split].to_string(), padded[split..].to_string())
    };
    let all: String = format!("{int_part}{frac_part}");
    let significant = all.trim_start_matches('0').trim_end_matches('0').len();
    if significant > MAX_DIGITS || int_part.len() > MAX_DIGITS + 4 {
        return None;
    }
    let frac_part = if frac_part.is_empty() {
        "0".to_string()
    } else {
        frac_part
    };
    let sign = if negative { "-" } else { "" };
    Some(format!("{sign}{int_part}.{frac_part}f"))
}

/// The `f32` enclosure `[lo', hi']` of the `f64` interval `[lo, hi]` that the generated code
/// uses for constants: `lo'` is the largest `f32` `<= lo`, `hi'` the smallest `>= hi`,
/// except that neither bound is ever subnormal, so the enclosure stays sound on hardware
/// that flushes subnormals to zero. A subnormal bound moves outward to zero or to
/// `±f32::MIN_POSITIVE` (the smallest normal), and a zero bound is `+0.0`.
///
/// A bound beyond the `f32` range becomes an infinity (`lo < -f32::MAX` gives `-inf`,
/// `hi > f32::MAX` gives `+inf`).
pub fn enclose_f32(lo: f64, hi: f64) -> (f32, f32) {
    let mut l = <f32 as Float>::from_f64_down(lo);
    let mut h = <f32 as Float>::from_f64_up(hi);
    if l != 0.0 && l.abs() < f32::MIN_POSITIVE {
        l = if l > 0.0 { 0.0 } else { -f32::MIN_POSITIVE };
    }
    if h != 0.0 && h.abs() < f32::MIN_POSITIVE {
        h = if h < 0.0 { 0.0 } else { f32::MIN_POSITIVE };
    }
    // Both zeros are +0.0.
    (l + 0.0, h + 0.0)
}

/// The `f32` a point evaluation uses for the `f64` value `v`: the nearest one, clamped to the
/// finite range (WGSL cannot write an infinity).
pub(crate) fn point_f32(v: f64) -> f32 {
    let r = v as f32;
    if r.is_finite() {
        r
    } else if r > 0.0 {
        f32::MAX
    } else {
        f32::MIN
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals() {
        assert_eq!(f32_literal(0.5).unwrap(), "0.5f");
        assert_eq!(f32_literal(3.0).unwrap(), "3.0f");
        assert_eq!(f32_literal(-1.25).unwrap(), "-1.25f");
        assert_eq!(f32_literal(1024.0).unwrap(), "1024.0f");
        assert_eq!(f32_literal(0.0).unwrap(), "0.0f");
        assert_eq!(f32_literal(-0.0).unwrap(), "0.0f");
        assert_eq!(f32_literal(0.1).unwrap(), "0x1.99999ap-4f");
        assert_eq!(f32_literal(-0.1).unwrap(), "-0x1.99999ap-4f");
        assert_eq!(f32_literal(f32::MAX).unwrap(), "0x1.fffffep127f");
        assert_eq!(f32_literal(f32::MIN_POSITIVE).unwrap(), "0x1p-126f");
        assert_eq!(f32_literal(1e-45).unwrap(), "0x1p-149f");
        assert_eq!(f32_literal(1.0 + f32::EPSILON).unwrap(), "0x1.000002p0f");
        assert_eq!(f32_literal(3.0 * 2f32.powi(40)).unwrap(), "0x1.8p41f");
        assert_eq!(f32_literal(0.000_976_562_5).unwrap(), "0.0009765625f");
        assert!(f32_literal(f32::INFINITY).is_none());
        assert!(f32_literal(f32::NAN).is_none());
    }

    #[test]
    fn decimal_literals_are_exact() {
        let mut v = 1.0f32;
        for i in 0..200_000u32 {
            // A spread of values: small dyadics, integers, and arbitrary bit patterns.
            let x = match i % 3 {
                0 => (i as f32) / 64.0 - 1000.0,
                1 => f32::from_bits(i.wrapping_mul(2_654_435_761)),
                _ => {
                    v = v * 1.5 + 0.25;
                    if !v.is_finite() {
                        v = 1.0;
                    }
                    v
                }
            };
            if let Some(t) = f32_literal(x)
                && !t.contains("0x")
                && let Some(d) = t.strip_suffix('f')
            {
                // Rust parses correctly rounded; exactness means the nearest f32 is x and
                // the f64 parse (exact for these short expansions) is x too.
                assert_eq!(d.parse::<f32>().unwrap(), x + 0.0, "{t}");
                assert_eq!(d.parse::<f64>().unwrap(), f64::from(x + 0.0), "{t}");
            }
        }
    }

    /// Reads a literal of [`f32_literal`] back, exactly.
    fn read(text: &str) -> f64 {
        let t = text.strip_suffix('f').unwrap();
        let (negative, t) = match t.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, t),
        };
        let v = match t.strip_prefix("0x1") {
            Some(hex) => {
                let (frac, exp) = hex.split_once('p').unwrap();
                let frac = frac.strip_prefix('.').unwrap_or("");
                let mut m = 1.0f64;
                for (i, d) in frac.chars().enumerate() {
                    m += f64::from(d.to_digit(16).unwrap()) * 16f64.powi(-(i as i32 + 1));
                }
                m * 2f64.powi(exp.parse().unwrap())
            }
            None => t.parse().unwrap(),
        };
        if negative { -v } else { v }
    }

    #[test]
    fn hex_literals_are_exact() {
        let mut x = 0x9e37_79b9u32;
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            let v = f32::from_bits(x);
            if v.is_finite() {
                let t = f32_literal(v).unwrap();
                assert_eq!(read(&t), f64::from(v + 0.0), "{t}");
            }
        }
    }

    #[test]
    fn enclosures_are_outward_and_normal() {
        let tiny = f64::from(f32::MIN_POSITIVE) / 8.0;
        assert_eq!(enclose_f32(tiny, tiny), (0.0, f32::MIN_POSITIVE));
        assert_eq!(enclose_f32(-tiny, -tiny), (-f32::MIN_POSITIVE, 0.0));
        assert_eq!(enclose_f32(-0.0, -0.0), (0.0, 0.0));
        assert_eq!(enclose_f32(0.1, 0.1), (0.099_999_994, 0.1));
        assert_eq!(
            enclose_f32(-1e300, 1e300),
            (f32::NEG_INFINITY, f32::INFINITY)
        );
        assert_eq!(enclose_f32(1e300, 1e300), (f32::MAX, f32::INFINITY));
        assert_eq!(enclose_f32(1.5, 2.0), (1.5, 2.0));
        assert!(enclose_f32(-0.0, 0.0).0.is_sign_positive());
    }

    #[test]
    fn point_values_are_finite() {
        assert_eq!(point_f32(1e300), f32::MAX);
        assert_eq!(point_f32(-1e300), f32::MIN);
        assert_eq!(point_f32(0.1), 0.1f32);
    }
}
