//! The `.vm` SSA text format of implicit-surface benchmarks (the format of fidget's
//! `prospero.vm`): one instruction per line, `ID OP ARGS...`.
//!
//! ```text
//! # a sphere of radius 1
//! _0 var-x
//! _1 square _0
//! _2 var-y
//! _3 square _2
//! _4 add _1 _3
//! _5 const 1
//! _6 sub _4 _5
//! ```
//!
//! An id is any token (usually `_` and hexadecimal digits, `_1a`, but `y`, `mxy` or
//! `sphere-3` are ids too, as in fidget's model files); each is defined once, before its
//! uses. `#` starts a comment (a whole line or the rest of one); blank lines are
//! ignored. The last instruction is the root of the expression.
//!
//! | ops | arguments |
//! |---|---|
//! | `var-x var-y var-z` | none |
//! | `const` | a decimal number (`0.25`, `-1.5e3`; enclosed like a formula literal) |
//! | `add sub mul div min max` | two ids |
//! | `neg square sqrt abs recip sin cos tan asin acos atan exp ln floor ceil round not copy` | one id (`copy` is the same node again) |
//!
//! The format's `compare`, `and`, `or`, `mod` and two-argument `atan` have no counterpart
//! in this crate's operations and are rejected with an error.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::ops::Range;

use crate::constant::Constant;
use crate::context::{Context, Node, NodeId, Var};
use crate::error::Error;
use crate::op::{BinaryOp, UnaryOp};
use crate::parse::{quote, suggest};
use crate::print::literals;

/// What an op name of the format stands for.
#[derive(Copy, Clone, Debug)]
enum Op {
    Var(Var),
    Const,
    Unary(UnaryOp),
    Binary(BinaryOp),
    Copy,
}

/// The supported ops: name, meaning, number of arguments.
const OPS: [(&str, Op, usize); 28] = [
    ("var-x", Op::Var(Var::X), 0),
    ("var-y", Op::Var(Var::Y), 0),
    ("var-z", Op::Var(Var::Z), 0),
    ("const", Op::Const, 1),
    ("add", Op::Binary(BinaryOp::Add), 2),
    ("sub", Op::Binary(BinaryOp::Sub), 2),
    ("mul", Op::Binary(BinaryOp::Mul), 2),
    ("div", Op::Binary(BinaryOp::Div), 2),
    ("min", Op::Binary(BinaryOp::Min), 2),
    ("max", Op::Binary(BinaryOp::Max), 2),
    ("neg", Op::Unary(UnaryOp::Neg), 1),
    ("square", Op::Unary(UnaryOp::Sqr), 1),
    ("sqrt", Op::Unary(UnaryOp::Sqrt), 1),
    ("abs", Op::Unary(UnaryOp::Abs), 1),
    ("recip", Op::Unary(UnaryOp::Recip), 1),
    ("sin", Op::Unary(UnaryOp::Sin), 1),
    ("cos", Op::Unary(UnaryOp::Cos), 1),
    ("tan", Op::Unary(UnaryOp::Tan), 1),
    ("asin", Op::Unary(UnaryOp::Asin), 1),
    ("acos", Op::Unary(UnaryOp::Acos), 1),
    ("atan", Op::Unary(UnaryOp::Atan), 1),
    ("exp", Op::Unary(UnaryOp::Exp), 1),
    ("ln", Op::Unary(UnaryOp::Ln), 1),
    ("floor", Op::Unary(UnaryOp::Floor), 1),
    ("ceil", Op::Unary(UnaryOp::Ceil), 1),
    ("round", Op::Unary(UnaryOp::Round), 1),
    ("not", Op::Unary(UnaryOp::Not), 1),
    ("copy", Op::Copy, 1),
];

/// Ops of the format that this crate does not have.
const UNSUPPORTED: [&str; 4] = ["compare", "and", "or", "mod"];

/// One whitespace-separated token and its byte span in the whole input.
type Tok<'t> = (&'t str, Range<usize>);

/// The tokens of a line that starts at byte `start`, up to a `#` comment.
fn tokens(line: &str, start: usize) -> Vec<Tok<'_>> {
    let mut out = Vec::new();
    let mut i = 0;
    let bytes = line.as_bytes();
    while i < bytes.len() {
        if bytes[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        if bytes[i] == b'#' {
            break;
        }
        let j = bytes[i..]
            .iter()
            .position(|b| b.is_ascii_whitespace())
            .map_or(bytes.len(), |k| i + k);
        out.push((&line[i..j], start + i..start + j));
        i = j;
    }
    out
}

