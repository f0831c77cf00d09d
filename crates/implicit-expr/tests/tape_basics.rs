//! Compilation, register allocation and pruning on hand-built graphs.

use implicit_expr::{Choice, Context, Evaluator, Grad, SliceEvaluator, Tape};
use interval_core::{Inner, Interval, Modal, Outer};

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

/// x² + y² + z² - 1 and its tape.
fn sphere() -> (Context, Tape) {
    let mut c = Context::new();
    let (x, y, z) = (c.x(), c.y(), c.z());
    let (x2, y2, z2) = (c.sqr(x), c.sqr(y), c.sqr(z));
    let s = c.add(x2, y2);
    let s = c.add(s, z2);
    let one = c.constant(1.0).unwrap();
    let f = c.sub(s, one);
    let t = Tape::new(&c, &[f]).unwrap();
    (c, t)
}

#[test]
fn point_interval_and_slice_agree() {
    let (_, t) = sphere();
    let mut e = Evaluator::<f64>::new(&t);
    assert_eq!(e.eval(&[1.0, 2.0, 3.0]).unwrap(), 13.0);
    let mut ei = Evaluator::<Interval<f64>>::new(&t);
    let r = ei
        .eval(&[iv(-1.0, 1.0), iv(0.0, 1.0), iv(2.0, 2.0)])
        .unwrap();
    assert_eq!(r, iv(3.0, 5.0));
    let xs: Vec<f64> = (0..200).map(|i| i as f64 * 0.01).collect();
    let ys = vec![0.5; 200];
    let zs = vec![-0.25; 200];
    let mut out = vec![0.0; 200];
    let mut se = SliceEvaluator::<f64>::new(&t);
    se.eval(&[&xs, &ys, &zs], &mut out).unwrap();
    for i in 0..200 {
        assert_eq!(out[i], e.eval(&[xs[i], ys[i], zs[i]]).unwrap());
    }
}

#[test]
fn hash_consing_shares_and_simplifies() {
    let mut c = Context::new();
    let x = c.x();
    let y = c.y();
    let a = c.add(x, y);
    let b = c.add(y, x);
    assert_eq!(a, b);
    let d = c.sub(a, b);
    assert_eq!(c.as_const(d).map(|k| k.value()), Some(0.0));
    let m = c.mul(x, x);
    assert_eq!(m, c.sqr(x));
}

#[test]
fn pruning_min_max() {
    // min(x, x + 10): over x in [0, 1] the left branch is always taken.
    let mut c = Context::new();
    let x = c.x();
    let ten = c.constant(10.0).unwrap();
    let y = c.y();
    let far = c.add(x, ten);
    let far = c.mul(far, y);
    let f = c.min(x, far);
    let t = Tape::new(&c, &[f]).unwrap();
    let mut e = Evaluator::<Interval<f64>>::new(&t);
    let mut trace = Vec::new();
    e.eval_traced(&[iv(0.0, 1.0), iv(2.0, 3.0), iv(0.0, 0.0)], &mut trace)
        .unwrap();
    assert_eq!(trace, vec![Choice::Left]);
    let p = t.simplify(&trace).unwrap();
    assert!(p.len() < t.len());
    let mut ep = Evaluator::<f64>::new(&p);
    assert_eq!(ep.eval(&[0.5, 2.5, 0.0]).unwrap(), 0.5);
}

#[test]
fn gradient_and_modal() {
    let (_, t) = sphere();
    let mut e = Evaluator::<Grad<f64>>::new(&t);
    let g = e.eval(&Grad::point(1.0, 2.0, 3.0)).unwrap();
    assert_eq!(g.v, 13.0);
    assert_eq!(g.d, [2.0, 4.0, 6.0]);
    let m = |a: f64, b: f64| Modal::<f64, Outer>::new(a, b).unwrap();
    let mut eo = Evaluator::<Modal<f64, Outer>>::new(&t);
    let r = eo.eval(&[m(1.0, 2.0), m(0.0, 0.0), m(0.0, 0.0)]).unwrap();
    assert_eq!((r.first(), r.second()), (0.0, 3.0));
    let mi = |a: f64, b: f64| Modal::<f64, Inner>::new(a, b).unwrap();
    let mut ei = Evaluator::<Modal<f64, Inner>>::new(&t);
    let r = ei
        .eval(&[mi(2.0, 1.0), mi(0.0, 0.0), mi(0.0, 0.0)])
        .unwrap();
    assert_eq!((r.first(), r.second()), (3.0, 0.0));
}

#[test]
fn substitute_binds_parameters() {
    let mut c = Context::new();
    let x = c.x();
    let a = c.named_var("a");
    let f = c.mul(a, x);
    let two = c.constant(2.0).unwrap();
    let g = c.substitute(f, &[(implicit_expr::Var(3), two)]);
    let t = Tape::new(&c, &[g]).unwrap();
    assert_eq!(
        Evaluator::<f64>::new(&t)
            .eval(&[3.0, 0.0, 0.0, 100.0])
            .unwrap(),
        6.0
    );
    // Binding to zero folds the product away.
    let zero = c.constant(0.0).unwrap();
    let h = c.substitute(f, &[(implicit_expr::Var(3), zero)]);
    assert_eq!(c.as_const(h).map(|k| k.value()), Some(0.0));
}

