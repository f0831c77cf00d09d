//! The crate's error type.

use std::ops::Range;

/// Everything that can go wrong in this crate. Errors about text carry the byte span of the
/// problem (and, for `.vm` files, the line), and say what was expected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Error {
    /// A formula that does not follow the grammar.
    #[error("{message} at {}..{}{}", span.start, span.end, hint_suffix(hint))]
    Syntax {
        /// What is wrong, and what was expected.
        message: String,
        /// Byte range of the problem in the input.
        span: Range<usize>,
        /// A suggestion (`did you mean 'sin'?`), if there is one.
        hint: Option<String>,
    },
    /// A `.vm` (SSA text) file that cannot be imported.
    #[error("line {line}: {message} at {}..{}{}", span.start, span.end, hint_suffix(hint))]
    Vm {
        /// 1-based line number.
        line: usize,
        /// What is wrong, and what was expected.
        message: String,
        /// Byte range of the problem in the whole input.
        span: Range<usize>,
        /// A suggestion, if there is one.
        hint: Option<String>,
    },
    /// A variable slot that the context has not declared.
    #[error("variable slot {0} is not declared in this context")]
    UnknownVar(u32),
    /// An evaluation given fewer variable values than the expression uses.
    #[error("variable slot {slot} has no value: {given} values given")]
    MissingVar {
        /// The slot without a value.
        slot: u32,
        /// How many values were given.
        given: usize,
    },
    /// A NaN or infinite constant (the graph holds finite constants only).
    #[error("constant {0} is not finite")]
    NonFiniteConstant(f64),
    /// A catalog name that does not exist.
    #[error("unknown surface '{name}'{}", hint_suffix(hint))]
    UnknownSurface {
        /// The name asked for.
        name: String,
        /// The closest catalog name, if any is close.
        hint: Option<String>,
    },
    /// An operation that a transformation cannot handle (with the reason).
    #[error("{0}")]
    Unsupported(String),
}

fn hint_suffix(hint: &Option<String>) -> String {
    match hint {
        Some(h) => format!("; {h}"),
        None => String::new(),
    }
}
