//! WGSL generation: every generated module is parsed and validated by naga.
//!
//! The interval functions need an interval library. The preludes below are type-checking
//! stand-ins only: they declare the type and every function of the contract with the right
//! signatures so that naga can check the generated code, but their bodies are NOT sound
//! interval arithmetic (no outward rounding, no domain handling) and must never be used to
//! compute anything.

use std::time::Instant;

use implicit_expr::parse::parse;
use implicit_expr::ray::{RAY_VARS, RayFunction};
use implicit_expr::wgsl::{
    self, Generator, LIBRARY, LIBRARY_FUNCTIONS, binary_function, enclose_f32, f32_literal,
    unary_function,
};
use implicit_expr::{BinaryOp, Constant, Context, Error, NodeId, Tape, UnaryOp};

/// Type-checking prelude: the `Interval` declaration, then every function of the contract
/// with its signature and a placeholder body. NOT a sound interval library.
fn prelude(interval: &str) -> String {
    let mut s = format!("{interval}\n");
    for f in LIBRARY {
        s.push_str(&format!(
            "{} {{ return Interval(0.0f, 0.0f); }}\n",
            f.signature()
        ));
    }
    s
}

/// The prelude with `Interval` as a struct.
fn struct_prelude() -> String {
    prelude("struct Interval { lo: f32, hi: f32 }")
}

/// The prelude with `Interval` as `vec2<f32>`.
fn alias_prelude() -> String {
    prelude("alias Interval = vec2<f32>;")
}

/// Parses and validates `source` with naga; panics with naga's report on failure.
fn validate(source: &str) {
    let module = match naga::front::wgsl::parse_str(source) {
        Ok(m) => m,
        Err(e) => panic!("parse error:\n{}", e.emit_to_string(source)),
    };
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    );
    if let Err(e) = validator.validate(&module) {
        panic!("validation error:\n{}", e.emit_to_string(source));
    }
}

/// A caller of the generated interval function, to check that the documented layout can be
/// called as documented.
fn interval_caller(g: &Generator) -> String {
    let mut args: Vec<String> = g
        .inputs()
        .iter()
        .map(|_| "Interval(0.0f, 1.0f)".to_string())
        .collect();
    if g.param_count() > 0 {
        args.push("params".into());
    }
    let field = if g.output_count() > 1 { ".out0" } else { "" };
    format!(
        "fn call_{0}() -> Interval {{\n    var params: array<Interval, {1}>;\n    return {0}({2}){field};\n}}\n",
        g.name(),
        g.param_count().max(1),
        args.join(", ")
    )
}

/// A caller of the generated point function.
fn point_caller(g: &Generator) -> String {
    let mut args: Vec<String> = g.inputs().iter().map(|_| "0.5f".to_string()).collect();
    if g.param_count() > 0 {
        args.push("params".into());
    }
    let field = if g.output_count() > 1 { ".out0" } else { "" };
    format!(
        "fn call_{0}() -> f32 {{\n    var params: array<f32, {1}>;\n    return {0}({2}){field};\n}}\n",
        g.point_name(),
        g.param_count().max(1),
        args.join(", ")
    )
}

/// Validates the interval function with both preludes and the point function alone, each
/// with a caller; returns the seconds the struct-prelude validation took.
fn check(g: &Generator) -> f64 {
    let interval = g.interval_source();
    let start = Instant::now();
    validate(&format!(
        "{}\n{interval}\n{}",
        struct_prelude(),
        interval_caller(g)
    ));
    let secs = start.elapsed().as_secs_f64();
    validate(&format!(
        "{}\n{interval}\n{}",
        alias_prelude(),
        interval_caller(g)
    ));
    // The point function needs no library.
    validate(&format!("{}\n{}", g.point_source(), point_caller(g)));
    // Both in one module, as a backend would paste them.
    validate(&format!("{}\n{}", struct_prelude(), g.source()));
    secs
}

fn sphere() -> (Context, NodeId) {
    let mut c = Context::new();
    let f = parse(&mut c, "x^2 + y^2 + z^2 - 1", &[]).unwrap();
    (c, f)
}

