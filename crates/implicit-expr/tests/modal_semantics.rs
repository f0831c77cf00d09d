//! Modal semantics (thesis 3.5.1 and 3.5.2): the interpretability theorems chosen and
//! evaluated from the formula alone, checked against exact rationals and against brute-force
//! min-max computations of `f*` and `f**`.

use implicit_expr::parse::parse;
use implicit_expr::semantics::{Estimate, MAX_TREE_SIZE, Monotony, Theorem, analyze};
use implicit_expr::{Context, Error, Evaluator, NodeId, Tape, Var};
use interval_core::{Interval, Modal};
use proptest::prelude::*;
use rug::Rational;

fn m(a: f64, b: f64) -> Modal<f64> {
    Modal::new(a, b).unwrap()
}

fn q(n: i64, d: i64) -> Rational {
    Rational::from((n, d))
}

fn r(x: f64) -> Rational {
    Rational::from_f64(x).unwrap()
}

/// `x` is within `k` ulps of the rational `v`.
fn within_ulps(x: f64, v: &Rational, k: u32) -> bool {
    let mut lo = x;
    let mut hi = x;
    for _ in 0..k {
        lo = lo.next_down();
        hi = hi.next_up();
    }
    r(lo) <= *v && *v <= r(hi)
}

/// The outer estimate contains the exact `[a, b]` (modal inclusion) and is within a few
/// ulps of it.
fn assert_outer_tight(e: &Estimate, a: &Rational, b: &Rational) {
    let o = e.outer.expect("an outer estimate");
    assert!(r(o.first()) <= *a && r(o.second()) >= *b, "{e}");
    assert!(
        within_ulps(o.first(), a, 4) && within_ulps(o.second(), b, 4),
        "{e}"
    );
}

/// The inner estimate is contained in the exact `[a, b]` and within a few ulps of it.
fn assert_inner_tight(e: &Estimate, a: &Rational, b: &Rational) {
    let i = e.inner.expect("an inner estimate");
    assert!(r(i.first()) >= *a && r(i.second()) <= *b, "{e}");
    assert!(
        within_ulps(i.first(), a, 4) && within_ulps(i.second(), b, 4),
        "{e}"
    );
}

fn outer_estimates(estimates: &[Estimate]) -> Vec<Theorem> {
    estimates
        .iter()
        .filter(|e| e.outer.is_some())
        .map(|e| e.theorem)
        .collect()
}

/// The thesis' example of 3.5.2, from the formula text alone.
#[test]
fn thesis_example_xy_over_x_plus_y() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "x*y/(x+y)", &[]).unwrap();
    let res = analyze(&ctx, f, &[m(2.0, 3.0), m(4.0, 3.0)]).unwrap();
    println!("{res}");

    let names: Vec<&str> = (0..4).map(|i| res.split.name(i)).collect();
    assert_eq!(names, ["x1", "y1", "x2", "y2"]);
    use Monotony::{Decreasing, Increasing};
    assert_eq!(
        res.incidence_monotony,
        [Increasing, Increasing, Decreasing, Decreasing]
    );
    assert!(res.variables.iter().all(|v| v.totally_monotone));
    assert!(res.variables.iter().all(|v| v.monotony == Increasing));
    assert!(res.tree_optimal);

    // 1. Theorem 5: Xt* = ([2,3], [4,4], [2,3], [4,4]), fR(Xt*) = [8/7, 2].
    let t5 = res.estimate(Theorem::Theorem5).unwrap();
    assert_eq!(
        t5.vector,
        [m(2.0, 3.0), m(4.0, 4.0), m(2.0, 3.0), m(4.0, 4.0)]
    );
    assert_outer_tight(t5, &q(8, 7), &q(2, 1));

    // 2. Theorem 3: XDt* = ([2,3], [4,4], [3,2], [4,4]), fR(XDt*) = [4/3, 12/7].
    let t3 = res.estimate(Theorem::Theorem3).unwrap();
    assert_eq!(t3.monotone, [Var::X]);
    assert_eq!(
        t3.vector,
        [m(2.0, 3.0), m(4.0, 4.0), m(3.0, 2.0), m(4.0, 4.0)]
    );
    assert_outer_tight(t3, &q(4, 3), &q(12, 7));

    // 3. Theorem 6: XD = ([2,3], [4,3], [3,2], [3,4]), f*(X) = fR(XD) = f**(X) = [4/3, 3/2].
    let t6 = res.estimate(Theorem::Theorem6).unwrap();
    assert_eq!(
        t6.vector,
        [m(2.0, 3.0), m(4.0, 3.0), m(3.0, 2.0), m(3.0, 4.0)]
    );
    assert_outer_tight(t6, &q(4, 3), &q(3, 2));
    assert_inner_tight(t6, &q(4, 3), &q(3, 2));
    assert!(res.is_optimal());
    assert_eq!(res.outer().theorem, Theorem::Theorem6);
    assert_eq!(res.inner().theorem, Theorem::Theorem6);

    // f*(X) = fR(XD) ⊆ fR(XDt*) ⊆ fR(Xt*).
    let (o6, o3, o5) = (t6.outer.unwrap(), t3.outer.unwrap(), t5.outer.unwrap());
    assert!(o6.subset(o3) && o3.subset(o5));
    assert_eq!(
        outer_estimates(&res.estimates),
        [Theorem::Theorem5, Theorem::Theorem3, Theorem::Theorem6]
    );
    for e in &res.estimates {
        println!("{:.4}", e);
    }
    for t in [Theorem::Theorem5, Theorem::Theorem3, Theorem::Theorem6] {
        println!("{t}: {}", res.estimate(t).unwrap().outer.unwrap());
    }

    // The inner estimates of theorem 4 lie inside f**(X) = [4/3, 3/2].
    for e in res
        .estimates
        .iter()
        .filter(|e| e.theorem == Theorem::Theorem4)
    {
        let i = e.inner.unwrap();
        assert!(r(i.first()) >= q(4, 3) && r(i.second()) <= q(3, 2), "{e}");
    }
}

