//! Decorated intervals (IEEE 1788-2015 §8, §11): an [`Interval`] paired with a
//! [`Decoration`] that records what is known about the evaluation that produced it — whether
//! every operation was defined, continuous and bounded on its whole argument box.
//!
//! The decorations form a chain `Ill < Trv < Def < Dac < Com`:
//!
//! | decoration | meaning for `y = f(x)` over the box `x` |
//! |---|---|
//! | `com` | `f` is defined and continuous on `x`, `x` and the result are bounded and nonempty |
//! | `dac` | `f` is defined and continuous on `x` (the result may be unbounded or overflow) |
//! | `def` | `f` is defined on `x` (possibly discontinuous: `floor` at a jump, `atan2` on its cut) |
//! | `trv` | nothing is known (`f` may be undefined on part of `x`: `sqrt([−1, 4])`) |
//! | `ill` | not an interval (NaI), from an invalid construction |
//!
//! **Propagation** (§11.7): the result of an operation carries the minimum of the inputs'
//! decorations and the operation's own decoration on the box — `com` where it is defined
//! and continuous with a bounded result, `dac` where defined and continuous but unbounded,
//! `def` where defined but possibly discontinuous, `trv` where possibly undefined on part of
//! the box. A NaI input gives NaI. Set operations (`intersection`, `convex_hull`), the
//! cancellative and the reverse operations give `trv` (they are not point functions). The
//! rules of each operation are in [`rules`]; the operations in [`ops`].
//!
//! ```
//! use interval_core::{DecInterval, Decoration, Interval};
//!
//! let x = DecInterval::new(Interval::new(-1.0, 4.0)?);
//! assert_eq!(x.decoration(), Decoration::Com);
//! let y = x.sqrt();
//! assert_eq!(y.interval(), Interval::new(0.0, 2.0)?);
//! assert_eq!(y.decoration(), Decoration::Trv); // sqrt is undefined on [−1, 0)
//! let z = DecInterval::new(Interval::new(0.5, 1.5)?).floor();
//! assert_eq!(z.decoration(), Decoration::Def); // a jump at 1
//! # Ok::<(), interval_core::IntervalError>(())
//! ```

pub mod ops;
pub mod rules;

use crate::IntervalError;
use crate::float::Float;
use crate::interval::Interval;
use core::fmt;

/// The decoration of an interval (IEEE 1788 §8.2), ordered `Ill < Trv < Def < Dac < Com`
/// (the order of the information it carries).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Decoration {
    /// Ill-formed: not an interval (NaI).
    Ill,
    /// Trivial: nothing is known.
    Trv,
    /// Defined: every operation was defined on its argument box.
    Def,
    /// Defined and continuous on the argument boxes.
    Dac,
    /// Common: defined, continuous and bounded, with bounded nonempty arguments.
    Com,
}

impl fmt::Display for Decoration {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Decoration::Ill => "ill",
            Decoration::Trv => "trv",
            Decoration::Def => "def",
            Decoration::Dac => "dac",
            Decoration::Com => "com",
        })
    }
}

/// A decorated interval (IEEE 1788 §8): an [`Interval`] and a [`Decoration`]. Its invariants
/// are those of the standard: an empty interval is `trv` (or `ill` for NaI), an unbounded one
/// is at most `dac`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecInterval<T: Float = f64> {
    /// The interval part (empty for NaI).
    x: Interval<T>,
    /// Its decoration.
    d: Decoration,
}

impl<T: Float> DecInterval<T> {
    /// NaI, "not an interval": the result of an invalid construction (`ill`).
    pub const NAI: Self = Self {
        x: Interval::EMPTY,
        d: Decoration::Ill,
    };
    /// The empty set, decorated `trv`.
    pub const EMPTY: Self = Self {
        x: Interval::EMPTY,
        d: Decoration::Trv,
    };
    /// `[−∞, +∞]`, decorated `dac`.
    pub const ENTIRE: Self = Self {
        x: Interval::ENTIRE,
        d: Decoration::Dac,
    };