#[test]
fn sphere_validates() {
    let (c, f) = sphere();
    let tape = Tape::new(&c, &[f]).unwrap();
    let g = Generator::new(&tape, "sphere").unwrap();
    check(&g);
    let src = g.interval_source();
    assert!(src.contains("fn sphere(x: Interval, y: Interval, z: Interval) -> Interval {"));
    assert!(src.contains("Interval(1.0f, 1.0f)"));
    assert!(!src.contains("struct"));
    assert_eq!(g.required_functions(), ["i_add", "i_sub", "i_sqr"]);
    assert_eq!(g.param_count(), 0);
    let point = g.point_source();
    assert!(point.contains("fn sphere_point(x: f32, y: f32, z: f32) -> f32 {"));
    // The shorthands give the same text.
    assert_eq!(wgsl::interval_function(&tape, "sphere").unwrap(), src);
    assert_eq!(wgsl::point_function(&tape, "sphere").unwrap(), point);
    assert_eq!(wgsl::required_functions(&tape), g.required_functions());
}

/// A graph that uses every operation, the integer powers and constants of every kind.
fn every_op() -> (Context, NodeId) {
    let mut c = Context::new();
    let (x, y, z) = (c.x(), c.y(), c.z());
    let mut acc = c.add(x, y);
    for op in UnaryOp::ALL {
        let u = c.unary(op, acc);
        acc = c.add(u, z);
    }
    for op in BinaryOp::ALL {
        let b = c.binary(op, acc, y);
        acc = c.sub(b, x);
    }
    for n in [3, -3, 7, 100, -1000, i32::MAX, i32::MIN] {
        let p = c.pown(x, n);
        acc = c.add(acc, p);
    }
    for text in ["0.1", "3", "-2.5", "1e-40", "1e300", "-1e300", "1e-300"] {
        let k = c.constant_enclosed(Constant::from_decimal(text.trim_start_matches('-')).unwrap());
        let k = if text.starts_with('-') { c.neg(k) } else { k };
        acc = c.mul(acc, k);
    }
    let entire = Constant::enclosed(0.0, -1e300, 1e300).unwrap();
    let e = c.constant_enclosed(entire);
    acc = c.add(acc, e);
    let pi = c.constant_enclosed(Constant::pi());
    acc = c.add(acc, pi);
    (c, acc)
}

#[test]
fn every_operation_validates() {
    let (c, f) = every_op();
    let tape = Tape::new(&c, &[f]).unwrap();
    let g = Generator::new(&tape, "every_op").unwrap();
    check(&g);
    // Every library function is needed by this tape.
    assert_eq!(g.required_functions(), LIBRARY_FUNCTIONS);
    let src = g.interval_source();
    assert!(src.contains("i_pown(v"));
    assert!(src.contains("(-2147483647i - 1i)"));
    assert!(src.contains("i_at_least(0x1.fffffep127f)"));
    assert!(src.contains("i_entire()"));
}

#[test]
fn parsed_formula_validates() {
    let mut c = Context::new();
    let text = "sqrt(abs(x)) + exp(-y) - ln(z^2 + 1) * log(x^2 + 2) + sin(x) * cos(y) / tan(z) \
                + asin(x / 2) + acos(y / 3) + atan(z) + floor(x) + ceil(y) + round(z) + not(x) \
                + min(x, y, z) + max(x, 2) + pow(x, y) + x^-3 + recip(y) + sqr(z) + pi * e";
    let f = parse(&mut c, text, &[]).unwrap();
    let tape = Tape::new(&c, &[f]).unwrap();
    check(&Generator::new(&tape, "formula").unwrap());
}

#[test]
fn parameters_go_to_the_array() {
    let mut c = Context::new();
    let f = parse(&mut c, "(x - a)^2 + y^2 + z^2 - r^2", &["r", "a"]).unwrap();
    let tape = Tape::new(&c, &[f]).unwrap();
    let g = Generator::new(&tape, "moved_sphere").unwrap();
    assert_eq!(g.param_count(), 2);
    check(&g);
    let src = g.interval_source();
    assert!(src.contains(
        "fn moved_sphere(x: Interval, y: Interval, z: Interval, p: array<Interval, 2>) -> Interval {"
    ));
    // r is slot 3 (p[0]), a is slot 4 (p[1]).
    assert!(src.contains("= p[0];") && src.contains("= p[1];"));
    assert!(g.point_source().contains("p: array<f32, 2>) -> f32 {"));

    // Fewer named inputs: more slots in the array.
    let g2 = Generator::new(&tape, "all_in_p")
        .unwrap()
        .with_inputs::<&str>(&[])
        .unwrap();
    assert_eq!(g2.param_count(), 5);
    check(&g2);
    assert!(
        g2.interval_source()
            .contains("fn all_in_p(p: array<Interval, 5>) -> Interval {")
    );
}

