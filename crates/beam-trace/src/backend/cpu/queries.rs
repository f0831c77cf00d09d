//! The CPU's queries for one scene: per-thread evaluators, and the searches every answer is
//! made of (beam classification, first roots, shading points).

use std::ops::{Deref, DerefMut};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::Instant;

use interval_core::Interval;
use rayon::prelude::*;

use crate::backend::query::Answers;
use crate::backend::query::{BeamQuery, CellQuery, Classified, DirectHits};
use crate::beam::{
    BeamScope, BoxClass, Extent, Inherited, child_window, evaluate_box_within, forward,
};
use crate::camera::EdgeBeams;
use crate::free_ranges::BeamKey;
use crate::frustum::{self, TileCells, first_cells};
use crate::grid::{Grid, GridEval};
use crate::mesh::MeshIndex;
use crate::plan::Plan;
use crate::ray::{Beam, BeamEval, Precision, Ray};
use crate::root::{Escalating, RayFn, RootCounters, RootFinder, RootResult, RootSettings};
use crate::sample::Hit;
use crate::scene::Scene;
use crate::scene::geometry::GeometryEval;
use crate::screen::PixelRect;

use super::scoped::{ScopedEval, ScopedFunctions};

/// The mean length of the grid's cell functions from which tracing an undecided pixel's
/// rays in the frustum octree pays ([`CellQuery::traced_rays`]). Measured on the
/// `render3d_compare` models and the default scene (2 threads, `render` with the octree):
/// csg3d-2k (cell functions of 59 instructions) 0.79 s without tracing, 0.69 s with it;
/// csg3d-660 (16) 0.53 s either way; the default scene (22, 9 rays per pixel) 2.07 s
/// without, 2.73 s with; the root finder's Newton steps through short cell functions beat
/// the bisection of long rays.
const TRACE_MIN_CELL_INSTRS: u64 = 32;

/// The number of distinct cell functions of the grid from which tracing an undecided
/// pixel's rays in the frustum octree pays whatever their length: the root finder compiles
/// each cell function it meets for rays (`g` and `g'` by symbolic differentiation, about
/// 190 k instructions on the CSG models, as much as a few hundred evaluations), and through
/// a grid of hundreds of functions the undecided rays pay for compiling most of them, while
/// the octree traces with the pruned tapes it holds. csg3d-660 (769 functions of 16
/// instructions) at 512 × 512 on one thread: 2.10 G instructions without tracing, 1.89 G with
/// it (482 functions compiled for 6.6 k rays before); the default scene has 13.
const TRACE_MIN_CELL_FUNCTIONS: u64 = 256;

/// The CPU's queries for one scene.
pub struct CpuQueries<'a> {
    pub(super) scene: &'a Scene,
    pub(super) plan: &'a Plan,
    pub(super) grid: Option<Grid>,
    pub(super) finder: Escalating,
    /// The functions of the scopes rays are searched with.
    pub(super) scoped: ScopedFunctions,
    /// The scene's triangle meshes, searched beside the implicit surfaces (`None` for a
    /// scene without meshes).
    pub(super) meshes: Option<MeshIndex>,
    /// The diagonal of the implicit surfaces' and the meshes' box
    /// ([`Scene::diagonal`], which walks every triangle), for the shadow offset.
    pub(super) diagonal: f64,
    /// Evaluators given back by finished pieces of work, for the next ones: a scene's
    /// evaluators (of long tapes, of every object) cost more to make than many queries.
    pub(super) pool: Mutex<Vec<Evals>>,
    /// The beams of the camera's pixel rectangles over the whole image, made for the first
    /// tile of the frustum octree and shared by every other (the same edges, the same
    /// beams).
    pub(super) edge_beams: OnceLock<EdgeBeams>,
}

/// Per-thread evaluators lent by [`CpuQueries::evals`], given back to its pool when dropped.
pub(crate) struct Lease<'q> {
    evals: Option<Evals>,
    pool: &'q Mutex<Vec<Evals>>,
}

impl Deref for Lease<'_> {
    type Target = Evals;
    fn deref(&self) -> &Evals {
        self.evals.as_ref().expect("held until dropped")
    }
}

impl DerefMut for Lease<'_> {
    fn deref_mut(&mut self) -> &mut Evals {
        self.evals.as_mut().expect("held until dropped")
    }
}

