//! Malformed formulas and `.vm` files: each error says what is wrong, where (exact byte
//! span, and line for `.vm`) and, where it helps, what to do. Deeply nested and very long
//! inputs neither panic nor overflow the stack.

use std::ops::Range;

use implicit_expr::parse::parse;
use implicit_expr::print::to_formula;
use implicit_expr::vm::import_vm;
use implicit_expr::{Context, Error, UnaryOp};

/// (input, message contains, span, hint contains)
const FORMULAS: &[(&str, &str, Range<usize>, Option<&str>)] = &[
    (
        "sine(x)",
        "unknown function 'sine'",
        0..4,
        Some("did you mean 'sin'?"),
    ),
    (
        "Sin(x)",
        "unknown function 'Sin'",
        0..3,
        Some("did you mean 'sin'?"),
    ),
    (
        "sqrtt(x)",
        "unknown function 'sqrtt'",
        0..5,
        Some("did you mean 'sqrt'?"),
    ),
    (
        "x + cso(y)",
        "unknown function 'cso'",
        4..7,
        Some("did you mean 'cos'?"),
    ),
    ("", "expected an expression", 0..0, None),
    ("   ", "expected an expression", 3..3, None),
    ("x +", "expected an expression", 3..3, None),
    ("x^", "expected an expression", 2..2, None),
    ("max(1, 2,", "expected an expression", 9..9, None),
    ("(x + 1", "unmatched '('", 0..1, Some("add ')'")),
    ("((x)", "unmatched '('", 0..1, None),
    ("x*(y + (z)", "unmatched '('", 2..3, None),
    ("sin(x", "unmatched '('", 3..4, None),
    ("x + 1)", "unmatched ')'", 5..6, None),
    (
        "2x",
        "missing operator before 'x'",
        1..2,
        Some("insert '*'"),
    ),
    (
        "x y",
        "missing operator before 'y'",
        2..3,
        Some("insert '*'"),
    ),
    (
        "2 3",
        "missing operator before '3'",
        2..3,
        Some("insert '*'"),
    ),
    (
        "(x)(y)",
        "missing operator before '('",
        3..4,
        Some("insert '*'"),
    ),
    (
        "x(y)",
        "missing operator before '('",
        1..2,
        Some("insert '*'"),
    ),
    (
        "2exp(x)",
        "missing operator before 'exp'",
        1..4,
        Some("insert '*'"),
    ),
    (
        "q + x",
        "unknown variable 'q'",
        0..1,
        Some("the variables are x, y, z"),
    ),
    (
        "xx",
        "unknown variable 'xx'",
        0..2,
        Some("did you mean 'x*x'?"),
    ),
    (
        "sinx",
        "unknown variable 'sinx'",
        0..4,
        Some("did you mean 'sin(x)'?"),
    ),
    (
        "PI*x",
        "unknown variable 'PI'",
        0..2,
        Some("did you mean 'pi'?"),
    ),
    (
        "sin x",
        "expected '(' after function 'sin'",
        0..3,
        Some("sin(...)"),
    ),
    ("sin(x, y)", "'sin' takes 1 argument, got 2", 0..9, None),
    ("sin()", "'sin' takes 1 argument, got 0", 0..5, None),
    (
        "min(x)",
        "'min' takes at least 2 arguments, got 1",
        0..6,
        None,
    ),
    (
        "1 + max()",
        "'max' takes at least 2 arguments, got 0",
        4..9,
        None,
    ),
    ("pow(x)", "'pow' takes 2 arguments, got 1", 0..6, None),
    (
        "pown(x, 0.5)",
        "the exponent of 'pown' must be an integer constant",
        0..12,
        None,
    ),
    (
        "1e",
        "malformed number '1e'",
        0..2,
        Some("digits after the exponent"),
    ),
    ("2.5e+", "malformed number '2.5e+'", 0..5, None),
    (
        "1.2.3",
        "malformed number '1.2.3'",
        0..5,
        Some("at most one '.'"),
    ),
    ("x + .", "malformed number '.'", 4..5, None),
    ("1e400", "number out of range", 0..5, None),
    ("x - 2e308", "number out of range", 4..9, None),
    ("x $ y", "unexpected character '$'", 2..3, None),
    ("x é", "unexpected character 'é'", 2..4, None),
    (
        "x^2 + y^2 = 1",
        "unexpected character '='",
        10..11,
        Some("lhs - (rhs)"),
    ),
    ("[x + y]", "unexpected character '['", 0..1, Some("use '('")),
    (
        "x ** 2",
        "expected an expression, found '*'",
        3..4,
        Some("use '^' for powers"),
    ),
    ("x + * y", "expected an expression, found '*'", 4..5, None),
    ("min(x,)", "expected an expression, found ')'", 6..7, None),
    ("()", "expected an expression, found ')'", 1..2, None),
    (
        "(x, y)",
        "unexpected ','",
        2..3,
        Some("separates the arguments"),
    ),
];