#[test]
fn ray_functions_multi_output() {
    let mut c = Context::new();
    let f = parse(&mut c, "x^2 + y^2 + z^2 - r^2 + sin(k * x)", &["r", "k"]).unwrap();
    let ray = RayFunction::new(&c, f).unwrap();
    let tape = ray.g_dg_tape();
    assert_eq!(tape.ssa_outputs().len(), 2);
    let g = Generator::new(tape, "g_dg")
        .unwrap()
        .with_inputs(&RAY_VARS)
        .unwrap();
    assert_eq!(g.param_count(), 2);
    assert_eq!(g.output_count(), 2);
    check(&g);
    let src = g.interval_source();
    assert!(src.contains("struct g_dg_out { out0: Interval, out1: Interval }"));
    assert!(src.contains(
        "fn g_dg(cx: Interval, cy: Interval, cz: Interval, t: Interval, dx: Interval, \
         dy: Interval, dz: Interval, p: array<Interval, 2>) -> g_dg_out {"
    ));
    assert!(src.contains("return g_dg_out(v"));
    let point = g.point_source();
    assert!(point.contains("struct g_dg_point_out { out0: f32, out1: f32 }"));

    // g alone, one output, in the same module as g and g'.
    let g_only = Generator::new(ray.g_tape(), "g")
        .unwrap()
        .with_inputs(&RAY_VARS)
        .unwrap();
    assert_eq!(g_only.output_count(), 1);
    validate(&format!(
        "{}\n{}\n{}",
        struct_prelude(),
        g.source(),
        g_only.source()
    ));
}

#[test]
fn three_outputs_and_repeated_outputs() {
    let mut c = Context::new();
    let (x, y) = (c.x(), c.y());
    let s = c.add(x, y);
    let one = c.constant(1.0).unwrap();
    let tape = Tape::new(&c, &[s, x, one, s]).unwrap();
    let g = Generator::new(&tape, "four").unwrap();
    assert_eq!(g.output_count(), 4);
    check(&g);
    assert!(g.interval_source().contains("out3: Interval }"));
}

/// The union of `n` spheres at pseudo-random centres: a `min` tree.
fn blobs(n: usize) -> (Context, NodeId) {
    let mut c = Context::new();
    let (x, y, z) = (c.x(), c.y(), c.z());
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut acc: Option<NodeId> = None;
    for i in 0..n {
        let mut s = None;
        for v in [x, y, z] {
            let k = c.constant(next()).unwrap();
            let d = c.sub(v, k);
            let d2 = c.sqr(d);
            s = Some(match s {
                None => d2,
                Some(t) => c.add(t, d2),
            });
        }
        let r = c.constant(0.01 + 0.1 * next().abs()).unwrap();
        let sphere = c.sub(s.unwrap(), r);
        acc = Some(match acc {
            None => sphere,
            Some(a) if i % 3 == 0 => c.max(a, sphere),
            Some(a) => c.min(a, sphere),
        });
    }
    (c, acc.unwrap())
}

#[test]
fn large_min_max_tree_validates() {
    let (c, f) = blobs(450);
    let tape = Tape::new(&c, &[f]).unwrap();
    assert!(tape.ssa().len() >= 5000, "{}", tape.ssa().len());
    let g = Generator::new(&tape, "blobs").unwrap();
    let secs = check(&g);
    eprintln!("{} SSA values validated in {secs:.3} s", tape.ssa().len());
}

