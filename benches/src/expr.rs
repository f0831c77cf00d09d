//! The expression benchmarks' shared workloads: expressions built both as our
//! [`Tape`] and as fidget shapes, the same points and boxes for both, and one function per
//! (engine, evaluation mode) that runs a whole workload, so that the criterion benchmarks
//! (`benches/expr_eval.rs`) and the `expr_report` binary time exactly the same code.
//!
//! Both sides get the same expression: a `.vm` text is read by our importer and by fidget's
//! `Context::from_text`; a formula is parsed by our parser and its graph rebuilt node by
//! node in a fidget context ([`to_fidget`]). Inputs are `f32` values (exact in `f64`), drawn
//! from a seeded generator. The comparison is like for like in precision: our `f32` point
//! and `Interval<f32>` evaluators against fidget's (whose intervals are `f32` with
//! round-to-nearest bounds, not sound); our `f64` evaluators are timed as well.

use std::hint::black_box;

use fidget::context::Node as FNode;
use fidget::eval::{BulkEvaluator, Function, MathFunction, TracingEvaluator};
use fidget::jit::JitFunction;
use fidget::var::Var as FVar;
use fidget::vm::VmFunction;
use implicit_expr::{
    BinaryOp, Context, Error, Evaluator, Node, NodeId, SliceEvaluator, Tape, UnaryOp,
};
use interval_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// The `.vm` text of the generated 2D CSG page (`data/models/csg2d.vm`).
pub const CSG2D_VM: &str = include_str!("../../data/models/csg2d.vm");

/// Number of points of a point workload.
pub const N_POINTS: usize = 4096;

/// Number of boxes of an interval workload.
pub const N_BOXES: usize = 1024;

/// Seed of the points and boxes.
pub const SEED: u64 = 0x5eed_f1d9;

/// A named expression, built for both libraries.
pub struct Expr {
    /// Short name (`sphere`, `csg2d`, ...).
    pub name: String,
    /// Whether the expression depends on `x` and `y` only (2D workloads use `z = 0`).
    pub planar: bool,
    /// Our graph.
    pub ctx: Context,
    /// Our root node.
    pub root: NodeId,
    /// Our compiled tape.
    pub tape: Tape,
    /// fidget's graph and root, or why the expression has no fidget equivalent.
    pub fidget: Result<(fidget::Context, FNode), String>,
}

impl Expr {
    /// An expression from formula text (parsed by our parser; fidget gets the same graph).
    ///
    /// Returns an error when the formula does not parse.
    pub fn from_formula(name: &str, text: &str) -> Result<Self, Error> {
        let mut ctx = Context::new();
        let root = implicit_expr::parse::parse(&mut ctx, text, &[])?;
        Self::from_graph(name, ctx, root)
    }

    /// An expression from `.vm` text, read by both importers.
    ///
    /// Returns an error when our importer rejects the text.
    pub fn from_vm(name: &str, text: &str) -> Result<Self, Error> {
        let mut ctx = Context::new();
        let root = import_vm(&mut ctx, text)?;
        let mut e = Self::from_graph(name, ctx, root)?;
        e.fidget = fidget::Context::from_text(text.as_bytes()).map_err(|err| err.to_string());
        Ok(e)
    }

    /// An expression from a graph of ours.
    ///
    /// Returns an error when the tape cannot be compiled.
    pub fn from_graph(name: &str, ctx: Context, root: NodeId) -> Result<Self, Error> {
        let tape = Tape::new(&ctx, &[root])?;
        let planar = !ctx
            .reachable(&[root])
            .iter()
            .any(|&id| matches!(ctx.get(id), Node::Var(v) if v.index() >= 2));
        let fidget = to_fidget(&ctx, root);
        Ok(Self {
            name: name.to_string(),
            planar,
            ctx,
            root,
            tape,
            fidget,
        })
    }

    /// fidget's VM function of the expression.
    pub fn fidget_vm(&self) -> Result<VmFunction, String> {
        let (ctx, root) = self.fidget.as_ref().map_err(Clone::clone)?;
        VmFunction::new(ctx, &[*root]).map_err(|e| e.to_string())
    }

    /// fidget's JIT function of the expression.
    pub fn fidget_jit(&self) -> Result<JitFunction, String> {
        let (ctx, root) = self.fidget.as_ref().map_err(Clone::clone)?;
        JitFunction::new(ctx, &[*root]).map_err(|e| e.to_string())
    }
}

/// Reads `.vm` text into `ctx` with our importer.
///
/// Returns the importer's error for text it rejects.
pub fn import_vm(ctx: &mut Context, text: &str) -> Result<NodeId, Error> {
    implicit_expr::vm::import_vm(ctx, text)
}