fn syntax_error(text: &str, params: &[&str]) -> (String, Range<usize>, Option<String>) {
    let mut ctx = Context::new();
    match parse(&mut ctx, text, params) {
        Err(Error::Syntax {
            message,
            span,
            hint,
        }) => (message, span, hint),
        other => panic!("{text:?}: expected a syntax error, got {other:?}"),
    }
}

#[test]
fn formula_error_corpus() {
    let mut wrong = Vec::new();
    for (text, message, span, hint) in FORMULAS {
        let (m, s, h) = syntax_error(text, &[]);
        let hint_ok = match hint {
            Some(want) => h.as_deref().is_some_and(|h| h.contains(want)),
            None => true,
        };
        if !m.contains(message) || s != *span || !hint_ok {
            wrong.push(format!("{text:?}: got {m:?} at {s:?}, hint {h:?}"));
        }
        assert!(
            s.end <= text.len() && text.is_char_boundary(s.start) && text.is_char_boundary(s.end)
        );
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    assert!(FORMULAS.len() >= 30);
}

#[test]
fn error_display() {
    let mut ctx = Context::new();
    let err = parse(&mut ctx, "1 + sine(x)", &[]).unwrap_err();
    assert_eq!(
        err.to_string(),
        "unknown function 'sine' at 4..8; did you mean 'sin'?"
    );
    let err = parse(&mut ctx, "", &[]).unwrap_err();
    assert_eq!(err.to_string(), "expected an expression at 0..0");
    let err = parse(&mut ctx, "sin(x, y)", &[]).unwrap_err();
    assert_eq!(err.to_string(), "'sin' takes 1 argument, got 2 at 0..9");
}

#[test]
fn parameters() {
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "a*x + b", &["a", "b"]).unwrap();
    assert_eq!(ctx.var_names(), ["x", "y", "z", "a", "b"]);
    assert_eq!(ctx.eval::<f64>(f, &[2.0, 0.0, 0.0, 3.0, 1.0]).unwrap(), 7.0);

    let (m, s, h) = syntax_error("a + c", &["a"]);
    assert_eq!((m.as_str(), s), ("unknown variable 'c'", 4..5));
    assert_eq!(h.as_deref(), Some("the variables are x, y, z, a"));
    let (_, _, h) = syntax_error("radius", &["radius2"]);
    assert_eq!(h.as_deref(), Some("did you mean 'radius2'?"));
    let (_, _, h) = syntax_error("ab", &["a", "b"]);
    assert_eq!(h.as_deref(), Some("did you mean 'a*b'?"));

    for (bad, why) in [
        ("sin", "reserved for a function"),
        ("pi", "reserved for a constant"),
        ("e", "reserved for a constant"),
        ("2a", "not a name"),
        ("", "not a name"),
        ("a b", "not a name"),
    ] {
        let (m, s, _) = syntax_error("x", &[bad]);
        assert!(m.contains(why), "{bad:?}: {m}");
        assert_eq!(s, 0..0);
    }
}

#[test]
fn long_tokens_are_quoted_short() {
    let name = "w".repeat(100_000);
    let (m, s, _) = syntax_error(&name, &[]);
    assert!(m.len() < 100, "{m}");
    assert_eq!(s, 0..100_000);
    let (m, _, _) = syntax_error(&"1".repeat(100_000), &[]);
    assert_eq!(m, "number out of range");
}

const N: usize = 100_000;

