//! WGSL code generation: a [`Tape`] written as WGSL functions, for a GPU backend to paste
//! next to its interval library and its kernels.
//!
//! For a tape and a name `f`, a [`Generator`] writes
//!
//! * the **interval function** `fn f(x: Interval, y: Interval, z: Interval) -> Interval`,
//!   which calls the interval library (below) once per operation, and
//! * the **point function** `fn f_point(x: f32, y: f32, z: f32) -> f32`, which uses only
//!   WGSL built-ins and so needs nothing else.
//!
//! The text is a fragment: no entry point, no bindings, no library. This crate never links
//! a GPU API; it only writes text.
//!
//! # Example
//!
//! ```
//! use implicit_expr::{Context, Tape, wgsl};
//!
//! let mut ctx = Context::new();
//! let (x, y, z) = (ctx.x(), ctx.y(), ctx.z());
//! let (x2, y2, z2) = (ctx.sqr(x), ctx.sqr(y), ctx.sqr(z));
//! let s = ctx.add(x2, y2);
//! let s = ctx.add(s, z2);
//! let one = ctx.constant(1.0)?;
//! let f = ctx.sub(s, one);
//! let tape = Tape::new(&ctx, &[f])?;
//!
//! let generator = wgsl::Generator::new(&tape, "sphere")?;
//! let source = generator.interval_source();
//! assert!(source.contains("fn sphere(x: Interval, y: Interval, z: Interval) -> Interval {"));
//! assert!(source.contains("i_sqr(v1)"));
//! assert_eq!(generator.required_functions(), ["i_add", "i_sub", "i_sqr"]);
//! assert!(generator.point_source().contains("fn sphere_point(x: f32, y: f32, z: f32) -> f32 {"));
//! # Ok::<(), implicit_expr::Error>(())
//! ```
//!
//! # The layout of the generated functions
//!
//! With the function name `f` (checked to be a WGSL identifier that is neither a keyword,
//! a reserved word nor a predeclared name, and that does not start with `i_` nor equals
//! `Interval`, which belong to the library):
//!
//! ```text
//! fn f(x: Interval, y: Interval, z: Interval, p: array<Interval, K>) -> Interval
//! fn f_point(x: f32, y: f32, z: f32, p: array<f32, K>) -> f32
//! ```
//!
//! * **Inputs.** Variable slots `0, 1, 2` are the arguments `x, y, z`; the names (and how
//!   many slots get an argument of their own) can be changed with
//!   [`Generator::with_inputs`], e.g. `cx cy cz t dx dy dz` for the ray functions of
//!   [`RayFunction`](crate::ray::RayFunction). The remaining slots (the parameters) are the
//!   elements of the array argument `p`, in slot order: slot `inputs + k` is `p[k]`. `p` is
//!   left out when no slot remains (`K` would be 0). An argument the tape does not use is
//!   still declared, so the signature depends only on the inputs and the slot count.
//! * **Outputs.** A tape with one output returns it. A tape with `n > 1` outputs (as `g` and
//!   `g'` of a ray) returns a struct, declared just before the function:
//!   `struct f_out { out0: Interval, ..., out{n-1}: Interval }` for the interval function,
//!   `struct f_point_out { out0: f32, ... }` for the point function.
//! * **Body.** One `let` per SSA value (`let v7 = i_mul(v3, v5);`), in tape order, then the
//!   `return`. Nothing nests, so a tape of any length is valid WGSL.
//!
//! # The contract with the interval library
//!
//! The interval function uses a type and functions that it does not declare; the module it
//! is pasted into must provide them:
//!
//! * **`Interval`**, any type that can be built as `Interval(lo, hi)` from two `f32`: a
//!   `struct Interval { lo: f32, hi: f32 }` or `alias Interval = vec2<f32>` both fit. The
//!   generated code never reads a field, compares or branches on an interval; how the
//!   library stands for empty and unbounded intervals is its own affair.
//! * **The functions of [`LIBRARY`]**, with exactly those names and signatures. Each must be
//!   an inclusion function: its result contains `op(a)` (or `op(a, b)`) for every `a` in
//!   the argument interval (and `b` in the second one) where the operation is defined,
//!   following the definitions of [`UnaryOp`] and [`BinaryOp`] (IEEE 1788 domains: `sqrt`
//!   and `ln` on `a >= 0`, `pow` on `a > 0` and `a = 0, b > 0`, and so on, and the slope
//!   operations as documented on [`UnaryOp`]). [`function`] names the function of each
//!   [`Op`], and [`Op::ALL`] lists the operations; [`Generator::required_functions`] tells
//!   which of the functions one tape needs.
//!
//! Constants are folded into the text as `f32` enclosures of the tape's `f64` enclosures,
//! rounded outward ([`enclose_f32`]) and written exactly ([`f32_literal`]):
//! `Interval(0x1.999998p-4f, 0x1.99999ap-4f)` for `0.1`, `Interval(0.5f, 0.5f)` for `0.5`.
//! Every literal is exact (decimal only where the value has a short exact expansion,
//! hexadecimal otherwise), so no WGSL implementation may round it either way. No bound is
//! subnormal, so the enclosure survives hardware that flushes subnormals to zero. WGSL cannot write an infinite value, so a constant whose enclosure
//! leaves the `f32` range is built by the library instead: `i_at_least(lo)` for
//! `[lo, +inf]`, `i_at_most(hi)` for `[-inf, hi]`, `i_entire()` for both.
//!
//! The point function rounds each constant to the nearest `f32` (clamped to the finite
//! range) and uses the built-ins: `log10(a)` is `log2(a) * log10(2)`, `round` rounds halves
//! away from zero as [`UnaryOp::Round`] does (WGSL's `round` rounds them to even), `pown`
//! is unrolled into multiplications, `pow` is WGSL's `pow` (undefined for `a < 0`), and the
//! slope operations are `0`. Point values are estimates, never bounds.

