//! One triangle, and what a ray or a box proves about it in outward-rounded interval
//! arithmetic.

use glam::DVec3;
use interval_core::Interval;

use crate::ibox::{IBox, disjoint, hull, ipoint};
use crate::ray::Beam;

/// A triangle of a mesh, by its three vertices (in world coordinates).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Triangle {
    /// The vertices; their order gives the geometric normal `(v1 − v0) × (v2 − v0)`.
    pub v: [DVec3; 3],
}

/// Where a ray crosses a triangle, as far as outward-rounded arithmetic proves it.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Crossing {
    /// An enclosure of the ray parameter of the crossing.
    pub t: Interval<f64>,
    /// `true`: the ray is proven to cross the triangle at a parameter in `t`; `false`: it
    /// may (it passes within rounding of an edge or of the triangle's plane), and no
    /// crossing lies outside `t`.
    pub proven: bool,
}

/// An interval vector.
type IVec = [Interval<f64>; 3];

fn ivec(p: DVec3) -> IVec {
    [ipoint(p.x), ipoint(p.y), ipoint(p.z)]
}

fn sub(a: &IVec, b: &IVec) -> IVec {
    std::array::from_fn(|i| a[i].sub(b[i]))
}

// The products by IEEE 1788's sign cases: the same intervals as `mul`'s eight corner
// products (up to the sign of a zero bound, which no test here reads) from two directed
// products in most cases.
#[inline(always)]
fn mul(a: Interval<f64>, b: Interval<f64>) -> Interval<f64> {
    a.mul_sign_cases(b)
}

fn dot(a: &IVec, b: &IVec) -> Interval<f64> {
    mul(a[0], b[0]).add(mul(a[1], b[1])).add(mul(a[2], b[2]))
}

fn cross(a: &IVec, b: &IVec) -> IVec {
    [
        mul(a[1], b[2]).sub(mul(a[2], b[1])),
        mul(a[2], b[0]).sub(mul(a[0], b[2])),
        mul(a[0], b[1]).sub(mul(a[1], b[0])),
    ]
}

/// The sign an interval proves: `Some(true)` positive, `Some(false)` negative, `None`
/// where it holds zero (or is NaN).
fn sign(x: Interval<f64>) -> Option<bool> {
    if x.is_empty() {
        None
    } else if x.inf() > 0.0 {
        Some(true)
    } else if x.sup() < 0.0 {
        Some(false)
    } else {
        None
    }
}

/// The box of the triangles' vertices (`None` for no triangle).
pub fn bounds_of(triangles: &[Triangle]) -> Option<IBox> {
    triangles
        .iter()
        .map(Triangle::bounds)
        .reduce(|a, b| hull(&a, &b))
}

impl Triangle {
    /// The triangle `a, b, c`.
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> Self {
        Self { v: [a, b, c] }
    }

    /// The unit geometric normal `(v1 − v0) × (v2 − v0)` normalised (zero for a degenerate
    /// triangle).
    pub fn normal(&self) -> DVec3 {
        (self.v[1] - self.v[0])
            .cross(self.v[2] - self.v[0])
            .normalize_or_zero()
    }

    /// Whether the three vertices lie on one line, proven: every component of the cross
    /// product `(v1 − v0) × (v2 − v0)`, enclosed in outward-rounded interval arithmetic, is
    /// exactly zero. Such a triangle has no area and meets no ray in a set of positive
    /// measure; a tiny triangle whose products underflow keeps a non-zero bound and is not
    /// called degenerate.
    pub fn is_degenerate(&self) -> bool {
        self.interval_normal()
            .iter()
            .all(|c| c.inf() == 0.0 && c.sup() == 0.0)
    }

    /// The normal `(v1 − v0) × (v2 − v0)` enclosed in interval arithmetic.
    fn interval_normal(&self) -> IVec {
        let v0 = ivec(self.v[0]);
        cross(&sub(&ivec(self.v[1]), &v0), &sub(&ivec(self.v[2]), &v0))
    }

    /// The side of the triangle's plane that all the `points` lie on, proven: `Some(true)`
    /// where `(p − v0) · ((v1 − v0) × (v2 − v0)) > 0` for every point `p` (in front of the
    /// winding's normal), `Some(false)` where it is negative for every one, `None`
    /// otherwise (an enclosure holds zero, or the points lie on both sides).
    pub fn side_of_all(&self, points: &[DVec3]) -> Option<bool> {
        let (v0, n) = (ivec(self.v[0]), self.interval_normal());
        let mut sides = points.iter().map(|&p| sign(dot(&sub(&ivec(p), &v0), &n)));
        let first = sides.next()??;
        sides.all(|s| s == Some(first)).then_some(first)
    }

    /// Six times the signed volume of the tetrahedron of `o` and the triangle,
    /// `(v0 − o) · ((v1 − o) × (v2 − o))`, enclosed.
    pub fn signed_volume(&self, o: DVec3) -> Interval<f64> {
        let o = ivec(o);
        let [a, b, c] = self.v.map(|p| sub(&ivec(p), &o));
        dot(&a, &cross(&b, &c))
    }

    /// Whether every coordinate is finite.
    pub fn is_finite(&self) -> bool {
        self.v.iter().all(|p| p.is_finite())
    }

