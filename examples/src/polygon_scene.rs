//! Polygonal test scenes for the exact soft shadows: procedural triangle meshes above a
//! floor lit by horizontal square lights, a bounding-volume hierarchy for the segment tests
//! of the stochastic baseline, and shaft culling of the occluders of a floor tile.
//!
//! The meshes stand in for the paper's scanned models, which cannot be fetched here: a
//! *lumpy ball* (a latitude-longitude sphere whose radius varies with a seeded sum of
//! sines, so that its silhouette has many small features) and a *canopy* of small leaf
//! triangles scattered over it, the kind of occluder set whose penumbrae overlap.

use beam_trace::shadow::Patch;
use glam::DVec3;

/// A triangle.
pub type Triangle = [DVec3; 3];

/// SplitMix64: seeded scenes and samples.
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The generator starting from `seed`.
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The next number, uniform in `[0, 1)`.
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// About `triangles` triangles: a lumpy ball of radius about 0.7 centred at height 1.4
/// (outward winding, closed), and (a tenth of the count) leaves above it, both from `seed`.
/// Returns the ball's triangles (closed, wound outward) and the leaves apart: a segment
/// from a light point through the ball enters it through a face that has that point in
/// front, so the ball's faces with every light point behind their plane need not be
/// occluders ([`facing`]).
pub fn lumpy_ball_and_canopy(triangles: usize, seed: u64) -> (Vec<Triangle>, Vec<Triangle>) {
    let mut rng = SplitMix64::new(seed);
    let leaves = triangles / 10;
    let ball = triangles - leaves;
    // rings · segments · 2 ≈ ball, with segments = 2 · rings.
    let rings = ((ball as f64 / 4.0).sqrt().round() as usize).max(3);
    let segments = 2 * rings;
    let waves: Vec<(f64, f64, f64, f64)> = (0..6)
        .map(|_| {
            (
                1.0 + 6.0 * rng.next_f64(),
                1.0 + 6.0 * rng.next_f64(),
                6.3 * rng.next_f64(),
                0.04 + 0.05 * rng.next_f64(),
            )
        })
        .collect();
    let centre = DVec3::new(0.0, 1.4, 0.0);
    // The bumps fade toward the poles (each pole is one point) and the seam reuses the
    // first meridian's vertices, so the mesh is closed.
    let point = |i: usize, j: usize| {
        let j = j % segments;
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        let phi = std::f64::consts::TAU * j as f64 / segments as f64;
        let bumps: f64 = waves
            .iter()
            .map(|&(a, b, p, h)| h * (a * theta + p).sin() * (b * phi).cos())
            .sum();
        let r = 0.7 + theta.sin() * bumps;
        if i == 0 || i == rings {
            return centre + DVec3::new(0.0, if i == 0 { r } else { -r }, 0.0);
        }
        centre
            + r * DVec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            )
    };
    let mut out = Vec::with_capacity(ball);
    for i in 0..rings {
        for j in 0..segments {
            let (a, b) = (point(i, j), point(i, j + 1));
            let (c, d) = (point(i + 1, j), point(i + 1, j + 1));
            if i > 0 {
                out.push([a, b, d]);
            }
            if i + 1 < rings {
                out.push([a, d, c]);
            }
        }
    }
    // Outward winding (the ball is star-shaped around its centre).
    let mid = out[out.len() / 2];
    let n = (mid[1] - mid[0]).cross(mid[2] - mid[0]);
    if n.dot(mid[0] - centre) < 0.0 {
        for t in &mut out {
            t.swap(1, 2);
        }
    }
    let mut canopy = Vec::with_capacity(leaves);
    for _ in 0..leaves {
        let c = DVec3::new(
            3.0 * rng.next_f64() - 1.5,
            2.3 + 0.6 * rng.next_f64(),
            3.0 * rng.next_f64() - 1.5,
        );
        let s = 0.05 + 0.1 * rng.next_f64();
        let mut corner = || {
            c + s * DVec3::new(
                rng.next_f64() - 0.5,
                0.4 * (rng.next_f64() - 0.5),
                rng.next_f64() - 0.5,
            )
        };
        canopy.push([corner(), corner(), corner()]);
    }
    (out, canopy)
}

