//! Workloads shared by the criterion benchmarks (`benches/interval_ops.rs`) and the
//! `ops_report` binary, so that both time the same seeded random intervals.
//!
//! A workload is a vector of `f64` intervals drawn from a seeded [`StdRng`] in the natural
//! domain of the operation it feeds (see [`Domain`]). With the `inari` feature the same
//! values can be converted to `inari::Interval` (`to_inari`) and results compared
//! (`compare`).
//!
//! The expression benchmarks (`benches/expr_eval.rs`, the `expr_report`,
//! `render2d_compare` and `render3d_compare` binaries) share the module [`expr`]
//! (expressions, points and boxes, and the same expressions built for fidget) and the
//! committed models of `data/models/` ([`models`]), written by seeded generators: [`csg2d`]
//! (a large `min`/`max`-heavy 2D expression), [`text2d`] (2D text with the operation mix of
//! `prospero.vm`) and [`csg3d`] (3D CSG models: a city, a molecule), over the `.vm` writer of
//! [`vmgen`]; [`octree`] is fidget's subdivision of 3D tiles with our intervals, which
//! `render3d_compare` times beside both renderers.

pub mod csg2d;
pub mod csg3d;
pub mod expr;
pub mod models;
pub mod octree;
pub mod text2d;
pub mod vmgen;

/// The exit of a report binary: success, or the error printed as `error: ...` and failure.
pub fn exit(result: Result<(), String>) -> std::process::ExitCode {
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

use interval_core::Interval;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

/// Number of intervals per workload.
pub const N: usize = 1_000_000;

/// Seed of the first operand; the second operand of binary operations uses `SEED + 1`.
pub const SEED: u64 = 0x1788_2015;

/// The kind of arguments a workload holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Random signs, midpoint magnitudes `10^U(-3, 3)`; 90 % of the intervals have a
    /// relative width `10^U(-6, 0)` (sign-definite), 10 % straddle zero.
    General,
    /// Positive intervals `[m, m·(1 + w)]`, `m = 10^U(-3, 3)`, `w = 10^U(-6, 0)` (for `sqrt`).
    Positive,
    /// Midpoints uniform in `[-50, 50]`, widths `10^U(-6, 0)` (for `exp`).
    Exp,
    /// Midpoints uniform in `[-10, 10]`, widths `10^U(-6, 0)` (for `sin`).
    Sin,
}

/// `10^u` with `u` uniform in `[lo, hi)`.
fn log_uniform(rng: &mut StdRng, lo: f64, hi: f64) -> f64 {
    10f64.powf(rng.gen_range(lo..hi))
}

/// One random interval of the given domain.
fn draw(rng: &mut StdRng, domain: Domain) -> Interval<f64> {
    let (lo, hi) = match domain {
        Domain::General => {
            let m = log_uniform(rng, -3.0, 3.0);
            let m = if rng.gen_bool(0.5) { m } else { -m };
            if rng.gen_bool(0.9) {
                let half = 0.5 * m.abs() * log_uniform(rng, -6.0, 0.0);
                (m - half, m + half)
            } else {
                let r = m.abs() * rng.gen_range(1.0..3.0);
                (m - r, m + r)
            }
        }
        Domain::Positive => {
            let m = log_uniform(rng, -3.0, 3.0);
            (m, m + m * log_uniform(rng, -6.0, 0.0))
        }
        Domain::Exp | Domain::Sin => {
            let r = if domain == Domain::Exp { 50.0 } else { 10.0 };
            let c = rng.gen_range(-r..r);
            let half = 0.5 * log_uniform(rng, -6.0, 0.0);
            (c - half, c + half)
        }
    };
    Interval::new(lo, hi).expect("workload bounds are ordered and finite")
}

/// `n` random intervals of `domain`, reproducible from `seed`.
///
/// ```
/// use benches::{Domain, intervals};
/// let xs = intervals(Domain::Positive, 10, 1);
/// assert_eq!(xs, intervals(Domain::Positive, 10, 1));
/// assert!(xs.iter().all(|x| x.inf() > 0.0));
/// ```
pub fn intervals(domain: Domain, n: usize, seed: u64) -> Vec<Interval<f64>> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..n).map(|_| draw(&mut rng, domain)).collect()
}

/// The operands of the binary operations: two independent [`Domain::General`] vectors.
pub fn binary_operands(n: usize) -> (Vec<Interval<f64>>, Vec<Interval<f64>>) {
    (
        intervals(Domain::General, n, SEED),
        intervals(Domain::General, n, SEED + 1),
    )
}

/// The same intervals as `inari` intervals.
#[cfg(feature = "inari")]
pub fn to_inari(xs: &[Interval<f64>]) -> Vec<inari::Interval> {
    xs.iter()
        .map(|x| match x.bounds() {
            Some((a, b)) => inari::Interval::try_from((a, b)).expect("valid interval"),
            None => inari::Interval::EMPTY,
        })
        .collect()
}

/// How two libraries' results for the same operation compare, counted element-wise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Comparison {
    /// Elements compared.
    pub total: usize,
    /// Elements with equal bounds (`-0 = +0`; both empty counts as equal).
    pub identical: usize,
    /// Elements where the first result strictly contains the second.
    pub first_wider: usize,
    /// Elements where the second result strictly contains the first.
    pub second_wider: usize,
    /// Elements where neither contains the other (never expected).
    pub incomparable: usize,
}

/// Compares interval-core results `ours` with inari results `theirs`, element by element.
#[cfg(feature = "inari")]
pub fn compare(ours: &[Interval<f64>], theirs: &[inari::Interval]) -> Comparison {
    let mut c = Comparison::default();
    for (a, b) in ours.iter().zip(theirs) {
        c.total += 1;
        let a = a.bounds();
        let b = (!b.is_empty()).then(|| (b.inf(), b.sup()));
        match (a, b) {
            (None, None) => c.identical += 1,
            (Some(_), None) => c.first_wider += 1,
            (None, Some(_)) => c.second_wider += 1,
            (Some((al, ah)), Some((bl, bh))) => {
                if al == bl && ah == bh {
                    c.identical += 1;
                } else if al <= bl && bh <= ah {
                    c.first_wider += 1;
                } else if bl <= al && ah <= bh {
                    c.second_wider += 1;
                } else {
                    c.incomparable += 1;
                }
            }
        }
    }
    c
}
