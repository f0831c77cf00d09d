//! [`Dd`]: a double-double number, the unevaluated sum of two `f64`.

use core::cmp::Ordering;
use core::fmt;
use core::ops::Neg;

use crate::float::two_sum;

/// A double-double number: the exact sum `hi + lo` of two `f64`, normalised so that
/// `hi = RN(hi + lo)` (then `|lo| ≤ ulp(hi) / 2`), which gives about 106 significant bits.
///
/// Infinite values have `lo = 0`. Values are compared exactly (lexicographically by `hi`,
/// then `lo`, which is the order of the sums for normalised pairs).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Dd {
    hi: f64,
    lo: f64,
}

impl Dd {
    /// 0.
    pub const ZERO: Self = Self { hi: 0.0, lo: 0.0 };
    /// +∞.
    pub const INFINITY: Self = Self {
        hi: f64::INFINITY,
        lo: 0.0,
    };
    /// −∞.
    pub const NEG_INFINITY: Self = Self {
        hi: f64::NEG_INFINITY,
        lo: 0.0,
    };

    /// The `f64` `x`, exactly.
    pub const fn from_f64(x: f64) -> Self {
        Self { hi: x, lo: 0.0 }
    }

    /// The exact sum `a + b` as a normalised pair (`None` if it overflows or is NaN).
    pub fn from_sum(a: f64, b: f64) -> Option<Self> {
        let (hi, lo) = two_sum(a, b);
        (hi.is_finite() && lo.is_finite()).then_some(Self { hi, lo })
    }

    /// The leading part: `RN(hi + lo)`.
    pub const fn hi(self) -> f64 {
        self.hi
    }

    /// The trailing part.
    pub const fn lo(self) -> f64 {
        self.lo
    }

    /// Whether the value is finite.
    pub fn is_finite(self) -> bool {
        self.hi.is_finite()
    }

    /// The largest `f64` not above the value.
    pub fn to_f64_down(self) -> f64 {
        if self.lo < 0.0 {
            self.hi.next_down()
        } else {
            self.hi
        }
    }

    /// The smallest `f64` not below the value.
    pub fn to_f64_up(self) -> f64 {
        if self.lo > 0.0 {
            self.hi.next_up()
        } else {
            self.hi
        }
    }

    /// The sign of the value: `-1`, `0` or `1` (`0` for NaN).
    pub fn signum(self) -> i8 {
        if self.hi > 0.0 {
            1
        } else if self.hi < 0.0 {
            -1
        } else {
            0
        }
    }
}

impl Neg for Dd {
    type Output = Self;

    /// `-self`, exactly.
    fn neg(self) -> Self {
        Self {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl PartialOrd for Dd {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        match self.hi.partial_cmp(&other.hi)? {
            Ordering::Equal => self.lo.partial_cmp(&other.lo),
            o => Some(o),
        }
    }
}

impl fmt::Display for Dd {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.lo == 0.0 {
            write!(f, "{:e}", self.hi)
        } else {
            write!(f, "{:e} + {:e}", self.hi, self.lo)
        }
    }
}