/// The expressions of the benchmarks: a sphere, three formulas, the generated 2D CSG page,
/// and any extra `.vm` files named by the caller (`(name, text)` pairs).
///
/// Returns an error when one of them cannot be built.
pub fn expressions(extra_vm: &[(String, String)]) -> Result<Vec<Expr>, Error> {
    let mut out = Vec::new();
    for (name, formula) in FORMULAS {
        out.push(Expr::from_formula(name, formula)?);
    }
    for name in CATALOG {
        out.push(catalog_expr(name)?);
    }
    out.push(Expr::from_vm("csg2d", CSG2D_VM)?);
    for (name, text) in extra_vm {
        out.push(Expr::from_vm(name, text)?);
    }
    Ok(out)
}

/// The catalog surfaces in the benchmarks (fidget can express them: no `log`, no real
/// powers); their parameters are bound to the catalog's values.
pub const CATALOG: [&str; 6] = [
    "chubs",
    "kusner-schmitt",
    "mcmullen-k3",
    "orthocircle",
    "barth-sextic",
    "tangle-cube",
];

/// The catalog surface `name` with its parameters bound to constants.
///
/// Returns an error for an unknown name or a formula that does not build.
pub fn catalog_expr(name: &str) -> Result<Expr, Error> {
    let surface = implicit_expr::catalog::get(name)?;
    let mut ctx = Context::new();
    let root = surface.build(&mut ctx)?;
    let mut bind = Vec::new();
    for (i, value) in surface.param_values().into_iter().enumerate() {
        let c = ctx.constant(value)?;
        bind.push((implicit_expr::Var(3 + i as u32), c));
    }
    let root = ctx.substitute(root, &bind);
    let (ctx, root) = ctx.extract(root);
    Expr::from_graph(name, ctx, root)
}

/// The formula expressions: `(name, text)`.
pub const FORMULAS: [(&str, &str); 4] = [
    ("sphere", "sqrt(x^2 + y^2 + z^2) - 1"),
    ("torus", "(sqrt(x^2 + y^2) - 0.6)^2 + z^2 - 0.09"),
    (
        "gyroid",
        "sin(6*x)*cos(6*y) + sin(6*y)*cos(6*z) + sin(6*z)*cos(6*x)",
    ),
    (
        "heart",
        "(x^2 + 2.25*y^2 + z^2 - 1)^3 - x^2*z^3 - 0.1125*y^2*z^3",
    ),
];

/// Rebuilds the graph of `root` in a fidget context, node by node.
///
/// Returns the reason when the graph uses an operation fidget lacks (`log10`, real `pow`,
/// the slope operations, variables other than `x`, `y`, `z`).
pub fn to_fidget(ctx: &Context, root: NodeId) -> Result<(fidget::Context, FNode), String> {
    let mut f = fidget::Context::new();
    let mut map: Vec<Option<FNode>> = vec![None; ctx.len()];
    let err = |e: fidget::context::BadNode| e.to_string();
    for id in ctx.reachable(&[root]) {
        let arg = |a: NodeId| map[a.index()].expect("children come first");
        let node = match *ctx.get(id) {
            Node::Var(v) => match v.index() {
                0 => f.x(),
                1 => f.y(),
                2 => f.z(),
                _ => return Err(format!("variable '{}'", ctx.var_names()[v.index()])),
            },
            Node::Const(c) => f.constant(c.value() as f32),
            Node::Unary(op, a) => {
                let a = arg(a);
                match op {
                    UnaryOp::Neg => f.neg(a),
                    UnaryOp::Abs => f.abs(a),
                    UnaryOp::Sqr => f.square(a),
                    UnaryOp::Sqrt => f.sqrt(a),
                    UnaryOp::Recip => f.recip(a),
                    UnaryOp::Exp => f.exp(a),
                    UnaryOp::Ln => f.ln(a),
                    UnaryOp::Sin => f.sin(a),
                    UnaryOp::Cos => f.cos(a),
                    UnaryOp::Tan => f.tan(a),
                    UnaryOp::Asin => f.asin(a),
                    UnaryOp::Acos => f.acos(a),
                    UnaryOp::Atan => f.atan(a),
                    UnaryOp::Floor => f.floor(a),
                    UnaryOp::Ceil => f.ceil(a),
                    UnaryOp::Round => f.round(a),
                    UnaryOp::Not => f.not(a),
                    other => return Err(format!("operation '{}'", other.name())),
                }
                .map_err(err)?
            }
            Node::Binary(op, a, b) => {
                let (a, b) = (arg(a), arg(b));
                match op {
                    BinaryOp::Add => f.add(a, b),
                    BinaryOp::Sub => f.sub(a, b),
                    BinaryOp::Mul => f.mul(a, b),
                    BinaryOp::Div => f.div(a, b),
                    BinaryOp::Min => f.min(a, b),
                    BinaryOp::Max => f.max(a, b),
                    BinaryOp::Pow | BinaryOp::Domain => {
                        return Err(format!("operation '{}'", op.name()));
                    }
                }
                .map_err(err)?
            }
            Node::Pown(a, n) => {
                // Square-and-multiply with the same intermediate values as a naive product.
                let base = arg(a);
                let mut result: Option<FNode> = None;
                let mut square = base;
                let mut k = n.unsigned_abs();
                loop {
                    if k & 1 == 1 {
                        result = Some(match result {
                            Some(r) => f.mul(r, square).map_err(err)?,
                            None => square,
                        });
                    }
                    k >>= 1;
                    if k == 0 {
                        break;
                    }
                    square = f.square(square).map_err(err)?;
                }
                let r = result.expect("pown exponents are not 0");
                if n < 0 { f.recip(r).map_err(err)? } else { r }
            }
        };
        map[id.index()] = Some(node);
    }
    Ok((f, map[root.index()].expect("root is reachable")))
}

