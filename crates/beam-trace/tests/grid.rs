//! The regular grid: classification, per-cell CSG reduction, ray and beam traversal, and
//! the first root through the grid against the first root of the whole scene function.

use std::collections::HashMap;

use beam_trace::beam::forward;
use beam_trace::grid::{CellHit, Grid};
use beam_trace::ray::{Beam, BeamEval, IBox, Ray};
use beam_trace::root::{
    Proof, RayFn, RootCounters, RootFinder, RootMethod, RootResult, RootSettings,
};
use beam_trace::scene::{Csg, Geometry, Leaf, Material};
use glam::DVec3;
use implicit_expr::{Context, Evaluator, parse::parse};
use interval_core::Interval;

// ---------------------------------------------------------------------------------------
// Helpers.

/// xorshift64*: a small deterministic generator.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    fn next_u64(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    /// Uniform in `[0, 1)`.
    fn f(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f()
    }
    fn unit(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length();
            if l > 0.1 && l <= 1.0 {
                return v / l;
            }
        }
    }
    fn in_box(&mut self, b: &IBox) -> DVec3 {
        DVec3::new(
            self.range(b[0].inf(), b[0].sup()),
            self.range(b[1].inf(), b[1].sup()),
            self.range(b[2].inf(), b[2].sup()),
        )
    }
}

fn iv(lo: f64, hi: f64) -> Interval<f64> {
    Interval::new_unchecked(lo, hi)
}

fn cube(r: f64) -> IBox {
    [iv(-r, r); 3]
}

/// A geometry of leaves given by formulas and CSG objects over them.
fn geometry(formulas: &[&str], objects: Vec<Csg>, bounds: IBox) -> Geometry {
    let mut ctx = Context::new();
    let leaves = formulas
        .iter()
        .enumerate()
        .map(|(i, f)| Leaf {
            name: format!("leaf{i}"),
            node: parse(&mut ctx, f, &[]).expect("formula parses"),
            material: Material::default(),
            bounds,
            clipped: false,
        })
        .collect();
    Geometry::new(ctx, leaves, objects).expect("geometry builds")
}

fn sphere() -> Geometry {
    geometry(&["x^2+y^2+z^2-1"], vec![Csg::Leaf(0)], cube(1.5))
}

fn two_spheres() -> Geometry {
    geometry(
        &["(x-0.5)^2+y^2+z^2-0.36", "(x+0.5)^2+(y-0.2)^2+z^2-0.25"],
        vec![Csg::Union(vec![Csg::Leaf(0), Csg::Leaf(1)])],
        cube(1.2),
    )
}

/// The same two spheres as two top-level objects.
fn two_objects() -> Geometry {
    geometry(
        &["(x-0.5)^2+y^2+z^2-0.36", "(x+0.5)^2+(y-0.2)^2+z^2-0.25"],
        vec![Csg::Leaf(0), Csg::Leaf(1)],
        cube(1.2),
    )
}

fn difference() -> Geometry {
    geometry(
        &["x^2+y^2+z^2-1", "(x-0.6)^2+y^2+(z+0.1)^2-0.36"],
        vec![Csg::Difference(
            Box::new(Csg::Leaf(0)),
            Box::new(Csg::Leaf(1)),
        )],
        cube(1.5),
    )
}

fn intersection() -> Geometry {
    geometry(
        &["x^2+y^2+z^2-1", "z^2-0.25", "(x+y)^2-0.8"],
        vec![Csg::Intersection(vec![
            Csg::Leaf(0),
            Csg::Leaf(1),
            Csg::Leaf(2),
        ])],
        cube(1.5),
    )
}

/// A nested tree: (sphere − small sphere) ∪ (slab ∩ ball), and a second object.
fn nested() -> Geometry {
    geometry(
        &[
            "x^2+y^2+z^2-1",
            "(x-0.7)^2+y^2+z^2-0.3",
            "y^2-0.04",
            "(x+0.8)^2+(y+0.3)^2+z^2-0.5",
            "(x-0.2)^2+(y-0.9)^2+(z-0.3)^2-0.1",
        ],
        vec![
            Csg::Union(vec![
                Csg::Difference(Box::new(Csg::Leaf(0)), Box::new(Csg::Leaf(1))),
                Csg::Intersection(vec![Csg::Leaf(2), Csg::Leaf(3)]),
            ]),
            Csg::Leaf(4),
        ],
        cube(1.6),
    )
}

/// A union with a leaf undefined for `x < -0.3`: the scene function is undefined there,
/// so no cell entirely at `x < -0.3` may hold a surface, and the leaf, positive wherever
/// it is defined, may not be dropped from a cell where it is undefined somewhere (the
/// reduced function would be defined, with the sphere's roots, where `f` is not).
fn partly_undefined() -> Geometry {
    geometry(
        &["x^2+y^2+z^2-1", "sqrt(x+0.3)+0.5"],
        vec![Csg::Union(vec![Csg::Leaf(0), Csg::Leaf(1)])],
        cube(1.5),
    )
}