/// A piece of work of [`CpuQueries::map_pieces`]: the thread's evaluators, the counters of
/// its queries (added to `total` when it ends) and when its last answer was made.
struct Piece<'q> {
    evals: Lease<'q>,
    counters: RootCounters,
    total: &'q Mutex<RootCounters>,
    last: Option<Instant>,
}

impl Drop for Piece<'_> {
    fn drop(&mut self) {
        if let Ok(mut total) = self.total.lock() {
            total.add(&self.counters);
        }
    }
}

impl Drop for Lease<'_> {
    fn drop(&mut self) {
        if let (Some(e), Ok(mut pool)) = (self.evals.take(), self.pool.lock()) {
            pool.push(e);
        }
    }
}

/// Per-thread evaluators.
pub(crate) struct Evals {
    pub(super) geo: GeometryEval,
    pub(super) grid: Option<GridEval>,
    pub(super) scoped: ScopedEval,
    /// The frustum octree's working memory for the tiles this thread searches.
    pub(super) cells: frustum::Scratch,
}

impl CpuQueries<'_> {
    /// Per-thread evaluators, from the pool when it has some.
    pub(super) fn evals(&self) -> Lease<'_> {
        let pooled = self.pool.lock().ok().and_then(|mut p| p.pop());
        Lease {
            evals: Some(pooled.unwrap_or_else(|| self.new_evals())),
            pool: &self.pool,
        }
    }

    /// New evaluators; every evaluator of `g` and `g'` runs in the plan's precision.
    fn new_evals(&self) -> Evals {
        let precision = self.plan.precision;
        let mut geo = self.scene.geometry.evaluator();
        geo.beam.set_precision(precision);
        for e in &mut geo.objects {
            e.set_precision(precision);
        }
        Evals {
            geo,
            grid: self.grid.as_ref().map(|g| g.evaluator_with(precision)),
            scoped: ScopedEval::new(self.scene.geometry.ray_function(), precision),
            cells: frustum::Scratch::default(),
        }
    }

    /// Answers `queries` in parallel, each with `f`, timing each answer when `timed` (the
    /// kinds of primary visibility, whose cost the cost map shows; the others cost 0).
    pub(super) fn map<Q: Sync, T: Send>(
        &self,
        queries: &[Q],
        timed: bool,
        f: impl Fn(&mut Evals, &Q, &mut RootCounters) -> T + Sync,
    ) -> Answers<T> {
        /// Queries per piece of work: one set of counters and vectors per piece.
        const PIECE: usize = 256;
        self.map_pieces(queries, PIECE, timed, f)
    }

    /// [`map`](Self::map) with at least `piece` queries per piece of work (fewer for
    /// queries that are much work each). The answers are written in place, in the
    /// queries' order, by the threads that compute them; each piece of work adds its
    /// counters to the total when it ends (sums of whole numbers: the same whatever the
    /// split).
    pub(super) fn map_pieces<Q: Sync, T: Send>(
        &self,
        queries: &[Q],
        piece: usize,
        timed: bool,
        f: impl Fn(&mut Evals, &Q, &mut RootCounters) -> T + Sync,
    ) -> Answers<T> {
        let total = Mutex::new(RootCounters::default());
        let mut values = Vec::new();
        let mut cost = Vec::new();
        queries
            .par_iter()
            .with_min_len(piece.max(1))
            .map_init(
                || Piece {
                    evals: self.evals(),
                    counters: RootCounters::default(),
                    total: &total,
                    last: timed.then(Instant::now),
                },
                |w, q| {
                    let value = f(&mut w.evals, q, &mut w.counters);
                    // Each answer's time runs from the end of the one before.
                    let cost = w.last.as_mut().map_or(0.0, |last| {
                        let now = Instant::now();
                        let t = (now - *last).as_secs_f32();
                        *last = now;
                        t
                    });
                    (value, cost)
                },
            )
            .unzip_into_vecs(&mut values, &mut cost);
        let search = total.into_inner().unwrap_or_else(|e| e.into_inner());
        Answers {
            values,
            cost,
            search,
        }
    }

    /// Answers `queries` in parallel, each with `f` and timed, taken in their order by
    /// whichever thread is free next (each keeping its evaluators for every query it takes)
    /// and written in the queries' order. For queries that are much work each, such as
    /// the octree's tiles: no thread waits while another finishes a batch's last query
    /// (as rayon's split of a batch in halves, or a batch per band of rows, make them
    /// do), and neighbouring queries, which share prunings and compiled tapes, are
    /// answered near in time. csg3d-2k at 512 × 512 on two threads: the octree's tiles in
    /// bands of four rows of tiles took 38.5–40.5 ms, with threads idle 3 to 5 ms a render;
    /// all of them pulled in order 35.9–36.3 ms, idle 0.1 to 0.2 ms.
    pub(super) fn map_pulled<Q: Sync, T: Send>(
        &self,
        queries: &[Q],
        f: impl Fn(&mut Evals, &Q, &mut RootCounters) -> T + Sync,
    ) -> Answers<T> {
        let total = Mutex::new(RootCounters::default());
        let next = AtomicUsize::new(0);
        let workers = rayon::current_num_threads().clamp(1, queries.len().max(1));
        // Each worker's answers with their indices (a worker that starts after the last
        // query was taken has none).
        let answered: Vec<Vec<(usize, T, f32)>> = (0..workers)
            .into_par_iter()
            .with_max_len(1)
            .map(|_| {
                let mut w = Piece {
                    evals: self.evals(),
                    counters: RootCounters::default(),
                    total: &total,
                    last: None,
                };
                let mut out = Vec::new();
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(q) = queries.get(i) else {
                        break;
                    };
                    let start = Instant::now();
                    let value = f(&mut w.evals, q, &mut w.counters);
                    out.push((i, value, start.elapsed().as_secs_f32()));
                }
                out
            })
            .collect();
        let mut slots: Vec<Option<(T, f32)>> = (0..queries.len()).map(|_| None).collect();
        for (i, value, cost) in answered.into_iter().flatten() {
            slots[i] = Some((value, cost));
        }
        let (values, cost) = slots
            .into_iter()
            .map(|s| s.expect("each query is taken by one worker"))
            .unzip();
        let search = total.into_inner().unwrap_or_else(|e| e.into_inner());
        Answers {
            values,
            cost,
            search,
        }
    }

    /// The parameter ranges a beam must search inside `window`: the grid's non-empty
    /// cells, or the scene bounds, from the origin on.
    pub(super) fn beam_ranges(&self, beam: &Beam, window: Interval<f64>) -> Vec<Interval<f64>> {
        let window = window.intersection(forward());
        if window.is_empty() {
            return Vec::new();
        }
        match &self.grid {
            Some(g) => g.beam_t_ranges_within(beam, window),
            None => beam
                .t_range_within(&self.scene.geometry.bounds(), window)
                .into_iter()
                .collect(),
        }
    }

    /// The first cell of each pixel of a tile ([`crate::frustum::first_cells`]), searched
    /// where the tile's beam crosses the grid's non-empty cells (or the scene bounds). The
    /// undecided pixels' rays are traced in the octree only where the grid's cell functions
    /// are long ([`TRACE_MIN_CELL_INSTRS`]) or many ([`TRACE_MIN_CELL_FUNCTIONS`]):
    /// elsewhere the root finder through the cells is the cheaper search.
    pub(super) fn cells(
        &self,
        ev: &mut Evals,
        query: &CellQuery,
        c: &mut RootCounters,
    ) -> TileCells {
        let cam = &self.scene.camera;
        let r = query.tile;
        let beam = cam.beam(
            f64::from(r.x0),
            f64::from(r.y0),
            f64::from(r.x1),
            f64::from(r.y1),
        );
        let ranges = self.beam_ranges(&beam, forward());
        let range = match (ranges.first(), ranges.last()) {
            (Some(a), Some(b)) => Interval::new_unchecked(a.inf(), b.sup()),
            _ => Interval::EMPTY,
        };
        let bounds = self.scene.geometry.bounds();
        let trace = self.grid.as_ref().is_none_or(|g| {
            let stats = g.stats();
            stats.cell_instrs >= TRACE_MIN_CELL_INSTRS
                || stats.functions >= TRACE_MIN_CELL_FUNCTIONS
        });
        let traced_rays = if trace { query.traced_rays } else { 0 };
        let beams = self.edge_beams.get_or_init(|| {
            cam.edge_beams(PixelRect {
                x0: 0,
                y0: 0,
                x1: cam.width(),
                y1: cam.height(),
            })
        });
        first_cells(
            (&mut ev.geo.beam, &mut ev.cells),
            (cam, beams, &bounds),
            r,
            (range, self.plan.beam.epsilon, traced_rays),
            c,
        )
    }

    /// EvaluateBox of a beam against the whole scene function. A beam lying inside a
    /// classified `parent` beam searches only what the parent left open (see
    /// [`child_window`]); inside a Hit parent, exactly the parent's `T_final`, whose ends
    /// already have one strict sign for every ray.
    ///
    /// The search restricts `g` to each range before searching it ([`RayFn::restrict`]):
    /// the whole function pruned to the beam over the range.
    pub(super) fn classify(
        &self,
        ev: &mut Evals,
        query: &BeamQuery,
        c: &mut RootCounters,
    ) -> Classified {
        let implicit = self.classify_implicit(ev, query, c);
        let Some(m) = &self.meshes else {
            return implicit;
        };
        let window = child_window(query.parent.as_ref());
        let class = m.primary_beam(implicit.class, &query.beam, window);
        // The implicit surfaces' scope goes with their own Hit only.
        let scope = if class == implicit.class {
            implicit.scope
        } else {
            None
        };
        Classified { class, scope }
    }

    /// [`classify`](Self::classify) against the implicit surfaces alone.
    fn classify_implicit(
        &self,
        ev: &mut Evals,
        query: &BeamQuery,
        c: &mut RootCounters,
    ) -> Classified {
        let (beam, parent) = (&query.beam, query.parent.as_ref());
        let window = child_window(parent);
        // Inside an Undecided parent, first up to the end of the parent's restriction
        // (where its tape holds, and where the parent's undecided piece lies), then, where
        // that part is rejected, the rest of the window.
        let cap = match (parent, &query.scope) {
            (Some(BoxClass::Undecided { .. }), Some(s))
                if s.t.sup() > window.inf() && s.t.sup() < window.sup() =>
            {
                Some(s.t.sup())
            }
            _ => None,
        };
        let (searched, rest) = match cap {
            Some(cap) => (
                Interval::new_unchecked(window.inf(), cap),
                Some(Interval::new_unchecked(cap, window.sup())),
            ),
            None => (window, None),
        };
        let ranges = match parent {
            Some(BoxClass::Hit { t_final }) => vec![*t_final],
            _ => self.beam_ranges(beam, searched),
        };
        if ranges.is_empty() && rest.is_none() {
            return BoxClass::Miss.into();
        }
        ev.geo.beam.set_beam(beam);
        let bounds = self.scene.geometry.bounds();
        let extent = Extent {
            beam,
            bounds: &bounds,
        };
        // Inside an Undecided parent the search starts at the scale the parent stopped at.
        let near = match parent {
            Some(BoxClass::Undecided { t }) => Some(*t),
            _ => None,
        };
        // A frame of a block searches with the block's proofs of this beam; the block's
        // own pass records them.
        let proofs = self.scene.proofs.as_deref();
        let key = proofs.map(|_| BeamKey::of(beam));
        // Not below a scope pruned in a higher precision, nor in double-double (whose
        // centred form is not evaluated operation by operation): there the frame's own
        // evaluation need not lie inside the block's.
        let plain = query.scope.as_ref().is_none_or(|s| !s.escalated)
            && self.plan.precision != Precision::Dd;
        let free = match (proofs, &key) {
            (Some(p), Some(k)) if plain => p.free(k),
            _ => &[],
        };
        let mut record = proofs.filter(|p| p.records()).map(|_| Vec::new());
        let inherited = Inherited {
            scope: query.scope.as_ref(),
            near,
            free,
        };
        // The rest of the window (its ranges walked only when it is reached) inherits only
        // the block's proofs: the parent's restriction and undecided piece lie before it.
        let later = Inherited {
            scope: None,
            near: None,
            free,
        };
        let parts = std::iter::once((ranges, inherited))
            .chain(rest.into_iter().map(|w| (self.beam_ranges(beam, w), later)));
        let (mut class, mut scope) = (BoxClass::Miss, None);
        for (ranges, inherited) in parts {
            if !ranges.is_empty() {
                (class, scope) = evaluate_box_within(
                    &mut ev.geo.beam,
                    &ranges,
                    inherited,
                    Some(&extent),
                    &self.plan.beam,
                    record.as_mut(),
                    c,
                );
            }
            if class != BoxClass::Miss {
                break;
            }
        }
        if let (Some(p), Some(k), Some(r)) = (proofs, key, record) {
            p.record(k, &r);
        }
        Classified { class, scope }
    }

    /// The first root along `ray` for parameters in `t` (clipped to `t ≥ 0`): with the
    /// function of the `scope` of the beam the ray lies in where `t` is inside its
    /// parameters (see [`super::scoped`]), else through the grid's cells when there is a
    /// grid (each with its reduced function), else with the whole scene function; inside
    /// the scene bounds. `root` is the plan's root settings, or their
    /// [`existence`](RootSettings::existence) form where only whether a root exists matters.
    pub(super) fn cast(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        (scope, root): (Option<&BeamScope>, &RootSettings),
        c: &mut RootCounters,
    ) -> RootResult {
        let t = t.intersection(forward());
        if t.is_empty() {
            return RootResult::NoRoot;
        }
        let implicit = self.cast_implicit(ev, ray, t, (scope, root), c);
        match &self.meshes {
            Some(m) => m.first_root(implicit, ray, t),
            None => implicit,
        }
    }

    /// [`cast`](Self::cast) against the implicit surfaces alone, `t` already clipped.
    fn cast_implicit(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        (scope, root): (Option<&BeamScope>, &RootSettings),
        c: &mut RootCounters,
    ) -> RootResult {
        if let Some(eval) = ev.scoped.within(&self.scoped, scope, t) {
            return self.first_root_in_bounds(eval, ray, (t, root), c);
        }
        match (&self.grid, ev.grid.as_mut()) {
            (Some(g), Some(gev)) => g.first_root_within(gev, ray, t, &self.finder, root, c),
            _ => self.first_root_in_bounds(&mut ev.geo.beam, ray, (t, root), c),
        }
    }

    /// The first root along `ray` for parameters in `t` inside the scene bounds, searched
    /// with `eval`'s function (the ray is set on it).
    fn first_root_in_bounds(
        &self,
        eval: &mut BeamEval,
        ray: &Ray,
        (t, root): (Interval<f64>, &RootSettings),
        c: &mut RootCounters,
    ) -> RootResult {
        match ray.beam().t_range_within(&self.scene.geometry.bounds(), t) {
            Some(t) => {
                eval.set_ray(ray);
                self.finder.first_root(eval, t, root, c)
            }
            None => RootResult::NoRoot,
        }
    }

    /// A hit record for the first root `t` of `ray` (or the first undecided range).
    ///
    /// The point is placed inside `t` where the floating-point values of `g` change sign
    /// (bisection on point values, for shading only: the proof is `t`), on the side of the
    /// ray's origin, so that shadow segments start outside the surface they leave. Where one
    /// grid cell holds the points of `t`, `g` is the cell's function (sign-equivalent to the
    /// scene function there, and much shorter); where `t` lies in the parameters of the
    /// `scope` of the beam the ray lies in, its function (equal to the scene function
    /// there); else the scene function. Where the plan does not narrow hits
    /// ([`Plan::narrow_hits`](crate::plan::Plan::narrow_hits): an unlit scene of one
    /// colour, whose image needs no normal and no telling objects apart) the point is
    /// `t`'s near end, with no search.
    pub(super) fn hit(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        scope: Option<&BeamScope>,
        c: &mut RootCounters,
    ) -> Hit {
        // Where the record follows from `t` alone, it is the one a primary pass makes
        // without asking (one rule for both).
        if let Some(hit) = self.direct_hits().and_then(|d| d.hit(ray, t)) {
            return hit;
        }
        // A triangle crossed inside the enclosure is taken as the hit (where an implicit
        // surface may also be, the proof is `t` either way).
        if let Some(m) = &self.meshes
            && let first = m.bvh().first_crossing(ray, t)
            && let (Some(tri), Some(tt)) = (first.triangle, first.result.root())
        {
            return Hit {
                t,
                point: ray.at(tt.mid()),
                to_eye: (-ray.dir).normalize_or_zero(),
                leaf: self.scene.mesh_leaf(m.owner(tri) as usize),
                normal: m.normal(tri),
            };
        }
        let tm = if self.plan.narrow_hits || !t.inf().is_finite() {
            self.shading_parameter(ev, ray, t, scope, c)
        } else {
            t.inf()
        };
        let point = ray.at(tm);
        let leaf = if ev.geo.single_leaf() {
            0
        } else {
            match self.grid.as_ref().and_then(|g| g.leaf_candidates_at(point)) {
                Some(c) => ev.geo.leaf_among(&c, point),
                None => ev.geo.leaf_at(point),
            }
        };
        Hit::on_ray(ray, t, tm, leaf as u32)
    }

    /// The hits made without a query: where the scene has one leaf surface and no mesh and
    /// the plan does not narrow hits, [`hit`](Self::hit) evaluates nothing.
    pub(super) fn direct_hits(&self) -> Option<DirectHits> {
        (self.meshes.is_none() && !self.plan.narrow_hits && self.scene.geometry.leaves().len() == 1)
            .then_some(DirectHits { leaf: 0 })
    }

    /// The parameter of `ray`'s shading point inside the root enclosure `t`
    /// ([`shading_parameter`]), with the shortest function that has the scene function's
    /// signs there (see [`hit`](Self::hit)).
    fn shading_parameter(
        &self,
        ev: &mut Evals,
        ray: &Ray,
        t: Interval<f64>,
        scope: Option<&BeamScope>,
        c: &mut RootCounters,
    ) -> f64 {
        let eval = match ev.scoped.within(&self.scoped, scope, t) {
            Some(e) => e,
            // Inside one cell, its (reduced, pruned) function has the scene function's
            // signs.
            None => match self
                .grid
                .as_ref()
                .zip(ev.grid.as_mut())
                .and_then(|(g, gev)| g.function_over(ray, t).map(|f| gev.get(g, f)))
            {
                Some(e) => e,
                None => &mut ev.geo.beam,
            },
        };
        shading_parameter(eval, ray, t, c)
    }
}

