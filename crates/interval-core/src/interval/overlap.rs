//! The interval overlapping relation (IEEE 1788 §10.6.4, Allen's interval algebra): which of
//! the 13 relative positions two nonempty intervals are in, plus the three empty cases.

use super::Interval;
use crate::float::Float;

/// The relative position of two intervals `x = [a, b]` and `y = [c, d]` (IEEE 1788 Table
/// 10.7). The thirteen states for nonempty intervals are mutually exclusive and cover every
/// pair; the conditions are those of the standard.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Overlap {
    /// Both intervals are empty.
    BothEmpty,
    /// `x` is empty, `y` is not.
    FirstEmpty,
    /// `y` is empty, `x` is not.
    SecondEmpty,
    /// `b < c`.
    Before,
    /// `a < b = c < d`.
    Meets,
    /// `a < c < b < d`.
    Overlaps,
    /// `a = c`, `b < d`.
    Starts,
    /// `c < a`, `b < d`.
    ContainedBy,
    /// `c < a`, `b = d`.
    Finishes,
    /// `a = c`, `b = d`.
    Equals,
    /// `a < c`, `b = d`.
    FinishedBy,
    /// `a < c`, `d < b`.
    Contains,
    /// `a = c`, `d < b`.
    StartedBy,
    /// `c < a < d < b`.
    OverlappedBy,
    /// `c < d = a < b`.
    MetBy,
    /// `d < a`.
    After,
}

impl<T: Float> Interval<T> {
    /// The overlapping state of `self` and `y` (IEEE 1788 `overlap`). Exact.
    ///
    /// ```
    /// use interval_core::Interval;
    /// use interval_core::Overlap;
    /// let x = Interval::new(1.0, 2.0)?;
    /// assert_eq!(x.overlap(Interval::new(2.0, 3.0)?), Overlap::Meets);
    /// assert_eq!(x.overlap(Interval::new(0.0, 3.0)?), Overlap::ContainedBy);
    /// assert_eq!(Interval::new(1.0, 1.0)?.overlap(x), Overlap::Starts);
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn overlap(self, y: Self) -> Overlap {
        match (self.bounds(), y.bounds()) {
            (None, None) => Overlap::BothEmpty,
            (None, Some(_)) => Overlap::FirstEmpty,
            (Some(_), None) => Overlap::SecondEmpty,
            (Some((a, b)), Some((c, d))) => {
                if b < c {
                    Overlap::Before
                } else if d < a {
                    Overlap::After
                } else if a == c && b == d {
                    Overlap::Equals
                } else if a == c {
                    if b < d {
                        Overlap::Starts
                    } else {
                        Overlap::StartedBy
                    }
                } else if b == d {
                    if c < a {
                        Overlap::Finishes
                    } else {
                        Overlap::FinishedBy
                    }
                } else if b == c {
                    Overlap::Meets
                } else if a == d {
                    Overlap::MetBy
                } else if a < c {
                    if d < b {
                        Overlap::Contains
                    } else {
                        Overlap::Overlaps
                    }
                } else if b < d {
                    Overlap::ContainedBy
                } else {
                    Overlap::OverlappedBy
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new(a, b).unwrap()
    }

    #[test]
    fn standard_table() {
        use Overlap::*;
        let e = Interval::<f64>::EMPTY;
        let inf = f64::INFINITY;
        let cases = [
            (e, e, BothEmpty),
            (e, iv(1.0, 2.0), FirstEmpty),
            (iv(1.0, 2.0), e, SecondEmpty),
            (iv(1.0, 2.0), iv(3.0, 4.0), Before),
            (iv(1.0, 1.0), iv(3.0, 4.0), Before),
            (iv(1.0, 2.0), iv(2.0, 4.0), Meets),
            (iv(1.0, 3.0), iv(2.0, 4.0), Overlaps),
            (iv(1.0, 2.0), iv(1.0, 4.0), Starts),
            (iv(1.0, 1.0), iv(1.0, 4.0), Starts),
            (iv(2.0, 3.0), iv(1.0, 4.0), ContainedBy),
            (iv(2.0, 2.0), iv(1.0, 4.0), ContainedBy),
            (iv(2.0, 4.0), iv(1.0, 4.0), Finishes),
            (iv(4.0, 4.0), iv(1.0, 4.0), Finishes),
            (iv(1.0, 4.0), iv(1.0, 4.0), Equals),
            (iv(2.0, 2.0), iv(2.0, 2.0), Equals),
            (iv(1.0, 4.0), iv(2.0, 4.0), FinishedBy),
            (iv(1.0, 4.0), iv(4.0, 4.0), FinishedBy),
            (iv(1.0, 4.0), iv(2.0, 3.0), Contains),
            (iv(1.0, 4.0), iv(1.0, 2.0), StartedBy),
            (iv(1.0, 4.0), iv(1.0, 1.0), StartedBy),
            (iv(2.0, 4.0), iv(1.0, 3.0), OverlappedBy),
            (iv(2.0, 4.0), iv(1.0, 2.0), MetBy),
            (iv(3.0, 4.0), iv(1.0, 2.0), After),
            (Interval::ENTIRE, Interval::ENTIRE, Equals),
            (iv(-inf, 0.0), Interval::ENTIRE, Starts),
        ];
        for (x, y, want) in cases {
            assert_eq!(x.overlap(y), want, "overlap({x}, {y})");
        }
    }
}
