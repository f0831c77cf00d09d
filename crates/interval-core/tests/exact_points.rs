//! Tight results at the exact points of elementary functions: where the exact value of a
//! bound is a float, or lies on the known side of one, the bound is that float (the issue's
//! cases and their relatives), for `f64` and `f32`.

use interval_core::{Float, Interval};
use proptest::prelude::*;

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

fn iv32(a: f32, b: f32) -> Interval<f32> {
    Interval::new(a, b).unwrap()
}

#[test]
fn exp_of_non_positive_and_non_negative_intervals() {
    assert_eq!(iv(-1.0, -1e-300).exp().sup(), 1.0);
    assert_eq!(iv(-5.0, 0.0).exp().sup(), 1.0);
    assert_eq!(iv(1e-300, 2.0).exp().inf(), 1.0);
    assert_eq!(iv(0.0, 0.0).exp(), iv(1.0, 1.0));
    assert_eq!(iv32(-1.0, -1e-30).exp().sup(), 1.0);
    assert_eq!(iv32(1e-30, 1.0).exp().inf(), 1.0);
}

#[test]
fn exp2_and_exp10_of_integers() {
    assert_eq!(iv(-1074.0, 1023.0).exp2(), iv(5e-324, 2f64.powi(1023)));
    assert_eq!(iv(-3.0, 10.0).exp2(), iv(0.125, 1024.0));
    assert_eq!(iv(0.0, 22.0).exp10(), iv(1.0, 1e22));
    assert_eq!(iv(-0.5, -1e-200).exp10().sup(), 1.0);
    // Between two integers, the powers bound the result exactly.
    assert!(iv(2.0, 2.0f64.next_up()).exp2().inf() == 4.0);
    assert_eq!(
        iv32(-149.0, 127.0).exp2(),
        iv32(f32::from_bits(1), 2f32.powi(127))
    );
}

#[test]
fn logarithms_of_one_and_exact_powers() {
    assert_eq!(iv(1.0, f64::MAX).log2(), iv(0.0, 1024.0));
    assert_eq!(iv(1.0, f64::MAX).log2().sup(), 1024.0);
    assert_eq!(iv(1.0, 1.0).log(), iv(0.0, 0.0));
    assert_eq!(iv(0.5, 1.0).log().sup(), 0.0);
    assert_eq!(iv(1.0, 2.0).log().inf(), 0.0);
    assert_eq!(iv(5e-324, 0.25).log2(), iv(-1074.0, -2.0));
    assert_eq!(iv(1.0, 1e22).log10(), iv(0.0, 22.0));
    assert_eq!(iv(0.5, 1.0).log10().sup(), 0.0);
    assert_eq!(iv32(1.0, f32::MAX).log2(), iv32(0.0, 128.0));
    assert_eq!(iv32(1.0, 1000.0).log10(), iv32(0.0, 3.0));
}

#[test]
fn pown_of_exact_quotients() {
    // 0.01 (the double) is slightly above 1/100, so 0.01⁻² lies just below 10000.
    assert_eq!(iv(0.01, 2.33).pown(-2).sup(), 10000.0);
    assert_eq!(iv(0.5, 4.0).pown(-3), iv(1.0 / 64.0, 8.0));
    assert_eq!(iv(3.0, 3.0).pown(4), iv(81.0, 81.0));
    assert_eq!(iv(-2.0, 3.0).pown(-4).inf(), 1.0f64.div_down(81.0));
    // 0.01f32 lies below 1/100: its inverse square is just above 10000.
    assert_eq!(
        iv32(0.01, 0.01).pown(-2),
        iv32(10000.0, 10000.0f32.next_up())
    );
    assert_eq!(
        iv(0.1, 0.1).pown(3).inf(),
        iv(0.1, 0.1).pown(3).sup().next_down()
    );
}

proptest! {
    /// The range facts hold on random intervals: `exp ≤ 1` on `x ≤ 0`, `≥ 1` on `x ≥ 0`;
    /// `log2` of `[2ᵏ, 2ᵏ⁺¹)` stays in `[k, k + 1]`; `log ≤ 0` below 1.
    #[test]
    fn range_facts(a in -50.0f64..50.0, b in -50.0f64..50.0, m in 1.0f64..2.0, k in -1020i32..1020) {
        let x = iv(a.min(b), a.max(b));
        if x.sup() <= 0.0 {
            prop_assert!(x.exp().sup() <= 1.0);
        }
        if x.inf() >= 0.0 {
            prop_assert!(x.exp().inf() >= 1.0);
        }
        let v = m * 2f64.powi(k);
        let l = iv(v, v).log2();
        prop_assert!(l.inf() >= f64::from(k) && l.sup() <= f64::from(k) + 1.0, "log2({v:e}) = {l:?}");
        if v < 1.0 {
            prop_assert!(iv(v, v).log().sup() <= 0.0);
        }
    }
}