/// Thesis 3.5.1: `[1, 3] + [3, 2] = [4, 5]`, theorems 1 and 2 directly.
#[test]
fn uni_incident_sum() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "x + y", &[]).unwrap();
    let res = analyze(&ctx, f, &[m(1.0, 3.0), m(3.0, 2.0)]).unwrap();
    let t1 = res.estimate(Theorem::Theorem1).unwrap();
    let t2 = res.estimate(Theorem::Theorem2).unwrap();
    assert_eq!(t1.vector, [m(1.0, 3.0), m(3.0, 2.0)]);
    assert_eq!(t1.outer.unwrap(), Modal::new(4.0, 5.0).unwrap());
    assert_eq!(t2.inner.unwrap(), Modal::new(4.0, 5.0).unwrap());
    assert!(res.estimate(Theorem::Theorem5).is_none());
    assert!(res.estimate(Theorem::Theorem3).is_none());
    assert!(res.is_optimal());
}

/// Uni-incident but not monotone: `sqr(x - y)` across zero is not tree-optimal, so only
/// theorems 1 and 2 apply (both with the plain vector).
#[test]
fn uni_incident_not_tree_optimal() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "(x - y)^2", &[]).unwrap();
    let res = analyze(&ctx, f, &[m(-1.0, 1.0), m(1.0, -1.0)]).unwrap();
    assert!(!res.tree_optimal && !res.is_optimal());
    assert_eq!(res.outer().theorem, Theorem::Theorem1);
    assert_eq!(res.inner().theorem, Theorem::Theorem2);
    // f*(X) = [min_x max_y (x-y)², max_x min_y (x-y)²] = [1, 0].
    let o = res.outer().outer.unwrap();
    assert!(o.first() <= 1.0 && o.second() >= 0.0);
    // f**(X) = [max_y min_x, min_y max_x] = [0, 1].
    let i = res.inner().inner.unwrap();
    assert!(i.first() >= 0.0 && i.second() <= 1.0);
}

/// A multi-incident improper component without monotony: only theorem 5 gives an outer
/// estimate.
#[test]
fn non_monotone_only_theorem_5() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "x*x*x - x + y", &[]).unwrap();
    let res = analyze(&ctx, f, &[m(1.0, -1.0), m(0.0, 1.0)]).unwrap();
    let x = &res.variables[0];
    assert_eq!((x.incidences, x.monotony), (3, Monotony::Undecided));
    assert!(!x.totally_monotone);
    assert_eq!(outer_estimates(&res.estimates), [Theorem::Theorem5]);
    let t5 = res.outer();
    assert_eq!(t5.theorem, Theorem::Theorem5);
    assert_eq!(
        t5.vector,
        [m(1.0, 1.0), m(1.0, 1.0), m(1.0, 1.0), m(0.0, 1.0)]
    );
    // f*(X) = [max_x (x³ - x), min_x (x³ - x) + 1] = [2/(3√3), 1 - 2/(3√3)].
    let c = 2.0 / (3.0 * 3f64.sqrt());
    let o = t5.outer.unwrap();
    assert!(o.first() <= c && o.second() >= 1.0 - c, "{t5}");
    // The proper y is uni-incident: theorem 2 for the inner estimate, f**(X) = f*(X) here.
    assert_eq!(res.inner().theorem, Theorem::Theorem2);
    let i = res.inner().inner.unwrap();
    assert!(
        i.first() >= c - 1e-12 && i.second() <= 1.0 - c + 1e-12,
        "{res}"
    );
    assert!(!res.is_optimal());
}

