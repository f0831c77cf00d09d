//! Primary visibility with beams and rays: the screen box structure (thesis 5.4), level by
//! level, and the rays of each pixel searched where its box left them open.

use std::time::Instant;

use interval_core::Interval;
use rayon::prelude::*;

use super::batches::{RAY_BATCH_PIXELS, RowBatch, row_batches};
use super::buffers;
use super::classes::{BoxPixel, PixelClasses};
use super::pixel_box::Kind;
use super::pixels::{self, owners};
use super::resolve::{PixelSink, RayBatch};
use crate::backend::{
    BeamQuery, CellQuery, DirectHits, HitQuery, Queries, RayQuery, VariationQuery,
};
use crate::beam::{BeamScope, BoxClass};
use crate::beam::{child_window, forward};
use crate::camera::{Camera, RayTable};
use crate::error::Error;
use crate::frustum::{TileCells, Traced};
use crate::plan::{Pass, Plan, Primary};
use crate::progress::Progress;
use crate::ray::Ray;
use crate::root::{Proof, RootResult};
use crate::sample::Area;
use crate::scene::Scene;
use crate::screen::{
    OCTREE_TILE, PixelRect, SCREEN_TILE as TILE, needs_split, stratified_offsets, stratified_side,
};
use crate::stats::PassStats;
use crate::stats::counters::{PrimaryRayCounters, ScreenBoxCounters};
use crate::window::Window;

/// What the search of each of a pixel's rays proved past its first cell, for each pixel
/// the frustum octree traced
/// ([`FirstCell::traced`](crate::frustum::FirstCell::traced)), by increasing pixel index
/// (few pixels have them: the silhouette's); empty after the screen box structure.
pub(super) type PixelTraces = Vec<(u32, Vec<Traced>)>;

/// The traces of pixel `p`'s rays in `traces` (empty where it has none). Only an
/// Undecided pixel's rays are traced, so a Hit or Miss pixel's (`kind`) are known empty
/// without a look-up.
fn traces_of(kind: Kind, traces: &PixelTraces, p: usize) -> &[Traced] {
    if matches!(kind, Kind::Hit | Kind::Miss) {
        return &[];
    }
    match traces.binary_search_by_key(&p, |&(q, _)| q as usize) {
        Ok(k) => &traces[k].1,
        Err(_) => &[],
    }
}

/// The first primary pass of `plan` over `window`'s pixels: the frustum octree's first
/// cells for [`Primary::Octree`], else the screen box structure.
pub(super) fn structure(
    q: &dyn Queries,
    scene: &Scene,
    plan: &Plan,
    window: &Window,
    progress: &dyn Progress,
) -> Result<(PixelClasses, PixelTraces, PassStats), Error> {
    match plan.primary {
        // The octree traces each undecided pixel's rays.
        Primary::Octree { rays_per_undecided } => {
            octree(q, window, (rays_per_undecided, plan.narrow_hits), progress)
        }
        _ => {
            let (classes, stats) = screen_boxes(q, scene, plan, window, progress)?;
            Ok((classes, Vec::new(), stats))
        }
    }
}

