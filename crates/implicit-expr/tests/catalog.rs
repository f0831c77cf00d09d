//! The surface catalog: every formula parses and compiles (with its gradient and its ray
//! functions), its box really holds surface points, the box's corners and faces are outside
//! where the catalog says the box encloses the surface, the sign convention (negative inside)
//! holds, and lookups by name suggest the closest name.

use implicit_expr::catalog::{self, Surface};
use implicit_expr::{Context, Error, Evaluator, RayFunction, Tape};
use interval_core::Interval;

/// The compiled formula and the evaluator inputs' tail (the parameters' default values).
struct Compiled {
    tape: Tape,
    params: Vec<f64>,
}

fn compile(s: &Surface) -> Compiled {
    let mut ctx = Context::new();
    let f = s
        .build(&mut ctx)
        .unwrap_or_else(|e| panic!("{}: {e}", s.name));
    Compiled {
        tape: Tape::new(&ctx, &[f]).unwrap(),
        params: s.param_values(),
    }
}

impl Compiled {
    fn at(&self, e: &mut Evaluator<f64>, p: [f64; 3]) -> f64 {
        let mut v = p.to_vec();
        v.extend(&self.params);
        e.eval(&v).unwrap()
    }

    fn over(&self, e: &mut Evaluator<Interval<f64>>, b: [Interval<f64>; 3]) -> Interval<f64> {
        let mut v = b.to_vec();
        v.extend(self.params.iter().map(|&p| Interval::new(p, p).unwrap()));
        e.eval(&v).unwrap()
    }
}

/// The corners of a box, in binary order (bit `i` set: the maximum along axis `i`).
fn corners(s: &Surface) -> [[f64; 3]; 8] {
    let (lo, hi) = s.bounds;
    std::array::from_fn(|c| std::array::from_fn(|i| if (c >> i) & 1 == 1 { hi[i] } else { lo[i] }))
}

#[test]
fn names_are_unique_and_kebab_case() {
    let names: Vec<&str> = catalog::names().collect();
    assert_eq!(names.len(), catalog::all().len());
    assert_eq!(names.len(), 16);
    for (i, n) in names.iter().enumerate() {
        assert!(!names[..i].contains(n), "duplicate name {n}");
        assert!(
            !n.is_empty()
                && n.bytes()
                    .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'-')
                && !n.starts_with('-')
                && !n.ends_with('-')
                && !n.contains("--"),
            "{n} is not kebab-case"
        );
        assert_eq!(catalog::get(n).unwrap().name, *n);
    }
    for s in catalog::all() {
        assert!(!s.source.is_empty(), "{}: no source", s.name);
    }
}

#[test]
fn every_formula_parses_and_compiles_with_gradient_and_ray_functions() {
    for s in catalog::all() {
        let mut ctx = Context::new();
        let f = s
            .build(&mut ctx)
            .unwrap_or_else(|e| panic!("{}: {e}", s.name));
        // Slots: x, y, z, then the parameters in declaration order.
        let names: Vec<&str> = ctx.var_names().iter().map(String::as_str).collect();
        let mut expected = vec!["x", "y", "z"];
        expected.extend(s.param_names());
        assert_eq!(names, expected, "{}", s.name);
        let [fx, fy, fz] = ctx.gradient(f);
        let tape = Tape::new(&ctx, &[f, fx, fy, fz]).unwrap();
        assert_eq!(tape.outputs().len(), 4);
        let ray = RayFunction::new(&ctx, f).unwrap();
        assert_eq!(ray.params().len(), s.params.len(), "{}", s.name);
        // The gradient is finite at a generic point of the box.
        let (lo, hi) = s.bounds;
        let mut p: Vec<f64> = (0..3).map(|i| lo[i] + 0.37 * (hi[i] - lo[i])).collect();
        p.extend(s.param_values());
        let mut out = [0.0; 4];
        Evaluator::<f64>::new(&tape)
            .eval_outputs(&p, &mut out)
            .unwrap();
        assert!(out.iter().all(|v| v.is_finite()), "{}: {out:?}", s.name);
    }
}

#[test]
fn parameters_and_boxes() {
    let o = catalog::get("orthocircle").unwrap();
    assert_eq!(o.param_names(), ["a", "b"]);
    assert_eq!(o.param_values(), [0.075, 3.0]);
    let t = catalog::get("twist").unwrap();
    assert_eq!(t.param_names(), ["k"]);
    for s in catalog::all() {
        let (lo, hi) = s.bounds;
        let b = s.bounding_box();
        for i in 0..3 {
            assert!(lo[i] < hi[i], "{}", s.name);
            assert_eq!((b[i].inf(), b[i].sup()), (lo[i], hi[i]));
        }
        let distinct: Vec<&str> = s.param_names();
        for (i, p) in distinct.iter().enumerate() {
            assert!(
                !distinct[..i].contains(p),
                "{}: parameter {p} twice",
                s.name
            );
        }
    }
}

