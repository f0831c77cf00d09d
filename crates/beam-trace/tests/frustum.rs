//! The frustum octree (`primary = "octree"`): what its first cells prove, and the images it
//! gives against the screen box structure with the same rays.

mod ball;

use ball::Ball;
use beam_trace::backend::{Backend, CellQuery, QueryKind};
use beam_trace::beam::BoxClass;
use beam_trace::frustum::{FirstCell, Traced};
use beam_trace::screen::{PixelRect, stratified_offsets};
use beam_trace::{Cpu, NoProgress, Plan, Progress, Scene, render};
use glam::DVec3;
use std::sync::atomic::{AtomicU64, Ordering};

/// The render table of the scenes of these tests: the frustum octree.
const OCTREE: &str = "[render]\nprimary = \"octree\"";

/// A progress that counts the units reported done.
#[derive(Default)]
struct Counted(AtomicU64);

impl Progress for Counted {
    fn advance(&self, n: u64) {
        self.0.fetch_add(n, Ordering::Relaxed);
    }
}

/// What [`check_first_cells`] counted: pixels with a first cell, traced rays that missed,
/// that found their first root (and of those, past their pixel's first cell: rays that
/// pass a silhouette and meet a surface behind), that were left to the root finder, and
/// proven hits.
#[derive(Debug, Default)]
struct Checked {
    covered: usize,
    traced_miss: usize,
    traced_hit: usize,
    traced_behind: usize,
    stuck: usize,
    hits: usize,
}

/// The first cells of `tiles` of `scene` (octree, 2 x 2 traced rays), checked on a 5 x 5
/// grid of every pixel's rays against `exact` (a ray's exact first intersection
/// parameter): none meets the surface before the pixel's first cell, a pixel without one
/// has no ray meeting it, and where the first cell is a proven hit every ray meets it
/// inside. Where the first cell is undecided, the rays traced on from there meet the
/// surface where the traces say: nowhere, or first in the range it proved.
fn check_first_cells(
    scene: &Scene,
    tiles: &[PixelRect],
    exact: impl Fn(DVec3, DVec3) -> Option<f64>,
) -> Checked {
    let plan = Plan::for_scene(scene);
    let prepared = Cpu
        .prepare(scene, &plan, &[QueryKind::Cells])
        .unwrap_or_else(|e| panic!("{e}"));
    let cam = &scene.camera;
    let offsets = stratified_offsets(4);
    let queries: Vec<CellQuery> = tiles
        .iter()
        .map(|&tile| CellQuery {
            tile,
            traced_rays: 4,
        })
        .collect();
    let done = Counted::default();
    let answers = prepared
        .queries
        .first_cells(&queries, &done)
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(answers.search.g_evals > 0);
    // Every tile's pixels reported done, once.
    assert_eq!(
        done.0.load(Ordering::Relaxed),
        tiles.iter().map(|t| t.area()).sum::<u64>()
    );
    let mut n = Checked::default();
    for (tile, cells) in tiles.iter().zip(&answers.values) {
        // One record per pixel: its first cell where it has one.
        let mut firsts: Vec<Option<&FirstCell>> = vec![None; tile.area() as usize];
        for (k, f) in cells.iter() {
            assert!(
                firsts[k as usize].is_none(),
                "pixel {k} of {tile:?} given twice"
            );
            firsts[k as usize] = Some(f);
        }
        for ((x, y), first) in tile.pixels().zip(firsts) {
            for k in 0..25 {
                let (fx, fy) = (f64::from(k % 5) / 4.0, f64::from(k / 5) / 4.0);
                let ray = cam.ray(f64::from(x) + fx, f64::from(y) + fy);
                let hit = exact(ray.origin, ray.dir);
                match (first, hit) {
                    (Some(f), Some(t)) => {
                        assert!(
                            t >= f.t.inf() * (1.0 - 1e-12),
                            "pixel ({x}, {y}): a root at {t} before its first cell {:?}",
                            f.t
                        );
                        if f.hit {
                            assert!(
                                t <= f.t.sup() * (1.0 + 1e-12),
                                "pixel ({x}, {y}): a proven hit in {:?}, the root at {t}",
                                f.t
                            );
                        }
                    }
                    (Some(f), None) => {
                        assert!(!f.hit, "pixel ({x}, {y}): a proven hit, a ray missing")
                    }
                    (None, Some(t)) => panic!("pixel ({x}, {y}) has no first cell, a root at {t}"),
                    (None, None) => {}
                }
            }
            n.covered += usize::from(first.is_some());
            n.hits += usize::from(first.is_some_and(|f| f.hit));
            let traced = first.as_ref().map_or(&[][..], |f| &f.traced[..]);
            assert!(
                traced.is_empty() || traced.len() == offsets.len(),
                "pixel ({x}, {y}): {} traces",
                traced.len()
            );
            for (traced, &(ox, oy)) in traced.iter().zip(&offsets) {
                let ray = cam.ray(f64::from(x) + ox, f64::from(y) + oy);
                match (traced, exact(ray.origin, ray.dir)) {
                    (&Traced::Clear { until }, exact) => {
                        assert!(
                            exact.is_none_or(|t| t >= until * (1.0 - 1e-12)),
                            "pixel ({x}, {y}) at ({ox}, {oy}): the root at {exact:?}, clear until {until}"
                        );
                        n.stuck += 1;
                    }
                    (Traced::NoRoot, None) => n.traced_miss += 1,
                    (Traced::First { t: range, .. }, Some(t)) => {
                        assert!(
                            range.inf() * (1.0 - 1e-12) <= t && t <= range.sup() * (1.0 + 1e-12),
                            "pixel ({x}, {y}) at ({ox}, {oy}): the root at {t}, traced in {range:?}"
                        );
                        n.traced_hit += 1;
                        n.traced_behind +=
                            usize::from(range.inf() > first.map_or(0.0, |f| f.t.sup()));
                    }
                    (traced, exact) => {
                        panic!(
                            "pixel ({x}, {y}) at ({ox}, {oy}): traced {traced:?}, root {exact:?}"
                        )
                    }
                }
            }
        }
    }
    n
}