#[test]
fn ten_thousand_instructions_validate() {
    let mut c = Context::new();
    let (x, y) = (c.x(), c.y());
    let mut acc = x;
    let ops = [UnaryOp::Sin, UnaryOp::Atan, UnaryOp::Abs, UnaryOp::Sqr];
    for i in 0..5000 {
        let u = c.unary(ops[i % ops.len()], acc);
        acc = if i % 2 == 0 { c.add(u, y) } else { c.mul(u, y) };
    }
    let tape = Tape::new(&c, &[acc]).unwrap();
    assert!(tape.len() >= 10_000, "{}", tape.len());
    let g = Generator::new(&tape, "deep").unwrap();
    let start = Instant::now();
    let src = g.interval_source();
    let gen_secs = start.elapsed().as_secs_f64();
    let secs = check(&g);
    eprintln!(
        "{} instructions: generated {} bytes in {gen_secs:.3} s, validated in {secs:.3} s",
        tape.len(),
        src.len()
    );
}

#[test]
fn library_functions_match_the_generator() {
    // Each operation's tape needs exactly its own function.
    let mut seen: Vec<&str> = Vec::new();
    for op in UnaryOp::ALL {
        let mut c = Context::new();
        let x = c.x();
        let u = c.unary(op, x);
        let tape = Tape::new(&c, &[u]).unwrap();
        assert_eq!(
            wgsl::required_functions(&tape),
            [unary_function(op)],
            "{op}"
        );
        assert!(
            Generator::new(&tape, "f")
                .unwrap()
                .interval_source()
                .contains(unary_function(op))
        );
        seen.push(unary_function(op));
    }
    for op in BinaryOp::ALL {
        let mut c = Context::new();
        let (x, y) = (c.x(), c.y());
        let b = c.binary(op, x, y);
        let tape = Tape::new(&c, &[b]).unwrap();
        assert_eq!(
            wgsl::required_functions(&tape),
            [binary_function(op)],
            "{op}"
        );
        seen.push(binary_function(op));
    }
    {
        let mut c = Context::new();
        let x = c.x();
        let p = c.pown(x, 5);
        let tape = Tape::new(&c, &[p]).unwrap();
        assert_eq!(wgsl::required_functions(&tape), [wgsl::POWN_FUNCTION]);
        seen.push(wgsl::POWN_FUNCTION);
    }
    // Constants beyond the f32 range.
    for (lo, hi, name) in [
        (1e300, 2e300, "i_at_least"),
        (-2e300, -1e300, "i_at_most"),
        (-1e300, 1e300, "i_entire"),
    ] {
        let mut c = Context::new();
        let k = c.constant_enclosed(Constant::enclosed(lo, lo, hi).unwrap());
        let tape = Tape::new(&c, &[k]).unwrap();
        assert_eq!(wgsl::required_functions(&tape), [name]);
        seen.push(name);
    }
    // Bounded constants and variables need nothing.
    let mut c = Context::new();
    let k = c.constant(0.25).unwrap();
    let tape = Tape::new(&c, &[k]).unwrap();
    assert!(wgsl::required_functions(&tape).is_empty());

    seen.sort_unstable();
    seen.dedup();
    let mut all: Vec<&str> = LIBRARY_FUNCTIONS.to_vec();
    all.sort_unstable();
    assert_eq!(
        seen, all,
        "LIBRARY_FUNCTIONS is exactly what the generator can call"
    );
}

#[test]
fn prelude_declares_the_contract() {
    let prelude = struct_prelude();
    for f in LIBRARY {
        assert!(
            prelude.contains(&format!("{} {{", f.signature())),
            "prelude lacks {}",
            f.signature()
        );
    }
    validate(&prelude);
    validate(&alias_prelude());
}

/// The literal of one bound, read back exactly: `0.5f`, `-1.25f` or `-0x1.99999ap-4f`.
fn read_literal(text: &str) -> f32 {
    let body = text
        .trim()
        .strip_suffix('f')
        .unwrap_or_else(|| panic!("not an f32 literal: {text}"));
    let (negative, unsigned) = match body.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, body),
    };
    let v = if let Some(hex) = unsigned.strip_prefix("0x1") {
        let (frac, exp) = hex.split_once('p').unwrap();
        let frac = frac.strip_prefix('.').unwrap_or("");
        assert!(frac.len() <= 6, "{text}");
        let mut m = 1.0f64;
        for (i, d) in frac.chars().enumerate() {
            m += f64::from(d.to_digit(16).unwrap()) * 16f64.powi(-(i as i32 + 1));
        }
        m * 2f64.powi(exp.parse().unwrap())
    } else {
        // A decimal literal must be exact: its f64 reading is already an f32.
        let v: f64 = unsigned.parse().unwrap();
        assert_eq!(f64::from(v as f32), v, "inexact decimal {text}");
        v
    };
    let v = if negative { -v } else { v };
    assert_eq!(f64::from(v as f32), v, "{text} is not an f32");
    v as f32
}