/// The frustum octree pass ([`crate::frustum`]): every tile in one batch (the backend
/// reports each tile's pixels done as it goes); each pixel a Hit in the range its first
/// cell proved (with that cell's scope), else Undecided in its first cell (its
/// `traced_rays` stratified rays traced on from there), or a Miss without one. Each first
/// cell is one box of the classes, its pixels' index.
fn octree(
    q: &dyn Queries,
    window: &Window,
    (traced_rays, narrow_hits): (u32, bool),
    progress: &dyn Progress,
) -> Result<(PixelClasses, PixelTraces, PassStats), Error> {
    let t0 = Instant::now();
    progress.begin(Pass::ScreenBoxes.name(), window.len() as u64);
    let mut traced: PixelTraces = Vec::new();
    let mut c = ScreenBoxCounters::default();
    let all = window.tiles(OCTREE_TILE);
    let queries: Vec<CellQuery> = all
        .iter()
        .map(|&tile| CellQuery { tile, traced_rays })
        .collect();
    let answers = q.first_cells(&queries, progress)?;
    c.search.add(&answers.search);
    // Each tile's first cells (a pixel without one is proven missed).
    let mut firsts: Vec<TileCells> = answers.values;
    for (tile, cells) in all.iter().zip(&mut firsts) {
        c.add_pixels(&BoxClass::Miss, tile.area() - cells.len() as u64);
        let width = tile.x1 - tile.x0;
        for &(k, j) in &cells.pixels {
            let f = &mut cells.cells[j as usize];
            c.add_pixels(&f.class(), 1);
            if !f.traced.is_empty() {
                // A traced cell is a single pixel's.
                let (x, y) = (tile.x0 + k % width, tile.y0 + k / width);
                traced.push((window.local(x, y) as u32, std::mem::take(&mut f.traced)));
            }
        }
    }
    traced.sort_unstable_by_key(|&(p, _)| p);
    // Every first cell a box, with the scope its pixels keep: a Hit pixel's ray is searched
    // (in the cell's scope) only where the plan narrows hits. Cell `j` of tile `t` is box
    // `first_box[t] + j`; a pixel without a first cell stays in the Miss box.
    let mut classes = PixelClasses::filled(window.len(), Some(BoxClass::Miss));
    let mut first_box = Vec::with_capacity(firsts.len());
    for cells in &mut firsts {
        // The boxes of one tile's cells have consecutive indices.
        let mut first = None;
        for f in &mut cells.cells {
            let scope = f.scope.take().filter(|_| !f.hit || narrow_hits);
            let id = classes.add_box(f.class(), scope)?;
            first.get_or_insert(id);
        }
        first_box.push(first.unwrap_or(0));
    }
    // Every pixel's box, a band of tile rows at a time in parallel: the tiles lie on the
    // image's grid of `OCTREE_TILE` from the window's corner, row by row.
    let (corner, width) = (window.rect(), window.width() as usize);
    let columns = width.div_ceil(OCTREE_TILE as usize);
    let band = OCTREE_TILE as usize * width;
    debug_assert_eq!(all.len(), columns * window.len().div_ceil(band));
    classes
        .bands_mut(band)
        .zip(all.par_chunks(columns).zip(firsts.par_chunks(columns)))
        .zip(first_box.par_chunks(columns))
        .for_each(|((mut classes, (tiles, firsts)), first_box)| {
            for ((tile, cells), &first) in tiles.iter().zip(firsts).zip(first_box) {
                let tile_width = tile.x1 - tile.x0;
                for &(k, j) in &cells.pixels {
                    let (x, y) = (tile.x0 + k % tile_width, tile.y0 + k / tile_width);
                    // The band's first row is the tile's.
                    let p = (y - tile.y0) as usize * width + (x - corner.x0) as usize;
                    classes.assign(p, first + j, false);
                }
            }
        });
    // The beams evaluated: the cells and the leaves' inclusion tests.
    c.beams = c.search.g_evals;
    progress.end();
    Ok((
        classes,
        traced,
        PassStats::of(Pass::ScreenBoxes, t0.elapsed(), &c),
    ))
}

/// The screen box pass: tiles classified in one batch, the boxes to split in the next
/// batch, down to single pixels (Undecided boxes and wide Hit boxes are split; a part
/// searches only what its parent left open).
fn screen_boxes(
    q: &dyn Queries,
    scene: &Scene,
    plan: &Plan,
    window: &Window,
    progress: &dyn Progress,
) -> Result<(PixelClasses, PassStats), Error> {
    let cam = &scene.camera;
    let t0 = Instant::now();
    progress.begin(Pass::ScreenBoxes.name(), window.len() as u64);
    let mut classes = PixelClasses::filled(window.len(), None);
    let mut c = ScreenBoxCounters::default();
    // With anti-aliasing, the Hit boxes of more than one pixel whose shading is judged
    // once for all their pixels.
    let judge = plan.primary.pixel_beams().and_then(|p| p.threshold);
    let mut judged: Vec<(PixelRect, VariationQuery)> = Vec::new();
    // Each box with the class and the backend's scope of the box it was split from.
    let mut level: Vec<(PixelRect, Option<BoxClass>, Option<BeamScope>)> = window
        .tiles(TILE)
        .into_iter()
        .map(|t| (t, None, None))
        .collect();
    while !level.is_empty() {
        let queries: Vec<BeamQuery> = level
            .iter()
            .map(|(r, parent, scope)| BeamQuery {
                beam: cam.beam(
                    f64::from(r.x0),
                    f64::from(r.y0),
                    f64::from(r.x1),
                    f64::from(r.y1),
                ),
                parent: *parent,
                scope: scope.clone(),
            })
            .collect();
        let answers = q.beams(&queries)?;
        c.beams += queries.len() as u64;
        c.search.add(&answers.search);
        let mut next = Vec::new();
        for ((rect, _, _), (query, answer)) in level.iter().zip(queries.iter().zip(answers.values))
        {
            let class = answer.class;
            if needs_split(rect, &class, plan.t_final_width) {
                next.extend(
                    rect.split()
                        .into_iter()
                        .map(|r| (r, Some(class), answer.scope.clone())),
                );
                continue;
            }
            c.add_pixels(&class, rect.area());
            if let (Some(threshold), BoxClass::Hit { t_final }) = (judge, class)
                && rect.area() > 1
            {
                judged.push((
                    *rect,
                    VariationQuery {
                        beam: query.beam,
                        t_final,
                        threshold,
                    },
                ));
            }
            // A Miss box's pixels take no ray, nor its scope.
            let scope = answer
                .scope
                .clone()
                .filter(|_| !matches!(class, BoxClass::Miss));
            let id = classes.add_box(class, scope)?;
            for (x, y) in rect.pixels() {
                let edge = x == rect.x0 || y == rect.y0;
                classes.assign(window.local(x, y), id, edge);
            }
            progress.advance(rect.area());
        }
        level = next;
    }
    mark_smooth(q, &judged, window, &mut classes, &mut c)?;
    progress.end();
    Ok((classes, PassStats::of(Pass::ScreenBoxes, t0.elapsed(), &c)))
}

