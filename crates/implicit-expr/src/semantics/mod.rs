//! Modal semantics of a formula (thesis 3.5.1 and 3.5.2): which interpretability theorem
//! gives the modal rational extension `fR` a logical meaning on a given modal interval
//! vector `X`, on which transformed vector, and whether the result is optimal.
//!
//! For a continuous `f` and modal `X`, the semantic extensions are (3.5.1)
//!
//! ```text
//! f*(X)  = [ min_{x_p} max_{x_i} f(x_p, x_i),  max_{x_p} min_{x_i} f(x_p, x_i) ]
//! f**(X) = [ max_{x_i} min_{x_p} f(x_p, x_i),  min_{x_i} max_{x_p} f(x_p, x_i) ]
//! ```
//!
//! with `x_p` ranging over the proper components and `x_i` over the improper ones, and
//! `f*(X) ⊆ f**(X)`. They are not computable directly, but the theorems of 3.5.2 relate them
//! to `fR`, the formula evaluated with modal arithmetic ([`Modal<f64, Outer>`] gives
//! `Out(fR(·))`, [`Modal<f64, Inner>`] gives `Inn(fR(·))`):
//!
//! | theorem | condition | result |
//! |---|---|---|
//! | 1 | improper components uni-incident | `f*(X) ⊆ Out(fR(X))` |
//! | 2 | proper components uni-incident | `Inn(fR(X)) ⊆ f**(X)` |
//! | 3 | total monotony for a subset `Z` | `f*(X) ⊆ Out(fR(XDt*))` |
//! | 4 | total monotony for a subset `Z` | `Inn(fR(XDt**)) ⊆ f**(X)` |
//! | 5 | none (general case) | `f*(X) ⊆ Out(fR(Xt*))` |
//! | 6 | total monotony of every multi-incident component, tree-optimality | `f*(X) = fR(XD) = f**(X)` |
//!
//! [`analyze`] finds the incidences of each variable in the syntax tree, builds the
//! incidence-split function ([`split_incidences`]), proves the monotony of each incidence and
//! each variable over `Prop(X)` with interval enclosures of the partial derivatives
//! ([`Monotony`]), decides tree-optimality, builds the transformed vectors and evaluates
//! every applicable theorem ([`Estimate`]), picking the best outer and inner ones.
//!
//! All the theorems need `f` defined and continuous on `Prop(X)` ("`Out(fR(Prop(X)))` does
//! exist"); [`analyze`] checks this operation by operation and returns
//! [`Error::Unsupported`] when it cannot prove it. A component that is a point is a constant
//! of the formula: it is neither proper nor improper for the conditions of the theorems.
//!
//! # Example (thesis 3.5.2)
//!
//! `f(x, y) = xy/(x+y)` with `X = [2, 3]`, `Y = [4, 3]`: `f` is totally monotonous in `x` and
//! `y`, the split function `x1·y1/(x2+y2)` is decreasing in `x2` and `y2`, and the result is
//! optimal, `f*(X) = fR(XD) = [4/3, 3/2]`.
//!
//! ```
//! use implicit_expr::Context;
//! use implicit_expr::semantics::{Theorem, analyze};
//! use interval_core::Modal;
//!
//! let mut ctx = Context::new();
//! let (x, y) = (ctx.x(), ctx.y());
//! let (num, den) = (ctx.mul(x, y), ctx.add(x, y));
//! let f = ctx.div(num, den);
//! let r = analyze(&ctx, f, &[Modal::new(2.0, 3.0)?, Modal::new(4.0, 3.0)?])?;
//!
//! // Theorem 5: Xt* = ([2, 3], [4, 4], [2, 3], [4, 4]) gives [8/7, 2].
//! let t5 = r.estimate(Theorem::Theorem5).unwrap();
//! assert_eq!(t5.vector[1], Modal::new(4.0, 4.0)?);
//! let o = t5.outer.unwrap();
//! assert!(o.first() <= 8.0 / 7.0 && o.second() >= 2.0);
//!
//! // Theorem 3: XDt* = ([2, 3], [4, 4], [3, 2], [4, 4]) gives [4/3, 12/7].
//! let t3 = r.estimate(Theorem::Theorem3).unwrap();
//! assert_eq!(t3.vector[2], Modal::new(3.0, 2.0)?);
//!
//! // Theorem 6: XD = ([2, 3], [4, 3], [3, 2], [3, 4]) gives f*(X) = f**(X) = [4/3, 3/2].
//! assert!(r.is_optimal());
//! assert_eq!(r.outer().theorem, Theorem::Theorem6);
//! let (out, inn) = (r.outer().outer.unwrap(), r.inner().inner.unwrap());
//! assert!(out.first() <= 4.0 / 3.0 && 1.5 <= out.second());
//! assert!(inn.first() >= out.first() && inn.second() <= out.second());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod incidence;
mod monotonicity;
mod theorems;

