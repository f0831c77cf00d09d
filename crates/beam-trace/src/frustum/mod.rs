//! Primary visibility by an octree over the view frustum: each pixel's first cell where the
//! surface may be, the way a voxel renderer finds its depth image (fidget's 3D tiles), with
//! every cell a beam over a parameter range.
//!
//! A cell is a rectangle of pixels `R` and a range `T` of the ray parameter; its enclosure is
//! `g` over every ray of `R`'s beam for `t ∈ T`. Cells are searched depth first, the nearer
//! half of `T` first, so that along every pixel's column of cells they come in increasing
//! `t`; a cell whose pixels all have their first cell already is skipped, and one some of
//! whose pixels have theirs is evaluated over the beam of the smallest rectangle holding
//! the others (its *open* pixels: what is proven below is proven for their rays; the rays
//! of a filled pixel, inside or past the surface, would keep the enclosure from ever being
//! positive behind a step in depth). A cell is
//!
//! * **rejected** where its enclosure is positive (or empty: `g` undefined there): no ray
//!   of `R`'s open pixels meets the surface in `T`;
//! * **first** for the pixels of `R` that have no first cell yet where its enclosure is
//!   negative (every ray is inside: the surface lies at its near face, which only a jump or
//!   a hole in `g`'s domain allows after positive cells), or where it may vanish and it is a
//!   leaf: one pixel wide, and `T` *shallow*, no longer than `DEPTH_RATIO` times the
//!   pixel's cross-section at `T`'s far end (nor `epsilon`); a leaf longer than the
//!   cross-section that the inclusion test (below) cannot place is halved in depth first
//!   (but where exactly one ray of each pixel is traced, below);
//! * **first** for the pixels of a block of up to 8 × 8 pixels whose `T` is shallow for
//!   the block's cross-section where it passes the inclusion test (below) as a whole: every
//!   ray of every pixel of the block meets the surface in one range (a face seen head on);
//!   a block that fails it, or some of whose pixels have their first cell already (where
//!   the test fails: the rays of those pixels are inside or past the surface at `inf T`),
//!   is searched as its quadrants over the same `T`;
//! * else split: `T` in two where it is not shallow for `R`'s beam, else `R` in four and
//!   `T` in two.
//!
//! What a pixel's first cell proves: every earlier cell of its column was rejected, so no
//! ray of the pixel meets the surface before `T`: the pixel is
//! [`BoxClass::Undecided`] with `T`, and its rays search
//! from there. Where the first cell is a leaf or a block that passes the inclusion test
//! ([`inclusion_test`]: `g` continuous over the cell's beam and `T`, with opposite signs at
//! `T`'s ends for every ray, both ends inside the scene bounds) on `T`, or on `[inf T, p]`
//! for a probe `p` up to 16 lengths of `T` further, every ray of its pixels has its first
//! root in that range: each pixel is a [`BoxClass::Hit`] with it
//! as `T_final` (shallow for the pixel, or the block, before the probes). A pixel without a first cell is a
//! [`BoxClass::Miss`].
//! A cell that is split prunes `g` to the beam it was evaluated over (its open pixels')
//! and `T` ([`RayFn::restrict`]) for the cells inside it (whose open pixels and pending
//! rays, below, are among its own: a pixel only ever goes from open to pending to done),
//! where its evaluation decided a quarter of the choices or more, so the deep cells
//! evaluate a few instructions of a long formula; the restrictions of the cells holding a
//! leaf are kept, and a probe past the region of the leaf's own is evaluated with the next
//! one out (the whole `g` past them all), or first with the look-behind of the outermost
//! cell at most 16 pixels wide holding the leaf (`g` pruned for that cell's beam over its
//! range and as much again behind it, made when a probe first passes its range).
//!
//! A pixel whose first cell is an undecided leaf (its beam straddles the silhouette, or the
//! inclusion test cannot place every ray's root) may have its rays traced
//! ([`FirstCell::traced`]): its rays at the stratified positions asked for are *pending*.
//! Each is searched over the leaf's range by itself, the range halved nearer half first
//! (pruned for its halves every third halving); one rejected there goes on with the octree:
//! the cells after the leaf that hold its pixel are evaluated over the beam of their open
//! pixels and their pending rays, so that a ray past a silhouette is searched in the cells,
//! with the restrictions, of the neighbouring pixels whose columns go on behind it (rather
//! than with the long restrictions of the wide cells around the leaf), and a cell one pixel
//! wide searches each pending ray of its pixel by itself. A ray ends rejected everywhere to
//! the end of the tile's range ([`Traced::NoRoot`]), or at a range where the inclusion test
//! places its first root ([`Traced::First`]), or stuck (a graze, a jump, or its budget of
//! evaluations spent in its own searches: the renderer's root finder takes the ray over
//! from where it is proven clear, [`Traced::Clear`]). A leaf right behind cells rejected as
//! positive knows the sign at its near face and spends no evaluation on it.
//!
//! Against the screen box structure ([`crate::beam::evaluate_box_within`]), a cell costs one
//! evaluation (a leaf that may hold the surface a few more for its inclusion test; no
//! bisection of a wide beam along `T`, no `T_final` refinement), and space and screen are
//! subdivided together.

mod pixels;

use implicit_expr::Tape;
use interval_core::Interval;

use crate::beam::{BeamScope, BoxClass, Extent, inclusion_test};
use crate::camera::{Camera, EdgeBeams};
use crate::ibox::{IBox, hull};
use crate::ray::{Beam, BeamEval, RayFn};
use crate::root::RootCounters;
use crate::root::search::{Eval, sign, sign_change};
use crate::screen::{PixelRect, stratified_offsets};
use pixels::{Filled, Pending};

/// How far [`Search::included`] looks past a leaf: up to `2^LOOK_AHEAD` of its lengths.
const LOOK_AHEAD: u32 = 4;