mod ident;
mod literal;

use std::fmt::Write;

use crate::constant::Constant;
use crate::error::Error;
use crate::op::{BinaryOp, Op, UnaryOp};
use crate::tape::{Opcode, Tape};

pub use literal::{enclose_f32, f32_literal};

/// One function that the interval library must provide.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct LibraryFunction {
    /// The function's name, e.g. `i_add`.
    pub name: &'static str,
    /// Its parameters as WGSL declares them, e.g. `a: Interval, b: Interval`.
    pub params: &'static str,
    /// What its result must contain.
    pub encloses: &'static str,
}

impl LibraryFunction {
    /// The function of the operation `op`.
    pub const fn of(op: Op) -> Self {
        let (name, params, encloses) = match op {
            Op::Binary(b) => (
                binary_entry(b).0,
                "a: Interval, b: Interval",
                binary_entry(b).1,
            ),
            Op::Pown => (
                POWN_FUNCTION,
                "a: Interval, n: i32",
                "a^n for the integer n (a^0 = 1; a != 0 when n < 0)",
            ),
            Op::Unary(u) => (unary_entry(u).0, "a: Interval", unary_entry(u).1),
        };
        LibraryFunction {
            name,
            params,
            encloses,
        }
    }

    /// Its WGSL declaration without the body, e.g.
    /// `fn i_add(a: Interval, b: Interval) -> Interval`.
    pub fn signature(&self) -> String {
        format!("fn {}({}) -> Interval", self.name, self.params)
    }
}

/// The constructors of constants beyond the `f32` range, after the operations' functions in
/// [`LIBRARY`].
const CONSTRUCTORS: [LibraryFunction; 3] = [
    LibraryFunction {
        name: "i_entire",
        params: "",
        encloses: "every real: [-inf, +inf]",
    },
    LibraryFunction {
        name: "i_at_least",
        params: "lo: f32",
        encloses: "[lo, +inf]",
    },
    LibraryFunction {
        name: "i_at_most",
        params: "hi: f32",
        encloses: "[-inf, hi]",
    },
];