#[test]
fn unknown_names_get_a_suggestion() {
    let err = catalog::get("sphre").unwrap_err();
    assert_eq!(
        err,
        Error::UnknownSurface {
            name: "sphre".into(),
            hint: Some("did you mean 'sphere'?".into()),
        }
    );
    assert_eq!(
        err.to_string(),
        "unknown surface 'sphre'; did you mean 'sphere'?"
    );
    let err = catalog::get("gumdrop-tours").unwrap_err();
    assert!(
        err.to_string().ends_with("did you mean 'gumdrop-torus'?"),
        "{err}"
    );
    let err = catalog::get("Steiner").unwrap_err();
    assert!(
        err.to_string().ends_with("did you mean 'steiner'?"),
        "{err}"
    );
    match catalog::get("no-such-surface-at-all") {
        Err(Error::UnknownSurface { hint: None, .. }) => {}
        other => panic!("{other:?}"),
    }
}

/// The lines through the box along which a sign change is looked for: the three axes through
/// the centre, the four body diagonals and the six face diagonals through the centre.
fn lines(s: &Surface) -> Vec<([f64; 3], [f64; 3])> {
    let (lo, hi) = s.bounds;
    let mid: [f64; 3] = std::array::from_fn(|i| 0.5 * (lo[i] + hi[i]));
    let mut out = Vec::new();
    for axis in 0..3 {
        let (mut a, mut b) = (mid, mid);
        a[axis] = lo[axis];
        b[axis] = hi[axis];
        out.push((a, b));
    }
    let c = corners(s);
    for k in 0..4 {
        out.push((c[k], c[7 - k]));
    }
    for axis in 0..3 {
        let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
        for flip in [false, true] {
            let (mut a, mut b) = (mid, mid);
            a[i] = lo[i];
            b[i] = hi[i];
            (a[j], b[j]) = if flip { (hi[j], lo[j]) } else { (lo[j], hi[j]) };
            out.push((a, b));
        }
    }
    out
}

/// Each box holds points of its surface: `f` changes sign along some line through the box
/// (sampled in `f64`), and the interval value over the whole box contains 0.
#[test]
fn every_box_holds_surface_points() {
    for s in catalog::all() {
        let c = compile(s);
        let mut e = Evaluator::<f64>::new(&c.tape);
        let n = 2000;
        let mut crossings = 0;
        for (a, b) in lines(s) {
            let mut prev: Option<f64> = None;
            for k in 0..=n {
                let t = k as f64 / n as f64;
                let p: [f64; 3] = std::array::from_fn(|i| a[i] + t * (b[i] - a[i]));
                let v = c.at(&mut e, p);
                assert!(!v.is_nan(), "{}: NaN at {p:?}", s.name);
                if let Some(u) = prev
                    && (u < 0.0) != (v < 0.0)
                {
                    crossings += 1;
                }
                prev = Some(v);
            }
        }
        assert!(crossings > 0, "{}: no sign change inside the box", s.name);
        let mut ie = Evaluator::<Interval<f64>>::new(&c.tape);
        let whole = c.over(&mut ie, s.bounding_box());
        assert!(whole.contains(0.0), "{}: {whole:?}", s.name);
    }
}

/// The sign convention: negative at a point inside, positive far outside.
#[test]
fn negative_inside() {
    let inside: [(&str, [f64; 3]); 16] = [
        ("sphere", [0.0, 0.0, 0.0]),
        ("drop", [-0.5, 0.0, 0.0]),
        ("kusner-schmitt", [0.0, 0.0, 0.0]),
        ("crosscap", [0.0, 0.5, 0.0]),
        ("chubs", [0.8, 0.8, 0.8]),
        ("mcmullen-k3", [0.0, 0.0, 0.0]),
        ("horned-cube", [0.0, 0.0, 0.0]),
        ("gumdrop-torus", [0.0, 1.5, 0.0]),
        ("orthocircle", [1.0, 0.0, 0.0]),
        ("steiner", [0.2, 0.2, 0.2]),
        ("blobby", [0.6, 0.0, 0.0]),
        ("tri-trumpet", [0.0, 0.0, 0.0]),
        ("tangle-cube", [2.0, 2.0, 2.0]),
        ("barth-sextic", [0.0, 0.0, 0.0]),
        ("weird", [0.1, 0.1, 0.1]),
        ("twist", [0.0, 0.0, 0.0]),
    ];
    for (name, p) in inside {
        let s = catalog::get(name).unwrap();
        let c = compile(s);
        let mut e = Evaluator::<f64>::new(&c.tape);
        let v = c.at(&mut e, p);
        assert!(v < 0.0, "{name}: f{p:?} = {v}");
    }
    // The small separate sphere of the blobby surface is inside, the gap to it outside.
    let s = catalog::get("blobby").unwrap();
    let c = compile(s);
    let mut e = Evaluator::<f64>::new(&c.tape);
    assert!(c.at(&mut e, [0.0, -0.85, 0.2]) < 0.0);
    assert!(c.at(&mut e, [0.0, -0.55, 0.1]) > 0.0);
}

