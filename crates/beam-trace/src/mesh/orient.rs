//! Exact orientation predicates on a mesh's vertices (Shewchuk's adaptive predicates, the
//! `robust` crate, on the doubles given).

use glam::DVec3;

use super::triangle::Triangle;

/// The sign of `orient3d(a, b, c, d)`: positive where `d` lies below the plane through
/// `a, b, c` seen counterclockwise (Shewchuk's convention), exactly.
pub(super) fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    sign(robust::orient3d(p(a), p(b), p(c), p(d)))
}

fn sign(x: f64) -> i8 {
    i8::from(x > 0.0) - i8::from(x < 0.0)
}

/// The sign of `orient2d(a, b, c)` of points of a plane, exactly: positive where `a, b, c`
/// turn counterclockwise.
pub(super) fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i8 {
    let p = |v: [f64; 2]| robust::Coord { x: v[0], y: v[1] };
    sign(robust::orient2d(p(a), p(b), p(c)))
}

/// A plane's points seen along the axis `drop` (that coordinate left out: exact), where
/// orientations in the plane keep their signs up to one factor for the whole plane.
#[derive(Copy, Clone)]
pub(super) struct Projection {
    drop: usize,
}

impl Projection {
    /// The projection along the largest component of the normal of `t` (`None` for a
    /// triangle whose normal may vanish).
    pub(super) fn of(t: &Triangle) -> Option<Self> {
        let n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
        let a = n.abs();
        let drop = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        // The largest component is exactly non-zero when it exceeds its rounding (six
        // products of rounded differences and their sums: far below 16 ulps of the terms).
        let [d0, d1] = [t.v[1] - t.v[0], t.v[2] - t.v[0]];
        let (i, j) = ((drop + 1) % 3, (drop + 2) % 3);
        let terms = (d0[i] * d1[j]).abs() + (d0[j] * d1[i]).abs();
        (a[drop] > 16.0 * f64::EPSILON * terms).then_some(Projection { drop })
    }

    /// The sign of `orient2d(a, b, c)` of the projected points, exactly.
    pub(super) fn orient(&self, a: DVec3, b: DVec3, c: DVec3) -> i8 {
        let (i, j) = ((self.drop + 1) % 3, (self.drop + 2) % 3);
        let p = |v: DVec3| [v[i], v[j]];
        orient2d(p(a), p(b), p(c))
    }
}

/// Whether the exact predicates stay exact on `p`: coordinates zero or of magnitude
/// between `1e-30` and `1e30` (no product of differences overflows or underflows).
pub(crate) fn in_range(p: DVec3) -> bool {
    p.to_array()
        .iter()
        .all(|&x| x == 0.0 || (1e-30..=1e30).contains(&x.abs()))
}