/// Every function the generated interval code may call, in a fixed order: one per
/// operation (in [`Op::ALL`] order: the binary operations, `i_pown`, the unary operations),
/// then the constructors of unbounded constants (`i_entire`, `i_at_least`, `i_at_most`).
pub const LIBRARY: [LibraryFunction; Op::ALL.len() + CONSTRUCTORS.len()] = {
    let mut all = [CONSTRUCTORS[0]; Op::ALL.len() + CONSTRUCTORS.len()];
    let mut i = 0;
    while i < Op::ALL.len() {
        all[i] = LibraryFunction::of(Op::ALL[i]);
        i += 1;
    }
    let mut k = 0;
    while k < CONSTRUCTORS.len() {
        all[Op::ALL.len() + k] = CONSTRUCTORS[k];
        k += 1;
    }
    all
};

/// The names of [`LIBRARY`], in the same order.
pub const LIBRARY_FUNCTIONS: [&str; LIBRARY.len()] = {
    let mut names = [""; LIBRARY.len()];
    let mut i = 0;
    while i < LIBRARY.len() {
        names[i] = LIBRARY[i].name;
        i += 1;
    }
    names
};

/// The library function of a unary operation and what its result must contain: the one
/// table of the unary operations' part of the contract.
const fn unary_entry(op: UnaryOp) -> (&'static str, &'static str) {
    match op {
        UnaryOp::Neg => ("i_neg", "-a"),
        UnaryOp::Abs => ("i_abs", "|a|"),
        UnaryOp::Sqr => ("i_sqr", "a^2"),
        UnaryOp::Sqrt => ("i_sqrt", "sqrt(a) for a >= 0"),
        UnaryOp::Recip => ("i_recip", "1 / a (a != 0)"),
        UnaryOp::Exp => ("i_exp", "e^a"),
        UnaryOp::Ln => ("i_ln", "ln(a) for a > 0"),
        UnaryOp::Log10 => ("i_log10", "log10(a) for a > 0"),
        UnaryOp::Sin => ("i_sin", "sin(a)"),
        UnaryOp::Cos => ("i_cos", "cos(a)"),
        UnaryOp::Tan => ("i_tan", "tan(a) away from the poles"),
        UnaryOp::Asin => ("i_asin", "asin(a) for -1 <= a <= 1"),
        UnaryOp::Acos => ("i_acos", "acos(a) for -1 <= a <= 1"),
        UnaryOp::Atan => ("i_atan", "atan(a)"),
        UnaryOp::Floor => ("i_floor", "floor(a)"),
        UnaryOp::Ceil => ("i_ceil", "ceil(a)"),
        UnaryOp::Round => ("i_round", "round(a), halves away from zero"),
        UnaryOp::Not => ("i_not", "1 where a = 0, else 0"),
        UnaryOp::SlopeFloor => (
            "i_slope_floor",
            "0 if a holds no integer, else [-inf, +inf]",
        ),
        UnaryOp::SlopeRound => (
            "i_slope_round",
            "0 if a holds no half-integer, else [-inf, +inf]",
        ),
        UnaryOp::SlopeNot => ("i_slope_not", "0 if a does not hold 0, else [-inf, +inf]"),
    }
}

/// The library function of a binary operation and what its result must contain.
const fn binary_entry(op: BinaryOp) -> (&'static str, &'static str) {
    match op {
        BinaryOp::Add => ("i_add", "a + b"),
        BinaryOp::Sub => ("i_sub", "a - b"),
        BinaryOp::Mul => ("i_mul", "a * b"),
        BinaryOp::Div => ("i_div", "a / b (b != 0)"),
        BinaryOp::Min => ("i_min", "min(a, b)"),
        BinaryOp::Max => ("i_max", "max(a, b)"),
        BinaryOp::Pow => ("i_pow", "a^b for a > 0, and for a = 0 when b > 0"),
        BinaryOp::Domain => ("i_domain", "b where a <= 0, +inf where a > 0"),
    }
}