/// The points and boxes of an evaluation workload.
#[derive(Clone, Debug)]
pub struct Inputs {
    /// Points in `[-1, 1]³` (`z = 0` for planar expressions).
    pub points: Vec<[f32; 3]>,
    /// Boxes `[lo, hi]` per axis inside `[-1, 1]³`, half-widths `10^U(-3, -1)`
    /// (`z = [0, 0]` for planar expressions).
    pub boxes: Vec<[[f32; 2]; 3]>,
}

/// The seeded inputs: [`N_POINTS`] points and [`N_BOXES`] boxes.
pub fn inputs(planar: bool) -> Inputs {
    let mut rng = StdRng::seed_from_u64(SEED);
    let points = (0..N_POINTS)
        .map(|_| {
            let z = if planar {
                0.0
            } else {
                rng.gen_range(-1.0f32..1.0)
            };
            [rng.gen_range(-1.0f32..1.0), rng.gen_range(-1.0f32..1.0), z]
        })
        .collect();
    let boxes = (0..N_BOXES)
        .map(|_| {
            let mut b = [[0.0f32; 2]; 3];
            for (axis, slot) in b.iter_mut().enumerate() {
                if planar && axis == 2 {
                    continue;
                }
                let h = 10f32.powf(rng.gen_range(-3.0f32..-1.0));
                let c = rng.gen_range(-1.0f32 + h..1.0 - h);
                *slot = [c - h, c + h];
            }
            b
        })
        .collect();
    Inputs { points, boxes }
}

/// How an expression is evaluated.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Mode {
    /// One point per call.
    PointScalar,
    /// All points in one call of a slice evaluator.
    PointBatch,
    /// One box per call (with the `min`/`max` trace, as renderers use it).
    IntervalScalar,
    /// All boxes in one call of a slice evaluator.
    IntervalBatch,
}

impl Mode {
    /// Every mode, in table order.
    pub const ALL: [Mode; 4] = [
        Mode::PointScalar,
        Mode::PointBatch,
        Mode::IntervalScalar,
        Mode::IntervalBatch,
    ];

    /// Name used in benchmark ids and tables.
    pub fn name(self) -> &'static str {
        match self {
            Mode::PointScalar => "point-scalar",
            Mode::PointBatch => "point-batch",
            Mode::IntervalScalar => "interval-scalar",
            Mode::IntervalBatch => "interval-batch",
        }
    }

    /// Evaluations per workload pass.
    pub fn evaluations(self) -> usize {
        match self {
            Mode::PointScalar | Mode::PointBatch => N_POINTS,
            Mode::IntervalScalar | Mode::IntervalBatch => N_BOXES,
        }
    }
}

/// Who evaluates.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Engine {
    /// Our evaluators in `f32` (points) and `Interval<f32>`.
    Ours32,
    /// Our evaluators in `f64` and `Interval<f64>`.
    Ours64,
    /// fidget's bytecode VM.
    FidgetVm,
    /// fidget's JIT.
    FidgetJit,
}

impl Engine {
    /// Every engine, in table order.
    pub const ALL: [Engine; 4] = [
        Engine::Ours32,
        Engine::Ours64,
        Engine::FidgetVm,
        Engine::FidgetJit,
    ];