/// The pixels of each box of `judged` whose shading is judged to vary by at most the
/// threshold over the box's hit region (and each point light's shadow proven the same over
/// it), marked smooth: every ray of a pixel is a ray of its box, so what the box's
/// judgement bounds holds for the pixel, and the pixel needs no beam of its own.
fn mark_smooth(
    q: &dyn Queries,
    judged: &[(PixelRect, VariationQuery)],
    window: &Window,
    classes: &mut PixelClasses,
    c: &mut ScreenBoxCounters,
) -> Result<(), Error> {
    if judged.is_empty() {
        return Ok(());
    }
    let queries: Vec<VariationQuery> = judged.iter().map(|&(_, v)| v).collect();
    let variation = q.shading_variation(&queries)?;
    c.search.add(&variation.search);
    for ((rect, v), spread) in judged.iter().zip(variation.values) {
        // As the pixels' own judgement: anything but a spread within the threshold (NaN
        // included) is not smooth.
        let smooth = spread <= v.threshold;
        if !smooth {
            continue;
        }
        c.smooth_boxes += 1;
        c.smooth_pixels += rect.area();
        for (x, y) in rect.pixels() {
            classes.mark_smooth(window.local(x, y));
        }
    }
    Ok(())
}

/// The rays of the primary-rays pass: through each pixel's centre and through its `k × k`
/// stratified positions (`((a + 0.5) / k, (b + 0.5) / k)` inside it, `a` across, `b` down),
/// bit for bit the camera's ([`Camera::ray_table`]).
struct PixelRays {
    table: RayTable,
    k: usize,
    /// The image coordinates of the first pixel of the table.
    origin: (u32, u32),
}

impl PixelRays {
    /// The rays of `cam`'s pixels in `window`, `n` stratified ones per pixel (a square; its
    /// nearest).
    fn new(cam: &Camera, n: u32, window: &Window) -> Self {
        let k = stratified_side(n) as usize;
        // Per pixel and axis: the centre, then the `k` stratified positions, the very
        // values the frustum octree traces its rays at (`stratified_offsets`: its first
        // row holds the `x` offsets, its first column the `y` offsets), so that a traced
        // ray and its scope are this ray's.
        let offsets = stratified_offsets(n);
        let across: Vec<f64> = std::iter::once(0.5)
            .chain(offsets[..k].iter().map(|o| o.0))
            .collect();
        let down: Vec<f64> = std::iter::once(0.5)
            .chain(offsets.iter().step_by(k).map(|o| o.1))
            .collect();
        let positions = |pixels: std::ops::Range<u32>, inside: &[f64]| -> Vec<f64> {
            pixels
                .flat_map(|p| inside.iter().map(move |o| f64::from(p) + o))
                .collect()
        };
        let r = window.rect();
        Self {
            table: cam.ray_table(
                &positions(r.x0..r.x1, &across),
                &positions(r.y0..r.y1, &down),
            ),
            k,
            origin: (r.x0, r.y0),
        }
    }