/// A closed prism over the convex polygon `base` (points `(x, z)` in order, either way
/// round) from height `y0` to `y1`: its sides as quads cut in two, its caps as fans, every
/// triangle wound outward. Vertical sides and horizontal caps keep each face's corners on
/// one plane exactly (a side's upper corners are its lower ones raised), so a mesh's
/// coplanar neighbours can be merged into its faces again.
fn prism(base: &[(f64, f64)], y0: f64, y1: f64) -> Vec<Triangle> {
    let n = base.len();
    let at = |k: usize, y: f64| DVec3::new(base[k % n].0, y, base[k % n].1);
    let mut out = Vec::with_capacity(4 * n - 4);
    for k in 0..n {
        let (a, b) = (at(k, y0), at(k + 1, y0));
        let (c, d) = (at(k + 1, y1), at(k, y1));
        out.push([a, b, c]);
        out.push([a, c, d]);
    }
    for k in 1..n - 1 {
        out.push([at(0, y0), at(k + 1, y0), at(k, y0)]);
        out.push([at(0, y1), at(k, y1), at(k + 1, y1)]);
    }
    // Outward: each triangle's normal away from the prism's centre (it is convex).
    let centre = (0..n).map(|k| at(k, 0.5 * (y0 + y1))).sum::<DVec3>() / n as f64;
    for t in &mut out {
        let normal = (t[1] - t[0]).cross(t[2] - t[0]);
        if normal.dot((t[0] + t[1] + t[2]) / 3.0 - centre) < 0.0 {
            t.swap(1, 2);
        }
    }
    out
}

/// The map from a piece's own floor coordinates `(x, z)` to the hall's: turned by `angle`
/// about the vertical, then moved to `(cx, cz)`.
fn placed((cx, cz): (f64, f64), angle: f64) -> impl Fn((f64, f64)) -> (f64, f64) {
    let (s, c) = angle.sin_cos();
    move |(x, z)| (cx + c * x - s * z, cz + s * x + c * z)
}

/// The base of a box of half-sides `(hx, hz)` about `centre`, turned by `angle` about the
/// vertical.
fn rectangle(centre: (f64, f64), (hx, hz): (f64, f64), angle: f64) -> Vec<(f64, f64)> {
    [(-hx, -hz), (hx, -hz), (hx, hz), (-hx, hz)]
        .map(placed(centre, angle))
        .to_vec()
}

/// The base of a leg: a regular polygon of `sides` corners and radius `r` about `(cx, cz)`.
fn circle((cx, cz): (f64, f64), r: f64, sides: usize) -> Vec<(f64, f64)> {
    (0..sides)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / sides as f64;
            (cx + r * a.cos(), cz + r * a.sin())
        })
        .collect()
}

