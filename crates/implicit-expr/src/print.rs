//! Printing a graph back as a formula of the [formula language](crate::parse).
//!
//! [`to_formula`] writes text that [`parse`] reads back into the
//! *same* node of the same context (hash-consing makes the check a comparison of
//! [`NodeId`]s), provided every constant of the graph has a literal form:
//!
//! * exact constants always do: their shortest decimal (`0.5`, `3`, `1e-7`), or, when that
//!   decimal is not the double exactly, a product of exact literals that folds back to the
//!   double (`(3602879701896397*5.5511151231257827021181583404541015625e-17)`);
//! * an inexact literal such as `0.1` prints as itself, and reading it again gives the same
//!   enclosure; `pi`, `e` and their negatives print by name;
//! * a constant folded from an expression (`1/3`, `sin(1)`) carries an enclosure that no
//!   literal reproduces. It prints as its point value (the double nearest the folded
//!   result), so the text reads back into a constant with the same value but the enclosure
//!   of that decimal literal: the same function for point evaluation, a slightly different
//!   constant for interval evaluation.
//!
//! Parentheses are minimal (`x^2 + y^2 - 1`, `-(x + y)`, `(x^2)^3`, `a - (b - c)`), except
//! that no operand right after an operator starts with a sign (`x*(-y)`, `x - (-2)*y`).
//! The operands of `+`, `*`, `min` and `max` are printed in the order that needs the fewest
//! parentheses (constants first in products, last in sums); the graph stores them in a
//! canonical order anyway, so either order reads back into the same node, and nested
//! `min`/`max` print as one call (`min(x, y, z)`). A subexpression shared in the graph is printed at each use, so the text of
//! a graph with much sharing can be much longer than the graph. The printer walks the graph
//! with an explicit stack: no depth of nesting exhausts the call stack.

use std::collections::HashMap;

use crate::constant::Constant;
use crate::context::{Context, Node, NodeId};
use crate::op::{BinaryOp, UnaryOp};
use crate::parse::parse;

/// Prints the graph of `root` as a formula.
///
/// Variables print by their names in `ctx`; parsing the text with
/// `ctx.var_names()[3..]` as parameters gives `root` again (see the
/// [module documentation](self) for the constants for which this holds).
///
/// ```
/// use implicit_expr::{Context, parse::parse, print::to_formula};
///
/// let mut ctx = Context::new();
/// let f = parse(&mut ctx, "(x*x + y^2) - sin(z)*-0.1", &[]).unwrap();
/// let text = to_formula(&ctx, f);
/// assert_eq!(text, "x^2 + y^2 - (-0.1)*sin(z)");
/// assert_eq!(parse(&mut ctx, &text, &[]).unwrap(), f);
/// ```
pub fn to_formula(ctx: &Context, root: NodeId) -> String {
    let mut consts = HashMap::new();
    for id in ctx.reachable(&[root]) {
        if let Node::Const(c) = ctx.get(id) {
            consts.insert(id, constant_formula(c));
        }
    }
    let printer = Printer { ctx, consts };
    let mut out = String::new();
    let mut stack = vec![Item::Node(root, Slot::Any(true))];
    let mut parts = Vec::with_capacity(8);
    while let Some(item) = stack.pop() {
        let (id, slot) = match item {
            Item::Str(s) => {
                out.push_str(s);
                continue;
            }
            Item::Owned(s) => {
                out.push_str(&s);
                continue;
            }
            Item::Node(id, slot) => (id, slot),
        };
        let wrap = !fits(printer.prec(id), slot);
        if wrap {
            out.push('(');
            stack.push(Item::Str(")"));
        }
        // A sign may open the node's text if it may open the slot's text.
        let lead = wrap || slot.sign_ok();
        printer.parts(id, lead, &mut parts);
        stack.extend(parts.drain(..).rev());
    }
    out
}

/// A piece of output still to be written.
enum Item<'a> {
    Str(&'a str),
    Owned(String),
    Node(NodeId, Slot),
}