    /// Name used in benchmark ids and tables.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Ours32 => "ours-f32",
            Engine::Ours64 => "ours-f64",
            Engine::FidgetVm => "fidget-vm",
            Engine::FidgetJit => "fidget-jit",
        }
    }
}

/// Our evaluators of one tape and the inputs in their layouts.
pub struct Ours<T: implicit_expr::Number + interval_core::Float>
where
    Interval<T>: implicit_expr::Number,
{
    point: Evaluator<T>,
    slice: SliceEvaluator<T>,
    interval: Evaluator<Interval<T>>,
    islice: SliceEvaluator<Interval<T>>,
    points: Vec<[T; 3]>,
    columns: [Vec<T>; 3],
    boxes: Vec<[Interval<T>; 3]>,
    box_columns: [Vec<Interval<T>>; 3],
    out: Vec<T>,
    iout: Vec<Interval<T>>,
    trace: Vec<implicit_expr::Choice>,
}

impl<T: implicit_expr::Number + interval_core::Float> Ours<T>
where
    Interval<T>: implicit_expr::Number,
{
    /// Evaluators for `tape` with `inputs` converted to `T` (exactly).
    pub fn new(tape: &Tape, inputs: &Inputs) -> Self {
        let t = |v: f32| T::from_f64_rn(v as f64);
        let points: Vec<[T; 3]> = inputs.points.iter().map(|p| p.map(t)).collect();
        let columns = [0, 1, 2].map(|a| points.iter().map(|p| p[a]).collect());
        let boxes: Vec<[Interval<T>; 3]> = inputs
            .boxes
            .iter()
            .map(|b| b.map(|[lo, hi]| Interval::new(t(lo), t(hi)).expect("ordered bounds")))
            .collect();
        let box_columns = [0, 1, 2].map(|a| boxes.iter().map(|b| b[a]).collect());
        Self {
            point: Evaluator::new(tape),
            slice: SliceEvaluator::new(tape),
            interval: Evaluator::new(tape),
            islice: SliceEvaluator::new(tape),
            out: vec![T::ZERO; points.len()],
            iout: vec![Interval::ZERO; boxes.len()],
            points,
            columns,
            boxes,
            box_columns,
            trace: Vec::new(),
        }
    }

    /// One pass of `mode` over the workload; returns a checksum of the results.
    pub fn run(&mut self, mode: Mode) -> f64 {
        match mode {
            Mode::PointScalar => {
                let mut acc = 0.0;
                for p in black_box(&self.points) {
                    acc += self.point.eval(p).expect("three variables").to_f64();
                }
                acc
            }
            Mode::PointBatch => {
                let vars = [
                    &self.columns[0][..],
                    &self.columns[1][..],
                    &self.columns[2][..],
                ];
                self.slice
                    .eval(black_box(&vars), &mut self.out)
                    .expect("equal lengths");
                self.out.iter().map(|v| v.to_f64()).sum()
            }
            Mode::IntervalScalar => {
                let mut acc = 0.0;
                for b in black_box(&self.boxes) {
                    let v = self
                        .interval
                        .eval_traced(b, &mut self.trace)
                        .expect("three variables");
                    acc += v.inf().to_f64();
                }
                acc
            }
            Mode::IntervalBatch => {
                let vars = [
                    &self.box_columns[0][..],
                    &self.box_columns[1][..],
                    &self.box_columns[2][..],
                ];
                self.islice
                    .eval(black_box(&vars), &mut self.iout)
                    .expect("equal lengths");
                self.iout.iter().map(|v| v.inf().to_f64()).sum()
            }
        }
    }
}

/// fidget's evaluators of one function (VM or JIT) and the inputs in its variable order.
pub struct Fidget<F: Function> {
    point_tape: <F::PointEval as TracingEvaluator>::Tape,
    interval_tape: <F::IntervalEval as TracingEvaluator>::Tape,
    slice_tape: <F::FloatSliceEval as BulkEvaluator>::Tape,
    point: F::PointEval,
    interval: F::IntervalEval,
    slice: F::FloatSliceEval,
    /// Points, `k` values each in the tape's variable order.
    points: Vec<f32>,
    boxes: Vec<fidget::types::Interval>,
    columns: Vec<Vec<f32>>,
    k: usize,
}

