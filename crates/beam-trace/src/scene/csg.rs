//! The `[[csg]]` nodes of a scene file: child names resolved to surfaces and other nodes,
//! cycles and oversized trees refused, and the [`Csg`](super::Csg) trees built.

use std::collections::HashMap;

use implicit_expr::parse::suggest;

use super::diagnostics::Doc;
use super::geometry::Csg;
use super::schema::{CsgOp, RawCsg};
use crate::error::Error;

/// Largest number of leaf references of one expanded csg tree.
const MAX_CSG_LEAVES: usize = 10_000;
/// Deepest csg nesting.
const MAX_CSG_DEPTH: usize = 64;

/// What a csg child name refers to.
#[derive(Copy, Clone, PartialEq, Eq, Debug)]
pub(super) enum Ref {
    Surface(usize),
    Csg(usize),
}

pub(super) fn ref_path(r: Ref) -> String {
    match r {
        Ref::Surface(i) => format!("surfaces[{i}]"),
        Ref::Csg(j) => format!("csg[{j}]"),
    }
}

/// Checks the csg nodes: children exist, counts, no cycle, bounded size. Returns the
/// resolved children and a topological order (children first).
pub(super) fn resolve_csg(
    doc: &Doc<'_>,
    csg: &[RawCsg],
    names: &HashMap<&str, Ref>,
    all_names: &[&str],
) -> Result<(Vec<Vec<Ref>>, Vec<usize>), Error> {
    let mut kids = Vec::with_capacity(csg.len());
    for (j, c) in csg.iter().enumerate() {
        let n = c.children.len();
        let bad = match c.op {
            CsgOp::Difference if n != 2 => Some("'difference' needs exactly 2 children"),
            CsgOp::Union | CsgOp::Intersection if n < 2 => Some("needs at least 2 children"),
            _ => None,
        };
        if let Some(m) = bad {
            return Err(doc.err(&format!("csg[{j}].children"), format!("{m}, got {n}")));
        }
        let mut refs = Vec::with_capacity(n);
        for (k, child) in c.children.iter().enumerate() {
            let Some(&r) = names.get(child.as_str()) else {
                let hint = suggest::did_you_mean(child, all_names.iter().copied())
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                return Err(doc.err(
                    &format!("csg[{j}].children[{k}]"),
                    format!("unknown surface or csg node '{child}'{hint}"),
                ));
            };
            refs.push(r);
        }
        kids.push(refs);
    }
    // Kahn's algorithm over the csg → csg edges: children before parents.
    let mut pending: Vec<usize> = kids
        .iter()
        .map(|k| k.iter().filter(|r| matches!(r, Ref::Csg(_))).count())
        .collect();
    let mut parents: Vec<Vec<usize>> = vec![Vec::new(); csg.len()];
    for (j, k) in kids.iter().enumerate() {
        for r in k {
            if let Ref::Csg(c) = r {
                parents[*c].push(j);
            }
        }
    }
    let mut order: Vec<usize> = (0..csg.len()).filter(|&j| pending[j] == 0).collect();
    let mut next = 0;
    while next < order.len() {
        let j = order[next];
        next += 1;
        for &p in &parents[j] {
            pending[p] -= 1;
            if pending[p] == 0 {
                order.push(p);
            }
        }
    }
    if order.len() < csg.len() {
        // Every remaining node lies on or leads to a cycle: walk to a repeat.
        let start = (0..csg.len()).find(|&j| pending[j] > 0).unwrap_or(0);
        let mut seen = vec![usize::MAX; csg.len()];
        let mut walk = vec![start];
        let mut j = start;
        loop {
            seen[j] = walk.len() - 1;
            let Some((k, c)) = kids[j].iter().enumerate().find_map(|(k, r)| match r {
                Ref::Csg(c) if pending[*c] > 0 => Some((k, *c)),
                _ => None,
            }) else {
                break;
            };
            if seen[c] != usize::MAX {
                let cycle: Vec<&str> = walk[seen[c]..]
                    .iter()
                    .chain(std::iter::once(&c))
                    .map(|&n| csg[n].name.as_str())
                    .collect();
                return Err(doc.err(
                    &format!("csg[{j}].children[{k}]"),
                    format!("csg cycle: {}", cycle.join(" -> ")),
                ));
            }
            walk.push(c);
            j = c;
        }
        return Err(doc.err(&format!("csg[{start}]"), "csg cycle"));
    }
    let mut size = vec![0usize; csg.len()];
    let mut depth = vec![0usize; csg.len()];
    for &j in &order {
        for r in &kids[j] {
            let (s, d) = match *r {
                Ref::Surface(_) => (1, 0),
                Ref::Csg(c) => (size[c], depth[c]),
            };
            size[j] = size[j].saturating_add(s);
            depth[j] = depth[j].max(d + 1);
        }
        if size[j] > MAX_CSG_LEAVES {
            return Err(doc.err(
                &format!("csg[{j}]"),
                format!("the tree expands to more than {MAX_CSG_LEAVES} leaves"),
            ));
        }
        if depth[j] > MAX_CSG_DEPTH {
            return Err(doc.err(
                &format!("csg[{j}]"),
                format!("csg nodes nest deeper than {MAX_CSG_DEPTH} levels"),
            ));
        }
    }
    Ok((kids, order))
}

pub(super) fn csg_tree(j: usize, csg: &[RawCsg], kids: &[Vec<Ref>], leaf_of: &[usize]) -> Csg {
    let child = |r: &Ref| match *r {
        Ref::Surface(i) => Csg::Leaf(leaf_of[i]),
        Ref::Csg(c) => csg_tree(c, csg, kids, leaf_of),
    };
    let ch: Vec<Csg> = kids[j].iter().map(child).collect();
    match csg[j].op {
        CsgOp::Union => Csg::Union(ch),
        CsgOp::Intersection => Csg::Intersection(ch),
        CsgOp::Difference => {
            let mut it = ch.into_iter();
            match (it.next(), it.next()) {
                (Some(a), Some(b)) => Csg::Difference(Box::new(a), Box::new(b)),
                // Unreachable after `resolve_csg`; an empty union keeps this panic-free.
                _ => Csg::Union(Vec::new()),
            }
        }
    }
}