/// The side in pixels of the cells whose restriction gets a look-behind
/// ([`Search::behind_scope`]): the outermost cell of a leaf's chain at most this wide. On
/// `csg3d-2k` at 512 × 512, 16,310 of the leaves' probes reach past the range of their
/// 16-pixel cell, and all of them fall in the ranges of 332 such cells: each look-behind
/// (one evaluation and one pruning) serves about fifty probes that would otherwise be
/// made with the tapes of cells 32 or 64 pixels wide, five times as long.
const BEHIND_SIDE: u32 = 16;

/// The side in pixels from which a cell's restriction is compiled at its first
/// evaluation ([`Tape::expect_reuse`]) rather than interpreted [`COMPILE_AFTER`] times
/// first: the cells and leaves inside a cell this wide, their probes and traced rays,
/// evaluate its restriction many times (with the look-behinds, which serve about fifty
/// evaluations each). On `csg3d-2k` at 512 × 512, one thread, a render takes 131 ms
/// against 142 (the interpreter ran the first evaluations of the tapes of the cells 16
/// to 64 pixels wide, hundreds of instructions long); sides of 2 to 8 pixels are no
/// faster, and `csg3d-660` at 1024 × 1024 is the same either way.
///
/// [`COMPILE_AFTER`]: implicit_expr::jit::COMPILE_AFTER
const HOT_SIDE: u32 = 16;

/// A cell that is split prunes `g` for the cells inside it where its evaluation decided
/// the choice of at least this share of the tape's `min`/`max` operations (a tape too
/// short to record them is pruned as before). A pruned tape serves the cells down to the
/// next pruning; pruning at every level made a tape (and, for the hot ones, compiled it)
/// for the few cells of the next level only, many of them hardly shorter. On `csg3d-2k` at
/// 512 × 512 (one thread, per render) pruning at every level made 7,000 prunings afresh
/// (8,300 more found in the cache) that read 1.9 M instructions, and compiled 490,000
/// instructions, against 14.4 M evaluated. Renders of `csg3d-2k` at 512 and 1024 and of
/// `csg3d-660` at 1024 (one thread, best of 4 to 10): pruning at every level 113–119,
/// 218–223 and 93 ms; at every second level 104–107, 208–234 and 90–91; with a share of
/// 0.15, 0.2, 0.25, 0.3, 0.4 and 0.5 103–104, 100–101, 100–101, 100–101, 101 and 107–108
/// ms; 192–201, 180–187, 178–182, 181–182, 194–197 and 196–197; 92–93, 92–94, 91–92, 91–92,
/// 90–95 and 89–90.
const PRUNE_SHARE: f64 = 0.25;

/// Tapes this short are not pruned for the cells inside a cell (a pruning costs about two
/// evaluations of the tape it prunes).
const PRUNE_MIN_LEN: usize = 16;

/// A cell is *shallow* where its range `T` is no longer than this many times its beam's
/// cross-section at `sup T` (or `epsilon`): a shallow cell one pixel wide is a leaf, a
/// shallow block is tried as one leaf, and a shallow cell is split on the screen and in
/// depth together (a cell that is not is split in depth only). Cells twice as deep as
/// wide make fewer levels of cells in front of the surface and leaves whose range more
/// often holds their rays' roots, at the cost of longer tapes where a cell decides fewer
/// choices. Unlit renders, two threads, ratio 1 → 2 (paired runs alternating, ten rounds):
/// `csg3d-2k` at 1024 × 1024 686,858 → 591,159 evaluations, 5.4 % less time; at 512 ×
/// 512 304,258 → 257,486, 3.9 % less; `csg3d-660` 6.9 and 9.4 % less (eight rounds). A
/// ratio of 3 is no faster than 2 at 1024 × 1024, and 4 is slower than 1 at 512 × 512
/// (232,856 evaluations, 3.6 % more time). A `T_final` is at most this many times the
/// cross-section before the probes (which extend it up to 16 lengths).
const DEPTH_RATIO: f64 = 2.0;

/// The side in pixels of the largest block of pixels tried as one leaf: a cell at most this
/// wide whose range is shallow (`DEPTH_RATIO`) passes the inclusion test
/// for all its pixels at once where their rays meet the surface in that range alike (a
/// face seen head on), and is searched as its quadrants over the same range where not.
/// Cell evaluations of an unlit render with blocks of 2, 4, 8 and 16 pixels a side:
/// `csg3d-2k` at 512 × 512 423,613, 378,943, 373,738 and 372,444; `csg3d-660` at 1024 ×
/// 1024 577,112 with 2, 375,887 with 8 (single pixels cost 27 % more than blocks of 2 on
/// `csg3d-660`, 46 % more on `csg3d-2k`). Beyond 8 the blocks rarely pass as a whole.
const BLOCK: u32 = 8;

/// Tapes this long are evaluated in the cells with their `min`/`max` choices recorded, so
/// that a cell that is split prunes without evaluating again.
const TRACED_MIN_LEN: usize = 24;

/// How far below its leaf size a traced ray's range is halved in search of a sign change
/// before the ray is left to the root finder: `2^-TRACE_DEPTH` of it.
const TRACE_DEPTH: i32 = 10;

/// How often a traced ray's ranges prune the tape for their halves: every third halving.
/// A pruned tape of one ray's range serves a few evaluations only, each interpreted (a tape
/// is compiled after [`implicit_expr::jit::COMPILE_AFTER`] evaluations); pruning every
/// range costs more than the shorter tapes save (csg3d-2k at 512 and 1024 on 2 threads:
/// 100 and 212 ms a render pruning every range, 91 and 189 every third, 92 and 190 every
/// fourth).
const TRACE_PRUNE_EVERY: u32 = 3;

/// The evaluations a traced ray may spend in its own searches (over its leaf's range and
/// in the cells of its pixel alone; not in the cells it shares with other pixels' rays)
/// before it is left to the root finder. Bisection finds a ray's first root or its absence
/// in a few dozen evaluations where the pruned formulas are tight (the CSG models: 90 % of
/// the rays in fewer than 16); where a ray runs long beside a surface it can take hundreds
/// (the default scene: half of them more than 64), and the root finder's Newton steps are
/// cheaper there.
const TRACE_BUDGET: u64 = 32;