/// [`check_first_cells`] on a ball, over a whole view and a tile that is not square.
#[test]
fn no_ray_meets_the_surface_before_its_first_cell() {
    let ball = Ball {
        centre: [0.2, -0.1, 0.3],
        r: 0.8,
        eye: [1.0, 2.0, 5.0],
        size: 48,
        fov: 35.0,
    };
    let scene = ball.scene(OCTREE);
    let tiles = [
        PixelRect {
            x0: 0,
            y0: 0,
            x1: 48,
            y1: 48,
        },
        PixelRect {
            x0: 7,
            y0: 13,
            x1: 30,
            y1: 21,
        },
    ];
    let n = check_first_cells(&scene, &tiles, |o, d| ball.exact_t(o, d));
    assert!(
        n.traced_miss > 0 && n.traced_hit > 0,
        "the silhouette's undecided pixels trace both ways: {n:?}"
    );
    // The rest are left to the root finder past the part proven clear (a graze, or the
    // budget of evaluations spent).
    assert!(
        n.stuck * 3 <= n.traced_miss + n.traced_hit,
        "most rays are decided: {n:?}"
    );
    assert!(n.covered > 500, "the ball covers much of the view: {n:?}");
    assert!(
        n.hits > 100,
        "most of the ball's pixels are proven hits: {n:?}"
    );
}

/// [`check_first_cells`] where the depth steps: a small ball in front of a large one, so
/// that many cells hold pixels that found the near ball and pixels whose rays go on to
/// the far one (the search goes on over the beam of the pixels left).
#[test]
fn first_cells_hold_behind_a_step_in_depth() {
    let near = Ball {
        centre: [0.3, 0.2, 1.2],
        r: 0.45,
        eye: [0.0, 0.0, 6.0],
        size: 64,
        fov: 40.0,
    };
    let far = Ball {
        centre: [-0.2, -0.1, -1.0],
        r: 1.2,
        ..near
    };
    let ball = |b: &Ball| {
        let [cx, cy, cz] = b.centre;
        format!(
            "(x - {cx:?})^2 + (y - {cy:?})^2 + (z - {cz:?})^2 - {:?}",
            b.r * b.r
        )
    };
    // Seen from the eye looking at the origin.
    let view = Ball {
        centre: [0.0; 3],
        ..near
    };
    let scene = view.view(
        &format!("min({}, {})", ball(&near), ball(&far)),
        ([-2.5; 3], [2.5; 3]),
        OCTREE,
    );
    let tiles = [PixelRect {
        x0: 0,
        y0: 0,
        x1: 64,
        y1: 64,
    }];
    let exact = |o, d| match (near.exact_t(o, d), far.exact_t(o, d)) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    let n = check_first_cells(&scene, &tiles, exact);
    assert!(n.covered > 700, "the balls cover much of the view: {n:?}");
    assert!(n.hits > 400, "most of their pixels are proven hits: {n:?}");
    assert!(
        n.traced_behind > 0,
        "rays past the near ball's silhouette meet the far one: {n:?}"
    );
}

