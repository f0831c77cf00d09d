//! Certified soft shadows: the visible fraction of an area light proven to lie in a bound
//! `[lo, hi]`, refined until `hi − lo` is at most a tolerance, with an estimate inside it.
//!
//! The light is subdivided as a quadtree over its parameters `(u, v)`, largest undecided
//! parts first, in rounds: each round splits as many of them as should bring the bound to
//! the tolerance ([`DECIDED_SHARE`]), the others wait. For each part a shadow beam from
//! the point over the part is searched with the rejection and inclusion tests:
//!
//! * **rejected** ([`BoxClass::Miss`]): no segment from the point to the part meets a
//!   surface, so the whole part is visible: its area is added to `lo`;
//! * **included** ([`BoxClass::Hit`]): every segment meets a surface between the point and
//!   the light (a proven sign change of a continuous `g` on every ray of the beam), so the
//!   whole part is hidden: its area is taken from `hi`;
//! * **undecided**: split into four at the next level (when a round comes to it), each
//!   searched from where the part's beam cleared every ray.
//!
//! The refinement stops when `hi − lo ≤ tolerance`, or when the per-point budget of beams
//! is spent (the bound then stays wider than the tolerance and is reported as it is), or at
//! [`MAX_LEVEL`]. Areas are dyadic, so `lo` and `hi` are exact sums.
//!
//! The estimate that shades the point is `lo` plus, for each part left undecided, its area
//! times the share of stratified shadow segments into it found free: each part's share is
//! an unbiased estimate of its visible part (jittered stratified samples are uniform over
//! the part), and lies in `[0, area]`, so the estimate never leaves `[lo, hi]`. Where more
//! parts are left than segments, the segments are spread over them by area instead, at
//! most one per part, and their share found free estimates the visible share of the parts'
//! whole area (systematic sampling by area with a uniform point in each part: every point
//! of the open area is equally likely, so this is unbiased likewise). Before the
//! segments, a part that would get at least [`SCREEN_MIN_SEGMENTS`] of them is *screened*:
//! its quadrants' beams are searched with the rejection test alone (no inclusion test, no
//! mean-value form: about one segment's cost each), each rejected quadrant is proven
//! visible (added to `lo`, no segment spent on it), and the others share the part's
//! segments. A penumbra point whose light the occluder covers only partly thus spends its
//! segments where the shadow is.
//!
//! Every question is a beam or a segment, asked a round of the refinement at a time, so the
//! method runs in batched rounds ([`super::rounds`]) on any backend: one per round of the
//! refinement, one for the screening and one for the segments.

use super::hard::Visibility;
use super::method::{BeamStart, LightVisibility, Occluders, ShadowMethod, ShadowQuery, ShadowWork};
use super::patch::Patch;
use super::spec::{ShadowSpec, Tolerance};
use super::stochastic::{mix, strata, unit};
use crate::beam::BoxClass;
use crate::root::RootCounters;
use glam::DVec3;
use interval_core::Interval;

/// Deepest level of the subdivision: parts of `2^-MAX_LEVEL` of the light's side.
pub const MAX_LEVEL: u32 = 10;

/// Segments spread over the parts left undecided (shared equally among them, or at most
/// one each where the parts are more). On
/// `scenes/soft-shadows.toml` at 128 × 96 (`accuracy-cost`, reference `stochastic:1024`),
/// `certified:0.5`'s RMSE is 0.0069 with 16, 0.0043 with 32 and 0.0027 with 64, for
/// 1.73, 1.63 and 2.08 times `stochastic:64`'s time (0.0052) in the same runs: 32 is the
/// fewest that estimate inside a bound of width 0.5 as well as 64 stratified samples do
/// over the whole light.
pub const ESTIMATE_SEGMENTS: u32 = 32;

/// The share of a part's area that splitting it is expected to decide: a smooth boundary
/// crossing a part leaves about half its quadrants undecided (on `scenes/soft-shadows.toml`
/// 48 to 60 % of the parts tested at levels 2 to 6 were decided). A round splits the
/// largest undecided parts, only as many as should bring the bound to the tolerance
/// (`certified:0.05`: sub-beams 265,880 → 212,104 and interval evaluations 11.7 M → 8.8 M
/// against splitting every undecided part of a level, every pixel still certified; the
/// mean bound width 4,451 → 5,585 ppm); expecting a quarter saved 2 % more beams in more
/// rounds, expecting twice as much 10 % fewer.
pub const DECIDED_SHARE: f64 = 0.5;