fn scenes() -> Vec<(&'static str, Geometry)> {
    vec![
        ("sphere", sphere()),
        ("two spheres", two_spheres()),
        ("two objects", two_objects()),
        ("difference", difference()),
        ("intersection", intersection()),
        ("nested", nested()),
        ("partly undefined", partly_undefined()),
    ]
}

const RESOLUTIONS: [u32; 5] = [1, 4, 7, 16, 32];

fn all_cells(grid: &Grid) -> impl Iterator<Item = [u32; 3]> + '_ {
    let [nx, ny, nz] = grid.dims();
    (0..nz).flat_map(move |k| (0..ny).flat_map(move |j| (0..nx).map(move |i| [i, j, k])))
}

/// The cells whose closed box holds `p`, from the grid's own boxes.
struct CellFinder {
    ranges: [Vec<Interval<f64>>; 3],
}

impl CellFinder {
    fn new(grid: &Grid) -> Self {
        let n = grid.dims();
        CellFinder {
            ranges: std::array::from_fn(|a| {
                (0..n[a])
                    .map(|i| {
                        let mut c = [0; 3];
                        c[a] = i;
                        grid.cell_box(c)[a]
                    })
                    .collect()
            }),
        }
    }

    fn cells(&self, p: DVec3) -> Vec<[u32; 3]> {
        let p = p.to_array();
        let idx: [Vec<u32>; 3] = std::array::from_fn(|a| {
            (0..self.ranges[a].len() as u32)
                .filter(|&i| {
                    let r = self.ranges[a][i as usize];
                    r.inf() <= p[a] && p[a] <= r.sup()
                })
                .collect()
        });
        let mut out = Vec::new();
        for &i in &idx[0] {
            for &j in &idx[1] {
                for &k in &idx[2] {
                    out.push([i, j, k]);
                }
            }
        }
        out
    }
}

fn in_box(b: &IBox, p: DVec3) -> bool {
    let p = p.to_array();
    (0..3).all(|a| b[a].inf() <= p[a] && p[a] <= b[a].sup())
}

/// Point values of the full scene function.
struct FullF(Evaluator<f64>);

impl FullF {
    fn new(g: &Geometry) -> Self {
        FullF(Evaluator::new(g.tape()))
    }
    fn at(&mut self, p: DVec3) -> f64 {
        self.0.eval(&[p.x, p.y, p.z]).unwrap()
    }
}

/// Points where the scene function changes sign (within 1e-13 along a segment): points of
/// the true surface, up to rounding.
fn surface_points(g: &Geometry, rng: &mut Rng, want: usize) -> Vec<DVec3> {
    let mut f = FullF::new(g);
    let b = g.bounds();
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < want && tries < want * 200 {
        tries += 1;
        let p = rng.in_box(&b);
        let q = rng.in_box(&b);
        let (fp, fq) = (f.at(p), f.at(q));
        if !(fp.is_finite() && fq.is_finite()) || (fp < 0.0) == (fq < 0.0) {
            continue;
        }
        let (mut a, mut c, mut fa) = (p, q, fp);
        let mut ok = true;
        while a.distance(c) > 1e-13 {
            let m = (a + c) * 0.5;
            let fm = f.at(m);
            if !fm.is_finite() {
                ok = false;
                break;
            }
            if (fm < 0.0) == (fa < 0.0) {
                a = m;
                fa = fm;
            } else {
                c = m;
            }
            if m == a && m == c {
                break;
            }
        }
        if ok {
            out.push((a + c) * 0.5);
        }
    }
    assert!(
        out.len() >= want / 2,
        "too few surface points: {}",
        out.len()
    );
    out
}

// ---------------------------------------------------------------------------------------
// A tiny interval bisection, independent of the crate's root finders.

#[derive(Debug)]
struct TestBisection;

impl RootFinder for TestBisection {
    fn name(&self) -> &'static str {
        "test-bisection"
    }
    fn first_root(
        &self,
        g: &mut dyn RayFn,
        t: Interval<f64>,
        settings: &RootSettings,
        counters: &mut RootCounters,
    ) -> RootResult {
        if t.is_empty() {
            return RootResult::NoRoot;
        }
        let mut stack = vec![t];
        let mut steps = 0;
        while let Some(x) = stack.pop() {
            counters.g_evals += 1;
            let (v, continuous) = g.g_checked(x);
            if v.is_empty() || !v.contains(0.0) {
                continue;
            }
            if x.wid() <= settings.epsilon || x.mid() == x.inf() || x.mid() == x.sup() {
                let ga = g.g(iv(x.inf(), x.inf()));
                let gb = g.g(iv(x.sup(), x.sup()));
                let change =
                    (ga.sup() < 0.0 && gb.inf() > 0.0) || (ga.inf() > 0.0 && gb.sup() < 0.0);
                let proof = if continuous && change {
                    Proof::Exists
                } else {
                    Proof::Possible
                };
                return RootResult::Root { t: x, proof };
            }
            steps += 1;
            if steps > settings.max_steps {
                return RootResult::Undecided {
                    t: iv(x.inf(), t.sup()),
                };
            }
            counters.bisections += 1;
            let (l, r) = x.bisect();
            stack.push(r);
            stack.push(l);
        }
        RootResult::NoRoot
    }
}