/// The library function that the interval code calls for `op`.
pub const fn function(op: Op) -> &'static str {
    LibraryFunction::of(op).name
}

/// The library function that the interval code calls for `op`.
pub const fn unary_function(op: UnaryOp) -> &'static str {
    unary_entry(op).0
}

/// The library function that the interval code calls for `op`.
pub const fn binary_function(op: BinaryOp) -> &'static str {
    binary_entry(op).0
}

/// The library function that the interval code calls for an integer power.
pub const POWN_FUNCTION: &str = "i_pown";

/// Name of the array argument that holds the variable slots past the named inputs.
pub const PARAMS_ARG: &str = "p";

/// How a constant's `f32` enclosure is built in WGSL.
enum ConstForm {
    /// Both bounds finite: `Interval(lo, hi)`.
    Bounded(f32, f32),
    /// `[lo, +inf]`.
    AtLeast(f32),
    /// `[-inf, hi]`.
    AtMost(f32),
    /// `[-inf, +inf]`.
    Entire,
}

impl ConstForm {
    fn of(c: &Constant) -> Self {
        let (lo, hi) = enclose_f32(c.lo(), c.hi());
        match (lo.is_finite(), hi.is_finite()) {
            (true, true) => ConstForm::Bounded(lo, hi),
            (true, false) => ConstForm::AtLeast(lo),
            (false, true) => ConstForm::AtMost(hi),
            (false, false) => ConstForm::Entire,
        }
    }

    fn function(&self) -> Option<&'static str> {
        match self {
            ConstForm::Bounded(..) => None,
            ConstForm::AtLeast(_) => Some("i_at_least"),
            ConstForm::AtMost(_) => Some("i_at_most"),
            ConstForm::Entire => Some("i_entire"),
        }
    }

    fn write(&self, out: &mut String) {
        // Bounds here are finite, so `f32_literal` always answers.
        let lit = |v: f32| f32_literal(v).unwrap_or_else(|| "0.0f".into());
        let _ = match self {
            ConstForm::Bounded(lo, hi) => write!(out, "Interval({}, {})", lit(*lo), lit(*hi)),
            ConstForm::AtLeast(lo) => write!(out, "i_at_least({})", lit(*lo)),
            ConstForm::AtMost(hi) => write!(out, "i_at_most({})", lit(*hi)),
            ConstForm::Entire => write!(out, "i_entire()"),
        };
    }
}

/// An `i32` WGSL expression for `n` (`i32::MIN` has no literal: its magnitude overflows).
fn i32_expr(n: i32) -> String {
    if n == i32::MIN {
        "(-2147483647i - 1i)".into()
    } else {
        format!("{n}i")
    }
}

/// Writes the WGSL functions of one tape. See the [module documentation](self) for the
/// layout and the contract with the interval library.
#[derive(Clone, Debug)]
pub struct Generator {
    tape: Tape,
    name: String,
    inputs: Vec<String>,
}

impl Generator {
    /// A generator for `tape` whose interval function is called `name` (and the point
    /// function `name_point`), with the inputs `x, y, z`.
    ///
    /// Returns [`Error::Unsupported`] when `name` is not a usable WGSL identifier: not of the
    /// form `[A-Za-z_][A-Za-z0-9_]*`, `_`, starting with `__`, a keyword or reserved word, a
    /// predeclared name (`sin`, `f32`, ...), `Interval`, or starting with `i_` (the
    /// library's names).
    pub fn new(tape: &Tape, name: &str) -> Result<Self, Error> {
        check_name(name, "function name")?;
        for derived in [
            format!("{name}_point"),
            format!("{name}_out"),
            format!("{name}_point_out"),
        ] {
            check_name(&derived, "derived name")?;
        }
        Ok(Self {
            tape: tape.clone(),
            name: name.to_string(),
            inputs: vec!["x".into(), "y".into(), "z".into()],
        })
    }

