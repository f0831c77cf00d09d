//! What the generators of `.vm` models share: a seeded random generator whose output is
//! fixed by its definition ([`SplitMix64`]), a writer of `.vm` lines ([`VmWriter`]) with the
//! operations and the shape helpers that every dimension uses, and counts of a `.vm` text's
//! operations ([`op_count`], [`op_histogram`]).
//!
//! The `.vm` format has one operation per line, `name opcode args...`, the last line being
//! the output. The writer names lines `_0`, `_1`, ... (hexadecimal), writes every constant
//! with four decimals (or as many as asked) on a line of its own, shared between the uses
//! of the same printed value, and starts with `var-x` and `var-y` (and `var-z` for a 3D
//! model), after the header comments. Every number comes from a [`SplitMix64`] seeded by the caller, so a
//! model's text is the same on every machine and every version.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;

/// SplitMix64: a tiny generator whose output is fixed by its definition, not by a crate
/// version (the committed models must stay reproducible).
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// The generator seeded with `seed`.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let u = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// `true` with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.range(0.0, 1.0) < p
    }

    /// The elements of `0..n` in a random order (Fisher-Yates).
    pub fn permutation(&mut self, n: usize) -> Vec<usize> {
        let mut v: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = self.below(i + 1);
            v.swap(i, j);
        }
        v
    }
}

/// A value of the expression being written: the number of its line.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Val(usize);

/// A point of a [`VmWriter`]'s text to come back to with [`VmWriter::rewind`].
#[derive(Copy, Clone, Debug)]
pub struct Mark {
    text: usize,
    lines: usize,
}

/// Writes `.vm` lines; constants are shared by their printed value.
#[derive(Clone, Debug)]
pub struct VmWriter {
    text: String,
    lines: usize,
    consts: HashMap<String, Val>,
    /// Operations already written, by their text, when they are shared
    /// ([`VmWriter::share_operations`]).
    ops_written: Option<HashMap<String, Val>>,
    /// Decimals of the constants.
    decimals: usize,
    x: Val,
    y: Val,
    z: Option<Val>,
}

impl VmWriter {
    /// A writer of a planar model in `x` and `y`: the `header` lines as `#` comments, then
    /// `var-x` and `var-y`.
    pub fn new_2d(header: &[String]) -> Self {
        Self::with_vars(header, false)
    }

    /// A writer of a model in `x`, `y` and `z`: the `header` lines as `#` comments, then
    /// `var-x`, `var-y` and `var-z`.
    pub fn new_3d(header: &[String]) -> Self {
        Self::with_vars(header, true)
    }

    fn with_vars(header: &[String], z: bool) -> Self {
        let mut w = Self {
            text: String::new(),
            lines: 0,
            consts: HashMap::new(),
            ops_written: None,
            decimals: 4,
            x: Val(0),
            y: Val(0),
            z: None,
        };
        for h in header {
            let _ = writeln!(w.text, "# {h}");
        }
        w.x = w.line("var-x".into());
        w.y = w.line("var-y".into());
        if z {
            w.z = Some(w.line("var-z".into()));
        }
        w
    }

    /// From now on, an operation written again with the same arguments returns the line
    /// written the first time (as a compiler's common subexpression elimination would),
    /// like constants.
    pub fn share_operations(mut self) -> Self {
        self.ops_written = Some(HashMap::new());
        self
    }

    /// From now on, constants are written with `decimals` decimals instead of four.
    pub fn with_decimals(mut self, decimals: usize) -> Self {
        self.decimals = decimals;
        self
    }

    /// The variable `x`.
    pub fn x(&self) -> Val {
        self.x
    }

    /// The variable `y`.
    pub fn y(&self) -> Val {
        self.y
    }

    /// The variable `z`.
    ///
    /// # Panics
    ///
    /// On a planar writer ([`VmWriter::new_2d`]), which has no `z`.
    pub fn z(&self) -> Val {
        self.z.expect("a 3D writer (VmWriter::new_3d) has z")
    }

    /// The variables `[x, y, z]` of a 3D writer (see [`VmWriter::z`]).
    pub fn xyz(&self) -> [Val; 3] {
        [self.x, self.y, self.z()]
    }

    /// Operations written so far: lines other than constants (the variables count).
    pub fn ops(&self) -> usize {
        self.lines - self.consts.len()
    }

