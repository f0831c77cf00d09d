//! Batch operations against the scalar operations: the results must be bit-identical for
//! every input (empty and unbounded intervals, zeros of both signs, subnormals, overflow,
//! and the magnitudes where the vectorised fast paths hand over to the scalar code).

use interval_core::interval::batch;
use interval_core::{Float, Interval, IntervalError};
use proptest::prelude::*;

/// `2^k` as `f64`.
fn pow2(k: i32) -> f64 {
    2f64.powi(k)
}

/// Bit-for-bit equality of two intervals (any NaN payload counts as the same empty set,
/// but the signs of zero bounds must agree).
fn same<T: Float>(a: Interval<T>, b: Interval<T>) -> bool {
    match (a.bounds(), b.bounds()) {
        (None, None) => true,
        (Some((al, ah)), Some((bl, bh))) => {
            al.to_f64().to_bits() == bl.to_f64().to_bits()
                && ah.to_f64().to_bits() == bh.to_f64().to_bits()
        }
        _ => false,
    }
}

/// Nonnegative magnitudes at and around every threshold of the scalar and batch code.
fn magnitudes() -> Vec<f64> {
    let mut m = vec![
        0.0,
        f64::MIN_POSITIVE_SUBNORMAL,
        3.0 * f64::MIN_POSITIVE_SUBNORMAL,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE.next_down(),
        0.1,
        1.0 / 3.0,
        1.0,
        1.5,
        3.0,
        7.0,
        1e300,
        f64::MAX,
        f64::MAX.next_down(),
        f64::INFINITY,
        // MAX − 4.77e307 is finite, but Knuth's TwoSum overflows in `s − a`.
        4.770813245647214e307,
    ];
    for k in [
        -1074, -1000, -967, -961, -960, -959, -500, -481, -480, -479, -300,
    ] {
        m.push(pow2(k));
        m.push(pow2(k) * 1.000_000_000_000_2);
    }
    for k in [300, 480, 499, 500, 501, 511, 512, 513, 980, 1000, 1023] {
        m.push(pow2(k));
        m.push(pow2(k).next_down());
    }
    m
}

/// Signed values: every magnitude with both signs (and both zeros).
fn values() -> Vec<f64> {
    let mut v = Vec::new();
    for x in magnitudes() {
        v.push(x);
        v.push(-x);
    }
    v
}

/// Intervals built from all ordered pairs of a sample of [`values`], plus the empty set.
fn adversarial_intervals() -> Vec<Interval<f64>> {
    let vals = values();
    let mut out = vec![Interval::EMPTY, Interval::ENTIRE];
    for (i, &a) in vals.iter().enumerate() {
        for &b in vals.iter().skip(i % 3).step_by(3) {
            if let Ok(x) = Interval::new(a.min(b), a.max(b)) {
                out.push(x);
            }
        }
    }
    out
}

type Binary =
    fn(&[Interval<f64>], &[Interval<f64>], &mut [Interval<f64>]) -> Result<(), IntervalError>;