    /// Gives the first `names.len()` variable slots arguments of their own, with these
    /// names; the remaining slots go to the array argument `p`.
    ///
    /// Returns [`Error::Unsupported`] when a name is not a usable WGSL identifier (as for
    /// [`Generator::new`]), appears twice, is `p`, has the form of a value name (`v`
    /// followed by a digit), or equals the function name or a struct name of this
    /// generator.
    pub fn with_inputs<S: AsRef<str>>(mut self, names: &[S]) -> Result<Self, Error> {
        let mut inputs: Vec<String> = Vec::with_capacity(names.len());
        for n in names {
            let n = n.as_ref();
            check_name(n, "input name")?;
            let taken = [
                self.name.clone(),
                self.point_name(),
                self.struct_name(),
                self.point_struct_name(),
                PARAMS_ARG.to_string(),
            ];
            if taken.iter().any(|t| t == n) {
                return Err(Error::Unsupported(format!(
                    "input name '{n}' is already used by the generated code"
                )));
            }
            if n.starts_with('v') && n[1..].starts_with(|c: char| c.is_ascii_digit()) {
                return Err(Error::Unsupported(format!(
                    "input name '{n}' has the form of a generated value name ('v' and a digit)"
                )));
            }
            if inputs.iter().any(|i| i == n) {
                return Err(Error::Unsupported(format!(
                    "input name '{n}' appears twice"
                )));
            }
            inputs.push(n.to_string());
        }
        self.inputs = inputs;
        Ok(self)
    }

    /// The name of the interval function.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The name of the point function: the name followed by `_point`.
    pub fn point_name(&self) -> String {
        format!("{}_point", self.name)
    }

    /// The struct the interval function returns when the tape has several outputs:
    /// the name followed by `_out`.
    pub fn struct_name(&self) -> String {
        format!("{}_out", self.name)
    }

    /// The struct the point function returns when the tape has several outputs: the name
    /// followed by `_point_out`.
    pub fn point_struct_name(&self) -> String {
        format!("{}_point_out", self.name)
    }

    /// The names of the inputs that are arguments of their own, in slot order.
    pub fn inputs(&self) -> &[String] {
        &self.inputs
    }

    /// The length `K` of the array argument `p` (0 when the function has none).
    pub fn param_count(&self) -> usize {
        let used = self
            .tape
            .ssa()
            .iter()
            .filter(|o| o.op == Opcode::Var)
            .map(|o| o.a as usize + 1)
            .max()
            .unwrap_or(0);
        self.tape
            .var_count()
            .max(used)
            .saturating_sub(self.inputs.len())
    }

    /// Number of outputs (fields of the output struct when more than one).
    pub fn output_count(&self) -> usize {
        self.tape.ssa_outputs().len()
    }