fn supported_list() -> String {
    let names: Vec<&str> = OPS.iter().map(|o| o.0).collect();
    format!("supported: {}", names.join(", "))
}

/// Reads a `.vm` file into `ctx` and returns the node of its last instruction.
///
/// Constants become [`Constant::from_decimal`] enclosures (negated for a leading `-`), so
/// a literal such as `0.1` keeps its enclosure.
///
/// # Errors
///
/// [`Error::Vm`] with the line, the byte span in `text` and often a hint, for: an unknown
/// or unsupported op, a wrong number of arguments, an argument that is no id defined on an
/// earlier line, an id defined twice, a constant that is not a finite decimal number, and a
/// file without instructions.
///
/// ```
/// use implicit_expr::{Context, vm::import_vm};
///
/// let mut ctx = Context::new();
/// let f = import_vm(&mut ctx, "_0 var-x\n_1 square _0\n_2 const 1\n_3 sub _1 _2\n").unwrap();
/// assert_eq!(ctx.eval::<f64>(f, &[3.0, 0.0, 0.0]).unwrap(), 8.0);
///
/// let err = import_vm(&mut ctx, "_0 var-x\n_1 sqaure _0\n").unwrap_err();
/// assert_eq!(err.to_string(), "line 2: unknown op 'sqaure' at 12..18; did you mean 'square'?");
/// ```
pub fn import_vm(ctx: &mut Context, text: &str) -> Result<NodeId, Error> {
    let mut ids: HashMap<&str, (NodeId, usize)> = HashMap::new();
    let mut last = None;
    let mut start = 0;
    let mut line_no = 0;
    for line in text.split('\n') {
        line_no += 1;
        let toks = tokens(line, start);
        start += line.len() + 1;
        let err = |message: String, span: Range<usize>, hint: Option<String>| Error::Vm {
            line: line_no,
            message,
            span,
            hint,
        };
        let Some((id, id_span)) = toks.first().cloned() else {
            continue;
        };
        if let Some((_, first)) = ids.get(id) {
            return Err(err(
                format!("duplicate id {}", quote(id)),
                id_span,
                Some(format!("it was defined on line {first}")),
            ));
        }
        let Some((op_name, op_span)) = toks.get(1).cloned() else {
            return Err(err(
                format!("missing op after {}", quote(id)),
                id_span,
                Some("each line is 'ID OP ARGS...', e.g. '_0 var-x'".into()),
            ));
        };
        let args = &toks[2..];
        let Some(&(_, op, arity)) = OPS.iter().find(|o| o.0 == op_name) else {
            let unsupported = UNSUPPORTED.contains(&op_name);
            let message = if unsupported {
                format!("unsupported op {}", quote(op_name))
            } else {
                format!("unknown op {}", quote(op_name))
            };
            let hint = if unsupported {
                None
            } else {
                suggest::did_you_mean(op_name, OPS.iter().map(|o| o.0))
            };
            return Err(err(
                message,
                op_span,
                hint.or_else(|| Some(supported_list())),
            ));
        };
        if args.len() != arity {
            if op_name == "atan" && args.len() == 2 {
                return Err(err(
                    "unsupported op 'atan' with two arguments (atan2)".into(),
                    op_span.start..args[1].1.end,
                    Some(supported_list()),
                ));
            }
            let span = match args.get(arity) {
                Some(extra) => extra.1.start..args[args.len() - 1].1.end,
                None => op_span.start..args.last().map_or(op_span.end, |a| a.1.end),
            };
            let plural = if arity == 1 { "argument" } else { "arguments" };
            return Err(err(
                format!("'{op_name}' takes {arity} {plural}, got {}", args.len()),
                span,
                None,
            ));
        }
        let node = match op {
            Op::Const => {
                let (text, span) = &args[0];
                constant(ctx, text).ok_or_else(|| {
                    err(
                        format!("bad constant {}", quote(text)),
                        span.clone(),
                        Some("expected a finite decimal number such as 0.25 or -1.5e3".into()),
                    )
                })?
            }
            Op::Var(v) => ctx.var(v)?,
            _ => {
                let mut nodes = [None; 2];
                for (slot, (arg, span)) in nodes.iter_mut().zip(args) {
                    *slot = Some(lookup(&ids, arg).map_err(|(m, h)| err(m, span.clone(), h))?);
                }
                let [a, b] = nodes;
                let a = a.expect("arity checked");
                match op {
                    Op::Unary(u) => ctx.unary(u, a),
                    Op::Binary(o) => ctx.binary(o, a, b.expect("arity checked")),
                    _ => a, // copy
                }
            }
        };
        ids.insert(id, (node, line_no));
        last = Some(node);
    }
    last.ok_or_else(|| Error::Vm {
        line: line_no.max(1),
        message: "no instruction: the input is empty or holds only comments".into(),
        span: text.len()..text.len(),
        hint: Some("each line is 'ID OP ARGS...', e.g. '_0 var-x'".into()),
    })
}