fn settings() -> RootSettings {
    RootSettings {
        epsilon: 1e-9,
        max_steps: 200_000,
        ..RootSettings::default()
    }
}

// ---------------------------------------------------------------------------------------
// Building.

#[test]
fn dims_statistics_and_thread_independence() {
    let g = geometry(
        &["x^2+y^2+z^2-1"],
        vec![Csg::Leaf(0)],
        [iv(-2.0, 2.0), iv(-1.0, 1.0), iv(-0.1, 0.1)],
    );
    let grid = Grid::build(&g, 8);
    assert_eq!(grid.dims(), [8, 4, 1]);
    let s = grid.stats();
    assert_eq!(s.cells, 32);
    // The octree classification: the whole grid, then the blocks the sphere's surface
    // crosses, never more than twice the flat classification's one evaluation per cell.
    assert!(
        s.leaf_evals >= 1 && s.leaf_evals <= 2 * s.cells,
        "{}",
        s.leaf_evals
    );
    assert!(s.non_empty > 0 && s.non_empty < s.cells);
    assert!(s.functions >= 1);
    // Resolution 0 is one cell.
    assert_eq!(Grid::build(&g, 0).dims(), [1, 1, 1]);

    for (name, g) in scenes() {
        let grid = Grid::build(&g, 9);
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| Grid::build(&g, 9));
        assert_eq!(grid.stats(), one.stats(), "{name}");
        for c in all_cells(&grid) {
            assert_eq!(grid.cell_function(c), one.cell_function(c), "{name} {c:?}");
        }
        let st = grid.stats();
        let counted = all_cells(&grid)
            .filter(|&c| grid.cell_function(c).is_some())
            .count() as u64;
        assert_eq!(st.non_empty, counted, "{name}");
        assert!(st.functions as usize <= grid.function_count());
        // Serializable statistics.
        let json = serde_json::to_string(&st).unwrap();
        assert!(json.contains("non_empty"), "{json}");
    }
}

#[test]
fn cells_tile_the_bounds() {
    let g = two_spheres();
    for res in RESOLUTIONS {
        let grid = Grid::build(&g, res);
        let b = grid.bounds();
        let [nx, ny, nz] = grid.dims();
        assert_eq!(grid.cell_box([0, 0, 0])[0].inf(), b[0].inf());
        assert_eq!(grid.cell_box([nx - 1, ny - 1, nz - 1])[2].sup(), b[2].sup());
        for c in all_cells(&grid) {
            let cb = grid.cell_box(c);
            let kb = grid.class_box(c);
            for a in 0..3 {
                assert!(cb[a].subset(kb[a]) && cb[a].inf() > kb[a].inf());
                if c[a] + 1 < grid.dims()[a] {
                    let mut n = c;
                    n[a] += 1;
                    assert_eq!(cb[a].sup(), grid.cell_box(n)[a].inf());
                }
            }
        }
    }
}

#[test]
fn every_cell_with_surface_is_non_empty() {
    let mut rng = Rng::new(1);
    for (name, g) in scenes() {
        let pts = surface_points(&g, &mut rng, 400);
        for res in RESOLUTIONS {
            let grid = Grid::build(&g, res);
            let finder = CellFinder::new(&grid);
            for &p in &pts {
                let mut found = 0;
                for c in finder.cells(p) {
                    assert!(in_box(&grid.cell_box(c), p));
                    {
                        found += 1;
                        assert!(
                            grid.cell_function(c).is_some(),
                            "{name} res {res}: surface point {p} in empty cell {c:?}"
                        );
                    }
                }
                assert!(found >= 1, "{name}: {p} in no cell");
            }
        }
    }
}

#[test]
fn reduced_functions_keep_sign_and_zero_set() {
    let mut rng = Rng::new(2);
    for (name, g) in scenes() {
        let mut full = FullF::new(&g);
        for res in [2, 5, 11, 24] {
            let grid = Grid::build(&g, res);
            let mut evals: HashMap<u32, BeamEval> = HashMap::new();
            let mut compared = 0;
            for c in all_cells(&grid) {
                let Some(fi) = grid.cell_function(c) else {
                    continue;
                };
                let e = evals
                    .entry(fi)
                    .or_insert_with(|| BeamEval::new(grid.function(fi)));
                let kb = grid.class_box(c);
                for _ in 0..30 {
                    let p = rng.in_box(&kb);
                    e.set_ray(&Ray {
                        origin: p,
                        dir: DVec3::ZERO,
                    });
                    let r = e.g_point(0.0);
                    let f = full.at(p);
                    if f.is_nan() || r.is_nan() {
                        assert!(
                            f.is_nan() && r.is_nan(),
                            "{name} {c:?} at {p}: f {f}, reduced {r}"
                        );
                        continue;
                    }
                    if f.abs() < 1e-12 {
                        continue;
                    }
                    assert_eq!(
                        f < 0.0,
                        r < 0.0,
                        "{name} res {res} cell {c:?} at {p}: f {f}, reduced {r}"
                    );
                    assert!(r.abs() > 0.0, "{name}: reduced zero where f = {f}");
                    compared += 1;
                }
            }
            assert!(compared > 0, "{name}");
        }
    }
}