/// `exp(x) - sqrt(x)`: the incidences have opposite senses, the variable is increasing, and
/// the result is optimal for proper and improper `X`.
#[test]
fn exp_minus_sqrt_is_optimal() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "exp(x) - sqrt(x)", &[]).unwrap();
    let e = std::f64::consts::E;
    let (lo, hi) = (e - 1.0, e.powi(4) - 2.0);
    for (x, want) in [((1.0, 4.0), (lo, hi)), ((4.0, 1.0), (hi, lo))] {
        let res = analyze(&ctx, f, &[m(x.0, x.1)]).unwrap();
        assert_eq!(
            res.incidence_monotony,
            [Monotony::Increasing, Monotony::Decreasing]
        );
        assert_eq!(res.variables[0].monotony, Monotony::Increasing);
        assert!(res.is_optimal(), "{res}");
        let t6 = res.outer();
        assert_eq!(t6.vector, [m(x.0, x.1), m(x.1, x.0)]);
        let (o, i) = (t6.outer.unwrap(), t6.inner.unwrap());
        let tol = 1e-12;
        assert!(o.first() <= want.0 + tol && o.second() >= want.1 - tol);
        assert!((o.first() - want.0).abs() < tol && (o.second() - want.1).abs() < tol);
        assert!((i.first() - want.0).abs() < tol && (i.second() - want.1).abs() < tol);
        assert!(i.with_rounding().subset(o));
    }
}

/// `x / (x + y)`: incidences of contrary senses (`x1` increasing, `x2` decreasing), but the
/// variable as a whole is increasing, so theorem 6 dualises `x2`.
#[test]
fn contrary_incidences_are_dualised() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "x / (x + y)", &[]).unwrap();
    let res = analyze(&ctx, f, &[m(3.0, 1.0), m(1.0, 2.0)]).unwrap();
    assert!(res.is_optimal(), "{res}");
    assert_eq!(res.outer().vector, [m(3.0, 1.0), m(1.0, 3.0), m(1.0, 2.0)]);
    // f*(X) = [min_y max_x, max_y min_x] = [3/5, 1/2].
    let (o, i) = (res.outer().outer.unwrap(), res.inner().inner.unwrap());
    assert!(r(o.first()) <= q(3, 5) && r(o.second()) >= q(1, 2));
    assert!(r(i.first()) >= q(3, 5) && r(i.second()) <= q(1, 2));
    assert!(within_ulps(o.first(), &q(3, 5), 4) && within_ulps(o.second(), &q(1, 2), 4));
}

#[test]
fn point_components_are_constants() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "(x - y)*(x + y)", &[]).unwrap();
    // y is a point, a constant of the formula: (x - 2)(x + 2) over x in [3, 4].
    let res = analyze(&ctx, f, &[m(3.0, 4.0), m(2.0, 2.0)]).unwrap();
    assert!(res.is_optimal(), "{res}");
    let o = res.outer().outer.unwrap();
    assert!(o.first() <= 5.0 && o.second() >= 12.0);
    assert!((o.first() - 5.0).abs() < 1e-12 && (o.second() - 12.0).abs() < 1e-12);
}

