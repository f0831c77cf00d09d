//! Proptest strategies (the `proptest` cargo feature): random expressions in `x`, `y`, `z`
//! over every operation of the crate, and random regions with points inside, for property
//! tests of code that evaluates formulas.
//!
//! ```
//! use implicit_expr::testing::strategy::{expression, region_and_point};
//! use implicit_expr::testing::{CheckError, check_sound};
//! use proptest::prelude::*;
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::default();
//! runner
//!     .run(&(expression(), region_and_point::<f64>(3)), |(e, (region, point))| {
//!         let tape = e.tape();
//!         match check_sound(&tape, &region, &point) {
//!             Err(e @ CheckError::Unsound { .. }) => Err(TestCaseError::fail(e.to_string())),
//!             _ => Ok(()),
//!         }
//!     })
//!     .unwrap();
//! ```
//!
//! Expressions are built through the [`Context`] API, so they are what a parser would
//! give: constants folded, equal subexpressions shared. Their [`Debug`](std::fmt::Debug)
//! form is the formula, so a failing case reads as text.

use std::fmt;

use interval_core::testing::strategy as core_strategy;
use interval_core::{Float, Interval};
use proptest::prelude::*;

use crate::constant::Constant;
use crate::context::{Context, NodeId, Var};
use crate::op::{BinaryOp, UnaryOp};
use crate::print::to_formula;
use crate::tape::Tape;

/// A random expression in `x`, `y`, `z` (variable slots 0, 1, 2).
#[derive(Clone)]
pub struct Expression {
    context: Context,
    root: NodeId,
}

impl Expression {
    /// The graph holding the expression.
    pub fn context(&self) -> &Context {
        &self.context
    }

    /// The expression's node.
    pub fn root(&self) -> NodeId {
        self.root
    }

    /// The expression compiled to a tape with one output.
    pub fn tape(&self) -> Tape {
        Tape::new(&self.context, &[self.root]).expect("a graph in x, y, z compiles")
    }

    /// The expression as a formula the parser reads back.
    pub fn formula(&self) -> String {
        to_formula(&self.context, self.root)
    }
}

impl fmt::Debug for Expression {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.formula())
    }
}

/// Which expressions [`expression_with`] builds.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct ExpressionOptions {
    /// The most operations an expression has (at least 1).
    pub max_operations: usize,
    /// Whether partial operations appear: `sqrt`, `ln`, `log`, `/`, `1/x`, `tan`, `asin`,
    /// `acos`, `pow`, negative integer powers and `domain`. Without them every expression
    /// is defined everywhere.
    pub partial: bool,
    /// Whether step functions appear (`floor`, `ceil`, `round`, `not` and their slopes).
    /// Without them (and without partial operations) every expression is continuous.
    pub discontinuous: bool,
}

impl Default for ExpressionOptions {
    /// Up to 16 operations of every kind.
    fn default() -> Self {
        Self {
            max_operations: 16,
            partial: true,
            discontinuous: true,
        }
    }
}

impl ExpressionOptions {
    /// Only the operations defined and continuous on the whole line (`+ − ×`, `min`,
    /// `max`, `abs`, squares and non-negative powers, `exp`, `sin`, `cos`, `atan`).
    pub fn total_and_continuous() -> Self {
        Self {
            partial: false,
            discontinuous: false,
            ..Self::default()
        }
    }

    fn unary_ops(&self) -> Vec<UnaryOp> {
        UnaryOp::ALL
            .into_iter()
            .filter(|op| {
                (self.partial || op.is_total()) && (self.discontinuous || !op.is_discontinuous())
            })
            .collect()
    }

    fn binary_ops(&self) -> Vec<BinaryOp> {
        BinaryOp::ALL
            .into_iter()
            .filter(|op| self.partial || op.is_total())
            .collect()
    }
}

/// Literals of the constants: exact ones, and ones no double represents.
const DECIMALS: [&str; 10] = ["0", "0.5", "1", "2", "3", "10", "0.1", "0.3", "1.7", "1e-3"];

