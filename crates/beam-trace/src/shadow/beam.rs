//! Soft shadows with interval shadow beams (the reliable soft-shadow paper).
//!
//! A shadow beam from a point over (a part of) the light is the set of segments from the
//! point to every point of that part. Its rejection test proves that none of them meets a
//! surface, thin features included.
//!
//! * [`Strategy::Initial`]: one beam over the whole light first. Rejected: the point is
//!   proven fully lit and costs nothing more. Otherwise the light is split into `n × n`
//!   cells and a sub-beam is traced to each; the visible fraction is the share of rejected
//!   sub-beams (a proven lower bound of the true fraction).
//! * [`Strategy::All`]: the `n × n` sub-beams for every point, the paper's baseline.
//! * [`Strategy::Quadtree`]: the cells are visited as a quadtree from the whole light down;
//!   a rejected beam clears all the cells under it (sub-beams of a rejected beam would be
//!   rejected too: interval evaluation is inclusion monotone), at a different cost.
//!
//! A beam that is not rejected clears every one of its rays up to its first undecided piece,
//! and the beams under it start there. The three strategies therefore cut the parameter
//! range differently and can differ on a few grazing cells; each fraction is a proven lower
//! bound of the true one.

use glam::DVec3;

use super::method::{BeamStart, LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork};
use super::patch::Patch;
use super::spec::ShadowSpec;
pub use super::spec::Strategy;
use crate::beam::{BeamSettings, BoxClass};
use crate::sample::SHADOW_OFFSET;

/// Width of a shadow beam's final pieces relative to their parameter (see
/// [`BeamSettings::rel_epsilon`]).
const SHADOW_REL_EPSILON: f64 = 1.0 / 16.0;

/// The beam tolerances of a shadow beam from `from` over `light` (`t ∈ [0, 1]`) in a scene
/// whose bounds have the diagonal `diagonal`, from the primary beams' `base`: pieces down to
/// a tenth of the shadow offset in length, so that the first piece can be cleared of the
/// surface the beam leaves; no `T_final` refinement. Every backend searches shadow beams
/// with these.
pub fn shadow_beam_settings(
    base: &BeamSettings,
    diagonal: f64,
    from: DVec3,
    light: &Patch,
) -> BeamSettings {
    let reach = light
        .corners()
        .iter()
        .map(|c| c.distance(from))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let offset = SHADOW_OFFSET * diagonal;
    BeamSettings {
        epsilon: 0.1 * offset / reach,
        rel_epsilon: SHADOW_REL_EPSILON,
        refine_steps: 0,
        ..*base
    }
}

/// Final pieces of a beam inside an outer one ([`BeamStart::Finer`]) are at most this share
/// of the part's angular size long, relative to their parameter (and never longer than
/// [`SHADOW_REL_EPSILON`]).
const INNER_REL_EPSILON: f64 = 0.25;

/// Look-ahead steps of a beam inside an outer one: its final pieces are shorter, so it
/// takes more steps to look as far ([`BeamSettings::look_ahead`]).
const INNER_LOOK_AHEAD: u32 = 12;

/// The settings of a shadow beam from `from` over `light` (a part of a light) inside an outer
/// beam: final pieces no longer than a quarter of the part's angular size relative to their
/// parameter, and a look-ahead of more steps. Deep in a subdivision of the light a piece
/// `1/16` of its parameter long is many times longer than the beam is wide, and where the beam
/// grazes a surface its enclosure keeps both signs at any depth. On
/// `scenes/soft-shadows.toml` at 128 × 96, `certified:0.05:1024:1`: 7,466 pixels certified
/// instead of 7,204, the widest bound 0.18 instead of 0.48, 654 k sub-beams instead of
/// 995 k, in 1.7 times the time (finer pieces alone, with the default look-ahead, whose
/// reach shrank with them: 7,034 pixels, widest 0.99). Not used by the exact method's
/// pieces ([`BeamStart::Near`]): on `scenes/meshes.toml` it gave the same estimate with
/// tighter bounds in 1.4 times the time.
pub fn inner_beam_settings(outer: &BeamSettings, from: DVec3, light: &Patch) -> BeamSettings {
    let corners = light.corners();
    let nearest = corners
        .iter()
        .map(|c| c.distance(from))
        .fold(f64::INFINITY, f64::min)
        .max(f64::MIN_POSITIVE);
    let size = corners[0]
        .distance(corners[2])
        .max(corners[1].distance(corners[3]));
    BeamSettings {
        rel_epsilon: outer.rel_epsilon.min(INNER_REL_EPSILON * size / nearest),
        look_ahead: outer.look_ahead.max(INNER_LOOK_AHEAD),
        ..*outer
    }
}

