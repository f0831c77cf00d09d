//! Rays and beams (thesis 5.4.1), and the evaluator that restricts a scene function to one.
//!
//! A [`Ray`] is a point origin and a point direction; a [`Beam`] is the set of rays whose
//! origin lies in a box and whose direction lies in a box (the eye and a screen area for a
//! primary beam, a surface patch and a light for a shadow beam). Points on a ray are
//! `origin + t · dir`; for a beam, `origin + T · dir` encloses the points of every ray.

use glam::DVec3;
use implicit_expr::{RayEvaluator, RayFunction};
use interval_core::Interval;

use crate::root::RayFn;

/// A box in space: one interval per axis.
pub type IBox = [Interval<f64>; 3];

/// The degenerate interval `[x, x]` (`x` finite).
#[inline]
pub fn ipoint(x: f64) -> Interval<f64> {
    Interval::new_unchecked(x, x)
}

/// `[lo, hi]` (the caller guarantees `lo <= hi`, both not NaN).
#[inline]
pub fn ival(lo: f64, hi: f64) -> Interval<f64> {
    debug_assert!(lo <= hi, "[{lo}, {hi}]");
    Interval::new_unchecked(lo, hi)
}

/// A box of one point.
pub fn point_box(p: DVec3) -> IBox {
    [ipoint(p.x), ipoint(p.y), ipoint(p.z)]
}

/// A ray `origin + t · dir`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Ray {
    /// Origin.
    pub origin: DVec3,
    /// Direction (not necessarily unit length).
    pub dir: DVec3,
}

impl Ray {
    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }

    /// The ray as a beam of one ray.
    pub fn beam(&self) -> Beam {
        Beam {
            origin: point_box(self.origin),
            dir: point_box(self.dir),
        }
    }
}

/// A beam: every ray with origin in `origin` and direction in `dir`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Beam {
    /// Box of origins (a point box for primary beams).
    pub origin: IBox,
    /// Box of directions.
    pub dir: IBox,
}

impl Beam {
    /// An enclosure of the points of every ray of the beam for `t ∈ t`.
    pub fn points(&self, t: Interval<f64>) -> IBox {
        std::array::from_fn(|i| self.origin[i] + t * self.dir[i])
    }

    /// The slab test on one axis: an enclosure, rounded outward, of the parameters `t ∈ t`
    /// at which some ray of the beam has its coordinate on `axis` in `slab`. Empty when no
    /// ray of the beam reaches the slab for `t ∈ t`.
    ///
    /// Solves `o + t·d ∈ slab` for `o ∈ origin[axis]`, `d ∈ dir[axis]` with the extended
    /// division (`t ∈ (slab − o) / d`): a direction interval holding 0 gives up to two
    /// unbounded pieces, each is clipped to `t` before their hull is taken; a zero direction
    /// gives every `t` when the origin lies in the slab and none otherwise (rays parallel
    /// to the slab).
    pub fn slab_t(&self, axis: usize, slab: Interval<f64>, t: Interval<f64>) -> Interval<f64> {
        let v = slab - self.origin[axis];
        let (p, q) = self.dir[axis].mul_rev_to_pair(v);
        p.intersection(t).convex_hull(q.intersection(t))
    }

    /// An enclosure, rounded outward, of the parameters `t ∈ t` at which some ray of the
    /// beam is inside the box `b` (the intersection of the three slab tests of
    /// [`Beam::slab_t`]); `None` when it is empty, a proof that no ray of the beam is in
    /// `b` for `t ∈ t`. For a beam of many rays it is a hull: different rays may be inside
    /// at different parameters.
    pub fn t_range_within(&self, b: &IBox, t: Interval<f64>) -> Option<Interval<f64>> {
        let mut r = t;
        for (axis, slab) in b.iter().enumerate() {
            r = self.slab_t(axis, *slab, r);
            if r.is_empty() {
                return None;
            }
        }
        Some(r)
    }

    /// [`Beam::t_range_within`] over every parameter (negative ones included).
    pub fn t_range(&self, b: &IBox) -> Option<Interval<f64>> {
        self.t_range_within(b, Interval::ENTIRE)
    }

    /// The central ray (midpoints of the boxes).
    pub fn central_ray(&self) -> Ray {
        Ray {
            origin: DVec3::new(
                self.origin[0].mid(),
                self.origin[1].mid(),
                self.origin[2].mid(),
            ),
            dir: DVec3::new(self.dir[0].mid(), self.dir[1].mid(), self.dir[2].mid()),
        }
    }
}

/// Evaluates `g` and `g'` of a [`RayFunction`] on one ray or beam at a time: the
/// renderer's [`RayFn`]. Owns its scratch space; make one per thread.
#[derive(Clone, Debug)]
pub struct BeamEval {
    interval: RayEvaluator<Interval<f64>>,
    point: RayEvaluator<f64>,
}

impl BeamEval {
    /// An evaluator for `f` (a function without free parameters).
    pub fn new(f: &RayFunction) -> Self {
        Self {
            interval: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
            point: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
        }
    }

    /// Sets the beam the following evaluations are about.
    pub fn set_beam(&mut self, beam: &Beam) {
        self.interval.set_ray(beam.origin, beam.dir);
        let c = beam.central_ray();
        self.point.set_ray(c.origin.to_array(), c.dir.to_array());
    }

    /// Sets a single ray.
    pub fn set_ray(&mut self, ray: &Ray) {
        self.interval
            .set_ray(point_box(ray.origin), point_box(ray.dir));
        self.point
            .set_ray(ray.origin.to_array(), ray.dir.to_array());
    }
}

impl RayFn for BeamEval {
    #[inline]
    fn g(&mut self, t: Interval<f64>) -> Interval<f64> {
        self.interval.g(t)
    }

    #[inline]
    fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
        self.interval.g_dg(t)
    }

    #[inline]
    fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool) {
        self.interval.g_checked(t)
    }

    #[inline]
    fn g_point(&mut self, t: f64) -> f64 {
        self.point.g(t)
    }
}