#[test]
fn reduction_simplifies_cells() {
    // Far from the small sphere the difference reduces to the big sphere alone, so the
    // grid has more than one distinct function, and some are shorter than the full one.
    let g = difference();
    let grid = Grid::build(&g, 12);
    assert!(grid.stats().functions >= 2, "{:?}", grid.stats());
    let full_len = grid.function(grid.full_function()).g_tape().len();
    let shortest = (0..grid.function_count() as u32)
        .map(|i| grid.function(i).g_tape().len())
        .min()
        .unwrap();
    assert!(shortest < full_len, "{shortest} vs {full_len}");

    // The partly undefined union: where `sqrt(x + 0.3)` is undefined (cells entirely at
    // x < -0.3) its object is absent, and a cell there keeps the sphere exactly where the
    // sphere crosses it (its natural extension is the exact range over a box).
    let g = partly_undefined();
    let grid = Grid::build(&g, 10);
    let (mut crossed, mut empty) = (0, 0);
    for c in all_cells(&grid) {
        let b = grid.class_box(c);
        if b[0].sup() < -0.3 {
            let sphere = b[0].sqr() + b[1].sqr() + b[2].sqr() - Interval::new(1.0, 1.0).unwrap();
            let crosses = sphere.contains(0.0);
            assert_eq!(grid.cell_function(c).is_some(), crosses, "{c:?}");
            if crosses {
                crossed += 1;
            } else {
                empty += 1;
            }
        }
    }
    assert!(crossed > 0 && empty > 0, "{crossed} {empty}");
}

// ---------------------------------------------------------------------------------------
// Ray traversal.