impl<F: Function> Fidget<F> {
    /// Evaluators for `f` with `inputs`.
    pub fn new(f: &F, inputs: &Inputs) -> Self {
        let vars = f.vars();
        let k = vars.len();
        let slot = |axis: usize| {
            let v = [FVar::X, FVar::Y, FVar::Z][axis];
            vars.get(&v)
        };
        let mut points = vec![0.0f32; inputs.points.len() * k];
        let mut boxes = vec![fidget::types::Interval::from(0.0); inputs.boxes.len() * k];
        let mut columns = vec![vec![0.0f32; inputs.points.len()]; k];
        for axis in 0..3 {
            if let Some(s) = slot(axis) {
                for (i, p) in inputs.points.iter().enumerate() {
                    points[i * k + s] = p[axis];
                    columns[s][i] = p[axis];
                }
                for (i, b) in inputs.boxes.iter().enumerate() {
                    boxes[i * k + s] = fidget::types::Interval::new(b[axis][0], b[axis][1]);
                }
            }
        }
        Self {
            point_tape: f.point_tape(Default::default()),
            interval_tape: f.interval_tape(Default::default()),
            slice_tape: f.float_slice_tape(Default::default()),
            point: Default::default(),
            interval: Default::default(),
            slice: Default::default(),
            points,
            boxes,
            columns,
            k,
        }
    }

    /// One pass of `mode` over the workload; returns a checksum of the results, or `None`
    /// for interval batches (fidget has no interval slice evaluator).
    pub fn run(&mut self, mode: Mode) -> Option<f64> {
        let k = self.k;
        match mode {
            Mode::PointScalar => {
                let mut acc = 0.0;
                for p in black_box(&self.points).chunks_exact(k.max(1)) {
                    let (out, _) = self.point.eval(&self.point_tape, p).expect("vars given");
                    acc += out[0] as f64;
                }
                Some(acc)
            }
            Mode::PointBatch => {
                let out = self
                    .slice
                    .eval(&self.slice_tape, black_box(&self.columns[..]))
                    .expect("equal lengths");
                Some(out[0].iter().map(|&v| v as f64).sum())
            }
            Mode::IntervalScalar => {
                let mut acc = 0.0;
                for b in black_box(&self.boxes).chunks_exact(k.max(1)) {
                    let (out, _) = self
                        .interval
                        .eval(&self.interval_tape, b)
                        .expect("vars given");
                    acc += out[0].lower() as f64;
                }
                Some(acc)
            }
            Mode::IntervalBatch => None,
        }
    }
}

/// Every engine of one expression, ready to run.
pub struct Engines {
    /// Ours in `f32`.
    pub ours32: Ours<f32>,
    /// Ours in `f64`.
    pub ours64: Ours<f64>,
    /// fidget's VM, or why there is none.
    pub vm: Result<Fidget<VmFunction>, String>,
    /// fidget's JIT, or why there is none.
    pub jit: Result<Fidget<JitFunction>, String>,
    /// Instructions of our tape.
    pub ours_len: usize,
    /// Instructions of fidget's VM tape (its register tape, loads and stores included).
    pub vm_len: Option<usize>,
}

impl Engines {
    /// Builds every engine for `e` with the seeded inputs.
    pub fn new(e: &Expr) -> Self {
        let inputs = inputs(e.planar);
        let vm_fn = e.fidget_vm();
        let vm_len = vm_fn.as_ref().ok().map(|f| f.size());
        Self {
            ours32: Ours::new(&e.tape, &inputs),
            ours64: Ours::new(&e.tape, &inputs),
            vm: vm_fn.map(|f| Fidget::new(&f, &inputs)),
            jit: e.fidget_jit().map(|f| Fidget::new(&f, &inputs)),
            ours_len: e.tape.len(),
            vm_len,
        }
    }

    /// One pass of `mode` by `engine`; `None` where that engine cannot run that mode.
    pub fn run(&mut self, engine: Engine, mode: Mode) -> Option<f64> {
        match engine {
            Engine::Ours32 => Some(self.ours32.run(mode)),
            Engine::Ours64 => Some(self.ours64.run(mode)),
            Engine::FidgetVm => self.vm.as_mut().ok()?.run(mode),
            Engine::FidgetJit => self.jit.as_mut().ok()?.run(mode),
        }
    }
}

/// What is evaluated inside each tile of a [`PruneBench`].
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Samples {
    /// A `k × k` grid of points (cell centres), evaluated in one slice call.
    Points(usize),
    /// A `k × k` grid of sub-boxes, each evaluated in interval arithmetic.
    Boxes(usize),
}

impl Samples {
    /// Evaluations per tile.
    pub fn per_tile(self) -> usize {
        match self {
            Samples::Points(k) | Samples::Boxes(k) => k * k,
        }
    }