/// An undecided part that would get at least this many of the estimate's segments has its
/// quadrants screened by rejection beams first (each quadrant then has at least 4). On
/// `scenes/soft-shadows.toml` at 128 × 96, `certified:1:1024:64`: 11,764 screening beams
/// (a fifth of the quadrants proven visible) save 63,884 of 211,752 segments; the time
/// 0.45 → 0.44 × `stochastic:64`'s and the RMSE 0.00551 → 0.00492 (`stochastic:64`:
/// 0.00523). Screening again inside screened quadrants (down to 16 parts) cost 17 % more
/// time. With tolerances below 1 and the default 32 segments it takes about the same time
/// and narrows the mean bound (`certified:0.5` 62,764 → 43,642 ppm).
pub const SCREEN_MIN_SEGMENTS: u32 = 16;

/// How many of the open parts a round of the refinement splits: given their levels, largest
/// first, the leading ones whose areas, each expected to decide [`DECIDED_SHARE`] of itself,
/// first cover `need` (the bound's width above the tolerance), at most `affordable` of them and
/// none at [`MAX_LEVEL`]. Zero when `need` is not positive: the refinement is done.
pub fn parts_to_split(
    levels: impl IntoIterator<Item = u32>,
    need: f64,
    affordable: usize,
) -> usize {
    let mut split = 0;
    let mut expected = 0.0;
    for level in levels.into_iter().take(affordable) {
        if need <= 0.0 || level >= MAX_LEVEL || expected >= need {
            break;
        }
        expected += 0.25f64.powi(level as i32) * DECIDED_SHARE;
        split += 1;
    }
    split
}

/// The certified method.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Certified {
    /// Width of the bound at which the refinement stops.
    pub tolerance: Tolerance,
    /// Largest number of beams per point and light.
    pub budget: u32,
    /// Stratified segments of the estimate inside the bound, spread over the parts left
    /// undecided (at most one per part where the parts are more; [`ESTIMATE_SEGMENTS`] by
    /// default).
    pub segments: u32,
}

/// A square part of the light's parameter square: `[i, i + 1] × [j, j + 1]` scaled by
/// `2^-level`, and how the beam of its parent ended (none for the whole light).
#[derive(Copy, Clone, Debug)]
struct Part {
    level: u32,
    i: u32,
    j: u32,
    outer: Option<BoxClass>,
}

impl Part {
    /// The whole light.
    const WHOLE: Part = Part {
        level: 0,
        i: 0,
        j: 0,
        outer: None,
    };

    /// Its share of the light's area (exact: a power of 4).
    fn area(&self) -> f64 {
        0.25f64.powi(self.level as i32)
    }

    /// The part of `light` it stands for.
    fn patch(&self, light: &Patch) -> Patch {
        let (i, j, s) = self.square();
        light.part(i * s, (i + 1.0) * s, j * s, (j + 1.0) * s)
    }

    /// The outward-rounded box of [`Part::patch`]'s exact points ([`Patch::covering_part`]),
    /// so that its beam's proofs hold for all of it despite the part's rounding.
    fn covering_patch(&self, light: &Patch) -> Patch {
        let (i, j, s) = self.square();
        light.covering_part(i * s, (i + 1.0) * s, j * s, (j + 1.0) * s)
    }

    /// Its indices and side in the parameter square.
    fn square(&self) -> (f64, f64, f64) {
        (
            f64::from(self.i),
            f64::from(self.j),
            0.5f64.powi(self.level as i32),
        )
    }

    /// Its four quadrants, searched from where its own beam cleared every ray.
    fn quadrants(&self) -> [Part; 4] {
        let (i, j) = (2 * self.i, 2 * self.j);
        [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(di, dj)| Part {
            level: self.level + 1,
            i: i + di,
            j: j + dj,
            outer: self.outer,
        })
    }