/// The bounds of the single constant of a one-constant tape, read from the generated text.
fn emitted_bounds(src: &str) -> (f32, f32) {
    let line = src
        .lines()
        .find(|l| l.trim_start().starts_with("let v0 = "))
        .unwrap();
    let expr = line
        .trim()
        .trim_start_matches("let v0 = ")
        .trim_end_matches(';');
    if expr == "i_entire()" {
        return (f32::NEG_INFINITY, f32::INFINITY);
    }
    if let Some(a) = expr
        .strip_prefix("i_at_least(")
        .and_then(|e| e.strip_suffix(')'))
    {
        return (read_literal(a), f32::INFINITY);
    }
    if let Some(b) = expr
        .strip_prefix("i_at_most(")
        .and_then(|e| e.strip_suffix(')'))
    {
        return (f32::NEG_INFINITY, read_literal(b));
    }
    let inner = expr
        .strip_prefix("Interval(")
        .and_then(|e| e.strip_suffix(')'))
        .unwrap_or_else(|| panic!("unexpected constant {expr}"));
    let (a, b) = inner.split_once(", ").unwrap();
    (read_literal(a), read_literal(b))
}

fn constant_tape(lo: f64, hi: f64) -> Tape {
    let mut c = Context::new();
    let k = c.constant_enclosed(Constant::enclosed(lo, lo, hi).unwrap());
    Tape::new(&c, &[k]).unwrap()
}

fn is_subnormal(v: f32) -> bool {
    v != 0.0 && v.abs() < f32::MIN_POSITIVE
}

#[test]
fn constants_are_rounded_outward() {
    let mut state = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut cases: Vec<(f64, f64)> = vec![
        (0.1, 0.1),
        (-0.1, 0.1),
        (1.0, 1.0),
        (-0.0, 0.0),
        (1e-40, 1e-40),
        (-1e-40, 1e-40),
        (-1e-300, -1e-300),
        (f64::from(f32::MAX), f64::from(f32::MAX)),
        (f64::from(f32::MAX), f64::from(f32::MAX) * 1.000_000_1),
        (1e300, 1e301),
        (-1e301, -1e300),
        (-1e300, 1e300),
        (std::f64::consts::PI, std::f64::consts::PI),
    ];
    for _ in 0..20_000 {
        // Random doubles over the whole range, with a bias to the f32 range.
        let a = f64::from_bits(next());
        let scale = f64::from_bits(next() & 0x000f_ffff_ffff_ffff | 0x3ff0_0000_0000_0000);
        let b = scale * 2f64.powi((next() % 300) as i32 - 150);
        for v in [a, b, -b] {
            if v.is_finite() {
                let w = v + v.abs() * f64::from_bits(next() % 0x3cb0_0000_0000_0000);
                if w.is_finite() {
                    cases.push((v.min(w), v.max(w)));
                }
            }
        }
    }
    let mut bounded = 0;
    for (lo, hi) in cases {
        let tape = constant_tape(lo, hi);
        let src = wgsl::interval_function(&tape, "k").unwrap();
        let (l, h) = emitted_bounds(&src);
        assert!(
            f64::from(l) <= lo && f64::from(h) >= hi,
            "[{lo:e}, {hi:e}] -> [{l:e}, {h:e}]"
        );
        assert!(!is_subnormal(l) && !is_subnormal(h));
        assert_eq!((l, h), enclose_f32(lo, hi));
        // Tight: the next f32 inward would not enclose (unless a subnormal was avoided).
        if l.is_finite() && !is_subnormal(l.next_up()) && l.next_up() != 0.0 {
            assert!(f64::from(l.next_up()) > lo, "lo not tight for {lo:e}");
        }
        if h.is_finite() && !is_subnormal(h.next_down()) && h.next_down() != 0.0 {
            assert!(f64::from(h.next_down()) < hi, "hi not tight for {hi:e}");
        }
        if l.is_finite() && h.is_finite() {
            bounded += 1;
        }
    }
    assert!(bounded > 10_000);
    // A sample of them through naga too.
    for (lo, hi) in [(0.1, 0.3), (-1e-40, 2.5), (1e300, 1e301), (-3.0, -1e-300)] {
        let g = Generator::new(&constant_tape(lo, hi), "k").unwrap();
        check(&g);
    }
}