/// Where a pixel's surface may begin: the range `t` of its first cell (no ray of the pixel
/// meets the surface before it), whether every ray of the pixel meets it there, and the
/// scene function pruned to a region holding the cell.
#[derive(Clone, Debug, PartialEq)]
pub struct FirstCell {
    /// The parameter range of the cell.
    pub t: Interval<f64>,
    /// Every ray of the pixel has its first root in `t` (the inclusion test passed).
    pub hit: bool,
    /// `g` pruned for a cell holding this one, for the pixel's rays over the scope's own
    /// parameters: `t` for a Hit, the whole region of the restriction (which holds `t`)
    /// otherwise.
    pub scope: Option<BeamScope>,
    /// What the search of each of the pixel's traced rays (at the stratified positions of
    /// the number asked for) found from `inf t` on; empty where none was traced (a Hit, or
    /// no tracing asked for).
    pub traced: Vec<Traced>,
}

/// What the search of one of an undecided pixel's rays (through a position of the pixel,
/// as [`Camera::ray`] makes it) proved from its first cell on, in the cells after it that
/// hold the pixel, with their restrictions.
#[derive(Clone, Debug, PartialEq)]
pub enum Traced {
    /// No root: the ray meets no surface (every range of it was rejected up to the end of
    /// the tile's range, past which no ray of the tile is in a non-empty grid cell).
    NoRoot,
    /// The ray's first root lies in `t`: every earlier range was rejected, `g` is
    /// continuous over `t` with opposite signs at its ends, both inside the scene bounds.
    First {
        /// The range: no longer than the pixel's cross-section there (or `epsilon`), or
        /// where the inclusion test of a block of pixels placed every ray of the block's
        /// open pixels and pending rays, that block's range.
        t: Interval<f64>,
        /// `g` pruned for the ray over a range holding `t`, its parameters `t`.
        scope: Option<BeamScope>,
    },
    /// No root before `until`; past it the search got stuck (a graze, a jump) or ran out of
    /// its budget of evaluations (32 in its own searches) and the root finder takes the ray
    /// over.
    Clear {
        /// Where the part of the ray proven root-free ends.
        until: f64,
    },
}

/// How a range of a traced ray came out.
enum Step {
    /// No root in it; `positive_end`: `g > 0` is proven at its end (its enclosure was
    /// positive; an empty one, `g` undefined there, proves no sign).
    Rejected { positive_end: bool },
    /// The first root is in it (see [`Traced::First`]).
    Found(Interval<f64>, Option<BeamScope>),
    /// Neither could be proven from the parameter it holds on (a graze, a jump, a range too
    /// short to halve, the budget spent): every parameter before it was rejected.
    Stuck(f64),
}

impl FirstCell {
    /// What a pending ray of this cell's rectangle (not yet settled before it) proved,
    /// where the cell is the first for the rectangle's open pixels: a Hit's inclusion test
    /// holds for every ray of the cell's beam, the pending ray's too, so its first root is
    /// in `t`; where every ray is inside at once (an undecided cell that is not a leaf), the
    /// ray is clear up to `inf t`.
    fn settles(&self) -> Traced {
        if self.hit {
            Traced::First {
                t: self.t,
                scope: self.scope.clone(),
            }
        } else {
            Traced::Clear {
                until: self.t.inf(),
            }
        }
    }

    /// The pixel's class: a Hit with `T_final = t` where every ray meets the surface in
    /// `t`, else Undecided in `t`.
    pub fn class(&self) -> BoxClass {
        if self.hit {
            BoxClass::Hit { t_final: self.t }
        } else {
            BoxClass::Undecided { t: self.t }
        }
    }
}

/// The first cells of a tile's pixels that have one, in the order the search found them;
/// the tile's other pixels are proven missed (no ray of theirs meets a surface in the range
/// searched). Sparse, so that a tile costs what its surface does, not a record per pixel;
/// the pixels of one leaf share its record.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TileCells {
    /// The cells, each the first cell of one or more pixels.
    pub cells: Vec<FirstCell>,
    /// Each pixel that has a first cell: its row-major index in the tile, and its cell's
    /// index in [`cells`](Self::cells). A pixel appears once.
    pub pixels: Vec<(u32, u32)>,
}

impl TileCells {
    /// The number of pixels that have a first cell.
    pub fn len(&self) -> usize {
        self.pixels.len()
    }

    /// Whether no pixel has a first cell (every one is proven missed).
    pub fn is_empty(&self) -> bool {
        self.pixels.is_empty()
    }

    /// Each pixel that has a first cell, by its row-major index in the tile, with that
    /// cell.
    pub fn iter(&self) -> impl Iterator<Item = (u32, &FirstCell)> {
        self.pixels
            .iter()
            .map(|&(k, c)| (k, &self.cells[c as usize]))
    }
}

/// The memory a tile's search works in, kept from one tile to the next so that a render
/// does not map fresh pages for every tile (a tile of 64 × 64 pixels makes up to 5,461
/// columns).
#[derive(Default)]
pub struct Scratch {
    columns: Columns,
    filled: Filled,
    pending: Pending,
}

