//! The side operator of Plücker coordinates as an exact orientation predicate.
//!
//! For the oriented lines `a → b` and `c → d`, `side(ab, cd) = (b − a) · ((c − a) × (d − a))
//! = det[b − a, c − a, d − a]`: zero where the lines meet or are parallel, and its sign tells
//! how one turns around the other. Every sign the exact method decides is one of these, so
//! it is evaluated exactly on the doubles given: Shewchuk's adaptive `orient3d` (the
//! `robust` crate), which is exact for every input and as fast as a plain determinant when
//! the sign is clear.

use glam::DVec3;

/// The sign (−1, 0, 1) of `side(a → b, c → d) = det[b − a, c − a, d − a]`, exactly.
pub(super) fn side_sign(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    // A shared point makes the lines meet: zero, without the adaptive stages that an exact
    // zero would run through (neighbouring mesh triangles share vertices).
    if d == a || d == b || c == a || c == b || c == d || a == b {
        return 0;
    }
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    // `orient3d(a, b, c, d) = det[a − d, b − d, c − d] = −det[b − a, c − a, d − a]`.
    let o = robust::orient3d(p(a), p(b), p(c), p(d));
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
}