#[test]
fn deep_nesting_does_not_overflow() {
    let mut ctx = Context::new();
    let x = ctx.x();

    let (m, s, _) = syntax_error(&"(".repeat(N), &[]);
    assert_eq!((m.as_str(), s), ("expected an expression", N..N));
    let (m, s, _) = syntax_error(&format!("{}x", "(".repeat(N)), &[]);
    assert_eq!((m.as_str(), s), ("unmatched '('", N - 1..N));
    let (m, s, _) = syntax_error(&format!("x{}", ")".repeat(N)), &[]);
    assert_eq!((m.as_str(), s), ("unmatched ')'", 1..2));

    let text = format!("{}x{}", "(".repeat(N), ")".repeat(N));
    assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), x);
    let text = format!("{}x", "-".repeat(N));
    assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), x);
    let text = format!("{}x", "-".repeat(N + 1));
    let neg_x = ctx.neg(x);
    assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), neg_x);
    let text = format!("{}x", "+-".repeat(N));
    assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), x);

    // x^x^...^x is right-associative: the deepest node is at the right.
    let text = format!("{}x", "x^".repeat(N));
    let f = parse(&mut ctx, &text, &[]).unwrap();
    assert!(matches!(ctx.get(f), implicit_expr::Node::Binary(_, a, _) if *a == x));
    let printed = to_formula(&ctx, f);
    assert_eq!(parse(&mut ctx, &printed, &[]).unwrap(), f);

    let text = format!("{}x{}", "sin(".repeat(N), ")".repeat(N));
    let f = parse(&mut ctx, &text, &[]).unwrap();
    let printed = to_formula(&ctx, f);
    assert_eq!(printed, text);
    assert_eq!(parse(&mut ctx, &printed, &[]).unwrap(), f);
    let mut g = x;
    for _ in 0..N {
        g = ctx.unary(UnaryOp::Sin, g);
    }
    assert_eq!(f, g);

    let text = format!("{}x{}", "(-".repeat(N), ")".repeat(N));
    assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), x);
    let text = format!("{}1{}", "min(x, ".repeat(N), ")".repeat(N));
    assert!(parse(&mut ctx, &text, &[]).is_ok());
}

#[test]
fn long_flat_chains() {
    let mut ctx = Context::new();
    let text = format!("{}x", "x + ".repeat(N));
    let f = parse(&mut ctx, &text, &[]).unwrap();
    assert_eq!(
        ctx.eval::<f64>(f, &[1.0, 0.0, 0.0]).unwrap(),
        (N + 1) as f64
    );
    let printed = to_formula(&ctx, f);
    assert_eq!(parse(&mut ctx, &printed, &[]).unwrap(), f);

    let text = format!("{}1", "x*y - ".repeat(N));
    let f = parse(&mut ctx, &text, &[]).unwrap();
    let printed = to_formula(&ctx, f);
    assert_eq!(parse(&mut ctx, &printed, &[]).unwrap(), f);
}

/// A malformed `.vm` input: (input, line, message contains, span, hint contains).
type VmCase = (
    &'static str,
    usize,
    &'static str,
    Range<usize>,
    Option<&'static str>,
);