    /// The number of stratified rays per pixel.
    fn count(&self) -> usize {
        self.k * self.k
    }

    /// The ray through the centre of the image's pixel `(x, y)`.
    fn centre(&self, x: u32, y: u32) -> Ray {
        let per = self.k + 1;
        let (x, y) = (x - self.origin.0, y - self.origin.1);
        self.table.ray(x as usize * per, y as usize * per)
    }

    /// Stratified ray `r` of the image's pixel `(x, y)`.
    fn stratified(&self, x: u32, y: u32, r: usize) -> Ray {
        let per = self.k + 1;
        let (x, y) = (x - self.origin.0, y - self.origin.1);
        self.table.ray(
            x as usize * per + 1 + r % self.k,
            y as usize * per + 1 + r / self.k,
        )
    }
}

/// One ray of a pixel (each of a pixel's rays weighs the same in its colour): the query,
/// and the window searched (with the whole function) when the query's search ends without
/// a root (the whole ray after a Hit box's `T_final`, where a root is known to exist, so a
/// limit was reached; the rest of the ray after a first cell of the frustum octree). A ray
/// whose answer is known ([`known_root`]) is not searched.
#[derive(Clone)]
struct PixelRay {
    query: RayQuery,
    fallback: Option<Interval<f64>>,
}

/// Where the rays of an Undecided pixel start.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum RayStart {
    /// A little before the undecided range of the pixel's screen box
    /// ([`child_window`]), with the whole function.
    BoxWindow,
    /// At the pixel's first cell of the frustum octree ([`crate::frustum`]): searched
    /// first inside the cell with the cell's scope, then on from there.
    FirstCell,
}

/// What is proven about the share of a pixel of a class of kind `kind` that one of its
/// samples stands for.
fn sample_area(kind: Kind) -> Area {
    match kind {
        Kind::Miss => Area::Missed,
        Kind::Hit => Area::Covered,
        Kind::Undecided | Kind::Unclassified => Area::Unknown,
    }
}

/// The number of rays of a pixel of a class of kind `kind`: the central ray in a Hit box;
/// `stratified` rays in an Undecided box (or without a box); none in a Miss box.
fn ray_count(kind: Kind, stratified: usize) -> usize {
    // A look-up rather than a branch: a row's kinds change from pixel to pixel at every
    // silhouette, where branches are mispredicted. Indexed by kind: unclassified, Miss,
    // Hit, Undecided.
    let counts = [stratified, 0, 1, stratified];
    counts[kind as usize]
}

/// Ray `r` of `window`'s pixel `i` of box class `class`: the central
/// ray, searched in a Hit box's `T_final` (with the box's `scope`) where `narrow`, else
/// known to have its first root there; else stratified ray `r`, searched from where the
/// pixel's beam proved every ray root-free (see [`ray_count`]), or, where it is the
/// pixel's ray `r` the octree `traced`, known to meet no surface, or searched in (or
/// known to have its first root in) the range the octree proved, or searched past the part
/// it proved clear.
fn pixel_ray(
    (rays, start, narrow): (&PixelRays, RayStart, bool),
    i: usize,
    window: &Window,
    (class, scope, traced): (Option<BoxPixel>, Option<&BeamScope>, &[Traced]),
    r: usize,
) -> PixelRay {
    let kind = Kind::of(class.as_ref().map(|c| &c.class));
    let ray = ray_of_pixel(rays, window.pixel(i), kind, traced, r);
    if let Some(traced) = octree_trace(traced, rays.count(), r) {
        return match traced {
            Traced::NoRoot => PixelRay {
                query: RayQuery {
                    ray,
                    window: forward(),
                    scope: None,
                },
                fallback: None,
            },
            Traced::First { t, scope } => PixelRay {
                query: RayQuery {
                    ray,
                    window: *t,
                    scope: scope.clone(),
                },
                fallback: Some(Interval::new_unchecked(t.inf(), f64::INFINITY)),
            },
            // The rest of the ray, with the whole function.
            &Traced::Clear { until } => PixelRay {
                query: RayQuery {
                    ray,
                    window: Interval::new_unchecked(until, f64::INFINITY),
                    scope: None,
                },
                fallback: None,
            },
        };
    }
    match class.map(|c| c.class) {
        Some(BoxClass::Hit { t_final }) => PixelRay {
            query: RayQuery {
                ray,
                window: t_final,
                // A ray that is not searched needs no scope.
                scope: if narrow { scope.cloned() } else { None },
            },
            fallback: Some(forward()),
        },
        class => {
            let (window, scope, fallback) = match (start, class) {
                (RayStart::FirstCell, Some(BoxClass::Undecided { t })) => {
                    // No ray of the pixel meets a surface before its first cell: from the
                    // cell through the region of its scope where it has one (the scope
                    // holds there), then the rest of the ray.
                    let rest = Interval::new_unchecked(t.inf(), f64::INFINITY);
                    match scope.filter(|s| t.subset(s.t)) {
                        Some(s) => (
                            Interval::new_unchecked(t.inf(), s.t.sup()),
                            Some(s.clone()),
                            Some(rest),
                        ),
                        None => (rest, None, None),
                    }
                }
                _ => (child_window(class.as_ref()), None, None),
            };
            PixelRay {
                query: RayQuery { ray, window, scope },
                fallback,
            }
        }
    }
}