    /// The box of the vertices.
    pub fn bounds(&self) -> IBox {
        std::array::from_fn(|i| {
            let lo = self.v[0][i].min(self.v[1][i]).min(self.v[2][i]);
            let hi = self.v[0][i].max(self.v[1][i]).max(self.v[2][i]);
            Interval::new_unchecked(lo, hi)
        })
    }

    /// The crossing of the ray `origin + t·dir` with the triangle for `t` in `window`:
    /// `None` is a proof that there is none.
    ///
    /// The line meets the triangle where the three signed volumes `dir · (a × b)` of the
    /// vertices taken from the origin (`a = v_i − origin`) share one sign; they are enclosed
    /// in interval arithmetic, so a sign proven the other way is a proof of a miss, and three
    /// proven alike a proof of a crossing. The parameter is `n · (v0 − origin) / (n · dir)`
    /// with the normal `n`, enclosed the same way; where the enclosure does not lie inside
    /// `window`, a crossing is not proven inside it.
    pub fn crossing(&self, origin: DVec3, dir: DVec3, window: Interval<f64>) -> Option<Crossing> {
        if !(origin.is_finite() && dir.is_finite()) {
            // Nothing can be proven of such a ray.
            return (!window.is_empty()).then_some(Crossing {
                t: window,
                proven: false,
            });
        }
        let d = ivec(dir);
        let (s, [a, b, c]) = self.volumes(&ivec(origin), &d);
        let positive = s.contains(&Some(true));
        let negative = s.contains(&Some(false));
        if positive && negative {
            return None;
        }
        let inside = s.iter().all(|x| x.is_some());
        let n = cross(&sub(&b, &a), &sub(&c, &a));
        let (num, den) = (dot(&n, &a), dot(&n, &d));
        // Where the three volumes share a proven sign, `n · d` (their sum) is not zero, and
        // the quotient encloses the crossing even where the divisor's enclosure holds 0. Else
        // a ray in (or within rounding of) the triangle's plane meets it at every parameter
        // where it lies inside: the quotient of `[0, 0]` by an enclosure of zero is no
        // bound, and any parameter of the window may be a crossing.
        let t = if inside && !den.is_empty() {
            num.div(den)
        } else if den.is_empty() || num.is_empty() || den.contains(0.0) {
            window
        } else {
            num.div(den)
        };
        let t = if t.is_empty() { window } else { t };
        let within = t.intersection(window);
        if within.is_empty() {
            return None;
        }
        Some(Crossing {
            t: within,
            proven: inside && within == t,
        })
    }

    /// An enclosure of the parameters at which the rays of `beam` cross the triangle, where
    /// every ray of the beam is proven to cross it inside `window`; `None` where that is not
    /// proven.
    ///
    /// The signed volumes `d · (a × b)` (with `a = v_i − o`) are enclosed over the beam's
    /// boxes of origins and directions at once (the interval extension of the same
    /// formulas as [`Triangle::crossing`]): three proven of one sign prove that every ray's
    /// line crosses the triangle, and the parameter's enclosure over the boxes must lie in
    /// the window.
    pub fn covers(&self, beam: &Beam, window: Interval<f64>) -> Option<Interval<f64>> {
        let (s, [a, b, c]) = self.beam_volumes(beam);
        let one_sign = s[0].is_some() && s[1] == s[0] && s[2] == s[0];
        if !one_sign {
            return None;
        }
        let d = &beam.dir;
        let n = cross(&sub(&b, &a), &sub(&c, &a));
        let (num, den) = (dot(&n, &a), dot(&n, d));
        if den.is_empty() || num.is_empty() || den.contains(0.0) {
            return None;
        }
        let t = num.div(den);
        (!t.is_empty() && t.intersection(window) == t).then_some(t)
    }

    /// Whether no ray's line of `beam` meets the triangle, proven: two of the signed
    /// volumes of [`Triangle::covers`] have opposite signs over the whole beam (every line
    /// passes outside one edge).
    pub fn beam_misses(&self, beam: &Beam) -> bool {
        let (s, _) = self.beam_volumes(beam);
        s.contains(&Some(true)) && s.contains(&Some(false))
    }

    /// The signs of the three signed volumes over the beam's boxes, and the vertices taken
    /// from its origins.
    fn beam_volumes(&self, beam: &Beam) -> ([Option<bool>; 3], [IVec; 3]) {
        self.volumes(&beam.origin, &beam.dir)
    }

    /// The signs of the signed volumes `d · (a × b)` of the vertices taken from the origins
    /// `o` (`a = v_i − o`), over the boxes `o` and `d`, and those vertices.
    fn volumes(&self, o: &IVec, d: &IVec) -> ([Option<bool>; 3], [IVec; 3]) {
        let a = sub(&ivec(self.v[0]), o);
        let b = sub(&ivec(self.v[1]), o);
        let c = sub(&ivec(self.v[2]), o);
        let s = [
            dot(d, &cross(&b, &c)),
            dot(d, &cross(&c, &a)),
            dot(d, &cross(&a, &b)),
        ]
        .map(sign);
        (s, [a, b, c])
    }

    /// Whether no point of the box `b` is proven off the triangle: `false` is a proof that
    /// the triangle misses the box (the boxes are disjoint, or the plane misses the box).
    pub fn may_meet(&self, b: &IBox) -> bool {
        if disjoint(&self.bounds(), b) {
            return false;
        }
        let h = dot(&self.interval_normal(), &sub(b, &ivec(self.v[0])));
        sign(h).is_none()
    }
}
