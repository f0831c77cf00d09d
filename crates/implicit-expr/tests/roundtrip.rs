//! Round trips: random formulas parsed, printed and parsed again give the same node of the
//! same context; graphs exported to `.vm` and imported again give the same node; and the
//! re-read graphs evaluate like the originals.
//!
//! The same node is promised when every constant of the graph has a literal form (see
//! `implicit_expr::print`): literals and exact constants do, constants folded from an
//! expression such as `sin(0.1)` usually do not. For those graphs only the point values
//! are compared.

use implicit_expr::parse::parse;
use implicit_expr::print::to_formula;
use implicit_expr::vm::{export_vm, import_vm};
use implicit_expr::{Context, Node, NodeId};
use proptest::prelude::*;

const PARAMS: [&str; 2] = ["a", "b"];

const LITERALS: [&str; 17] = [
    "0",
    "1",
    "2",
    "7",
    "0.5",
    "0.1",
    "3.25",
    "1e-3",
    "2.5e10",
    "1e23",
    "123456789.123",
    ".5",
    "2.",
    "1.5E+2",
    "0.3",
    "pi",
    "e",
];

const UNARY: [&str; 21] = [
    "sqrt",
    "exp",
    "ln",
    "log",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "abs",
    "sqr",
    "recip",
    "floor",
    "ceil",
    "round",
    "not",
    "neg",
    "slope_floor",
    "slope_round",
    "slope_not",
];

/// Functions of one argument that the `.vm` format has.
const VM_UNARY: [&str; 17] = [
    "sqrt", "exp", "ln", "sin", "cos", "tan", "asin", "acos", "atan", "abs", "sqr", "recip",
    "floor", "ceil", "round", "not", "neg",
];

/// Random formula text over the whole grammar, nesting depth at most 6.
fn formula(
    vars: &'static [&'static str],
    unary: &'static [&'static str],
    powers: bool,
) -> BoxedStrategy<String> {
    let leaf = prop_oneof![
        3 => prop::sample::select(vars).prop_map(str::to_string),
        2 => prop::sample::select(&LITERALS[..]).prop_map(str::to_string),
    ];
    leaf.prop_recursive(6, 48, 3, move |inner| {
        let mut choices: Vec<BoxedStrategy<String>> = vec![
            (prop::sample::select(unary), inner.clone())
                .prop_map(|(f, a)| format!("{f}({a})"))
                .boxed(),
            (prop::sample::select(&["-", "+", "- "][..]), inner.clone())
                .prop_map(|(s, a)| format!("{s}{a}"))
                .boxed(),
            (
                inner.clone(),
                prop::sample::select(&["+", "-", "*", "/", " + ", " - "][..]),
                inner.clone(),
                any::<bool>(),
            )
                .prop_map(|(a, op, b, paren)| {
                    if paren {
                        format!("({a}{op}{b})")
                    } else {
                        format!("{a}{op}{b}")
                    }
                })
                .boxed(),
            (
                prop::sample::select(&["min", "max"][..]),
                prop::collection::vec(inner.clone(), 2..4),
            )
                .prop_map(|(f, args)| format!("{f}({})", args.join(", ")))
                .boxed(),
        ];
        if powers {
            choices.push(
                (inner.clone(), -4i32..6, any::<bool>())
                    .prop_map(|(a, n, paren)| {
                        if paren {
                            format!("({a})^({n})")
                        } else {
                            format!("({a})^{n}")
                        }
                    })
                    .boxed(),
            );
            choices.push(
                (inner.clone(), inner.clone(), any::<bool>())
                    .prop_map(|(a, b, call)| {
                        if call {
                            format!("pow({a}, {b})")
                        } else {
                            format!("({a})^({b})")
                        }
                    })
                    .boxed(),
            );
        } else {
            choices.push(inner.clone().prop_map(|a| format!("({a})^2")).boxed());
        }
        prop::strategy::Union::new(choices)
    })
    .boxed()
}

fn params(ctx: &Context) -> Vec<String> {
    ctx.var_names()[3..].to_vec()
}

fn reparse(ctx: &mut Context, text: &str) -> NodeId {
    let names = params(ctx);
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    parse(ctx, text, &names).unwrap_or_else(|e| panic!("printed text {text:?} does not parse: {e}"))
}

/// Whether every constant of the graph reads back as itself from its printed form.
fn constants_print_exactly(ctx: &mut Context, root: NodeId) -> bool {
    ctx.reachable(&[root]).into_iter().all(|id| {
        !matches!(ctx.get(id), Node::Const(_)) || {
            let text = to_formula(ctx, id);
            parse(ctx, &text, &[]).ok() == Some(id)
        }
    })
}

/// Whether every constant of the graph reads back as itself from its `.vm` form.
fn constants_export_exactly(ctx: &mut Context, root: NodeId) -> bool {
    ctx.reachable(&[root]).into_iter().all(|id| {
        !matches!(ctx.get(id), Node::Const(_)) || {
            let text = export_vm(ctx, id).unwrap();
            import_vm(ctx, &text).ok() == Some(id)
        }
    })
}

const POINTS: [[f64; 5]; 4] = [
    [0.3, -0.7, 1.9, 0.25, -2.5],
    [-1.25, 0.5, 0.0, 3.0, 0.1],
    [2.0, 2.0, -0.5, -1.0, 1.0],
    [0.9, -0.2, 0.45, 0.6, 0.75],
];