/// Ray `r` of the pixel at `(x, y)` of a class of kind `kind` whose rays the octree
/// `traced`, as [`pixel_ray`] makes it: the octree's ray `r` where it traced the pixel's
/// rays (at the same stratified position), else a Hit box's central ray or stratified ray
/// `r`.
fn ray_of_pixel(
    rays: &PixelRays,
    (x, y): (u32, u32),
    kind: Kind,
    traced: &[Traced],
    r: usize,
) -> Ray {
    match kind {
        Kind::Hit if octree_trace(traced, rays.count(), r).is_none() => rays.centre(x, y),
        _ => rays.stratified(x, y, r),
    }
}

/// The octree's trace of a pixel's ray `r` among its `traced` rays, where they are the
/// pixel's `count` stratified rays.
fn octree_trace(traced: &[Traced], count: usize, r: usize) -> Option<&Traced> {
    traced.get(r).filter(|_| traced.len() == count)
}

/// The first root of a pixel's ray known without a search, as [`pixel_ray`] gives it (and
/// without making the ray): none for a ray the octree traced to no root; where the plan
/// does not narrow hits, the range the octree's trace or the Hit box proved; else `None`.
fn known_root(narrow: bool, class: Option<BoxPixel>, trace: Option<&Traced>) -> Option<RootResult> {
    match trace {
        Some(Traced::NoRoot) => Some(RootResult::NoRoot),
        Some(Traced::First { t, .. }) => (!narrow).then_some(RootResult::included(*t)),
        Some(Traced::Clear { .. }) => None,
        None => match class.map(|c| c.class) {
            Some(BoxClass::Hit { t_final }) => (!narrow).then_some(RootResult::included(t_final)),
            _ => None,
        },
    }
}

