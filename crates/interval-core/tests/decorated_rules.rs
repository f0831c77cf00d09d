//! Property tests of the decoration rules of `DecInterval` (IEEE 1788 §11.7), for `f64` and
//! `f32`, on random intervals of every kind and random input decorations:
//!
//! * the interval part is exactly the plain operation's result;
//! * the decoration never exceeds the inputs' (propagation by minimum), and NaI propagates;
//! * `def` or better: the function is defined at every sampled point of the box (the plain
//!   operation on the point is nonempty), and for the step functions `dac` or better means
//!   the function is constant on the samples (no jump);
//! * `com`: the inputs are `com` and the result is bounded and nonempty;
//! * sharpness: on a bounded box inside the domain, with `com` inputs and a bounded result,
//!   the decoration is `com` (the rules do not lose information where the function is
//!   continuous: the elementary functions and, for steps, boxes without a jump).

mod common;

use common::{TestFloat, config, interval, point_seeds, points_in};
use interval_core::{DecInterval, Decoration, Float, Interval};
use proptest::prelude::*;

type Op<T> = (
    &'static str,
    fn(DecInterval<T>) -> DecInterval<T>,
    fn(Interval<T>) -> Interval<T>,
    bool,
);

/// (name, decorated, plain, is a step function).
fn unary_ops<T: Float>() -> Vec<Op<T>> {
    vec![
        ("neg", DecInterval::neg, Interval::neg, false),
        ("recip", DecInterval::recip, Interval::recip, false),
        ("sqr", DecInterval::sqr, Interval::sqr, false),
        ("sqrt", DecInterval::sqrt, Interval::sqrt, false),
        ("abs", DecInterval::abs, Interval::abs, false),
        ("exp", DecInterval::exp, Interval::exp, false),
        ("exp2", DecInterval::exp2, Interval::exp2, false),
        ("exp10", DecInterval::exp10, Interval::exp10, false),
        ("expm1", DecInterval::expm1, Interval::expm1, false),
        ("log", DecInterval::log, Interval::log, false),
        ("log2", DecInterval::log2, Interval::log2, false),
        ("log10", DecInterval::log10, Interval::log10, false),
        ("log1p", DecInterval::log1p, Interval::log1p, false),
        ("sin", DecInterval::sin, Interval::sin, false),
        ("cos", DecInterval::cos, Interval::cos, false),
        ("tan", DecInterval::tan, Interval::tan, false),
        ("asin", DecInterval::asin, Interval::asin, false),
        ("acos", DecInterval::acos, Interval::acos, false),
        ("atan", DecInterval::atan, Interval::atan, false),
        ("sinh", DecInterval::sinh, Interval::sinh, false),
        ("cosh", DecInterval::cosh, Interval::cosh, false),
        ("tanh", DecInterval::tanh, Interval::tanh, false),
        ("asinh", DecInterval::asinh, Interval::asinh, false),
        ("acosh", DecInterval::acosh, Interval::acosh, false),
        ("atanh", DecInterval::atanh, Interval::atanh, false),
        ("floor", DecInterval::floor, Interval::floor, true),
        ("ceil", DecInterval::ceil, Interval::ceil, true),
        ("trunc", DecInterval::trunc, Interval::trunc, true),
        ("sign", DecInterval::sign, Interval::sign, true),
        (
            "round_ties_to_even",
            DecInterval::round_ties_to_even,
            Interval::round_ties_to_even,
            true,
        ),
        (
            "round_ties_to_away",
            DecInterval::round_ties_to_away,
            Interval::round_ties_to_away,
            true,
        ),
    ]
}

fn decoration() -> impl Strategy<Value = Decoration> {
    prop_oneof![
        4 => Just(Decoration::Com),
        1 => Just(Decoration::Dac),
        1 => Just(Decoration::Def),
        1 => Just(Decoration::Trv),
        1 => Just(Decoration::Ill),
    ]
}

/// The box's points, its ends included.
fn samples<T: TestFloat>(x: Interval<T>, seeds: &[(T, f64)]) -> Vec<T> {
    points_in(x, seeds)
}

