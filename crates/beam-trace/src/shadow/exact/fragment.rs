//! Fragments of the light: convex polygons of its parameter square `(u, v) ∈ [0, 1]²`, split
//! by the affine functions `s(u, v) = c0 + cu·u + cv·v` that the query plane through the
//! shaded point and an occluder edge defines (zero on that plane). The map from `(u, v)` to
//! the light is affine, so a fragment's area in the square is its share of the light.
//!
//! The functions are computed in floating point, and so are the vertices where a fragment
//! is cut; [`Fragment::misplaced`] bounds the area that this may put on the wrong side of a
//! cut, so that the sum of the visible fragments' areas comes with a proven error bound.

/// The unit roundoff of `f64`.
pub(super) const UNIT: f64 = f64::EPSILON / 2.0;

/// How far rounding may move the computed value of an affine function `s` at a vertex of a
/// fragment, as a multiple of `UNIT · (|c0| + |cu| + |cv|)`: the evaluation at a vertex
/// (three roundings of terms at most that large, the vertices lying in the square up to
/// rounding) and the vertices [`Fragment::clip`] computes on `s = 0` (an error of about
/// `12 UNIT` of that magnitude: the two evaluations, the quotient and the coordinates'
/// rounding). The margin over those counts is deliberate.
const SLOP: f64 = 64.0;

/// `s(u, v) = c0 + cu·u + cv·v`.
#[derive(Copy, Clone, Debug)]
pub(super) struct Affine {
    pub c0: f64,
    pub cu: f64,
    pub cv: f64,
}

impl Affine {
    fn at(&self, p: [f64; 2]) -> f64 {
        self.c0 + self.cu * p[0] + self.cv * p[1]
    }

    /// `|c0| + |cu| + |cv|`: the largest `|s|` on the square.
    fn magnitude(&self) -> f64 {
        self.c0.abs() + self.cu.abs() + self.cv.abs()
    }
}

/// Where a fragment lies against `s = 0`.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// `s ≥ 0` everywhere, `> 0` somewhere.
    Pos,
    /// `s ≤ 0` everywhere, `< 0` somewhere.
    Neg,
    /// `s = 0` everywhere (the point lies on the edge's line).
    On,
    /// Both signs.
    Both,
}

/// A convex polygon of the parameter square, counterclockwise.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Fragment {
    pub verts: Vec<[f64; 2]>,
}

impl Fragment {
    /// The whole light.
    pub fn whole() -> Fragment {
        Fragment {
            verts: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        }
    }