    /// Short description for tables.
    pub fn describe(self) -> String {
        match self {
            Samples::Points(k) => format!("{k}x{k} points"),
            Samples::Boxes(k) => format!("{k}x{k} boxes"),
        }
    }
}

/// `[[x_lo, x_hi], [y_lo, y_hi]]`.
type Rect = [[f32; 2]; 2];

/// The square tiles of `[-1, 1]²` (`n × n` of them, `z = 0`) and, per tile, the sample
/// points or sub-boxes, as `f32` bounds.
fn tile_grid(n: usize, samples: Samples) -> Vec<(Rect, Vec<Rect>)> {
    let edge = |k: usize, of: usize| -1.0 + 2.0 * k as f32 / of as f32;
    let mut out = Vec::with_capacity(n * n);
    for tj in 0..n {
        for ti in 0..n {
            let tile = [
                [edge(ti, n), edge(ti + 1, n)],
                [edge(tj, n), edge(tj + 1, n)],
            ];
            let (k, point) = match samples {
                Samples::Points(k) => (k, true),
                Samples::Boxes(k) => (k, false),
            };
            let mut s = Vec::with_capacity(k * k);
            for sj in 0..k {
                for si in 0..k {
                    let (i, j) = (ti * k + si, tj * k + sj);
                    if point {
                        let x = -1.0 + 2.0 * (i as f32 + 0.5) / (n * k) as f32;
                        let y = -1.0 + 2.0 * (j as f32 + 0.5) / (n * k) as f32;
                        s.push([[x, x], [y, y]]);
                    } else {
                        s.push([
                            [edge(i, n * k), edge(i + 1, n * k)],
                            [edge(j, n * k), edge(j + 1, n * k)],
                        ]);
                    }
                }
            }
            out.push((tile, s));
        }
    }
    out
}

/// The tape-pruning workload on a planar expression: for each of `n × n` tiles of
/// `[-1, 1]²`, evaluate its samples either with the full tape, or after an interval
/// evaluation of the tile with the `min`/`max` trace and [`Tape::simplify`], with the
/// pruned tape (the work of a renderer's tile, tracing and pruning included). `f32`.
pub struct PruneBench {
    tape: Tape,
    samples: Samples,
    tiles: Vec<[Interval<f32>; 3]>,
    /// Per tile: the sample columns (points) or boxes.
    columns: Vec<[Vec<f32>; 3]>,
    boxes: Vec<Vec<[Interval<f32>; 3]>>,
    interval: Evaluator<Interval<f32>>,
    slice: SliceEvaluator<f32>,
    trace: Vec<implicit_expr::Choice>,
    out: Vec<f32>,
    /// Sum of the pruned tape lengths over the last [`pruned`](Self::pruned) pass.
    pruned_len_sum: usize,
}

impl PruneBench {
    /// The workload of `tape` on `n × n` tiles with `samples` per tile.
    pub fn new(tape: &Tape, n: usize, samples: Samples) -> Self {
        let iv = |[lo, hi]: [f32; 2]| Interval::new(lo, hi).expect("ordered bounds");
        let zero = Interval::new(0.0f32, 0.0).expect("ordered bounds");
        let grid = tile_grid(n, samples);
        let tiles = grid
            .iter()
            .map(|(t, _)| [iv(t[0]), iv(t[1]), zero])
            .collect();
        let columns = grid
            .iter()
            .map(|(_, s)| {
                [
                    s.iter().map(|b| b[0][0]).collect(),
                    s.iter().map(|b| b[1][0]).collect(),
                    vec![0.0; s.len()],
                ]
            })
            .collect();
        let boxes = grid
            .iter()
            .map(|(_, s)| s.iter().map(|b| [iv(b[0]), iv(b[1]), zero]).collect())
            .collect();
        Self {
            tape: tape.clone(),
            samples,
            tiles,
            columns,
            boxes,
            interval: Evaluator::new(tape),
            slice: SliceEvaluator::new(tape),
            trace: Vec::new(),
            out: vec![0.0; samples.per_tile()],
            pruned_len_sum: 0,
        }
    }

    /// Number of tiles.
    pub fn tiles(&self) -> usize {
        self.tiles.len()
    }

    /// Evaluations per pass.
    pub fn evaluations(&self) -> usize {
        self.tiles.len() * self.samples.per_tile()
    }

    fn samples(&mut self, tape: &Tape, tile: usize) -> f64 {
        match self.samples {
            Samples::Points(_) => {
                let c = &self.columns[tile];
                self.slice.set_tape(tape);
                self.slice
                    .eval(&[&c[0][..], &c[1][..], &c[2][..]], &mut self.out)
                    .expect("equal lengths");
                self.out.iter().map(|&v| v as f64).sum()
            }
            Samples::Boxes(_) => {
                self.interval.set_tape(tape);
                let mut acc = 0.0;
                for b in &self.boxes[tile] {
                    acc += self.interval.eval(b).expect("three variables").inf() as f64;
                }
                acc
            }
        }
    }

