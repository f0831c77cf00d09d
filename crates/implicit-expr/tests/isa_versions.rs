//! The evaluators' loops compiled for the baseline instruction set and for the best one the
//! CPU has (`interval_core::isa`) give bit-identical results: interval values in `f64` and
//! `f32`, decorations, traced choices and pruned tapes, point values, and the slice
//! evaluator's values, on random expressions over random boxes.
//!
//! The instruction set is a process-wide setting, so this file holds one test, which
//! switches it back and forth itself. On a CPU without x86-64-v3 (or another architecture)
//! both runs take the baseline loops and the test checks only that they repeat. Needs the
//! `proptest` feature (the crate's strategies).

#![cfg(feature = "proptest")]

use implicit_expr::Tape;
use implicit_expr::eval::{Choice, Evaluator, SliceEvaluator};
use implicit_expr::testing::strategy::{expression, region_and_point};
use interval_core::isa::{self, Isa};
use interval_core::{Decoration, Interval};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

/// Everything one evaluation of `tape` at `region` (and `point`) gives, as bits.
#[derive(Debug, PartialEq)]
struct Results {
    interval: (u64, u64),
    decorated: ((u64, u64), Decoration),
    continuous: ((u64, u64), bool),
    single: (u32, u32),
    point: u64,
    choices: Vec<Choice>,
    pruned: Vec<(u64, u64)>,
    slice: Vec<(u64, u64)>,
}

fn bits(x: Interval<f64>) -> (u64, u64) {
    (x.inf().to_bits(), x.sup().to_bits())
}

/// The results of every evaluator in the instruction set `isa`.
fn evaluate(tape: &Tape, region: &[Interval<f64>], point: &[f64], isa: Isa) -> Results {
    isa::set_limit(isa);
    let mut iv = Evaluator::<Interval<f64>>::new(tape);
    let interval = bits(iv.eval(region).unwrap());
    let (v, d) = iv.eval_decorated(region).unwrap();
    let (c, ok) = iv.eval_continuous(region).unwrap();
    let mut choices = Vec::new();
    iv.eval_traced(region, &mut choices).unwrap();
    let pruned_tape = iv.pruned(region, &mut Vec::new()).unwrap();
    let mut sub = Evaluator::<Interval<f64>>::new(&pruned_tape);
    // The pruned tape at the box and at its point.
    let pruned = vec![
        bits(sub.eval(region).unwrap()),
        bits(
            sub.eval(
                &point
                    .iter()
                    .map(|&p| Interval::point(p).unwrap())
                    .collect::<Vec<_>>(),
            )
            .unwrap(),
        ),
    ];
    let region32: Vec<Interval<f32>> = region.iter().map(|x| x.cast()).collect();
    let s = Evaluator::<Interval<f32>>::new(tape)
        .eval(&region32)
        .unwrap();
    let point_value = Evaluator::<f64>::new(tape).eval(point).unwrap();
    // 70 inputs: a full chunk of the slice evaluator and a tail, the box and its point.
    let columns: Vec<Vec<Interval<f64>>> = region
        .iter()
        .zip(point)
        .map(|(&r, &p)| {
            (0..70)
                .map(|i| {
                    if i % 2 == 0 {
                        r
                    } else {
                        Interval::point(p).unwrap()
                    }
                })
                .collect()
        })
        .collect();
    let vars: Vec<&[Interval<f64>]> = columns.iter().map(Vec::as_slice).collect();
    let mut out = vec![Interval::<f64>::EMPTY; 70];
    SliceEvaluator::new(tape).eval(&vars, &mut out).unwrap();
    Results {
        interval,
        decorated: (bits(v), d),
        continuous: (bits(c), ok),
        single: (s.inf().to_bits(), s.sup().to_bits()),
        point: point_value.to_bits(),
        choices,
        pruned,
        slice: out.into_iter().map(bits).collect(),
    }
}

#[test]
fn every_instruction_set_gives_the_same_bits() {
    let best = isa::detected();
    let cases = std::env::var("INTERVAL_CORE_TEST_SCALE")
        .ok()
        .and_then(|s| s.parse::<u32>().ok())
        .unwrap_or(1)
        * 512;
    let mut runner = TestRunner::new(Config::with_cases(cases));
    let result = runner.run(
        &(expression(), region_and_point::<f64>(3)),
        |(e, (region, point))| {
            let tape = e.tape();
            let base = evaluate(&tape, &region, &point, Isa::Baseline);
            let wide = evaluate(&tape, &region, &point, best);
            prop_assert_eq!(&base, &wide, "{:?}", e);
            Ok(())
        },
    );
    isa::set_limit(best);
    result.unwrap();
}
