//! The frustum octree (`primary = "octree"`): what its first cells prove, and the images it
//! gives against the screen box structure with the same rays.

mod ball;

use ball::Ball;
use beam_trace::backend::{Backend, CellQuery, QueryKind};
use beam_trace::beam::BoxClass;
use beam_trace::frustum::{FirstCell, Traced};
use beam_trace::screen::{PixelRect, stratified_offsets};
use beam_trace::{Cpu, NoProgress, Plan, render};

/// For every pixel, a 5 x 5 grid of its rays: none meets the ball before the pixel's first
/// cell, a pixel without one has no ray meeting the ball, and where the first cell is a
/// proven hit every ray meets the ball inside it. Where the first cell is undecided, the
/// rays traced on from there (2 x 2 of them) meet the ball where the traces say: nowhere, or first
/// in the range it proved.
#[test]
fn no_ray_meets_the_surface_before_its_first_cell() {
    let ball = Ball {
        centre: [0.2, -0.1, 0.3],
        r: 0.8,
        eye: [1.0, 2.0, 5.0],
        size: 48,
        fov: 35.0,
    };
    let scene = ball.scene("[render]\nprimary = \"octree\"");
    let plan = Plan::for_scene(&scene);
    let prepared = Cpu
        .prepare(&scene, &plan, &[QueryKind::Cells])
        .unwrap_or_else(|e| panic!("{e}"));
    let cam = &scene.camera;
    let offsets = stratified_offsets(4);
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
    let queries: Vec<CellQuery> = tiles
        .iter()
        .map(|&tile| CellQuery {
            tile,
            traced_rays: 4,
        })
        .collect();
    let answers = prepared
        .queries
        .first_cells(&queries)
        .unwrap_or_else(|e| panic!("{e}"));
    let (mut covered, mut traced_miss, mut traced_hit, mut stuck) = (0, 0, 0, 0);
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
                let hit = ball.exact_t(ray.origin, ray.dir);
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
            covered += usize::from(first.is_some());
            let traced = first.as_ref().map_or(&[][..], |f| &f.traced[..]);
            assert!(
                traced.is_empty() || traced.len() == offsets.len(),
                "pixel ({x}, {y}): {} traces",
                traced.len()
            );
            for (traced, &(ox, oy)) in traced.iter().zip(&offsets) {
                let ray = cam.ray(f64::from(x) + ox, f64::from(y) + oy);
                match (traced, ball.exact_t(ray.origin, ray.dir)) {
                    (&Traced::Clear { until }, exact) => {
                        assert!(
                            exact.is_none_or(|t| t >= until * (1.0 - 1e-12)),
                            "pixel ({x}, {y}) at ({ox}, {oy}): the root at {exact:?}, clear until {until}"
                        );
                        stuck += 1;
                    }
                    (Traced::NoRoot, None) => traced_miss += 1,
                    (Traced::First { t: range, .. }, Some(t)) => {
                        assert!(
                            range.inf() * (1.0 - 1e-12) <= t && t <= range.sup() * (1.0 + 1e-12),
                            "pixel ({x}, {y}) at ({ox}, {oy}): the root at {t}, traced in {range:?}"
                        );
                        traced_hit += 1;
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
    assert!(
        traced_miss > 0 && traced_hit > 0,
        "the silhouette's undecided pixels trace both ways: {traced_miss} misses, {traced_hit} hits"
    );
    // The rest are left to the root finder past the part proven clear (a graze, or the
    // budget of evaluations spent).
    assert!(
        stuck * 3 <= traced_miss + traced_hit,
        "most rays are decided: {stuck} of {} left to the root finder",
        stuck + traced_miss + traced_hit
    );
    assert!(covered > 500, "the ball covers much of the view: {covered}");
    let hits: usize = answers
        .values
        .iter()
        .flat_map(|cells| cells.iter())
        .filter(|(_, f)| f.hit)
        .count();
    assert!(
        hits > 100,
        "most of the ball's pixels are proven hits: {hits}"
    );
    assert!(answers.search.g_evals > 0);
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