    /// The text written so far.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// The finished text; its last line is the output.
    pub fn finish(self) -> String {
        self.text
    }

    /// The current end of the text.
    pub fn mark(&self) -> Mark {
        Mark {
            text: self.text.len(),
            lines: self.lines,
        }
    }

    /// Removes every line written after `m` (constants included).
    pub fn rewind(&mut self, m: Mark) {
        self.text.truncate(m.text);
        self.lines = m.lines;
        self.consts.retain(|_, v| v.0 < m.lines);
        if let Some(ops) = &mut self.ops_written {
            ops.retain(|_, v| v.0 < m.lines);
        }
    }

    fn line(&mut self, body: String) -> Val {
        let v = Val(self.lines);
        let _ = writeln!(self.text, "_{:x} {body}", v.0);
        self.lines += 1;
        v
    }

    /// The constant `value`, written with four decimals (or those set by
    /// [`VmWriter::with_decimals`]; `-0.0000` as `0.0000`) on a line of its own the first
    /// time it is used.
    pub fn c(&mut self, value: f64) -> Val {
        let mut s = format!("{value:.*}", self.decimals);
        if let Some(zero) = s.strip_prefix('-')
            && zero.bytes().all(|b| b == b'0' || b == b'.')
        {
            s = zero.to_string();
        }
        if let Some(&v) = self.consts.get(&s) {
            return v;
        }
        let v = self.line(format!("const {s}"));
        self.consts.insert(s, v);
        v
    }

    /// The line of the operation `body`, written unless it is shared and already there.
    fn op(&mut self, body: String) -> Val {
        let Some(ops) = &self.ops_written else {
            return self.line(body);
        };
        if let Some(&v) = ops.get(&body) {
            return v;
        }
        let v = self.line(body.clone());
        if let Some(ops) = &mut self.ops_written {
            ops.insert(body, v);
        }
        v
    }

    /// The unary operation `op` (a `.vm` opcode) of `a`.
    pub fn un(&mut self, op: &str, a: Val) -> Val {
        self.op(format!("{op} _{:x}", a.0))
    }

    /// The binary operation `op` (a `.vm` opcode) of `a` and `b`.
    pub fn bin(&mut self, op: &str, a: Val, b: Val) -> Val {
        self.op(format!("{op} _{:x} _{:x}", a.0, b.0))
    }

    /// `a + b`.
    pub fn add(&mut self, a: Val, b: Val) -> Val {
        self.bin("add", a, b)
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Val, b: Val) -> Val {
        self.bin("sub", a, b)
    }

    /// `a · b`.
    pub fn mul(&mut self, a: Val, b: Val) -> Val {
        self.bin("mul", a, b)
    }

    /// `min(a, b)`: the union of two solids.
    pub fn min(&mut self, a: Val, b: Val) -> Val {
        self.bin("min", a, b)
    }

    /// `max(a, b)`: the intersection of two solids.
    pub fn max(&mut self, a: Val, b: Val) -> Val {
        self.bin("max", a, b)
    }

    /// `-a`.
    pub fn neg(&mut self, a: Val) -> Val {
        self.un("neg", a)
    }

    /// `|a|`.
    pub fn abs(&mut self, a: Val) -> Val {
        self.un("abs", a)
    }

    /// `max(a, -b)`: the solid `a` with `b` cut out.
    pub fn difference(&mut self, a: Val, b: Val) -> Val {
        let nb = self.neg(b);
        self.max(a, nb)
    }

    /// `v - c`.
    pub fn offset(&mut self, v: Val, c: f64) -> Val {
        let c = self.c(c);
        self.sub(v, c)
    }

    /// The Euclidean length `sqrt(a² + b² + ...)` of `parts` (squares first, then the sums
    /// from the left, then the root).
    pub fn length(&mut self, parts: &[Val]) -> Val {
        let squares: Vec<Val> = parts.iter().map(|&p| self.un("square", p)).collect();
        let mut sum = squares[0];
        for &s in &squares[1..] {
            sum = self.add(sum, s);
        }
        self.un("sqrt", sum)
    }

    /// `vs` combined by `op` (`min` or `max`) from the left: `op(op(op(a, b), c), d)`;
    /// `None` for no value.
    pub fn reduce_left(&mut self, op: &str, vs: &[Val]) -> Option<Val> {
        let (&first, rest) = vs.split_first()?;
        Some(rest.iter().fold(first, |acc, &v| self.bin(op, acc, v)))
    }