    /// IEEE 1788 `newDec`: the interval with the best decoration it can carry — `com` if
    /// nonempty and bounded, `dac` if unbounded, `trv` if empty.
    pub fn new(x: Interval<T>) -> Self {
        let d = if x.is_empty() {
            Decoration::Trv
        } else if x.is_common_interval() {
            Decoration::Com
        } else {
            Decoration::Dac
        };
        Self { x, d }
    }

    /// IEEE 1788 `setDec`: `x` with the decoration `d`, lowered where the invariants require
    /// it (an empty interval is `trv`, an unbounded one at most `dac`); `ill` gives NaI.
    pub fn set_dec(x: Interval<T>, d: Decoration) -> Self {
        if d == Decoration::Ill {
            return Self::NAI;
        }
        Self {
            x,
            d: d.min(Self::new(x).d),
        }
    }

    /// The interval part (empty for NaI).
    pub fn interval(self) -> Interval<T> {
        self.x
    }

    /// The decoration.
    pub fn decoration(self) -> Decoration {
        self.d
    }

    /// True for NaI.
    pub fn is_nai(self) -> bool {
        self.d == Decoration::Ill
    }

    /// True for an empty interval part (NaI included).
    pub fn is_empty(self) -> bool {
        self.x.is_empty()
    }
}

impl<T: Float> DecInterval<T> {
    /// Reads a decorated interval literal (IEEE 1788 §12.11): a bare literal as in
    /// [`Interval::parse`] followed by `_com`, `_dac`, `_def`, `_trv` or `_ill`, or without a
    /// suffix (then [`DecInterval::new`]); `"[nai]"` is NaI. A decoration the interval cannot
    /// carry (`"[empty]_com"`, `"[1, inf]_com"`) is an error.
    ///
    /// # Errors
    /// [`IntervalError::Parse`] for malformed text or an impossible decoration; the errors of
    /// [`Interval::parse`] for the bounds.
    ///
    /// ```
    /// use interval_core::{DecInterval, Decoration};
    /// let x: DecInterval = DecInterval::parse("[0.1, 2]_def")?;
    /// assert_eq!(x.decoration(), Decoration::Def);
    /// assert!("[1, 2]".parse::<DecInterval<f32>>()?.decoration() == Decoration::Com);
    /// assert!(DecInterval::<f64>::parse("[nai]")?.is_nai());
    /// assert!(DecInterval::<f64>::parse("[empty]_com").is_err());
    /// # Ok::<(), interval_core::IntervalError>(())
    /// ```
    pub fn parse(text: &str) -> Result<Self, IntervalError> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("[nai]") {
            return Ok(Self::NAI);
        }
        let close = t.rfind(']').ok_or(IntervalError::Parse {
            position: text.len(),
            reason: "expected ']'",
        })?;
        let x = Interval::parse(&t[..=close])?;
        let suffix = &t[close + 1..];
        let d = match suffix.to_ascii_lowercase().as_str() {
            "" => return Ok(Self::new(x)),
            "_com" => Decoration::Com,
            "_dac" => Decoration::Dac,
            "_def" => Decoration::Def,
            "_trv" => Decoration::Trv,
            "_ill" => Decoration::Ill,
            _ => {
                return Err(IntervalError::Parse {
                    position: text.len() - text.trim_start().len() + close + 1,
                    reason: "expected a decoration _com, _dac, _def, _trv or _ill",
                });
            }
        };
        let y = Self::set_dec(x, d);
        if y.d != d {
            return Err(IntervalError::Parse {
                position: text.len() - text.trim_start().len() + close + 1,
                reason: "the interval cannot carry this decoration",
            });
        }
        Ok(y)
    }
}

impl<T: Float> core::str::FromStr for DecInterval<T> {
    type Err = IntervalError;
    /// [`DecInterval::parse`].
    fn from_str(s: &str) -> Result<Self, IntervalError> {
        Self::parse(s)
    }
}

impl<T: Float> From<Interval<T>> for DecInterval<T> {
    /// [`DecInterval::new`].
    fn from(x: Interval<T>) -> Self {
        Self::new(x)
    }
}

impl<T: Float> fmt::Display for DecInterval<T> {
    /// `[a, b]_dec` as in IEEE 1788 literals; `[nai]` for NaI.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_nai() {
            return f.write_str("[nai]");
        }
        write!(f, "{}_{}", self.x, self.d)
    }
}
