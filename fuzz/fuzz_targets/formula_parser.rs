//! Fuzz target: the formula parser and printer of `implicit-expr`.
//!
//! The input bytes, decoded as UTF-8 (invalid sequences replaced), are parsed with the
//! parameters `a`, `b` and `t`. Any input must give a node or an error, never a panic, and
//! an error's span must lie on character boundaries of the text. A parsed graph is printed
//! and the text parsed again: it must give the same node when every constant of the graph
//! has an exact printed form (the printer's documented guarantee), and a node with the
//! same point values otherwise.

#![no_main]

use implicit_expr::parse::parse;
use implicit_expr::print::to_formula;
use implicit_expr::{Context, Error, Node, NodeId};
use libfuzzer_sys::fuzz_target;

mod common;

const PARAMS: [&str; 3] = ["a", "b", "t"];

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let mut ctx = Context::new();
    let f = match parse(&mut ctx, &text, &PARAMS) {
        Ok(f) => f,
        Err(Error::Syntax { span, .. }) => {
            assert!(span.start <= span.end && span.end <= text.len(), "{span:?}");
            assert!(text.is_char_boundary(span.start) && text.is_char_boundary(span.end));
            return;
        }
        Err(e) => panic!("unexpected error kind: {e:?}"),
    };
    let printed = to_formula(&ctx, f);
    let g = parse(&mut ctx, &printed, &PARAMS)
        .unwrap_or_else(|e| panic!("{text:?} printed as {printed:?} does not parse: {e}"));
    if constants_print_exactly(&mut ctx, f) {
        assert_eq!(g, f, "{text:?} printed as {printed:?}");
    }
    let point = [0.37, -1.25, 2.5, 0.5, -0.75, 3.0];
    let (vf, vg) = (
        ctx.eval::<f64>(f, &point).unwrap(),
        ctx.eval::<f64>(g, &point).unwrap(),
    );
    assert!(
        common::same_value(vf, vg),
        "{text:?} printed as {printed:?}: {vf} vs {vg}"
    );
});

/// Whether every constant of the graph reads back as itself from its printed form.
fn constants_print_exactly(ctx: &mut Context, root: NodeId) -> bool {
    ctx.reachable(&[root]).into_iter().all(|id| {
        !matches!(ctx.get(id), Node::Const(_)) || {
            let text = to_formula(ctx, id);
            parse(ctx, &text, &[]).ok() == Some(id)
        }
    })
}
