//! Formatting: `[inf, sup]`, `[empty]` and `[entire]` as in IEEE 1788's interval literals.
//!
//! The `Display` impl forwards the format options (precision, `{:e}`) to both bounds. The
//! printed decimals are the stored bounds rounded to nearest by the formatter, so with a
//! reduced precision the text may not enclose the interval; use the full default precision
//! (shortest round-trip digits) when the text must be re-read exactly.

use super::Interval;
use crate::float::Float;
use core::fmt;

impl<T: Float> fmt::Display for Interval<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("[empty]");
        }
        if self.is_entire() {
            return f.write_str("[entire]");
        }
        f.write_str("[")?;
        fmt::Display::fmt(&self.lo, f)?;
        f.write_str(", ")?;
        fmt::Display::fmt(&self.hi, f)?;
        f.write_str("]")
    }
}

impl<T: Float> fmt::LowerExp for Interval<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("[empty]");
        }
        f.write_str("[")?;
        fmt::LowerExp::fmt(&self.lo, f)?;
        f.write_str(", ")?;
        fmt::LowerExp::fmt(&self.hi, f)?;
        f.write_str("]")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals() {
        assert_eq!(Interval::<f64>::EMPTY.to_string(), "[empty]");
        assert_eq!(Interval::<f64>::ENTIRE.to_string(), "[entire]");
        assert_eq!(Interval::new(1.0, 2.5).unwrap().to_string(), "[1, 2.5]");
        assert_eq!(
            format!("{:.2}", Interval::new(1.0f32, 2.5).unwrap()),
            "[1.00, 2.50]"
        );
    }
}