#[test]
fn errors() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "sqrt(x) + x", &[]).unwrap();
    let e = analyze(&ctx, f, &[m(-1.0, 1.0)]).unwrap_err();
    assert!(matches!(e, Error::Unsupported(_)), "{e}");
    assert!(e.to_string().contains("sqrt"), "{e}");
    let g = parse(&mut ctx, "x / y", &[]).unwrap();
    let e = analyze(&ctx, g, &[m(1.0, 2.0)]).unwrap_err();
    assert_eq!(e, Error::MissingVar { slot: 1, given: 1 });
    let e = analyze(&ctx, g, &[m(1.0, 2.0), m(1.0, -1.0)]).unwrap_err();
    assert!(e.to_string().contains("divisor"), "{e}");
    let e = analyze(&ctx, g, &[m(1.0, f64::INFINITY), m(1.0, 2.0)]).unwrap_err();
    assert!(e.to_string().contains("unbounded"), "{e}");
    let h = parse(&mut ctx, "floor(x) * x", &[]).unwrap();
    assert!(analyze(&ctx, h, &[m(0.5, 1.5)]).is_err());
    assert!(analyze(&ctx, h, &[m(0.25, 0.75)]).is_ok());

    // A graph of a few hundred nodes whose tree is astronomically large.
    let mut f = ctx.x();
    for _ in 0..100 {
        let s = ctx.sqrt(f);
        f = ctx.add(s, f);
    }
    let e = analyze(&ctx, f, &[m(1.0, 2.0)]).unwrap_err();
    assert!(e.to_string().contains(&MAX_TREE_SIZE.to_string()), "{e}");
}

// ---------------------------------------------------------------------------------------
// Brute force: f* and f** by nested min/max over grids, with a Lipschitz error bound.

/// A small rational formula.
#[derive(Clone, Debug)]
enum E {
    Var(u32),
    Const(i32),
    Add(Box<E>, Box<E>),
    Sub(Box<E>, Box<E>),
    Mul(Box<E>, Box<E>),
    Div(Box<E>, Box<E>),
    Sqr(Box<E>),
}

fn formula(vars: u32) -> impl Strategy<Value = E> {
    let leaf = prop_oneof![
        3 => (0..vars).prop_map(E::Var),
        1 => (1..4i32).prop_map(E::Const),
    ];
    leaf.prop_recursive(4, 16, 2, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| E::Add(a.into(), b.into())),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| E::Sub(a.into(), b.into())),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| E::Mul(a.into(), b.into())),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| E::Div(a.into(), b.into())),
            inner.prop_map(|a| E::Sqr(a.into())),
        ]
    })
}

fn build(ctx: &mut Context, e: &E) -> NodeId {
    match e {
        E::Var(v) => ctx.var(Var(*v)).unwrap(),
        E::Const(c) => ctx.constant(f64::from(*c)).unwrap(),
        E::Add(a, b) | E::Sub(a, b) | E::Mul(a, b) | E::Div(a, b) => {
            let (a2, b2) = (build(ctx, a), build(ctx, b));
            match e {
                E::Add(..) => ctx.add(a2, b2),
                E::Sub(..) => ctx.sub(a2, b2),
                E::Mul(..) => ctx.mul(a2, b2),
                _ => ctx.div(a2, b2),
            }
        }
        E::Sqr(a) => {
            let a = build(ctx, a);
            ctx.sqr(a)
        }
    }
}

/// Grid estimates of `f*(X)` and `f**(X)` and a bound `delta` on their error.
struct Brute {
    star: (f64, f64),
    star2: (f64, f64),
    delta: f64,
}