const VM: &[VmCase] = &[
    ("", 1, "no instruction", 0..0, None),
    ("# only a comment\n", 2, "no instruction", 17..17, None),
    (
        "_0 var-x\n_1 sqaure _0",
        2,
        "unknown op 'sqaure'",
        12..18,
        Some("did you mean 'square'?"),
    ),
    (
        "_0 var-x\n_1 frobnicate _0",
        2,
        "unknown op 'frobnicate'",
        12..22,
        Some("supported: var-x"),
    ),
    (
        "_0 var-x\r\n_1 foo _0\r\n",
        2,
        "unknown op 'foo'",
        13..16,
        None,
    ),
    (
        "_0 var-x\n_1 compare _0 _0",
        2,
        "unsupported op 'compare'",
        12..19,
        Some("supported:"),
    ),
    (
        "_0 var-x\n_1 mod _0 _0",
        2,
        "unsupported op 'mod'",
        12..15,
        None,
    ),
    (
        "_0 var-x\n_1 atan _0 _0",
        2,
        "unsupported op 'atan' with two arguments",
        12..22,
        None,
    ),
    (
        "_0 var-x\n_1 add _0",
        2,
        "'add' takes 2 arguments, got 1",
        12..18,
        None,
    ),
    (
        "_0 var-x\n_1 neg _0 _0 _0",
        2,
        "'neg' takes 1 argument, got 3",
        19..24,
        None,
    ),
    (
        "_0 var-x extra",
        1,
        "'var-x' takes 0 arguments, got 1",
        9..14,
        None,
    ),
    ("_0 const", 1, "'const' takes 1 argument, got 0", 3..8, None),
    (
        "_0 var-x\n_1 neg _5",
        2,
        "undefined id '_5'",
        16..18,
        Some("earlier line"),
    ),
    ("_0 var-x\n_1 neg _1", 2, "undefined id '_1'", 16..18, None),
    (
        "_0 var-x\n_1 add _0 x",
        2,
        "undefined id 'x'",
        19..20,
        Some("earlier line"),
    ),
    (
        "_0 var-x\n_0 var-y",
        2,
        "duplicate id '_0'",
        9..11,
        Some("line 1"),
    ),
    (
        "_0 const abc",
        1,
        "bad constant 'abc'",
        9..12,
        Some("decimal number"),
    ),
    ("_0 const 1e400", 1, "bad constant '1e400'", 9..14, None),
    ("_0 const nan", 1, "bad constant 'nan'", 9..12, None),
    ("_0 const --1", 1, "bad constant '--1'", 9..12, None),
    (
        "\n\n  _0   # comment\n",
        3,
        "missing op after '_0'",
        4..6,
        None,
    ),
];

#[test]
fn vm_error_corpus() {
    let mut wrong = Vec::new();
    for (text, line, message, span, hint) in VM {
        let mut ctx = Context::new();
        match import_vm(&mut ctx, text) {
            Err(Error::Vm {
                line: l,
                message: m,
                span: s,
                hint: h,
            }) => {
                let hint_ok = match hint {
                    Some(want) => h.as_deref().is_some_and(|h| h.contains(want)),
                    None => true,
                };
                if l != *line || !m.contains(message) || s != *span || !hint_ok {
                    wrong.push(format!(
                        "{text:?}: got line {l}: {m:?} at {s:?}, hint {h:?}"
                    ));
                }
            }
            other => wrong.push(format!("{text:?}: expected a .vm error, got {other:?}")),
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
    assert!(VM.len() >= 12);
}

#[test]
fn vm_display_and_long_files() {
    let mut ctx = Context::new();
    let err = import_vm(&mut ctx, "_0 var-x\n_1 sqaure _0\n").unwrap_err();
    assert_eq!(
        err.to_string(),
        "line 2: unknown op 'sqaure' at 12..18; did you mean 'square'?"
    );

    // A chain of 100 000 additions, hexadecimal ids, comments and blank lines.
    let mut text = String::from("# chain\n_0 var-x\n\n");
    for i in 1..=N {
        text.push_str(&format!("_{i:x} add _{:x} _0\n", i - 1));
    }
    let f = import_vm(&mut ctx, &text).unwrap();
    assert_eq!(
        ctx.eval::<f64>(f, &[1.0, 0.0, 0.0]).unwrap(),
        (N + 1) as f64
    );
}

/// fidget's own model files name their values freely (`y`, `mxy`, `sphere-3`): every
/// token is an id.
#[test]
fn vm_ids_need_not_start_with_underscore() {
    let mut ctx = Context::new();
    let text = "# fidget style\ny var-y\nx var-x\nmxy max x y\nr const 0.5\n\
                sphere-3 sub mxy r\n_5 square sphere-3\n";
    let f = import_vm(&mut ctx, text).unwrap();
    // max(0.25, 1) - 0.5 = 0.5, squared.
    assert_eq!(ctx.eval::<f64>(f, &[0.25, 1.0, 0.0]).unwrap(), 0.25);
    // A name that is only defined later is still an undefined id.
    let err = import_vm(&mut ctx, "a add b b\nb var-x\n").unwrap_err();
    assert!(err.to_string().contains("undefined id 'b'"), "{err}");
}