    /// The library functions the interval function calls, in [`LIBRARY`] order.
    pub fn required_functions(&self) -> Vec<&'static str> {
        required_functions(&self.tape)
    }

    /// The `xname(args)` argument list for one element type.
    fn arguments(&self, ty: &str) -> String {
        let mut args: Vec<String> = self.inputs.iter().map(|n| format!("{n}: {ty}")).collect();
        let k = self.param_count();
        if k > 0 {
            args.push(format!("{PARAMS_ARG}: array<{ty}, {k}>"));
        }
        args.join(", ")
    }

    /// The WGSL expression of variable slot `slot`.
    fn input(&self, slot: u32) -> String {
        let s = slot as usize;
        match self.inputs.get(s) {
            Some(n) => n.clone(),
            None => format!("{PARAMS_ARG}[{}]", s - self.inputs.len()),
        }
    }

    fn header(&self, out: &mut String, what: &str, ret: &str, ty: &str, fn_name: &str) {
        let ssa = self.tape.ssa();
        let _ = writeln!(
            out,
            "// {what} generated from a tape of {} operations with {} output(s).",
            ssa.len(),
            self.output_count()
        );
        if self.param_count() > 0 {
            let _ = writeln!(
                out,
                "// {PARAMS_ARG}[k] holds variable slot {} + k.",
                self.inputs.len()
            );
        }
        let outputs = self.output_count();
        let ret_ty = if outputs > 1 {
            let _ = write!(out, "struct {ret} {{");
            for i in 0..outputs {
                let sep = if i == 0 { " " } else { ", " };
                let _ = write!(out, "{sep}out{i}: {ty}");
            }
            let _ = writeln!(out, " }}");
            ret.to_string()
        } else {
            ty.to_string()
        };
        let _ = writeln!(out, "fn {fn_name}({}) -> {ret_ty} {{", self.arguments(ty));
    }

    fn footer(&self, out: &mut String, ret: &str) {
        let outputs = self.tape.ssa_outputs();
        if outputs.len() == 1 {
            let _ = writeln!(out, "    return v{};", outputs[0]);
        } else {
            let list: Vec<String> = outputs.iter().map(|o| format!("v{o}")).collect();
            let _ = writeln!(out, "    return {ret}({});", list.join(", "));
        }
        out.push_str("}\n");
    }

    /// The interval function (preceded by its output struct when the tape has several
    /// outputs). It needs the interval library; see the [module documentation](self).
    pub fn interval_source(&self) -> String {
        let ssa = self.tape.ssa();
        let consts = self.tape.consts();
        let mut out = String::with_capacity(64 * ssa.len() + 512);
        let ret = self.struct_name();
        let needs = self.required_functions();
        self.header(&mut out, "Interval function", &ret, "Interval", &self.name);
        if !needs.is_empty() {
            let _ = writeln!(out, "    // Library functions used: {}.", needs.join(", "));
        }
        for (i, op) in ssa.iter().enumerate() {
            let _ = write!(out, "    let v{i} = ");
            let _ = match op.op {
                Opcode::Var => write!(out, "{}", self.input(op.a)),
                Opcode::Const => match consts.get(op.a as usize) {
                    Some(c) => {
                        ConstForm::of(c).write(&mut out);
                        Ok(())
                    }
                    None => write!(out, "i_entire()"),
                },
                Opcode::Copy => write!(out, "v{}", op.a),
                Opcode::Unary(u) => write!(out, "{}(v{})", unary_function(u), op.a),
                Opcode::Binary(b) => {
                    write!(out, "{}(v{}, v{})", binary_function(b), op.a, op.b)
                }
                Opcode::Pown => {
                    write!(out, "{POWN_FUNCTION}(v{}, {})", op.a, i32_expr(op.b as i32))
                }
            };
            out.push_str(";\n");
        }
        self.footer(&mut out, &ret);
        out
    }

    /// The point function (preceded by its output struct when the tape has several
    /// outputs). It uses WGSL built-ins only.
    pub fn point_source(&self) -> String {
        let ssa = self.tape.ssa();
        let consts = self.tape.consts();
        let mut out = String::with_capacity(48 * ssa.len() + 512);
        let ret = self.point_struct_name();
        self.header(&mut out, "Point function", &ret, "f32", &self.point_name());
        let lit = |v: f32| f32_literal(v).unwrap_or_else(|| "0.0f".into());
        for (i, op) in ssa.iter().enumerate() {
            let a = format!("v{}", op.a);
            let expr = match op.op {
                Opcode::Var => self.input(op.a),
                Opcode::Const => {
                    let v = consts.get(op.a as usize).map_or(0.0, |c| c.value());
                    lit(literal::point_f32(v))
                }
                Opcode::Copy => a,
                Opcode::Unary(u) => point_unary(u, &a),
                Opcode::Binary(b) => {
                    let b_ = format!("v{}", op.b);
                    match b {
                        BinaryOp::Add => format!("{a} + {b_}"),
                        BinaryOp::Sub => format!("{a} - {b_}"),
                        BinaryOp::Mul => format!("{a} * {b_}"),
                        BinaryOp::Div => format!("{a} / {b_}"),
                        BinaryOp::Min => format!("min({a}, {b_})"),
                        BinaryOp::Max => format!("max({a}, {b_})"),
                        BinaryOp::Pow => format!("pow({a}, {b_})"),
                        // The largest f32 (no infinities in WGSL) where the domain test fails.
                        BinaryOp::Domain => format!("select({b_}, 0x1.fffffep+127f, {a} > 0.0)"),
                    }
                }
                Opcode::Pown => point_pown(&mut out, i, &a, op.b as i32),
            };
            let _ = writeln!(out, "    let v{i} = {expr};");
        }
        self.footer(&mut out, &ret);
        out
    }

    /// The interval function followed by the point function.
    pub fn source(&self) -> String {
        let mut s = self.interval_source();
        s.push('\n');
        s.push_str(&self.point_source());
        s
    }
}