    /// Its beam from `from` over [`Part::covering_patch`] with both tests, searched from
    /// where its parent's beam cleared every ray, with pieces graded from the parent's
    /// undecided piece, and final pieces scaled to its width ([`BeamStart::Finer`]: the
    /// search starts at the scale where the parent's stopped, and decides small parts).
    fn beam(
        &self,
        occluders: &mut dyn Occluders,
        from: DVec3,
        light: &Patch,
        c: &mut RootCounters,
    ) -> BoxClass {
        occluders.beam(from, &self.covering_patch(light), self.start(), true, c)
    }

    /// Where its searches start (its segments from [`BeamStart::at`]: every one is free
    /// before).
    fn start(&self) -> BeamStart {
        self.outer
            .as_ref()
            .map_or(BeamStart::At(0.0), BeamStart::finer_inside)
    }
}

/// The bound and the parts left undecided after the refinement.
struct Refined {
    /// Proven visible share of the light.
    lo: f64,
    /// One minus the proven hidden share.
    hi: f64,
    /// Undecided parts.
    open: Vec<Part>,
    /// Beams searched so far.
    used: u32,
}

impl Certified {
    /// The quadtree refinement of `q` (see the module documentation).
    fn refine(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> Refined {
        let tolerance = self.tolerance.value();
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        // Undecided parts, largest first.
        let mut open: Vec<Part> = Vec::new();
        let mut asked = vec![Part::WHOLE];
        let mut used = 0u32;
        loop {
            for part in &asked {
                used += 1;
                if part.level == 0 {
                    work.initial_beams += 1;
                } else {
                    work.sub_beams += 1;
                }
                let class = part.beam(occluders, q.origin, &q.light, &mut work.root);
                match class {
                    BoxClass::Miss => lo += part.area(),
                    BoxClass::Hit { .. } => {
                        hi -= part.area();
                        if part.level == 0 {
                            work.umbra_proofs += 1;
                        }
                    }
                    // No larger than any part still open (the parts split were the
                    // largest): the order stays largest first.
                    BoxClass::Undecided { .. } => open.push(Part {
                        outer: Some(class),
                        ..*part
                    }),
                }
                if part.level == 0 && class != BoxClass::Miss {
                    work.initial_occluded += 1;
                }
            }
            // The largest parts are split, as many as should bring the bound to the
            // tolerance (and at least one), none at `MAX_LEVEL`: the others wait for the
            // next round.
            let affordable = (self.budget.saturating_sub(used) / 4) as usize;
            let split = parts_to_split(
                open.iter().map(|p| p.level),
                (hi - lo) - tolerance,
                affordable,
            );
            if split == 0 {
                return Refined { lo, hi, open, used };
            }
            asked = open.drain(..split).flat_map(|p| p.quadrants()).collect();
        }
    }

    /// Screens the undecided parts of `r` that would get at least [`SCREEN_MIN_SEGMENTS`]
    /// segments, where the budget of beams allows and none is at [`MAX_LEVEL`]: each
    /// quadrant of such a part whose beam the rejection test proves free is added to `lo`;
    /// the others stay undecided, to be estimated from the part's segments (see the module
    /// documentation).
    fn screen(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        r: &mut Refined,
        work: &mut ShadowWork,
    ) {
        let parts = r.open.len() as u32;
        let beams = 4 * parts;
        if parts == 0
            || self.segments / parts < SCREEN_MIN_SEGMENTS
            || r.used.saturating_add(beams) > self.budget
            || r.open.iter().any(|p| p.level >= MAX_LEVEL)
        {
            return;
        }
        r.used += beams;
        let mut open = Vec::with_capacity(r.open.len() * 4);
        for quadrant in r.open.iter().flat_map(Part::quadrants) {
            work.sub_beams += 1;
            let patch = quadrant.covering_patch(&q.light);
            match occluders.beam(q.origin, &patch, quadrant.start(), false, &mut work.root) {
                BoxClass::Miss => r.lo += quadrant.area(),
                class => open.push(Part {
                    outer: Some(class),
                    ..quadrant
                }),
            }
        }
        r.open = open;
    }
}

/// The estimate inside the bound: `lo` plus the open parts' visible area estimated from
/// `segments` segments, stratified in each part ([`per_part`]) where the parts are no more
/// than the segments, spread over them by area ([`spread`]) where they are more.
fn estimate(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    (r, segments): (&Refined, u32),
    work: &mut ShadowWork,
) -> f64 {
    if r.open.is_empty() {
        return r.lo;
    }
    let visible = if r.open.len() <= segments as usize {
        per_part(occluders, q, (&r.open, segments), work)
    } else {
        spread(occluders, q, (&r.open, segments), work)
    };
    (r.lo + visible).clamp(r.lo, r.hi)
}

/// Whether the segment from the query's point to `to`, searched from where `part`'s beams
/// cleared every ray, is free.
fn free_to(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    (part, to): (&Part, DVec3),
    work: &mut ShadowWork,
) -> bool {
    work.rays += 1;
    let o = occluders.segment(q.origin, to, part.start().at(), &mut work.root);
    o.visibility == Visibility::Lit
}

/// Each part's area times the share of its stratified segments found free, `segments`
/// shared equally among the parts (rounded up): each share is an unbiased estimate of the
/// part's visible share (jittered stratified samples are uniform over the part), and lies
/// in `[0, 1]`.
fn per_part(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    (open, segments): (&[Part], u32),
    work: &mut ShadowWork,
) -> f64 {
    let each = segments.div_ceil(open.len() as u32).max(1);
    let mut visible = 0.0;
    for (k, part) in open.iter().enumerate() {
        let patch = part.patch(&q.light);
        let mut free = 0u32;
        for (u, v) in strata(each, mix(q.seed ^ (k as u64))) {
            free += u32::from(free_to(occluders, q, (part, patch.point(u, v)), work));
        }
        visible += part.area() * f64::from(free) / f64::from(each);
    }
    visible
}

/// More parts than segments: the parts' total area times the share of `segments` segments
/// found free, the segments spread over the parts by area (systematic sampling: the `j`-th
/// at `(j + s) / segments` of the way through the parts' areas laid end to end, for one
/// uniform `s`), each to a uniform point of the part it falls in. Every segment then ends
/// anywhere in the open area with the same density, so the share is an unbiased estimate
/// of its visible share, and no part gets two segments while another may get none by
/// chance alone. At `certified:0.05` the refinement leaves 75 to 100 parts open where the
/// shadow's edge is long: one segment each cost more than the default 32.
fn spread(
    occluders: &mut dyn Occluders,
    q: &ShadowQuery,
    (open, segments): (&[Part], u32),
    work: &mut ShadowWork,
) -> f64 {
    // Exact: the areas are powers of 4 of at most `MAX_LEVEL` levels.
    let total: f64 = open.iter().map(Part::area).sum();
    let seed = mix(q.seed ^ SPREAD_SEED);
    let s = unit(seed);
    let (mut k, mut end) = (0, open[0].area());
    let mut free = 0u32;
    for j in 0..segments {
        let at = (f64::from(j) + s) / f64::from(segments) * total;
        while at >= end && k + 1 < open.len() {
            k += 1;
            end += open[k].area();
        }
        let part = &open[k];
        let h = mix(seed ^ u64::from(j));
        let to = part.patch(&q.light).point(unit(h), unit(mix(h)));
        free += u32::from(free_to(occluders, q, (part, to), work));
    }
    total * f64::from(free) / f64::from(segments)
}

/// Mixed into a query's seed for [`spread`]'s numbers.
const SPREAD_SEED: u64 = 0x5350_5245_4144_0001;

impl ShadowMethod for Certified {
    fn name(&self) -> String {
        ShadowSpec::Certified {
            tolerance: self.tolerance,
            budget: self.budget,
            segments: self.segments,
        }
        .to_string()
    }

