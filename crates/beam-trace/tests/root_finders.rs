//! The root finders on functions whose roots are known: test functions written in interval
//! arithmetic, and the renderer's own evaluator on a unit sphere.
//!
//! Every reliable method must enclose the true first root, answer `NoRoot` only where there
//! is no root, claim `Unique`/`Exists` only where that holds, and agree with the others.

use beam_trace::Geometry;
use beam_trace::ray::Ray;
use beam_trace::root::counter_bisection::section_end;
use beam_trace::root::{Proof, RayFn, RootCounters, RootMethod, RootResult, RootSettings};
use beam_trace::scene::{Csg, Leaf};
use glam::DVec3;
use implicit_expr::Context;
use interval_core::Interval;
use proptest::prelude::*;

fn iv(a: f64, b: f64) -> Interval<f64> {
    Interval::new(a, b).unwrap()
}

fn pt(x: f64) -> Interval<f64> {
    iv(x, x)
}

/// A test function: `g` and `g'` in interval arithmetic, `g` in floating point, and the
/// exact roots in its search interval.
#[derive(Clone, Copy)]
struct TestFn {
    name: &'static str,
    g: fn(Interval<f64>) -> Interval<f64>,
    dg: fn(Interval<f64>) -> Interval<f64>,
    p: fn(f64) -> f64,
    /// A jump of `g` (not continuous on intervals holding it from the left).
    jump: Option<f64>,
    t: (f64, f64),
    roots: &'static [f64],
    /// How much wider than needed `g` encloses values (0: as tight as interval arithmetic).
    /// A possible root may lie up to `blur` (over the slope) before the true one.
    blur: f64,
}

impl RayFn for TestFn {
    fn g(&mut self, t: Interval<f64>) -> Interval<f64> {
        (self.g)(t)
    }

    fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
        ((self.g)(t), (self.dg)(t))
    }

    fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool) {
        let cont = self.jump.is_none_or(|j| !(t.inf() < j && t.sup() >= j));
        ((self.g)(t), cont)
    }

    fn g_point(&mut self, t: f64) -> f64 {
        (self.p)(t)
    }
}

const TWO_ROOTS: TestFn = TestFn {
    name: "(t-1)(t-2)",
    g: |x| (x - pt(1.0)) * (x - pt(2.0)),
    dg: |x| pt(2.0) * x - pt(3.0),
    p: |t| (t - 1.0) * (t - 2.0),
    jump: None,
    t: (0.0, 3.0),
    roots: &[1.0, 2.0],
    blur: 0.0,
};

/// A double root at 1/3 (not a float: no end of a piece can hit it exactly).
const DOUBLE: TestFn = TestFn {
    name: "(t-1/3)^2",
    g: |x| (x - pt(1.0) / pt(3.0)).sqr(),
    dg: |x| pt(2.0) * (x - pt(1.0) / pt(3.0)),
    p: |t| (t - 1.0 / 3.0) * (t - 1.0 / 3.0),
    jump: None,
    t: (0.0, 1.0),
    roots: &[1.0 / 3.0],
    blur: 0.0,
};

const SINE: TestFn = TestFn {
    name: "sin(5t)",
    g: |x| (pt(5.0) * x).sin(),
    dg: |x| pt(5.0) * (pt(5.0) * x).cos(),
    p: |t| (5.0 * t).sin(),
    jump: None,
    t: (0.3, 2.0),
    roots: &[
        std::f64::consts::PI / 5.0,
        2.0 * std::f64::consts::PI / 5.0,
        3.0 * std::f64::consts::PI / 5.0,
    ],
    blur: 0.0,
};

const NONE: TestFn = TestFn {
    name: "t^2+1",
    g: |x| x.sqr() + pt(1.0),
    dg: |x| pt(2.0) * x,
    p: |t| t * t + 1.0,
    jump: None,
    t: (-2.0, 2.0),
    roots: &[],
    blur: 0.0,
};