/// The float parameters where the ray is in a box (slab test in rounded arithmetic).
fn float_t_range(ray: &Ray, b: &IBox) -> Option<(f64, f64)> {
    let (o, d) = (ray.origin.to_array(), ray.dir.to_array());
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for a in 0..3 {
        if d[a] == 0.0 {
            if o[a] < b[a].inf() || o[a] > b[a].sup() {
                return None;
            }
        } else {
            let t1 = (b[a].inf() - o[a]) / d[a];
            let t2 = (b[a].sup() - o[a]) / d[a];
            lo = lo.max(t1.min(t2));
            hi = hi.min(t1.max(t2));
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// Rays of every kind for a grid over `cube(r)`.
fn test_rays(rng: &mut Rng, r: f64, grid: &Grid, count: usize) -> Vec<Ray> {
    let mut rays = Vec::new();
    let b = grid.bounds();
    // A boundary plane value of the grid on each axis (a cell corner).
    let mid = grid.dims().map(|n| n / 2);
    let corner = grid.cell_box(mid).map(|x| x.inf());
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    for (a, &ax) in axes.iter().enumerate() {
        for s in [1.0, -1.0] {
            // Along a grid edge line (two coordinates on boundaries), from outside.
            let mut o = DVec3::from_array(corner);
            o[a] = -s * 3.0 * r;
            rays.push(Ray {
                origin: o,
                dir: s * ax,
            });
            // In a grid plane, from inside.
            let mut o = DVec3::new(0.13, -0.21, 0.07);
            o[(a + 1) % 3] = corner[(a + 1) % 3];
            rays.push(Ray {
                origin: o,
                dir: s * ax,
            });
            // Diagonal in a grid plane (one zero component).
            let mut d = DVec3::ONE * s;
            d[a] = 0.0;
            let mut o = DVec3::new(-2.0 * r, -2.0 * r, -2.0 * r) * s;
            o[a] = corner[a];
            rays.push(Ray { origin: o, dir: d });
        }
    }
    // Through cell corners exactly (ties between all axes).
    rays.push(Ray {
        origin: DVec3::splat(-3.0 * r),
        dir: DVec3::ONE,
    });
    rays.push(Ray {
        origin: DVec3::from_array(corner),
        dir: DVec3::new(1.0, -1.0, 1.0),
    });
    // A zero direction inside the grid, and a ray missing the grid.
    rays.push(Ray {
        origin: DVec3::new(0.1, 0.2, 0.3),
        dir: DVec3::ZERO,
    });
    rays.push(Ray {
        origin: DVec3::splat(3.0 * r),
        dir: DVec3::X,
    });
    // Aimed at points of grid edges (two coordinates on cell boundaries): the ray crosses
    // two boundaries at nearly the same parameter, which rounding may order either way.
    let dims = grid.dims();
    for _ in 0..count / 4 {
        let cell = dims.map(|n| (rng.next_u64() % n as u64) as u32);
        let cb = grid.cell_box(cell);
        let free = (rng.next_u64() % 3) as usize;
        let mut p = DVec3::from_array(cb.map(|x| x.inf()));
        p[free] = rng.range(cb[free].inf(), cb[free].sup());
        let d = rng.unit() * rng.range(0.5, 2.0);
        rays.push(Ray {
            origin: p - 2.5 * r * d,
            dir: d,
        });
    }
    while rays.len() < count {
        let target = rng.in_box(&b);
        let origin = if rng.f() < 0.3 {
            rng.in_box(&b)
        } else {
            rng.unit() * 3.0 * r
        };
        let mut dir = target - origin;
        if rng.f() < 0.2 {
            // Some zero components.
            let a = (rng.next_u64() % 3) as usize;
            dir[a] = 0.0;
        }
        if dir == DVec3::ZERO {
            continue;
        }
        let scale = rng.range(0.3, 3.0);
        rays.push(Ray {
            origin,
            dir: dir * scale,
        });
    }
    rays
}

fn check_ray_traversal(name: &str, grid: &Grid, ray: &Ray, t: Interval<f64>) {
    let hits = grid.ray_cells(ray, t);
    // Increasing t_c.inf(), each cell once, only non-empty cells, within t.
    for w in hits.windows(2) {
        assert!(
            w[0].t.inf() <= w[1].t.inf(),
            "{name}: order {:?} then {:?} for {ray:?}",
            w[0],
            w[1]
        );
    }
    let mut seen = HashMap::new();
    for h in &hits {
        assert!(
            seen.insert(h.cell, h.t).is_none(),
            "{name}: {:?} twice",
            h.cell
        );
        // A non-empty cell, searched with its own function (or the full one as fallback).
        let own = grid.cell_function(h.cell).expect("non-empty cell");
        assert!(h.function == own || h.function == grid.full_function());
        assert!(h.t.subset(t), "{name}: {:?} outside {t:?}", h.t);
        assert!((h.function as usize) < grid.function_count());
        // Tight: the ray's point at the middle of t_c is (nearly) in the cell.
        let tm = h.t.mid();
        if tm.is_finite() {
            let p = ray.at(tm);
            let cb = grid.class_box(h.cell);
            let slack = 1e-9 * (1.0 + p.abs().max_element());
            let near = (0..3).all(|a| cb[a].inf() - slack <= p[a] && p[a] <= cb[a].sup() + slack);
            assert!(near, "{name}: {:?} far from {p} for {ray:?}", h);
        }
    }
    // The slab walk of the one-ray beam finds the same parameter ranges (a subset of
    // the cells: it also filters by the ray's coordinates over each slab).
    if ray.dir != DVec3::ZERO {
        for bc in grid.beam_cells_within(&ray.beam(), t) {
            assert_eq!(
                seen.get(&bc.cell),
                Some(&bc.t),
                "{name}: beam walk {bc:?} for {ray:?}"
            );
        }
    }
    // Brute force over every cell.
    for c in all_cells(grid) {
        if grid.cell_function(c).is_none() {
            continue;
        }
        let Some((lo, hi)) = float_t_range(ray, &grid.cell_box(c)) else {
            continue;
        };
        let (lo, hi) = (lo.max(t.inf()), hi.min(t.sup()));
        if lo > hi {
            continue;
        }
        let samples: Vec<f64> = if lo.is_finite() && hi.is_finite() {
            (0..=8).map(|k| lo + (hi - lo) * k as f64 / 8.0).collect()
        } else {
            vec![if lo.is_finite() { lo } else { hi.min(0.0) }]
        };
        for s in samples {
            if !in_box(&grid.cell_box(c), ray.at(s)) {
                continue;
            }
            let slack = 1e-12 * (1.0 + s.abs());
            let covered = seen
                .get(&c)
                .is_some_and(|tc| tc.inf() - slack <= s && s <= tc.sup() + slack);
            assert!(
                covered,
                "{name}: ray {ray:?} in non-empty cell {c:?} at t = {s}, visits {:?}",
                seen.get(&c)
            );
        }
    }
}

#[test]
fn ray_traversal_is_ordered_and_covers_non_empty_cells() {
    let mut rng = Rng::new(3);
    for (name, g) in scenes() {
        let r = g.bounds()[0].sup();
        for res in RESOLUTIONS {
            let grid = Grid::build(&g, res);
            let rays = test_rays(&mut rng, r, &grid, 120);
            for ray in &rays {
                check_ray_traversal(name, &grid, ray, forward());
                check_ray_traversal(name, &grid, ray, Interval::ENTIRE);
                check_ray_traversal(name, &grid, ray, iv(0.5, 2.0));
            }
        }
    }
}

#[test]
fn special_rays() {
    let g = sphere();
    let grid = Grid::build(&g, 6);
    // Missing the grid.
    let miss = Ray {
        origin: DVec3::new(5.0, 5.0, 5.0),
        dir: DVec3::X,
    };
    assert!(grid.ray_cells(&miss, forward()).is_empty());
    // Pointing away from it.
    let away = Ray {
        origin: DVec3::new(-3.0, 0.0, 0.0),
        dir: -DVec3::X,
    };
    assert!(grid.ray_cells(&away, forward()).is_empty());
    assert!(!grid.ray_cells(&away, Interval::ENTIRE).is_empty());
    // Along the x axis (on grid planes y = 0 and z = 0): the cells at both ends of the
    // sphere, each of the four cells sharing the edge line, in order.
    let axis = Ray {
        origin: DVec3::new(-3.0, 0.0, 0.0),
        dir: DVec3::X,
    };
    let hits = grid.ray_cells(&axis, forward());
    let near: Vec<&CellHit> = hits.iter().filter(|h| h.cell[0] == 1).collect();
    assert_eq!(near.len(), 4, "{hits:?}");
    assert!(hits.iter().any(|h| h.cell[0] == 4));
    // The sphere is entered at t = 2 (x = -1): the first visits cover it.
    assert!(hits[0].t.inf() <= 2.0 && 2.0 <= hits[0].t.sup());
    // Starting inside a cell.
    let inside = Ray {
        origin: DVec3::new(0.95, 0.05, 0.02),
        dir: DVec3::new(0.0, 0.0, 1.0),
    };
    let hits = grid.ray_cells(&inside, forward());
    assert_eq!(hits[0].cell, [4, 3, 3]);
    assert_eq!(hits[0].t.inf(), 0.0);
    // Zero direction: the cell of the origin, for every t.
    let still = Ray {
        origin: DVec3::new(0.99, 0.1, 0.1),
        dir: DVec3::ZERO,
    };
    let hits = grid.ray_cells(&still, forward());
    assert_eq!(hits.len(), 1);
    assert_eq!(hits[0].t, forward());
}

#[test]
fn beam_t_range_slab_test() {
    let b = cube(1.0);
    let ray = Ray {
        origin: DVec3::new(-3.0, 0.5, 0.0),
        dir: DVec3::new(2.0, 0.0, 0.0),
    };
    let t = ray.beam().t_range(&b).unwrap();
    assert!(t.inf() <= 1.0 && t.sup() >= 2.0 && t.wid() < 1.0 + 1e-12);
    // Parallel to a slab and outside it.
    let out = Ray {
        origin: DVec3::new(-3.0, 1.5, 0.0),
        dir: DVec3::X,
    };
    assert!(out.beam().t_range(&b).is_none());
    // A beam whose x direction straddles 0: two pieces, clipped to t before the hull.
    let beam = Beam {
        origin: [iv(3.0, 3.0), iv(0.0, 0.0), iv(0.0, 0.0)],
        dir: [iv(-1.0, 0.5), iv(0.0, 0.0), iv(0.0, 0.0)],
    };
    let t = beam.t_range_within(&b, forward()).unwrap();
    assert!(t.inf() <= 2.0 && t.sup() == f64::INFINITY);
    let t = beam.slab_t(0, iv(-1.0, 1.0), iv(-10.0, -5.0));
    assert!(t.contains(-5.0) && t.contains(-8.0) && !t.contains(-2.0));
}

// ---------------------------------------------------------------------------------------
// First root through the grid.

/// Checks what the two results prove about each other (a proven root of one may not lie
/// before the other's enclosure, nor where the other proves no root), and returns whether
/// they agree: both miss, or both hit at the same parameter (within 1e-6).
fn compare_first_roots(name: &str, grid_r: RootResult, full_r: RootResult, ray: &Ray) -> bool {
    let proven =
        |r: &RootResult| matches!(r, RootResult::Root { proof, .. } if *proof != Proof::Possible);
    match (grid_r, full_r) {
        (RootResult::NoRoot, RootResult::NoRoot) => true,
        (RootResult::Root { t: a, .. }, RootResult::Root { t: b, .. }) => {
            // Neither has a root before its enclosure, so a proven root of one is at or
            // after the other's lower bound.
            if proven(&grid_r) {
                assert!(b.inf() <= a.sup(), "{name}: grid {a:?} full {b:?} {ray:?}");
            }
            if proven(&full_r) {
                assert!(a.inf() <= b.sup(), "{name}: grid {a:?} full {b:?} {ray:?}");
            }
            (a.mid() - b.mid()).abs() <= 1e-6 * (1.0 + a.mid().abs())
        }
        (g, f) => {
            assert!(
                !proven(&g) && !proven(&f),
                "{name}: grid {g:?} but full {f:?} for {ray:?}"
            );
            false
        }
    }
}

fn first_roots_agree(finder: &dyn RootFinder, rays_per_grid: usize) {
    let mut rng = Rng::new(4);
    let s = settings();
    for (name, g) in scenes() {
        let r = g.bounds()[0].sup();
        let bounds = g.bounds();
        let mut full = BeamEval::new(g.ray_function());
        for res in [1, 5, 13] {
            let grid = Grid::build(&g, res);
            let mut evals = grid.evaluator();
            let rays = test_rays(&mut rng, r, &grid, rays_per_grid);
            let (mut agreed, mut hits, mut total) = (0, 0, 0);
            for ray in &rays {
                if ray.dir == DVec3::ZERO {
                    continue;
                }
                let mut c = RootCounters::default();
                let gr = grid.first_root(&mut evals, ray, finder, &s, &mut c);
                let fr = match ray.beam().t_range_within(&bounds, forward()) {
                    None => RootResult::NoRoot,
                    Some(t) => {
                        full.set_ray(ray);
                        finder.first_root(&mut full, t, &s, &mut c)
                    }
                };
                total += 1;
                if compare_first_roots(name, gr, fr, ray) {
                    agreed += 1;
                }
                if fr.root().is_some() {
                    hits += 1;
                }
            }
            assert!(hits > total / 10, "{name}: only {hits} hits of {total}");
            assert!(
                agreed * 100 >= total * 98,
                "{name} res {res}: {agreed} of {total} agree"
            );
        }
    }
}

#[test]
fn first_root_through_grid_equals_full_search() {
    first_roots_agree(&TestBisection, 150);
}

#[test]
fn first_root_with_the_crate_bisection() {
    let finder = RootMethod::Bisection.finder();
    // Until the method is implemented it panics: then there is nothing to test here.
    let probe = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let mut ctx = Context::new();
        let f = parse(&mut ctx, "x-0.5", &[]).unwrap();
        let rf = implicit_expr::RayFunction::new(&ctx, f).unwrap();
        let mut e = BeamEval::new(&rf);
        e.set_ray(&Ray {
            origin: DVec3::ZERO,
            dir: DVec3::X,
        });
        finder.first_root(
            &mut e,
            iv(0.0, 1.0),
            &settings(),
            &mut RootCounters::default(),
        )
    }));
    match probe {
        Err(_) => eprintln!("the bisection root finder is not available yet"),
        Ok(r) => {
            assert!(r.root().is_some_and(|t| t.contains(0.5)), "{r:?}");
            first_roots_agree(finder, 80);
        }
    }
}

