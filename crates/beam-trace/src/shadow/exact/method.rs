//! The exact method as a soft-shadow method of the renderer (`exact`, `exact:D`): the
//! scene's triangles by the lazy BSP in Plücker space, the implicit surfaces by shadow
//! beams over the visible fragments.

use std::time::{Duration, Instant};

use glam::DVec3;
use interval_core::{Float, Interval};

use super::fragment::{Affine, Fragment};
use super::group::{ExactShadows, Plane};
use crate::beam::BoxClass;
use crate::ibox::{IBox, ival, point_box};
use crate::mesh::Shaft;
use crate::shadow::beam::cleared;
use crate::shadow::hard::Visibility;
use crate::shadow::method::{
    BeamStart, LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork,
    triangle_occluders,
};
use crate::shadow::spec::ShadowSpec;
use crate::shadow::stochastic::Stochastic;

/// Shadow segments of the estimate where the BSP cannot be built for a point (a point in
/// the light's own plane).
const FALLBACK_SAMPLES: u32 = 64;

/// The exact method of seed 003, for groups of neighbouring points of one light.
///
/// 1. **Shaft culling**: the triangles that some segment from the group's points to the
///    light may meet ([`Occluders::triangles`]).
/// 2. **The BSP**, one per group of neighbouring queries ([`ShadowMethod::visibility_run`])
///    whose points lie on one plane (within `1e-6` of their distance to the light): the
///    plane parallel to the light, or the first point's tangent plane where the whole light
///    is in front of it (see `group_plane`). That plane is the receiver plane, the occluders
///    are the group's triangles (less the faces of closed meshes turned away from the light)
///    clipped to the region between it and the light's plane, and the tree's region is the
///    box of the points. Each point is queried where it is (off the plane by up to that
///    tolerance); its visible fragments are the parts of the light that no triangle hides,
///    exact up to the rounding of the fragments' vertices where the proof below holds. A
///    point on a curved receiver is a group of its own.
/// 3. **Implicit occluders**: one shadow beam over the whole light against the implicit
///    surfaces alone ([`Occluders::implicit_beam`]); where it is not rejected, each
///    visible fragment's beam (over its bounding rectangle) is rejected (visible), proven
///    blocked, or halved along its longer side, `depth` times at most; a piece left open
///    counts between 0 and its area, and its estimate is one shadow segment to its
///    centroid.
///
/// The visible fraction is the visible fragments' area, and its bounds are proven:
///
/// * where no triangle lies in the group's shaft, or where the point's fragments add up to
///   the whole light and its own shaft holds no triangle: the light is then taken whole,
///   its pieces are halves of the parameter square, of exact areas, and every test is a
///   proof;
/// * elsewhere, the fragments' area widened by the bound on their rounding that the query
///   sums ([`ExactShadows::visible_bounds`]: the band of uncertain sign around each cut,
///   inside the fragment it cuts), where the tree's answer is the point's own: every
///   occluder lies proven on one side of the light's plane and of the receiver's (none is
///   cut there), none is degenerate between them, and the point lies between those in front
///   of the receiver's plane and those behind it. The faces of closed meshes turned away
///   from the light and the squares inside them change no fraction: the index takes them
///   only from closed meshes proven embedded ([`crate::mesh::MeshIndex::turned_away`]);
/// * elsewhere (a wall reaching through the receiver's plane, a point on a ball whose
///   tangent plane the light straddles), not at all: `[0, 1]`.
///
/// A point counts as certified ([`ShadowMethod::tolerance`]) where its bound is at most
/// `1e-6` wide.
///
/// The paper gives no formula for the irradiance over the visible parts. The library's is
/// Lambert's ([`super::form_factor`], [`super::ExactShadows::visible_irradiance`]); the
/// renderer shades a point with the light's colour times the visible fraction at the
/// light's centre direction, the same Phong model as every other method, so that the
/// methods' images and fractions compare.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Exact {
    /// Halvings of a visible fragment against the implicit surfaces.
    pub depth: u32,
    /// Most neighbouring queries sharing one BSP (1: a tree per query, the method without
    /// coherence).
    pub group: u32,
    /// The occluders are the meshes' faces ([`Occluders::faces`]: coplanar neighbours
    /// merged), not their triangles.
    pub faces: bool,
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
    /// A bound on the rounding of the pieces' areas.
    rounding: f64,
    /// The pieces summed.
    pieces: u32,
}

