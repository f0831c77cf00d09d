//! Which leaf shades a hit point, per cell: the leaves that may vanish in the cell.
//!
//! The shading material of a hit at `p` is the leaf whose value at `p` has the smallest
//! magnitude ([`GeometryEval::leaf_at`](crate::scene::GeometryEval::leaf_at)), a search over
//! every leaf of the scene. In a cell, a leaf proven of one strict sign has magnitude at
//! least the mignitude of its enclosure over the cell; when some other leaf is smaller than
//! the smallest such bound at `p`, the search among the other leaves (the *candidates*, in
//! leaf order) finds the same leaf. Cells with the same candidates share one tape.

use std::collections::HashMap;

use implicit_expr::{Context, NodeId, Tape};

use super::cells::EMPTY;
use super::classify::Row;
use super::reduce::{C_NEG, C_POS};

/// The candidate leaves of a cell: their tape (one output per candidate, in leaf order),
/// their leaf indices, and the bound below which a candidate wins.
#[derive(Copy, Clone, Debug)]
pub struct LeafCandidates<'a> {
    /// One output per candidate.
    pub tape: &'a Tape,
    /// The candidates' leaf indices, increasing.
    pub leaves: &'a [u32],
    /// The smallest magnitude over the cell of the leaves left out.
    pub bound: f64,
}

/// The candidate sets of a grid's non-empty cells.
#[derive(Clone, Debug, Default)]
pub(super) struct CellLeaves {
    sets: Vec<(Tape, Vec<u32>)>,
    cell_set: Vec<u32>,
    bound: Vec<f64>,
}

impl CellLeaves {
    /// The candidates of every cell that `non_empty` keeps: `rows` holds the distinct
    /// class vectors (sparse: the columns whose class is not positive, `used[k]` the leaf of
    /// class column `k`), `row_of` each cell's, `bound` per cell the smallest mignitude of its
    /// leaves of proven sign; `leaf_nodes` are the leaves' nodes in `ctx`. Each distinct
    /// vector is looked at once. Returns `None` when a tape cannot be built (the full search
    /// is used then).
    pub(super) fn build(
        ctx: &Context,
        leaf_nodes: &[NodeId],
        used: &[usize],
        rows: &[Row],
        row_of: &[u32],
        bound: Vec<f64>,
        non_empty: impl Fn(usize) -> bool,
    ) -> Option<Self> {
        // Leaves no object uses have no class: always candidates.
        let mut in_use = vec![false; leaf_nodes.len()];
        for &i in used {
            in_use[i] = true;
        }
        let unused: Vec<u32> = (0..leaf_nodes.len() as u32)
            .filter(|&i| !in_use[i as usize])
            .collect();
        let mut by_set: HashMap<Vec<u32>, u32> = HashMap::new();
        let mut sets = Vec::new();
        // Each distinct class vector's candidate set (EMPTY: none), built when first used.
        let mut row_set: Vec<Option<u32>> = vec![None; rows.len()];
        let mut cell_set = vec![EMPTY; row_of.len()];
        for (idx, set) in cell_set.iter_mut().enumerate() {
            if !non_empty(idx) || used.is_empty() {
                continue;
            }
            let r = row_of[idx] as usize;
            if let Some(s) = row_set[r] {
                *set = s;
                continue;
            }
            // The leaves not proven of one sign: the unused ones and the row's unknown
            // and undefined ones (a leaf the row does not list is positive).
            let mut leaves: Vec<u32> = rows[r]
                .iter()
                .filter(|&&(_, c)| !matches!(c, C_POS | C_NEG))
                .map(|&(k, _)| used[k as usize] as u32)
                .chain(unused.iter().copied())
                .collect();
            leaves.sort_unstable();
            *set = if leaves.is_empty() {
                EMPTY
            } else {
                match by_set.get(&leaves) {
                    Some(&s) => s,
                    None => {
                        let nodes: Vec<NodeId> =
                            leaves.iter().map(|&i| leaf_nodes[i as usize]).collect();
                        let tape = Tape::new(ctx, &nodes).ok()?;
                        sets.push((tape, leaves.clone()));
                        by_set.insert(leaves, (sets.len() - 1) as u32);
                        (sets.len() - 1) as u32
                    }
                }
            };
            row_set[r] = Some(*set);
        }
        Some(Self {
            sets,
            cell_set,
            bound,
        })
    }

    /// The candidates of cell `idx`, `None` for a cell without.
    pub(super) fn get(&self, idx: usize) -> Option<LeafCandidates<'_>> {
        let s = *self.cell_set.get(idx)?;
        (s != EMPTY).then(|| {
            let (tape, leaves) = &self.sets[s as usize];
            LeafCandidates {
                tape,
                leaves,
                bound: self.bound[idx],
            }
        })
    }
}