/// A leaf of a recipe.
#[derive(Clone, Debug)]
enum Leaf {
    Var(u32),
    Decimal(&'static str),
    Pi,
}

/// An operation of a recipe on earlier nodes, chosen by [`pick`].
#[derive(Clone, Debug)]
enum Step {
    Unary(UnaryOp, usize),
    Binary(BinaryOp, usize, usize),
    Pown(usize, i32),
}

fn leaf() -> impl Strategy<Value = Leaf> {
    prop_oneof![
        6 => (0u32..3).prop_map(Leaf::Var),
        3 => prop::sample::select(DECIMALS.to_vec()).prop_map(Leaf::Decimal),
        1 => Just(Leaf::Pi),
    ]
}

/// The node an argument code `a` selects among `k` earlier nodes: often the newest (deep
/// expressions), else one of the three newest, sometimes any (shared subexpressions).
fn pick(a: usize, k: usize) -> usize {
    match a % 10 {
        0..5 => k - 1,
        5..8 => k - 1 - (a / 10) % k.min(3),
        _ => (a / 10) % k,
    }
}

/// Random expressions with up to 16 operations of every kind
/// ([`ExpressionOptions::default`]).
pub fn expression() -> BoxedStrategy<Expression> {
    expression_with(ExpressionOptions::default())
}

/// Random expressions as `options` say.
pub fn expression_with(options: ExpressionOptions) -> BoxedStrategy<Expression> {
    let unary = options.unary_ops();
    let binary = options.binary_ops();
    let min_power = if options.partial { -3 } else { 0 };
    let step = prop_oneof![
        4 => (prop::sample::select(unary), any::<usize>()).prop_map(|(op, a)| Step::Unary(op, a)),
        5 => (prop::sample::select(binary), any::<usize>(), any::<usize>())
            .prop_map(|(op, a, b)| Step::Binary(op, a, b)),
        1 => (any::<usize>(), min_power..=5i32).prop_map(|(a, n)| Step::Pown(a, n)),
    ];
    (
        prop::collection::vec(leaf(), 1..5),
        prop::collection::vec(step, 1..=options.max_operations.max(1)),
    )
        .prop_map(|(leaves, steps)| build(&leaves, &steps))
        .boxed()
}

/// The expression of a recipe: its leaves, then each step on earlier nodes; the last node is
/// the root.
fn build(leaves: &[Leaf], steps: &[Step]) -> Expression {
    let mut context = Context::new();
    let mut nodes: Vec<NodeId> = Vec::with_capacity(leaves.len() + steps.len());
    for l in leaves {
        nodes.push(match l {
            Leaf::Var(i) => context.var(Var(*i)).expect("x, y and z are declared"),
            Leaf::Decimal(s) => {
                context.constant_enclosed(Constant::from_decimal(s).expect("a decimal literal"))
            }
            Leaf::Pi => context.constant_enclosed(Constant::pi()),
        });
    }
    for s in steps {
        let k = nodes.len();
        let n = match *s {
            Step::Unary(op, a) => context.unary(op, nodes[pick(a, k)]),
            Step::Binary(op, a, b) => context.binary(op, nodes[pick(a, k)], nodes[pick(b, k)]),
            Step::Pown(a, n) => context.pown(nodes[pick(a, k)], n),
        };
        nodes.push(n);
    }
    let root = *nodes.last().expect("at least one leaf");
    Expression { context, root }
}

/// A coordinate interval: mostly moderate (a point, a few ulps, a general interval in
/// `[-4, 4]` with integer ends often, one around zero), sometimes any bounded interval of
/// interval-core's strategies (huge, tiny and subnormal bounds).
fn coordinate<T: Float>() -> BoxedStrategy<Interval<T>> {
    let moderate = prop_oneof![
        3 => (-4i32..=4).prop_map(f64::from),
        4 => -4.0..4.0f64,
        1 => -1e-6..1e-6f64,
    ];
    let outward = |a: f64, b: f64| {
        let (a, b) = (a.min(b), a.max(b));
        Interval::new_unchecked(T::from_f64_down(a), T::from_f64_up(b))
    };
    prop_oneof![
        2 => moderate.clone().prop_map(move |v| outward(v, v)),
        4 => (moderate.clone(), moderate).prop_map(move |(a, b)| outward(a, b)),
        2 => (0.0..3.0f64, 0.0..3.0f64).prop_map(move |(a, b)| outward(-a, b)),
        2 => core_strategy::bounded_interval::<T>(),
    ]
    .boxed()
}

/// Regions of `vars` coordinates: nonempty bounded boxes (see the module's intervals).
pub fn region<T: Float>(vars: usize) -> BoxedStrategy<Vec<Interval<T>>> {
    prop::collection::vec(coordinate::<T>(), vars).boxed()
}

/// A [`region`] and a point inside it (its corners and interior points).
pub fn region_and_point<T: Float>(vars: usize) -> BoxedStrategy<(Vec<Interval<T>>, Vec<T>)> {
    region::<T>(vars)
        .prop_flat_map(|r| {
            let points: Vec<_> = r.iter().map(|&x| core_strategy::point_in(x)).collect();
            (Just(r), points)
        })
        .boxed()
}
