//! One receiver plane and one light: [`ExactShadows`], the tree grown by the queries of its
//! points.

use glam::DVec3;
use interval_core::Float;

use super::bsp::{Bsp, Occluder, enclosing_corners};
use super::fragment::{Affine, Fragment, UNIT};
use super::irradiance::form_factor;
use super::orient::{cross_terms, side_sign};
use crate::mesh::in_range;
use crate::shadow::Patch;
use crate::shadow::exact_work::BspWork;

/// An oriented plane: the points `p` with `(p − point) · normal = 0`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Plane {
    /// A point of the plane.
    pub point: DVec3,
    /// Its normal (any length).
    pub normal: DVec3,
}

impl Plane {
    fn height(&self, p: DVec3) -> f64 {
        (p - self.point).dot(self.normal)
    }

    /// [`Plane::height`] and a bound on its error against the plane whose normal differs
    /// from `normal` by at most `normal_error` in each coordinate (a rounded difference,
    /// three products and two sums: below `5 UNIT` of the terms' magnitudes; `8` with a
    /// margin).
    fn height_with_error(&self, p: DVec3, normal_error: DVec3) -> (f64, f64) {
        let d = p - self.point;
        let e = 8.0 * UNIT * d.abs().dot(self.normal.abs()) + d.abs().dot(normal_error);
        (d.dot(self.normal), e * (1.0 + 4.0 * UNIT))
    }

    /// Whether every vertex of `poly` lies proven above the plane (`Some(true)`, with the
    /// lowest height's lower bound), proven below (`Some(false)`, with the highest height's
    /// upper bound), or neither (`None`); the normal as in [`Plane::height_with_error`].
    fn proven_side(&self, poly: &[DVec3], normal_error: DVec3) -> Option<(bool, f64)> {
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut above, mut below) = (true, true);
        for &p in poly {
            let (h, e) = self.height_with_error(p, normal_error);
            above &= h > e;
            below &= h < -e;
            low = low.min(h - e);
            high = high.max(h + e);
        }
        if above {
            Some((true, low))
        } else if below {
            Some((false, high))
        } else {
            None
        }
    }
}

/// What the slab between the receiver's plane and the light holds, as far as proofs need:
/// whether every occluder lies proven on one side of each of the two planes (none was cut
/// by them, whose cut vertices would be rounded, and none dropped as degenerate inside the
/// slab), and how close to the receiver's plane they come from either side.
#[derive(Copy, Clone, Debug)]
struct Slab {
    /// Every occluder lies proven on one side of each plane, none degenerate between them.
    exact: bool,
    /// A lower bound on the heights (toward the light) of the occluders kept.
    front: f64,
    /// An upper bound on the heights of the occluders behind the receiver's plane.
    behind: f64,
    /// A lower bound on the heights of the light's points.
    light: f64,
}

impl Slab {
    /// Whether a point at height `h` (rounding error up to `e`) sees every kept occluder in
    /// front of it, every dropped one behind it and the whole light above it; with the
    /// point on the receiver's side of the light's plane, every line from the light
    /// through a kept occluder to it then meets the occluder between the two, and the
    /// tree's answer is its own.
    fn holds_at(&self, (h, e): (f64, f64)) -> bool {
        self.exact && h + e < self.front.min(self.light) && h - e > self.behind
    }
}

/// The light's plane with its normal toward the receiver, and a bound on the rounding of
/// that normal (`e_u × e_v`, two products and a difference per coordinate).
fn light_plane_of(light: &Patch, ln: DVec3, toward: DVec3) -> (Plane, DVec3) {
    let terms = cross_terms(light.edge_u, light.edge_v);
    let plane = Plane {
        point: light.corner,
        normal: if ln.dot(toward - light.corner) > 0.0 {
            ln
        } else {
            -ln
        },
    };
    (plane, 3.0 * UNIT * terms)
}

