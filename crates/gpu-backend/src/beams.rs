//! Beams on the GPU: any set of rays `origin + t · dir` whose origin and direction lie in
//! boxes (a primary beam through a pixel or a screen box, a single ray, a shadow segment, a
//! shadow beam over a light or one of its sub-beams), searched over a parameter range with
//! the counter-based non-recursive bisection and classified by the rejection and inclusion
//! tests, as the CPU renderer's beams are ([`beam_trace::beam`]).
//!
//! The inclusion test needs `g` continuous and defined along every ray; the kernel has no
//! definedness tracking, so it runs only for surfaces built from total continuous
//! operations ([`Tape::is_total_and_continuous`]); for the others every beam that is not rejected
//! is reported undecided, which is sound.

use beam_trace::ray::{Beam, IBox};
use bytemuck::{Pod, Zeroable};
use implicit_expr::{Tape, wgsl};
use interval_core::Interval;

use crate::device::Gpu;
use crate::dispatch::Kernel;
use crate::error::GpuError;
use crate::library::INTERVAL_LIBRARY;

const BEAMS_KERNEL: &str = include_str!("wgsl/beams.wgsl");

/// What the GPU proved about one beam.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum GpuClass {
    /// No ray of the beam meets the surface in its parameter range.
    Miss,
    /// Every ray of the beam has its first root in `t`.
    Hit {
        /// The section holding every ray's first root.
        t: Interval<f64>,
    },
    /// The first section that could be neither rejected nor proven (every ray is root-free
    /// before it).
    Undecided {
        /// That section.
        t: Interval<f64>,
    },
}

/// One beam's result.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct GpuBeam {
    /// The class.
    pub class: GpuClass,
    /// Sections evaluated.
    pub steps: u32,
}

/// A beam and the parameter range to search.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct BeamQuery {
    /// The beam.
    pub beam: Beam,
    /// The range of `t` (finite; empty: nothing to search).
    pub t: Interval<f64>,
}

/// Settings of the GPU search.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct KernelSettings {
    /// Width of a final section (absolute, in the ray parameter).
    pub epsilon: f32,
    /// Width of a final section relative to its start `t` (0: only `epsilon`).
    pub rel_epsilon: f32,
    /// Largest number of descents per beam.
    pub max_steps: u32,
    /// Whether to try the inclusion test (proving hits); it runs only when the surface is
    /// total and continuous.
    pub inclusion: bool,
    /// Whether the inclusion test runs on final sections only (and their look-ahead), so
    /// that a proven section is narrow: for a ray whose first root is to be located, not
    /// only proven.
    pub narrow_hits: bool,
}

impl Default for KernelSettings {
    fn default() -> Self {
        Self {
            epsilon: 1e-4,
            rel_epsilon: 0.0,
            max_steps: 4096,
            inclusion: true,
            narrow_hits: false,
        }
    }
}

#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct SceneParams {
    bounds: [[f32; 4]; 2],
    tol: [f32; 4],
    ints: [u32; 4],
}

/// The beam kernel of one scene function.
#[derive(Debug)]
pub struct BeamKernel {
    kernel: Kernel,
    continuous: bool,
    bounds: IBox,
}

impl BeamKernel {
    /// Compiles the kernel for the scene function `tape` (a function of `x y z`) whose
    /// surface lives inside `bounds` (inclusion proofs must place roots there).
    ///
    /// # Errors
    ///
    /// [`GpuError::Expr`] if the tape cannot be written as WGSL, [`GpuError::Validation`]
    /// if the adapter rejects the shader.
    pub fn new(gpu: &Gpu, tape: &Tape, bounds: IBox) -> Result<BeamKernel, GpuError> {
        let generator = wgsl::Generator::new(tape, "surface")?;
        let source = format!(
            "{INTERVAL_LIBRARY}\n{}\n{BEAMS_KERNEL}",
            generator.interval_source()
        );
        Ok(BeamKernel {
            kernel: Kernel::new(gpu, "beam kernel", source, &[])?,
            continuous: tape.is_total_and_continuous(),
            bounds,
        })
    }

    /// Whether the kernel can prove hits (the surface is total and continuous).
    pub fn proves_hits(&self) -> bool {
        self.continuous
    }

