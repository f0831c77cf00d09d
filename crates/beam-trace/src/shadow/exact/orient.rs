//! The side operator of Plücker coordinates as an exact orientation predicate.
//!
//! For the oriented lines `a → b` and `c → d`, `side(ab, cd) = (b − a) · ((c − a) × (d − a))
//! = det[b − a, c − a, d − a]`: zero where the lines meet or are parallel, and its sign tells
//! how one turns around the other. Every sign the exact method decides is one of these, so
//! it is evaluated exactly on the doubles given: Shewchuk's adaptive `orient3d` (the
//! `robust` crate), which is exact for every input and as fast as a plain determinant when
//! the sign is clear.

use glam::DVec3;

/// Half an ulp of 1 (the unit roundoff of `f64`).
const UNIT: f64 = f64::EPSILON / 2.0;

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
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let (bc, cb) = (bd.x * cd.y, cd.x * bd.y);
    let (ca, ac) = (cd.x * ad.y, ad.x * cd.y);
    let (ab, ba) = (ad.x * bd.y, bd.x * ad.y);
    let det = ad.z * (bc - cb) + bd.z * (ca - ac) + cd.z * (ab - ba);
    let permanent = (bc.abs() + cb.abs()) * ad.z.abs()
        + (ca.abs() + ac.abs()) * bd.z.abs()
        + (ab.abs() + ba.abs()) * cd.z.abs();
    let bound = FILTER * permanent;
    (det > bound || -det > bound).then_some(det)
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

/// `side(a → b, c → d)` in floating point (for the affine functions of the queries).
pub(super) fn side(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    (b - a).dot((c - a).cross(d - a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn sign_convention_matches_the_determinant() {
        let (a, b) = (DVec3::ZERO, DVec3::X);
        // det[x, y, z] = 1.
        assert_eq!(side_sign(a, b, DVec3::Y, DVec3::Z), 1);
        assert!(side(a, b, DVec3::Y, DVec3::Z) > 0.0);
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