/// A dip below zero only 2·10⁻⁴ wide, between two samples of the point-sampling baseline.
const DIP: TestFn = TestFn {
    name: "(t-0.7003)^2-1e-8",
    g: |x| (x - pt(0.7003)).sqr() - pt(1e-8),
    dg: |x| pt(2.0) * (x - pt(0.7003)),
    p: |t| (t - 0.7003) * (t - 0.7003) - 1e-8,
    jump: None,
    t: (0.0, 2.0),
    // 0.7003 ∓ 1e-4, as the f64 nearest.
    roots: &[0.7002, 0.7004],
    blur: 0.0,
};

/// A sign change without a root: −1 left of 1, +1 from 1 on.
const JUMP: TestFn = TestFn {
    name: "step",
    g: |x| {
        if x.sup() < 1.0 {
            pt(-1.0)
        } else if x.inf() >= 1.0 {
            pt(1.0)
        } else {
            iv(-1.0, 1.0)
        }
    },
    dg: |x| {
        if x.inf() < 1.0 && x.sup() >= 1.0 {
            Interval::ENTIRE
        } else {
            pt(0.0)
        }
    },
    p: |t| if t < 1.0 { -1.0 } else { 1.0 },
    jump: Some(1.0),
    t: (0.0, 2.0),
    roots: &[],
    blur: 0.0,
};

/// No root: a positive dip to 10⁻⁶ at 1/3, written with `mul` so that its enclosures
/// over pieces around 1/3 wider than 10⁻³ hold 0, then a jump to −1 at 0.6. A sign change
/// seen across the jump proves nothing.
const DIP_THEN_JUMP: TestFn = TestFn {
    name: "dip then jump",
    g: |x| {
        let third = pt(1.0) / pt(3.0);
        let dip = |x: Interval<f64>| (x - third) * (x - third) + pt(1e-6);
        if x.sup() < 0.6 {
            dip(x)
        } else if x.inf() >= 0.6 {
            pt(-1.0)
        } else {
            dip(x).convex_hull(pt(-1.0))
        }
    },
    dg: |x| {
        if x.inf() < 0.6 && x.sup() >= 0.6 {
            Interval::ENTIRE
        } else if x.inf() >= 0.6 {
            pt(0.0)
        } else {
            pt(2.0) * (x - pt(1.0) / pt(3.0))
        }
    },
    p: |t| {
        if t < 0.6 {
            (t - 1.0 / 3.0) * (t - 1.0 / 3.0) + 1e-6
        } else {
            -1.0
        }
    },
    jump: Some(0.6),
    t: (0.0, 1.0),
    roots: &[],
    blur: 0.0,
};

/// The root 0.5 of `t − 0.5` through an enclosure that is sound but 10⁻³ too wide on each
/// side: the ends of pieces near the root straddle 0, which proves no sign change.
const BLURRED: TestFn = TestFn {
    name: "t-0.5, blurred",
    g: |x| x - pt(0.5) + iv(-1e-3, 1e-3),
    dg: |_| pt(1.0),
    p: |t| t - 0.5,
    jump: None,
    t: (0.0, 1.0),
    roots: &[0.5],
    blur: 1e-3,
};

/// No root in `[0, 1]` (the root 1.0005 lies after it), through enclosures of `g` and
/// `g'` that are sound but too wide: pieces near 1 keep 0 in `G`, and Newton images there
/// are not proofs of a root.
const NEAR_MISS: TestFn = TestFn {
    name: "t-1.0005, blurred",
    g: |x| x - pt(1.0005) + iv(-1e-3, 1e-3),
    dg: |_| iv(0.5, 2.0),
    p: |t| t - 1.0005,
    jump: None,
    t: (0.0, 1.0),
    roots: &[],
    blur: 1e-3,
};

const AT_START: TestFn = TestFn {
    name: "t",
    g: |x| x,
    dg: |_| pt(1.0),
    p: |t| t,
    jump: None,
    t: (0.0, 1.0),
    roots: &[0.0],
    blur: 0.0,
};