impl Exact {
    /// Tests the fragment `f` against the implicit surfaces, `depth` halvings left, inside
    /// the beam of the piece it was cut from (or of the whole light), which ended as
    /// `outer`: searched from where that beam cleared every ray, with pieces graded from
    /// its undecided piece ([`BeamStart::inside`]).
    fn refine(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        (f, depth, outer): (Fragment, u32, BoxClass),
        sums: &mut Sums,
        work: &mut ShadowWork,
    ) {
        let area = f.area();
        sums.rounding = sums.rounding.add_up(f.area_error());
        sums.pieces += 1;
        let (lo, hi) = f.bounds();
        let part = q.light.covering_part(lo[0], hi[0], lo[1], hi[1]);
        work.sub_beams += 1;
        let start = BeamStart::inside(&outer);
        let class = occluders.implicit_beam(q.origin, &part, start, true, &mut work.root);
        match class {
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
                    .segment(q.origin, to, cleared(&class), &mut work.root)
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
                        self.refine(occluders, q, (piece, depth - 1, class), sums, work);
                    }
                }
            }
        }
    }
}

impl Exact {
    /// The answers of a group of queries of one light whose points share the plane
    /// through the first one with normal `n` ([`group_plane`]): one BSP grown by all of
    /// them, its region their box.
    fn group(
        &self,
        occluders: &mut dyn Occluders,
        (queries, n): (&[ShadowQuery], DVec3),
        work: &mut ShadowWork,
        out: &mut Vec<LightVisibility>,
    ) {
        let first = &queries[0];
        // The box of the points: the tree's region, and the shaft's (every point's own
        // shaft lies in it, so its triangles are among the group's).
        let (lo, hi) = queries
            .iter()
            .fold((first.origin, first.origin), |(lo, hi), q| {
                (lo.min(q.origin), hi.max(q.origin))
            });
        let region: IBox = std::array::from_fn(|k| ival(lo[k], hi[k]));
        let times = &mut work.exact_times;
        let (triangles, inner) = timed(&mut times.shaft, || {
            (
                occluders.triangles(&region, &first.light),
                occluders.inner_occluders(&region, &first.light),
            )
        });
        if triangles.is_empty() {
            for q in queries {
                out.push(self.finish(occluders, q, (vec![Fragment::whole()], Some(0.0)), work));
            }
            return;
        }
        // Faces of closed meshes turned away from the light block nothing that their
        // mesh's other faces do not: the tree needs only the others, each coplanar
        // neighbourhood as one convex face (no edge between two of its triangles to sort).
        work.shaft_triangles += triangles.iter().filter(|t| !t.redundant).count() as u64;
        let polygons = if self.faces {
            timed(&mut times.shaft, || occluders.faces(&triangles))
        } else {
            triangle_occluders(&triangles)
        };
        work.shaft_faces += polygons.len() as u64;
        let receiver = Plane {
            point: first.origin,
            normal: n,
        };
        let built = timed(&mut times.init, || {
            // Squares inside closed meshes first: they close the umbra of their solid in a
            // few cells, and the faces' edges then cut only the rest.
            ExactShadows::with_first(first.light, receiver, &inner, &polygons, first.seed).and_then(
                |mut e| {
                    e.set_region(lo, hi)?;
                    Ok(e)
                },
            )
        });
        let Ok(mut tree) = built else {
            // The points lie in the light's own plane: no slab separates them.
            for q in queries {
                out.push(fallback(occluders, q, work));
            }
            return;
        };
        for q in queries {
            // The point itself, off the plane by up to `GROUP_TOLERANCE`: its answer is its
            // own wherever the tree proves it (`ExactShadows::visible_parts_near`).
            let parts = timed(&mut work.exact_times.queries, || {
                tree.visible_parts_near(q.origin)
            });
            let Ok((parts, slack)) = parts else {
                out.push(fallback(occluders, q, work));
                continue;
            };
            // A point that sees the whole light past the group's triangles (its query met
            // no edge, or its fragments add up to the light up to their rounding) is
            // proven to see it exactly where its own shaft holds none of the triangles
            // (the test itself is the proof, whatever passes it).
            let whole = parts.len() == 1 && parts[0] == Fragment::whole()
                || parts.iter().map(Fragment::area).sum::<f64>() >= 1.0 - WHOLE_SLACK;
            let lit = whole
                && timed(&mut work.exact_times.shaft, || {
                    let own = Shaft::new(&point_box(q.origin), &q.light.bounding_box());
                    !triangles.iter().any(|t| own.may_meet(&t.triangle))
                });
            let answer = if lit {
                self.finish(occluders, q, (vec![Fragment::whole()], Some(0.0)), work)
            } else {
                self.finish(occluders, q, (parts, slack), work)
            };
            out.push(answer);
        }
        work.bsp.add(&tree.work());
    }

