//! The forward-mode gradient of a polynomial tape as a tape of its own: the operations the
//! gradient evaluator ([`Grad`](crate::Grad)) makes at run time, written out once, so that
//! an interval evaluation of the new tape gives the gradient evaluator's enclosures and,
//! having only operations the code generator has, runs as machine code ([`crate::jit`]).
//!
//! Each value of the tape carries its three partial derivatives by the variable slots 0, 1
//! and 2, each known to be 0, known to be 1, or held in a register. The rules are the
//! gradient evaluator's, operation for operation, with its zeros and ones left out where
//! they are structural (a sum with 0, a product with 1: exact either way):
//!
//! | value | derivative |
//! |---|---|
//! | `-a` | `(-1)·a'`, written `-a'` (exact) |
//! | `a²` | `(2·a)·a'` |
//! | `a ± b` | `a' ± b'` |
//! | `a·b` | `a·b' + b·a'` |
//!
//! A tape with any other operation (`min`, `max`, `abs`, roots, quotients, powers, the
//! elementary functions, whose derivatives select a branch or divide) has no such tape.

use super::{Opcode, SsaOp, Tape};
use crate::constant::Constant;
use crate::number::Choice;
use crate::op::{BinaryOp, UnaryOp};

/// A partial derivative while the tape is written: structurally 0 or 1, or the SSA
/// position of its value.
#[derive(Copy, Clone, Debug, PartialEq)]
enum D {
    Zero,
    One,
    At(u32),
}

/// The SSA list of the gradient tape being written, with its constants.
struct Writer {
    ssa: Vec<SsaOp>,
    consts: Vec<Constant>,
    /// The positions of the constants 0, 1, 2 and −1 once written.
    small: [Option<u32>; 4],
}

impl Writer {
    fn push(&mut self, op: Opcode, a: u32, b: u32) -> u32 {
        self.ssa.push(SsaOp { op, a, b });
        (self.ssa.len() - 1) as u32
    }

    /// The position of the small constant `k` (0, 1, 2 or −1).
    fn constant(&mut self, k: usize) -> u32 {
        if let Some(p) = self.small[k] {
            return p;
        }
        let value = [0.0, 1.0, 2.0, -1.0][k];
        self.consts
            .push(Constant::exact(value).expect("a small integer is exact"));
        let p = self.push(Opcode::Const, (self.consts.len() - 1) as u32, 0);
        self.small[k] = Some(p);
        p
    }

    /// The position of `d`'s value.
    fn at(&mut self, d: D) -> u32 {
        match d {
            D::Zero => self.constant(0),
            D::One => self.constant(1),
            D::At(p) => p,
        }
    }

    /// `s · d` where `s` is the value at position `s`: the gradient evaluator's `scale`.
    fn scale(&mut self, s: u32, d: D) -> D {
        match d {
            D::Zero => D::Zero,
            D::One => D::At(s),
            D::At(p) => D::At(self.push(Opcode::Binary(BinaryOp::Mul), s, p)),
        }
    }

    /// `a + b`, or `a − b` where `sub`.
    fn sum(&mut self, a: D, b: D, sub: bool) -> D {
        match (a, b, sub) {
            (a, D::Zero, _) => a,
            (D::Zero, b, false) => b,
            (D::Zero, D::One, true) => D::At(self.constant(3)),
            (D::Zero, D::At(p), true) => D::At(self.push(Opcode::Unary(UnaryOp::Neg), p, 0)),
            (a, b, sub) => {
                let (pa, pb) = (self.at(a), self.at(b));
                let op = if sub { BinaryOp::Sub } else { BinaryOp::Add };
                D::At(self.push(Opcode::Binary(op), pa, pb))
            }
        }
    }
}

impl Tape {
    /// The gradient of the tape's first output by the variable slots 0, 1 and 2 as a tape
    /// with those three partial derivatives as its outputs, where every operation of this
    /// tape is a variable, a constant, a copy, `-a`, `a²`, `a + b`, `a − b` or `a · b` (a
    /// polynomial); `None` otherwise.
    ///
    /// Its interval evaluation makes the operations that [`Grad`](crate::Grad)'s makes
    /// (`Evaluator<Grad<Interval<f64>>>` over the same box, the slots 0 to 2 its variables,
    /// the others constants), less those with a structural 0 or 1, which change nothing: the
    /// same enclosures of the partial derivatives, up to the sign of a zero bound, wherever
    /// the values are not empty (where one is, the gradient evaluator's components that
    /// are structurally 0 are empty, the tape's `[0, 0]`; a polynomial over a bounded box
    /// has no empty value). Every
    /// operation of it is one the code generator has ([`Tape::has_code_ops`]), so on a
    /// platform with the generator it runs as machine code once compiled.
    pub fn gradient_tape(&self) -> Option<Tape> {
        let src = self.ssa();
        let mut w = Writer {
            ssa: Vec::with_capacity(4 * src.len()),
            consts: self.consts().to_vec(),
            small: [None; 4],
        };
        // Each source position's value position and derivatives.
        let mut value: Vec<u32> = Vec::with_capacity(src.len());
        let mut grad: Vec<[D; 3]> = Vec::with_capacity(src.len());
        for op in src {
            let (a, b) = (op.a as usize, op.b as usize);
            let (v, d) = match op.op {
                Opcode::Var => {
                    let mut d = [D::Zero; 3];
                    if let Some(slot) = d.get_mut(op.a as usize) {
                        *slot = D::One;
                    }
                    (w.push(Opcode::Var, op.a, 0), d)
                }
                Opcode::Const => (w.push(Opcode::Const, op.a, 0), [D::Zero; 3]),
                Opcode::Copy => (value[a], grad[a]),
                Opcode::Unary(UnaryOp::Neg) => {
                    let v = w.push(op.op, value[a], 0);
                    (v, grad[a].map(|d| w.sum(D::Zero, d, true)))
                }
                Opcode::Unary(UnaryOp::Sqr) => {
                    let v = w.push(op.op, value[a], 0);
                    let da = grad[a];
                    if da == [D::Zero; 3] {
                        (v, da)
                    } else {
                        let two = w.constant(2);
                        let slope = w.push(Opcode::Binary(BinaryOp::Mul), two, value[a]);
                        (v, da.map(|d| w.scale(slope, d)))
                    }
                }
                Opcode::Binary(op @ (BinaryOp::Add | BinaryOp::Sub)) => {
                    let v = w.push(Opcode::Binary(op), value[a], value[b]);
                    let sub = op == BinaryOp::Sub;
                    let d = std::array::from_fn(|i| w.sum(grad[a][i], grad[b][i], sub));
                    (v, d)
                }
                Opcode::Binary(BinaryOp::Mul) => {
                    let v = w.push(op.op, value[a], value[b]);
                    let d = std::array::from_fn(|i| {
                        let left = w.scale(value[a], grad[b][i]);
                        let right = w.scale(value[b], grad[a][i]);
                        w.sum(left, right, false)
                    });
                    (v, d)
                }
                _ => return None,
            };
            value.push(v);
            grad.push(d);
        }
        let out = grad[*self.ssa_outputs().first()? as usize];
        let outputs: Vec<u32> = out.iter().map(|&d| w.at(d)).collect();
        Some(Tape::compiled(
            &w.ssa,
            &w.consts,
            &outputs,
            self.var_count() as u32,
            |_| Choice::Both,
        ))
    }
}