    /// One pass with the full tape on every tile; returns a checksum.
    pub fn full(&mut self) -> f64 {
        let tape = self.tape.clone();
        (0..self.tiles.len()).map(|t| self.samples(&tape, t)).sum()
    }

    /// One pass with tracing, pruning and the pruned tape on every tile; returns a checksum.
    pub fn pruned(&mut self) -> f64 {
        let mut acc = 0.0;
        self.pruned_len_sum = 0;
        for t in 0..self.tiles.len() {
            self.interval.set_tape(&self.tape);
            self.interval
                .eval_traced(&self.tiles[t], &mut self.trace)
                .expect("three variables");
            let sub = self.tape.simplify(&self.trace).expect("trace of this tape");
            self.pruned_len_sum += sub.len();
            acc += self.samples(&sub, t);
        }
        acc
    }

    /// Only the tracing and pruning of [`pruned`](Self::pruned), without the samples.
    pub fn trace_and_simplify(&mut self) -> usize {
        let mut total = 0;
        for t in 0..self.tiles.len() {
            self.interval.set_tape(&self.tape);
            self.interval
                .eval_traced(&self.tiles[t], &mut self.trace)
                .expect("three variables");
            total += self
                .tape
                .simplify(&self.trace)
                .expect("trace of this tape")
                .len();
        }
        total
    }

    /// Mean length of the pruned tapes of the last [`pruned`](Self::pruned) pass.
    pub fn mean_pruned_len(&self) -> f64 {
        self.pruned_len_sum as f64 / self.tiles.len() as f64
    }
}

/// [`PruneBench`] with fidget's VM: its interval trace and `simplify`.
pub struct FidgetPruneBench {
    f: VmFunction,
    samples: Samples,
    tiles: Vec<[fidget::types::Interval; 2]>,
    columns: Vec<[Vec<f32>; 2]>,
    boxes: Vec<Vec<[fidget::types::Interval; 2]>>,
    interval: <VmFunction as Function>::IntervalEval,
    slice: <VmFunction as Function>::FloatSliceEval,
    workspace: <VmFunction as Function>::Workspace,
    pruned_len_sum: usize,
}

impl FidgetPruneBench {
    /// The workload of the planar VM function `f` (variables `x`, `y` only) on `n × n`
    /// tiles with `samples` per tile.
    ///
    /// Returns an error when `f` uses `z` or does not use both `x` and `y`.
    pub fn new(f: &VmFunction, n: usize, samples: Samples) -> Result<Self, String> {
        let vars = f.vars();
        let (ix, iy) = match (vars.get(&FVar::X), vars.get(&FVar::Y)) {
            (Some(ix), Some(iy)) if vars.len() == 2 => (ix, iy),
            _ => return Err("the pruning workload needs a function of x and y".into()),
        };
        // Two values per sample in the function's variable order.
        let order = |x: [f32; 2], y: [f32; 2]| {
            let mut v = [[0.0f32; 2]; 2];
            v[ix] = x;
            v[iy] = y;
            v
        };
        let iv = |[lo, hi]: [f32; 2]| fidget::types::Interval::new(lo, hi);
        let grid = tile_grid(n, samples);
        Ok(Self {
            f: f.clone(),
            samples,
            tiles: grid
                .iter()
                .map(|(t, _)| order(t[0], t[1]).map(iv))
                .collect(),
            columns: grid
                .iter()
                .map(|(_, s)| {
                    let mut c = [Vec::new(), Vec::new()];
                    c[ix] = s.iter().map(|b| b[0][0]).collect();
                    c[iy] = s.iter().map(|b| b[1][0]).collect();
                    c
                })
                .collect(),
            boxes: grid
                .iter()
                .map(|(_, s)| s.iter().map(|b| order(b[0], b[1]).map(iv)).collect())
                .collect(),
            interval: Default::default(),
            slice: Default::default(),
            workspace: Default::default(),
            pruned_len_sum: 0,
        })
    }

    fn samples(&mut self, f: &VmFunction, tile: usize) -> f64 {
        match self.samples {
            Samples::Points(_) => {
                let tape = f.float_slice_tape(Default::default());
                let out = self
                    .slice
                    .eval(&tape, &self.columns[tile][..])
                    .expect("equal lengths");
                out[0].iter().map(|&v| v as f64).sum()
            }
            Samples::Boxes(_) => {
                let tape = f.interval_tape(Default::default());
                let mut acc = 0.0;
                for b in &self.boxes[tile] {
                    acc += self.interval.eval(&tape, b).expect("two variables").0[0].lower() as f64;
                }
                acc
            }
        }
    }

