//! How many parts of an area light a certified soft shadow must decide, in an idealised
//! setting: the shadow an occluder casts on the light (seen from the shaded point) is a
//! disc, and every part is decided exactly (free when it misses the disc, blocked when the
//! disc holds it, open otherwise), as a perfectly tight beam would decide it.
//!
//! Two ways of splitting the unit light square until the open area is at most the
//! tolerance are counted side by side:
//!
//! * the **quadtree** of `certified:TOL` (`beam_trace::shadow::certified`): the largest open
//!   squares split into four, in rounds of as many as should close the gap
//!   ([`parts_to_split`], [`DECIDED_SHARE`](beam_trace::shadow::certified::DECIDED_SHARE));
//! * **parts that follow the edge**: the quadtree down to squares of a quarter of the light,
//!   then each open square cut into columns whose slanted sides run along the shadow's edge
//!   (its direction at the column's middle, known exactly here), each column bisected across
//!   the edge until the open band is at most `TOL / L` tall for an edge `L` sides long, and
//!   halved where the edge's curvature leaves more than two such bands open. The renderer's
//!   beams cannot do this yet (a beam covers its part by a box of directions); the count
//!   says what they would save.
//!
//! ```text
//! cargo run --release -p examples --bin light-parts
//! cargo run --release -p examples --bin light-parts -- --tolerance 0.1
//! ```

use beam_trace::shadow::certified::parts_to_split;
use clap::Parser;
use glam::{DVec2, Vec2Swizzles};

/// Counts the parts that decide a disc-shaped shadow on a square light to a tolerance.
#[derive(Parser, Debug)]
#[command(name = "light-parts")]
struct Args {
    /// Width of the bound on the visible fraction at which the splitting stops.
    #[arg(long, default_value_t = 0.05)]
    tolerance: f64,
}

/// The shadow on the light: a disc in the light's parameter square `[0, 1]²`.
#[derive(Copy, Clone, Debug)]
struct Disc {
    centre: DVec2,
    radius: f64,
}

/// What an exact test says of a part.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Class {
    /// The part misses the disc: visible.
    Free,
    /// The disc holds the part: hidden.
    Blocked,
    /// The part holds points of both.
    Open,
}

impl Disc {
    /// The disc with the axes swapped (for columns that run along `v`).
    fn transposed(self) -> Disc {
        Disc {
            centre: self.centre.yx(),
            radius: self.radius,
        }
    }

    /// The class of the convex polygon `poly`.
    fn classify(&self, poly: &[DVec2]) -> Class {
        let r2 = self.radius * self.radius;
        if poly.iter().all(|p| p.distance_squared(self.centre) <= r2) {
            return Class::Blocked;
        }
        if contains(poly, self.centre) {
            return Class::Open;
        }
        let n = poly.len();
        let nearest = (0..n)
            .map(|k| segment_distance(poly[k], poly[(k + 1) % n], self.centre))
            .fold(f64::INFINITY, f64::min);
        if nearest >= self.radius {
            Class::Free
        } else {
            Class::Open
        }
    }

    /// Points sampled on the edge (the circle).
    const EDGE_SAMPLES: u32 = 4096;

    /// Points of the edge (the circle), [`Disc::EDGE_SAMPLES`] of them.
    fn edge_points(&self) -> impl Iterator<Item = DVec2> + '_ {
        (0..Self::EDGE_SAMPLES).map(move |k| {
            let a = std::f64::consts::TAU * f64::from(k) / f64::from(Self::EDGE_SAMPLES);
            self.centre + self.radius * DVec2::new(a.cos(), a.sin())
        })
    }

    /// The edge's length inside the light, in sides of the light (from the sampled edge).
    fn edge_length(&self) -> f64 {
        let inside = self
            .edge_points()
            .filter(|p| p.cmpge(DVec2::ZERO).all() && p.cmple(DVec2::ONE).all())
            .count();
        std::f64::consts::TAU * self.radius * inside as f64 / f64::from(Self::EDGE_SAMPLES)
    }

    /// The point of the edge in `[u0, u1] × [v0, v1]` nearest the column's middle `u`, if
    /// any.
    fn edge_point_in(&self, (u0, u1): (f64, f64), (v0, v1): (f64, f64)) -> Option<DVec2> {
        let middle = 0.5 * (u0 + u1);
        self.edge_points()
            .filter(|p| (u0..=u1).contains(&p.x) && (v0..=v1).contains(&p.y))
            .min_by(|a, b| (a.x - middle).abs().total_cmp(&(b.x - middle).abs()))
    }
}