#[test]
fn first_root_misses_and_limits() {
    let g = sphere();
    let grid = Grid::build(&g, 8);
    let mut evals = grid.evaluator();
    let s = settings();
    let mut c = RootCounters::default();
    let miss = Ray {
        origin: DVec3::new(-3.0, 1.2, 0.0),
        dir: DVec3::X,
    };
    assert_eq!(
        grid.first_root(&mut evals, &miss, &TestBisection, &s, &mut c),
        RootResult::NoRoot
    );
    let hit = Ray {
        origin: DVec3::new(-3.0, 0.0, 0.0),
        dir: DVec3::X,
    };
    let r = grid.first_root(&mut evals, &hit, &TestBisection, &s, &mut c);
    assert!(r.root().is_some_and(|t| t.contains(2.0)), "{r:?}");
    // From inside the sphere the first root is the exit.
    let inside = Ray {
        origin: DVec3::ZERO,
        dir: DVec3::new(0.0, -2.0, 0.0),
    };
    let r = grid.first_root(&mut evals, &inside, &TestBisection, &s, &mut c);
    assert!(r.root().is_some_and(|t| t.contains(0.5)), "{r:?}");
    // A range that ends before the sphere.
    let r = grid.first_root_within(&mut evals, &hit, iv(0.0, 1.9), &TestBisection, &s, &mut c);
    assert_eq!(r, RootResult::NoRoot);
    let r = grid.first_root_within(&mut evals, &hit, iv(2.5, 10.0), &TestBisection, &s, &mut c);
    assert!(r.root().is_some_and(|t| t.contains(4.0)), "{r:?}");
    assert!(c.g_evals > 0);
}