fn check_unary<T: TestFloat>(
    (name, dec, plain, is_step): Op<T>,
    x: Interval<T>,
    d: Decoration,
    seeds: &[(T, f64)],
) -> Result<(), TestCaseError> {
    let input = DecInterval::set_dec(x, d);
    let got = dec(input);
    if input.is_nai() {
        prop_assert!(got.is_nai(), "{name}: NaI must propagate");
        return Ok(());
    }
    let r = plain(x);
    prop_assert!(
        got.interval() == r,
        "{name}({input}): interval {} vs {}",
        got.interval(),
        r
    );
    prop_assert!(
        got.decoration() <= input.decoration(),
        "{name}({input}) = {got}"
    );
    let pts = samples(x, seeds);
    let point = |p: T| plain(Interval::new(p, p).unwrap());
    if got.decoration() >= Decoration::Def {
        for &p in &pts {
            prop_assert!(
                !point(p).is_empty(),
                "{name}({input}) = {got}, undefined at {p:?}"
            );
        }
    }
    if is_step
        && got.decoration() >= Decoration::Dac
        && let Some(&first) = pts.first()
    {
        for &p in &pts {
            prop_assert!(point(p) == point(first), "{name}({input}) = {got} jumps");
        }
    }
    if got.decoration() == Decoration::Com {
        prop_assert!(input.decoration() == Decoration::Com && r.is_common_interval());
    }
    Ok(())
}

/// Sharpness on boxes well inside the domains: `com` in, bounded out, gives `com`.
fn check_sharp<T: TestFloat>(
    (name, dec, plain, is_step): Op<T>,
    x: Interval<T>,
) -> Result<(), TestCaseError> {
    let Some((lo, hi)) = x.bounds() else {
        return Ok(());
    };
    if !x.is_common_interval() {
        return Ok(());
    }
    let inside = match name {
        "recip" => !x.contains(T::ZERO),
        "sqrt" => lo >= T::ZERO,
        "log" | "log2" | "log10" => lo > T::ZERO,
        "log1p" => lo > -T::ONE,
        "asin" | "acos" => lo >= -T::ONE && hi <= T::ONE,
        "acosh" => lo >= T::ONE,
        "atanh" => lo > -T::ONE && hi < T::ONE,
        "tan" => !plain(x).is_entire(),
        // Constant on the box, and continuous at both ends (com asks continuity at every
        // point of the box, not only of the restriction).
        _ if is_step => {
            plain(Interval::new(lo, lo).unwrap()) == plain(Interval::new(hi, hi).unwrap())
                && !jump_at(name, lo.to_f64())
                && !jump_at(name, hi.to_f64())
        }
        _ => true,
    };
    let r = plain(x);
    if inside && r.is_common_interval() {
        let got = dec(DecInterval::new(x));
        prop_assert!(
            got.decoration() == Decoration::Com,
            "{name}({x}) = {got}, expected com"
        );
    }
    Ok(())
}

fn check_binary<T: TestFloat>(
    x: Interval<T>,
    y: Interval<T>,
    dx: Decoration,
    dy: Decoration,
    n: i32,
) -> Result<(), TestCaseError> {
    let (a, b) = (DecInterval::set_dec(x, dx), DecInterval::set_dec(y, dy));
    let cases: [(&str, DecInterval<T>, Interval<T>); 9] = [
        ("add", a + b, x + y),
        ("sub", a - b, x - y),
        ("mul", a * b, x * y),
        ("div", a / b, x / y),
        ("pow", a.pow(b), x.pow(y)),
        ("atan2", a.atan2(b), x.atan2(y)),
        ("hypot", a.hypot(b), x.hypot(y)),
        ("pown", a.pown(n), x.pown(n)),
        ("rootn", a.rootn(n), x.rootn(n)),
    ];
    for (name, got, plain) in cases {
        if a.is_nai() || (b.is_nai() && !matches!(name, "pown" | "rootn")) {
            prop_assert!(got.is_nai(), "{name}: NaI must propagate");
            continue;
        }
        prop_assert!(got.interval() == plain, "{name}: interval part");
        let min_in = if matches!(name, "pown" | "rootn") {
            a.decoration()
        } else {
            a.decoration().min(b.decoration())
        };
        prop_assert!(got.decoration() <= min_in, "{name}({a}, {b}) = {got}");
        if got.decoration() == Decoration::Com {
            prop_assert!(plain.is_common_interval());
        }
    }
    // Division: com/dac exactly when 0 ∉ y (with com/dac inputs).
    if !a.is_nai()
        && !b.is_nai()
        && a.decoration() >= Decoration::Dac
        && b.decoration() >= Decoration::Dac
    {
        let q = a / b;
        prop_assert_eq!(
            q.decoration() >= Decoration::Dac,
            !y.contains(T::ZERO) && !(x / y).is_empty()
        );
    }
    Ok(())
}

