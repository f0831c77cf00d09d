//! The formula parser: operator precedence with explicit stacks, no recursion.
//!
//! The parser alternates between two states: expecting an operand (a number, a name, a
//! call, a prefix sign or an opening parenthesis) and expecting an operator (an infix
//! operator, `,`, `)` or the end). Pending operators, parentheses and calls wait on a
//! stack of [`Frame`]s and operands on a stack of nodes; an infix operator first applies
//! the pending operators that bind at least as tightly. Nesting depth is therefore limited
//! by memory only, and `x+x+…` or `x^x^…` of any length needs no recursion.
//!
//! Precedence, loosest first: `+ -` (left), `* /` (left), prefix `- +`, `^` (right). So
//! `-x^2 = -(x^2)`, `2^-x = 2^(-x)`, `-x*y = (-x)*y`, `x^y^z = x^(y^z)`.

use std::ops::Range;

use super::lexer::{Kind, Lexer, Token, syntax};
use super::suggest;
use crate::constant::Constant;
use crate::context::{Context, NodeId};
use crate::error::Error;
use crate::op::{BinaryOp, UnaryOp};

/// Names of the constants.
pub(crate) const CONSTANTS: [&str; 2] = ["pi", "e"];

/// What a function name calls.
#[derive(Copy, Clone, Debug)]
pub(crate) enum Func {
    /// One argument.
    Unary(UnaryOp),
    /// `min` or `max`: two or more arguments, folded from the left.
    Fold(BinaryOp),
    /// A two-argument function: `pow(a, b)` (the same as `a ^ b`) or `domain(d, f)`.
    Binary(BinaryOp),
    /// `pown(a, n)` for an integer constant `n`.
    Pown,
}

/// The function called `name`, if there is one.
pub(crate) fn function(name: &str) -> Option<Func> {
    if let Some(op) = UnaryOp::ALL.iter().find(|op| op.name() == name) {
        return Some(Func::Unary(*op));
    }
    match name {
        "min" => Some(Func::Fold(BinaryOp::Min)),
        "max" => Some(Func::Fold(BinaryOp::Max)),
        "pow" => Some(Func::Binary(BinaryOp::Pow)),
        "domain" => Some(Func::Binary(BinaryOp::Domain)),
        "pown" => Some(Func::Pown),
        _ => None,
    }
}

/// All function names, for suggestions.
pub(crate) fn function_names() -> impl Iterator<Item = &'static str> {
    UnaryOp::ALL
        .iter()
        .map(|op| op.name())
        .chain(["min", "max", "pow", "pown", "domain"])
}

/// The value of a named constant.
fn named_constant(name: &str) -> Option<Constant> {
    match name {
        "pi" => Some(Constant::pi()),
        "e" => Some(Constant::e()),
        _ => None,
    }
}

/// A pending operator, parenthesis or call.
enum Frame {
    /// Prefix `-` (`neg: true`) or `+`; its operand comes next.
    Prefix { neg: bool },
    /// An infix operator; its left operand is on the value stack.
    Infix { op: BinaryOp },
    /// An opening parenthesis.
    Group { open: Range<usize> },
    /// `name(`, with the number of arguments completed so far on the value stack.
    Call {
        func: Func,
        name: Range<usize>,
        open: Range<usize>,
        args: usize,
    },
}

const PREC_SUM: u8 = 1;
const PREC_PRODUCT: u8 = 2;
const PREC_PREFIX: u8 = 3;
const PREC_POWER: u8 = 4;

fn infix_prec(op: BinaryOp) -> u8 {
    match op {
        BinaryOp::Add | BinaryOp::Sub => PREC_SUM,
        BinaryOp::Pow => PREC_POWER,
        _ => PREC_PRODUCT,
    }
}

/// A token's text for a message, shortened when long.
pub(crate) fn quote(text: &str) -> String {
    const MAX: usize = 40;
    if text.chars().count() <= MAX {
        format!("'{text}'")
    } else {
        let head: String = text.chars().take(MAX).collect();
        format!("'{head}…'")
    }
}