const AT_END: TestFn = TestFn {
    name: "1-t",
    g: |x| pt(1.0) - x,
    dg: |_| pt(-1.0),
    p: |t| 1.0 - t,
    jump: None,
    t: (0.0, 1.0),
    roots: &[1.0],
    blur: 0.0,
};

const ALL_FNS: [TestFn; 9] = [
    TWO_ROOTS,
    DOUBLE,
    SINE,
    NONE,
    DIP,
    JUMP,
    DIP_THEN_JUMP,
    AT_START,
    AT_END,
];

fn reliable() -> impl Iterator<Item = RootMethod> {
    RootMethod::ALL
        .into_iter()
        .filter(|m| m.finder().is_reliable())
}

fn solve(
    m: RootMethod,
    g: &mut dyn RayFn,
    t: Interval<f64>,
    s: &RootSettings,
) -> (RootResult, RootCounters) {
    let mut c = RootCounters::default();
    let r = m.finder().first_root(g, t, s, &mut c);
    (r, c)
}

/// Tolerance of the comparisons with exact roots given as `f64`.
const TOL: f64 = 1e-12;

fn holds(t: Interval<f64>, r: f64) -> bool {
    t.inf() - TOL <= r && r <= t.sup() + TOL
}

/// `t` starts no later than `r` and ends at most `4ε + blur` before it: a possible root
/// reported for the root `r` (the interval evaluations over pieces just before `r` may
/// hold 0).
fn near(t: Interval<f64>, r: f64, epsilon: f64, blur: f64) -> bool {
    t.inf() - TOL <= r && r <= t.sup() + 4.0 * epsilon + blur
}

/// Checks a reliable method's answer against the exact roots.
fn check(m: RootMethod, f: &TestFn, r: RootResult, s: &RootSettings) {
    let first = f.roots.first().copied();
    match r {
        RootResult::Root { t, proof } => {
            assert!(
                t.subset(iv(f.t.0, f.t.1)),
                "{m} on {}: {t:?} outside T",
                f.name
            );
            if let Some(r0) = first {
                assert!(
                    t.inf() <= r0 + TOL,
                    "{m} on {}: {t:?} starts after the first root {r0}",
                    f.name
                );
            }
            let inside = f.roots.iter().filter(|&&r| holds(t, r)).count();
            match proof {
                Proof::Unique => assert_eq!(inside, 1, "{m} on {}: Unique {t:?}", f.name),
                Proof::Exists => assert!(inside >= 1, "{m} on {}: Exists {t:?}", f.name),
                Proof::Possible => assert!(
                    t.wid() <= s.epsilon,
                    "{m} on {}: Possible {t:?} wider than ε",
                    f.name
                ),
            }
            // A proven root holds the first root. A possible root lies at most a few ε
            // before it (where the enclosures of g over pieces next to the root hold 0).
            if proof != Proof::Possible {
                let r0 = first.unwrap_or_else(|| panic!("{m} on {}: {proof:?} {t:?}", f.name));
                assert!(holds(t, r0), "{m} on {}: {t:?} misses {r0}", f.name);
            } else if let Some(r0) = first {
                assert!(
                    near(t, r0, s.epsilon, f.blur),
                    "{m} on {}: {t:?} far from {r0}",
                    f.name
                );
            }
        }
        RootResult::NoRoot => {
            assert!(first.is_none(), "{m} on {}: NoRoot, root {first:?}", f.name)
        }
        RootResult::Undecided { t } => panic!("{m} on {}: undecided {t:?}", f.name),
    }
}

#[test]
fn names_and_reliability() {
    for m in RootMethod::ALL {
        assert_eq!(m.finder().name(), m.name());
        assert_eq!(m.name().parse::<RootMethod>(), Ok(m));
        let baseline = matches!(m, RootMethod::PointSampling | RootMethod::SphereTracing);
        assert_eq!(m.finder().is_reliable(), !baseline, "{m}");
    }
}