fn brute(ctx: &mut Context, f: NodeId, x: &[Modal<f64>], n: usize) -> Option<Brute> {
    // Lipschitz constants from interval enclosures of the partial derivatives.
    let props: Vec<Interval<f64>> = x.iter().map(|m| m.prop()).collect();
    let mut delta = 0.0;
    for (k, p) in props.iter().enumerate() {
        let d = ctx.deriv(f, Var(k as u32));
        let l = ctx.eval::<Interval<f64>>(d, &props).ok()?.mag();
        if !l.is_finite() {
            return None;
        }
        delta += l * p.wid() / (n - 1) as f64 / 2.0;
    }
    let tape = Tape::new(ctx, &[f]).ok()?;
    let mut ev = Evaluator::<f64>::new(&tape);
    let grid = |m: Modal<f64>| -> Vec<f64> {
        let (lo, hi) = (m.prop().inf(), m.prop().sup());
        (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect()
    };
    let proper: Vec<usize> = (0..x.len()).filter(|&k| x[k].is_proper()).collect();
    let improper: Vec<usize> = (0..x.len()).filter(|&k| !x[k].is_proper()).collect();
    let points = |idx: &[usize]| -> Vec<Vec<(usize, f64)>> {
        let mut out = vec![Vec::new()];
        for &k in idx {
            out = out
                .into_iter()
                .flat_map(|p| {
                    grid(x[k]).into_iter().map(move |v| {
                        let mut q = p.clone();
                        q.push((k, v));
                        q
                    })
                })
                .collect();
        }
        out
    };
    let (pp, ii) = (points(&proper), points(&improper));
    let mut vals = vec![vec![0.0; ii.len()]; pp.len()];
    let mut arg = vec![0.0; 3.max(x.len())];
    for (a, p) in pp.iter().enumerate() {
        for (b, i) in ii.iter().enumerate() {
            for &(k, v) in p.iter().chain(i) {
                arg[k] = v;
            }
            let v = ev.eval(&arg).ok()?;
            if !v.is_finite() {
                return None;
            }
            vals[a][b] = v;
        }
    }
    let minmax = |outer_min: bool, rows: &dyn Fn(usize) -> Vec<f64>, count: usize| {
        let inner: Vec<f64> = (0..count)
            .map(|k| {
                let row = rows(k);
                if outer_min {
                    row.into_iter().fold(f64::NEG_INFINITY, f64::max)
                } else {
                    row.into_iter().fold(f64::INFINITY, f64::min)
                }
            })
            .collect();
        if outer_min {
            inner.into_iter().fold(f64::INFINITY, f64::min)
        } else {
            inner.into_iter().fold(f64::NEG_INFINITY, f64::max)
        }
    };
    let by_p = |a: usize| vals[a].clone();
    let by_i = |b: usize| vals.iter().map(|row| row[b]).collect::<Vec<f64>>();
    Some(Brute {
        // f* = [min_p max_i f, max_p min_i f]
        star: (
            minmax(true, &by_p, pp.len()),
            minmax(false, &by_p, pp.len()),
        ),
        // f** = [max_i min_p f, min_i max_p f]
        star2: (
            minmax(false, &by_i, ii.len()),
            minmax(true, &by_i, ii.len()),
        ),
        delta,
    })
}

fn modal_arg(lo: i32, hi: i32) -> impl Strategy<Value = Modal<f64>> {
    (lo..=hi, lo..=hi).prop_map(|(a, b)| m(f64::from(a) / 4.0, f64::from(b) / 4.0))
}

/// Checks every estimate of `analyze` against the brute force; returns whether the case was
/// checked (it is skipped where `f` is not defined on `Prop(X)`).
fn check(e: &E, x: &[Modal<f64>]) -> Result<bool, TestCaseError> {
    let mut ctx = Context::new();
    let f = build(&mut ctx, e);
    let Ok(res) = analyze(&ctx, f, x) else {
        return Ok(false);
    };
    let Some(b) = brute(&mut ctx, f, x, 17) else {
        return Ok(false);
    };
    let tol = |v: f64| b.delta + 1e-9 * (1.0 + v.abs());
    for est in &res.estimates {
        if let Some(o) = est.outer {
            prop_assert!(
                o.first() <= b.star.0 + tol(b.star.0),
                "{}\n{:?}",
                est,
                b.star
            );
            prop_assert!(
                o.second() >= b.star.1 - tol(b.star.1),
                "{}\n{:?}",
                est,
                b.star
            );
        }
        if let Some(i) = est.inner {
            prop_assert!(
                i.first() >= b.star2.0 - tol(b.star2.0),
                "{}\n{:?}",
                est,
                b.star2
            );
            prop_assert!(
                i.second() <= b.star2.1 + tol(b.star2.1),
                "{}\n{:?}",
                est,
                b.star2
            );
        }
    }
    if res.is_optimal() {
        let (o, i) = (res.outer().outer.unwrap(), res.inner().inner.unwrap());
        for (v, w) in [
            (o.first(), b.star.0),
            (o.second(), b.star.1),
            (i.first(), b.star2.0),
            (i.second(), b.star2.1),
        ] {
            prop_assert!(
                (v - w).abs() <= tol(w),
                "{}\n{:?} {:?}",
                res,
                b.star,
                b.star2
            );
        }
    }
    Ok(true)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(384))]

    /// Every outer estimate contains `f*(X)`, every inner one lies in `f**(X)`, and an
    /// optimal result equals both, each up to the grid's error bound. Positive domains:
    /// mostly monotone formulas, where theorems 3, 4 and 6 apply.
    #[test]
    fn estimates_bracket_brute_force_positive(
        e in formula(3),
        x in prop::collection::vec(modal_arg(1, 12), 3),
    ) {
        check(&e, &x)?;
    }

    /// The same on domains around zero: non-monotone formulas, not tree-optimal ones.
    #[test]
    fn estimates_bracket_brute_force_signed(
        e in formula(2),
        x in prop::collection::vec(modal_arg(-8, 8), 2),
    ) {
        check(&e, &x)?;
    }
}