/// Parser state for one formula.
pub(crate) struct Parser<'a> {
    ctx: &'a mut Context,
    text: &'a str,
    lexer: Lexer<'a>,
    peeked: Option<Token>,
    vars: Vec<&'a str>,
    frames: Vec<Frame>,
    values: Vec<NodeId>,
}

impl<'a> Parser<'a> {
    /// A parser of `text` where `x`, `y`, `z` and `params` name variables.
    pub fn new(ctx: &'a mut Context, text: &'a str, params: &[&'a str]) -> Self {
        let mut vars = vec!["x", "y", "z"];
        for p in params {
            if !vars.contains(p) {
                vars.push(p);
            }
        }
        Self {
            ctx,
            text,
            lexer: Lexer::new(text),
            peeked: None,
            vars,
            frames: Vec::new(),
            values: Vec::new(),
        }
    }

    fn next(&mut self) -> Result<Token, Error> {
        match self.peeked.take() {
            Some(t) => Ok(t),
            None => self.lexer.next_token(),
        }
    }

    fn peek(&mut self) -> Result<&Token, Error> {
        if self.peeked.is_none() {
            self.peeked = Some(self.lexer.next_token()?);
        }
        Ok(self.peeked.as_ref().expect("just filled"))
    }

    fn text_of(&self, span: &Range<usize>) -> &'a str {
        &self.text[span.clone()]
    }

    /// Parses the whole text.
    pub fn run(mut self) -> Result<NodeId, Error> {
        loop {
            if self.operand()? {
                continue;
            }
            // An operand is complete: now an operator, a separator, `)` or the end.
            loop {
                let tok = self.next()?;
                let op = match tok.kind {
                    Kind::Plus => BinaryOp::Add,
                    Kind::Minus => BinaryOp::Sub,
                    Kind::Star => BinaryOp::Mul,
                    Kind::Slash => BinaryOp::Div,
                    Kind::Caret => BinaryOp::Pow,
                    Kind::RParen => {
                        self.close(tok.span)?;
                        continue;
                    }
                    Kind::Comma => {
                        self.reduce(0, false);
                        match self.frames.last_mut() {
                            Some(Frame::Call { args, .. }) => {
                                *args += 1;
                                break;
                            }
                            _ => {
                                return Err(syntax(
                                    "unexpected ','".into(),
                                    tok.span,
                                    Some("',' separates the arguments of a function call".into()),
                                ));
                            }
                        }
                    }
                    Kind::End => return self.finish(),
                    Kind::Number | Kind::Ident | Kind::LParen => {
                        let found = quote(self.text_of(&tok.span));
                        return Err(syntax(
                            format!("missing operator before {found}"),
                            tok.span,
                            Some("insert '*' to multiply".into()),
                        ));
                    }
                };
                let prec = infix_prec(op);
                self.reduce(prec, op == BinaryOp::Pow);
                self.frames.push(Frame::Infix { op });
                break;
            }
        }
    }