fn exponent() -> impl Strategy<Value = i32> {
    -5i32..=6
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn unary_rules_f64(x in interval::<f64>(), d in decoration(), s in point_seeds::<f64>(4)) {
        for op in unary_ops::<f64>() {
            check_unary(op, x, d, &s)?;
            check_sharp(op, x)?;
        }
    }

    #[test]
    fn unary_rules_f32(x in interval::<f32>(), d in decoration(), s in point_seeds::<f32>(4)) {
        for op in unary_ops::<f32>() {
            check_unary(op, x, d, &s)?;
            check_sharp(op, x)?;
        }
    }

    #[test]
    fn binary_rules_f64(x in interval::<f64>(), y in interval::<f64>(), dx in decoration(), dy in decoration(), n in exponent()) {
        check_binary(x, y, dx, dy, n)?;
    }

    #[test]
    fn binary_rules_f32(x in interval::<f32>(), y in interval::<f32>(), dx in decoration(), dy in decoration(), n in exponent()) {
        check_binary(x, y, dx, dy, n)?;
    }
}

/// Where the step function `name` is discontinuous (its jumps), written out here
/// independently of the library.
fn jump_at(name: &str, v: f64) -> bool {
    let integer = v.is_finite() && v == v.trunc();
    match name {
        "floor" | "ceil" => integer,
        "trunc" => integer && v != 0.0,
        "sign" => v == 0.0,
        "round_ties_to_even" | "round_ties_to_away" => v.is_finite() && (v - v.floor()) == 0.5,
        _ => false,
    }
}

#[test]
fn standard_examples() {
    use Decoration::*;
    let d = |a: f64, b: f64| DecInterval::new(Interval::new(a, b).unwrap());
    // IEEE 1788 §11.7 examples and their relatives.
    assert_eq!((d(1.0, 2.0) + d(3.0, 4.0)).decoration(), Com);
    assert_eq!((d(1.0, f64::MAX) * d(2.0, 2.0)).decoration(), Dac);
    assert_eq!(d(-1.0, 4.0).sqrt().decoration(), Trv);
    assert_eq!(d(-4.0, -1.0).sqrt().decoration(), Trv);
    assert!(d(-4.0, -1.0).sqrt().is_empty());
    assert_eq!(d(0.5, 1.5).floor().decoration(), Def);
    // Constant on [1, 1.5], so its restriction is continuous, but floor jumps at 1.
    assert_eq!(d(1.0, 1.5).floor().decoration(), Dac);
    assert_eq!(d(1.25, 1.5).floor().decoration(), Com);
    assert_eq!(d(0.0, 0.0).sign().decoration(), Dac);
    assert_eq!(d(-0.5, 0.5).trunc().decoration(), Com);
    assert_eq!(d(0.0, 1.0).sign().decoration(), Def);
    assert_eq!(d(1.0, 2.0).sign().decoration(), Com);
    assert_eq!(d(2.0, 3.0).recip().decoration(), Com);
    assert_eq!(d(-2.0, 3.0).recip().decoration(), Trv);
    assert_eq!(DecInterval::<f64>::ENTIRE.exp().decoration(), Dac);
    assert_eq!(DecInterval::<f64>::ENTIRE.sin().decoration(), Dac);
    assert_eq!(d(0.5, 0.5).atanh().decoration(), Com);
    assert_eq!(d(0.5, 1.0).atanh().decoration(), Trv);
    assert_eq!(format!("{}", d(1.0, 2.0)), "[1, 2]_com");
    assert_eq!(format!("{}", DecInterval::<f64>::NAI), "[nai]");
}