/// Why an exact-shadow group cannot be built or queried.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExactError {
    /// The light has no area.
    #[error("the light has no area: the exact method needs an area light")]
    DegenerateLight,
    /// The receiver's plane does not separate: the light touches or crosses it.
    #[error("the light is not strictly on one side of the receiver's plane")]
    LightCrossesReceiver,
    /// A query point is not on the receiver's plane.
    #[error("query point {0:?} is not on the receiver's plane")]
    OffReceiver(DVec3),
    /// A query point lies outside the box given by [`ExactShadows::set_region`].
    #[error("query point {0:?} is outside the receivers' region")]
    OutsideRegion(DVec3),
    /// The receivers' region is not a box (`lo ≤ hi`, finite).
    #[error("the receivers' region [{0:?}, {1:?}] is not a box with finite corners")]
    BadRegion(DVec3, DVec3),
}

/// The irradiance at a point from an area light, as form factors (`E / (π L)` for a
/// Lambertian light of radiance `L`): [`ExactShadows::visible_irradiance`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Irradiance {
    /// From the light's parts visible past the occluders.
    pub visible: f64,
    /// From all of the light above the point's horizon.
    pub unoccluded: f64,
}

/// A visible fraction and proven bounds on it ([`ExactShadows::visible_bounds`]).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct FractionBounds {
    /// The computed fraction (the visible fragments' area).
    pub fraction: f64,
    /// A proven lower bound of the exact fraction.
    pub lower: f64,
    /// A proven upper bound of the exact fraction.
    pub upper: f64,
}

impl FractionBounds {
    /// `fraction ± slack` (rounded outward), within `[0, 1]`.
    fn around(fraction: f64, slack: f64) -> Self {
        FractionBounds {
            fraction,
            lower: fraction.sub_down(slack).max(0.0),
            upper: fraction.add_up(slack).min(1.0),
        }
    }

    fn estimate(fraction: f64) -> Self {
        FractionBounds {
            fraction,
            lower: 0.0,
            upper: 1.0,
        }
    }
}

/// The exact visibility of one area light from the points of one planar receiver, through
/// convex polygonal occluders (see the [module documentation](super)).
#[derive(Clone, Debug)]
pub struct ExactShadows {
    light: Patch,
    receiver: Plane,
    bsp: Bsp,
    /// The box every query point must lie in ([`ExactShadows::set_region`]).
    region: Option<(DVec3, DVec3)>,
    /// Occluders given, and those clipped away or dropped as degenerate.
    given: usize,
    dropped: usize,
    /// The receiver's plane with its normal toward the light.
    toward_light: Plane,
    /// The light's plane with its normal toward the receiver, and its normal's rounding.
    light_plane: (Plane, DVec3),
    slab: Slab,
}

/// Sutherland–Hodgman: the part of the convex polygon where `plane`'s height is `≥ 0`.
fn clip(poly: &[DVec3], plane: &Plane) -> Vec<DVec3> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (hp, hq) = (plane.height(p), plane.height(q));
        if hp >= 0.0 {
            out.push(p);
        }
        if (hp > 0.0 && hq < 0.0) || (hp < 0.0 && hq > 0.0) {
            out.push(p + (q - p) * (hp / (hp - hq)));
        }
    }
    out
}

/// Twice the area of a planar polygon.
fn twice_area(poly: &[DVec3]) -> f64 {
    let n = poly.len();
    (1..n.saturating_sub(1))
        .map(|i| (poly[i] - poly[0]).cross(poly[i + 1] - poly[0]))
        .sum::<DVec3>()
        .length()
}

impl ExactShadows {
    /// A group: the light, the receiver's plane (query points lie on it; its normal may
    /// point either way), the occluders (convex polygons, vertices in order, either
    /// winding), and the seed of the random choices.
    ///
    /// # Errors
    /// [`ExactError`] for a light without area or one that touches the receiver's plane.
    pub fn new(
        light: Patch,
        receiver: Plane,
        occluders: &[Vec<DVec3>],
        seed: u64,
    ) -> Result<Self, ExactError> {
        Self::with_first(light, receiver, &[], occluders, seed)
    }