/// The value naga gives the module-scope constant `c`.
fn naga_constant(literal: &str) -> f32 {
    let source = format!("const c: f32 = {literal};\nfn use_c() -> f32 {{ return c; }}\n");
    let module = naga::front::wgsl::parse_str(&source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)));
    let (_, constant) = module.constants.iter().next().unwrap();
    match module.global_expressions[constant.init] {
        naga::Expression::Literal(naga::Literal::F32(v)) => v,
        ref other => panic!("{literal} is not folded to a literal: {other:?}"),
    }
}

#[test]
fn literals_denote_exactly_their_f32() {
    let mut state = 0x1234_5678_9abc_def1u64;
    let mut values: Vec<f32> = vec![
        0.5,
        -0.5,
        3.0,
        1024.0,
        0.1,
        -0.1,
        f32::MAX,
        f32::MIN,
        f32::MIN_POSITIVE,
        f32::EPSILON,
        1e-45,
        -1e-45,
        16_777_216.0,
        16_777_217.0_f32.next_up(),
        0.000_976_562_5,
    ];
    for _ in 0..300 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let v = f32::from_bits(state as u32);
        if v.is_finite() {
            values.push(v);
        }
        values.push((state % 100_000) as f32 / 256.0);
    }
    for v in values {
        let lit = f32_literal(v).unwrap();
        let got = naga_constant(&lit);
        assert_eq!(got.to_bits(), (v + 0.0).to_bits(), "{lit} for {v:e}");
    }
    assert_eq!(f32_literal(-0.0).unwrap(), "0.0f");
    assert!(f32_literal(f32::INFINITY).is_none());
}

#[test]
fn bad_names_are_errors() {
    let (c, f) = sphere();
    let tape = Tape::new(&c, &[f]).unwrap();
    for name in [
        "", "1f", "a-b", "a b", "_", "__f", "fn", "let", "struct", "sin", "f32", "vec3",
        "Interval", "i_add", "i_mine", "select", "é", "while", "handle",
        // `i` would make the point function `i_point`, in the library's namespace.
        "i",
    ] {
        match Generator::new(&tape, name) {
            Err(Error::Unsupported(msg)) => assert!(!msg.is_empty()),
            other => panic!("{name:?} accepted: {other:?}"),
        }
    }
    // Every word naga reserves or predeclares is refused.
    for word in naga::keywords::wgsl::RESERVED
        .iter()
        .chain(naga::keywords::wgsl::BUILTIN_IDENTIFIERS)
    {
        assert!(Generator::new(&tape, word).is_err(), "{word} accepted");
    }
    let g = Generator::new(&tape, "f").unwrap();
    for inputs in [
        &["x", "x"][..],
        &["p"],
        &["v0"],
        &["v12x"],
        &["f"],
        &["f_out"],
        &["f_point"],
        &["sin"],
        &["i_x"],
        &["1x"],
    ] {
        assert!(
            g.clone().with_inputs(inputs).is_err(),
            "{inputs:?} accepted"
        );
    }
    // Names close to the reserved ones are fine.
    for name in ["v", "value", "p1", "x", "interval", "ii", "sphere_2", "F"] {
        let g = Generator::new(&tape, name).unwrap();
        check(&g);
    }
    let g = g.with_inputs(&["vx", "p_0", "z"]).unwrap();
    check(&g);
}

#[test]
fn reserved_words_are_rejected_by_naga_too() {
    // The words refused above really are unusable (a sample; naga is the judge).
    for word in ["fn", "let", "while", "enum", "self", "typedef"] {
        let src = format!("fn {word}() {{}}");
        assert!(naga::front::wgsl::parse_str(&src).is_err(), "{word}");
    }
}