// ---------------------------------------------------------------------------------------
// Beam traversal.

fn random_beam(rng: &mut Rng, r: f64, b: &IBox) -> Beam {
    let eye = rng.unit() * 3.0 * r;
    let target = rng.in_box(b);
    let d = target - eye;
    let w = rng.range(0.0, 0.4) * d.length();
    let origin = if rng.f() < 0.3 {
        let e = rng.range(0.0, 0.2);
        eye.to_array().map(|x| iv(x - e, x + e))
    } else {
        eye.to_array().map(|x| iv(x, x))
    };
    let dir = d.to_array().map(|x| {
        let (lo, hi) = (x - w * rng.f(), x + w * rng.f());
        iv(lo, hi)
    });
    Beam { origin, dir }
}

fn check_beam(name: &str, grid: &Grid, beam: &Beam, rng: &mut Rng) {
    let cells = grid.beam_cells(beam);
    for w in cells.windows(2) {
        assert!(w[0].t.inf() <= w[1].t.inf(), "{name}: order");
    }
    let by_cell: HashMap<[u32; 3], Interval<f64>> = cells.iter().map(|c| (c.cell, c.t)).collect();
    assert_eq!(by_cell.len(), cells.len(), "{name}: a cell twice");
    for c in &cells {
        assert_eq!(grid.cell_function(c.cell), Some(c.function));
        assert!(c.t.inf() >= 0.0);
    }
    let ranges = grid.beam_t_ranges(beam);
    for w in ranges.windows(2) {
        assert!(w[0].sup() < w[1].inf(), "{name}: ranges {ranges:?}");
    }
    for c in &cells {
        assert!(ranges.iter().any(|r| c.t.subset(*r)));
    }
    // Sample rays of the beam (corners included) and points along them.
    let finder = CellFinder::new(grid);
    for k in 0..24 {
        let pick = |x: Interval<f64>, rng: &mut Rng| match k % 3 {
            0 => x.inf(),
            1 => x.sup(),
            _ => rng.range(x.inf(), x.sup()),
        };
        let ray = Ray {
            origin: DVec3::from_array(beam.origin.map(|x| pick(x, rng))),
            dir: DVec3::from_array(beam.dir.map(|x| pick(x, rng))),
        };
        let Some(t) = ray.beam().t_range_within(&grid.bounds(), forward()) else {
            continue;
        };
        for s in 0..=200 {
            let tt = t.inf() + (t.sup() - t.inf()) * s as f64 / 200.0;
            let p = ray.at(tt);
            for cell in finder.cells(p) {
                if grid.cell_function(cell).is_none() {
                    continue;
                }
                let slack = 1e-12 * (1.0 + tt.abs());
                let covered = by_cell
                    .get(&cell)
                    .is_some_and(|tc| tc.inf() - slack <= tt && tt <= tc.sup() + slack);
                assert!(
                    covered,
                    "{name}: ray {ray:?} at t = {tt} in {cell:?} not covered"
                );
                assert!(
                    ranges
                        .iter()
                        .any(|r| r.inf() - slack <= tt && tt <= r.sup() + slack),
                    "{name}: t = {tt} outside the ranges"
                );
            }
        }
    }
}