    /// The answer of one query from the visible parts of its light past the triangles and
    /// the proven bound on their area's error (`None`: no proof): the implicit surfaces
    /// tested over them.
    fn finish(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        (parts, slack): (Vec<Fragment>, Option<f64>),
        work: &mut ShadowWork,
    ) -> LightVisibility {
        let start = Instant::now();
        let answer = self.against_implicit(occluders, q, (parts, slack), work);
        work.exact_times.implicit += start.elapsed();
        answer
    }

    /// [`Exact::finish`] without its timing.
    fn against_implicit(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        (parts, slack): (Vec<Fragment>, Option<f64>),
        work: &mut ShadowWork,
    ) -> LightVisibility {
        work.queries += 1;
        let visible: f64 = parts.iter().map(Fragment::area).sum();
        // The implicit surfaces: one beam over the whole light first.
        work.initial_beams += 1;
        let start = BeamStart::At(0.0);
        let whole = occluders.implicit_beam(q.origin, &q.light, start, true, &mut work.root);
        let sums = match whole {
            BoxClass::Miss => Sums {
                lower: visible,
                upper: visible,
                estimate: visible,
                rounding: 0.0,
                pieces: 0,
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
                    self.refine(occluders, q, (f, self.depth, whole), &mut sums, work);
                }
                sums
            }
        };
        let clamp = |v: f64| v.clamp(0.0, 1.0);
        let fraction = clamp(sums.estimate) as f32;
        let Some(slack) = slack else {
            return LightVisibility::estimate(fraction);
        };
        // The fragments' areas are off by `slack` at most (the parts they misplace are
        // counted in either sum or in neither), and the pieces' by their rounding; a point
        // proven without the tree (`slack` zero) has the whole light and its halves, whose
        // areas are exact.
        let slack = if slack > 0.0 {
            // The sums of `pieces` terms: `pieces − 1` roundings of at most their total.
            let summing = 2.0 * f64::from(sums.pieces + 1) * f64::EPSILON * sums.upper;
            slack.add_up(sums.rounding).add_up(summing)
        } else {
            0.0
        };
        let bound = Interval::new_unchecked(
            clamp(sums.lower.sub_down(slack)),
            clamp(sums.upper.add_up(slack)),
        )
        .cast::<f32>();
        LightVisibility {
            fraction: fraction.clamp(bound.inf(), bound.sup()),
            lower: bound.inf(),
            upper: bound.sup(),
        }
    }
}

/// The estimate of a point that no slab separates from the light (it lies in the light's
/// plane): stratified shadow segments.
fn fallback(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    work: &mut ShadowWork,
) -> LightVisibility {
    let sampling = Stochastic {
        samples: FALLBACK_SAMPLES,
        cache: false,
    };
    let start = Instant::now();
    let answer = sampling.visibility(occluders, q, work);
    work.exact_times.implicit += start.elapsed();
    answer
}

/// Runs `f`, adding its time to `into`.
fn timed<T>(into: &mut Duration, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let value = f();
    *into += start.elapsed();
    value
}

/// The bound width up to which a point counts as certified (the per-light table's
/// `certified_pixels`): a few `f32` ulps and the fragments' slack.
const CERTIFIED_WIDTH: f32 = 1e-6;

/// How much less than the whole light the visible fragments of a point may add up to for
/// the point to be tested as seeing all of it: the rounding of a few fragments' vertices.
const WHOLE_SLACK: f64 = 1e-9;

/// How far, as a share of its distance to the light's centre, a point may lie off the plane
/// of its group: the points a root search places on a plane (a floor) scatter by about
/// its tolerance. A group's tree clips its occluders to the plane, which is what a point
/// this far off it sees unless an occluder lies that close to the plane (then its answer
/// carries no proof); far less than the offset of shadow origins off their surfaces
/// (`1e-4` of the scene's diagonal).
const GROUP_TOLERANCE: f64 = 1e-6;

/// How wide a group's points may spread, as a share of the diagonal of its light. A tree
/// sorts the lines from the whole region of its points, and each query walks only those
/// through its own point: where the points spread, the tree's cells multiply faster than
/// the queries share them (on a ball under a canopy of 965 leaves at 80 × 60 pixels, runs
/// of 16 points 0.3 wide under a light of side 1 built 15 to 40 thousand nodes per query
/// against 3.7 thousand for a tree per query, and took 2.5 times as long). At this width a
/// group's shaft is wider than a point's by at most a twentieth of the light, at any
/// depth; at higher resolutions the groups fill up again.
const GROUP_EXTENT: f64 = 0.05;