/// The first cell of each pixel of `tile` that has one ([`TileCells`]), searched in the
/// parameter range `range` (where the tile's beam lies in the scene bounds `bounds`), with `g` the scene
/// function of the camera's beams; leaves are no longer than `epsilon` or
/// `DEPTH_RATIO` times the pixel's cross-section. With `traced_rays` more than 0, the rays of each pixel whose first cell
/// is an undecided leaf, at the stratified positions of that many, are searched on from
/// there ([`FirstCell::traced`]). Counts each cell's evaluation (and the inclusion tests',
/// and the traced rays') in `counters.g_evals`.
/// `scratch` is working memory (what it held before does not matter).
pub fn first_cells(
    (g, scratch): (&mut BeamEval, &mut Scratch),
    (cam, beams, bounds): (&Camera, &EdgeBeams, &IBox),
    tile: PixelRect,
    (range, epsilon, traced_rays): (Interval<f64>, f64, u32),
    counters: &mut RootCounters,
) -> TileCells {
    let nodes = quadtree_nodes(tile).unwrap_or(0);
    scratch.columns.reset(nodes);
    scratch.filled.reset(tile, nodes);
    let traced = if traced_rays == 0 {
        Vec::new()
    } else {
        stratified_offsets(traced_rays)
    };
    scratch.pending.reset(tile.area() as usize, traced.len());
    let mut search = Search {
        g,
        cam,
        traced,
        beams,
        bounds,
        range,
        tile,
        epsilon,
        first: TileCells::default(),
        look_from: 0,
        filled: &mut scratch.filled,
        pending: &mut scratch.pending,
        counters,
        chain: Vec::new(),
        columns: &mut scratch.columns,
        behind: None,
    };
    if !range.is_empty() {
        let column = search.column(tile, 0);
        search.visit(&column, range, false);
    }
    search.first
}

/// A rectangle of pixels with its beam and the beam's largest spread of directions (its
/// cross-section at `t` is the spread times `t`: the origin is the eye), and its node in
/// the tile's quadtree.
#[derive(Copy, Clone)]
struct Column {
    r: PixelRect,
    beam: Beam,
    spread: f64,
    node: usize,
}

impl Column {
    /// The column of `r`, node `node` of the quadtree, whose beam `beams` gives.
    fn of(beams: &EdgeBeams, r: PixelRect, node: usize) -> Self {
        let beam = beams.beam(r);
        let spread = beam.dir.iter().map(|d| d.wid()).fold(0.0, f64::max);
        Self {
            r,
            beam,
            spread,
            node,
        }
    }

    /// The quadtree node of the quadrant at `position` (0 to 3) of this column's rectangle:
    /// the tile is node 0, the quadrants of node `n` are `4n + 1` to `4n + 4`.
    fn child(&self, position: usize) -> usize {
        // Saturating: a node past any table (a tile deeper than `MAX_DEPTH`) is looked up
        // nowhere.
        self.node.saturating_mul(4).saturating_add(1 + position)
    }
}

/// Tiles whose quadtree is deeper than this (wider than 1024 pixels) keep no table per node
/// (it would hold more than a million nodes): their columns are made each time and their
/// filled pixels counted from the bitmap.
const MAX_DEPTH: u32 = 10;

/// The row-major index of pixel `(x, y)` in `tile`.
fn pixel_index(tile: PixelRect, x: u32, y: u32) -> usize {
    let width = (tile.x1 - tile.x0) as usize;
    (y - tile.y0) as usize * width + (x - tile.x0) as usize
}

/// The number of nodes of `tile`'s quadtree where it is at most [`MAX_DEPTH`] deep.
fn quadtree_nodes(tile: PixelRect) -> Option<usize> {
    // Halving a side of `n` pixels (the larger half first) reaches one pixel after
    // `ceil(log2 n)` splits.
    let side = tile.side().max(1);
    let depth = side.next_power_of_two().trailing_zeros();
    (depth <= MAX_DEPTH).then(|| (4usize.pow(depth + 1) - 1) / 3)
}

/// The columns of a tile's quadtree made so far, by node: a rectangle is split again in
/// each range of its parent's column that is split, and its beam (rounded sums per axis)
/// is made once.
#[derive(Default)]
struct Columns {
    /// Per node, 0 where its column is not made yet, else its index in `made` plus one.
    slots: Vec<u32>,
    made: Vec<Column>,
}

impl Columns {
    /// No column made, with a table of `nodes` nodes (0: none kept, see [`MAX_DEPTH`]).
    fn reset(&mut self, nodes: usize) {
        self.slots.clear();
        self.slots.resize(nodes, 0);
        self.made.clear();
    }
}

/// One tile's search.
struct Search<'a> {
    g: &'a mut BeamEval,
    cam: &'a Camera,
    /// The positions inside an undecided pixel of the rays traced (none: no tracing).
    traced: Vec<(f64, f64)>,
    beams: &'a EdgeBeams,
    bounds: &'a IBox,
    range: Interval<f64>,
    tile: PixelRect,
    epsilon: f64,
    first: TileCells,
    /// The pixels that have their first cell in `first`, and those of them with rays
    /// pending.
    filled: &'a mut Filled,
    /// The rays of the pixels pending.
    pending: &'a mut Pending,
    counters: &'a mut RootCounters,
    /// The restrictions of `g` of the cells holding the one searched, outermost first
    /// (each over its own cell's open pixels and range, a part of the one before); empty:
    /// the whole `g`.
    chain: Vec<BeamScope>,
    /// The columns made so far.
    columns: &'a mut Columns,
    /// The look-behind of the outermost restriction of the chain made for a cell at most
    /// [`BEHIND_SIDE`] pixels wide, where there is one.
    behind: Option<Behind>,
    /// The probe of [`Search::included`] at which the tile's last passing leaf found every
    /// ray's sign changed (0 before any): the next leaf's probes start one before it.
    look_from: u32,
}

/// The look-behind of a restriction of the chain ([`Search::behind_scope`]): `g` pruned
/// for the beam of the restricted cell over its range and as much again behind it.
struct Behind {
    /// The index of the restriction in [`Search::chain`].
    at: usize,
    /// The beam the restricted cell was evaluated over (its open pixels').
    beam: Beam,
    /// The look-behind once made: `None` before; `Some(None)` where it would not be
    /// shorter than the tapes it stands for, or the cell's range reaches the end of the
    /// tile's (nothing lies behind it).
    scope: Option<Option<BeamScope>>,
}