/// The point expression of `op(a)`.
fn point_unary(op: UnaryOp, a: &str) -> String {
    match op {
        UnaryOp::Neg => format!("-{a}"),
        UnaryOp::Abs => format!("abs({a})"),
        UnaryOp::Sqr => format!("{a} * {a}"),
        UnaryOp::Sqrt => format!("sqrt({a})"),
        UnaryOp::Recip => format!("1.0f / {a}"),
        UnaryOp::Exp => format!("exp({a})"),
        UnaryOp::Ln => format!("log({a})"),
        UnaryOp::Log10 => {
            let k = f32_literal(std::f64::consts::LOG10_2 as f32).unwrap_or_default();
            format!("log2({a}) * {k}")
        }
        UnaryOp::Sin => format!("sin({a})"),
        UnaryOp::Cos => format!("cos({a})"),
        UnaryOp::Tan => format!("tan({a})"),
        UnaryOp::Asin => format!("asin({a})"),
        UnaryOp::Acos => format!("acos({a})"),
        UnaryOp::Atan => format!("atan({a})"),
        UnaryOp::Floor => format!("floor({a})"),
        UnaryOp::Ceil => format!("ceil({a})"),
        // Halves away from zero: a - trunc(a) is exact, so the test is exact.
        UnaryOp::Round => {
            format!("trunc({a}) + select(0.0f, sign({a}), abs({a} - trunc({a})) >= 0.5f)")
        }
        UnaryOp::Not => format!("select(0.0f, 1.0f, {a} == 0.0f)"),
        UnaryOp::SlopeFloor | UnaryOp::SlopeRound | UnaryOp::SlopeNot => "0.0f".into(),
    }
}

/// Writes the squarings of `a^n` as `let v{i}_k` lines and returns the expression of the
/// product (by repeated squaring: at most 32 squarings and 32 products).
fn point_pown(out: &mut String, i: usize, a: &str, n: i32) -> String {
    let mut m = n.unsigned_abs();
    if m == 0 {
        return "1.0f".into();
    }
    let mut factors: Vec<String> = Vec::new();
    let mut square = a.to_string();
    let mut k = 0;
    loop {
        if m & 1 == 1 {
            factors.push(square.clone());
        }
        m >>= 1;
        if m == 0 {
            break;
        }
        let next = format!("v{i}_{k}");
        let _ = writeln!(out, "    let {next} = {square} * {square};");
        square = next;
        k += 1;
    }
    let product = factors.join(" * ");
    if n < 0 {
        format!("1.0f / ({product})")
    } else {
        product
    }
}