/// Whether the convex polygon `poly` holds `p`.
fn contains(poly: &[DVec2], p: DVec2) -> bool {
    let n = poly.len();
    let side = |k: usize| (poly[(k + 1) % n] - poly[k]).perp_dot(p - poly[k]);
    (0..n).all(|k| side(k) >= 0.0) || (0..n).all(|k| side(k) <= 0.0)
}

/// The distance from `p` to the segment `a b`.
fn segment_distance(a: DVec2, b: DVec2, p: DVec2) -> f64 {
    let d = b - a;
    let t = if d == DVec2::ZERO {
        0.0
    } else {
        ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
    };
    (a + t * d).distance(p)
}

/// The area of the polygon `poly`.
fn area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    0.5 * (0..n)
        .map(|k| poly[k].perp_dot(poly[(k + 1) % n]))
        .sum::<f64>()
        .abs()
}

/// `poly` clipped to `v0 ≤ y ≤ v1` (Sutherland–Hodgman, one side at a time).
fn clip_rows(poly: &[DVec2], v0: f64, v1: f64) -> Vec<DVec2> {
    let keep_above = |poly: &[DVec2], v: f64, sign: f64| -> Vec<DVec2> {
        let n = poly.len();
        let mut out = Vec::with_capacity(n + 2);
        for k in 0..n {
            let (p, q) = (poly[k], poly[(k + 1) % n]);
            let (p_in, q_in) = (sign * (p.y - v) >= 0.0, sign * (q.y - v) >= 0.0);
            if p_in {
                out.push(p);
            }
            if p_in != q_in {
                out.push(p + (q - p) * ((v - p.y) / (q.y - p.y)));
            }
        }
        out
    };
    keep_above(&keep_above(poly, v0, 1.0), v1, -1.0)
}

/// The square part `[i, i + 1] × [j, j + 1]` scaled by `2^-level`.
#[derive(Copy, Clone, Debug)]
struct Square {
    level: u32,
    i: u32,
    j: u32,
}

impl Square {
    fn side(&self) -> f64 {
        0.5f64.powi(self.level as i32)
    }

    fn low(&self) -> DVec2 {
        DVec2::new(f64::from(self.i), f64::from(self.j)) * self.side()
    }

    fn corners(&self) -> [DVec2; 4] {
        let (p, s) = (self.low(), self.side());
        [p, p + DVec2::X * s, p + DVec2::splat(s), p + DVec2::Y * s]
    }

    fn quadrants(&self) -> [Square; 4] {
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(di, dj)| Square {
            level: self.level + 1,
            i: 2 * self.i + di,
            j: 2 * self.j + dj,
        })
    }
}

/// What a splitting decided: parts tested, and the areas proven visible, proven hidden and
/// left open.
#[derive(Copy, Clone, Debug, Default)]
struct Tally {
    parts: u32,
    free: f64,
    blocked: f64,
    open: f64,
}

impl Tally {
    /// Records one tested part of area `a`.
    fn add(&mut self, class: Class, a: f64) {
        self.parts += 1;
        match class {
            Class::Free => self.free += a,
            Class::Blocked => self.blocked += a,
            Class::Open => self.open += a,
        }
    }

    fn merge(&mut self, other: Tally) {
        self.parts += other.parts;
        self.free += other.free;
        self.blocked += other.blocked;
        self.open += other.open;
    }

    /// The bound's width: the area neither proven visible nor proven hidden.
    fn width(&self) -> f64 {
        (1.0 - self.free - self.blocked).max(0.0)
    }
}

/// Tests `squares` into `tally` (counting each, adding the decided areas) and returns the
/// open ones.
fn test_squares(disc: &Disc, squares: &[Square], tally: &mut Tally) -> Vec<Square> {
    let mut open = Vec::new();
    for s in squares {
        match disc.classify(&s.corners()) {
            Class::Open => {
                tally.parts += 1;
                open.push(*s);
            }
            class => tally.add(class, s.side() * s.side()),
        }
    }
    open
}

/// The whole light.
const WHOLE: Square = Square {
    level: 0,
    i: 0,
    j: 0,
};