/// A furnished hall, about `triangles` triangles from `seed`: a grid of tables, each with
/// four chairs around it (2.1 apart, so that no two sets meet), every piece a closed prism
/// (box tops, seats and backs; legs turned as polygons of many sides), each table and chair
/// turned a little at random.
/// The architectural kind of model the paper renders (a conference room): large planar
/// faces, each triangulated, and many small parts. Returns the pieces' triangles and the
/// half-width of the square the hall's furniture stands in (centred on the origin).
///
/// A set (a table and its chairs) with legs of `n` sides is `80 n + 28` triangles; the
/// hall holds up to 100 sets, and beyond that the legs get more sides.
pub fn furnished_hall(triangles: usize, seed: u64) -> (Vec<Triangle>, f64) {
    let mut rng = SplitMix64::new(seed);
    let sets = (triangles / 1_300).clamp(1, 100);
    let sides = ((triangles / sets).saturating_sub(28) / 80).max(6);
    let per_row = (sets as f64).sqrt().ceil() as usize;
    let spacing = 2.1;
    let half = 0.5 * spacing * per_row as f64;
    let mut out = Vec::with_capacity(sets * (80 * sides + 28));
    let mut piece = |top: Vec<(f64, f64)>,
                     legs: &[(f64, f64)],
                     leg: (f64, f64),
                     back: Option<Vec<(f64, f64)>>| {
        // The parts a millimetre apart: touching parts would share no edge but meet, and
        // the mesh index judges only pieces proven closed and embedded.
        out.extend(prism(&top, leg.1, leg.1 + 0.04));
        for &p in legs {
            out.extend(prism(&circle(p, leg.0, sides), 0.0, leg.1 - 0.001));
        }
        if let Some(b) = back {
            out.extend(prism(&b, leg.1 + 0.041, leg.1 + 0.5));
        }
    };
    for k in 0..sets {
        let centre = (
            spacing * ((k % per_row) as f64 + 0.5) - half,
            spacing * ((k / per_row) as f64 + 0.5) - half,
        );
        let turn = 0.3 * (rng.next_f64() - 0.5);
        let place = placed(centre, turn);
        // The table: a top of 0.9 × 0.9 at 0.72, four legs.
        let corners = [(-0.38, -0.38), (0.38, -0.38), (0.38, 0.38), (-0.38, 0.38)];
        piece(
            rectangle(centre, (0.45, 0.45), turn),
            &corners.map(place),
            (0.03, 0.72),
            None,
        );
        // The chairs, one per side, facing the table, each turned a little more.
        for side in 0..4 {
            let a = turn + std::f64::consts::FRAC_PI_2 * side as f64 + 0.2 * (rng.next_f64() - 0.5);
            let at = placed(centre, a);
            let seat = at((0.0, 0.72));
            let legs = [(-0.17, 0.55), (0.17, 0.55), (0.17, 0.89), (-0.17, 0.89)].map(&at);
            piece(
                rectangle(seat, (0.21, 0.21), a),
                &legs,
                (0.02, 0.44),
                Some(rectangle(at((0.0, 0.9)), (0.2, 0.02), a)),
            );
        }
    }
    (out, half)
}

/// The triangles of a closed, outward-wound mesh that have some corner of `light` in front
/// of their plane (the others are redundant occluders, see [`lumpy_ball_and_canopy`]).
pub fn facing(tris: &[Triangle], light: &Patch) -> Vec<Triangle> {
    tris.iter()
        .copied()
        .filter(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]);
            light.corners().iter().any(|c| n.dot(*c - t[0]) > 0.0)
        })
        .collect()
}

/// An axis-aligned box.
#[derive(Copy, Clone, Debug)]
struct Aabb {
    lo: DVec3,
    hi: DVec3,
}

impl Aabb {
    fn of(t: &Triangle) -> Aabb {
        Aabb {
            lo: t[0].min(t[1]).min(t[2]),
            hi: t[0].max(t[1]).max(t[2]),
        }
    }

    fn join(self, o: Aabb) -> Aabb {
        Aabb {
            lo: self.lo.min(o.lo),
            hi: self.hi.max(o.hi),
        }
    }

    /// Whether the segment `a + s·d`, `s ∈ [0, 1]`, meets the box (slab test).
    fn meets(&self, a: DVec3, inv: DVec3) -> bool {
        let t0 = (self.lo - a) * inv;
        let t1 = (self.hi - a) * inv;
        let (tmin, tmax) = (t0.min(t1), t0.max(t1));
        let enter = tmin.max_element().max(0.0);
        let leave = tmax.min_element().min(1.0);
        enter <= leave
    }
}

/// A bounding-volume hierarchy over triangles (median splits, leaves of at most 4).
pub struct Bvh {
    tris: Vec<Triangle>,
    /// `(box, first, count)` for leaves (`count > 0`), `(box, left child, 0)` for inner
    /// nodes, whose right child follows the left subtree.
    nodes: Vec<(Aabb, usize, usize)>,
}

impl Bvh {
    /// The hierarchy of `tris`.
    pub fn new(mut tris: Vec<Triangle>) -> Bvh {
        let mut nodes = Vec::new();
        let n = tris.len();
        if n > 0 {
            build(&mut tris, 0, n, &mut nodes);
        }
        Bvh { tris, nodes }
    }