    /// The area (the share of the light).
    pub fn area(&self) -> f64 {
        let n = self.verts.len();
        let twice: f64 = (0..n)
            .map(|i| {
                let (p, q) = (self.verts[i], self.verts[(i + 1) % n]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum();
        0.5 * twice.abs()
    }

    /// Where the fragment lies against `s = 0`, from the signs at its vertices (the
    /// fragment is convex and `s` affine).
    #[cfg(test)]
    pub fn side(&self, s: &Affine) -> Side {
        self.side_and_misplaced(s, 0.0).0
    }

    /// The parts with `s ≥ 0` and `s ≤ 0` (either may be empty: fewer than 3 vertices).
    pub fn split(&self, s: &Affine) -> (Fragment, Fragment) {
        (self.clip(s, 1.0), self.clip(s, -1.0))
    }

    /// The part where `sign · s ≥ 0` (Sutherland–Hodgman on one half-plane).
    pub fn clip(&self, s: &Affine, sign: f64) -> Fragment {
        let n = self.verts.len();
        let mut out = Vec::with_capacity(n + 1);
        for i in 0..n {
            let (p, q) = (self.verts[i], self.verts[(i + 1) % n]);
            let (sp, sq) = (sign * s.at(p), sign * s.at(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
                let t = sp / (sp - sq);
                out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
        }
        if out.len() < 3 {
            out.clear();
        }
        Fragment { verts: out }
    }

    /// The smallest rectangle of parameters holding the fragment: its lower and upper
    /// corners.
    pub fn bounds(&self) -> ([f64; 2], [f64; 2]) {
        self.verts.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), p| {
                (
                    [lo[0].min(p[0]), lo[1].min(p[1])],
                    [hi[0].max(p[0]), hi[1].max(p[1])],
                )
            },
        )
    }

    /// Whether nothing is left.
    pub fn is_empty(&self) -> bool {
        self.verts.len() < 3
    }

    /// A bound on the rounding error of [`Fragment::area`]: the shoelace sum's `n + 2`
    /// roundings of terms no larger than their absolute sum, with a margin.
    pub fn area_error(&self) -> f64 {
        let n = self.verts.len();
        let terms: f64 = (0..n)
            .map(|i| {
                let (p, q) = (self.verts[i], self.verts[(i + 1) % n]);
                (p[0] * q[1]).abs() + (q[0] * p[1]).abs()
            })
            .sum();
        2.0 * (n as f64 + 3.0) * UNIT * terms
    }

    /// A bound on the area of this fragment whose side of the cut `s` a computed split may
    /// get wrong, where the true function differs from `s` by at most `error` on the
    /// square: the part of the fragment where `|s| ≤ error` plus the rounding of the
    /// computed values ([`SLOP`]). Zero where every vertex lies beyond that band on one
    /// side (the fragment is convex and `s` affine, so all of it does); otherwise the
    /// smaller of the fragment's area and the band's (its width `2 e / |∇s|` times the
    /// fragment's diameter), with margins for their own rounding.
    ///
    /// A point of the light that a query puts in the wrong leaf is put on the wrong side
    /// of some cut it meets on its way, inside the fragment it lies in there and inside
    /// that cut's band: the sum of this bound over every fragment and every node a query
    /// visits bounds the area it misplaces.
    pub fn misplaced(&self, s: &Affine, error: f64) -> f64 {
        self.side_and_misplaced(s, error).1
    }

    /// [`Fragment::side`] and [`Fragment::misplaced`] in one pass over the vertices.
    pub fn side_and_misplaced(&self, s: &Affine, error: f64) -> (Side, f64) {
        let e = error + SLOP * UNIT * s.magnitude();
        let (mut pos, mut neg) = (false, false);
        let (mut above, mut below) = (true, true);
        for &p in &self.verts {
            let v = s.at(p);
            pos |= v > 0.0;
            neg |= v < 0.0;
            above &= v > e;
            below &= v < -e;
        }
        let side = match (pos, neg) {
            (true, false) => Side::Pos,
            (false, true) => Side::Neg,
            (false, false) => Side::On,
            (true, true) => Side::Both,
        };
        if above || below {
            return (side, 0.0);
        }
        (side, self.band_area(s, e))
    }

    /// A bound on the area of the fragment where `|s| ≤ e`.
    fn band_area(&self, s: &Affine, e: f64) -> f64 {
        let whole = || (self.area() + self.area_error()) * (1.0 + 1e-12);
        let gradient = s.cu.hypot(s.cv) * (1.0 - 1e-12);
        if gradient <= 0.0 {
            return whole();
        }
        let (lo, hi) = self.bounds();
        let diameter = (hi[0] - lo[0]).hypot(hi[1] - lo[1]) * (1.0 + 1e-12);
        let band = 2.0 * e / gradient * diameter * (1.0 + 1e-12);
        // A thin band (the usual case) needs no area to compare with.
        if band < 1e-9 { band } else { band.min(whole()) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_keep_the_area() {
        let f = Fragment::whole();
        assert_eq!(f.area(), 1.0);
        // u + v = 1: two triangles of area 1/2.
        let s = Affine {
            c0: -1.0,
            cu: 1.0,
            cv: 1.0,
        };
        assert_eq!(f.side(&s), Side::Both);
        let (p, n) = f.split(&s);
        assert!((p.area() - 0.5).abs() < 1e-15 && (n.area() - 0.5).abs() < 1e-15);
        assert_eq!(p.side(&s), Side::Pos);
        assert_eq!(n.side(&s), Side::Neg);
        // A line outside the square.
        let far = Affine {
            c0: 3.0,
            cu: 1.0,
            cv: 0.0,
        };
        assert_eq!(f.side(&far), Side::Pos);
        assert!(f.clip(&far, -1.0).is_empty());
    }
}
