//! Interval anti-aliasing, IAA (thesis 5.5.2): the estimators that decide whether a proven
//! hit region is shaded once. The pass itself is the pixel-beams pass of the renderer.
//!
//! Each pixel starts as its beam from the screen box structure. A rejected beam is
//! background; a beam that the inclusion test proves to hit everywhere is shaded once if
//! its shading varies little across it, judged by [`shading_variation`] (the thesis's
//! normal-variation estimator of eq. 5.10 judges the surface's curvature instead, which
//! splits curved surfaces whose colour hardly changes). Any other
//! beam is split in four, down to a depth limit; the pixel's colour is the area-weighted
//! sum of its parts.
//!
//! A region shaded once takes one sample's shadow query for each light, so a hard shadow's
//! edge across it would be lost: for each point light whose term in the colour
//! ([`Variation::light_terms`]) could change it by more than the threshold, the shadow
//! beam from the region's points lifted off the surface ([`shadow_origins`]) to the light
//! must be proven free or proven blocked, else the region is split as one whose shading
//! varies (the CPU backend's shading-variation query makes that judgement).
//!
//! At the depth limit, an undecided part is shaded with the first surface its beam may
//! meet: its central ray's hit if it has one, else the point of the central ray in the
//! first parameter range the beam could not reject. So a feature thinner than a pixel
//! that touches any part of the pixel's beam is never lost: the beam cannot be rejected
//! there, and the part is shaded with the feature's surface.

use std::f64::consts::PI;

use glam::DVec3;
use interval_core::Interval;

use crate::ibox::{IBox, ipoint};
use crate::scene::Material;

/// A light as the shading variation sees it: where its direction is taken from, and its
/// colour times intensity.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct LightSource {
    /// The point shading takes the light's direction from.
    pub position: [f64; 3],
    /// Colour times intensity.
    pub color: [f32; 3],
}

/// A cone of directions: every direction of a box of vectors lies within `angle` of `axis`.
#[derive(Copy, Clone, Debug)]
struct Cone {
    axis: DVec3,
    angle: f64,
}

impl Cone {
    /// The cone of the directions of the vectors of `b`: around its centre, with half-angle
    /// `asin(r / |c|)` for the box's half-diagonal `r`; `None` when the box may hold the
    /// zero vector (or is unbounded).
    fn of(b: &IBox) -> Option<Cone> {
        let c = DVec3::new(b[0].mid(), b[1].mid(), b[2].mid());
        let r = DVec3::new(b[0].rad(), b[1].rad(), b[2].rad()).length();
        let len = c.length();
        (len.is_finite() && r.is_finite() && r < len).then(|| Cone {
            axis: c / len,
            angle: (r / len).asin(),
        })
    }

    /// The range of the cosine between a direction of this cone and one of `other`.
    fn cos_range(&self, other: &Cone) -> (f64, f64) {
        let a = self.axis.angle_between(other.axis);
        let d = self.angle + other.angle;
        ((a + d).min(PI).cos(), (a - d).max(0.0).cos())
    }
}

/// One light's factors in the colour over a region.
struct LightTerm {
    /// Colour times intensity.
    color: [Interval<f64>; 3],
    /// The diffuse cosine.
    nl: Interval<f64>,
    /// The highlight's cosine.
    er: Interval<f64>,
}

/// How much the Phong colour ([`phong`](crate::shading::phong)) may vary over a proven hit
/// region, as [`shading_variation`] bounds it.
#[derive(Clone, Debug, PartialEq)]
pub struct Variation {
    /// The largest width, over the colour channels, of the hull of the colours the region
    /// may take, shadows aside.
    pub spread: f64,
    /// For each light, the most it adds to a channel of the colour at a point of the region:
    /// what its shadow may take away there.
    pub light_terms: Vec<f64>,
}

impl Variation {
    /// Unbounded: a region that must be split.
    fn unbounded(lights: usize) -> Variation {
        Variation {
            spread: f64::INFINITY,
            light_terms: vec![f64::INFINITY; lights],
        }
    }
}