    /// Whether the open segment from `a` to `b` meets a triangle (floating point,
    /// Möller–Trumbore): the stochastic baseline's test.
    pub fn blocked(&self, a: DVec3, b: DVec3) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let d = b - a;
        let inv = DVec3::ONE / d;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let (bb, first, count) = self.nodes[i];
            if !bb.meets(a, inv) {
                continue;
            }
            if count > 0 {
                if self.tris[first..first + count]
                    .iter()
                    .any(|t| hits(a, d, t))
                {
                    return true;
                }
            } else {
                stack.push(first);
                stack.push(skip(&self.nodes, first));
            }
        }
        false
    }
}

/// The index after the subtree rooted at `i`.
fn skip(nodes: &[(Aabb, usize, usize)], i: usize) -> usize {
    let mut end = i + 1;
    let mut pending = if nodes[i].2 > 0 { 0 } else { 2 };
    while pending > 0 {
        pending -= 1;
        if nodes[end].2 == 0 {
            pending += 2;
        }
        end += 1;
    }
    end
}

fn build(tris: &mut [Triangle], first: usize, count: usize, nodes: &mut Vec<(Aabb, usize, usize)>) {
    let part = &mut tris[first..first + count];
    let bb = part
        .iter()
        .map(Aabb::of)
        .reduce(Aabb::join)
        .expect("nonempty");
    if count <= 4 {
        nodes.push((bb, first, count));
        return;
    }
    let axis = (bb.hi - bb.lo).max_position();
    part.sort_by(|p, q| {
        let c = |t: &Triangle| t[0][axis] + t[1][axis] + t[2][axis];
        c(p).total_cmp(&c(q))
    });
    let me = nodes.len();
    nodes.push((bb, me + 1, 0));
    let half = count / 2;
    build(tris, first, half, nodes);
    build(tris, first + half, count - half, nodes);
}

/// Möller–Trumbore on the open segment `a + s·d`, `s ∈ (0, 1)`.
fn hits(a: DVec3, d: DVec3, t: &Triangle) -> bool {
    let (e1, e2) = (t[1] - t[0], t[2] - t[0]);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return false;
    }
    let tv = a - t[0];
    let u = tv.dot(p) / det;
    let q = tv.cross(e1);
    let v = d.dot(q) / det;
    let s = e2.dot(q) / det;
    (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0 && s > 0.0 && s < 1.0
}