/// The parameter of the shading point of a hit with enclosure `t`: the end on the origin's
/// side of a floating-point sign change of `g` inside `t`, the bracket narrowed to adjacent
/// floats by the Illinois variant of regula falsi on point values (a bisection step where two
/// steps did not halve it); the midpoint where `g` shows no sign change (a tangent, a
/// possible root). For shading only: the proof is `t`.
fn shading_parameter(
    eval: &mut BeamEval,
    ray: &Ray,
    t: Interval<f64>,
    c: &mut RootCounters,
) -> f64 {
    let (mut a, mut b) = (t.inf(), t.sup());
    if !(a.is_finite() && b.is_finite()) {
        return t.mid();
    }
    eval.set_ray(ray);
    let (mut ga, mut gb) = (eval.g_point(a), eval.g_point(b));
    c.point_evals += 2;
    if ga == 0.0 {
        return a;
    }
    if ga.is_nan() || gb.is_nan() || (ga > 0.0) == (gb > 0.0) && gb != 0.0 {
        return t.mid();
    }
    let origin_side = ga > 0.0;
    // Which end the last step kept (Illinois halves the kept end's value when it is kept
    // twice, so that both ends move), and the bracket's width two steps ago.
    let mut kept_a = None;
    let mut width = b - a;
    for step in 0..MAX_SHADING_STEPS {
        let mid = 0.5 * (a + b);
        if mid <= a || mid >= b {
            break;
        }
        if step % 2 == 0 {
            width = b - a;
        }
        let secant = (a * gb - b * ga) / (gb - ga);
        let bisect = step % 2 == 1 && b - a > 0.5 * width;
        let m = if !bisect && secant > a && secant < b {
            secant
        } else {
            mid
        };
        let gm = eval.g_point(m);
        c.point_evals += 1;
        if gm.is_nan() {
            break;
        }
        if gm != 0.0 && (gm > 0.0) == origin_side {
            a = m;
            ga = gm;
            if kept_a == Some(false) {
                gb *= 0.5;
            }
            kept_a = Some(false);
        } else {
            b = m;
            gb = gm;
            if kept_a == Some(true) {
                ga *= 0.5;
            }
            kept_a = Some(true);
        }
    }
    a
}

/// Most steps of [`shading_parameter`]: a bisection at least every other step reaches
/// adjacent floats from any bracket in fewer.
const MAX_SHADING_STEPS: u32 = 256;