#[cfg(test)]
mod tests {
    use interval_core::Interval;
    use proptest::prelude::*;

    use crate::context::Context;
    use crate::eval::Evaluator;
    use crate::{Grad, Tape};

    fn tape(formula: &str) -> Tape {
        let mut ctx = Context::new();
        let root = crate::parse::parse(&mut ctx, formula, &[]).expect("parses");
        Tape::new(&ctx, &[root]).expect("compiles")
    }

    /// The gradient evaluator's enclosures and the gradient tape's, over `b`.
    fn both(t: &Tape, b: [Interval<f64>; 3]) -> ([Interval<f64>; 3], [Interval<f64>; 3]) {
        let vars: Vec<Grad<Interval<f64>>> = (0..t.var_count())
            .map(|i| match b.get(i) {
                Some(&x) => Grad::var(x, i),
                None => Grad::constant_value(Interval::ZERO),
            })
            .collect();
        let want = Evaluator::<Grad<Interval<f64>>>::new(t)
            .eval(&vars)
            .unwrap()
            .d;
        let g = t.gradient_tape().expect("a polynomial");
        // Compiled at once, where the platform has the code generator.
        g.expect_reuse();
        let mut got = [Interval::EMPTY; 3];
        let plain: Vec<Interval<f64>> = (0..t.var_count().max(g.var_count()))
            .map(|i| b.get(i).copied().unwrap_or(Interval::ZERO))
            .collect();
        Evaluator::<Interval<f64>>::new(&g)
            .eval_outputs(&plain, &mut got)
            .unwrap();
        (want, got)
    }

    fn box3() -> impl Strategy<Value = [Interval<f64>; 3]> {
        let iv = (-3.0f64..3.0, 0.0f64..2.0)
            .prop_map(|(lo, w)| Interval::new(lo, lo + w).expect("ordered"));
        [iv.clone(), iv.clone(), iv]
    }

    proptest! {
        /// On polynomials of the catalog's kind (a torus, a quartic with products and
        /// differences, constants not exact in binary), the gradient tape gives the
        /// gradient evaluator's enclosures.
        #[test]
        fn the_gradient_tape_is_the_gradient_evaluator(b in box3()) {
            for f in [
                "(x^2 + y^2 + z^2 + 0.4275)^2 - 1.96 * (x^2 + y^2)",
                "x*y*z - 0.3*(x - y)^2 + -(z^2) * 1.7 - 2.1",
                "(x - 0.1) * (y + 0.2) * (x*x - z)",
                "y + 1.25",
            ] {
                let (want, got) = both(&tape(f), b);
                prop_assert_eq!(want, got, "{}", f);
            }
        }
    }

    /// The tape has the operations the code generator has, and a formula with any other
    /// has no gradient tape.
    #[test]
    fn only_polynomials_have_one() {
        let g = tape("(x^2 + y^2 + z^2 + 0.4275)^2 - 1.96 * (x^2 + y^2)")
            .gradient_tape()
            .expect("a polynomial");
        assert!(g.has_code_ops());
        assert_eq!(g.outputs().len(), 3);
        for f in [
            "sqrt(x^2 + y^2) - 1",
            "min(x, y)",
            "abs(x) - y",
            "x / y",
            "x^3 - y",
        ] {
            assert!(tape(f).gradient_tape().is_none(), "{f}");
        }
    }

    /// A constant gradient (a plane) and a variable not differentiated (slot 3).
    #[test]
    fn constant_and_absent_derivatives() {
        let (want, got) = both(&tape("y + 1.25"), [Interval::new(0.0, 1.0).unwrap(); 3]);
        assert_eq!(want, got);
        assert_eq!(got[1], Interval::ONE);
        assert_eq!(got[0], Interval::ZERO);
    }
}