/// The spread of the Phong colour ([`phong`](crate::shading::phong)) over a proven hit
/// region: the largest width, over the colour channels, of the hull of the colours that
/// the region's normals, view and light directions allow, for every material in
/// `materials` (the leaves that may shade the region); and each light's largest term in
/// that colour. The normals are the directions of
/// `gradient` (an enclosure of the scene function's gradient over the region), the view
/// directions those from the hit points `region` to the viewpoints `eye`; each set is
/// bounded by a cone around its centre direction, and the cosines of the diffuse and
/// highlight terms by the angles between the cones' axes plus their half-angles (a
/// reflection about a normal in a cone of half-angle θ turns by at most 2θ). Shadows are
/// not part of the spread: a region shaded once takes its one sample's shadow query, and
/// a light's term bounds what its shadow changes.
///
/// Infinite where the region may hold a silhouette (the normal may face both towards and
/// away from the eye), the gradient may vanish, or the enclosures are unbounded. It bounds
/// the spread up to the rounding of the cone angles (an estimate for deciding splits, not a
/// rounded proof).
pub fn shading_variation(
    gradient: IBox,
    region: IBox,
    eye: IBox,
    materials: &[Material],
    ambient: f32,
    lights: &[LightSource],
) -> Variation {
    if materials.is_empty() {
        return Variation::unbounded(lights.len());
    }
    let towards = |to: &IBox| -> IBox { std::array::from_fn(|i| to[i] - region[i]) };
    let (Some(mut n), Some(e)) = (Cone::of(&gradient), Cone::of(&towards(&eye))) else {
        return Variation::unbounded(lights.len());
    };
    // The normal turned towards the eye: one orientation over the whole region.
    let (lo, hi) = n.cos_range(&e);
    if hi < 0.0 {
        n.axis = -n.axis;
    } else if lo <= 0.0 {
        return Variation::unbounded(lights.len());
    }
    let clamp = |(lo, hi): (f64, f64)| Interval::new_unchecked(lo.max(0.0), hi.max(0.0));
    let mut diffuse = [ipoint(f64::from(ambient)); 3];
    let mut terms: Vec<LightTerm> = Vec::new();
    for light in lights {
        let Some(l) = Cone::of(&towards(&light.position.map(ipoint))) else {
            return Variation::unbounded(lights.len());
        };
        let nl = clamp(n.cos_range(&l));
        // r = 2 (n·l) n − l: the reflection of the light's axis about the normal's axis (a
        // unit vector), within 2θ_n + θ_l of it.
        let r = Cone {
            axis: 2.0 * n.axis.dot(l.axis) * n.axis - l.axis,
            angle: 2.0 * n.angle + l.angle,
        };
        let er = clamp(r.cos_range(&e));
        let c = light.color.map(|c| ipoint(f64::from(c)));
        for k in 0..3 {
            diffuse[k] = diffuse[k] + c[k] * nl;
        }
        terms.push(LightTerm { color: c, nl, er });
    }
    // The hull of the colour over every material: leaves of different colours in one
    // region spread the colour as much as shading does.
    let mut hull: [Option<Interval<f64>>; 3] = [None; 3];
    let mut light_terms = vec![0.0f64; lights.len()];
    for m in materials {
        let p = f64::from(m.shininess);
        let power = |b: Interval<f64>| {
            Interval::new_unchecked(b.inf().min(1.0).powf(p), b.sup().min(1.0).powf(p))
        };
        let (kd, ks) = (
            m.color.map(|c| ipoint(f64::from(c))),
            ipoint(f64::from(m.specular)),
        );
        for (k, h) in hull.iter_mut().enumerate() {
            let mut colour = kd[k] * diffuse[k];
            for (term, l) in light_terms.iter_mut().zip(&terms) {
                let highlight = ks * l.color[k] * power(l.er);
                colour = colour + highlight;
                *term = term.max((kd[k] * l.color[k] * l.nl + highlight).sup());
            }
            *h = Some(h.map_or(colour, |h| h.convex_hull(colour)));
        }
    }
    let spread = hull.iter().flatten().map(|h| h.wid()).fold(0.0, f64::max);
    if spread.is_nan() || light_terms.iter().any(|t| t.is_nan()) {
        Variation::unbounded(lights.len())
    } else {
        Variation {
            spread,
            light_terms,
        }
    }
}

/// The products `∇g · (to − p)` of the gradients `gradient` with the directions from the
/// points `region` to the points `to`, over the region: where they keep one sign, every
/// normal of the region turns the same way with respect to `to` (towards it where positive).
pub fn facing(gradient: &IBox, region: &IBox, to: &IBox) -> Interval<f64> {
    (0..3).fold(ipoint(0.0), |d, i| d + gradient[i] * (to[i] - region[i]))
}

