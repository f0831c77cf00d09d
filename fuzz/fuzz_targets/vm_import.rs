//! Fuzz target: the `.vm` importer and exporter of `implicit-expr`.
//!
//! The input bytes, decoded as UTF-8 (invalid sequences replaced), are imported as a `.vm`
//! file. Any input must give a node or an error, never a panic; an error's span must lie on
//! character boundaries of the text and its line must be the line holding the span. An
//! imported graph is exported (which cannot fail: an import makes only operations the
//! format has) and imported again: the same node when every constant has an exact form in
//! the format, a node with the same point values otherwise.

#![no_main]

use implicit_expr::vm::{export_vm, import_vm};
use implicit_expr::{Context, Error, Node, NodeId};
use libfuzzer_sys::fuzz_target;

mod common;

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let mut ctx = Context::new();
    let f = match import_vm(&mut ctx, &text) {
        Ok(f) => f,
        Err(Error::Vm { line, span, .. }) => {
            assert!(span.start <= span.end && span.end <= text.len(), "{span:?}");
            assert!(text.is_char_boundary(span.start) && text.is_char_boundary(span.end));
            let span_line = text[..span.start].matches('\n').count() + 1;
            assert_eq!(line, span_line, "{span:?}");
            return;
        }
        Err(e) => panic!("unexpected error kind: {e:?}"),
    };
    let vm = export_vm(&ctx, f).unwrap_or_else(|e| panic!("{text:?}: export failed: {e}"));
    let g = import_vm(&mut ctx, &vm).unwrap_or_else(|e| panic!("{vm}: re-import failed: {e}"));
    if constants_export_exactly(&mut ctx, f) {
        assert_eq!(g, f, "{text:?} exported as\n{vm}");
    }
    let point = [0.37, -1.25, 2.5];
    let (vf, vg) = (
        ctx.eval::<f64>(f, &point).unwrap(),
        ctx.eval::<f64>(g, &point).unwrap(),
    );
    assert!(
        common::same_value(vf, vg),
        "{text:?} exported as\n{vm}\n{vf} vs {vg}"
    );
});

/// Whether every constant of the graph reads back as itself from its `.vm` form.
fn constants_export_exactly(ctx: &mut Context, root: NodeId) -> bool {
    ctx.reachable(&[root]).into_iter().all(|id| {
        !matches!(ctx.get(id), Node::Const(_)) || {
            let text = export_vm(ctx, id).expect("a constant can always be exported");
            import_vm(ctx, &text).ok() == Some(id)
        }
    })
}