#[test]
fn reliable_methods_find_the_first_root() {
    let s = RootSettings::default();
    for f in ALL_FNS.into_iter().chain([BLURRED, NEAR_MISS]) {
        for m in reliable() {
            let (r, _) = solve(m, &mut f.clone(), iv(f.t.0, f.t.1), &s);
            check(m, &f, r, &s);
        }
    }
}

#[test]
fn reliable_methods_with_a_coarse_epsilon() {
    let s = RootSettings {
        epsilon: 1e-2,
        ..RootSettings::default()
    };
    for f in ALL_FNS.into_iter().chain([BLURRED, NEAR_MISS]) {
        for m in reliable() {
            let (r, _) = solve(m, &mut f.clone(), iv(f.t.0, f.t.1), &s);
            check(m, &f, r, &s);
        }
    }
}

/// Asking only whether a root exists (`narrow_roots` off) changes how narrow a unique root's
/// enclosure is, never whether a root is found: the same kind of answer as the narrowing
/// search, every claim still true of the exact roots, and no more evaluations.
#[test]
fn existence_searches_answer_alike_with_less_work() {
    let narrow = RootSettings::default();
    let exist = narrow.existence();
    let mut widened = 0;
    for f in ALL_FNS.into_iter().chain([BLURRED, NEAR_MISS]) {
        for m in reliable() {
            let t = iv(f.t.0, f.t.1);
            let (a, ca) = solve(m, &mut f.clone(), t, &narrow);
            let (b, cb) = solve(m, &mut f.clone(), t, &exist);
            check(m, &f, b, &exist);
            assert_eq!(
                std::mem::discriminant(&a),
                std::mem::discriminant(&b),
                "{m} on {}: {a:?} against {b:?}",
                f.name
            );
            if let (Some(ta), Some(tb)) = (a.root(), b.root()) {
                assert!(ta.subset(tb), "{m} on {}: {ta:?} not in {tb:?}", f.name);
                widened += usize::from(tb.wid() > narrow.epsilon);
            }
            assert!(
                cb.g_evals + cb.dg_evals + cb.point_evals
                    <= ca.g_evals + ca.dg_evals + ca.point_evals,
                "{m} on {}: {cb:?} against {ca:?}",
                f.name
            );
        }
    }
    // The uniqueness proofs end the existence searches early somewhere.
    assert!(widened > 0);
}

#[test]
fn expected_proofs() {
    let s = RootSettings::default();
    for m in reliable() {
        let proof = |f: TestFn| match solve(m, &mut f.clone(), iv(f.t.0, f.t.1), &s).0 {
            RootResult::Root { proof, .. } => Some(proof),
            _ => None,
        };
        // A simple root of a continuous g is proven by every method (the counter bisection
        // by the end-value test of its final section).
        let simple = proof(TWO_ROOTS);
        assert!(
            matches!(simple, Some(Proof::Unique | Proof::Exists)),
            "{m}: {simple:?}"
        );
        // The jump is never taken for a proven root; the double root cannot be proven by
        // signs (g ≥ 0), nor unique (0 ∈ G' around it).
        assert_eq!(proof(JUMP), Some(Proof::Possible), "{m}");
        assert_eq!(proof(DOUBLE), Some(Proof::Possible), "{m}");
        assert_eq!(proof(DIP_THEN_JUMP), Some(Proof::Possible), "{m}");
    }
    // With a coarse ε the final piece around 1/3 keeps 0 in its enclosure; a sign change
    // after it lies only across the jump, which must not be taken for a root.
    let coarse = RootSettings { epsilon: 1e-2, ..s };
    for m in reliable() {
        let f = DIP_THEN_JUMP;
        let (r, _) = solve(m, &mut f.clone(), iv(f.t.0, f.t.1), &coarse);
        assert!(
            matches!(
                r,
                RootResult::Root {
                    proof: Proof::Possible,
                    ..
                }
            ),
            "{m}: {r:?}"
        );
    }
    // The derivative methods prove uniqueness.
    for m in [
        RootMethod::Mitchell,
        RootMethod::Newton,
        RootMethod::NewtonAlefeldHansen,
        RootMethod::NewtonHc4,
        RootMethod::MrfroNewton,
    ] {
        let (r, _) = solve(m, &mut TWO_ROOTS.clone(), iv(0.0, 3.0), &s);
        assert!(
            matches!(
                r,
                RootResult::Root {
                    proof: Proof::Unique,
                    ..
                }
            ),
            "{m}: {r:?}"
        );
    }
}

