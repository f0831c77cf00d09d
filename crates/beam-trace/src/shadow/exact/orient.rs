//! The side operator of Plücker coordinates as an exact orientation predicate.
//!
//! For the oriented lines `a → b` and `c → d`, `side(ab, cd) = (b − a) · ((c − a) × (d − a))
//! = det[b − a, c − a, d − a]`: zero where the lines meet or are parallel, and its sign tells
//! how one turns around the other. Every sign the exact method decides is one of these, so
//! it is evaluated exactly on the doubles given: Shewchuk's adaptive `orient3d` (the
//! `robust` crate), which is exact for every input and as fast as a plain determinant when
//! the sign is clear.

use glam::DVec3;

use interval_core::Float;

use super::fragment::{Affine, UNIT};
use crate::shadow::Patch;

/// Shewchuk's bound on the rounding error of [`filtered`]'s determinant, relative to its
/// permanent (`o3derrboundA`, "Adaptive precision floating-point arithmetic and fast robust
/// geometric predicates", 1997): where the computed determinant exceeds it in magnitude, its
/// sign is the exact sign.
const FILTER: f64 = (7.0 + 56.0 * UNIT) * UNIT;

/// `orient3d(a, b, c, d) = det[a − d, b − d, c − d]` in floating point, evaluated in the
/// order the bound [`FILTER`] is proven for, when its sign is certain; `None` when the
/// rounding error could reach zero (then the adaptive predicate decides).
#[inline]
fn filtered(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Option<f64> {
    let (det, permanent) = determinant(a, b, c, d);
    let bound = FILTER * permanent;
    (det > bound || -det > bound).then_some(det)
}

/// `orient3d(a, b, c, d)` in floating point, in the order [`FILTER`] is proven for, and
/// its permanent (the same sum with every term's magnitude).
#[inline]
fn determinant(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> (f64, f64) {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (bc, cb) = (bd.x * cd.y, cd.x * bd.y);
    let (ca, ac) = (cd.x * ad.y, ad.x * cd.y);
    let (ab, ba) = (ad.x * bd.y, bd.x * ad.y);
    let det = ad.z * (bc - cb) + bd.z * (ca - ac) + cd.z * (ab - ba);
    let permanent = (bc.abs() + cb.abs()) * ad.z.abs()
        + (ca.abs() + ac.abs()) * bd.z.abs()
        + (ab.abs() + ba.abs()) * cd.z.abs();
    (det, permanent)
}

/// `orient3d(a, b, c, d)` by Shewchuk's adaptive predicate (the `robust` crate): its sign is
/// exact for every input.
fn adaptive(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    robust::orient3d(p(a), p(b), p(c), p(d))
}

/// The sign (−1, 0, 1) of `side(a → b, c → d) = det[b − a, c − a, d − a]`, exactly.
pub(super) fn side_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    // `orient3d(a, b, c, d) = det[a − d, b − d, c − d] = −det[b − a, c − a, d − a]`.
    let o = match filtered(a, b, c, d) {
        Some(o) => o,
        // A shared point makes the lines meet: zero, without the adaptive stages that an
        // exact zero would run through (neighbouring mesh triangles share vertices).
        None if d == a || d == b || c == a || c == b || c == d || a == b => return 0,
        None => adaptive(a, b, c, d),
    };
    if o < 0.0 {
        1
    } else if o > 0.0 {
        -1
    } else {
        0
    }
}

/// The sign of `side(a → b, c → d)` for every point `c` of the box `[lo, hi]`, where it is
/// the same for all of them (`Some`; `0` where the determinant vanishes on the box), or `None`
/// where it may vary. The determinant is affine in `c` with gradient `(a − d) × (b − d)`,
/// so it varies over the box by at most `(hi − lo) · |terms of that gradient|` (`hi − lo`
/// is exact for the boxes of a rounding); where the filtered determinant at `lo` exceeds
/// that and its own error bound, its sign holds everywhere; otherwise the box's corners
/// decide, each exactly.
pub(super) fn side_sign_box(a: DVec3, b: DVec3, (lo, hi): (DVec3, DVec3), d: DVec3) -> Option<i8> {
    if lo == hi {
        return Some(side_sign(a, b, lo, d));
    }
    let (det, permanent) = determinant(a, b, lo, d);
    let spread = (hi - lo).dot(cross_terms(a - d, b - d)) * (1.0 + 1e-10);
    let bound = (FILTER * permanent).add_up(spread);
    if det > bound {
        return Some(-1);
    }
    if -det > bound {
        return Some(1);
    }
    let mut seen = None;
    for k in 0..8 {
        let s = side_sign(a, b, box_corner(lo, hi, k), d);
        match seen {
            None => seen = Some(s),
            Some(t) if t != s => return None,
            _ => {}
        }
    }
    seen
}

/// Corner `k` (`0..8`, bit `i` choosing `hi` along axis `i`) of the box `[lo, hi]`.
pub(super) fn box_corner(lo: DVec3, hi: DVec3, k: usize) -> DVec3 {
    DVec3::from(std::array::from_fn(|i| {
        if k >> i & 1 == 0 { lo[i] } else { hi[i] }
    }))
}

/// `(|u_y v_z| + |u_z v_y|, …)`: the cross product's terms in absolute value.
pub(super) fn cross_terms(u: DVec3, v: DVec3) -> DVec3 {
    let (u, v) = (u.abs(), v.abs());
    DVec3::new(
        u.y * v.z + u.z * v.y,
        u.z * v.x + u.x * v.z,
        u.x * v.y + u.y * v.x,
    )
}

/// The query plane through `x` and the edge `a → b`, in the light's parameters: `s(u, v) =
/// side(a → b, l(u, v) → x)` with `l(u, v) = c + u·e_u + v·e_v` (`light`), affine in `(u,
/// v)`: `c0 = (c − a) · m`, `cu = e_u · m`, `cv = e_v · m` for `m = (x − a) × (b − a)`,
/// computed in floating point. Also returns a bound on `|s − ŝ|` over the square between
/// the exact function and the computed one: each coefficient is a triple product of
/// rounded differences (at most four roundings on the way to each of its six terms, three
/// in the sum), so its error is below `8 UNIT` times the sum of its terms' magnitudes; the
/// bound takes `10 UNIT` for the roundings of that sum itself.
pub(super) fn query_plane(a: DVec3, b: DVec3, light: &Patch, x: DVec3) -> (Affine, f64) {
    let (d, w) = (b - a, x - a);
    let m = w.cross(d);
    let terms = cross_terms(w, d);
    let ca = light.corner - a;
    let s = Affine {
        c0: ca.dot(m),
        cu: light.edge_u.dot(m),
        cv: light.edge_v.dot(m),
    };
    let permanent = |e: DVec3| e.abs().dot(terms);
    let error = 10.0 * UNIT * (permanent(ca) + permanent(light.edge_u) + permanent(light.edge_v));
    (s, error)
}

#[cfg(test)]
mod tests {
    use super::*;
    use interval_core::Interval;
    use interval_core::dd::DdInterval;
    use proptest::prelude::*;

    #[test]
    fn sign_convention_matches_the_determinant() {
        let (a, b) = (DVec3::ZERO, DVec3::X);
        // det[x, y, z] = 1.
        assert_eq!(side_sign(a, b, DVec3::Y, DVec3::Z), 1);
        let light = Patch {
            corner: DVec3::Y,
            edge_u: DVec3::X,
            edge_v: DVec3::Z,
        };
        let (s, error) = query_plane(a, b, &light, DVec3::Z);
        assert!(s.c0 > error);
        assert_eq!(side_sign(a, b, DVec3::Z, DVec3::Y), -1);
        // Meeting lines: zero.
        assert_eq!(side_sign(a, b, DVec3::Y, DVec3::new(2.0, 0.0, 0.0)), 0);
        // Exact where floating point cancels: four nearly coplanar points.
        let e = f64::EPSILON;
        let c = DVec3::new(0.5, 1.0, 0.0);
        let d = DVec3::new(0.5 + e, 1.0 + e, e * e);
        assert_eq!(side_sign(a, b, c, d), side_sign(a, b, c, d));
        assert_ne!(side_sign(a, b, c, d), 0);
    }

    /// The adaptive predicate's sign of `side(a → b, c → d)`.
    fn adaptive_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
        let o = adaptive(a, b, c, d);
        -(o.signum() as i8) * i8::from(o != 0.0)
    }

    fn point() -> impl Strategy<Value = DVec3> {
        (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// The filtered sign is the adaptive predicate's, on random points and on points a
        /// few ulps off the plane of the other three (where the filter must hand over).
        #[test]
        fn the_filter_agrees_with_the_adaptive_predicate(
            (a, b, c, d) in (point(), point(), point(), point()),
            (s, t) in (-1.0..1.0f64, -1.0..1.0f64),
            ulps in -3i32..=3,
            near in any::<bool>(),
        ) {
            let d = if near {
                let p = a + s * (b - a) + t * (c - a);
                DVec3::new(p.x, p.y, p.z + f64::from(ulps) * p.z.abs().max(1e-300) * f64::EPSILON)
            } else {
                d
            };
            prop_assert_eq!(side_sign(a, b, c, d), adaptive_sign(a, b, c, d));
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// The query plane's coefficients lie within its error bound of the exact ones
        /// (enclosed in double-double interval arithmetic, far tighter than the bound),
        /// summed as the bound is over the light's square, also where they cancel: `x` a
        /// few ulps off the plane of the edge and the light's corner, at scales from 1e-3
        /// to 1e3.
        #[test]
        fn the_query_plane_error_bound_holds(
            (a, b, c, x) in (point(), point(), point(), point()),
            (s, t) in (-1.0..1.0f64, -1.0..1.0f64),
            scale in -3.0..3.0f64,
            near in any::<bool>(),
        ) {
            let k = 10f64.powf(scale);
            let (a, b, c) = (a * k, b * k, c * k + DVec3::splat(k));
            let x = if near { a + s * (b - a) + t * (c - a) } else { x * k };
            let light = Patch { corner: c, edge_u: DVec3::X * k, edge_v: DVec3::Y * k };
            let (plane, error) = query_plane(a, b, &light, x);
            let off = |computed: f64, exact: Interval<f64>| {
                (computed - exact.inf()).abs().max((exact.sup() - computed).abs())
            };
            let (c0, cu, cv) = exact_plane(a, b, &light, x);
            let misplaced = off(plane.c0, c0) + off(plane.cu, cu) + off(plane.cv, cv);
            prop_assert!(
                misplaced <= error,
                "c0 {} against {:?}, cu {} against {:?}, cv {} against {:?} (bound {})",
                plane.c0, c0, plane.cu, cu, plane.cv, cv, error
            );
        }
    }

    /// Enclosures of the query plane's coefficients `((c − a) · m, e_u · m, e_v · m)` for
    /// `m = (x − a) × (b − a)` on the doubles given, in double-double interval arithmetic.
    fn exact_plane(
        a: DVec3,
        b: DVec3,
        light: &Patch,
        x: DVec3,
    ) -> (Interval<f64>, Interval<f64>, Interval<f64>) {
        let v = |p: DVec3| p.to_array().map(DdInterval::point);
        let sub = |p: [DdInterval; 3], q: [DdInterval; 3]| std::array::from_fn(|i| p[i] - q[i]);
        let (a, b, x) = (v(a), v(b), v(x));
        let (w, d) = (sub(x, a), sub(b, a));
        let m: [DdInterval; 3] = [
            w[1] * d[2] - w[2] * d[1],
            w[2] * d[0] - w[0] * d[2],
            w[0] * d[1] - w[1] * d[0],
        ];
        let dot = |e: [DdInterval; 3]| (e[0] * m[0] + e[1] * m[1] + e[2] * m[2]).to_interval();
        (
            dot(sub(v(light.corner), a)),
            dot(v(light.edge_u)),
            dot(v(light.edge_v)),
        )
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        /// A box's sign, where one is given, is that of each of its corners (the
        /// determinant is affine in the point, so of every point of the box), also for
        /// boxes a few ulps wide on the plane of the other three points.
        #[test]
        fn a_box_sign_holds_at_every_corner(
            (a, b, d) in (point(), point(), point()),
            (s, t) in (-1.0..1.0f64, -1.0..1.0f64),
            ulps in 0i32..=4,
            near in any::<bool>(),
            far in point(),
        ) {
            let lo = if near { a + s * (b - a) + t * (d - a) } else { far };
            let hi = DVec3::from(lo.to_array().map(|x| {
                let mut x = x;
                for _ in 0..ulps {
                    x = x.next_up();
                }
                x
            }));
            let corners: Vec<i8> = (0..8)
                .map(|k| side_sign(a, b, box_corner(lo, hi, k), d))
                .collect();
            if let Some(sign) = side_sign_box(a, b, (lo, hi), d) {
                prop_assert!(corners.iter().all(|&c| c == sign), "{sign} {corners:?}");
            } else {
                prop_assert!(corners.iter().any(|&c| c != corners[0]));
            }
        }
    }

    #[test]
    fn the_filter_hands_nearly_flat_cases_over() {
        // d on the plane of a, b, c up to the rounding of its coordinates.
        let (a, b, c) = (
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(0.7, -0.4, 0.9),
            DVec3::new(-0.3, 0.8, 0.5),
        );
        let d = a + 0.37 * (b - a) + 0.21 * (c - a);
        assert_eq!(filtered(a, b, c, d), None);
        assert_eq!(side_sign(a, b, c, d), adaptive_sign(a, b, c, d));
        assert!(filtered(a, b, c, d + DVec3::Z).is_some());
    }
}