/// The quadtree of `certified:TOL`: rounds splitting the largest open squares, as many as
/// [`parts_to_split`] says.
fn quadtree(disc: &Disc, tolerance: f64) -> Tally {
    let mut tally = Tally::default();
    let mut open: Vec<Square> = Vec::new();
    let mut asked = vec![WHOLE];
    loop {
        open.extend(test_squares(disc, &asked, &mut tally));
        let split = parts_to_split(
            open.iter().map(|s| s.level),
            tally.width() - tolerance,
            usize::MAX,
        );
        if split == 0 {
            tally.open = open.iter().map(|s| s.side() * s.side()).sum();
            return tally;
        }
        asked = open.drain(..split).flat_map(|s| s.quadrants()).collect();
    }
}

/// Level of the squares the edge-following splitting starts from.
const COARSE_LEVEL: u32 = 2;

/// Narrowest column: below it an open column is left as it is.
const MIN_COLUMN: f64 = 1e-3;

/// The edge-following splitting (see the module documentation), with open bands at most
/// `band` tall.
fn edge_following(disc: &Disc, band: f64) -> Tally {
    let mut tally = Tally::default();
    let mut open = test_squares(disc, &[WHOLE], &mut tally);
    for _ in 0..COARSE_LEVEL {
        let quadrants: Vec<Square> = open.iter().flat_map(Square::quadrants).collect();
        open = test_squares(disc, &quadrants, &mut tally);
    }
    for s in open {
        // Columns across the edge's direction at the square's middle: along `u` where the
        // edge runs closer to `u`, else along `v` (the same with the axes swapped).
        let middle = s.low() + DVec2::splat(0.5 * s.side());
        let normal = middle - disc.centre;
        let (local, low) = if normal.y.abs() >= normal.x.abs() {
            (*disc, s.low())
        } else {
            (disc.transposed(), s.low().yx())
        };
        let rows = (low.y, low.y + s.side());
        let mut columns = vec![(low.x, low.x + s.side())];
        while let Some(cols) = columns.pop() {
            let (t, halve) = sheared_bands(&local, cols, rows, band);
            if halve {
                // The bands tested before the column was given up still count.
                tally.parts += t.parts;
                let m = 0.5 * (cols.0 + cols.1);
                columns.extend([(cols.0, m), (m, cols.1)]);
            } else {
                tally.merge(t);
            }
        }
    }
    tally
}

/// The column `cols × rows` cut into bands along the edge, and whether to halve it instead
/// (more than two bands' worth left open: the edge bends out of one band).
fn sheared_bands(
    disc: &Disc,
    (u0, u1): (f64, f64),
    (v0, v1): (f64, f64),
    band: f64,
) -> (Tally, bool) {
    let mut tally = Tally::default();
    let whole = [
        DVec2::new(u0, v0),
        DVec2::new(u1, v0),
        DVec2::new(u1, v1),
        DVec2::new(u0, v1),
    ];
    let Some(p) = disc.edge_point_in((u0, u1), (v0, v1)) else {
        // The edge does not cross the column's interior: one part decides it, unless the
        // sampled edge slipped between the column's sides.
        let class = disc.classify(&whole);
        tally.add(class, area(&whole));
        return (tally, class == Class::Open && u1 - u0 > MIN_COLUMN);
    };
    let tangent = (p - disc.centre).perp();
    let slope = if tangent.x.abs() > 1e-12 {
        tangent.y / tangent.x
    } else {
        0.0
    };
    let middle = 0.5 * (u0 + u1);
    let rise = slope.abs() * 0.5 * (u1 - u0);
    // The band `a ≤ v − slope·(u − middle) ≤ b` of the column, clipped to its rows.
    let band_poly = |a: f64, b: f64| {
        let at = |u: f64, c: f64| DVec2::new(u, c + slope * (u - middle));
        clip_rows(&[at(u0, a), at(u1, a), at(u1, b), at(u0, b)], v0, v1)
    };
    let mut stack = vec![(v0 - rise, v1 + rise)];
    while let Some((a, b)) = stack.pop() {
        let poly = band_poly(a, b);
        let part_area = if poly.len() < 3 { 0.0 } else { area(&poly) };
        if part_area == 0.0 {
            continue;
        }
        let class = disc.classify(&poly);
        if class == Class::Open && b - a > band {
            tally.parts += 1;
            let m = 0.5 * (a + b);
            stack.extend([(a, m), (m, b)]);
        } else {
            tally.add(class, part_area);
        }
    }
    let halve = tally.open > 2.0 * band * (u1 - u0) && u1 - u0 > MIN_COLUMN;
    (tally, halve)
}