#[test]
fn reliable_methods_agree() {
    let s = RootSettings::default();
    for f in ALL_FNS {
        let results: Vec<(RootMethod, RootResult)> = reliable()
            .map(|m| (m, solve(m, &mut f.clone(), iv(f.t.0, f.t.1), &s).0))
            .collect();
        for (ma, ra) in &results {
            for (mb, rb) in &results {
                match (ra, rb) {
                    (RootResult::Root { t: a, .. }, RootResult::Root { t: b, .. }) => {
                        let wa = iv(a.inf() - s.epsilon, a.sup() + s.epsilon);
                        assert!(wa.incident(*b), "{}: {ma} {a:?} vs {mb} {b:?}", f.name);
                    }
                    (RootResult::NoRoot, RootResult::NoRoot) => {}
                    _ => panic!("{}: {ma} {ra:?} vs {mb} {rb:?}", f.name),
                }
            }
        }
    }
}

#[test]
fn undecided_when_the_budget_is_spent() {
    for steps in [0, 1, 3] {
        let s = RootSettings {
            max_steps: steps,
            ..RootSettings::default()
        };
        for m in reliable() {
            let (r, _) = solve(m, &mut TWO_ROOTS.clone(), iv(0.0, 3.0), &s);
            match r {
                RootResult::Undecided { t } => {
                    assert_eq!(t.sup(), 3.0, "{m}: {t:?}");
                    assert!(t.inf() <= 1.0, "{m}: {t:?} skips the root 1");
                }
                RootResult::Root { .. } if steps > 0 => check(m, &TWO_ROOTS, r, &s),
                _ => panic!("{m} with {steps} steps: {r:?}"),
            }
            if steps == 0 {
                assert_eq!(r, RootResult::Undecided { t: iv(0.0, 3.0) }, "{m}");
            }
        }
    }
}

#[test]
fn counters() {
    let s = RootSettings::default();
    let uses_dg = [
        RootMethod::Mitchell,
        RootMethod::Newton,
        RootMethod::NewtonAlefeldHansen,
        RootMethod::NewtonHc4,
        RootMethod::MrfroNewton,
    ];
    for m in RootMethod::ALL {
        let mut c = RootCounters::default();
        let mut f = TWO_ROOTS;
        let first = m.finder().first_root(&mut f, iv(0.0, 3.0), &s, &mut c);
        assert!(first.root().is_some(), "{m}: {first:?}");
        if m.finder().is_reliable() {
            assert!(c.g_evals > 0, "{m}: {c:?}");
            assert_eq!(c.point_evals, 0, "{m}: {c:?}");
            assert!(c.bisections > 0 || c.dg_evals > 0, "{m}: {c:?}");
            assert!(c.bisections <= c.g_evals + c.dg_evals, "{m}: {c:?}");
            assert_eq!(c.dg_evals > 0, uses_dg.contains(&m), "{m}: {c:?}");
        } else {
            assert!(c.point_evals > 0, "{m}: {c:?}");
            assert_eq!((c.g_evals, c.dg_evals), (0, 0), "{m}: {c:?}");
        }
        // Counters accumulate over searches, and a search is deterministic.
        let once = c;
        let again = m.finder().first_root(&mut f, iv(0.0, 3.0), &s, &mut c);
        assert_eq!(again, first, "{m}");
        let mut twice = once;
        twice.add(&once);
        assert_eq!(c, twice, "{m}");
    }
}