/// How tightly a printed expression binds, loosest first.
#[derive(Copy, Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Prec {
    /// `a + b`, `a - b`
    Sum,
    /// `a * b`, `a / b`
    Product,
    /// `-a`
    Prefix,
    /// `a ^ b`
    Power,
    /// names, literals, calls, parenthesized text
    Atom,
}

/// Where an expression is printed. `true` in `Any` and `ProductLeft` allows the text to
/// start with a sign, which is never the case right after an operator.
#[derive(Copy, Clone, Debug)]
enum Slot {
    /// The whole formula, a call argument, or the left operand of `+`/`-`.
    Any(bool),
    /// Right operand of `+` or `-`.
    SumRight,
    /// Left operand of `*` or `/`.
    ProductLeft(bool),
    /// Right operand of `*` or `/`, operand of a prefix `-`, exponent of `^`.
    Tight,
    /// Base of `^`.
    Base,
}

impl Slot {
    /// Whether text here may start with a sign.
    fn sign_ok(self) -> bool {
        match self {
            Slot::Any(ok) | Slot::ProductLeft(ok) => ok,
            Slot::SumRight | Slot::Tight | Slot::Base => false,
        }
    }
}

/// Whether an expression of precedence `p` can stand in `slot` without parentheses.
fn fits(p: Prec, slot: Slot) -> bool {
    match slot {
        Slot::Any(sign_ok) => p != Prec::Prefix || sign_ok,
        Slot::SumRight => p >= Prec::Product && p != Prec::Prefix,
        Slot::ProductLeft(sign_ok) => p >= Prec::Product && (p != Prec::Prefix || sign_ok),
        Slot::Tight => p >= Prec::Power,
        Slot::Base => p == Prec::Atom,
    }
}

/// The graph and the text of its constants.
struct Printer<'a> {
    ctx: &'a Context,
    consts: HashMap<NodeId, (String, Prec)>,
}

impl<'a> Printer<'a> {
    fn prec(&self, id: NodeId) -> Prec {
        match self.ctx.get(id) {
            Node::Var(_) => Prec::Atom,
            Node::Const(_) => self.consts.get(&id).map_or(Prec::Atom, |k| k.1),
            Node::Unary(UnaryOp::Neg, _) => Prec::Prefix,
            Node::Unary(UnaryOp::Sqr, _) | Node::Pown(..) => Prec::Power,
            Node::Unary(..) => Prec::Atom,
            Node::Binary(op, ..) => match op {
                BinaryOp::Add | BinaryOp::Sub => Prec::Sum,
                BinaryOp::Mul | BinaryOp::Div => Prec::Product,
                BinaryOp::Min | BinaryOp::Max | BinaryOp::Domain => Prec::Atom,
                BinaryOp::Pow => Prec::Power,
            },
        }
    }

    fn is_const(&self, id: NodeId) -> bool {
        matches!(self.ctx.get(id), Node::Const(_))
    }

    /// The operands of a commutative `+` or `*` in the order that prints best: an operand
    /// of the same precedence (`a + b` in a sum) first, as it then needs no parentheses;
    /// then one that starts with a sign; constants first in products, last in sums.
    fn order(&self, same: Prec, a: NodeId, b: NodeId) -> (NodeId, NodeId) {
        let key = |id: NodeId| {
            let p = self.prec(id);
            let c = self.is_const(id);
            (
                p == same,
                p == Prec::Prefix,
                if same == Prec::Sum { !c } else { c },
            )
        };
        if key(b) > key(a) { (b, a) } else { (a, b) }
    }