type Unary = fn(&[Interval<f64>], &mut [Interval<f64>]) -> Result<(), IntervalError>;
/// A batch operation with its name and the scalar operation it must reproduce.
type BinaryCase = (
    &'static str,
    Binary,
    fn(Interval<f64>, Interval<f64>) -> Interval<f64>,
);
/// A unary batch operation with its name and scalar counterpart.
type UnaryCase = (&'static str, Unary, fn(Interval<f64>) -> Interval<f64>);

fn check_binary(
    name: &str,
    xs: &[Interval<f64>],
    ys: &[Interval<f64>],
    batch_op: Binary,
    scalar: fn(Interval<f64>, Interval<f64>) -> Interval<f64>,
) {
    let mut out = vec![Interval::ONE; xs.len()];
    batch_op(xs, ys, &mut out).unwrap();
    let mut wrong = 0;
    for i in 0..xs.len() {
        let expected = scalar(xs[i], ys[i]);
        if !same(out[i], expected) {
            if wrong < 10 {
                eprintln!(
                    "{name}: {:?} op {:?}: batch {:?}, scalar {:?}",
                    xs[i], ys[i], out[i], expected
                );
            }
            wrong += 1;
        }
    }
    assert_eq!(wrong, 0, "{name}: {wrong} of {} results differ", xs.len());
}

fn check_unary(
    name: &str,
    xs: &[Interval<f64>],
    batch_op: Unary,
    scalar: fn(Interval<f64>) -> Interval<f64>,
) {
    let mut out = vec![Interval::ONE; xs.len()];
    batch_op(xs, &mut out).unwrap();
    for i in 0..xs.len() {
        let expected = scalar(xs[i]);
        assert!(
            same(out[i], expected),
            "{name}: {:?}: batch {:?}, scalar {:?}",
            xs[i],
            out[i],
            expected
        );
    }
}

const BINARY: [BinaryCase; 4] = [
    ("add", batch::add, Interval::add),
    ("sub", batch::sub, Interval::sub),
    ("mul", batch::mul, Interval::mul),
    ("div", batch::div, Interval::div),
];

const UNARY: [UnaryCase; 2] = [
    ("sqr", batch::sqr, Interval::sqr),
    ("sqrt", batch::sqrt, Interval::sqrt),
];

const ELEMENTARY: [UnaryCase; 4] = [
    ("exp", batch::exp, Interval::exp),
    ("ln", batch::ln, Interval::ln),
    ("sin", batch::sin, Interval::sin),
    ("cos", batch::cos, Interval::cos),
];

#[test]
fn elementary_batches_match_scalar() {
    let ivs = adversarial_intervals();
    for (name, b, s) in ELEMENTARY {
        check_unary(name, &ivs, b, s);
    }
    for n in -4..=5 {
        let mut out = vec![Interval::EMPTY; ivs.len()];
        batch::pown(&ivs, n, &mut out).unwrap();
        for (x, z) in ivs.iter().zip(&out) {
            assert!(same(*z, x.pown(n)), "pown({x:?}, {n})");
        }
    }
    let mut short = vec![Interval::EMPTY; 3];
    assert!(batch::pown(&ivs, 3, &mut short).is_err());
    for (_, b, _) in ELEMENTARY {
        assert!(b(&ivs, &mut short).is_err());
    }
}

/// The same set: equal bounds as numbers (a zero bound may be `+0` in one and `-0` in the
/// other, which IEEE 1788 does not distinguish), or both empty.
fn same_set(a: Interval<f64>, b: Interval<f64>) -> bool {
    a.bounds() == b.bounds()
}

/// The sign-case multiplication gives the same interval as the branch-free one (zeros,
/// infinities, subnormals, every sign class).
#[test]
fn sign_case_mul_equals_mul() {
    let ivs = adversarial_intervals();
    for &x in &ivs {
        for &y in &ivs {
            let (p, q) = (x.mul_sign_cases(y), x.mul(y));
            assert!(same_set(p, q), "{x:?} · {y:?}: sign cases {p:?}, mul {q:?}");
        }
    }
}

#[test]
fn all_pairs_of_adversarial_intervals() {
    let ivs = adversarial_intervals();
    let mut xs = Vec::with_capacity(ivs.len() * ivs.len());
    let mut ys = Vec::with_capacity(ivs.len() * ivs.len());
    for &x in &ivs {
        for &y in &ivs {
            xs.push(x);
            ys.push(y);
        }
    }
    for (name, b, s) in BINARY {
        check_binary(name, &xs, &ys, b, s);
    }
    for (name, b, s) in UNARY {
        check_unary(name, &ivs, b, s);
    }
}

#[test]
fn fast_chunks_with_rare_slow_lanes() {
    // Mostly fast-path lanes, with one slow lane at a different position in each chunk.
    let n = 16 * 40 + 7;
    let slow = [
        Interval::EMPTY,
        Interval::ENTIRE,
        Interval::new(0.0, 1.0).unwrap(),
        Interval::new(-0.0, 0.0).unwrap(),
        Interval::new(f64::MAX, f64::MAX).unwrap(),
        Interval::new(pow2(-1000), pow2(-999)).unwrap(),
    ];
    let xs: Vec<_> = (0..n)
        .map(|i| {
            if i % 17 == 3 {
                slow[i % slow.len()]
            } else {
                let a = (i as f64 * 0.37).sin() * 10.0;
                Interval::new(a, a + 0.1 * (i % 5) as f64 + 1e-9).unwrap()
            }
        })
        .collect();
    let ys: Vec<_> = xs.iter().rev().map(|y| -*y).collect();
    for (name, b, s) in BINARY {
        check_binary(name, &xs, &ys, b, s);
        check_binary(name, &ys, &xs, b, s);
    }
    for (name, b, s) in UNARY {
        check_unary(name, &xs, b, s);
    }
}

#[test]
fn overflow_and_exact_results() {
    let big = Interval::new(f64::MAX.next_down(), f64::MAX).unwrap();
    let xs = vec![big; 20];
    let mut out = vec![Interval::EMPTY; 20];
    batch::add(&xs, &xs, &mut out).unwrap();
    assert!(
        out.iter()
            .all(|z| z.inf() == f64::MAX && z.sup() == f64::INFINITY)
    );
    // Finite sums whose Knuth TwoSum intermediate `s − a` overflows (e.g. MAX − 4.77e307).
    let m = 4.770813245647214e307;
    let xs: Vec<_> = (0..20)
        .map(|i| {
            let a = -m * (1.0 + i as f64 * 1e-3);
            Interval::new(a, a * 0.5).unwrap()
        })
        .collect();
    let mut ys: Vec<_> = (0..20)
        .map(|i| Interval::new(f64::MAX - i as f64 * 1e292, f64::MAX).unwrap())
        .collect();
    batch::add(&xs, &ys, &mut out).unwrap();
    for z in &out {
        assert!(z.inf().is_finite() && z.inf() < z.sup());
    }
    for _ in 0..2 {
        for (b, s) in [
            (batch::add as Binary, Interval::add as fn(_, _) -> _),
            (batch::sub, Interval::sub),
        ] {
            check_binary("near MAX", &xs, &ys, b, s);
            check_binary("near MAX", &ys, &xs, b, s);
        }
        ys.iter_mut().for_each(|y| *y = -*y);
    }
    // x − x with point intervals: exact zeros, +0 for both bounds as in round-to-nearest.
    let xs: Vec<_> = (1..=20)
        .map(|i| Interval::point(i as f64 * 0.1).unwrap())
        .collect();
    batch::sub(&xs, &xs, &mut out).unwrap();
    // (The stored bounds: `inf` itself reads a zero lower bound as −0, IEEE 1788 §12.12.8.)
    for z in &out {
        let (lo, hi) = z.bounds().unwrap();
        assert_eq!(lo.to_bits(), 0.0f64.to_bits());
        assert_eq!(hi.to_bits(), 0.0f64.to_bits());
    }
    // Exact products and quotients: no widening.
    let ys: Vec<_> = (1..=20)
        .map(|i| Interval::point(i as f64).unwrap())
        .collect();
    batch::mul(&ys, &ys, &mut out).unwrap();
    for (i, z) in out.iter().enumerate() {
        let sq = ((i + 1) * (i + 1)) as f64;
        assert_eq!((z.inf(), z.sup()), (sq, sq));
    }
}

#[test]
fn lengths_are_checked_and_out_untouched() {
    let xs = [Interval::<f64>::ONE; 20];
    let mut out = [Interval::ZERO; 19];
    for (name, b, _) in BINARY {
        let err = b(&xs, &xs, &mut out).unwrap_err();
        assert_eq!(
            err,
            IntervalError::LengthMismatch {
                operation: match name {
                    "add" => "batch::add",
                    "sub" => "batch::sub",
                    "mul" => "batch::mul",
                    _ => "batch::div",
                },
                argument: "out",
                expected: 20,
                found: 19
            }
        );
        assert!(b(&xs[..19], &xs, &mut out).is_err());
    }
    for (_, b, _) in UNARY {
        assert!(b(&xs, &mut out).is_err());
    }
    assert!(out.iter().all(|z| *z == Interval::ZERO));
    // Empty slices are fine.
    batch::mul::<f64>(&[], &[], &mut []).unwrap();
}

#[test]
fn f32_batches_match_scalar() {
    let xs: Vec<Interval<f32>> = (0..50)
        .map(|i| {
            let a = (i as f32 * 0.7).sin() * 3.0;
            Interval::new(a, a + (i % 4) as f32 * 0.3).unwrap()
        })
        .collect();
    let ys: Vec<Interval<f32>> = xs.iter().rev().copied().collect();
    let mut out = vec![Interval::EMPTY; xs.len()];
    batch::mul(&xs, &ys, &mut out).unwrap();
    assert!(
        xs.iter()
            .zip(&ys)
            .zip(&out)
            .all(|((x, y), z)| same(*z, *x * *y))
    );
    batch::div(&xs, &ys, &mut out).unwrap();
    assert!(
        xs.iter()
            .zip(&ys)
            .zip(&out)
            .all(|((x, y), z)| same(*z, *x / *y))
    );
    batch::sqrt(&xs, &mut out).unwrap();
    assert!(xs.iter().zip(&out).all(|(x, z)| same(*z, x.sqrt())));
}

/// Doubles biased toward the interesting exponents: near the fast-path limits, the
/// subnormal range, overflow, exact small integers, and plain moderate values.
fn any_bound() -> impl Strategy<Value = f64> {
    let scaled = (
        any::<u64>(),
        prop::sample::select(vec![
            -1074, -1060, -1022, -990, -967, -961, -960, -959, -700, -500, -481, -480, -479, -100,
            -10, -1, 0, 1, 10, 100, 479, 480, 499, 500, 501, 511, 512, 900, 980, 1000, 1020, 1021,
            1022, 1023,
        ]),
    )
        .prop_map(|(bits, k): (u64, i32)| {
            // A random significand in [1, 2) with a random sign, times 2^k (exact or rounded).
            let m = f64::from_bits((bits & 0x800f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
            if k >= -1022 {
                m * pow2(k)
            } else {
                m * pow2(k + 60) * pow2(-60)
            }
        });
    prop_oneof![
        4 => scaled,
        2 => -1e3f64..1e3,
        1 => (-64i32..64).prop_map(f64::from),
        1 => prop::sample::select(values()),
        1 => any::<f64>().prop_filter("not NaN", |x| !x.is_nan()),
    ]
}

fn any_interval() -> impl Strategy<Value = Interval<f64>> {
    (any_bound(), any_bound(), 0u8..20).prop_map(|(a, b, tag)| {
        if tag == 0 {
            Interval::EMPTY
        } else {
            Interval::new(a.min(b), a.max(b)).unwrap_or(Interval::ENTIRE)
        }
    })
}

/// Mostly sign-definite narrow intervals (the fast path), as in real workloads.
fn narrow_interval() -> impl Strategy<Value = Interval<f64>> {
    (any_bound(), 0u32..60).prop_map(|(a, k)| {
        let b = a + a.abs() * pow2(-(k as i32));
        Interval::new(a.min(b), a.max(b)).unwrap_or(Interval::EMPTY)
    })
}

fn operand_vec() -> impl Strategy<Value = Vec<Interval<f64>>> {
    prop::collection::vec(prop_oneof![any_interval(), narrow_interval()], 0..80)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn binary_batches_are_bit_identical(
        xs in operand_vec(),
        ys in operand_vec(),
    ) {
        let n = xs.len().min(ys.len());
        for (name, b, s) in BINARY {
            check_binary(name, &xs[..n], &ys[..n], b, s);
        }
    }

    #[test]
    fn sign_case_mul_is_bit_identical(xs in operand_vec(), ys in operand_vec()) {
        for (x, y) in xs.iter().zip(&ys) {
            let (p, q) = (x.mul_sign_cases(*y), x.mul(*y));
            prop_assert!(same_set(p, q), "{:?} · {:?}: {:?} vs {:?}", x, y, p, q);
        }
    }

    #[test]
    fn unary_batches_are_bit_identical(xs in operand_vec()) {
        for (name, b, s) in UNARY.into_iter().chain(ELEMENTARY) {
            check_unary(name, &xs, b, s);
        }
    }
}
