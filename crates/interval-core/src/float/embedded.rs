//! Directed rounding (of `f64` and, in [`single`], `f32`) by AVX-512 embedded rounding control, compiled in when the build
//! enables the `avx512f` target feature (for example `-C target-cpu=x86-64-v4` or
//! `-C target-cpu=native` on such a CPU).
//!
//! AVX-512 encodes the rounding direction in each instruction (`{rd-sae}`, `{ru-sae}`), so a
//! directed sum costs what a rounded-to-nearest one does: no error-free transformation sits
//! on the dependency chain, which matters when a tape of dependent interval operations is
//! evaluated. The results are IEEE 754 directed roundings, i.e. exactly the tight bounds the
//! error-free transformations compute; the callers in `f64_impl` use them only when they are
//! nonzero and finite, and defer to the portable code for zeros (whose signs follow this
//! crate's conventions), infinities and NaN, so every result is bit-identical with or
//! without the feature.

use core::arch::x86_64::{
    __m128, __m128d, _MM_FROUND_NO_EXC, _MM_FROUND_TO_NEG_INF, _MM_FROUND_TO_POS_INF,
    _mm_add_round_sd, _mm_add_round_ss, _mm_cvtsd_f64, _mm_cvtss_f32, _mm_div_round_sd,
    _mm_div_round_ss, _mm_fmadd_round_sd, _mm_fmadd_round_ss, _mm_mul_round_sd, _mm_mul_round_ss,
    _mm_set_sd, _mm_set_ss, _mm_sqrt_round_sd, _mm_sqrt_round_ss,
};

const DOWN: i32 = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
const UP: i32 = _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC;

#[inline(always)]
fn scalar(x: __m128d) -> f64 {
    // SAFETY: SSE2 is part of x86-64.
    unsafe { _mm_cvtsd_f64(x) }
}

#[inline(always)]
fn vector(x: f64) -> __m128d {
    // SAFETY: SSE2 is part of x86-64.
    unsafe { _mm_set_sd(x) }
}

macro_rules! binary {
    ($name:ident, $intrinsic:ident, $mode:ident) => {
        binary!($name, $intrinsic, $mode, f64);
    };
    ($name:ident, $intrinsic:ident, $mode:ident, $t:ty) => {
        #[doc = concat!("`", stringify!($intrinsic), "` with rounding `", stringify!($mode), "`.")]
        #[inline(always)]
        pub(in crate::float) fn $name(a: $t, b: $t) -> $t {
            // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
            scalar(unsafe { $intrinsic::<$mode>(vector(a), vector(b)) })
        }
    };
}

binary!(add_down, _mm_add_round_sd, DOWN);
binary!(add_up, _mm_add_round_sd, UP);
binary!(mul_down, _mm_mul_round_sd, DOWN);
binary!(mul_up, _mm_mul_round_sd, UP);
binary!(div_down, _mm_div_round_sd, DOWN);
binary!(div_up, _mm_div_round_sd, UP);

/// `√a` rounded toward −∞.
#[inline(always)]
pub(super) fn sqrt_down(a: f64) -> f64 {
    // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
    scalar(unsafe { _mm_sqrt_round_sd::<DOWN>(vector(a), vector(a)) })
}

/// `√a` rounded toward +∞.
#[inline(always)]
pub(super) fn sqrt_up(a: f64) -> f64 {
    // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
    scalar(unsafe { _mm_sqrt_round_sd::<UP>(vector(a), vector(a)) })
}

/// `a·b + c` rounded toward −∞.
#[inline(always)]
pub(super) fn fma_down(a: f64, b: f64, c: f64) -> f64 {
    // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
    scalar(unsafe { _mm_fmadd_round_sd::<DOWN>(vector(a), vector(b), vector(c)) })
}

/// `a·b + c` rounded toward +∞.
#[inline(always)]
pub(super) fn fma_up(a: f64, b: f64, c: f64) -> f64 {
    // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
    scalar(unsafe { _mm_fmadd_round_sd::<UP>(vector(a), vector(b), vector(c)) })
}

/// The same operations on `f32`.
pub(super) mod single {
    use super::*;

    #[inline(always)]
    fn scalar(x: __m128) -> f32 {
        // SAFETY: SSE is part of x86-64.
        unsafe { _mm_cvtss_f32(x) }
    }

    #[inline(always)]
    fn vector(x: f32) -> __m128 {
        // SAFETY: SSE is part of x86-64.
        unsafe { _mm_set_ss(x) }
    }

    binary!(add_down, _mm_add_round_ss, DOWN, f32);
    binary!(add_up, _mm_add_round_ss, UP, f32);
    binary!(mul_down, _mm_mul_round_ss, DOWN, f32);
    binary!(mul_up, _mm_mul_round_ss, UP, f32);
    binary!(div_down, _mm_div_round_ss, DOWN, f32);
    binary!(div_up, _mm_div_round_ss, UP, f32);

    /// `√a` rounded toward −∞.
    #[inline(always)]
    pub(in super::super) fn sqrt_down(a: f32) -> f32 {
        // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
        scalar(unsafe { _mm_sqrt_round_ss::<DOWN>(vector(a), vector(a)) })
    }

    /// `√a` rounded toward +∞.
    #[inline(always)]
    pub(in super::super) fn sqrt_up(a: f32) -> f32 {
        // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
        scalar(unsafe { _mm_sqrt_round_ss::<UP>(vector(a), vector(a)) })
    }

    /// `a·b + c` rounded toward −∞.
    #[inline(always)]
    pub(in super::super) fn fma_down(a: f32, b: f32, c: f32) -> f32 {
        // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
        scalar(unsafe { _mm_fmadd_round_ss::<DOWN>(vector(a), vector(b), vector(c)) })
    }

    /// `a·b + c` rounded toward +∞.
    #[inline(always)]
    pub(in super::super) fn fma_up(a: f32, b: f32, c: f32) -> f32 {
        // SAFETY: this module is compiled only when `avx512f` is enabled for the build.
        scalar(unsafe { _mm_fmadd_round_ss::<UP>(vector(a), vector(b), vector(c)) })
    }

    /// Whether an embedded-rounding result can be used as is: nonzero and finite.
    #[inline(always)]
    pub(in super::super) fn usable(r: f32) -> bool {
        r != 0.0 && r.is_finite()
    }
}

/// Whether an embedded-rounding result can be used as is: nonzero and finite.
#[inline(always)]
pub(super) fn usable(r: f64) -> bool {
    r != 0.0 && r.is_finite()
}