impl Search<'_> {
    /// The column of `r`, node `node` of the tile's quadtree, made on first use.
    fn column(&mut self, r: PixelRect, node: usize) -> Column {
        let Columns { slots, made } = &mut self.columns;
        let Some(slot) = slots.get_mut(node) else {
            return Column::of(self.beams, r, node);
        };
        if *slot == 0 {
            made.push(Column::of(self.beams, r, node));
            *slot = made.len() as u32;
        }
        made[*slot as usize - 1]
    }

    /// Where every ray of the leaf's beam (set on `g` with the innermost restriction: the
    /// beam of its open pixels, which are the ones a result is for) has its first root,
    /// given none before `t`, and the restriction that holds there: `[inf t, p]` for the
    /// first `p` of `sup t` and `sup t + w·2^k` (`k ≤` [`LOOK_AHEAD`], `w` the length of
    /// `t`) where the sign has changed for every ray since `inf t` (known
    /// positive there where `near_positive`), with `g` continuous up to `p` and both ends
    /// inside the scene bounds. The probes start one before the one at which the tile's
    /// last passing leaf stopped ([`Search::look_from`]): neighbouring leaves lie about as
    /// deep below the surface, and where every ray is inside only several leaf lengths past
    /// the leaf (a pixel on a sphere's flank) the nearer probes would be spent in vain, or
    /// give the look-ahead up too soon (on the CSG models 3 to 13 % fewer evaluations and
    /// more leaves passing; a probe's proof is the same whichever probes came before it).
    /// Each probe is made with the innermost restriction whose region holds it (the whole
    /// `g` past the region of every one), so the probes reach as far as the leaf's depth
    /// needs, each made once. Where `g > 0` at `inf t` and a probe's upper bound is no
    /// lower than the last one's (a ray that passes the surface by), or would
    /// still be positive at the last probe if it kept falling at the rate it fell since the
    /// last one, the probes stop: the leaf is left undecided (this decides nothing wrongly,
    /// it only gives up).
    fn included(
        &mut self,
        beam: &Beam,
        t: Interval<f64>,
        extent: &Extent<'_>,
        near_positive: bool,
    ) -> Option<(Interval<f64>, Option<BeamScope>)> {
        let (a, b, w) = (t.inf(), t.sup(), t.wid());
        if w.is_nan() || w <= 0.0 {
            return None;
        }
        let start = if near_positive {
            Interval::new_unchecked(f64::MIN_POSITIVE, f64::MAX)
        } else {
            Eval::new(&mut *self.g, self.counters).at(a)
        };
        if sign(start) == 0 {
            return None;
        }
        // Level `k` is the restriction `chain[k - 1]`, level 0 the whole `g` (for probes
        // past the region of every restriction: the tile's own cell may not prune, see
        // `PRUNE_SHARE`); the leaf's beam is set with the innermost.
        let range_end = self.range.sup();
        let limit = |chain: &[BeamScope], k: usize| match k {
            0 => range_end,
            k => chain[k - 1].t.sup(),
        };
        let mut level = self.chain.len();
        // The look-behind, once a probe passes the range of its restriction.
        let mut behind: Option<BeamScope> = None;
        let mut tried_behind = false;
        let mut step = 0.0;
        // The upper bound of `g` at the last probe (`g > 0` at `inf t` is what the probes
        // look past).
        let mut last_sup = f64::INFINITY;
        // Where the last probe was, and where the last one can be.
        let mut last_p = b;
        let reach = b + w * 2f64.powi(LOOK_AHEAD as i32);
        // The probes before the one the tile's last passing leaf stopped at, but one, are
        // not made.
        let first = self.look_from.saturating_sub(1);
        for k in 0..=LOOK_AHEAD + 1 {
            let p = b + step;
            step = if k == 0 { w } else { 2.0 * step };
            if k < first {
                continue;
            }
            let was = (level, behind.is_some());
            while level > 0 && limit(&self.chain, level) < p {
                level -= 1;
            }
            if behind.as_ref().is_some_and(|s| s.t.sup() < p) {
                behind = None;
            }
            // Past the range of the restriction with a look-behind, within the look-behind's
            // range: probed with it (made now where it is not yet, which sets another beam).
            let mut reset = false;
            if !tried_behind && self.behind.as_ref().is_some_and(|b| level <= b.at) {
                tried_behind = true;
                behind = self.behind_scope().filter(|s| s.t.sup() >= p);
                reset = true;
            }
            if reset || (level, behind.is_some()) != was {
                let scope = match &behind {
                    Some(s) => Some(&s.tape),
                    None => level.checked_sub(1).map(|i| &self.chain[i].tape),
                };
                self.g.set_interval_beam(beam, scope);
            }
            if limit(&self.chain, level) < p {
                // Past the tile's range.
                return None;
            }
            let mut ev = Eval::new(&mut *self.g, self.counters);
            let at = ev.at(p);
            if !sign_change(start, at) {
                if sign(start) > 0 && at.sup() >= last_sup {
                    // Some ray of the leaf is no nearer the surface than at the last probe
                    // (it passes the surface by, at a silhouette): the look-ahead is given
                    // up rather than spent on ever longer tapes.
                    return None;
                }
                if sign(start) > 0 && k > 0 && last_sup.is_finite() {
                    // Nor is it given up for less: where the upper bound, falling on at
                    // the rate it fell since the last probe, would still be positive at
                    // the last probe, some ray is unlikely to have met the surface by then
                    // (on the CSG models 3 to 10 % fewer evaluations; a few leaves that
                    // would have passed at a later probe are left undecided).
                    let fall = (last_sup - at.sup()) / (p - last_p);
                    if p + at.sup() / fall > reach {
                        return None;
                    }
                }
                last_sup = at.sup();
                last_p = p;
                continue;
            }
            if !extent.holds(p) {
                return None;
            }
            let h = Interval::new_unchecked(a, p);
            self.look_from = k;
            let continuous = ev.continuous(h);
            let scope = behind.or_else(|| level.checked_sub(1).map(|i| self.chain[i].clone()));
            return continuous.then_some((h, scope));
        }
        None
    }

    /// The range `t` of the ray `beam` (a beam of one ray) searched with `tape` (the whole
    /// `g` for `None`), the nearer half first, the ranges `depth` halvings down from the
    /// window (1 for the window itself) that are a multiple of [`TRACE_PRUNE_EVERY`]
    /// pruning the tape for their halves: rejected where the enclosure is positive or empty;
    /// the first root's where the range is no longer than the pixel's cross-section
    /// (`spread` times `t`, or `epsilon`) and passes the inclusion test with both ends in
    /// the scene bounds; else halved, down to `2^-TRACE_DEPTH` of that length, while the
    /// evaluations counted stay below `budget`.
    fn trace_range(
        &mut self,
        beam: &Beam,
        t: Interval<f64>,
        tape: Option<&Tape>,
        (start_positive, (spread, budget, depth)): (bool, (f64, u64, u32)),
    ) -> Step {
        if self.counters.g_evals >= budget {
            return Step::Stuck(t.inf());
        }
        self.g.set_interval_beam(beam, tape);
        let gt = self.enclosure(t);
        if gt.is_empty() || gt.inf() > 0.0 {
            return Step::Rejected {
                positive_end: !gt.is_empty(),
            };
        }
        if gt.sup() < 0.0 {
            // Inside right after rejected ranges: a jump, or a root at `inf t` that needs
            // the root finder's care.
            return Step::Stuck(t.inf());
        }
        let leaf = self.epsilon.max(spread * t.sup().abs());
        let extent = Extent {
            beam,
            bounds: self.bounds,
        };
        if t.wid() <= leaf
            && extent.holds(t.inf())
            && extent.holds(t.sup())
            && self.includes_root(t, start_positive)
        {
            let scope = tape.map(|tape| BeamScope {
                tape: tape.clone(),
                t,
                escalated: false,
            });
            return Step::Found(t, scope);
        }
        let (near, far) = t.bisect();
        if t.wid() <= leaf * 2f64.powi(-TRACE_DEPTH) || near.is_empty() || far.is_empty() {
            return Step::Stuck(t.inf());
        }
        // The halves search with the tape pruned to this range where that shortens it.
        // The ray and tape are still those of the evaluation above (the inclusion test
        // only evaluates them): its choices, where recorded, prune.
        let inner = if depth.is_multiple_of(TRACE_PRUNE_EVERY) {
            self.pruned_to(t).or_else(|| tape.cloned())
        } else {
            tape.cloned()
        };
        let below = (spread, budget, depth + 1);
        match self.trace_range(beam, near, inner.as_ref(), (start_positive, below)) {
            Step::Rejected { positive_end } => {
                self.trace_range(beam, far, inner.as_ref(), (positive_end, below))
            }
            step => step,
        }
    }

    /// The inclusion test of a traced ray's range `t` (`g` continuous over it, with
    /// opposite signs at its ends), where `start_positive` says that `g > 0` is proven at
    /// `inf t` already (a range before it was rejected as positive, or the first cell's
    /// near face): then only its end is evaluated.
    fn includes_root(&mut self, t: Interval<f64>, start_positive: bool) -> bool {
        if !start_positive {
            return inclusion_test(&mut *self.g, t, self.counters);
        }
        let mut ev = Eval::new(&mut *self.g, self.counters);
        ev.continuous(t) && ev.at(t.sup()).sup() < 0.0
    }

    /// The look-behind of the chain's restriction made for a cell at most [`BEHIND_SIDE`]
    /// pixels wide (made on first use): `g` pruned for the beam that cell was evaluated
    /// over and the range `[inf t, sup t + wid t]` of its range `t` (within the tile's),
    /// from the tape of the innermost restriction whose range holds that (the whole `g`
    /// without one). It holds for every leaf inside the cell, over the cell's range and as
    /// far again behind it: where a leaf's probes or traced rays pass the cell's range,
    /// they go on with it rather than with the tapes of the wider cells around. `None`
    /// where there is no such restriction, or pruning does not shorten the tape. Changes
    /// the beam set on `g`.
    fn behind_scope(&mut self) -> Option<BeamScope> {
        let b = self.behind.as_ref()?;
        if let Some(made) = &b.scope {
            return made.clone();
        }
        let (at, beam) = (b.at, b.beam);
        let t = self.chain[at].t;
        let end = (t.sup() + t.wid()).min(self.range.sup());
        let made = if end > t.sup() {
            let region = Interval::new_unchecked(t.inf(), end);
            let outer = (0..at)
                .rev()
                .find(|&i| self.chain[i].t.sup() >= end)
                .map(|i| self.chain[i].tape.clone());
            self.g.set_interval_beam(&beam, outer.as_ref());
            self.enclosure(region);
            self.pruned_to(region)
                // Worth it only where it is shorter than the tape it stands for.
                .filter(|tape| tape.len() < outer.as_ref().map_or(usize::MAX, Tape::len))
                .map(|tape| {
                    tape.expect_reuse();
                    BeamScope {
                        tape,
                        t: region,
                        escalated: false,
                    }
                })
        } else {
            None
        };
        if let Some(b) = &mut self.behind {
            b.scope = Some(made.clone());
        }
        made
    }

    /// The tape set pruned to `t` on the beam set (by the choices of the evaluation just
    /// made there, where it recorded them), where the tape is long enough to prune and the
    /// pruning shortens it; the evaluator then holds it. `None`: the tape set stays.
    fn pruned_to(&mut self, t: Interval<f64>) -> Option<Tape> {
        let current = self.g.scope().filter(|tape| tape.len() > PRUNE_MIN_LEN)?;
        self.g.restrict_traced(t);
        self.g.scope().filter(|p| !p.ptr_eq(&current))
    }

    /// `g` over `t` on the beam and tape set, counted. A long tape is evaluated with its
    /// choices recorded, so that a cell or range that is split prunes by them
    /// (`restrict_traced`) instead of evaluating again.
    fn enclosure(&mut self, t: Interval<f64>) -> Interval<f64> {
        self.counters.g_evals += 1;
        if self.g.scope_len() >= TRACED_MIN_LEN {
            self.g.g_traced(t)
        } else {
            self.g.g(t)
        }
    }

    /// Searches the cell `column × t` with the innermost restriction of the chain, where
    /// `near_positive` says that `g > 0` at `inf t` on every ray of the cell's pixels that
    /// have no first cell yet and of its pending rays (a cell before it in each of their
    /// columns was rejected as positive). Returns whether that is proven at `sup t` (for
    /// those rays).
    fn visit(&mut self, column: &Column, t: Interval<f64>, near_positive: bool) -> bool {
        let Column {
            r,
            ref beam,
            spread,
            ..
        } = *column;
        if self.filled.complete(r, column.node) {
            return false;
        }
        if r.is_pixel() && self.filled.is_pending(r.x0, r.y0) {
            return self.search_rays(column, t, near_positive);
        }
        // Only the pixels without a first cell, and the pending rays, are searched on:
        // where some pixel has one, the cell is evaluated over the beam of the smallest
        // rectangle holding the open pixels and of the pending rays (the other rays of the
        // pixels with a first cell, inside or past the surface there, would keep the
        // enclosure from being positive all the way to their own surface behind).
        let untouched = self.filled.untouched(r, column.node);
        let across = spread * t.sup().abs();
        let shallow = t.wid() <= self.epsilon.max(DEPTH_RATIO * across);
        // A shallow cell (a block, below, or a wider one) some of whose pixels have their
        // first cell straddles a step in depth: where a filled pixel lies in its open
        // rectangle, that pixel's rays are inside (or past) the surface at `inf t` and the
        // others' are not, so `g` at `inf t` has no one sign over the beam and a block's
        // inclusion test fails (on the CSG models, for 98 % of such blocks; where none
        // does, testing the open pixels as a block gains nothing: csg3d-2k, 3 % more
        // evaluations), and its enclosure over the open pixels rarely rejects them all.
        // Its quadrants are searched, without an evaluation of the cell. Blocks only:
        // csg3d-2k at 512 × 512 5 % fewer evaluations, a render 108 → 104 ms; at 1024 ×
        // 1024 7 % fewer; csg3d-660 3 % more, in the same time. Cells of any width: 2 %
        // fewer again on csg3d-2k, where they are the wide cells' long tapes, and 1 to 5 %
        // less time on it (one or two threads, 512 and 1024); csg3d-660 the same.
        if !untouched && !r.is_pixel() && shallow {
            return self.quadrants(column, &[t], near_positive);
        }
        let shrunk;
        let beam = if untouched {
            beam
        } else {
            let Some(open) = self.open_beam(r, column.node) else {
                return false;
            };
            shrunk = open;
            &shrunk
        };
        self.g
            .set_interval_beam(beam, self.chain.last().map(|s| &s.tape));
        let gt = self.enclosure(t);
        if gt.is_empty() {
            return false;
        }
        if gt.inf() > 0.0 {
            return true;
        }
        let leaf = r.is_pixel() && shallow;
        // A block: a leaf, or a cell of a few pixels as shallow, tried as one leaf.
        let block = r.side() <= BLOCK && shallow;
        if gt.sup() < 0.0 || block {
            let extent = Extent {
                beam,
                bounds: self.bounds,
            };
            // (No pixel of a block has its first cell: see above.)
            let included = if block && gt.inf() < 0.0 && extent.holds(t.inf()) {
                self.included(beam, t, &extent, near_positive)
            } else {
                None
            };
            if included.is_none() && gt.sup() >= 0.0 && !r.is_pixel() {
                // A block whose rays the inclusion test cannot place together: its
                // quadrants over the same range (most are rejected where the block only
                // grazes the surface), down to single pixels.
                return self.quadrants(column, &[t], near_positive);
            }
            if included.is_none()
                && gt.sup() >= 0.0
                && self.traced.len() != 1
                && t.wid() > self.epsilon.max(across)
            {
                // A leaf deeper than its pixel is wide that the inclusion test cannot
                // place: its halves in depth, each a leaf again, down to leaves as deep as
                // wide, which are left undecided. A longer undecided leaf leaves more of
                // its rays' search to the root finder after the octree (the default scene
                // at 640 × 480, unlit: 690 → 636 ms), or to the octree's traced rays, each
                // searched on by itself (the gallery, nine rays a pixel: 7.36 → 6.82 s).
                // One traced ray searches on from the leaf more cheaply than the leaf's
                // halves (csg3d-2k at 512 × 512: 257,486 evaluations against 306,968).
                return self.split(column, (*beam, t), (near_positive, false));
            }
            // A Hit's scope is asked about its range only; an undecided cell's keeps the
            // whole region it holds for, where the pixel's rays search on from the cell.
            let first = match included {
                Some((range, holds)) => FirstCell {
                    t: range,
                    hit: true,
                    scope: holds.map(|s| BeamScope { t: range, ..s }),
                    traced: Vec::new(),
                },
                None => FirstCell {
                    t,
                    hit: false,
                    scope: self.chain.last().cloned(),
                    traced: Vec::new(),
                },
            };
            let (tile, found) = (self.tile, &mut self.first);
            let cell = found.cells.len() as u32;
            found.cells.push(first);
            if leaf && !found.cells[cell as usize].hit && !self.traced.is_empty() {
                // The pixel's rays are searched on from its first cell, in the cells around
                // it where the octree searches its neighbours' columns.
                found
                    .pixels
                    .push((pixel_index(tile, r.x0, r.y0) as u32, cell));
                self.pend(column, cell);
                return self.search_rays(column, t, near_positive);
            }
            let (pending, filled) = (&mut *self.pending, &mut *self.filled);
            let mut opened = false;
            filled.fill(r, column.node, |x, y, was_pending| {
                let k = pixel_index(tile, x, y);
                if was_pending {
                    pending.settle_all(k, |first, i| {
                        let settled = found.cells[cell as usize].settles();
                        found.cells[first as usize].traced[i] = settled;
                    });
                } else {
                    found.pixels.push((k as u32, cell));
                    opened = true;
                }
            });
            if !opened {
                // Only pending rays were settled here.
                found.cells.pop();
            }
            return false;
        }
        self.split(column, (*beam, t), (near_positive, shallow))
    }

    /// The beam of the open pixels of `r`, node `node` of the quadtree, and of the pending
    /// rays inside it; `None` where there is neither.
    fn open_beam(&self, r: PixelRect, node: usize) -> Option<Beam> {
        let mut beam = self.filled.open(r).map(|open| self.beams.beam(open));
        self.filled.pending_in(r, node, |x, y| {
            for ray in self.pending.rays_of(pixel_index(self.tile, x, y)) {
                beam = Some(match beam {
                    None => *ray,
                    Some(b) => Beam {
                        origin: hull(&b.origin, &ray.origin),
                        dir: hull(&b.dir, &ray.dir),
                    },
                });
            }
        });
        beam
    }

    /// Makes the leaf `column`'s pixel, whose first cell is `cell` (undecided), pending:
    /// its rays at the stratified positions asked for are searched on from there.
    fn pend(&mut self, column: &Column, cell: u32) {
        let (x, y) = (column.r.x0, column.r.y0);
        self.first.cells[cell as usize].traced = vec![Traced::NoRoot; self.traced.len()];
        let cam = self.cam;
        let rays = self
            .traced
            .iter()
            .map(|&(ox, oy)| cam.ray(f64::from(x) + ox, f64::from(y) + oy).beam());
        let k = pixel_index(self.tile, x, y);
        self.pending.add(k, (column.node, cell), rays, TRACE_BUDGET);
        self.filled.pend(x, y, column.node);
    }

    /// Searches each pending ray of the pixel `column` over `t` by itself
    /// ([`Search::trace_range`], with the innermost restriction, within what is left of the
    /// ray's [`TRACE_BUDGET`] evaluations), where `near_positive` says that `g > 0` at
    /// `inf t` on each: a ray rejected stays pending, one whose first root the search
    /// places, or that gets stuck, is settled. Returns whether `g > 0` is proven at `sup t`
    /// on every ray still pending.
    fn search_rays(&mut self, column: &Column, t: Interval<f64>, near_positive: bool) -> bool {
        let (x, y) = (column.r.x0, column.r.y0);
        let k = pixel_index(self.tile, x, y);
        let Some(&pixel) = self.pending.pixel(k) else {
            return false;
        };
        let tape = self.chain.last().map(|s| s.tape.clone());
        let mut positive = true;
        for i in 0..self.traced.len() {
            let Some(ray) = self.pending.ray(k, i) else {
                continue;
            };
            let before = self.counters.g_evals;
            let traced = (near_positive, (column.spread, before + ray.budget, 1));
            let step = self.trace_range(&ray.beam, t, tape.as_ref(), traced);
            let settled = match step {
                Step::Rejected { positive_end } => {
                    self.pending.spend(k, i, self.counters.g_evals - before);
                    positive &= positive_end;
                    continue;
                }
                Step::Found(t, scope) => Traced::First { t, scope },
                Step::Stuck(until) => Traced::Clear { until },
            };
            self.first.cells[pixel.cell as usize].traced[i] = settled;
            if self.pending.settle(k, i) {
                self.filled.settle(x, y, pixel.node);
                return false;
            }
        }
        positive
    }

    /// Searches each quadrant of `column` over `ranges` in turn (consecutive, nearest
    /// first), where `near_positive` says that `g > 0` at the near end of the first for every
    /// ray of the column's pixels without a first cell and of its pending rays. Returns
    /// whether that is proven at the far end of the last.
    fn quadrants(
        &mut self,
        column: &Column,
        ranges: &[Interval<f64>],
        near_positive: bool,
    ) -> bool {
        let mut all = true;
        for (k, q) in column.r.numbered_quadrants() {
            if self.filled.complete(q, column.child(k)) {
                // Every range would return at once (not proven positive): no beam.
                all = false;
                continue;
            }
            let quadrant = self.column(q, column.child(k));
            let mut positive = near_positive;
            for &t in ranges {
                positive = self.visit(&quadrant, t, positive);
            }
            all &= positive;
        }
        all
    }

    /// Searches the cells inside the cell `column × t` (see [`Search::visit`]), with `g`
    /// pruned to it: `t` in two where it is not shallow for the column's beam (see
    /// `DEPTH_RATIO`), else the rectangle in four and `t` in two. Returns whether `g > 0`
    /// is proven at `sup t` for every ray of the column's pixels without a first cell and of
    /// its pending rays.
    fn split(
        &mut self,
        column: &Column,
        (beam, t): (Beam, Interval<f64>),
        (near_positive, shallow): (bool, bool),
    ) -> bool {
        // The cells inside this one search with `g` pruned to it where its evaluation
        // decided enough choices (`PRUNE_SHARE`); elsewhere, or where pruning shortens
        // nothing, the tape keeps the wider region it holds for.
        let worth = self
            .g
            .decided_share(t)
            .is_none_or(|share| share >= PRUNE_SHARE);
        let pruned = if worth { self.pruned_to(t) } else { None };
        let pushed = match pruned {
            Some(tape) => {
                let side = column.r.side();
                if side >= HOT_SIDE {
                    tape.expect_reuse();
                }
                if self.behind.is_none() && side <= BEHIND_SIDE {
                    self.behind = Some(Behind {
                        at: self.chain.len(),
                        beam,
                        scope: None,
                    });
                }
                self.chain.push(BeamScope {
                    tape,
                    t,
                    escalated: false,
                });
                true
            }
            None => false,
        };
        // Each pixel's cells come in increasing `t` either way: a quadrant's halves one
        // after the other.
        let (near, far) = t.bisect();
        let far_positive = if shallow {
            self.quadrants(column, &[near, far], near_positive)
        } else {
            let middle = self.visit(column, near, near_positive);
            self.visit(column, far, middle)
        };
        if pushed {
            self.chain.pop();
            if self
                .behind
                .as_ref()
                .is_some_and(|b| b.at == self.chain.len())
            {
                self.behind = None;
            }
        }
        far_positive
    }
}
