//! CSG reduction per cell (thesis 6.3): the leaves' sign classes over a cell, and the tree
//! of each object reduced to a sign-equivalent one (see the [grid's documentation](super)
//! for the rules and their proof).

use implicit_expr::{Context, NodeId};
use interval_core::Interval;

use crate::scene::Csg;

/// Sign class of a node of the CSG tree over a cell.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Sign {
    /// Defined nowhere in the cell.
    Undefined,
    /// Proven defined everywhere and positive.
    Pos,
    /// Proven defined everywhere and negative.
    Neg,
    /// Anything else.
    Unknown,
}

/// Leaf classes, one byte per used leaf of a cell (stored sparsely: see
/// [`super::classify::Row`]).
pub(super) const C_UNDEFINED: u8 = 0;
pub(super) const C_POS: u8 = 1;
pub(super) const C_NEG: u8 = 2;
pub(super) const C_UNKNOWN_DEFINED: u8 = 3;
pub(super) const C_UNKNOWN: u8 = 4;

/// A reduced tree: leaves (by index into the geometry's leaves), negation, `min`, `max`.
#[derive(Clone, Debug)]
pub(super) enum Expr {
    Leaf(usize),
    Neg(Box<Expr>),
    Min(Vec<Expr>),
    Max(Vec<Expr>),
}

/// The reduction of a node: a sign-equivalent tree, its sign class, and whether it is
/// proven defined at every point of the cell.
#[derive(Clone, Debug)]
pub(super) struct Reduced {
    pub(super) sign: Sign,
    pub(super) defined: bool,
    pub(super) expr: Expr,
}

impl Expr {
    pub(super) fn build(&self, ctx: &mut Context, leaves: &[NodeId]) -> NodeId {
        match self {
            Expr::Leaf(i) => leaves[*i],
            Expr::Neg(e) => {
                let n = e.build(ctx, leaves);
                ctx.neg(n)
            }
            Expr::Min(c) | Expr::Max(c) => {
                let min = matches!(self, Expr::Min(_));
                let mut acc = c[0].build(ctx, leaves);
                for e in &c[1..] {
                    let n = e.build(ctx, leaves);
                    acc = if min {
                        ctx.min(acc, n)
                    } else {
                        ctx.max(acc, n)
                    };
                }
                acc
            }
        }
    }
}

fn negate(r: Reduced) -> Reduced {
    let sign = match r.sign {
        Sign::Pos => Sign::Neg,
        Sign::Neg => Sign::Pos,
        s => s,
    };
    let expr = match r.expr {
        Expr::Neg(e) => *e,
        e => Expr::Neg(Box::new(e)),
    };
    Reduced {
        sign,
        defined: r.defined,
        expr,
    }
}

/// `min` (`is_min`) or `max` of reduced children.
pub(super) fn combine(children: Vec<Reduced>, is_min: bool) -> Reduced {
    let (absorbing, neutral) = if is_min {
        (Sign::Neg, Sign::Pos)
    } else {
        (Sign::Pos, Sign::Neg)
    };
    if let Some(u) = children.iter().find(|r| r.sign == Sign::Undefined) {
        return u.clone();
    }
    let first = children[0].expr.clone();
    let mut kept: Vec<Reduced> = children.into_iter().filter(|r| r.sign != neutral).collect();
    if kept.is_empty() {
        // Every child neutral: so is the node.
        return Reduced {
            sign: neutral,
            defined: true,
            expr: first,
        };
    }
    let all_defined = kept.iter().all(|r| r.defined);
    if all_defined && let Some(a) = kept.iter().find(|r| r.sign == absorbing) {
        return a.clone();
    }
    if kept.len() == 1 {
        return kept.pop().expect("one child");
    }
    let exprs = kept.into_iter().map(|r| r.expr).collect();
    Reduced {
        sign: Sign::Unknown,
        defined: all_defined,
        expr: if is_min {
            Expr::Min(exprs)
        } else {
            Expr::Max(exprs)
        },
    }
}

pub(super) fn reduce(csg: &Csg, class: &dyn Fn(usize) -> u8) -> Reduced {
    match csg {
        Csg::Leaf(i) => {
            let (sign, defined) = match class(*i) {
                C_UNDEFINED => (Sign::Undefined, false),
                C_POS => (Sign::Pos, true),
                C_NEG => (Sign::Neg, true),
                C_UNKNOWN_DEFINED => (Sign::Unknown, true),
                _ => (Sign::Unknown, false),
            };
            Reduced {
                sign,
                defined,
                expr: Expr::Leaf(*i),
            }
        }
        Csg::Union(c) => combine(c.iter().map(|c| reduce(c, class)).collect(), true),
        Csg::Intersection(c) => combine(c.iter().map(|c| reduce(c, class)).collect(), false),
        Csg::Difference(a, b) => {
            let a = reduce(a, class);
            let b = negate(reduce(b, class));
            combine(vec![a, b], false)
        }
    }
}

/// The class of a leaf whose enclosure over the cell is `f`.
pub(super) fn classify(f: Interval<f64>, defined: bool) -> u8 {
    if f.is_empty() {
        C_UNDEFINED
    } else if !defined {
        C_UNKNOWN
    } else if f.inf() > 0.0 {
        C_POS
    } else if f.sup() < 0.0 {
        C_NEG
    } else {
        C_UNKNOWN_DEFINED
    }
}