/// Point values agree: the same, or within a relative 1e-9 when both are finite.
///
/// A folded constant read back from its printed value may enable or disable a
/// simplification (an exact `0` makes `0*a` the constant 0 even where `a` is NaN) or turn a
/// real power into an integer one, which changes non-finite results and the last bits.
fn assert_same_values(ctx: &Context, f: NodeId, g: NodeId, exact: bool, what: &str) {
    for p in POINTS {
        let vf = ctx.eval::<f64>(f, &p).unwrap();
        let vg = ctx.eval::<f64>(g, &p).unwrap();
        let same = vf.to_bits() == vg.to_bits()
            || (!exact && (!vf.is_finite() || !vg.is_finite()))
            || (!exact && (vf - vg).abs() <= 1e-9 * vf.abs().max(vg.abs()));
        assert!(same, "{what} at {p:?}: {vf} vs {vg}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn parse_print_parse(text in formula(&["x", "y", "z", "a", "b"], &UNARY, true)) {
        let mut ctx = Context::new();
        let f = parse(&mut ctx, &text, &PARAMS).unwrap_or_else(|e| panic!("{text:?}: {e}"));
        let printed = to_formula(&ctx, f);
        let g = reparse(&mut ctx, &printed);
        let exact = constants_print_exactly(&mut ctx, f);
        if exact {
            prop_assert_eq!(g, f, "{} printed as {}", text, printed);
        }
        assert_same_values(&ctx, f, g, exact, &format!("{text} printed as {printed}"));
        // Printing is a fixed point from the second time on.
        let printed2 = to_formula(&ctx, g);
        let h = reparse(&mut ctx, &printed2);
        prop_assert_eq!(to_formula(&ctx, h), printed2);
    }

    #[test]
    fn vm_export_import(text in formula(&["x", "y", "z"], &VM_UNARY, false)) {
        let mut ctx = Context::new();
        let f = parse(&mut ctx, &text, &[]).unwrap_or_else(|e| panic!("{text:?}: {e}"));
        let vm = export_vm(&ctx, f).unwrap_or_else(|e| panic!("{text:?}: {e}"));
        let g = import_vm(&mut ctx, &vm).unwrap_or_else(|e| panic!("{vm}: {e}"));
        let exact = constants_export_exactly(&mut ctx, f);
        if exact {
            prop_assert_eq!(g, f, "{} exported as\n{}", text, vm);
        }
        assert_same_values(&ctx, f, g, exact, &format!("{text} exported as\n{vm}"));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    /// Every exact constant (any finite double, subnormals included) prints, and exports,
    /// as text that reads back into the same constant.
    #[test]
    fn exact_constants_round_trip(bits in any::<u64>(), scale in -60i32..60) {
        let v = f64::from_bits(bits);
        prop_assume!(v.is_finite());
        let mut ctx = Context::new();
        let x = ctx.x();
        for v in [v, v * 2f64.powi(scale)] {
            let Ok(c) = ctx.constant(v) else { continue };
            let f = ctx.mul(c, x);
            let printed = to_formula(&ctx, f);
            prop_assert_eq!(parse(&mut ctx, &printed, &[]).unwrap(), f, "{}", printed);
            let vm = export_vm(&ctx, f).unwrap();
            prop_assert_eq!(import_vm(&mut ctx, &vm).unwrap(), f, "{}", vm);
        }
    }
}

#[test]
fn most_random_formulas_round_trip_exactly() {
    // Guard against the property above passing vacuously: count the graphs whose
    // constants all print exactly.
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let strategy = formula(&["x", "y", "z", "a", "b"], &UNARY, true);
    let mut exact = 0;
    for _ in 0..200 {
        let text = strategy.new_tree(&mut runner).unwrap().current();
        let mut ctx = Context::new();
        let f = parse(&mut ctx, &text, &PARAMS).unwrap();
        if constants_print_exactly(&mut ctx, f) {
            exact += 1;
        }
    }
    assert!(
        exact >= 100,
        "only {exact} of 200 formulas have exactly printable constants"
    );
}

#[test]
fn inexact_literals_keep_their_enclosure() {
    let mut ctx = Context::new();
    for lit in ["0.1", "-0.1", "0.3", "1e23", "3.14159", "-2.5e-7", "1e-320"] {
        let f = parse(&mut ctx, lit, &[]).unwrap();
        let printed = to_formula(&ctx, f);
        assert_eq!(
            parse(&mut ctx, &printed, &[]).unwrap(),
            f,
            "{lit} printed as {printed}"
        );
        let vm = export_vm(&ctx, f).unwrap();
        assert_eq!(
            import_vm(&mut ctx, &vm).unwrap(),
            f,
            "{lit} exported as {vm}"
        );
    }
}

#[test]
fn underflowing_literal_prints_as_its_value() {
    // Found by the `formula_parser` fuzz target: `1e-400` is the constant enclosed by
    // [-2^-1074, 2^-1074] with value 0. It prints as `0`, which reads back as the exact 0,
    // and `0*a` then simplifies to 0: a different node, the same value wherever `a` is
    // defined.
    let mut ctx = Context::new();
    let f = parse(&mut ctx, "1e-400*sqrt(x)", &[]).unwrap();
    let printed = to_formula(&ctx, f);
    assert_eq!(printed, "0*sqrt(x)");
    let g = parse(&mut ctx, &printed, &[]).unwrap();
    assert_ne!(g, f);
    assert_eq!(ctx.eval::<f64>(f, &[4.0, 0.0, 0.0]).unwrap(), 0.0);
    assert_eq!(ctx.eval::<f64>(g, &[4.0, 0.0, 0.0]).unwrap(), 0.0);
    assert!(ctx.eval::<f64>(f, &[-1.0, 0.0, 0.0]).unwrap().is_nan());
}
