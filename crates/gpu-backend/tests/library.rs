//! Soundness of the WGSL interval library on a real adapter: every operation (arithmetic and
//! elementary functions) on 10⁵ random
//! and edge-case inputs per subnormal mode (zeros, subnormals, the smallest normals, powers of
//! two near overflow, the largest finite value, infinities, NaN), read back and checked
//! against the exact range computed on the CPU with interval-core's `f64` intervals. Zero
//! violations allowed: a result must contain the exact range, and no bound may be NaN,
//! infinite or subnormal.
//!
//! The tests run on whatever adapter wgpu finds (in CI, Mesa's lavapipe). With the `CI`
//! environment variable set, a missing adapter fails them; elsewhere they are skipped with
//! the reason printed.

use gpu_backend::library::{BIG, OpInput, OpRunner, bound_to_f64};
use gpu_backend::{Gpu, GpuError};
use implicit_expr::{BinaryOp, Op, UnaryOp};
use interval_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

const TINY: f32 = f32::MIN_POSITIVE;

/// Edge values: signed zeros, subnormals, the smallest normals, powers of two around the
/// guards of the library, the largest finite value, infinities and NaN.
fn specials() -> Vec<f32> {
    let mut v = vec![
        0.0,
        f32::from_bits(1),
        f32::from_bits(0x007f_ffff),
        TINY,
        TINY * 1.5,
        2.0 * TINY,
        2f32.powi(-125),
        2f32.powi(-63),
        1e-20,
        0.1,
        0.5,
        1.0,
        1.0 + f32::EPSILON,
        2.0,
        3.0,
        10.0,
        1e20,
        2f32.powi(63),
        2f32.powi(125),
        2f32.powi(126),
        1.5 * 2f32.powi(126),
        2f32.powi(127),
        f32::MAX / 2.0,
        f32::MAX,
        f32::INFINITY,
    ];
    let neg: Vec<f32> = v.iter().map(|x| -x).collect();
    v.extend(neg);
    v.push(f32::NAN);
    v
}