    /// Reads one token where an operand is expected. Returns `true` when an operand is
    /// still expected (after a prefix sign, `(` or `name(`), `false` when one is complete.
    fn operand(&mut self) -> Result<bool, Error> {
        let tok = self.next()?;
        match tok.kind {
            Kind::Number => {
                let node = self.number(&tok.span)?;
                self.values.push(node);
                Ok(false)
            }
            Kind::Ident => {
                if self.peek()?.kind == Kind::LParen {
                    let open = self.next()?.span;
                    let func = self.function(&tok.span, &open)?;
                    self.frames.push(Frame::Call {
                        func,
                        name: tok.span,
                        open,
                        args: 0,
                    });
                    return Ok(true);
                }
                let node = self.name(&tok.span)?;
                self.values.push(node);
                Ok(false)
            }
            Kind::Minus | Kind::Plus => {
                self.frames.push(Frame::Prefix {
                    neg: tok.kind == Kind::Minus,
                });
                Ok(true)
            }
            Kind::LParen => {
                self.frames.push(Frame::Group { open: tok.span });
                Ok(true)
            }
            Kind::RParen if matches!(self.frames.last(), Some(Frame::Call { args: 0, .. })) => {
                // `f()`: a call without arguments (an arity error for every function).
                let Some(Frame::Call { func, name, .. }) = self.frames.pop() else {
                    unreachable!("matched above")
                };
                let node = self.call(func, name.start..tok.span.end, &name, Vec::new())?;
                self.values.push(node);
                Ok(false)
            }
            Kind::End => Err(syntax("expected an expression".into(), tok.span, None)),
            Kind::Star | Kind::Slash | Kind::Caret | Kind::RParen | Kind::Comma => {
                let found = self.text_of(&tok.span);
                let hint = (tok.kind == Kind::Star
                    && tok.span.start > 0
                    && self.text.as_bytes()[tok.span.start - 1] == b'*')
                    .then(|| "use '^' for powers".to_string());
                Err(syntax(
                    format!("expected an expression, found '{found}'"),
                    tok.span,
                    hint,
                ))
            }
        }
    }

    /// Applies the pending prefix and infix operators that bind tighter than an incoming
    /// operator of precedence `prec` (or as tightly, for a left-associative one).
    fn reduce(&mut self, prec: u8, right_assoc: bool) {
        loop {
            let top = match self.frames.last() {
                Some(Frame::Prefix { .. }) => PREC_PREFIX,
                Some(Frame::Infix { op }) => infix_prec(*op),
                _ => return,
            };
            if top < prec || (top == prec && right_assoc) {
                return;
            }
            let value = match self.frames.pop() {
                Some(Frame::Prefix { neg }) => {
                    let a = self.pop_value();
                    if neg { self.ctx.neg(a) } else { a }
                }
                Some(Frame::Infix { op }) => {
                    let b = self.pop_value();
                    let a = self.pop_value();
                    self.ctx.binary(op, a, b)
                }
                _ => unreachable!("checked above"),
            };
            self.values.push(value);
        }
    }

    fn pop_value(&mut self) -> NodeId {
        self.values
            .pop()
            .expect("every pending operator has its operands on the value stack")
    }

    /// `)`: closes the innermost parenthesis or call.
    fn close(&mut self, close: Range<usize>) -> Result<(), Error> {
        self.reduce(0, false);
        match self.frames.pop() {
            Some(Frame::Group { .. }) => Ok(()),
            Some(Frame::Call {
                func, name, args, ..
            }) => {
                let args = self.values.split_off(self.values.len() - (args + 1));
                let node = self.call(func, name.start..close.end, &name, args)?;
                self.values.push(node);
                Ok(())
            }
            _ => Err(syntax(
                "unmatched ')'".into(),
                close,
                Some("no '(' is open here".into()),
            )),
        }
    }

    /// A decimal literal.
    fn number(&mut self, span: &Range<usize>) -> Result<NodeId, Error> {
        match Constant::from_decimal(self.text_of(span)) {
            Some(c) => Ok(self.ctx.constant_enclosed(c)),
            None => Err(syntax(
                "number out of range".into(),
                span.clone(),
                Some("finite numbers are below 1.8e308 in magnitude".into()),
            )),
        }
    }

    /// Whether `name` is a variable or a constant.
    fn is_value_name(&self, name: &str) -> bool {
        self.vars.contains(&name) || CONSTANTS.contains(&name)
    }

    /// A name used as a value: a variable or a constant.
    fn name(&mut self, span: &Range<usize>) -> Result<NodeId, Error> {
        let name = self.text_of(span);
        if let Some(c) = named_constant(name) {
            return Ok(self.ctx.constant_enclosed(c));
        }
        if self.vars.contains(&name) {
            return Ok(self.ctx.named_var(name));
        }
        if function(name).is_some() {
            return Err(syntax(
                format!("expected '(' after function '{name}'"),
                span.clone(),
                Some(format!("write '{name}(...)'")),
            ));
        }
        let hint = self.unknown_name_hint(name);
        Err(syntax(
            format!("unknown variable {}", quote(name)),
            span.clone(),
            hint,
        ))
    }