/// The primary-rays pass: in a Hit box one central ray per pixel searched in `T_final`
/// (the whole ray again if the search stops at a limit there); elsewhere `rays` stratified
/// rays per pixel, from where the pixel's beam proved them root-free; a Miss box's pixels
/// are background without a ray. `classes` holds each pixel's box and the scope of the
/// box's beam (none in per-pixel mode). Without `narrow`, a Hit box's ray is not
/// searched: its first root is the one the box proved in `T_final`. The pixels go, batch
/// by batch, to the sink `make` makes from the number of pixels and of rays
/// ([`PixelSink`]: their samples, or, unlit, their colours and coverage).
pub(super) fn primary_rays<S: PixelSink>(
    q: &dyn Queries,
    scene: &Scene,
    window: &Window,
    (classes, traced): (&PixelClasses, &PixelTraces),
    (rays, start, narrow): (u32, RayStart, bool),
    (make, progress): (impl FnOnce(usize, &dyn Fn() -> usize) -> S, &dyn Progress),
) -> Result<(S, Vec<f32>, PassStats), Error> {
    let (w, h) = (window.width(), window.height());
    let t0 = Instant::now();
    let pixel_rays = PixelRays::new(&scene.camera, rays, window);
    progress.begin(Pass::PrimaryRays.name(), u64::from(h));
    let mut c = PrimaryRayCounters::default();
    let direct = q.direct_hits();
    let npix = window.len();
    // Pixel `p`'s kind, and whether it is known from its box (by the leaf that shades its
    // one ray) where the sink takes such pixels ([`PixelSink::RESOLVES_KNOWN`]): a Hit
    // box's pixel whose central ray has its first root in `T_final` unsearched (hits are
    // not narrowed) and whose hit record the pass would make itself (nothing to search,
    // nothing to ask the backend).
    let known_leaf = direct.filter(|_| S::RESOLVES_KNOWN && !narrow);
    let kind_of = |p: usize| -> (Kind, bool) {
        let (kind, t) = classes.kind_and_range(p);
        let known = known_leaf.is_some() && kind == Kind::Hit && DirectHits::applies(t);
        (kind, known)
    };
    // The rays of a pixel of kind `kind` in the flat batches: none for a known pixel.
    let rays_of = |(kind, known): (Kind, bool)| {
        if known {
            0
        } else {
            ray_count(kind, pixel_rays.count())
        }
    };
    let all_rays = || {
        (0..classes.len())
            .into_par_iter()
            .map(|p| rays_of(kind_of(p)))
            .sum()
    };
    let mut sink = make(npix, &all_rays);
    let mut cost: Vec<f32> = buffers::with_room(npix);
    for RowBatch { rows, first, n } in row_batches(w, h, RAY_BATCH_PIXELS / w.max(1)) {
        // Each pixel's kind and whether it is known, read once from its box.
        let kinds: Vec<(Kind, bool)> = (0..n).into_par_iter().map(|k| kind_of(first + k)).collect();
        // The rays of every pixel of the batch but the known ones, built in parallel; pixel
        // `k` owns the rays `first_ray[k]..first_ray[k + 1]` of the flat batch.
        let first_ray = pixels::par_offsets(n, |k| rays_of(kinds[k]));
        let ray_pixel = owners(&first_ray);
        // Ray `j`'s pixel (in the image) and its index among the pixel's rays.
        let pixel_of = |j: usize| {
            let k = ray_pixel[j] as usize;
            (first + k, j - first_ray[k])
        };
        let kind = |p: usize| kinds[p - first].0;
        // Ray `j` of the batch, made again where it is needed rather than kept: most rays
        // are known (a Hit box's), and a record of every ray would be most of the pass's
        // memory.
        let ray_of = |j: usize| {
            let (p, r) = pixel_of(j);
            pixel_ray(
                (&pixel_rays, start, narrow),
                p,
                window,
                (
                    classes.get(p),
                    classes.scope(p),
                    traces_of(kind(p), traced, p),
                ),
                r,
            )
        };
        // Each ray's first root where it is known without a search (a Hit pixel's, a ray
        // the octree traced); `None` for the rays to search, filled in below.
        let mut results: Vec<Option<RootResult>> = (0..ray_pixel.len())
            .into_par_iter()
            .map(|j| {
                let (p, r) = pixel_of(j);
                let traced = traces_of(kind(p), traced, p);
                known_root(
                    narrow,
                    classes.get(p),
                    octree_trace(traced, pixel_rays.count(), r),
                )
            })
            .collect();
        let searched: Vec<usize> = (0..results.len())
            .filter(|&j| results[j].is_none())
            .collect();
        let queries: Vec<RayQuery> = searched.par_iter().map(|&j| ray_of(j).query).collect();
        let first_try = q.roots(&queries)?;
        c.rays += queries.len() as u64;
        c.search.add(&first_try.search);
        // Each ray's cost, where some ray was searched or asked about.
        let mut ray_cost = if searched.is_empty() {
            Vec::new()
        } else {
            vec![0f32; results.len()]
        };
        for ((&j, r), t) in searched.iter().zip(first_try.values).zip(first_try.cost) {
            results[j] = Some(r);
            ray_cost[j] = t;
        }
        // Ray `j`'s first root in `results`, searched or known (each searched ray has its
        // answer).
        let result_in =
            |results: &[Option<RootResult>], j: usize| results[j].unwrap_or(RootResult::NoRoot);
        // No root where one was expected first: search the fallback window, past the
        // first window where that one is proven root-free.
        let retry: Vec<(usize, Interval<f64>)> = searched
            .iter()
            .filter(|&&j| !matches!(result_in(&results, j), RootResult::Root { .. }))
            .filter_map(|&j| {
                let ray = ray_of(j);
                let w = ray.fallback?;
                let searched = ray.query.window;
                Some(match result_in(&results, j) {
                    RootResult::NoRoot if searched.inf() <= w.inf() => (
                        j,
                        Interval::new_unchecked(searched.sup().max(w.inf()), w.sup()),
                    ),
                    _ => (j, w),
                })
            })
            .collect();
        if !retry.is_empty() {
            let queries: Vec<RayQuery> = retry
                .iter()
                .map(|&(j, window)| RayQuery {
                    ray: ray_of(j).query.ray,
                    window,
                    scope: None,
                })
                .collect();
            let again = q.roots(&queries)?;
            c.search.add(&again.search);
            for ((&(j, _), r), t) in retry.iter().zip(again.values).zip(&again.cost) {
                results[j] = Some(r);
                ray_cost[j] += t;
            }
        }
        let result = |j: usize| result_in(&results, j);
        // A known pixel's one ray has its first root, proven to exist.
        if known_leaf.is_some() {
            c.hits += (0..n).into_par_iter().filter(|&k| kinds[k].1).count() as u64;
        }
        for j in 0..results.len() {
            match result(j) {
                RootResult::Root { proof, .. } => {
                    c.hits += 1;
                    match proof {
                        Proof::Unique => c.proven_unique += 1,
                        Proof::Possible => c.possible += 1,
                        Proof::Exists => {}
                    }
                }
                RootResult::Undecided { .. } => c.undecided += 1,
                RootResult::NoRoot => {}
            }
        }
        // The shading points of the rays that meet (or may meet) a surface: those the
        // backend leaves to the pass are made with the samples, the others asked for.
        let root_of = |j: usize| match result(j) {
            RootResult::Root { t, .. } | RootResult::Undecided { t } => Some(t),
            RootResult::NoRoot => None,
        };
        let asked =
            |j: usize| root_of(j).is_some_and(|t| direct.is_none() || !DirectHits::applies(t));
        // The rays asked about, in order (a ray's answer is at its rank among them).
        let hit_rays: Vec<usize> = (0..results.len()).filter(|&j| asked(j)).collect();
        let hit_queries: Vec<HitQuery> = hit_rays
            .par_iter()
            .map(|&j| {
                let RayQuery { ray, scope, .. } = ray_of(j).query;
                HitQuery {
                    ray,
                    scope,
                    t: root_of(j).expect("only rays that met a surface"),
                }
            })
            .collect();
        let hits = q.hit_points(&hit_queries)?;
        c.search.add(&hits.search);
        if !hit_rays.is_empty() {
            ray_cost.resize(results.len(), 0.0);
            for (&j, t) in hit_rays.iter().zip(&hits.cost) {
                ray_cost[j] += t;
            }
        }
        // Where ray `j`'s hit record comes from: made here from its root where the backend
        // leaves that to the pass (`Ok`), else the backend's answer at its rank among the
        // rays asked about (`Err(rank)`).
        let hit_source = |j: usize| {
            let t = root_of(j)?;
            match direct {
                Some(d) if DirectHits::applies(t) => Some(Ok((d, t))),
                _ => hit_rays.binary_search(&j).ok().map(Err),
            }
        };
        let hit_of = |j: usize| match hit_source(j)? {
            Ok((d, t)) => {
                let (p, r) = pixel_of(j);
                let traced = traces_of(kind(p), traced, p);
                let ray = ray_of_pixel(&pixel_rays, window.pixel(p), kind(p), traced, r);
                d.hit(&ray, t)
            }
            Err(rank) => Some(hits.values[rank]),
        };
        if ray_cost.is_empty() {
            // No ray was searched or asked about: no pixel of the batch cost anything
            // measured (every root and hit point followed from what the boxes proved).
            cost.resize(cost.len() + n, 0.0);
        } else {
            cost.extend(
                (0..n).map(|k| ray_cost[first_ray[k]..first_ray[k + 1]].iter().sum::<f32>()),
            );
        }
        // The leaf that shades ray `j`'s first root, without its hit record.
        let leaf_of = |j: usize| match hit_source(j)? {
            Ok((d, _)) => Some(d.leaf),
            Err(rank) => Some(hits.values[rank].leaf),
        };
        // Each pixel's rays, in order. A Miss box's pixel has none: it is background,
        // proven missed.
        sink.extend(
            RayBatch {
                first: &first_ray,
                owner: &ray_pixel,
            },
            (
                |k| sample_area(kinds[k].0),
                |k| known_leaf.filter(|_| kinds[k].1).map(|d| d.leaf),
            ),
            leaf_of,
            hit_of,
        );
        progress.advance(u64::from(rows));
    }
    progress.end();
    Ok((
        sink,
        cost,
        PassStats::of(Pass::PrimaryRays, t0.elapsed(), &c),
    ))
}