    /// The arguments of nested `op` calls (`min(min(x, y), z)`) as one list: descending
    /// into an argument that is itself `op` gives the arguments whose left fold makes the
    /// same nodes again, since the graph orders the two arguments canonically anyway.
    fn chain(&self, op: BinaryOp, a: NodeId, b: NodeId) -> Vec<NodeId> {
        let is_op = |id: NodeId| matches!(self.ctx.get(id), Node::Binary(o, ..) if *o == op);
        let children = |id: NodeId| match self.ctx.get(id) {
            Node::Binary(_, p, q) => (*p, *q),
            _ => unreachable!("checked by is_op"),
        };
        let mut rest = Vec::new();
        let (mut l, mut r) = (a, b);
        loop {
            if is_op(l) {
                rest.push(r);
                (l, r) = children(l);
            } else if is_op(r) {
                rest.push(l);
                (l, r) = children(r);
            } else {
                rest.push(r);
                rest.push(l);
                rest.reverse();
                return rest;
            }
        }
    }

    /// The pieces of node `id`, in output order; `lead` tells whether its text may start
    /// with a sign.
    fn parts(&'a self, id: NodeId, lead: bool, parts: &mut Vec<Item<'a>>) {
        use Item::{Node as N, Str};
        let any = Slot::Any(true);
        match *self.ctx.get(id) {
            Node::Var(v) => match self.ctx.var_names().get(v.index()) {
                Some(name) => parts.push(Str(name)),
                None => parts.push(Item::Owned(format!("var{}", v.index()))),
            },
            Node::Const(c) => match self.consts.get(&id) {
                Some(k) => parts.push(Str(&k.0)),
                None => parts.push(Item::Owned(constant_formula(&c).0)),
            },
            Node::Unary(UnaryOp::Neg, a) => parts.extend([Str("-"), N(a, Slot::Tight)]),
            Node::Unary(UnaryOp::Sqr, a) => parts.extend([N(a, Slot::Base), Str("^2")]),
            Node::Unary(op, a) => parts.extend([Str(op.name()), Str("("), N(a, any), Str(")")]),
            Node::Binary(op, a, b) => {
                let (left, mid, right) = match op {
                    BinaryOp::Add => {
                        let (a, b) = self.order(Prec::Sum, a, b);
                        (N(a, Slot::Any(lead)), " + ", N(b, Slot::SumRight))
                    }
                    BinaryOp::Sub => (N(a, Slot::Any(lead)), " - ", N(b, Slot::SumRight)),
                    BinaryOp::Mul => {
                        let (a, b) = self.order(Prec::Product, a, b);
                        (N(a, Slot::ProductLeft(lead)), "*", N(b, Slot::Tight))
                    }
                    BinaryOp::Div => (N(a, Slot::ProductLeft(lead)), "/", N(b, Slot::Tight)),
                    BinaryOp::Pow => (N(a, Slot::Base), "^", N(b, Slot::Tight)),
                    BinaryOp::Domain => {
                        parts.extend([Str(op.name()), Str("("), N(a, any), Str(", ")]);
                        parts.extend([N(b, any), Str(")")]);
                        return;
                    }
                    BinaryOp::Min | BinaryOp::Max => {
                        parts.extend([Str(op.name()), Str("(")]);
                        for (i, arg) in self.chain(op, a, b).into_iter().enumerate() {
                            if i > 0 {
                                parts.push(Str(", "));
                            }
                            parts.push(N(arg, any));
                        }
                        parts.push(Str(")"));
                        return;
                    }
                };
                parts.extend([left, Str(mid), right]);
            }
            // `x^n` reads back as `pown` for every `n` except `i32::MIN`, whose magnitude is
            // no `i32` (the parser then makes a real power): that one needs the call form.
            Node::Pown(a, i32::MIN) => {
                parts.extend([Str("pown("), N(a, any), Str(", -2147483648)")]);
            }
            Node::Pown(a, n) => parts.extend([
                N(a, Slot::Base),
                Str("^"),
                Item::Owned(if n < 0 {
                    format!("({n})")
                } else {
                    n.to_string()
                }),
            ]),
        }
    }
}

/// A constant as decimal literals: `[-]f0 * f1 * ...` (the sign applies to `f0`).
///
/// Reading the literals, negating the first when `negative`, and multiplying from the
/// left gives the constant exactly when `round_trips` is set; otherwise `factors` is the
/// single shortest decimal of the value.
pub(crate) struct Literals {
    /// Whether the first factor is negated.
    pub negative: bool,
    /// Unsigned decimal literals.
    pub factors: Vec<String>,
    /// Whether the literals fold back into the very constant.
    pub round_trips: bool,
}