/// The triangles that may meet a segment from the floor rectangle `[x0, x1] × [z0, z1]`
/// (at `y = 0`) to the horizontal, axis-aligned square `light`: those not entirely outside
/// one face of the convex hull of the two rectangles (shaft culling).
pub fn shaft(
    tris: &[Triangle],
    x0: f64,
    x1: f64,
    z0: f64,
    z1: f64,
    light: &Patch,
) -> Vec<Vec<DVec3>> {
    let c = light.corners();
    let (lx0, lx1) = (
        c.iter().map(|p| p.x).fold(f64::INFINITY, f64::min),
        c.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max),
    );
    let (lz0, lz1) = (
        c.iter().map(|p| p.z).fold(f64::INFINITY, f64::min),
        c.iter().map(|p| p.z).fold(f64::NEG_INFINITY, f64::max),
    );
    let h = c[0].y;
    // Each face as (point, outward normal): floor, light, and the four sides through
    // corresponding edges of the two parallel rectangles.
    let side = |p0: DVec3, p1: DVec3, q0: DVec3, inward: DVec3| {
        let mut n = (p1 - p0).cross(q0 - p0);
        if n.dot(inward) > 0.0 {
            n = -n;
        }
        (p0, n)
    };
    let mid = DVec3::new(
        (x0 + x1 + lx0 + lx1) / 4.0,
        h / 2.0,
        (z0 + z1 + lz0 + lz1) / 4.0,
    );
    let faces = [
        (DVec3::ZERO, -DVec3::Y),
        (DVec3::new(0.0, h, 0.0), DVec3::Y),
        side(
            DVec3::new(x0, 0.0, z0),
            DVec3::new(x0, 0.0, z1),
            DVec3::new(lx0, h, z0.min(lz0)),
            mid - DVec3::new(x0, 0.0, z0),
        ),
        side(
            DVec3::new(x1, 0.0, z0),
            DVec3::new(x1, 0.0, z1),
            DVec3::new(lx1, h, z0.min(lz0)),
            mid - DVec3::new(x1, 0.0, z0),
        ),
        side(
            DVec3::new(x0, 0.0, z0),
            DVec3::new(x1, 0.0, z0),
            DVec3::new(x0.min(lx0), h, lz0),
            mid - DVec3::new(x0, 0.0, z0),
        ),
        side(
            DVec3::new(x0, 0.0, z1),
            DVec3::new(x1, 0.0, z1),
            DVec3::new(x0.min(lx0), h, lz1),
            mid - DVec3::new(x0, 0.0, z1),
        ),
    ];
    tris.iter()
        .filter(|t| {
            !faces
                .iter()
                .any(|&(p, n)| t.iter().all(|v| (*v - p).dot(n) > 0.0))
        })
        .map(|t| t.to_vec())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use beam_trace::shadow::exact::{ExactShadows, Plane};

    /// The hall's pieces are closed, wound outward and apart from each other (every
    /// triangle faces out of its solid), about as many triangles as asked, and its faces
    /// merge: the boxes' quads and the legs' caps and sides, fewer than half the triangles.
    #[test]
    fn the_hall_is_closed_pieces_whose_faces_merge() {
        for asked in [3_000, 40_000] {
            let (hall, half) = furnished_hall(asked, 5);
            let tris: Vec<beam_trace::mesh::Triangle> = hall
                .iter()
                .map(|&[a, b, c]| beam_trace::mesh::Triangle::new(a, b, c))
                .collect();
            assert!(
                tris.len() as f64 > 0.8 * asked as f64 && (tris.len() as f64) < 1.2 * asked as f64,
                "{} triangles for {asked}",
                tris.len()
            );
            let f = beam_trace::mesh::facing(&tris);
            let out = f.iter().filter(|&&x| x == 1).count();
            assert_eq!(out, f.len(), "triangles facing out of a closed piece");
            assert!(
                hall.iter()
                    .flatten()
                    .all(|p| p.x.abs() <= half && p.z.abs() <= half)
            );
            let faces = beam_trace::mesh::faces(&tris, &vec![0; tris.len()]);
            assert!(2 * faces.len() < tris.len(), "{} faces", faces.len());
        }
    }

    /// The ball is closed: dropping the faces turned away from the light changes no exact
    /// visible fraction, and every edge is shared by exactly two triangles.
    #[test]
    fn the_ball_is_closed_and_its_back_faces_are_redundant() {
        let (ball, canopy) = lumpy_ball_and_canopy(400, 3);
        let mut edges = std::collections::HashMap::new();
        for t in &ball {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let key = |p: DVec3| p.to_array().map(f64::to_bits);
                let e = if key(a) < key(b) {
                    (key(a), key(b))
                } else {
                    (key(b), key(a))
                };
                *edges.entry(e).or_insert(0) += 1;
            }
        }
        assert!(
            edges.values().all(|&n| n == 2),
            "an edge not shared by two triangles"
        );
        let light = Patch::square(DVec3::new(0.3, 4.0, -0.2), 1.5, 1);
        let floor = Plane {
            point: DVec3::ZERO,
            normal: DVec3::Y,
        };
        let poly = |v: &[Triangle]| v.iter().map(|t| t.to_vec()).collect::<Vec<_>>();
        let mut all = poly(&ball);
        all.extend(poly(&canopy));
        let mut front = poly(&facing(&ball, &light));
        assert!(front.len() < ball.len());
        front.extend(poly(&canopy));
        let mut a = ExactShadows::new(light, floor, &all, 1).unwrap();
        let mut f = ExactShadows::new(light, floor, &front, 1).unwrap();
        for i in 0..12 {
            let x = DVec3::new(-1.0 + 0.18 * f64::from(i), 0.0, 0.3 - 0.07 * f64::from(i));
            let (va, vf) = (
                a.visible_fraction(x, None).unwrap(),
                f.visible_fraction(x, None).unwrap(),
            );
            assert!(
                (va - vf).abs() < 1e-9,
                "at {x}: {va} with every face, {vf} with the front ones"
            );
        }
    }
}