/// A random `f32` of one of several kinds: any bit pattern, a moderate value, or a value of
/// any exponent.
fn random_value(rng: &mut StdRng, specials: &[f32]) -> f32 {
    match rng.gen_range(0..12) {
        0 => f32::from_bits(rng.r#gen()),
        1 | 2 => specials[rng.gen_range(0..specials.len())],
        10 | 11 => rng.gen_range(-4.0..4.0),
        3..=5 => {
            let m: f32 = rng.gen_range(-10.0..10.0);
            m * 2f32.powi(rng.gen_range(-10..10))
        }
        _ => {
            let m: f32 = rng.gen_range(1.0..2.0);
            let s = if rng.r#gen() { 1.0 } else { -1.0 };
            s * m * 2f32.powi(rng.gen_range(-130..=127))
        }
    }
}

/// An interval's bit patterns from two values: ordered, or (1 in 20) reversed: empty.
fn random_interval(rng: &mut StdRng, specials: &[f32]) -> [u32; 2] {
    let a = random_value(rng, specials);
    let b = if rng.gen_range(0..4) == 0 {
        a
    } else {
        random_value(rng, specials)
    };
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    if rng.gen_range(0..20) == 0 {
        [hi.to_bits(), lo.to_bits()]
    } else {
        [lo.to_bits(), hi.to_bits()]
    }
}

/// The inputs of one operation: every pair of special point intervals, then random ones.
fn inputs(op: Op, n: usize, seed: u64) -> Vec<OpInput> {
    let sp = specials();
    let mut out = Vec::with_capacity(n);
    for &x in &sp {
        for &y in &sp {
            let b = match op {
                Op::Pown => [0, 0],
                _ => [y.to_bits(), y.to_bits()],
            };
            out.push([x.to_bits(), x.max(y).to_bits(), b[0], b[1]]);
        }
    }
    let mut rng = StdRng::seed_from_u64(seed);
    while out.len() < n {
        let a = random_interval(&mut rng, &sp);
        let b = random_interval(&mut rng, &sp);
        out.push([a[0], a[1], b[0], b[1]]);
    }
    if op == Op::Pown {
        for (i, input) in out.iter_mut().enumerate() {
            // Small exponents, and the extremes (|i32::MIN| does not fit an i32).
            let n = match i % 100 {
                0 => i32::MIN,
                1 => i32::MAX,
                2 => i32::MIN + 1,
                _ => (i % 15) as i32 - 5,
            };
            input[2] = n as u32;
        }
    }
    out
}

/// A bound as the kernel reads it (`bound_from_bits` of the library), as `f64` with the
/// library's `±BIG` as infinities.
fn bound(bits: u32, up: bool) -> f64 {
    let x = f32::from_bits(bits);
    let b = if x.is_nan() {
        if up { BIG } else { -BIG }
    } else if x.is_infinite() {
        BIG.copysign(x)
    } else if x.abs() == BIG {
        // The finite largest value: infinite on its own side, the value below it on the
        // other.
        if (x > 0.0) == up {
            x
        } else {
            f32::from_bits(0x7f7f_fffe).copysign(x)
        }
    } else if x != 0.0 && x.abs() < TINY {
        match (x < 0.0, up) {
            (true, false) => -TINY,
            (false, true) => TINY,
            _ => 0.0,
        }
    } else {
        x
    };
    bound_to_f64(b)
}

fn interval(lo: u32, hi: u32) -> Interval<f64> {
    Interval::new(bound(lo, false), bound(hi, true)).unwrap_or(Interval::EMPTY)
}

/// The exact range of `op` on the input, enclosed in `f64`.
fn reference(op: Op, v: &OpInput) -> Interval<f64> {
    let a = interval(v[0], v[1]);
    let b = interval(v[2], v[3]);
    let exact = |f: fn(f64) -> f64| match a.bounds() {
        None => Interval::EMPTY,
        Some((lo, hi)) => Interval::new(f(lo), f(hi)).unwrap_or(Interval::EMPTY),
    };
    // A slope: 0 without a jump in `a`, every real with one.
    let slope = |jump: fn(f64, f64) -> bool| match a.bounds() {
        None => Interval::EMPTY,
        Some((lo, hi)) if jump(lo, hi) => Interval::ENTIRE,
        Some(_) => Interval::new(0.0, 0.0).unwrap(),
    };
    match op {
        Op::Binary(BinaryOp::Add) => a.add(b),
        Op::Binary(BinaryOp::Sub) => a.sub(b),
        Op::Binary(BinaryOp::Mul) => a.mul(b),
        Op::Binary(BinaryOp::Div) => a.div(b),
        Op::Binary(BinaryOp::Min) => a.min(b),
        Op::Binary(BinaryOp::Max) => a.max(b),
        Op::Pown => a.pown(v[2] as i32),
        Op::Unary(UnaryOp::Neg) => a.neg(),
        Op::Unary(UnaryOp::Abs) => a.abs(),
        Op::Unary(UnaryOp::Sqr) => a.sqr(),
        Op::Unary(UnaryOp::Sqrt) => a.sqrt(),
        Op::Unary(UnaryOp::Recip) => a.recip(),
        Op::Unary(UnaryOp::Floor) => exact(f64::floor),
        Op::Unary(UnaryOp::Ceil) => exact(f64::ceil),
        Op::Unary(UnaryOp::Exp) => a.exp(),
        Op::Unary(UnaryOp::Ln) => a.ln(),
        Op::Unary(UnaryOp::Log10) => a.log10(),
        Op::Unary(UnaryOp::Sin) => a.sin(),
        Op::Unary(UnaryOp::Cos) => a.cos(),
        Op::Unary(UnaryOp::Tan) => a.tan(),
        Op::Unary(UnaryOp::Asin) => a.asin(),
        Op::Unary(UnaryOp::Acos) => a.acos(),
        Op::Unary(UnaryOp::Atan) => a.atan(),
        Op::Binary(BinaryOp::Pow) => a.pow(b),
        Op::Binary(BinaryOp::Domain) => {
            let absent = Interval::new(f64::MAX, f64::INFINITY).unwrap();
            match a.bounds() {
                Some((_, hi)) if hi <= 0.0 => b,
                Some((lo, _)) if lo > 0.0 => absent,
                _ => b.convex_hull(absent),
            }
        }
        // f64::round rounds halves away from zero, as the library's round does.
        Op::Unary(UnaryOp::Round) => exact(f64::round),
        Op::Unary(UnaryOp::Not) => match a.bounds() {
            None => Interval::EMPTY,
            Some((0.0, 0.0)) => Interval::new(1.0, 1.0).unwrap(),
            Some((lo, hi)) if lo > 0.0 || hi < 0.0 => Interval::new(0.0, 0.0).unwrap(),
            Some(_) => Interval::new(0.0, 1.0).unwrap(),
        },
        Op::Unary(UnaryOp::SlopeFloor) => slope(|lo, hi| lo.ceil() <= hi),
        Op::Unary(UnaryOp::SlopeRound) => slope(holds_half_integer),
        Op::Unary(UnaryOp::SlopeNot) => slope(|lo, hi| lo <= 0.0 && 0.0 <= hi),
    }
}

/// Whether `[lo, hi]` (bounds from `f32`s) holds a half-integer `k + 1/2`.
fn holds_half_integer(lo: f64, hi: f64) -> bool {
    if hi - lo >= 1.0 {
        return true;
    }
    if lo.abs().max(hi.abs()) >= 2f64.powi(24) {
        // Every f32 there is an integer: a half-integer lies between two distinct ones.
        return hi > lo;
    }
    // Half-integers are the odd integers of [2 lo, 2 hi] (exact below 2^25).
    let c = (2.0 * lo).ceil();
    let odd = if c.rem_euclid(2.0) == 1.0 { c } else { c + 1.0 };
    odd <= 2.0 * hi
}

/// Why a GPU result is wrong, if it is.
fn violation(op: Op, v: &OpInput, [lo, hi]: [f32; 2]) -> Option<String> {
    let bad_bound = |x: f32| x.is_nan() || x.is_infinite() || (x != 0.0 && x.abs() < TINY);
    let r = reference(op, v);
    let show = || {
        format!(
            "{}([{:e}, {:e}], [{:e}, {:e}]) = [{lo:e}, {hi:e}], exact range {r:?}",
            implicit_expr::wgsl::function(op),
            f32::from_bits(v[0]),
            f32::from_bits(v[1]),
            f32::from_bits(v[2]),
            f32::from_bits(v[3]),
        )
    };
    if bad_bound(lo) || bad_bound(hi) {
        return Some(format!("NaN, infinite or subnormal bound: {}", show()));
    }
    let (rlo, rhi) = r.bounds()?;
    // The reference is interval-core's f64 enclosure, outward by at most one f64 ULP
    // (2^-29 of an f32 ULP): an f32 bound within that ULP of the exact value cannot be
    // judged by it, so the check allows it.
    let (rlo, rhi) = (rlo.next_up().min(rhi), rhi.next_down().max(rlo));
    if !(bound_to_f64(lo) <= rlo && rhi <= bound_to_f64(hi)) {
        return Some(format!("does not contain the exact range: {}", show()));
    }
    None
}

fn check_library(flush: bool) -> Result<(), GpuError> {
    let Some(gpu) = Gpu::for_tests() else {
        return Ok(());
    };
    let runner = OpRunner::new(&gpu, flush)?;
    let mut failures = Vec::new();
    for (k, op) in Op::ALL.into_iter().enumerate() {
        let input = inputs(op, 100_000, 1000 + k as u64);
        let output = runner.run(&gpu, op, &input)?;
        assert_eq!(output.len(), input.len());
        let bad: Vec<String> = input
            .iter()
            .zip(&output)
            .filter_map(|(v, r)| violation(op, v, *r))
            .collect();
        eprintln!(
            "{} (flush {flush}): {} inputs, {} violations",
            implicit_expr::wgsl::function(op),
            input.len(),
            bad.len()
        );
        failures.extend(bad.into_iter().take(5));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    Ok(())
}

#[test]
fn every_operation_encloses_the_exact_range() -> Result<(), GpuError> {
    check_library(false)
}

#[test]
fn every_operation_encloses_the_exact_range_when_subnormals_are_flushed() -> Result<(), GpuError> {
    check_library(true)
}

/// The results are useful, not only sound: on moderate inputs, each result is as wide as
/// its WGSL error bound allows, no wider.
#[test]
fn arithmetic_is_tight_on_moderate_inputs() -> Result<(), GpuError> {
    let Some(gpu) = Gpu::for_tests() else {
        return Ok(());
    };
    let runner = OpRunner::new(&gpu, false)?;
    let p = |x: f32| [x.to_bits(), x.to_bits()];
    let a = p(1.0 / 3.0);
    let b = p(7.25);
    for (op, ulps) in [
        (Op::Binary(BinaryOp::Add), 2),
        (Op::Binary(BinaryOp::Mul), 2),
        (Op::Binary(BinaryOp::Div), 12),
        (Op::Unary(UnaryOp::Sqr), 2),
        (Op::Unary(UnaryOp::Sqrt), 20),
        (Op::Unary(UnaryOp::Exp), 2 * (2 * (3 + 2) + 1)),
        (Op::Unary(UnaryOp::Ln), 2 * 7 + 2),
        (Op::Unary(UnaryOp::Atan), 2 * 8193),
    ] {
        let [lo, hi] = runner.run(&gpu, op, &[[a[0], a[1], b[0], b[1]]])?[0];
        // ULPs between the bounds, from the ordered integer images of the floats.
        let ordered = |x: f32| {
            let m = i64::from(x.to_bits() & 0x7fff_ffff);
            if x < 0.0 { -m } else { m }
        };
        let width = ordered(hi) - ordered(lo);
        assert!(
            width <= ulps,
            "{}: [{lo:e}, {hi:e}] is {width} ULPs wide",
            implicit_expr::wgsl::function(op)
        );
    }
    Ok(())
}
