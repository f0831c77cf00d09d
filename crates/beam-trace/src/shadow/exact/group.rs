//! One receiver plane and one light: [`ExactShadows`], the tree grown by the queries of its
//! points.

use glam::DVec3;

use super::bsp::{Bsp, Occluder};
use super::fragment::{Affine, Fragment};
use super::irradiance::form_factor;
use super::orient::side_sign;
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
        let light_plane = Plane {
            point: light.corner,
            normal: if ln.dot(receiver.point - light.corner) > 0.0 {
                ln
            } else {
                -ln
            },
        };
        let mut kept = Vec::new();
        let mut dropped = 0;
        let mut kept_first = 0;
        for (k, poly) in first.iter().chain(occluders).enumerate() {
            let clipped = clip(&clip(poly, &light_plane), &receiver_side);
            let scale = poly
                .iter()
                .map(|p| (*p - poly[0]).length_squared())
                .fold(0.0, f64::max);
            if clipped.len() < 3 || twice_area(&clipped) <= 1e-12 * scale {
                dropped += 1;
                continue;
            }
            let stab = stab_sign(&light, &clipped);
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
        Ok(match self.above_horizon(x, normal)? {
            Some(f) => self.bsp.query(x, f),
            None => 0.0,
        })
    }

    /// The visible parts of the light from `x` ([`ExactShadows::visible_fraction`]), as
    /// convex fragments of its parameter square.
    pub(super) fn visible_parts(
        &mut self,
        x: DVec3,
        normal: Option<DVec3>,
    ) -> Result<Vec<Fragment>, ExactError> {
        let mut parts = Vec::new();
        if let Some(f) = self.above_horizon(x, normal)? {
            self.bsp.query_parts(x, f, Some(&mut parts));
        }
        Ok(parts)
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
        let Some(whole) = self.above_horizon(x, Some(n))? else {
            return Ok(Irradiance {
                visible: 0.0,
                unoccluded: 0.0,
            });
        };
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

    /// The part of the light above `x`'s horizon (`None`: nothing), once `x` is checked.
    fn above_horizon(
        &mut self,
        x: DVec3,
        normal: Option<DVec3>,
    ) -> Result<Option<Fragment>, ExactError> {
        let tolerance =
            1e-9 * (x - self.receiver.point).length().max(1.0) * self.receiver.normal.length();
        if self.receiver.height(x).abs() > tolerance {
            return Err(ExactError::OffReceiver(x));
        }
        if let Some((lo, hi)) = self.region
            && !(lo.cmple(x).all() && x.cmple(hi).all())
        {
            return Err(ExactError::OutsideRegion(x));
        }
        let mut f = Fragment::whole();
        if let Some(n) = normal {
            // Above the horizon: (l(u, v) − x) · n ≥ 0.
            let s = Affine {
                c0: (self.light.corner - x).dot(n),
                cu: self.light.edge_u.dot(n),
                cv: self.light.edge_v.dot(n),
            };
            f = f.clip(&s, 1.0);
            if f.is_empty() {
                return Ok(None);
            }
        }
        Ok(Some(f))
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
/// `0` (both) where the light's corners lie on both sides of its plane.
fn stab_sign(light: &Patch, poly: &[DVec3]) -> i8 {
    let (p0, p1, p2) = (poly[0], poly[1], poly[2]);
    let sides = light.corners().map(|c| side_sign(p0, p1, p2, c) as i32);
    if sides.iter().any(|&s| s > 0) && sides.iter().any(|&s| s < 0) {
        return 0;
    }
    let centroid = poly.iter().copied().sum::<DVec3>() / poly.len() as f64;
    let from = light
        .corners()
        .into_iter()
        .zip(sides)
        .find(|&(_, s)| s != 0)
        .map_or(light.center(), |(c, _)| c);
    let s = side_sign(poly[0], poly[1], from, centroid);
    if s == 0 { 1 } else { s }
}