/// The octree with one ray per covered pixel draws what the screen box structure with one
/// ray per undecided pixel draws: the same silhouette, and colours within a rounding of
/// the hit point.
#[test]
fn octree_images_are_the_screen_boxes_images() {
    let cases = [
        ([0.0, 0.0, 0.0], 1.0, [0.3, 0.4, 5.0]),
        ([0.25, -0.5, 0.1], 0.01, [0.25, -0.5, 0.2]),
    ];
    for (centre, r, eye) in cases {
        let ball = Ball {
            centre,
            r,
            eye,
            size: 40,
            fov: 35.0,
        };
        // Lit (each hit's root narrowed) and unlit (the silhouette, each ray's first root
        // the one its range proves: the octree's traced rays are not searched again).
        for light in [
            "\n[[lights]]\ntype = \"point\"\nposition = [3.0, 4.0, 6.0]\n",
            "",
        ] {
            let with_light = |render: &str| ball.scene(&format!("[render]\n{render}{light}"));
            let octree = with_light("primary = \"octree\"\nrays_per_undecided = 1");
            let boxes = with_light("primary = \"screen-rays\"\nrays_per_undecided = 1");
            let a = render(&octree, &NoProgress).unwrap_or_else(|e| panic!("{e}"));
            let b = render(&boxes, &NoProgress).unwrap_or_else(|e| panic!("{e}"));
            assert!(a.box_classes().iter().all(Option::is_some));
            assert!(
                a.box_classes()
                    .iter()
                    .any(|c| matches!(c, Some(BoxClass::Hit { .. })))
            );
            let mut differing = 0;
            for (p, q) in a.image.pixels.iter().zip(&b.image.pixels) {
                let d = p
                    .iter()
                    .zip(q)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f32::max);
                differing += usize::from(d > 1e-3);
            }
            assert_eq!(
                differing, 0,
                "ball of radius {r}, light {light:?}: pixels differ"
            );
        }
    }
}

/// [`check_first_cells`] on a cluster of balls joined by `min` (a molecule of the CSG
/// benchmarks, small): the cells prune the formula to the balls near them, and the leaves
/// on the balls' flanks probe, and the silhouettes' rays are traced, past the ranges of
/// their cells with the look-behinds of the cells 16 pixels wide (`frustum`'s
/// `BEHIND_SIDE`), which must hold wherever they are used.
#[test]
fn first_cells_hold_in_a_cluster_of_balls() {
    let view = Ball {
        centre: [0.0, 0.0, 0.0],
        r: 1.0,
        eye: [0.4, 0.7, 6.0],
        size: 128,
        fov: 30.0,
    };
    // A 4 x 3 lattice of balls of different sizes, staggered in depth.
    let balls: Vec<Ball> = (0..12)
        .map(|i| {
            let (col, row) = (f64::from(i % 4), f64::from(i / 4));
            Ball {
                centre: [
                    -1.05 + 0.7 * col,
                    -0.7 + 0.7 * row,
                    0.35 * ((i * 7 % 5) as f64 - 2.0),
                ],
                r: 0.22 + 0.03 * f64::from(i % 3),
                ..view
            }
        })
        .collect();
    let formula = balls
        .iter()
        .map(|b| {
            let [cx, cy, cz] = b.centre;
            format!(
                "sqrt((x - {cx:?})^2 + (y - {cy:?})^2 + (z - {cz:?})^2) - {:?}",
                b.r
            )
        })
        .reduce(|a, b| format!("min({a}, {b})"))
        .expect("balls");
    let scene = view.view(&formula, ([-2.0; 3], [2.0; 3]), OCTREE);
    let tiles: Vec<PixelRect> = (0..4)
        .map(|k| PixelRect {
            x0: 64 * (k % 2),
            y0: 64 * (k / 2),
            x1: 64 * (k % 2) + 64,
            y1: 64 * (k / 2) + 64,
        })
        .collect();
    let exact = |o, d| {
        balls
            .iter()
            .filter_map(|b| b.exact_t(o, d))
            .min_by(f64::total_cmp)
    };
    let n = check_first_cells(&scene, &tiles, exact);
    assert!(n.covered > 3000, "the balls cover much of the view: {n:?}");
    assert!(n.hits > 2000, "most of their pixels are proven hits: {n:?}");
    assert!(
        n.traced_miss > 0 && n.traced_hit > 0,
        "the silhouettes' undecided pixels trace both ways: {n:?}"
    );
    assert!(
        n.traced_behind > 0,
        "rays past a silhouette meet a ball behind: {n:?}"
    );
}