    /// A suggestion for an unknown variable: a missing `*` or call parenthesis (`xy`,
    /// `sinx`), else the closest known name, else the list of variables.
    fn unknown_name_hint(&self, name: &str) -> Option<String> {
        if name.len() <= 64 {
            for i in 1..name.len() {
                let (l, r) = name.split_at(i);
                if self.is_value_name(r) {
                    if self.is_value_name(l) {
                        return Some(format!("did you mean '{l}*{r}'?"));
                    }
                    if function(l).is_some() {
                        return Some(format!("did you mean '{l}({r})'?"));
                    }
                }
            }
        }
        let known = self.vars.iter().copied().chain(CONSTANTS);
        suggest::did_you_mean(name, known).or_else(|| {
            let mut list: Vec<&str> = self.vars.iter().copied().take(10).collect();
            if self.vars.len() > 10 {
                list.push("...");
            }
            Some(format!("the variables are {}", list.join(", ")))
        })
    }

    /// The function of `name(`, or an error.
    fn function(&self, span: &Range<usize>, open: &Range<usize>) -> Result<Func, Error> {
        let name = self.text_of(span);
        if let Some(f) = function(name) {
            return Ok(f);
        }
        if self.is_value_name(name) {
            return Err(syntax(
                "missing operator before '('".into(),
                open.clone(),
                Some("insert '*' to multiply".into()),
            ));
        }
        Err(syntax(
            format!("unknown function {}", quote(name)),
            span.clone(),
            suggest::did_you_mean(name, function_names()),
        ))
    }

    /// The node of a call with its arguments, after checking their number.
    fn call(
        &mut self,
        func: Func,
        span: Range<usize>,
        name: &Range<usize>,
        args: Vec<NodeId>,
    ) -> Result<NodeId, Error> {
        let name = self.text_of(name);
        let n = args.len();
        let plural = |k: usize| if k == 1 { "argument" } else { "arguments" };
        let arity = |want: usize| {
            syntax(
                format!("'{name}' takes {want} {}, got {n}", plural(want)),
                span.clone(),
                None,
            )
        };
        Ok(match (func, args.as_slice()) {
            (Func::Unary(op), &[a]) => self.ctx.unary(op, a),
            (Func::Unary(_), _) => return Err(arity(1)),
            (Func::Binary(op), &[a, b]) => self.ctx.binary(op, a, b),
            (Func::Pown, &[a, b]) => {
                let n = self.ctx.as_const(b).and_then(|c| {
                    let v = c.value();
                    let int = c.is_exact() && v.fract() == 0.0;
                    (int && v >= f64::from(i32::MIN) && v <= f64::from(i32::MAX))
                        .then_some(v as i32)
                });
                match n {
                    Some(n) => self.ctx.pown(a, n),
                    None => {
                        return Err(syntax(
                            "the exponent of 'pown' must be an integer constant".into(),
                            span,
                            Some("use '^' or 'pow' for other exponents".into()),
                        ));
                    }
                }
            }
            (Func::Binary(_) | Func::Pown, _) => return Err(arity(2)),
            (Func::Fold(op), &[first, ref rest @ ..]) if !rest.is_empty() => rest
                .iter()
                .fold(first, |acc, &b| self.ctx.binary(op, acc, b)),
            (Func::Fold(_), _) => {
                return Err(syntax(
                    format!("'{name}' takes at least 2 arguments, got {n}"),
                    span,
                    None,
                ));
            }
        })
    }

    /// End of input: everything must be closed.
    fn finish(mut self) -> Result<NodeId, Error> {
        self.reduce(0, false);
        match self.frames.last() {
            Some(Frame::Group { open } | Frame::Call { open, .. }) => Err(syntax(
                "unmatched '('".into(),
                open.clone(),
                Some("add ')' to close it".into()),
            )),
            _ => Ok(self.pop_value()),
        }
    }
}
