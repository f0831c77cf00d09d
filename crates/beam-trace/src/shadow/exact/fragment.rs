//! Fragments of the light: convex polygons of its parameter square `(u, v) ∈ [0, 1]²`, split
//! by the affine functions `s(u, v) = c0 + cu·u + cv·v` that the query plane through the
//! shaded point and an occluder edge defines (zero on that plane). The map from `(u, v)` to
//! the light is affine, so a fragment's area in the square is its share of the light.

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
    pub fn side(&self, s: &Affine) -> Side {
        let (mut pos, mut neg) = (false, false);
        for &p in &self.verts {
            let v = s.at(p);
            pos |= v > 0.0;
            neg |= v < 0.0;
        }
        match (pos, neg) {
            (true, false) => Side::Pos,
            (false, true) => Side::Neg,
            (false, false) => Side::On,
            (true, true) => Side::Both,
        }
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

    /// Whether nothing is left.
    pub fn is_empty(&self) -> bool {
        self.verts.len() < 3
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