/// The beam method with `n × n` sub-beams.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct BeamShadows {
    /// Sub-beams per side of the light.
    pub n: u32,
    /// How sub-beams are spent.
    pub strategy: Strategy,
}

impl ShadowMethod for BeamShadows {
    fn name(&self) -> String {
        ShadowSpec::Beam {
            n: self.n,
            strategy: self.strategy,
        }
        .to_string()
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        work.queries += 1;
        match self.strategy {
            Strategy::All => sub_beams(occluders, q, 0.0, self.n, work),
            Strategy::Initial => {
                work.initial_beams += 1;
                match occluders.beam(
                    q.origin,
                    &q.light,
                    BeamStart::At(0.0),
                    false,
                    &mut work.root,
                ) {
                    BoxClass::Miss => LightVisibility::LIT,
                    other => {
                        work.initial_occluded += 1;
                        sub_beams(occluders, q, cleared(&other), self.n, work)
                    }
                }
            }
            Strategy::Quadtree => {
                let mut free = 0u64;
                let n = self.n;
                quadtree(occluders, q, (0, n), (0, n), 0.0, n, &mut free, work);
                fraction(free, n)
            }
        }
    }
}

/// How far a beam over the light cleared every ray: the start of its first undecided
/// range (0 when it did not say).
pub fn cleared(class: &BoxClass) -> f64 {
    BeamStart::inside(class).at()
}

/// The `n × n` sub-beams of `q`, searched from `start` on: the share of them proven free
/// (also the Minkowski method's fine step with beams).
pub fn sub_beams(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    start: f64,
    n: u32,
    work: &mut ShadowWork,
) -> LightVisibility {
    let mut free = 0u64;
    for j in 0..n {
        for i in 0..n {
            work.sub_beams += 1;
            let cell = q.light.cell(i, j, n);
            if occluders.beam(q.origin, &cell, BeamStart::At(start), false, &mut work.root)
                == BoxClass::Miss
            {
                free += 1;
            }
        }
    }
    fraction(free, n)
}

/// The visible fraction from `free` rejected cells of `n × n`: a proven lower bound.
fn fraction(free: u64, n: u32) -> LightVisibility {
    let total = u64::from(n) * u64::from(n);
    if free == total {
        return LightVisibility::LIT;
    }
    let f = free as f32 / total as f32;
    LightVisibility {
        fraction: f,
        lower: f,
        upper: 1.0,
    }
}

/// Visits the cells `[i0, i1) × [j0, j1)` of the `n × n` grid: one beam over their union
/// (from `start`, where the parent beam cleared every ray); rejected, they are all free;
/// else the four quadrants, down to single cells.
#[allow(clippy::too_many_arguments)]
fn quadtree(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    (i0, i1): (u32, u32),
    (j0, j1): (u32, u32),
    start: f64,
    n: u32,
    free: &mut u64,
    work: &mut ShadowWork,
) {
    let k = f64::from(n);
    let part = q.light.part(
        f64::from(i0) / k,
        f64::from(i1) / k,
        f64::from(j0) / k,
        f64::from(j1) / k,
    );
    let whole = (i0, i1, j0, j1) == (0, n, 0, n);
    if whole {
        work.initial_beams += 1;
    } else {
        work.sub_beams += 1;
    }
    let class = occluders.beam(q.origin, &part, BeamStart::At(start), false, &mut work.root);
    if class == BoxClass::Miss {
        *free += u64::from(i1 - i0) * u64::from(j1 - j0);
        return;
    }
    let start = cleared(&class);
    if whole {
        work.initial_occluded += 1;
    }
    if i1 - i0 == 1 && j1 - j0 == 1 {
        return;
    }
    let (im, jm) = ((i0 + i1).div_ceil(2), (j0 + j1).div_ceil(2));
    for (ia, ib) in [(i0, im), (im, i1)] {
        for (ja, jb) in [(j0, jm), (jm, j1)] {
            if ia < ib && ja < jb {
                quadtree(occluders, q, (ia, ib), (ja, jb), start, n, free, work);
            }
        }
    }
}