/// `f > 0` at the corners of the box, except where the catalog documents otherwise: the
/// horned cube's horns run through all eight corners, and two corners of the weird surface's
/// box, `±(1, 1, 1)`, are on its negative side.
#[test]
fn corners_are_outside() {
    for s in catalog::all() {
        let c = compile(s);
        let mut e = Evaluator::<f64>::new(&c.tape);
        let values: Vec<f64> = corners(s).iter().map(|&p| c.at(&mut e, p)).collect();
        match s.name {
            "horned-cube" => assert!(values.iter().all(|&v| v < 0.0), "{values:?}"),
            "weird" => {
                for (k, v) in values.iter().enumerate() {
                    let diagonal = k == 0 || k == 7;
                    assert_eq!(*v < 0.0, diagonal, "weird corner {k}: {v}");
                }
            }
            _ => assert!(values.iter().all(|&v| v > 0.0), "{}: {values:?}", s.name),
        }
    }
}

/// Whether `f > 0` on the box `b` is proven by interval evaluation and bisection.
fn prove_positive(
    c: &Compiled,
    e: &mut Evaluator<Interval<f64>>,
    b: [Interval<f64>; 3],
    depth: u32,
) -> bool {
    let v = c.over(e, b);
    if v.inf() > 0.0 {
        return true;
    }
    if v.sup() <= 0.0 || depth == 0 {
        return false;
    }
    let axis = (0..3)
        .max_by(|&i, &j| b[i].wid().total_cmp(&b[j].wid()))
        .unwrap();
    let (l, r) = b[axis].bisect();
    let (mut bl, mut br) = (b, b);
    bl[axis] = l;
    br[axis] = r;
    prove_positive(c, e, bl, depth - 1) && prove_positive(c, e, br, depth - 1)
}

/// The six faces of a box, as thin boxes.
fn faces(s: &Surface) -> Vec<[Interval<f64>; 3]> {
    let b = s.bounding_box();
    let mut out = Vec::new();
    for axis in 0..3 {
        for v in [b[axis].inf(), b[axis].sup()] {
            let mut f = b;
            f[axis] = Interval::new(v, v).unwrap();
            out.push(f);
        }
    }
    out
}

/// Where the catalog says the box encloses the surface, interval arithmetic proves `f > 0` on
/// all six faces (so the surface does not cross them). Where it says the box clips, the faces
/// do meet the zero set: `f` is negative somewhere on them, or zero where a line of the zero
/// set (the cross-cap's and Steiner's axes) passes through.
#[test]
fn box_faces_are_outside_unless_clipped() {
    for s in catalog::all() {
        let c = compile(s);
        if !s.is_clipped() {
            let mut e = Evaluator::<Interval<f64>>::new(&c.tape);
            for face in faces(s) {
                assert!(
                    prove_positive(&c, &mut e, face, 22),
                    "{}: cannot prove f > 0 on the face {face:?}",
                    s.name
                );
            }
            continue;
        }
        let mut e = Evaluator::<f64>::new(&c.tape);
        let (mut negative, mut zero) = (false, false);
        let n = 40;
        for face in faces(s) {
            for i in 0..=n {
                for j in 0..=n {
                    let mut k = 0;
                    let p: [f64; 3] = std::array::from_fn(|a| {
                        let x = face[a];
                        if x.is_singleton() {
                            return x.inf();
                        }
                        let t = if k == 0 { i } else { j } as f64 / n as f64;
                        k += 1;
                        x.inf() + t * (x.sup() - x.inf())
                    });
                    let v = c.at(&mut e, p);
                    negative |= v < 0.0;
                    zero |= v == 0.0;
                }
            }
        }
        assert!(
            negative || zero,
            "{} is marked clipped but its faces are outside",
            s.name
        );
        if matches!(s.name, "crosscap" | "steiner") {
            // Only the measure-zero lines of the zero set cross the faces.
            assert!(!negative && zero, "{}", s.name);
        }
    }
}
