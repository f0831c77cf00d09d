//! The interpretability theorems of thesis 3.5.2 and the transformed vectors they evaluate
//! the modal rational extension on.

use std::fmt;

use interval_core::{Inner, Modal, Outer};

use super::incidence::SplitFunction;
use super::monotonicity::Monotony;
use crate::context::Var;

/// The theorem of thesis 3.5.2 that justifies an estimate.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Theorem {
    /// *-interpretability of modal rational functions: if the improper components of `X`
    /// are uni-incident, `Out(fR(X)) ⊇ f*(X)`.
    Theorem1,
    /// **-interpretability of modal rational functions: if the proper components of `X` are
    /// uni-incident, `Inn(fR(X)) ⊆ f**(X)`.
    Theorem2,
    /// *-interpretability with total monotony: `f*(X) ⊆ fR(XDt*)`.
    Theorem3,
    /// **-interpretability with total monotony: `fR(XDt**) ⊆ f**(X)`.
    Theorem4,
    /// Interpretability in the multi-incidence case (general case): `f*(X) ⊆ fR(Xt*)`.
    Theorem5,
    /// Coercion to optimality: `f*(X) = fR(XD) = f**(X)` for a tree-optimal `fR`.
    Theorem6,
}

impl Theorem {
    /// The theorem's number in the thesis (1 to 6).
    pub fn number(self) -> u8 {
        match self {
            Theorem::Theorem1 => 1,
            Theorem::Theorem2 => 2,
            Theorem::Theorem3 => 3,
            Theorem::Theorem4 => 4,
            Theorem::Theorem5 => 5,
            Theorem::Theorem6 => 6,
        }
    }

    /// The theorem's title in the thesis.
    pub fn title(self) -> &'static str {
        match self {
            Theorem::Theorem1 => "*-interpretability of modal rational functions",
            Theorem::Theorem2 => "**-interpretability of modal rational functions",
            Theorem::Theorem3 => "*-interpretability with total monotony",
            Theorem::Theorem4 => "**-interpretability with total monotony",
            Theorem::Theorem5 => "interpretability in the multi-incidence case",
            Theorem::Theorem6 => "coercion to optimality",
        }
    }

    /// The name of the transformed vector the theorem evaluates `fR` on.
    pub fn vector_name(self) -> &'static str {
        match self {
            Theorem::Theorem1 | Theorem::Theorem2 => "X",
            Theorem::Theorem3 => "XDt*",
            Theorem::Theorem4 => "XDt**",
            Theorem::Theorem5 => "Xt*",
            Theorem::Theorem6 => "XD",
        }
    }
}

/// `Theorem 5 (interpretability in the multi-incidence case)`.
impl fmt::Display for Theorem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Theorem {} ({})", self.number(), self.title())
    }
}

/// One estimate of the semantic extensions: `fR` of the split function evaluated on a
/// transformed vector, with the theorem that gives it a meaning.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// The theorem that justifies the estimate.
    pub theorem: Theorem,
    /// The subset `Z` of multi-incident variables used with their total monotony (theorems
    /// 3, 4 and 6): each incidence kept as an independent component, dualised where its
    /// monotony sense is contrary to the variable's. Empty for theorems 1, 2 and 5.
    pub monotone: Vec<Var>,
    /// The transformed vector, one component per incidence of the split function (in
    /// [`SplitFunction::incidences`] order, e.g. `(x1, y1, x2, y2)`).
    pub vector: Vec<Modal<f64>>,
    /// `Out(fR(vector)) ⊇ f*(X)`, when the theorem gives an outer estimate.
    pub outer: Option<Modal<f64, Outer>>,
    /// `Inn(fR(vector)) ⊆ f**(X)`, when the theorem gives an inner estimate.
    pub inner: Option<Modal<f64, Inner>>,
}

/// `Theorem 5 (...): Xt* = ([2, 3], [4, 4], ...), Out(fR(Xt*)) = [...] ⊇ f*(X)`. Format
/// options (precision, ...) apply to every bound.
impl fmt::Display for Estimate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.theorem.vector_name();
        write!(f, "{}: {v} = (", self.theorem)?;
        for (i, c) in self.vector.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            fmt::Display::fmt(c, f)?;
        }
        f.write_str(")")?;
        if let Some(o) = self.outer {
            write!(f, ", Out(fR({v})) = ")?;
            fmt::Display::fmt(&o, f)?;
            f.write_str(" ⊇ f*(X)")?;
        }
        if let Some(i) = self.inner {
            write!(f, ", Inn(fR({v})) = ")?;
            fmt::Display::fmt(&i, f)?;
            f.write_str(" ⊆ f**(X)")?;
        }
        if self.theorem == Theorem::Theorem6 {
            f.write_str(", f*(X) = fR(XD) = f**(X)")?;
        }
        Ok(())
    }
}

/// Which side a transformed vector serves: theorems 3 and 5 make improper multi-incident
/// components point-wise, theorem 4 proper ones.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(crate) enum Side {
    /// `f*(X) ⊆ fR(·)`.
    Outer,
    /// `fR(·) ⊆ f**(X)`.
    Inner,
}

/// What the vector construction needs to know about one original variable.
pub(crate) struct VarFacts {
    /// The modal interval given for the variable.
    pub value: Modal<f64>,
    /// Number of incidences.
    pub count: usize,
    /// The global monotony sense.
    pub monotony: Monotony,
}

/// The transformed vector (in incidence order) for the subset `z` of variables used with
/// their total monotony (`in_z(v)`), on `side`.
///
/// * A point component stays as it is (a constant of the formula).
/// * Each incidence of a variable of `z` is an independent component: `X_v`, or
///   `Dual(X_v)` where the incidence's sense is contrary to the variable's (theorems 3, 4
///   and 6).
/// * Any other multi-incident component that is improper (for [`Side::Outer`], theorems 3
///   and 5) or proper (for [`Side::Inner`], theorem 4) becomes the point-wise interval at
///   its *first canonical bound* (the thesis' example takes `[4, 4]` for `Y = [4, 3]`).
/// * Everything else stays `X_v`.
pub(crate) fn transformed_vector(
    split: &SplitFunction,
    facts: &impl Fn(Var) -> VarFacts,
    incidence_monotony: &[Monotony],
    in_z: &impl Fn(Var) -> bool,
    side: Side,
) -> Vec<Modal<f64>> {
    split
        .incidences
        .iter()
        .zip(incidence_monotony)
        .map(|(inc, &m)| {
            let VarFacts {
                value,
                count,
                monotony,
            } = facts(inc.var);
            if value.is_point() {
                value
            } else if in_z(inc.var) {
                if m.is_contrary_to(monotony) {
                    value.dual()
                } else {
                    value
                }
            } else if count > 1
                && match side {
                    Side::Outer => value.is_improper(),
                    Side::Inner => value.is_proper(),
                }
            {
                Modal::new_unchecked(value.first(), value.first())
            } else {
                value
            }
        })
        .collect()
}