    /// `vs` combined by `op` (`min` or `max`) as a balanced tree: `op(op(a, b), op(c, d))`;
    /// `None` for no value.
    pub fn reduce(&mut self, op: &str, vs: &[Val]) -> Option<Val> {
        match vs {
            [] => None,
            [v] => Some(*v),
            _ => {
                let (l, r) = vs.split_at(vs.len() / 2);
                let l = self.reduce(op, l)?;
                let r = self.reduce(op, r)?;
                Some(self.bin(op, l, r))
            }
        }
    }
}

/// Number of operations of a `.vm` text: lines that are neither comments, blank, nor
/// constants (the variables count).
pub fn op_count(text: &str) -> usize {
    op_histogram(text)
        .iter()
        .filter(|(op, _)| op.as_str() != "const")
        .map(|(_, n)| n)
        .sum()
}

/// How many lines of a `.vm` text use each opcode (constants and variables included),
/// by opcode.
pub fn op_histogram(text: &str) -> BTreeMap<String, usize> {
    let mut h = BTreeMap::new();
    for l in text.lines() {
        let l = l.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        if let Some(op) = l.split_whitespace().nth(1) {
            *h.entry(op.to_string()).or_insert(0) += 1;
        }
    }
    h
}

/// How many points of an `n`-point-per-axis grid of `[-1, 1]²` (`z = 0`) or `[-1, 1]³`
/// (`three_d`) are inside (`f < 0`) and outside (`f > 0`) the model of `text`: a model
/// whose surface crosses `[-1, 1]ⁿ` has both. Points are cell centres.
///
/// # Errors
///
/// The importer's error for text it rejects.
pub fn sign_counts(
    text: &str,
    n: usize,
    three_d: bool,
) -> Result<(usize, usize), implicit_expr::Error> {
    let mut ctx = implicit_expr::Context::new();
    let root = implicit_expr::vm::import_vm(&mut ctx, text)?;
    let tape = implicit_expr::Tape::new(&ctx, &[root])?;
    let mut eval = implicit_expr::Evaluator::<f64>::new(&tape);
    let at = |i: usize| -1.0 + (2 * i + 1) as f64 / n as f64;
    let (mut inside, mut outside) = (0, 0);
    for k in 0..if three_d { n } else { 1 } {
        let z = if three_d { at(k) } else { 0.0 };
        for j in 0..n {
            for i in 0..n {
                let f = eval.eval(&[at(i), at(j), z])?;
                if f < 0.0 {
                    inside += 1;
                } else if f > 0.0 {
                    outside += 1;
                }
            }
        }
    }
    Ok((inside, outside))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writer_counts_and_rewinds() {
        let mut w = VmWriter::new_3d(&["test".into()]);
        assert_eq!(w.ops(), 3);
        let [x, y, z] = w.xyz();
        let d = w.length(&[x, y, z]);
        let m = w.mark();
        let before = w.text().to_string();
        let one = w.c(1.0);
        let s = w.sub(d, one);
        assert_eq!(w.ops(), 3 + 6 + 1);
        w.rewind(m);
        assert_eq!(w.text(), before);
        // The constant went with the rewind: it is written again.
        let one_again = w.c(1.0);
        assert_eq!(one_again, one);
        w.sub(d, one_again);
        assert_eq!(s, Val(w.lines - 1));
        let text = w.finish();
        assert!(text.starts_with("# test\n_0 var-x\n_1 var-y\n_2 var-z\n"));
        assert_eq!(op_count(&text), 10);
        let h = op_histogram(&text);
        assert_eq!(h["square"], 3);
        assert_eq!(h["const"], 1);
    }

    #[test]
    fn balanced_reduce() {
        let mut w = VmWriter::new_2d(&[]);
        let vs: Vec<Val> = (0..5).map(|i| w.c(f64::from(i))).collect();
        let ops = w.ops();
        assert!(w.reduce("min", &vs).is_some());
        assert_eq!(w.ops(), ops + 4);
        assert_eq!(w.reduce("min", &[]), None);
    }

    #[test]
    fn permutation_is_one() {
        let mut p = SplitMix64::new(3).permutation(50);
        p.sort_unstable();
        assert_eq!(p, (0..50).collect::<Vec<_>>());
    }
}
