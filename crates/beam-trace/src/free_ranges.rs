//! Root-free parameter ranges of beams, proven once for a block of animation frames and
//! looked up by the searches of each frame (thesis 6.4).
//!
//! A block's geometry encloses the geometry of each of its frames: the same expression
//! graph with every constant widened to the hull of its values over the frames
//! ([`Scene::block_of`](crate::scene::Scene::block_of)). Interval arithmetic is inclusion
//! isotone, operation by operation: narrower arguments give an enclosure inside the wider
//! one's. So where the block's search proved a piece `P` of a beam root-free
//! (`0 ∉ g_block(P)`), the frame's `g` over any `Q ⊆ P` of the same beam excludes 0 as
//! well: the frame's rejection test on `Q` is known to succeed without evaluating it.
//!
//! The frame's search therefore takes every step it would take alone, in the same order,
//! and only skips the evaluations whose outcome is known: its results, and the image, are
//! bit for bit those of the frame rendered on its own. A piece is known free only when it
//! lies inside *one* proven piece of the *same* beam (the same origin and direction box,
//! bit for bit): the union of two proven pieces says nothing about an evaluation over a
//! piece that straddles them, and a sub-beam's enclosure is not guaranteed to lie inside
//! its parent's. Only rejections in the frame's own precision are recorded and used.

use std::collections::HashMap;
use std::sync::Mutex;

use interval_core::Interval;

use crate::ray::Beam;

/// Most pieces kept per beam (bounds the memory of a block's proofs).
pub const MAX_PIECES: usize = 64;

/// The bits of a beam's origin and direction boxes: equal keys, equal beams.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub struct BeamKey([u64; 12]);

impl BeamKey {
    /// The key of `beam`.
    pub fn of(beam: &Beam) -> Self {
        let mut k = [0; 12];
        for (i, iv) in beam.origin.iter().chain(&beam.dir).enumerate() {
            k[2 * i] = iv.inf().to_bits();
            k[2 * i + 1] = iv.sup().to_bits();
        }
        BeamKey(k)
    }
}

/// The pieces of parameter ranges proven root-free, per beam.
#[derive(Clone, Debug, Default)]
pub struct FreeRanges {
    /// Per beam, its proven pieces sorted by lower end (disjoint but for shared ends).
    pieces: HashMap<BeamKey, Vec<Interval<f64>>>,
}

impl FreeRanges {
    /// Adds the pieces proven root-free for `beam`; of a beam with more than
    /// [`MAX_PIECES`], the widest are kept (a piece not kept costs the frames an
    /// evaluation, never a wrong answer).
    pub fn add(&mut self, beam: BeamKey, pieces: &[Interval<f64>]) {
        if pieces.is_empty() {
            return;
        }
        let v = self.pieces.entry(beam).or_default();
        v.extend_from_slice(pieces);
        if v.len() > MAX_PIECES {
            v.sort_by(|a, b| b.wid().total_cmp(&a.wid()));
            v.truncate(MAX_PIECES);
        }
        v.sort_by(|a, b| a.inf().total_cmp(&b.inf()));
    }

    /// The pieces proven for `beam` (sorted by lower end), empty when none.
    pub fn of(&self, beam: &BeamKey) -> &[Interval<f64>] {
        self.pieces.get(beam).map_or(&[], Vec::as_slice)
    }

    /// Number of beams with proven pieces.
    pub fn beams(&self) -> usize {
        self.pieces.len()
    }

    /// Number of proven pieces.
    pub fn len(&self) -> usize {
        self.pieces.values().map(Vec::len).sum()
    }

    /// Whether no piece is proven.
    pub fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }
}

/// Whether `q` lies inside one of `pieces` (sorted by lower end, as
/// [`FreeRanges::of`] gives them).
pub fn covered(pieces: &[Interval<f64>], q: Interval<f64>) -> bool {
    if pieces.is_empty() || q.is_empty() {
        return false;
    }
    // The pieces starting at or below `q`'s start, from the nearest down, as long as they
    // reach `q`. (Pieces of one search are disjoint, so that the nearest decides; where
    // several searches of a beam overlap, a cover missed costs an evaluation, never a
    // wrong answer.)
    let end = pieces.partition_point(|p| p.inf() <= q.inf());
    pieces[..end]
        .iter()
        .rev()
        .take_while(|p| p.sup() >= q.inf())
        .any(|p| q.sup() <= p.sup())
}

/// What a render does with block proofs. Opaque: only the block renderer
/// ([`render_blocks`](crate::blocks::render_blocks)) makes them, for the frames its block
/// encloses (proofs handed to any other scene could skip tests that do not reject).
#[derive(Debug)]
pub struct BlockProofs(Role);

#[derive(Debug)]
enum Role {
    /// Record the pieces its beam searches prove root-free (the block's own pass).
    Record(Mutex<FreeRanges>),
    /// Skip the rejection tests these proofs decide (a frame of the block).
    Reuse(FreeRanges),
}

impl BlockProofs {
    /// A recorder, empty.
    pub(crate) fn recorder() -> Self {
        BlockProofs(Role::Record(Mutex::new(FreeRanges::default())))
    }

    /// Proofs for the frames of the block that recorded them.
    pub(crate) fn reuse(proven: FreeRanges) -> Self {
        BlockProofs(Role::Reuse(proven))
    }

    /// The recorded proofs (empty for proofs being reused).
    pub(crate) fn into_recorded(self) -> FreeRanges {
        match self.0 {
            Role::Record(m) => m.into_inner().unwrap_or_else(|p| p.into_inner()),
            Role::Reuse(_) => FreeRanges::default(),
        }
    }

    /// The proven pieces of `beam`, when these proofs are reused (empty otherwise).
    pub(crate) fn free(&self, beam: &BeamKey) -> &[Interval<f64>] {
        match &self.0 {
            Role::Reuse(f) => f.of(beam),
            Role::Record(_) => &[],
        }
    }

    /// Whether these proofs record.
    pub(crate) fn records(&self) -> bool {
        matches!(self.0, Role::Record(_))
    }

    /// Records `pieces` proven root-free for `beam` (nothing when reusing).
    pub(crate) fn record(&self, beam: BeamKey, pieces: &[Interval<f64>]) {
        if let Role::Record(m) = &self.0
            && let Ok(mut proofs) = m.lock()
        {
            proofs.add(beam, pieces);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn iv(a: f64, b: f64) -> Interval<f64> {
        Interval::new_unchecked(a, b)
    }

    #[test]
    fn a_piece_is_covered_only_inside_one_proof() {
        let mut f = FreeRanges::default();
        let k = BeamKey([0; 12]);
        f.add(k, &[iv(2.0, 3.0), iv(0.0, 1.0), iv(1.0, 2.0)]);
        let p = f.of(&k);
        assert!(covered(p, iv(0.0, 1.0)));
        assert!(covered(p, iv(1.25, 1.5)));
        assert!(covered(p, iv(2.0, 2.0)));
        // Straddles two proofs: unknown.
        assert!(!covered(p, iv(0.5, 1.5)));
        assert!(!covered(p, iv(2.5, 3.5)));
        assert!(!covered(p, iv(-1.0, 0.5)));
        assert!(!covered(f.of(&BeamKey([1; 12])), iv(0.0, 1.0)));
    }
}