#[test]
fn point_sampling_misses_the_thin_dip() {
    let s = RootSettings::default();
    let (r, _) = solve(
        RootMethod::PointSampling,
        &mut DIP.clone(),
        iv(0.0, 2.0),
        &s,
    );
    assert_eq!(r, RootResult::NoRoot);
    // With a step finer than the dip it finds it.
    let fine = RootSettings {
        sampling_step: 1e-5,
        ..s
    };
    let (r, _) = solve(
        RootMethod::PointSampling,
        &mut DIP.clone(),
        iv(0.0, 2.0),
        &fine,
    );
    assert!(holds(r.root().expect("a root"), 0.7002), "{r:?}");
    // Every reliable method finds it.
    for m in reliable() {
        let (r, _) = solve(m, &mut DIP.clone(), iv(0.0, 2.0), &s);
        assert!(r.root().is_some_and(|t| holds(t, 0.7002)), "{m}: {r:?}");
    }
}

/// The unit sphere as the renderer compiles it.
fn sphere() -> Geometry {
    let mut ctx = Context::new();
    let f = implicit_expr::parse::parse(&mut ctx, "x^2+y^2+z^2-1", &[]).unwrap();
    let b = iv(-1.25, 1.25);
    let leaf = Leaf {
        name: "sphere".into(),
        node: f,
        material: Default::default(),
        bounds: [b; 3],
        clipped: false,
    };
    Geometry::new(ctx, vec![leaf], vec![Csg::Leaf(0)]).unwrap()
}

