//! The instruction set that hot loops of interval arithmetic run in, chosen when they run.
//!
//! A loop worth it (the tape walks of `implicit-expr`, for example) is compiled twice on
//! x86-64: for the baseline instruction set every x86-64 CPU has (SSE2), and for x86-64-v3
//! (AVX2, FMA, BMI1/2, LZCNT: the CPUs sold since about 2015) by [`dispatch`], and each run
//! takes the second where [`x86_64_v3`] says the CPU has those features. The directed
//! rounding of the interval operations rests on error-free transformations whose products
//! take a fused multiply-add: without FMA in the instruction set it is a call to the C
//! library inside the loop; with it, one instruction. The cheap operations of
//! [`Interval`](crate::Interval) are always inlined so that they are compiled into such a
//! loop's instruction set.
//!
//! Both versions give **bit-identical** results: the same operations in the same order, each
//! correctly rounded (a fused multiply-add is exact before its one rounding, in hardware and
//! in the library alike; no multiply and add are ever fused that the source keeps apart).
//! [`set_limit`] lowers the instruction set for comparisons (benchmarks, and the tests that
//! check the identity).

use std::sync::atomic::{AtomicU8, Ordering};

/// An instruction set the evaluators are compiled for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Isa {
    /// What every CPU of the target architecture has.
    Baseline,
    /// x86-64-v3: AVX2, FMA, BMI1, BMI2, LZCNT (x86-64 only).
    X86_64V3,
}

impl Isa {
    /// The name used in reports: `baseline` or `x86-64-v3`.
    pub fn name(self) -> &'static str {
        match self {
            Isa::Baseline => "baseline",
            Isa::X86_64V3 => "x86-64-v3",
        }
    }

    fn from_u8(v: u8) -> Self {
        if v == Isa::X86_64V3 as u8 {
            Isa::X86_64V3
        } else {
            Isa::Baseline
        }
    }
}

/// The best instruction set this CPU supports among those the evaluators are compiled for.
pub fn detected() -> Isa {
    #[cfg(target_arch = "x86_64")]
    {
        if std::is_x86_feature_detected!("avx2")
            && std::is_x86_feature_detected!("fma")
            && std::is_x86_feature_detected!("bmi1")
            && std::is_x86_feature_detected!("bmi2")
            && std::is_x86_feature_detected!("lzcnt")
        {
            return Isa::X86_64V3;
        }
    }
    Isa::Baseline
}

/// Not yet set: the first query detects.
const UNSET: u8 = u8::MAX;

/// The instruction set in use (`UNSET` until the first query).
static ACTIVE: AtomicU8 = AtomicU8::new(UNSET);

/// The instruction set the evaluations run in: [`detected`], or lower after [`set_limit`].
#[inline]
pub fn active() -> Isa {
    match ACTIVE.load(Ordering::Relaxed) {
        UNSET => {
            let isa = detected();
            ACTIVE.store(isa as u8, Ordering::Relaxed);
            isa
        }
        v => Isa::from_u8(v),
    }
}

/// Makes the evaluations run in at most `limit` from now on, in every thread (never above
/// what the CPU has); returns the instruction set now in use. Results do not change, only
/// their cost: this is for measuring what the instruction set is worth and for testing that
/// the versions agree.
pub fn set_limit(limit: Isa) -> Isa {
    let isa = limit.min(detected());
    ACTIVE.store(isa as u8, Ordering::Relaxed);
    isa
}

/// Runs `f` in code compiled for the instruction set in use: for x86-64-v3 where
/// [`x86_64_v3`] says so, else for the baseline. `f` and what it calls inline (mark the
/// loop's functions `#[inline(always)]`) are compiled twice, once into each version; what
/// they call out of line stays in the crate's own instruction set.
///
/// ```
/// let sum = interval_core::isa::dispatch(
///     #[inline(always)]
///     || (1..=10).map(f64::from).sum::<f64>(),
/// );
/// assert_eq!(sum, 55.0);
/// ```
#[inline(always)]
pub fn dispatch<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(target_arch = "x86_64")]
    if x86_64_v3() {
        // SAFETY: `x86_64_v3` checked that the CPU has the features `in_v3` is compiled for.
        return unsafe { in_v3(f) };
    }
    f()
}

/// `f()` compiled for x86-64-v3.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma,bmi1,bmi2,lzcnt")]
fn in_v3<R>(f: impl FnOnce() -> R) -> R {
    f()
}

/// Whether the x86-64-v3 versions of the loops may run: the CPU has the features (the
/// caller's `unsafe` block relies on that) and [`set_limit`] did not lower the set.
#[inline(always)]
pub fn x86_64_v3() -> bool {
    cfg!(target_arch = "x86_64") && active() == Isa::X86_64V3
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_limit_never_exceeds_the_cpu() {
        let best = detected();
        assert_eq!(set_limit(Isa::Baseline), Isa::Baseline);
        assert_eq!(active(), Isa::Baseline);
        assert_eq!(set_limit(Isa::X86_64V3), best);
        assert_eq!(active(), best);
    }
}