pub use incidence::{Incidence, MAX_TREE_SIZE, SplitFunction, split_incidences, tree_size};
pub use monotonicity::Monotony;
pub use theorems::{Estimate, Theorem};

use std::fmt;

use interval_core::{Inner, Interval, Modal, Outer};

use crate::context::{Context, NodeId, Var};
use crate::error::Error;
use crate::eval::Evaluator;
use crate::tape::Tape;
use monotonicity::{Slopes, incidence_partials, non_optimal_node, ranges, variable_partials};
use theorems::{Side, VarFacts, transformed_vector};

/// What the analysis found about one variable of the formula.
#[derive(Clone, Debug, PartialEq)]
pub struct VariableInfo {
    /// The variable's slot in the original context.
    pub var: Var,
    /// The variable's name.
    pub name: String,
    /// The modal interval given for it.
    pub value: Modal<f64>,
    /// Its number of incidences in the syntax tree.
    pub incidences: usize,
    /// The sign of `∂f/∂var` over `Prop(X)` (uniform monotony of `f` in this variable).
    pub monotony: Monotony,
    /// Total monotony (3.5.2): uniformly monotonous for the variable and for each of its
    /// incidences taken as independent variables. For a uni-incident variable this is its
    /// uniform monotony.
    pub totally_monotone: bool,
}

/// The result of [`analyze`]: every applicable estimate, the best outer and inner ones, and
/// the facts they rest on.
#[derive(Clone, Debug)]
pub struct SemanticResult {
    /// The incidence-split function the estimates are computed on.
    pub split: SplitFunction,
    /// The variables of the formula, in slot order.
    pub variables: Vec<VariableInfo>,
    /// The sign of `∂g/∂x_k` over `Prop(X)` for each incidence `x_k` of the split function
    /// `g` (in [`SplitFunction::incidences`] order).
    pub incidence_monotony: Vec<Monotony>,
    /// Whether the split function is tree-optimal on `Prop(X)` (point components counted as
    /// constants). Theorem 6 also needs total monotony of every multi-incident component.
    pub tree_optimal: bool,
    /// Every applicable estimate: the outer ones (theorem 1 or 5, then theorem 3 for the
    /// proper totally monotonous components, then for all of them), the inner ones
    /// (theorem 2 or 4 with `Z = ∅`, then theorem 4 for the improper totally monotonous
    /// components, then for all of them), then theorem 6 when it applies (it replaces the
    /// theorem 3 and 4 estimates on the same vector `XD`).
    pub estimates: Vec<Estimate>,
    best_outer: usize,
    best_inner: usize,
}

impl SemanticResult {
    /// The best outer estimate `Out(fR(·)) ⊇ f*(X)`: theorem 6's when it applies, otherwise
    /// the narrowest (smallest `second − first`) of the outer estimates.
    pub fn outer(&self) -> &Estimate {
        &self.estimates[self.best_outer]
    }

    /// The best inner estimate `Inn(fR(·)) ⊆ f**(X)`: theorem 6's when it applies, otherwise
    /// the widest of the inner estimates.
    pub fn inner(&self) -> &Estimate {
        &self.estimates[self.best_inner]
    }

    /// Whether theorem 6 applies: `f*(X) = fR(XD) = f**(X)`, so [`outer`](Self::outer) and
    /// [`inner`](Self::inner) bracket the exact semantic extension (up to rounding, and up
    /// to the looseness of inner-rounded `sin` and `cos`).
    pub fn is_optimal(&self) -> bool {
        self.outer().theorem == Theorem::Theorem6
    }

    /// The first estimate given by `theorem`, if it applies.
    pub fn estimate(&self, theorem: Theorem) -> Option<&Estimate> {
        self.estimates.iter().find(|e| e.theorem == theorem)
    }
}