/// The first root of the unit sphere on a ray from outside it, and the distance of the
/// ray's line from the centre.
fn sphere_root(ray: &Ray) -> (f64, f64) {
    let (c, d) = (ray.origin, ray.dir);
    let a = d.dot(d);
    let b = 2.0 * c.dot(d);
    let cc = c.dot(c) - 1.0;
    let dist = (c - d * (c.dot(d) / a)).length();
    let disc = b * b - 4.0 * a * cc;
    if disc < 0.0 {
        return (f64::NAN, dist);
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    let (r1, r2) = (q / a, cc / q);
    (r1.min(r2), dist)
}

#[test]
fn sphere_through_the_renderer() {
    let geometry = sphere();
    let mut ev = geometry.evaluator().beam;
    let s = RootSettings::default();
    let ray = Ray {
        origin: DVec3::new(0.0, 0.0, 3.0),
        dir: DVec3::new(0.0, 0.0, -1.0),
    };
    ev.set_ray(&ray);
    for m in RootMethod::ALL {
        let (r, _) = solve(m, &mut ev, iv(0.0, 4.0), &s);
        let t = r.root().unwrap_or_else(|| panic!("{m}: {r:?}"));
        assert!(
            (t.inf() - 1e-5..=t.sup() + 1e-5).contains(&2.0),
            "{m}: {t:?}"
        );
        if let RootResult::Root { proof, .. } = r
            && m.finder().is_reliable()
        {
            match proof {
                Proof::Possible => assert!(near(t, 2.0, s.epsilon, 0.0), "{m}: {t:?}"),
                _ => assert!(holds(t, 2.0), "{m}: {t:?}"),
            }
        }
    }
    // A ray passing beside the sphere.
    let miss = Ray {
        origin: DVec3::new(1.1, 0.0, 3.0),
        dir: DVec3::new(0.0, 0.0, -1.0),
    };
    ev.set_ray(&miss);
    for m in reliable() {
        assert_eq!(
            solve(m, &mut ev, iv(0.0, 6.0), &s).0,
            RootResult::NoRoot,
            "{m}"
        );
    }
}

#[test]
fn counter_bisection_sections_tile_t() {
    let (lo, hi) = (0.1, 0.7);
    for ns in [0, 1, 5, 30, 59, 60] {
        let n = 1u64 << ns;
        assert_eq!(section_end(lo, hi, 0, ns), lo);
        assert_eq!(section_end(lo, hi, n, ns), hi);
        for k in [0, 1, n / 3, n / 2, n.saturating_sub(1)] {
            let k = k.min(n - 1);
            let (a, b) = (section_end(lo, hi, k, ns), section_end(lo, hi, k + 1, ns));
            assert!(lo <= a && a <= b && b <= hi, "ns {ns} k {k}: [{a}, {b}]");
            if ns < 60 {
                // The halves share the section's ends exactly.
                assert_eq!(section_end(lo, hi, 2 * k, ns + 1), a);
                assert_eq!(section_end(lo, hi, 2 * k + 2, ns + 1), b);
                let m = section_end(lo, hi, 2 * k + 1, ns + 1);
                assert!(a <= m && m <= b);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Random rays from outside at the unit sphere, through the renderer's evaluator.
    #[test]
    fn sphere_rays(
        r in 3.0f64..6.0,
        theta in 0.0f64..std::f64::consts::PI,
        phi in 0.0f64..std::f64::consts::TAU,
        target in prop::array::uniform3(-1.3f64..1.3),
    ) {
        let origin = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos()) * r;
        let ray = Ray { origin, dir: DVec3::from(target) - origin };
        let (t1, dist) = sphere_root(&ray);
        let geometry = sphere();
        let mut ev = geometry.evaluator().beam;
        ev.set_ray(&ray);
        let s = RootSettings::default();
        let t = iv(0.0, 10.0);
        let mut found = Vec::new();
        for m in reliable() {
            let (res, c) = solve(m, &mut ev, t, &s);
            prop_assert!(c.g_evals > 0);
            match res {
                RootResult::Root { t: x, proof } => {
                    if dist > 1.0 + 1e-9 {
                        prop_assert_eq!(proof, Proof::Possible, "{} {:?}", m, x);
                    }
                    if dist < 1.0 - 1e-3 {
                        if proof == Proof::Possible {
                            prop_assert!(near(x, t1, s.epsilon, 0.0), "{}: {:?} vs {}", m, x, t1);
                        } else {
                            prop_assert!(holds(x, t1), "{}: {:?} vs {}", m, x, t1);
                        }
                    }
                    if proof == Proof::Possible {
                        prop_assert!(x.wid() <= s.epsilon);
                    }
                    found.push((m, x));
                }
                RootResult::NoRoot => prop_assert!(dist > 1.0 - 1e-9, "{} missed {}", m, t1),
                RootResult::Undecided { t: x } => prop_assert!(false, "{} undecided {:?}", m, x),
            }
            if dist > 1.0 + 1e-3 {
                prop_assert_eq!(res, RootResult::NoRoot, "{}", m);
            }
        }
        if dist < 1.0 - 1e-3 {
            prop_assert_eq!(found.len(), reliable().count());
        }
    }
}

/// A line whose values are enclosed 1e-13 wide, with an exact derivative: Newton contracts
/// the piece around the root below that, where `g` at both ends of the final piece holds 0.
/// The probe around the final piece still proves the root, and unique (`g'` = 3 excludes 0).
#[test]
fn pieces_narrower_than_the_enclosures_stay_proven() {
    let mut line = TestFn {
        name: "3t - 1",
        g: |x| pt(3.0) * x - pt(1.0) + iv(-1e-13, 1e-13),
        dg: |_| pt(3.0),
        p: |t| 3.0 * t - 1.0,
        jump: None,
        t: (0.0, 1.0),
        roots: &[1.0 / 3.0],
        blur: 1e-13,
    };
    let settings = RootSettings {
        epsilon: 1e-14,
        ..RootSettings::default()
    };
    for m in [RootMethod::Newton, RootMethod::NewtonAlefeldHansen] {
        let (r, _) = solve(m, &mut line, iv(0.0, 1.0), &settings);
        check(m, &line, r, &settings);
        match r {
            RootResult::Root { t, proof } => {
                assert!(t.contains(1.0 / 3.0), "{m:?}: {t:?}");
                assert_eq!(proof, Proof::Unique, "{m:?}: {t:?}");
            }
            other => panic!("{m:?}: {other:?}"),
        }
    }
}