/// The node of an argument, or the message and hint of an error.
fn lookup(
    ids: &HashMap<&str, (NodeId, usize)>,
    arg: &str,
) -> Result<NodeId, (String, Option<String>)> {
    if let Some((node, _)) = ids.get(arg) {
        return Ok(*node);
    }
    Err((
        format!("undefined id {}", quote(arg)),
        Some("an id must be defined on an earlier line".into()),
    ))
}

/// The node of a constant's text: an optional sign, then an unsigned decimal literal.
fn constant(ctx: &mut Context, text: &str) -> Option<NodeId> {
    let (negative, digits) = match text.as_bytes().first()? {
        b'-' => (true, &text[1..]),
        b'+' => (false, &text[1..]),
        _ => (false, text),
    };
    if !digits.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None;
    }
    let node = ctx.constant_enclosed(Constant::from_decimal(digits)?);
    Some(if negative { ctx.neg(node) } else { node })
}

/// Writes the graph of `root` in the `.vm` format, one instruction per reachable node in
/// id order (ids `_0`, `_1`, ... in hexadecimal), the root last.
///
/// Operations the format lacks are written as the same real function in its ops:
/// `x^n` as a chain of `square` and `mul` (and `recip` for `n < 0`), `log(a)` as
/// `ln(a) / ln(10)`. A constant is written as a decimal literal that reads back into the
/// same constant, or as a product of such literals (an exact double whose shortest decimal
/// is not exact); a constant folded from an expression, whose enclosure no literal gives,
/// is written as its point value. Reading the output with [`import_vm`] therefore gives the
/// same node again when the graph has none of these rewritten operations and no folded
/// constants.
///
/// # Errors
///
/// [`Error::Unsupported`] for a real power `a ^ b`, the slope operations and variables
/// other than `x`, `y`, `z`, which the format cannot express.
///
/// ```
/// use implicit_expr::{Context, parse::parse, vm::{export_vm, import_vm}};
///
/// let mut ctx = Context::new();
/// let f = parse(&mut ctx, "sqrt(x^2 + y^2) - 0.5", &[]).unwrap();
/// let text = export_vm(&ctx, f).unwrap();
/// assert_eq!(import_vm(&mut ctx, &text).unwrap(), f);
/// ```
pub fn export_vm(ctx: &Context, root: NodeId) -> Result<String, Error> {
    let mut w = Writer {
        out: String::new(),
        next: 0,
        names: HashMap::new(),
    };
    for id in ctx.reachable(&[root]) {
        let line = match *ctx.get(id) {
            Node::Var(v) => {
                let op = match v.index() {
                    0 => "var-x",
                    1 => "var-y",
                    2 => "var-z",
                    i => {
                        let name = ctx.var_names().get(i).map_or("?", String::as_str);
                        return Err(Error::Unsupported(format!(
                            "variable '{name}' cannot be written as .vm: the format has only x, y and z"
                        )));
                    }
                };
                w.emit(op.to_string())
            }
            Node::Const(c) => {
                let lit = literals(&c);
                let sign = if lit.negative { "-" } else { "" };
                let mut acc = w.emit(format!("const {sign}{}", lit.factors[0]));
                for f in &lit.factors[1..] {
                    let k = w.emit(format!("const {f}"));
                    acc = w.emit(format!("mul {acc} {k}"));
                }
                acc
            }
            Node::Unary(op, a) => {
                let a = w.name(a);
                match op {
                    UnaryOp::Sqr => w.emit(format!("square {a}")),
                    UnaryOp::Log10 => {
                        let ten = w.emit("const 10".into());
                        let ln_ten = w.emit(format!("ln {ten}"));
                        let ln_a = w.emit(format!("ln {a}"));
                        w.emit(format!("div {ln_a} {ln_ten}"))
                    }
                    UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => {
                        return Err(Error::Unsupported(format!(
                            "'{}' cannot be written as .vm: the format has no slope operations",
                            op.name()
                        )));
                    }
                    _ => w.emit(format!("{} {a}", op.name())),
                }
            }
            Node::Binary(BinaryOp::Pow, ..) => {
                return Err(Error::Unsupported(
                    "a real power a^b cannot be written as .vm: the format has no pow".into(),
                ));
            }
            Node::Binary(op, a, b) => {
                let (a, b) = (w.name(a), w.name(b));
                w.emit(format!("{} {a} {b}", op.name()))
            }
            Node::Pown(a, n) => {
                let base = w.name(a);
                let mut acc = base.clone();
                let m = n.unsigned_abs();
                if m == 0 {
                    // Not made by `Context::pown` (which gives the constant 1), but valid.
                    let one = w.emit("const 1".into());
                    w.names.insert(id, one);
                    continue;
                }
                // Square and multiply, from the highest bit down.
                for bit in (0..31 - m.leading_zeros()).rev() {
                    acc = w.emit(format!("square {acc}"));
                    if m >> bit & 1 == 1 {
                        acc = w.emit(format!("mul {acc} {base}"));
                    }
                }
                if n < 0 {
                    acc = w.emit(format!("recip {acc}"));
                }
                acc
            }
        };
        w.names.insert(id, line);
    }
    Ok(w.out)
}