    fn tolerance(&self) -> f32 {
        self.tolerance.value() as f32
    }

    fn visibility(
        &self,
        occluders: &mut dyn Occluders,
        q: &ShadowQuery,
        work: &mut ShadowWork,
    ) -> LightVisibility {
        work.queries += 1;
        let mut r = self.refine(occluders, q, work);
        self.screen(occluders, q, &mut r, work);
        let fraction = estimate(occluders, q, (&r, self.segments), work);
        // Outward to f32 (exact for the dyadic areas of at most `MAX_LEVEL` levels).
        let bound = Interval::new_unchecked(r.lo, r.hi).cast::<f32>();
        LightVisibility {
            fraction: (fraction as f32).clamp(bound.inf(), bound.sup()),
            lower: bound.inf(),
            upper: bound.sup(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow::Occlusion;
    use interval_core::Interval;

    /// Occluders that hide the points of the light with `x + 0.6·z < 0.13` and nothing
    /// else: a straight shadow edge across the light, decided exactly by every beam.
    struct HalfPlane;

    impl HalfPlane {
        fn level(p: DVec3) -> f64 {
            p.x + 0.6 * p.z - 0.13
        }
    }

    impl Occluders for HalfPlane {
        fn segment(&mut self, _: DVec3, to: DVec3, _: f64, _: &mut RootCounters) -> Occlusion {
            let free = HalfPlane::level(to) >= 0.0;
            Occlusion {
                visibility: if free {
                    Visibility::Lit
                } else {
                    Visibility::Occluded
                },
                at: (!free).then_some(0.5),
            }
        }
        fn object_at(&mut self, _: DVec3) -> u32 {
            0
        }
        fn segment_meets_object(
            &mut self,
            _: u32,
            _: DVec3,
            _: DVec3,
            _: &mut RootCounters,
        ) -> bool {
            false
        }
        fn beam(
            &mut self,
            _: DVec3,
            light: &Patch,
            _: BeamStart,
            _: bool,
            _: &mut RootCounters,
        ) -> BoxClass {
            let levels = light.corners().map(HalfPlane::level);
            let t = Interval::new_unchecked(0.5, 0.5);
            if levels.iter().all(|&l| l >= 0.0) {
                BoxClass::Miss
            } else if levels.iter().all(|&l| l < 0.0) {
                BoxClass::Hit { t_final: t }
            } else {
                BoxClass::Undecided { t }
            }
        }
    }

    /// Where more parts stay open than there are segments, the segments spread over them
    /// by area give an estimate inside the bound whose mean over many seeds is the visible
    /// fraction.
    #[test]
    fn segments_spread_over_many_open_parts_estimate_without_bias() {
        let light = Patch::square(DVec3::new(0.0, 4.0, 0.0), 1.0, 1);
        let method = Certified {
            tolerance: Tolerance(50_000),
            budget: 1024,
            segments: 4,
        };
        let query = |seed| ShadowQuery {
            origin: DVec3::ZERO,
            normal: DVec3::Y,
            light,
            seed,
        };
        let mut work = ShadowWork::default();
        let r = method.refine(&mut HalfPlane, &query(0), &mut work);
        assert!(r.hi - r.lo <= 0.05, "[{}, {}]", r.lo, r.hi);
        assert!(r.open.len() > 4, "{} parts open", r.open.len());
        // The visible fraction, by the midpoint rule on a fine grid (exact to about 1e-6
        // for a straight edge).
        let n = 1000;
        let visible = (0..n * n)
            .filter(|k| {
                let (i, j) = (k % n, k / n);
                let p = light.point((f64::from(i) + 0.5) / 1e3, (f64::from(j) + 0.5) / 1e3);
                HalfPlane::level(p) >= 0.0
            })
            .count() as f64
            / 1e6;
        assert!(r.lo <= visible && visible <= r.hi);
        // The visible share of the open area, estimated: its mean within 4 standard errors
        // of the truth (a bias of 2 % of it shows).
        let open = r.hi - r.lo;
        let truth = (visible - r.lo) / open;
        let runs = 40_000u32;
        let (mut sum, mut sum_sq) = (0.0, 0.0);
        for seed in 0..u64::from(runs) {
            let e = estimate(&mut HalfPlane, &query(seed), (&r, 4), &mut work);
            assert!(r.lo <= e && e <= r.hi, "{e} outside [{}, {}]", r.lo, r.hi);
            let share = (e - r.lo) / open;
            sum += share;
            sum_sq += share * share;
        }
        let mean = sum / f64::from(runs);
        let sd = (sum_sq / f64::from(runs) - mean * mean).max(0.0).sqrt();
        assert!(sd > 0.0, "the estimate does not vary");
        assert!(
            (mean - truth).abs() <= 4.0 * sd / f64::from(runs).sqrt() + 1e-4,
            "mean share {mean} against {truth} (sd {sd})"
        );
    }
}