/// Where the shadow rays of a region's points start, and how far along them the region's
/// own slab reaches: see [`shadow_origins`].
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct ShadowStarts {
    /// Holds each point's shadow ray origin: the point moved `offset` along its unit
    /// normal turned towards the eye, as
    /// [`Hit::shadow_origin`](crate::sample::Hit::shadow_origin) places a sample's.
    pub origins: IBox,
    /// The unit normals turned towards the eye, over the region.
    pub normals: IBox,
    /// The region's extent along its normals (the largest `Σ |n_i| · wid(region_i)`): a
    /// box of a flat piece of surface holds points up to that far on either side of it.
    pub lift: f64,
    /// The sign that turns the gradients' directions into `normals` (`1.0` or `-1.0`).
    pub side: f64,
}

impl ShadowStarts {
    /// The parameter from which every ray `o + t·d` (`o` in the origins, `d` in `dirs`)
    /// has risen by at least [`lift`](Self::lift) along every normal of the region: past
    /// the region's own slab, where the surface of the region cannot block it. `None` where
    /// some direction may not rise (it grazes or leaves the surface), or the rays do not
    /// clear the slab before `t = 1` (the light lies inside it).
    pub fn clear_from(&self, dirs: &IBox) -> Option<f64> {
        let rise = (0..3).fold(ipoint(0.0), |d, i| d + self.normals[i] * dirs[i]);
        if rise.is_empty() || rise.inf() <= 0.0 {
            return None;
        }
        let t = (ipoint(self.lift) / ipoint(rise.inf())).sup();
        (t < 1.0).then_some(t)
    }
}