    /// [`ExactShadows::new`] with occluders `first` that the tree sorts before the others,
    /// in their order, wherever they reach: polygons that hide large parts of the light
    /// and nothing that `occluders` do not hide (squares inside closed meshes,
    /// [`crate::mesh::InnerSquare`]), so that the other occluders' edges cut only what
    /// they leave. The fractions are the same in exact arithmetic where every line that
    /// `first` blocks, `occluders` block (squares inside an embedded closed mesh none of
    /// whose faces were left out); the trees smaller.
    ///
    /// # Errors
    /// As [`ExactShadows::new`].
    pub fn with_first(
        light: Patch,
        receiver: Plane,
        first: &[Vec<DVec3>],
        occluders: &[Vec<DVec3>],
        seed: u64,
    ) -> Result<Self, ExactError> {
        let ln = light.edge_u.cross(light.edge_v);
        if ln == DVec3::ZERO {
            return Err(ExactError::DegenerateLight);
        }
        // The receiver's normal toward the light, the light's toward the receiver.
        let heights = light.corners().map(|c| receiver.height(c));
        let toward_light = if heights.iter().all(|&h| h > 0.0) {
            receiver.normal
        } else if heights.iter().all(|&h| h < 0.0) {
            -receiver.normal
        } else {
            return Err(ExactError::LightCrossesReceiver);
        };
        let receiver_side = Plane {
            point: receiver.point,
            normal: toward_light,
        };
        let light_plane = light_plane_of(&light, ln, receiver.point);
        let mut kept = Vec::new();
        let mut dropped = 0;
        let mut kept_first = 0;
        let corners = enclosing_corners(&light);
        let mut slab = Slab {
            exact: corners.iter().all(|&c| in_range(c)),
            front: f64::INFINITY,
            behind: f64::NEG_INFINITY,
            light: corners
                .iter()
                .map(|&c| {
                    let (h, e) = receiver_side.height_with_error(c, DVec3::ZERO);
                    h - e
                })
                .fold(f64::INFINITY, f64::min),
        };
        for (k, poly) in first.iter().chain(occluders).enumerate() {
            let clipped = clip(&clip(poly, &light_plane.0), &receiver_side);
            let scale = poly
                .iter()
                .map(|p| (*p - poly[0]).length_squared())
                .fold(0.0, f64::max);
            let degenerate = clipped.len() >= 3 && twice_area(&clipped) <= 1e-12 * scale;
            // The exact predicates are exact only where nothing overflows or underflows.
            slab.exact &= poly.iter().all(|&p| in_range(p));
            match (
                light_plane.0.proven_side(poly, light_plane.1),
                receiver_side.proven_side(poly, DVec3::ZERO),
            ) {
                // Behind the light: it blocks nothing.
                (Some((false, _)), _) => {}
                (Some((true, _)), Some((true, low))) if !degenerate => {
                    slab.front = slab.front.min(low);
                }
                (Some((true, _)), Some((false, high))) => slab.behind = slab.behind.max(high),
                _ => slab.exact = false,
            }
            if clipped.len() < 3 || degenerate {
                dropped += 1;
                continue;
            }
            let stab = stab_sign(&light, &corners, &clipped);
            kept_first += usize::from(k < first.len());
            kept.push(Occluder {
                verts: clipped,
                original: poly.clone(),
                stab,
            });
        }
        Ok(ExactShadows {
            light,
            receiver,
            bsp: Bsp::new(light, kept, kept_first, seed),
            region: None,
            given: first.len() + occluders.len(),
            dropped,
            toward_light: receiver_side,
            light_plane,
            slab,
        })
    }

    /// The visible fraction of the light from `x` (a point of the receiver's plane), the
    /// part below the receiver's horizon (`normal`'s side away from it) counted invisible
    /// when `normal` is given.
    ///
    /// # Errors
    /// [`ExactError::OffReceiver`] when `x` is not on the receiver's plane (up to rounding
    /// of its size).
    pub fn visible_fraction(&mut self, x: DVec3, normal: Option<DVec3>) -> Result<f64, ExactError> {
        let (f, _) = self.above_horizon(x, normal)?;
        Ok(if f.is_empty() {
            0.0
        } else {
            self.bsp.query(x, f)
        })
    }