/// Output of [`export_vm`]: lines and the id of each node's value.
struct Writer {
    out: String,
    next: usize,
    names: HashMap<NodeId, String>,
}

impl Writer {
    /// Writes one instruction under a fresh id and returns the id.
    fn emit(&mut self, instr: String) -> String {
        let id = format!("_{:x}", self.next);
        self.next += 1;
        let _ = writeln!(self.out, "{id} {instr}");
        id
    }

    /// The id holding the value of an already written node.
    fn name(&self, node: NodeId) -> String {
        self.names[&node].clone()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse;

    #[test]
    fn sphere() {
        let text = "# sphere\n_0 var-x\n_1 square _0\n_2 var-y\n_3 square _2\r\n\n_4 var-z\n\
                    _5 square _4 # z^2\n_6 add _1 _3\n_7 add _6 _5\n_8 sqrt _7\n_9 const 1\n\
                    _a sub _8 _9\n_b copy _a\n";
        let mut ctx = Context::new();
        let f = import_vm(&mut ctx, text).unwrap();
        let g = parse(&mut ctx, "sqrt(x^2 + y^2 + z^2) - 1", &[]).unwrap();
        assert_eq!(f, g);
    }

    #[test]
    fn export_rewrites() {
        let mut ctx = Context::new();
        for (formula, same) in [
            (
                "x^5 - y^-3 + log(z)",
                Some("(x^2)^2*x - recip(y^2*y) + ln(z)/ln(10)"),
            ),
            ("x^(-2147483647)", None),
            ("pown(x, -2147483648)", None),
            ("1/3 + x", None),
            ("0.1*x - pi", Some("0.1*x - 3.141592653589793")),
        ] {
            let f = parse(&mut ctx, formula, &[]).unwrap();
            let text = export_vm(&ctx, f).unwrap();
            let g = import_vm(&mut ctx, &text).unwrap();
            if let Some(same) = same {
                assert_eq!(g, parse(&mut ctx, same, &[]).unwrap(), "{formula}");
            }
            for p in [[0.3, 1.7, 2.5], [-1.1, 0.9, 0.01], [1.0, -1.0, 1.0]] {
                let vf = ctx.eval::<f64>(f, &p).unwrap();
                let vg = ctx.eval::<f64>(g, &p).unwrap();
                let close = (vf - vg).abs() <= 1e-12 * vf.abs().max(1.0);
                assert!(
                    close || vf.to_bits() == vg.to_bits(),
                    "{formula} at {p:?}: {vf} {vg}"
                );
            }
        }
    }

    #[test]
    fn export_errors() {
        let mut ctx = Context::new();
        for formula in ["x^y", "slope_floor(x)", "a + x"] {
            let f = parse(&mut ctx, formula, &["a"]).unwrap();
            assert!(
                matches!(export_vm(&ctx, f), Err(Error::Unsupported(_))),
                "{formula}"
            );
        }
    }
}