impl Literals {
    fn new(negative: bool, factors: Vec<String>) -> Self {
        Self {
            negative,
            factors,
            round_trips: false,
        }
    }

    /// The formula text and its precedence.
    fn formula(&self) -> (String, Prec) {
        let sign = if self.negative { "-" } else { "" };
        match self.factors.as_slice() {
            [one] if self.negative => (format!("-{one}"), Prec::Prefix),
            [one] => (one.clone(), Prec::Atom),
            many => (format!("({sign}{})", many.join("*")), Prec::Atom),
        }
    }

    /// Whether parsing the formula text gives exactly `c` (checked in a scratch context).
    fn check(&mut self, c: &Constant) -> bool {
        let mut scratch = Context::new();
        let ok = parse(&mut scratch, &self.formula().0, &[])
            .ok()
            .and_then(|n| scratch.as_const(n))
            .is_some_and(|k| k == *c);
        self.round_trips = ok;
        ok
    }
}

/// The literals of a constant (see [`Literals`]).
pub(crate) fn literals(c: &Constant) -> Literals {
    let v = c.value();
    let negative = v.is_sign_negative();
    let a = v.abs();
    let mut short = Literals::new(negative, vec![shortest_decimal(a)]);
    if short.check(c) {
        return short;
    }
    if c.is_exact()
        && let Some(factors) = exact_factors(a)
    {
        let mut exact = Literals::new(negative, factors);
        if exact.check(c) {
            return exact;
        }
    }
    short
}

/// The formula text of a constant and its precedence: `pi`, `e` or [`literals`].
fn constant_formula(c: &Constant) -> (String, Prec) {
    for (name, k) in [("pi", Constant::pi()), ("e", Constant::e())] {
        if *c == k {
            return (name.to_string(), Prec::Atom);
        }
        let mut scratch = Context::new();
        let n = scratch.constant_enclosed(k);
        let m = scratch.neg(n);
        if scratch.as_const(m) == Some(*c) {
            return (format!("-{name}"), Prec::Prefix);
        }
    }
    literals(c).formula()
}

/// The shortest decimal that reads back as the double `a >= 0` (`3` rather than `3.0`).
fn shortest_decimal(a: f64) -> String {
    let s = format!("{a:?}");
    match s.strip_suffix(".0") {
        Some(int) => int.to_string(),
        None => s,
    }
}

/// An exact positive double `a = m · 2^k` as literals `m`, then powers of two whose
/// decimal expansions are short enough (at most 38 digits) to be read as exact: `2^j` for
/// `j <= 126` and `2^-j` for `j <= 54`. Every partial product is a double, so each
/// multiplication is exact.
fn exact_factors(a: f64) -> Option<Vec<String>> {
    if a == 0.0 || !a.is_finite() {
        return None;
    }
    let bits = a.to_bits();
    let biased = ((bits >> 52) & 0x7ff) as i32;
    let frac = bits & ((1u64 << 52) - 1);
    let (mut m, mut k) = if biased == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), biased - 1075)
    };
    let tz = m.trailing_zeros();
    m >>= tz;
    k += tz as i32;
    let mut factors = vec![m.to_string()];
    while k != 0 {
        let step = k.clamp(-54, 126);
        factors.push(exact_decimal(2f64.powi(step)));
        k -= step;
    }
    Some(factors)
}