/// One line per estimate, then the best outer and inner estimates.
impl fmt::Display for SemanticResult {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for e in &self.estimates {
            fmt::Display::fmt(e, f)?;
            f.write_str("\n")?;
        }
        if let Some(o) = self.outer().outer {
            f.write_str("f*(X) ⊆ ")?;
            fmt::Display::fmt(&o, f)?;
            writeln!(f, " by theorem {}", self.outer().theorem.number())?;
        }
        if let Some(i) = self.inner().inner {
            fmt::Display::fmt(&i, f)?;
            write!(f, " ⊆ f**(X) by theorem {}", self.inner().theorem.number())?;
        }
        if self.is_optimal() {
            f.write_str(" (optimal: f*(X) = f**(X))")?;
        }
        Ok(())
    }
}

/// Analyses the modal semantics of the formula `f` of `ctx` on the modal intervals `args`
/// (one per variable slot; slots that `f` does not use may be missing or hold anything),
/// following thesis 3.5.2. See the [module documentation](self).
///
/// Returns [`Error::MissingVar`] when a variable of `f` has no value, and
/// [`Error::Unsupported`] when a value is unbounded, when the syntax tree has more than
/// [`MAX_TREE_SIZE`] nodes, or when `f` is not provably defined and continuous on `Prop(X)`.
pub fn analyze(ctx: &Context, f: NodeId, args: &[Modal<f64>]) -> Result<SemanticResult, Error> {
    let split = split_incidences(ctx, f)?;

    // The variables, their values and their incidence counts.
    let mut vars: Vec<Var> = split.incidences.iter().map(|i| i.var).collect();
    vars.sort();
    vars.dedup();
    for &v in &vars {
        let x = args.get(v.index()).ok_or(Error::MissingVar {
            slot: v.0,
            given: args.len(),
        })?;
        if !x.first().is_finite() || !x.second().is_finite() {
            return Err(Error::Unsupported(format!(
                "variable '{}' has the unbounded value {x}; the modal semantic analysis needs \
                 finite bounds",
                ctx.var_names()[v.index()]
            )));
        }
    }
    let value = |v: Var| args[v.index()];
    let count = |v: Var| split.incidences.iter().filter(|i| i.var == v).count();
    let multi = |v: Var| count(v) > 1 && !value(v).is_point();

    // Ranges and domain over Prop(X), incidence partials, variable partials.
    let inc_values: Vec<Modal<f64>> = split.incidences.iter().map(|i| value(i.var)).collect();
    let props: Vec<Interval<f64>> = inc_values.iter().map(|m| m.prop()).collect();
    let varying: Vec<bool> = inc_values.iter().map(|m| !m.is_point()).collect();
    let inputs = split.slot_values(&props, Interval::ZERO);
    let varying_slot = split.slot_values(&varying, false);
    let r = ranges(&split, &inputs, &varying_slot)?;
    let mut slopes = Slopes::default();
    let partials = incidence_partials(&split, &inputs, &varying_slot, &r, &mut slopes)?;
    let incidence_monotony: Vec<Monotony> = partials.iter().map(|&d| Monotony::of(d)).collect();
    let multi_vars: Vec<Var> = vars.iter().copied().filter(|&v| multi(v)).collect();
    let props_by_slot: Vec<Interval<f64>> = (0..ctx.var_count())
        .map(|s| args.get(s).map_or(Interval::ZERO, |m| m.prop()))
        .collect();
    let global = variable_partials(ctx, f, &multi_vars, &props_by_slot)?;

    let variables: Vec<VariableInfo> = vars
        .iter()
        .map(|&v| {
            let mine = || {
                split
                    .incidences
                    .iter()
                    .zip(&partials)
                    .zip(&incidence_monotony)
                    .filter(move |((inc, _), _)| inc.var == v)
            };
            let mut d = mine().fold(Interval::ZERO, |s, ((_, &p), _)| s + p);
            if let Some(j) = multi_vars.iter().position(|&w| w == v) {
                d = d.intersection(global[j]);
            }
            let monotony = Monotony::of(d);
            let totally_monotone = monotony.is_monotone() && mine().all(|(_, m)| m.is_monotone());
            VariableInfo {
                var: v,
                name: ctx.var_names()[v.index()].clone(),
                value: value(v),
                incidences: count(v),
                monotony,
                totally_monotone,
            }
        })
        .collect();
    let info = |v: Var| {
        variables
            .iter()
            .find(|i| i.var == v)
            .expect("every incidence's variable is listed")
    };
    let facts = |v: Var| {
        let i = info(v);
        VarFacts {
            value: i.value,
            count: i.incidences,
            monotony: i.monotony,
        }
    };

    let tree_optimal = non_optimal_node(&split, &r, &mut slopes)?.is_none();

    // The subsets Z of multi-incident components used with their total monotony.
    let z_all: Vec<Var> = multi_vars
        .iter()
        .copied()
        .filter(|&v| info(v).totally_monotone)
        .collect();
    let z_proper: Vec<Var> = z_all
        .iter()
        .copied()
        .filter(|&v| value(v).is_proper())
        .collect();
    let z_improper: Vec<Var> = z_all
        .iter()
        .copied()
        .filter(|&v| value(v).is_improper())
        .collect();
    let theorem6 = tree_optimal && z_all.len() == multi_vars.len();
    let improper_multi = multi_vars.iter().any(|&v| value(v).is_improper());
    let proper_multi = multi_vars.iter().any(|&v| value(v).is_proper());

    // Evaluation of fR on a vector given per incidence.
    let tape = Tape::new(&split.context, &[split.root])?;
    let mut eval_outer = Evaluator::<Modal<f64, Outer>>::new(&tape);
    let mut eval_inner = Evaluator::<Modal<f64, Inner>>::new(&tape);
    let mut outer_of = |v: &[Modal<f64>]| -> Result<Modal<f64, Outer>, Error> {
        eval_outer.eval(&split.slot_values(v, Modal::ZERO))
    };
    let mut inner_of = |v: &[Modal<f64>]| -> Result<Modal<f64, Inner>, Error> {
        let v: Vec<Modal<f64, Inner>> = v.iter().map(|m| m.with_rounding()).collect();
        eval_inner.eval(&split.slot_values(&v, Modal::ZERO))
    };
    let vector = |z: &[Var], side: Side| {
        transformed_vector(
            &split,
            &facts,
            &incidence_monotony,
            &|v| z.contains(&v),
            side,
        )
    };

    let mut estimates = Vec::new();
    let mut seen: Vec<&[Var]> = Vec::new();
    for z in [&[][..], z_proper.as_slice(), z_all.as_slice()] {
        if seen.contains(&z) || (theorem6 && !z.is_empty() && z == z_all.as_slice()) {
            continue;
        }
        seen.push(z);
        let theorem = match (z.is_empty(), improper_multi) {
            (false, _) => Theorem::Theorem3,
            (true, true) => Theorem::Theorem5,
            (true, false) => Theorem::Theorem1,
        };
        let v = vector(z, Side::Outer);
        estimates.push(Estimate {
            theorem,
            monotone: z.to_vec(),
            outer: Some(outer_of(&v)?),
            inner: None,
            vector: v,
        });
    }
    seen.clear();
    for z in [&[][..], z_improper.as_slice(), z_all.as_slice()] {
        if seen.contains(&z) || (theorem6 && !z.is_empty() && z == z_all.as_slice()) {
            continue;
        }
        seen.push(z);
        let theorem = if z.is_empty() && !proper_multi {
            Theorem::Theorem2
        } else {
            Theorem::Theorem4
        };
        let v = vector(z, Side::Inner);
        estimates.push(Estimate {
            theorem,
            monotone: z.to_vec(),
            outer: None,
            inner: Some(inner_of(&v)?),
            vector: v,
        });
    }
    if theorem6 {
        let v = vector(&z_all, Side::Outer);
        estimates.push(Estimate {
            theorem: Theorem::Theorem6,
            monotone: z_all.clone(),
            outer: Some(outer_of(&v)?),
            inner: Some(inner_of(&v)?),
            vector: v,
        });
    }

    let width = |a: f64, b: f64| b - a;
    let (best_outer, best_inner) = if theorem6 {
        (estimates.len() - 1, estimates.len() - 1)
    } else {
        let mut bo = 0;
        let mut bi = None;
        let mut wo = f64::INFINITY;
        let mut wi = f64::NEG_INFINITY;
        for (k, e) in estimates.iter().enumerate() {
            if let Some(o) = e.outer
                && width(o.first(), o.second()) < wo
            {
                wo = width(o.first(), o.second());
                bo = k;
            }
            if let Some(i) = e.inner
                && (bi.is_none() || width(i.first(), i.second()) > wi)
            {
                wi = width(i.first(), i.second());
                bi = Some(k);
            }
        }
        (bo, bi.unwrap_or(0))
    };

    Ok(SemanticResult {
        split,
        variables,
        incidence_monotony,
        tree_optimal,
        estimates,
        best_outer,
        best_inner,
    })
}