#[test]
fn beam_traversal_covers_rays_of_the_beam() {
    let mut rng = Rng::new(5);
    for (name, g) in scenes() {
        let r = g.bounds()[0].sup();
        let b = g.bounds();
        for res in [1, 4, 9] {
            let grid = Grid::build(&g, res);
            for _ in 0..12 {
                let beam = random_beam(&mut rng, r, &b);
                check_beam(name, &grid, &beam, &mut rng);
            }
            // A ray as a beam, and a beam from inside the grid.
            let ray = Ray {
                origin: DVec3::new(-3.0 * r, 0.0, 0.0),
                dir: DVec3::X,
            };
            check_beam(name, &grid, &ray.beam(), &mut rng);
            let inner = Beam {
                origin: [iv(0.1, 0.1), iv(0.2, 0.2), iv(-0.1, -0.1)],
                dir: [iv(0.5, 1.0), iv(-0.2, 0.3), iv(-0.1, 0.0)],
            };
            check_beam(name, &grid, &inner, &mut rng);
        }
    }
}

#[test]
fn beam_missing_the_grid_has_no_cells() {
    let grid = Grid::build(&sphere(), 6);
    let beam = Beam {
        origin: [iv(0.0, 0.0), iv(5.0, 5.0), iv(0.0, 0.0)],
        dir: [iv(0.9, 1.0), iv(0.0, 0.1), iv(-0.1, 0.1)],
    };
    assert!(grid.beam_cells(&beam).is_empty());
    assert!(grid.beam_t_ranges(&beam).is_empty());
    // A beam aimed at the sphere has cells, all of them with a non-empty cell function.
    let beam = Beam {
        origin: [iv(0.0, 0.0), iv(0.0, 0.0), iv(-4.0, -4.0)],
        dir: [iv(-0.05, 0.05), iv(-0.05, 0.05), iv(1.0, 1.0)],
    };
    let cells = grid.beam_cells(&beam);
    assert!(!cells.is_empty());
    let ranges = grid.beam_t_ranges(&beam);
    assert!(ranges[0].inf() <= 3.0, "{ranges:?}");
}

#[test]
fn one_large_leaf_is_pruned_per_cell() {
    // One formula of many `min`s (a union of spheres written as one leaf): the CSG
    // reduction cannot split it, the per-cell pruning does.
    let mut terms = Vec::new();
    for i in 0..12 {
        let c = -0.9 + 0.16 * i as f64;
        terms.push(format!("sqrt((x - {c})^2 + y^2 + z^2) - 0.1"));
    }
    let formula = terms
        .iter()
        .skip(1)
        .fold(terms[0].clone(), |acc, t| format!("min({acc}, {t})"));
    let scene = beam_trace::Scene::from_toml(
        &format!(
            "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
         [[surfaces]]\nformula = \"{formula}\"\nbounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n"
        ),
        "spheres.toml",
        None,
    )
    .unwrap();
    let grid = Grid::build(&scene.geometry, 25);
    let st = grid.stats();
    assert_eq!(st.reduced, 1, "{st:?}");
    assert!(st.functions > 1, "{st:?}");
    assert!(st.cell_instrs * 2 < st.full_instrs, "{st:?}");
}

#[test]
fn the_cells_leaf_candidates_find_the_same_leaf() {
    let mut rng = Rng::new(6);
    let mut narrowed = 0;
    for (name, g) in scenes() {
        let grid = Grid::build(&g, 6);
        let mut ev = g.evaluator();
        for c in all_cells(&grid) {
            if grid.cell_function(c).is_none() {
                continue;
            }
            for _ in 0..20 {
                let p = rng.in_box(&grid.cell_box(c));
                let Some(cands) = grid.leaf_candidates_at(p) else {
                    continue;
                };
                if cands.leaves.len() < g.leaves().len() {
                    narrowed += 1;
                }
                assert_eq!(ev.leaf_among(&cands, p), ev.leaf_at(p), "{name} {c:?} {p}");
            }
        }
    }
    assert!(narrowed > 0, "no cell narrowed the search");
}
