//! The shape of an area light: a parallelogram, and the pieces the shadow methods split it
//! into (an `n × n` grid of cells, quadrants, sample points).

use crate::ibox::{IBox, ipoint, ival, point_box};
use glam::DVec3;

/// The parallelogram `corner + u · edge_u + v · edge_v`, `u, v ∈ [0, 1]`. Either edge may be
/// zero (a segment light, or a point).
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct Patch {
    /// One corner.
    pub corner: DVec3,
    /// The first edge from the corner.
    pub edge_u: DVec3,
    /// The second edge from the corner.
    pub edge_v: DVec3,
}

impl Patch {
    /// The axis-aligned square of side `size` centred at `center`, perpendicular to `axis`
    /// (0 = x, 1 = y, 2 = z): the lights of the soft-shadow paper.
    pub fn square(center: DVec3, size: f64, axis: usize) -> Patch {
        let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
        let edge_u = DVec3::AXES[a] * size;
        let edge_v = DVec3::AXES[b] * size;
        Patch {
            corner: center - 0.5 * (edge_u + edge_v),
            edge_u,
            edge_v,
        }
    }

    /// The point at `(u, v)`.
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.corner + u * self.edge_u + v * self.edge_v
    }

    /// The centre.
    pub fn center(&self) -> DVec3 {
        self.point(0.5, 0.5)
    }

    /// The area.
    pub fn area(&self) -> f64 {
        self.edge_u.cross(self.edge_v).length()
    }

    /// The length of the longer diagonal: the light's size.
    pub fn extent(&self) -> f64 {
        (self.edge_u + self.edge_v)
            .length()
            .max((self.edge_u - self.edge_v).length())
    }

    /// Whether the light has no extent (both edges zero): a point light.
    pub fn is_point(&self) -> bool {
        self.edge_u == DVec3::ZERO && self.edge_v == DVec3::ZERO
    }

    /// The four corners.
    pub fn corners(&self) -> [DVec3; 4] {
        [
            self.point(0.0, 0.0),
            self.point(1.0, 0.0),
            self.point(1.0, 1.0),
            self.point(0.0, 1.0),
        ]
    }

    /// Whether the whole light lies behind the plane through `point` with normal `normal`
    /// (on or below it): a surface point there gets no direct light from it.
    pub fn is_behind(&self, point: DVec3, normal: DVec3) -> bool {
        self.corners().iter().all(|c| normal.dot(*c - point) <= 0.0)
    }

    /// The sub-parallelogram `[u0, u1] × [v0, v1]` of parameters.
    pub fn part(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> Patch {
        Patch {
            corner: self.point(u0, v0),
            edge_u: (u1 - u0) * self.edge_u,
            edge_v: (v1 - v0) * self.edge_v,
        }
    }

    /// The outward-rounded box of the exact points `c + [u0, u1]·e_u + [v0, v1]·e_v`.
    pub fn exact_box(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> IBox {
        let (u, v) = (ival(u0, u1), ival(v0, v1));
        std::array::from_fn(|k| {
            ipoint(self.corner[k]) + u * ipoint(self.edge_u[k]) + v * ipoint(self.edge_v[k])
        })
    }

    /// A patch whose [`directions_from`](Patch::directions_from) box from any point holds
    /// the exact sub-parallelogram `[u0, u1] × [v0, v1]`, which that of [`Patch::part`]
    /// may miss by the rounding of its corner and edges: the outward-rounded box of `c +
    /// [u0, u1]·e_u + [v0, v1]·e_v`, as the patch from its low corner along its diagonal
    /// (`e_v` zero). For the beams that prove a part free or blocked; it has no area.
    pub fn covering_part(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> Patch {
        let b = self.exact_box(u0, u1, v0, v1);
        let lo = DVec3::from(b.map(|i| i.inf()));
        let hi = DVec3::from(b.map(|i| i.sup()));
        // `lo + 1·(hi − lo)` reaches `hi` in the outward box sum: the difference rounded up.
        let diagonal = DVec3::from(std::array::from_fn(|k| {
            (ipoint(hi[k]) - ipoint(lo[k])).sup()
        }));
        Patch {
            corner: lo,
            edge_u: diagonal,
            edge_v: DVec3::ZERO,
        }
    }

    /// Cell `(i, j)` of the `n × n` grid of equal cells (`i` along `edge_u`).
    pub fn cell(&self, i: u32, j: u32, n: u32) -> Patch {
        let k = f64::from(n);
        self.part(
            f64::from(i) / k,
            f64::from(i + 1) / k,
            f64::from(j) / k,
            f64::from(j + 1) / k,
        )
    }

    /// The directions from `from` to every point of the light, as an outward-rounded box:
    /// `corner − from + [0, 1] · edge_u + [0, 1] · edge_v` in interval arithmetic. A shadow
    /// beam from `from` over the light is the beam with this direction box and `t ∈ [0, 1]`.
    pub fn directions_from(&self, from: DVec3) -> IBox {
        let unit = ival(0.0, 1.0);
        let c = point_box(self.corner);
        let f = point_box(from);
        std::array::from_fn(|k| {
            let mut d = c[k] - f[k];
            for e in [self.edge_u, self.edge_v] {
                let e = e.to_array()[k];
                if e != 0.0 {
                    d = d + unit * ipoint(e);
                }
            }
            d
        })
    }

    /// An outward-rounded box enclosing the light.
    pub fn bounding_box(&self) -> IBox {
        self.directions_from(DVec3::ZERO)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_is_centred_and_flat() {
        let p = Patch::square(DVec3::new(1.0, 5.0, -2.0), 2.0, 1);
        assert_eq!(p.center(), DVec3::new(1.0, 5.0, -2.0));
        assert_eq!(p.area(), 4.0);
        let b = p.bounding_box();
        assert_eq!(b[1], ipoint(5.0));
        assert!(b[0].inf() <= 0.0 && b[0].sup() >= 2.0);
    }

    /// A covering part's box holds the part's points (here its rounded corners, each within
    /// the exact part's box up to an ulp) and is no wider than the part, also for a light
    /// whose edge has a coordinate that is nearly zero.
    #[test]
    fn covering_parts_hold_their_part_and_no_more() {
        let light = Patch {
            corner: DVec3::new(-0.25, 2.0, -0.25),
            edge_u: DVec3::new(0.5, 3e-17, 0.0),
            edge_v: DVec3::new(0.0, 0.0, 0.5),
        };
        let (u0, u1, v0, v1) = (0.25, 0.5, 0.1, 0.7);
        let b = light.covering_part(u0, u1, v0, v1).bounding_box();
        for p in light.part(u0, u1, v0, v1).corners() {
            for k in 0..3 {
                assert!(b[k].inf() <= p[k] && p[k] <= b[k].sup(), "{p} {b:?}");
            }
        }
        assert!((b[0].wid() - 0.125).abs() < 1e-12, "{b:?}");
        assert!((b[2].wid() - 0.3).abs() < 1e-12, "{b:?}");
        assert!(b[1].wid() < 1e-15, "{b:?}");
        // The exact y of the part, 2 + u·3e-17, is not a double: the box holds it.
        assert!(b[1].inf() <= 2.0 && b[1].sup() > 2.0, "{b:?}");
    }

    #[test]
    fn cells_tile_the_light() {
        let p = Patch {
            corner: DVec3::ZERO,
            edge_u: DVec3::new(3.0, 0.0, 1.0),
            edge_v: DVec3::new(0.0, 2.0, 0.5),
        };
        let total: f64 = (0..5)
            .flat_map(|i| (0..5).map(move |j| (i, j)))
            .map(|(i, j)| p.cell(i, j, 5).area())
            .sum();
        assert!((total - p.area()).abs() < 1e-12);
        assert_eq!(p.cell(4, 4, 5).point(1.0, 1.0), p.point(1.0, 1.0));
    }

    #[test]
    fn direction_box_encloses_every_direction() {
        // Dyadic values: the sample directions below are exact.
        let p = Patch {
            corner: DVec3::new(0.125, 0.75, -0.25),
            edge_u: DVec3::new(0.375, 0.0, 0.125),
            edge_v: DVec3::new(-0.25, 0.5, 0.0),
        };
        let from = DVec3::new(0.25, -0.125, 0.875);
        let d = p.directions_from(from);
        for k in 0..=8 {
            for l in 0..=8 {
                let q = p.point(f64::from(k) / 8.0, f64::from(l) / 8.0) - from;
                for (a, x) in d.iter().zip(q.to_array()) {
                    assert!(a.contains(x), "{a:?} misses {x}");
                }
            }
        }
    }
}