#[test]
fn extract_drops_bound_parameters() {
    let mut c = Context::new();
    let x = c.x();
    let a = c.named_var("a");
    let b = c.named_var("b");
    let f = c.mul(a, x);
    let f = c.add(f, b);
    let two = c.constant(2.0).unwrap();
    let g = c.substitute(f, &[(implicit_expr::Var(3), two)]);
    let (e, r) = c.extract(g);
    assert_eq!(e.var_names(), ["x", "y", "z", "b"]);
    let t = Tape::new(&e, &[r]).unwrap();
    assert_eq!(t.var_count(), 4);
    assert_eq!(
        Evaluator::<f64>::new(&t)
            .eval(&[3.0, 0.0, 0.0, 1.0])
            .unwrap(),
        7.0
    );
}

#[test]
fn slice_traces_match_scalar_traces() {
    let mut c = Context::new();
    let f = implicit_expr::parse::parse(
        &mut c,
        "min(max(x - 0.5, y), min(sqrt(x + y) - 2, abs(x) - 0.25))",
        &[],
    )
    .unwrap();
    let t = Tape::new(&c, &[f]).unwrap();
    let boxes: Vec<[Interval<f64>; 3]> = (0..150)
        .map(|k| {
            let a = -2.0 + 0.03 * k as f64;
            let b = 1.0 - 0.02 * k as f64;
            [iv(a, a + 0.1), iv(b, b + 0.05), iv(0.0, 0.0)]
        })
        .collect();
    let cols: Vec<Vec<Interval<f64>>> = (0..3)
        .map(|s| boxes.iter().map(|b| b[s]).collect())
        .collect();
    let vars = [&cols[0][..], &cols[1][..], &cols[2][..]];
    let mut out = vec![Interval::ZERO; boxes.len()];
    let mut traces = vec![Vec::new(); boxes.len()];
    SliceEvaluator::<Interval<f64>>::new(&t)
        .eval_traced(&vars, &mut out, &mut traces)
        .unwrap();
    let mut e = Evaluator::<Interval<f64>>::new(&t);
    let mut trace = Vec::new();
    let mut decided = 0;
    for (k, b) in boxes.iter().enumerate() {
        let v = e.eval_traced(b, &mut trace).unwrap();
        assert_eq!(v, out[k]);
        assert_eq!(trace, traces[k], "box {k}");
        decided += trace.iter().filter(|&&c| c != Choice::Both).count();
    }
    assert!(decided > 0);
    assert!(
        SliceEvaluator::<Interval<f64>>::new(&t)
            .eval_traced(&vars, &mut out, &mut traces[1..])
            .is_err()
    );
}

#[test]
fn total_continuous_operations_are_those_decorated_com_on_the_whole_line() {
    use implicit_expr::{BinaryOp, Number, UnaryOp};
    use interval_core::Decoration;
    let all = Interval::<f64>::ENTIRE;
    for op in UnaryOp::ALL {
        let dec = Interval::<f64>::decoration_unary(op, all);
        assert_eq!(op.is_total(), dec >= Decoration::Def, "{op:?}");
        assert_eq!(
            op.is_total() && !op.is_discontinuous(),
            dec == Decoration::Com,
            "{op:?}"
        );
    }
    for op in BinaryOp::ALL {
        let dec = Interval::<f64>::decoration_binary(op, all, all);
        // `domain` is defined everywhere (the absent object outside), but jumps.
        let defined = op.is_total() || op == BinaryOp::Domain;
        assert_eq!(defined, dec >= Decoration::Def, "{op:?}");
        assert_eq!(op.is_total(), dec == Decoration::Com, "{op:?}");
    }
}

#[test]
fn total_and_continuous_formulas() {
    use implicit_expr::parse::parse;
    // (formula, total, total and continuous)
    let cases = [
        ("x^2 + y^2 + z^2 - 1", true, true),
        (
            "min(abs(x) - 1, max(y, -z)) * exp(sin(x) + cos(y)) + atan(z)",
            true,
            true,
        ),
        ("x^3 + sqr(y) - z", true, true),
        ("floor(x) + y", true, false),
        ("round(x) - not(y)", true, false),
        ("sqrt(x^2 + y^2) - 1", false, false),
        ("x / y", false, false),
        ("x^-2 - 1", false, false),
        ("ln(x) + tan(y)", false, false),
        ("asin(x) + acos(y) + log(z)", false, false),
        ("x ^ y", false, false),
    ];
    for (text, total, total_and_continuous) in cases {
        let mut c = Context::new();
        let f = parse(&mut c, text, &[]).unwrap();
        let t = Tape::new(&c, &[f]).unwrap();
        assert_eq!(c.is_total(f), total, "{text}");
        assert_eq!(t.is_total(), total, "{text}");
        assert_eq!(t.is_total_and_continuous(), total_and_continuous, "{text}");
    }
}