/// The shadow-ray starts of the points of `region` (a box holding hit points), each moved
/// along its unit normal turned towards the eye by `offset`, with the region's extent
/// along those normals ([`ShadowStarts`]). The normals are the directions of `gradient` (an
/// enclosure of the scene function's gradient over the region), turned by the sign of their
/// product with the directions to the viewpoints `eye`, in interval arithmetic rounded
/// outward.
///
/// A box of a flat piece of surface holds points on both sides of it, so rays from some of
/// its origins start inside the solid; a shadow beam over the region is searched from
/// [`ShadowStarts::clear_from`] on, where every ray has left the region's slab. Its rays are
/// the samples' own shadow rays (the same lines), without their first stretch.
///
/// `None` where that sign is not one over the region (a silhouette may cross it), the
/// gradient may vanish, or the enclosures are unbounded.
pub fn shadow_origins(
    gradient: &IBox,
    region: &IBox,
    eye: &IBox,
    offset: f64,
) -> Option<ShadowStarts> {
    let facing = facing(gradient, region, eye);
    let side = if facing.inf() > 0.0 {
        1.0
    } else if facing.sup() < 0.0 {
        -1.0
    } else {
        return None;
    };
    let length = (0..3)
        .fold(ipoint(0.0), |d, i| d + gradient[i].sqr())
        .sqrt();
    if length.is_empty() || length.inf() <= 0.0 || !length.sup().is_finite() {
        return None;
    }
    let normals: IBox = std::array::from_fn(|i| ipoint(side) * gradient[i] / length);
    let lift = (0..3)
        .fold(ipoint(0.0), |d, i| {
            d + normals[i].abs() * ipoint(region[i].wid())
        })
        .sup();
    let origins: IBox = std::array::from_fn(|i| region[i] + ipoint(offset) * normals[i]);
    let bounded = |b: &IBox| {
        b.iter()
            .all(|x| !x.is_empty() && x.inf().is_finite() && x.sup().is_finite())
    };
    (bounded(&origins) && bounded(&normals) && lift.is_finite()).then_some(ShadowStarts {
        origins,
        normals,
        lift,
        side,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The box `[c - r, c + r]` on each axis.
    fn around(c: DVec3, r: f64) -> IBox {
        std::array::from_fn(|i| Interval::new(c[i] - r, c[i] + r).expect("ordered bounds"))
    }

    proptest! {
        /// On the unit sphere (`g = |p|² − 1`, gradient `2p`, enclosed over a box by `2·box`)
        /// seen from outside, over a box around a point of it: the origins hold every point
        /// of the sphere in the box moved `offset` along its normal (its own shadow ray's
        /// start), and rays from them to a light outside along the normal have left the
        /// sphere from [`ShadowStarts::clear_from`] on.
        #[test]
        fn origins_hold_the_shadow_starts_and_the_rays_clear_the_solid(
            theta in 0.2f64..2.9,
            phi in 0.0f64..6.2,
            r in 0.0f64..0.05,
            offset in 1e-6f64..1e-2,
        ) {
            let p = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
            let eye = (p * 10.0).to_array().map(ipoint);
            let region = around(p, r);
            let gradient: IBox = std::array::from_fn(|i| ipoint(2.0) * region[i]);
            let starts = shadow_origins(&gradient, &region, &eye, offset)
                .expect("the sphere faces the eye over a small box");
            prop_assert_eq!(starts.side, 1.0);
            let held = |b: &IBox, x: DVec3| (0..3).all(|i| b[i].contains(x[i]));
            for k in 0..16 {
                let u = DVec3::new(
                    f64::from(k % 2) - 0.5,
                    f64::from(k / 2 % 2) - 0.5,
                    f64::from(k / 4 % 2) - 0.5,
                ) * r;
                let q = (p + u).normalize();
                if !held(&region, q) {
                    continue;
                }
                prop_assert!(held(&starts.origins, q + q * offset), "{q:?} in {starts:?}");
            }
            let light = (p * 3.0).to_array().map(ipoint);
            let dirs: IBox = std::array::from_fn(|i| light[i] - starts.origins[i]);
            let t = starts.clear_from(&dirs).expect("a light along the normal clears the slab");
            // Every point of the rays at `t` lies outside the sphere.
            let at: IBox = std::array::from_fn(|i| starts.origins[i] + ipoint(t) * dirs[i]);
            let nearest = (0..3)
                .map(|i| {
                    let x = at[i];
                    if x.inf() > 0.0 {
                        x.inf()
                    } else if x.sup() < 0.0 {
                        -x.sup()
                    } else {
                        0.0
                    }
                })
                .map(|d| d * d)
                .sum::<f64>();
            prop_assert!(nearest > 1.0, "rays at {t} still meet the sphere: {at:?}");
        }
    }

    /// A flat piece of the floor `z = 0` seen from above through a box that reaches below
    /// it: the origins are the box moved up by the offset, the rays to a light above clear
    /// the box's top from `clear_from` on, a light below or in the slab gives none, and a
    /// box whose normal may face either way gives no starts.
    #[test]
    fn rays_from_a_floor_box_clear_its_slab() {
        let region = [
            Interval::new(-0.1, 0.1).unwrap(),
            Interval::new(0.3, 0.4).unwrap(),
            Interval::new(-0.02, 0.02).unwrap(),
        ];
        let gradient = [ipoint(0.0), ipoint(0.0), ipoint(1.0)];
        let eye = [ipoint(0.0), ipoint(-5.0), ipoint(5.0)];
        let starts = shadow_origins(&gradient, &region, &eye, 1e-3).unwrap();
        assert_eq!(starts.side, 1.0);
        assert!(starts.origins[2].inf() <= -0.02 + 1e-3 && starts.origins[2].sup() >= 0.021);
        assert!(starts.lift >= 0.04);
        let dirs_to = |light: [f64; 3]| -> IBox {
            std::array::from_fn(|i| ipoint(light[i]) - starts.origins[i])
        };
        let up = dirs_to([1.0, 2.0, 5.0]);
        let t = starts.clear_from(&up).unwrap();
        let z = starts.origins[2] + ipoint(t) * up[2];
        assert!(z.inf() >= region[2].sup(), "{z:?} at {t}");
        assert!(starts.clear_from(&dirs_to([1.0, 2.0, -5.0])).is_none());
        assert!(starts.clear_from(&dirs_to([0.0, 0.35, 0.01])).is_none());
        // Seen from below, the facing normal points down: the origins go below.
        let below = [ipoint(0.0), ipoint(-5.0), ipoint(-5.0)];
        let under = shadow_origins(&gradient, &region, &below, 1e-3).unwrap();
        assert_eq!(under.side, -1.0);
        assert!(under.origins[2].sup() <= 0.02 - 1e-3 + 1e-12, "{under:?}");
        // An eye in the floor's plane: the normal may face either way.
        let level = [ipoint(0.0), ipoint(-5.0), Interval::new(-0.5, 0.5).unwrap()];
        assert!(shadow_origins(&gradient, &region, &level, 1e-3).is_none());
    }
}