    /// One pass with the full tape on every tile; returns a checksum.
    pub fn full(&mut self) -> f64 {
        let f = self.f.clone();
        (0..self.tiles.len()).map(|t| self.samples(&f, t)).sum()
    }

    /// One pass with tracing, pruning and the pruned tape on every tile; returns a checksum.
    pub fn pruned(&mut self) -> f64 {
        let tape = self.f.interval_tape(Default::default());
        let mut acc = 0.0;
        self.pruned_len_sum = 0;
        for t in 0..self.tiles.len() {
            let (_, trace) = self
                .interval
                .eval(&tape, &self.tiles[t])
                .expect("two variables");
            let sub = match trace {
                Some(trace) => self
                    .f
                    .simplify(trace, Default::default(), &mut self.workspace)
                    .expect("trace of this function"),
                None => self.f.clone(),
            };
            self.pruned_len_sum += sub.size();
            acc += self.samples(&sub, t);
        }
        acc
    }

    /// Mean length of the pruned tapes of the last [`pruned`](Self::pruned) pass.
    pub fn mean_pruned_len(&self) -> f64 {
        self.pruned_len_sum as f64 / self.tiles.len() as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both libraries evaluate the same function: point values agree to `f32` accuracy,
    /// and our interval values hold our point values.
    #[test]
    fn same_expressions_for_both_libraries() {
        for e in expressions(&[]).unwrap() {
            let f = e.fidget_vm().unwrap();
            let inputs = inputs(e.planar);
            let mut theirs = Fidget::new(&f, &inputs);
            let tape = f.point_tape(Default::default());
            let mut ours = Evaluator::<f64>::new(&e.tape);
            let mut ours_iv = Evaluator::<Interval<f64>>::new(&e.tape);
            for (k, p) in inputs.points.iter().take(64).enumerate() {
                let v = ours.eval(&p.map(f64::from)).unwrap();
                let w = theirs
                    .point
                    .eval(&tape, &theirs.points[k * theirs.k..(k + 1) * theirs.k])
                    .unwrap()
                    .0[0];
                assert!(
                    (v - w as f64).abs() <= 1e-4 * (1.0 + v.abs()),
                    "{} at {p:?}: {v} vs {w}",
                    e.name
                );
                let b = p.map(|c| Interval::new(c as f64, c as f64).unwrap());
                assert!(ours_iv.eval(&b).unwrap().contains(v), "{}", e.name);
            }
        }
    }

    #[test]
    fn every_engine_runs_every_mode() {
        let e = Expr::from_formula("disc", "x^2 + y^2 - 0.5").unwrap();
        assert!(e.planar);
        let mut en = Engines::new(&e);
        for mode in Mode::ALL {
            for engine in Engine::ALL {
                let r = en.run(engine, mode);
                let fidget = matches!(engine, Engine::FidgetVm | Engine::FidgetJit);
                assert_eq!(
                    r.is_none(),
                    fidget && mode == Mode::IntervalBatch,
                    "{engine:?} {mode:?}"
                );
            }
        }
    }

    #[test]
    fn pruned_tiles_give_the_full_results() {
        let e = Expr::from_vm("csg2d", CSG2D_VM).unwrap();
        let mut b = PruneBench::new(&e.tape, 16, Samples::Points(2));
        assert_eq!(b.full(), b.pruned());
        assert!(b.mean_pruned_len() < e.tape.len() as f64 / 2.0);
        let mut f = FidgetPruneBench::new(&e.fidget_vm().unwrap(), 16, Samples::Points(2)).unwrap();
        assert_eq!(f.full(), f.pruned());
    }

    #[test]
    fn unsupported_operations_are_reported() {
        let e = Expr::from_formula("log", "log(x^2 + 1) - y").unwrap();
        assert!(e.fidget.is_err());
        let e = Expr::from_formula("pown", "x^-3 + x^5 - y").unwrap();
        let (ctx, root) = e.fidget.as_ref().unwrap();
        let v = ctx.eval_xyz(*root, 1.5, 0.25, 0.0).unwrap();
        let w = e.ctx.eval::<f64>(e.root, &[1.5, 0.25, 0.0]).unwrap();
        assert!((v as f64 - w).abs() < 1e-5 * w.abs(), "{v} vs {w}");
    }
}
