//! The formula language: text such as `x^2 + y^2 + z^2 - 1` or `sin(a*x) - y` parsed into
//! an expression graph.
//!
//! # Grammar
//!
//! | form | meaning |
//! |---|---|
//! | `12`, `1.5`, `.5`, `2.`, `1e-3`, `1.5E+2` | decimal literals; one that no double equals (`0.1`) becomes a constant enclosed by the doubles around it |
//! | `x`, `y`, `z`, parameter names | variables (parameters are declared by the caller) |
//! | `pi`, `e` | the constants π and e (enclosed) |
//! | `a + b`, `a - b`, `a * b`, `a / b` | arithmetic, left-associative |
//! | `-a`, `+a` | prefix signs |
//! | `a ^ b` | power, right-associative, binds tighter than a prefix sign: `-x^2 = -(x^2)`, `2^-x = 2^(-x)`; an exponent that folds to an integer constant (`x^2`, `x^-3`, `x^(1+1)`) is the integer power `pown` |
//! | `(a)` | grouping |
//! | `sqrt exp ln log sin cos tan asin acos atan abs sqr recip floor ceil round not` | functions of one argument (`ln` natural, `log` base 10) |
//! | `neg slope_floor slope_round slope_not` | the remaining one-argument operations (see [`UnaryOp`](crate::UnaryOp)), so that every graph can be printed and read back |
//! | `min(a, b, ...)`, `max(a, b, ...)` | two or more arguments, folded from the left |
//! | `pow(a, b)`, `pown(a, n)` | `a ^ b`; the integer power with an integer constant `n` |
//!
//! Writing two operands side by side (`2x`) is an error: products need `*`.
//!
//! # Errors
//!
//! Every error is an [`Error::Syntax`] with the byte span of the offending token and, where
//! one helps, a hint: `unknown function 'sine' at 0..4; did you mean 'sin'?`.
//!
//! The parser uses no recursion: any nesting depth and any length parse without
//! exhausting the stack (memory is the only limit).

mod lexer;
mod parser;
pub mod suggest;

pub(crate) use parser::quote;

use crate::context::{Context, NodeId};
use crate::error::Error;

/// Parses `text` into `ctx` and returns the root node.
///
/// `x`, `y` and `z` are always variables (slots 0, 1, 2); `params` names further variables,
/// declared in `ctx` in the given order (names already declared keep their slots). Any
/// other name is an error, with a suggestion when it is close to a known one.
///
/// # Errors
///
/// [`Error::Syntax`] for text that does not follow the grammar of the
/// [module documentation](self), and for a parameter name that is not an identifier
/// (`[A-Za-z_][A-Za-z0-9_]*`) or that names a function or a constant (with the empty span
/// `0..0`).
///
/// ```
/// use implicit_expr::{Context, parse::parse};
///
/// let mut ctx = Context::new();
/// let f = parse(&mut ctx, "x^2 + y^2 - r^2", &["r"]).unwrap();
/// assert_eq!(ctx.eval::<f64>(f, &[3.0, 4.0, 0.0, 5.0]).unwrap(), 0.0);
///
/// let err = parse(&mut ctx, "sine(x)", &[]).unwrap_err();
/// assert_eq!(err.to_string(), "unknown function 'sine' at 0..4; did you mean 'sin'?");
/// ```
pub fn parse(ctx: &mut Context, text: &str, params: &[&str]) -> Result<NodeId, Error> {
    for p in params {
        check_param(p)?;
    }
    for p in params {
        ctx.declare_var(p);
    }
    parser::Parser::new(ctx, text, params).run()
}

/// Checks that a parameter name is an identifier and not a function or a constant.
fn check_param(name: &str) -> Result<(), Error> {
    let bytes = name.as_bytes();
    let ident = bytes
        .first()
        .is_some_and(|b| b.is_ascii_alphabetic() || *b == b'_')
        && bytes
            .iter()
            .all(|b| b.is_ascii_alphanumeric() || *b == b'_');
    let problem = if !ident {
        "is not a name of letters, digits and '_'"
    } else if parser::CONSTANTS.contains(&name) {
        "is reserved for a constant"
    } else if parser::function(name).is_some() {
        "is reserved for a function"
    } else {
        return Ok(());
    };
    Err(Error::Syntax {
        message: format!("parameter {} {problem}", quote(name)),
        span: 0..0,
        hint: None,
    })
}

/// Whether `name` can be used as a parameter name of [`parse`] (an identifier that is not
/// `pi`, `e` or a function name).
pub fn is_valid_param(name: &str) -> bool {
    check_param(name).is_ok()
}