/// The edge-following splitting with the band height `TOL / L` shrunk until the bound is
/// within the tolerance (the bands along a curved edge overlap it).
fn edge_following_to(disc: &Disc, tolerance: f64) -> Tally {
    let mut band = tolerance / disc.edge_length().max(tolerance);
    loop {
        let t = edge_following(disc, band);
        if t.width() <= tolerance || band < 1e-6 {
            return t;
        }
        band /= 1.1;
    }
}

/// Shadows of several sizes and places: closed ones inside the light and edges that cross
/// it.
const DISCS: [(f64, f64, f64); 10] = [
    (0.5, 0.5, 0.35),
    (0.5, 0.5, 0.5),
    (0.5, 0.5, 0.7),
    (1.4, 0.5, 1.0),
    (1.2, 0.3, 1.0),
    (0.5, -0.3, 0.8),
    (1.8, 0.9, 1.5),
    (0.9, 0.4, 0.6),
    (2.3, 0.5, 2.0),
    (0.7, 1.6, 1.0),
];

fn main() {
    let args = Args::parse();
    println!(
        "Parts tested to bound the visible fraction within {} (exact tests, disc-shaped shadow on the unit light square)\n",
        args.tolerance
    );
    println!(
        "| shadow disc (centre; radius) | edge (light sides) | quadtree parts | width | edge-following parts | width | quadtree / edge-following |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|");
    for (x, y, radius) in DISCS {
        let disc = Disc {
            centre: DVec2::new(x, y),
            radius,
        };
        let q = quadtree(&disc, args.tolerance);
        let e = edge_following_to(&disc, args.tolerance);
        println!(
            "| ({x}, {y}); {radius} | {:.2} | {} | {:.3} | {} | {:.3} | {:.1} |",
            disc.edge_length(),
            q.parts,
            q.width(),
            e.parts,
            e.width(),
            f64::from(q.parts) / f64::from(e.parts)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The share of the light the disc hides, on a fine grid of cell centres.
    fn hidden(disc: &Disc) -> f64 {
        let n = 600;
        let mut inside = 0u32;
        for i in 0..n {
            for j in 0..n {
                let p = (DVec2::new(f64::from(i), f64::from(j)) + 0.5) / f64::from(n);
                inside += u32::from(p.distance(disc.centre) < disc.radius);
            }
        }
        f64::from(inside) / f64::from(n * n)
    }

    #[test]
    fn classes_hold_for_points_of_the_part() {
        let disc = Disc {
            centre: DVec2::new(0.4, 0.55),
            radius: 0.3,
        };
        for level in 1..5 {
            for i in 0..(1 << level) {
                for j in 0..(1 << level) {
                    let s = Square { level, i, j };
                    let class = disc.classify(&s.corners());
                    for k in 0..=8 {
                        for l in 0..=8 {
                            let p =
                                s.low() + DVec2::new(f64::from(k), f64::from(l)) / 8.0 * s.side();
                            let inside = p.distance(disc.centre) < disc.radius;
                            assert!(
                                !(class == Class::Free && inside
                                    || class == Class::Blocked && !inside),
                                "{s:?} {class:?} {p}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// Both splittings account for the whole light, meet the tolerance, and bound the
    /// visible share.
    #[test]
    fn splittings_bound_the_visible_share() {
        for (x, y, radius) in DISCS {
            let disc = Disc {
                centre: DVec2::new(x, y),
                radius,
            };
            let visible = 1.0 - hidden(&disc);
            for t in [quadtree(&disc, 0.05), edge_following_to(&disc, 0.05)] {
                assert!(t.width() <= 0.05, "{disc:?} {t:?}");
                assert!(
                    (t.free + t.blocked + t.open - 1.0).abs() < 1e-9,
                    "{disc:?} {t:?}"
                );
                assert!(
                    t.free - 2e-3 <= visible && visible <= 1.0 - t.blocked + 2e-3,
                    "{disc:?} {t:?} {visible}"
                );
            }
        }
    }
}