/// All the digits of a double whose decimal expansion has at most 40 significant digits.
fn exact_decimal(p: f64) -> String {
    let s = format!("{p:.40e}");
    let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    if exp == "0" {
        mantissa.to_string()
    } else {
        format!("{mantissa}e{exp}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trip(ctx: &mut Context, id: NodeId) -> String {
        let text = to_formula(ctx, id);
        let params: Vec<String> = ctx.var_names()[3..].to_vec();
        let params: Vec<&str> = params.iter().map(String::as_str).collect();
        let back = parse(ctx, &text, &params).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(back, id, "{text}");
        text
    }

    #[test]
    fn exact_constants_round_trip() {
        let mut ctx = Context::new();
        for v in [
            0.1,
            -0.1,
            1.0 / 3.0,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            2.5e-320,
            1e300,
            123456.75,
            0.0,
            -0.0,
            std::f64::consts::PI,
        ] {
            let c = ctx.constant(v).unwrap();
            let text = round_trip(&mut ctx, c);
            let x = ctx.x();
            let p = ctx.mul(x, c);
            round_trip(&mut ctx, p);
            let q = ctx.sub(x, c);
            round_trip(&mut ctx, q);
            assert!(!text.is_empty());
        }
    }

    #[test]
    fn named_and_literal_constants() {
        let mut ctx = Context::new();
        for (text, printed) in [
            ("pi", "pi"),
            ("-pi", "-pi"),
            ("e", "e"),
            ("-e", "-e"),
            ("0.1", "0.1"),
            ("-0.1", "-0.1"),
            ("1e23", "1e23"),
            ("3", "3"),
            ("2.5e-10", "2.5e-10"),
        ] {
            let c = parse(&mut ctx, text, &[]).unwrap();
            assert_eq!(round_trip(&mut ctx, c), printed);
        }
    }

    #[test]
    fn parentheses() {
        let mut ctx = Context::new();
        let mut wrong = Vec::new();
        for (text, printed) in [
            ("x^2 + y^2 - 1", "x^2 + y^2 - 1"),
            ("-(x + y)", "-(x + y)"),
            ("-x^2", "-x^2"),
            ("(-x)^3", "(-x)^3"),
            ("(x^2)^3", "(x^2)^3"),
            ("x^y^z", "x^y^z"),
            ("(x^y)^z", "(x^y)^z"),
            ("x - (y - z)", "x - (y - z)"),
            ("x - (y + z)", "x - (y + z)"),
            ("(x - y) - z", "x - y - z"),
            ("x/(y*z)", "x/(y*z)"),
            ("x*(-y)", "-y*x"),
            ("x/(-y)", "x/(-y)"),
            ("x/(-2*y)", "x/(-2*y)"),
            ("x - -2", "x - (-2)"),
            ("y*-x", "-x*y"),
            ("x - -2*y", "x - (-2)*y"),
            ("x*(-2*y)", "-2*y*x"),
            ("-2*y - x", "-2*y - x"),
            ("(-2*y)^x", "(-2*y)^x"),
            ("x^-3", "x^(-3)"),
            ("x^-1", "recip(x)"),
            ("2^-x", "2^(-x)"),
            ("min(x, y, z)", "min(x, y, z)"),
            ("max(max(x, 1), max(y, z))", "max(x, 1, max(y, z))"),
            ("x + (y + z)", "y + z + x"),
            ("x*(y/z)", "y/z*x"),
            ("x*2", "2*x"),
            ("1 + x", "x + 1"),
            ("x + -y", "-y + x"),
            ("pown(x, -2147483648)", "pown(x, -2147483648)"),
            ("slope_floor(x) + floor(y)", "slope_floor(x) + floor(y)"),
            ("log(x) + ln(y)", "log(x) + ln(y)"),
        ] {
            let id = parse(&mut ctx, text, &[]).unwrap();
            let got = round_trip(&mut ctx, id);
            if got != printed {
                wrong.push(format!("{text} printed as {got}, expected {printed}"));
            }
        }
        assert!(wrong.is_empty(), "{wrong:#?}");
    }
    #[test]
    fn deep_graph_prints_without_recursion() {
        let mut ctx = Context::new();
        let mut f = ctx.x();
        for _ in 0..100_000 {
            f = ctx.unary(UnaryOp::Sin, f);
        }
        let text = to_formula(&ctx, f);
        assert_eq!(text.len(), 100_000 * 5 + 1);
    }
}
