//! The exact method as a soft-shadow method of the renderer (`exact`, `exact:D`): the
//! scene's triangles by the lazy BSP in Plücker space, the implicit surfaces by shadow
//! beams over the visible fragments.

use glam::DVec3;

use super::fragment::{Affine, Fragment};
use super::group::{ExactShadows, Plane};
use crate::beam::BoxClass;
use crate::shadow::hard::Visibility;
use crate::shadow::method::{LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork};
use crate::shadow::stochastic::Stochastic;

/// Halvings of a visible fragment against the implicit surfaces of `exact` without a
/// depth.
pub const DEFAULT_DEPTH: u32 = 8;

/// Shadow segments of the estimate where the BSP cannot be built for a point (a point in
/// the light's own plane).
const FALLBACK_SAMPLES: u32 = 64;

/// The exact method of seed 003 for one point and light at a time.
///
/// 1. **Shaft culling**: the triangles whose box meets the box of the point and the light
///    ([`Occluders::triangles`]).
/// 2. **The BSP**: the point's receiver plane is the plane through it parallel to the
///    light, the occluders are those triangles clipped to the slab between it and the
///    light, and the tree is grown for that one point (its region is the point, so an
///    insertion goes only where the lines through the point reach). Its visible fragments
///    are the parts of the light that no triangle hides, exact up to the rounding of the
///    fragments' vertices.
/// 3. **Implicit occluders**: one shadow beam over the whole light against the implicit
///    surfaces alone ([`Occluders::implicit_beam`]); where it is not rejected, each
///    visible fragment's beam (over its bounding rectangle) is rejected (visible), proven
///    blocked, or halved along its longer side, `depth` times at most; a piece left open
///    counts between 0 and its area, and its estimate is one shadow segment to its
///    centroid.
///
/// The visible fraction is the visible fragments' area. Its bounds are proven where no
/// triangle lies in the shaft (the fragments are then halves of the parameter square, of
/// exact areas, and every test is a proof); the areas of fragments cut by triangle edges are
/// not proven, so a point that a triangle may shade carries no certificate (`[0, 1]`).
///
/// The paper gives no formula for the irradiance over the visible parts; the renderer
/// shades a point with the light's colour times the visible fraction at the light's centre
/// direction (the same Phong model as every other method).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Exact {
    /// Halvings of a visible fragment against the implicit surfaces.
    pub depth: u32,
}

/// What the refinement against the implicit surfaces has summed.
#[derive(Default)]
struct Sums {
    /// Area proven visible.
    lower: f64,
    /// Area not proven blocked.
    upper: f64,
    /// The estimate.
    estimate: f64,
}

impl Exact {
    /// Tests the fragment `f` against the implicit surfaces, `depth` halvings left.
    fn refine(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        (f, depth): (Fragment, u32),
        sums: &mut Sums,
        work: &mut ShadowWork,
    ) {
        let area = f.area();
        let (lo, hi) = bounding_rect(&f);
        let part = q.light.part(lo[0], hi[0], lo[1], hi[1]);
        work.sub_beams += 1;
        match occluders.implicit_beam(q.origin, &part, 0.0, true, &mut work.root) {
            BoxClass::Miss => {
                sums.lower += area;
                sums.upper += area;
                sums.estimate += area;
            }
            BoxClass::Hit { .. } => {}
            BoxClass::Undecided { .. } if depth == 0 => {
                sums.upper += area;
                let centroid = f
                    .verts
                    .iter()
                    .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
                let n = f.verts.len() as f64;
                let to = q.light.point(centroid[0] / n, centroid[1] / n);
                work.rays += 1;
                if occluders
                    .segment(q.origin, to, 0.0, &mut work.root)
                    .visibility
                    == Visibility::Lit
                {
                    sums.estimate += area;
                }
            }
            BoxClass::Undecided { .. } => {
                // Halve along the longer side of the rectangle, at its middle.
                let axis = usize::from(hi[1] - lo[1] > hi[0] - lo[0]);
                let mid = 0.5 * (lo[axis] + hi[axis]);
                let cut = Affine {
                    c0: -mid,
                    cu: if axis == 0 { 1.0 } else { 0.0 },
                    cv: if axis == 1 { 1.0 } else { 0.0 },
                };
                for sign in [-1.0, 1.0] {
                    let piece = f.clip(&cut, sign);
                    if !piece.is_empty() {
                        self.refine(occluders, q, (piece, depth - 1), sums, work);
                    }
                }
            }
        }
    }
}

/// The smallest rectangle of parameters holding the fragment.
fn bounding_rect(f: &Fragment) -> ([f64; 2], [f64; 2]) {
    f.verts.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        },
    )
}

impl ShadowMethod for Exact {
    fn name(&self) -> String {
        if self.depth == DEFAULT_DEPTH {
            "exact".into()
        } else {
            format!("exact:{}", self.depth)
        }
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        let x = q.origin;
        let triangles = occluders.triangles(x, &q.light);
        let parts = if triangles.is_empty() {
            vec![Fragment::whole()]
        } else {
            work.shaft_triangles += triangles.len() as u64;
            let polygons: Vec<Vec<DVec3>> = triangles.iter().map(|t| t.to_vec()).collect();
            let receiver = Plane {
                point: x,
                normal: q.light.edge_u.cross(q.light.edge_v),
            };
            let built =
                ExactShadows::new(q.light, receiver, &polygons, q.seed).and_then(|mut e| {
                    e.set_region(x, x)?;
                    let parts = e.visible_parts(x, None);
                    work.bsp.add(&e.work());
                    parts
                });
            match built {
                Ok(parts) => parts,
                // The point lies in the light's plane: no slab separates them.
                Err(_) => {
                    let fallback = Stochastic {
                        samples: FALLBACK_SAMPLES,
                        cache: false,
                    };
                    return fallback.visibility(occluders, q, work);
                }
            }
        };
        work.queries += 1;
        let visible: f64 = parts.iter().map(Fragment::area).sum();
        // The implicit surfaces: one beam over the whole light first.
        work.initial_beams += 1;
        let whole = occluders.implicit_beam(x, &q.light, 0.0, true, &mut work.root);
        let sums = match whole {
            BoxClass::Miss => Sums {
                lower: visible,
                upper: visible,
                estimate: visible,
            },
            // Every ray to the light is blocked, whatever the triangles do.
            BoxClass::Hit { .. } => {
                work.umbra_proofs += 1;
                return LightVisibility::UMBRA;
            }
            BoxClass::Undecided { .. } => {
                work.initial_occluded += 1;
                let mut sums = Sums::default();
                for f in parts {
                    self.refine(occluders, q, (f, self.depth), &mut sums, work);
                }
                sums
            }
        };
        let clamp = |v: f64| v.clamp(0.0, 1.0) as f32;
        if triangles.is_empty() {
            LightVisibility {
                fraction: clamp(sums.estimate),
                lower: clamp(sums.lower),
                upper: clamp(sums.upper),
            }
        } else {
            LightVisibility::estimate(clamp(sums.estimate))
        }
    }
}