/// The largest angular size of a light (its diagonal over its distance from the group's
/// first point) by which [`GROUP_EXTENT`] widens a group. Beyond it the groups stop
/// widening with the light: each point's own shaft already crosses most occluders near it,
/// and a wider region makes the tree sort every line from it against them. On the furnished
/// hall of 10^5 triangles at 320 × 180 under a light of 10 times the side, groups as wide
/// as a twentieth of the light's diagonal grew 247 M nodes in 227 s, and with this cap (a
/// diagonal of about 20° seen from the group) 165 M in 115 s; at 5 times the side 24 → 18 s
/// (largest tree 876 k → 50 k nodes), at 2 times 2.7 → 2.5 s. The hall's own light (about
/// 20° from the floor under it) groups as before.
const GROUP_ANGLE: f64 = 0.35;

/// How many queries from the first on form its group, and the normal (any length) of
/// their receiver plane: the queries of the first one's light whose points lie on the
/// plane through its point with that normal (within [`GROUP_TOLERANCE`]) and spread no
/// wider than [`GROUP_EXTENT`] of the light's diagonal (of at most [`GROUP_ANGLE`] times
/// its distance). Two
/// planes are tried: the one parallel to the light (a floor under a ceiling light, points
/// of any surface that happen to share it), and the first point's tangent plane where the
/// whole light lies in front of it (a wall, a tilted face of a mesh); the one holding the
/// longer run is the group's, the tangent plane on a tie: it leaves the receiver's own
/// faces behind it, which then neither grow the tree nor stand in the way of a proof (a
/// plane parallel to the light through a point of a ball cuts the ball's faces).
fn group_plane(queries: &[ShadowQuery]) -> (usize, DVec3) {
    let first = &queries[0];
    let light = &first.light;
    let reach = GROUP_TOLERANCE * (light.center() - first.origin).length();
    let distance = (light.center() - first.origin).length();
    let spread = GROUP_EXTENT
        * (light.edge_u + light.edge_v)
            .length()
            .min(GROUP_ANGLE * distance);
    let run = |n: DVec3| {
        let on_plane =
            |q: &ShadowQuery| q.light == *light && (q.origin - first.origin).dot(n).abs() <= reach;
        let (mut lo, mut hi) = (first.origin, first.origin);
        let mut within = |q: &ShadowQuery| {
            (lo, hi) = (lo.min(q.origin), hi.max(q.origin));
            (hi - lo).length() <= spread
        };
        1 + queries[1..]
            .iter()
            .take_while(|q| on_plane(q) && within(q))
            .count()
    };
    let light_normal = light.edge_u.cross(light.edge_v);
    let parallel = light_normal.normalize_or_zero();
    let by_light = (run(parallel), light_normal);
    let tangent = first.normal.normalize_or_zero();
    let light_in_front = tangent != DVec3::ZERO
        && light
            .corners()
            .iter()
            .all(|&c| (c - first.origin).dot(tangent) > 0.0);
    if !light_in_front || tangent == parallel || tangent == -parallel {
        return by_light;
    }
    let by_tangent = (run(tangent), tangent);
    if by_tangent.0 >= by_light.0 {
        by_tangent
    } else {
        by_light
    }
}

impl ShadowMethod for Exact {
    fn name(&self) -> String {
        ShadowSpec::Exact {
            depth: self.depth,
            group: self.group,
            faces: self.faces,
        }
        .to_string()
    }

    /// Its bounds are exact up to rounding: the fragments' slack and the bounds' rounding
    /// to `f32`, far below this.
    fn tolerance(&self) -> f32 {
        CERTIFIED_WIDTH
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        self.visibility_run(occluders, std::slice::from_ref(q), work)
            .pop()
            .expect("one answer per query")
    }

    /// Groups of neighbouring queries on one plane share one BSP
    /// (the coherence of the paper's receiver groups).
    fn visibility_run(
        &self,
        occluders: &mut dyn Occluders,
        queries: &[ShadowQuery],
        work: &mut ShadowWork,
    ) -> Vec<LightVisibility> {
        let mut out = Vec::with_capacity(queries.len());
        let mut rest = queries;
        while !rest.is_empty() {
            let (len, normal) = group_plane(&rest[..rest.len().min(self.group as usize)]);
            self.group(occluders, (&rest[..len], normal), work, &mut out);
            rest = &rest[len..];
        }
        out
    }
}