/// Checks that `name` may be declared by the generated code.
fn check_name(name: &str, what: &str) -> Result<(), Error> {
    if let Some(problem) = ident::problem(name) {
        return Err(Error::Unsupported(format!("invalid {what}: {problem}")));
    }
    if name == "Interval" || name.starts_with("i_") {
        return Err(Error::Unsupported(format!(
            "invalid {what}: '{name}' belongs to the interval library ('Interval' and names \
             starting with 'i_')"
        )));
    }
    Ok(())
}

/// The library functions that the interval function of `tape` calls, in [`LIBRARY`] order.
pub fn required_functions(tape: &Tape) -> Vec<&'static str> {
    let mut used = vec![false; LIBRARY.len()];
    let mut mark = |name: &str| {
        if let Some(i) = LIBRARY_FUNCTIONS.iter().position(|n| *n == name) {
            used[i] = true;
        }
    };
    for op in tape.ssa() {
        match op.op {
            Opcode::Unary(u) => mark(function(Op::Unary(u))),
            Opcode::Binary(b) => mark(function(Op::Binary(b))),
            Opcode::Pown => mark(function(Op::Pown)),
            Opcode::Const => {
                let form = tape.consts().get(op.a as usize).map(ConstForm::of);
                match form {
                    Some(f) => {
                        if let Some(name) = f.function() {
                            mark(name);
                        }
                    }
                    None => mark("i_entire"),
                }
            }
            Opcode::Var | Opcode::Copy => {}
        }
    }
    LIBRARY_FUNCTIONS
        .iter()
        .zip(used)
        .filter(|(_, u)| *u)
        .map(|(n, _)| *n)
        .collect()
}

/// The interval function of `tape`, called `name`, with the inputs `x, y, z`
/// (shorthand for [`Generator::new`] and [`Generator::interval_source`]).
///
/// Returns an error when `name` is not a usable WGSL identifier.
pub fn interval_function(tape: &Tape, name: &str) -> Result<String, Error> {
    Ok(Generator::new(tape, name)?.interval_source())
}

/// The point function of `tape`, called `name_point`, with the inputs `x, y, z`
/// (shorthand for [`Generator::new`] and [`Generator::point_source`]).
///
/// Returns an error when `name` is not a usable WGSL identifier.
pub fn point_function(tape: &Tape, name: &str) -> Result<String, Error> {
    Ok(Generator::new(tape, name)?.point_source())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn library_tables_agree() {
        assert_eq!(LIBRARY.len(), Op::ALL.len() + 3);
        for (f, n) in LIBRARY.iter().zip(LIBRARY_FUNCTIONS) {
            assert_eq!(f.name, n);
            assert!(f.signature().starts_with(&format!("fn {n}(")));
            assert!(f.signature().ends_with(") -> Interval"));
        }
        for (op, f) in Op::ALL.into_iter().zip(LIBRARY) {
            assert_eq!(function(op), f.name, "{op}");
        }
        let mut names = LIBRARY_FUNCTIONS.to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(
            names.len(),
            LIBRARY.len(),
            "every function has a name of its own"
        );
        assert_eq!(
            LIBRARY[0].signature(),
            "fn i_add(a: Interval, b: Interval) -> Interval"
        );
        let pown = LIBRARY.iter().find(|f| f.name == "i_pown").unwrap();
        assert_eq!(
            pown.signature(),
            "fn i_pown(a: Interval, n: i32) -> Interval"
        );
        assert_eq!(
            LIBRARY.last().unwrap().signature(),
            "fn i_at_most(hi: f32) -> Interval"
        );
    }

    #[test]
    fn i32_expressions() {
        assert_eq!(i32_expr(3), "3i");
        assert_eq!(i32_expr(-3), "-3i");
        assert_eq!(i32_expr(i32::MIN), "(-2147483647i - 1i)");
    }
}