    /// Classifies every query.
    ///
    /// # Errors
    ///
    /// [`GpuError`] if the GPU rejects the work or the results cannot be read back.
    pub fn classify(
        &self,
        gpu: &Gpu,
        queries: &[BeamQuery],
        settings: &KernelSettings,
    ) -> Result<Vec<GpuBeam>, GpuError> {
        // Inclusion proofs must place roots inside the bounds: round them inward.
        let b = self.bounds.map(|i| inward_f32(i.inf(), i.sup()));
        // Only bounded ranges can be cut into sections; the others are reported undecided
        // (rejecting them whole would need the search the kernel does not run).
        let bounded = |q: &BeamQuery| q.t.is_empty() || q.t.is_common_interval();
        let searched: Vec<BeamQuery> = queries.iter().copied().filter(bounded).collect();
        let input: Vec<[u32; 16]> = searched.iter().map(encode).collect();
        let out: Vec<[u32; 4]> = self.kernel.map(gpu, &input, |count| {
            let params = SceneParams {
                bounds: [[b[0].0, b[1].0, b[2].0, 0.0], [b[0].1, b[1].1, b[2].1, 0.0]],
                tol: [settings.epsilon, settings.rel_epsilon, 0.0, 0.0],
                ints: [
                    count as u32,
                    settings.max_steps,
                    u32::from(settings.inclusion && self.continuous),
                    u32::from(settings.narrow_hits),
                ],
            };
            bytemuck::bytes_of(&params).to_vec()
        })?;
        let mut results = out.into_iter().map(decode);
        Ok(queries
            .iter()
            .map(|q| {
                if bounded(q) {
                    results.next().expect("one result per searched query")
                } else {
                    GpuBeam {
                        class: GpuClass::Undecided { t: q.t },
                        steps: 0,
                    }
                }
            })
            .collect())
    }
}

/// `[lo, hi]` rounded inward to `f32` (finite bounds clamped to the `f32` range; a bound
/// strictly inside the subnormal range goes to 0).
fn inward_f32(lo: f64, hi: f64) -> (f32, f32) {
    let max = f64::from(f32::MAX);
    let (lo, hi) = (lo.clamp(-max, max), hi.clamp(-max, max));
    let mut l = lo as f32;
    if f64::from(l) < lo {
        l = l.next_up();
    }
    let mut h = hi as f32;
    if f64::from(h) > hi {
        h = h.next_down();
    }
    let normal = |x: f32, inward_is_down: bool| {
        if x != 0.0 && x.abs() < f32::MIN_POSITIVE {
            if (x > 0.0) == inward_is_down {
                0.0
            } else if x > 0.0 {
                f32::MIN_POSITIVE
            } else {
                -f32::MIN_POSITIVE
            }
        } else {
            x
        }
    };
    (normal(l, false), normal(h, true))
}

/// The kernel input of a query: the beam's boxes and its range, rounded outward to `f32`
/// bit patterns; an empty range is sent as `t1 < t0` (nothing to search). Unbounded ranges
/// never reach the kernel ([`BeamKernel::classify`] reports them undecided).
fn encode(q: &BeamQuery) -> [u32; 16] {
    let mut out = [0u32; 16];
    for (k, axis) in q.beam.origin.iter().chain(&q.beam.dir).enumerate() {
        let (lo, hi) = wgsl::enclose_f32(axis.inf(), axis.sup());
        out[2 * k] = lo.to_bits();
        out[2 * k + 1] = hi.to_bits();
    }
    let (t0, t1) = match q.t.bounds() {
        Some((lo, hi)) if lo.is_finite() && hi.is_finite() => {
            let (a, b) = wgsl::enclose_f32(lo, hi);
            // Outward rounding of a finite value may reach infinity, which a kernel may
            // assume absent: keep the f32 range (the search still covers the range).
            (a.max(-f32::MAX), b.min(f32::MAX))
        }
        _ => (1.0, 0.0),
    };
    out[12] = t0.to_bits();
    out[13] = t1.to_bits();
    out
}

fn decode(r: [u32; 4]) -> GpuBeam {
    let t = || {
        let (lo, hi) = (f32::from_bits(r[1]), f32::from_bits(r[2]));
        Interval::new(f64::from(lo), f64::from(hi)).unwrap_or(Interval::EMPTY)
    };
    let class = match r[0] {
        0 => GpuClass::Miss,
        1 => GpuClass::Hit { t: t() },
        _ => GpuClass::Undecided { t: t() },
    };
    GpuBeam { class, steps: r[3] }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_round_inward() {
        let (l, h) = inward_f32(0.1, 0.3);
        assert!(f64::from(l) >= 0.1 && f64::from(h) <= 0.3);
        assert!(f64::from(l.next_down()) < 0.1 && f64::from(h.next_up()) > 0.3);
        assert_eq!(inward_f32(-1e-40, 1e-40), (0.0, 0.0));
        assert_eq!(inward_f32(1e-40, 1.0).0, f32::MIN_POSITIVE);
        assert_eq!(inward_f32(-1e300, 1e300), (-f32::MAX, f32::MAX));
    }
}