    /// [`ExactShadows::visible_fraction`] with proven bounds: the exact visible fraction
    /// lies in `[lower, upper]`, which is the computed fraction widened by a bound on the
    /// rounding of the fragments ([`FractionBounds`]) where the occluders allow a proof,
    /// and `[0, 1]` where they do not: an occluder cut by the light's plane or the
    /// receiver's (its cut vertices are rounded), or closer to the receiver's plane than
    /// `x` is, or degenerate between the planes.
    ///
    /// # Errors
    /// As [`ExactShadows::visible_fraction`].
    pub fn visible_bounds(
        &mut self,
        x: DVec3,
        normal: Option<DVec3>,
    ) -> Result<FractionBounds, ExactError> {
        let (f, horizon) = self.above_horizon(x, normal)?;
        if f.is_empty() {
            // What the horizon's rounding may have cut off is all there may be.
            return Ok(FractionBounds {
                fraction: 0.0,
                lower: 0.0,
                upper: horizon.min(1.0),
            });
        }
        let visible = self.bsp.query_parts(x, f, None);
        Ok(if self.proven_at(x) {
            FractionBounds::around(visible.area, visible.slack.add_up(horizon))
        } else {
            FractionBounds::estimate(visible.area)
        })
    }

    /// The visible parts of the light from `x` (as [`ExactShadows::visible_fraction`] with
    /// no horizon), as convex fragments of its parameter square, and the bound on their
    /// area's error where the occluders allow a proof ([`ExactShadows::visible_bounds`]).
    /// `x` must lie in the region ([`ExactShadows::set_region`]) but may lie off the
    /// receiver's plane: the answer is `x`'s own where the proof holds, and otherwise that
    /// of occluders clipped to the plane.
    ///
    /// # Errors
    /// [`ExactError::OutsideRegion`].
    pub(super) fn visible_parts_near(
        &mut self,
        x: DVec3,
    ) -> Result<(Vec<Fragment>, Option<f64>), ExactError> {
        self.check_region(x)?;
        let mut parts = Vec::new();
        let visible = self.bsp.query_parts(x, Fragment::whole(), Some(&mut parts));
        Ok((parts, self.proven_at(x).then_some(visible.slack)))
    }

    /// Whether the tree's answer at `x` is `x`'s exact one up to the query's rounding: no
    /// occluder was cut or dropped as degenerate, and `x` lies between those behind the
    /// receiver's plane and those in front of it ([`Slab`]).
    fn proven_at(&self, x: DVec3) -> bool {
        let (plane, normal_error) = self.light_plane;
        let (h, e) = plane.height_with_error(x, normal_error);
        h > e
            && in_range(x)
            && self
                .slab
                .holds_at(self.toward_light.height_with_error(x, DVec3::ZERO))
    }

    /// The irradiance at `x` (a point of the receiver's plane, with the normal `normal`:
    /// any length) from the light's parts above its horizon, as form factors by Lambert's
    /// formula ([`form_factor`]): from the visible parts, and from all of them as if no
    /// occluder stood in the way. Times `π L`, for a Lambertian light of radiance `L`, they
    /// are irradiances; their quotient is the share of the light's irradiance that reaches
    /// `x`, where [`ExactShadows::visible_fraction`] weighs every part of the light alike.
    /// A zero normal gives zeros.
    ///
    /// # Errors
    /// As [`ExactShadows::visible_fraction`].
    pub fn visible_irradiance(
        &mut self,
        x: DVec3,
        normal: DVec3,
    ) -> Result<Irradiance, ExactError> {
        let n = normal.normalize_or_zero();
        let (whole, _) = self.above_horizon(x, Some(n))?;
        if whole.is_empty() {
            return Ok(Irradiance {
                visible: 0.0,
                unoccluded: 0.0,
            });
        }
        let mut parts = Vec::new();
        self.bsp.query_parts(x, whole.clone(), Some(&mut parts));
        let light = self.light;
        let factor = |f: &Fragment| {
            let poly: Vec<DVec3> = f.verts.iter().map(|&[u, v]| light.point(u, v)).collect();
            form_factor(x, n, &poly)
        };
        Ok(Irradiance {
            visible: parts.iter().map(factor).sum(),
            unoccluded: factor(&whole),
        })
    }