/// Square roots of arguments non-negative by their form keep a tape continuous everywhere;
/// every such tape's decorated evaluation is at least `dac` on boxes anywhere, the others
/// are not flagged.
#[test]
fn continuous_everywhere_formulas() {
    use implicit_expr::parse::parse;
    use interval_core::Decoration;
    let cases = [
        ("x^2 + y^2 + z^2 - 1", true),
        ("sqrt(x^2 + y^2) - 1", true),
        ("sqrt(sqr(x - 1) + sqr(y) + sqr(z)) - 0.5", true),
        ("sqrt(abs(x) + 2) + sqrt(sqrt(y^4 + 1))", true),
        ("sqrt(max(x, sqr(y))) - z", true),
        ("sqrt(x * x + exp(y)) - 2", true),
        ("min(sqrt(x^2 + z^2) - 1, max(y, -z))", true),
        ("sqrt(min(x, sqr(y)))", false),
        ("sqrt(x^2 - 1)", false),
        ("sqrt(x)", false),
        ("sqrt(x * y + 1)", false),
        ("floor(x) + y", false),
        ("x / y", false),
        ("ln(x^2 + 1)", false),
    ];
    let boxes = [
        [iv(-3.0, -1.0), iv(-0.5, 0.25), iv(0.0, 4.0)],
        [iv(-1e3, 1e3), iv(-1e3, 1e3), iv(-1e3, 1e3)],
        [iv(0.5, 0.5), iv(-2.0, -2.0), iv(1.0, 1.5)],
    ];
    for (text, expected) in cases {
        let mut c = Context::new();
        let f = parse(&mut c, text, &[]).unwrap();
        let t = Tape::new(&c, &[f]).unwrap();
        assert_eq!(t.is_continuous_everywhere(), expected, "{text}");
        assert!(
            !t.is_total_and_continuous() || t.is_continuous_everywhere(),
            "{text}: total and continuous"
        );
        if expected {
            let mut e = Evaluator::<Interval<f64>>::new(&t);
            for b in &boxes {
                let (_, dec) = e.eval_decorated(b).unwrap();
                assert!(dec >= Decoration::Dac, "{text} on {b:?}: {dec:?}");
            }
        }
    }
}

#[test]
fn zero_variables_fold_the_ray_prefix_away() {
    // Every catalog surface without parameters, as a ray tape `f(c + t·d)`: with `t` and `d`
    // at 0 the folded tape is shorter and gives the same intervals (values and gradients)
    // over boxes of `c`.
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut checked = 0;
    for s in implicit_expr::catalog::all()
        .iter()
        .filter(|s| s.params.is_empty())
    {
        let mut c = Context::new();
        let f = implicit_expr::parse::parse(&mut c, s.formula, &[]).unwrap();
        let ray = implicit_expr::RayFunction::new(&c, f).unwrap();
        let tape = ray.g_tape();
        let folded = tape.with_zero_vars(&[3, 4, 5, 6]);
        assert!(folded.len() < tape.len(), "{}: nothing folded", s.name);
        assert_eq!(folded.var_count(), tape.var_count());
        let (mut a, mut b) = (
            Evaluator::<Interval<f64>>::new(tape),
            Evaluator::<Interval<f64>>::new(&folded),
        );
        let (mut ga, mut gb) = (
            Evaluator::<Grad<Interval<f64>>>::new(tape),
            Evaluator::<Grad<Interval<f64>>>::new(&folded),
        );
        for _ in 0..50 {
            let mut vars = vec![Interval::ZERO; 7];
            let mut grads = vec![Grad::constant_value(Interval::ZERO); 7];
            for k in 0..3 {
                let lo = 3.0 * next() - 1.5;
                vars[k] = iv(lo, lo + 0.2 * next());
                grads[k] = Grad::var(vars[k], k);
            }
            let (x, y) = (a.eval(&vars), b.eval(&vars));
            assert_eq!(format!("{x:?}"), format!("{y:?}"), "{}", s.name);
            let (x, y) = (ga.eval(&grads), gb.eval(&grads));
            assert_eq!(format!("{x:?}"), format!("{y:?}"), "{}", s.name);
            checked += 1;
        }
    }
    assert!(checked > 500, "{checked}");
    // Nothing to fold: the same tape.
    let (_, t) = sphere();
    assert!(t.with_zero_vars(&[]).ptr_eq(&t));
    // `x · 0` is not folded where `x` may be undefined.
    let mut c = Context::new();
    let (x, a) = (c.x(), c.named_var("a"));
    let r = c.sqrt(x);
    let f = c.mul(r, a);
    let t = Tape::new(&c, &[f]).unwrap();
    assert_eq!(t.with_zero_vars(&[3]).len(), t.len());
}