    /// The part of the light above `x`'s horizon (possibly empty), once `x` is checked,
    /// and a bound on the area the horizon's rounding may misplace.
    fn above_horizon(
        &mut self,
        x: DVec3,
        normal: Option<DVec3>,
    ) -> Result<(Fragment, f64), ExactError> {
        let tolerance =
            1e-9 * (x - self.receiver.point).length().max(1.0) * self.receiver.normal.length();
        if self.receiver.height(x).abs() > tolerance {
            return Err(ExactError::OffReceiver(x));
        }
        self.check_region(x)?;
        let whole = Fragment::whole();
        let Some(n) = normal else {
            return Ok((whole, 0.0));
        };
        // Above the horizon: (l(u, v) − x) · n ≥ 0.
        let to_corner = self.light.corner - x;
        let s = Affine {
            c0: to_corner.dot(n),
            cu: self.light.edge_u.dot(n),
            cv: self.light.edge_v.dot(n),
        };
        let error = 8.0
            * UNIT
            * (to_corner.abs() + self.light.edge_u.abs() + self.light.edge_v.abs()).dot(n.abs());
        Ok((whole.clip(&s, 1.0), whole.misplaced(&s, error)))
    }

    /// [`ExactError::OutsideRegion`] where `x` lies outside the region.
    fn check_region(&self, x: DVec3) -> Result<(), ExactError> {
        match self.region {
            Some((lo, hi)) if !(lo.cmple(x).all() && x.cmple(hi).all()) => {
                Err(ExactError::OutsideRegion(x))
            }
            _ => Ok(()),
        }
    }

    /// Tells the tree that every later query point lies in the box `[lo, hi]` (a group's
    /// receivers: a tile of the floor, a mesh triangle's bounding box). Insertions then
    /// skip the branches that no line from the light through an occluder to that box can
    /// reach, which makes smaller trees for the same fractions; queries outside the box are
    /// refused ([`ExactError::OutsideRegion`]). The tree restarts from its root.
    ///
    /// # Errors
    /// [`ExactError::BadRegion`] unless `lo ≤ hi` on every axis with finite corners.
    pub fn set_region(&mut self, lo: DVec3, hi: DVec3) -> Result<(), ExactError> {
        if !(lo.is_finite() && hi.is_finite() && lo.cmple(hi).all()) {
            return Err(ExactError::BadRegion(lo, hi));
        }
        self.region = Some((lo, hi));
        self.bsp.set_region(lo, hi);
        Ok(())
    }

    /// Back to the unexpanded tree (every query then pays the whole construction: the
    /// method without coherence).
    pub fn reset(&mut self) {
        self.bsp.reset();
    }

    /// The work so far.
    pub fn work(&self) -> BspWork {
        self.bsp.work
    }

    /// Occluders given, and how many were clipped away (outside the slab) or degenerate.
    pub fn occluder_counts(&self) -> (usize, usize) {
        (self.given, self.dropped)
    }
}

/// The sign of the edge sides of the lines from the light that cross the convex polygon
/// `poly`: that of a reference line from a light point off its plane through its centroid;
/// `0` (both) where the light may lie on both sides of its plane (its enclosing corners
/// `corners` do, [`enclosing_corners`]).
fn stab_sign(light: &Patch, corners: &[DVec3], poly: &[DVec3]) -> i8 {
    let (p0, p1, p2) = (poly[0], poly[1], poly[2]);
    let sides: Vec<i8> = corners.iter().map(|&c| side_sign(p0, p1, p2, c)).collect();
    if sides.contains(&1) && sides.contains(&-1) {
        return 0;
    }
    let centroid = poly.iter().copied().sum::<DVec3>() / poly.len() as f64;
    let from = corners
        .iter()
        .zip(&sides)
        .find(|&(_, &s)| s != 0)
        .map_or(light.center(), |(&c, _)| c);
    let s = side_sign(poly[0], poly[1], from, centroid);
    if s == 0 { 1 } else { s }
}
