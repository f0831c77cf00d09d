//! # beam-cluster
//!
//! Reliable rendering of implicit surfaces on a cluster (the thesis's section 7.2): the
//! scene is loaded by every rank, the screen is cut into boxes that the ranks render with
//! the one render pipeline of `beam-trace`, and rank 0 assembles an image equal bit for bit
//! to the one a single process renders, whatever the number of ranks and threads.
//!
//! * [`work`]: the screen boxes, their bisection and their credit (termination by credit
//!   recovery: rank 0 knows the render is complete when every box's credit has come back,
//!   so a box in transit is never lost and no rank waits forever).
//! * [`station`]: one rank: a render thread that takes boxes from its list, and a main
//!   thread that asks for boxes when the list runs short (the thesis: fewer than 2), gives
//!   a share of its boxes to a rank that asks (the thesis: 40 %), sends rendered boxes to
//!   rank 0, and reports a rank silent for longer than a timeout as an error.
//! * [`transport`]: MPI between processes (`transport::Mpi`, feature `mpi`, through the
//!   `mpi` crate), or channels between threads ([`transport::local_cluster`]).
//! * [`report`]: per rank busy, idle and communication time, requests, donations and
//!   bytes, and the matrix of who rendered the boxes of which initial part (Fig. 7.4).
//!
//! ## Ranks as threads
//!
//! ```
//! use beam_cluster::{Settings, render_local};
//! use beam_trace::{NoProgress, Scene, render};
//!
//! let mut scene = Scene::default_scene();
//! scene.camera = scene.camera.resized(96, 64)?;
//! let (output, report) = render_local(&scene, 2, &Settings::default())?;
//! let alone = render(&scene, &NoProgress)?;
//! assert_eq!(output.fingerprint(), alone.fingerprint());
//! assert_eq!(report.ranks.len(), 2);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod error;
pub mod message;
pub mod report;
pub mod settings;
pub mod station;
pub mod transport;
pub mod wire;
pub mod work;

pub use error::Error;
pub use report::{ClusterReport, RankStats};
pub use settings::{Initial, Settings};
pub use station::{Fault, Gathered, RankOptions, run_rank};

use std::time::Instant;

use beam_trace::render::Pipeline;
use beam_trace::{Cpu, Plan, RenderOutput, Scene};

/// Renders `scene` on `ranks` ranks that are threads of this process (each with its own
/// pipeline and grid, as processes would have), joined by channels: the image and report
/// of rank 0.
///
/// # Errors
///
/// The first error of a rank.
pub fn render_local(
    scene: &Scene,
    ranks: usize,
    settings: &Settings,
) -> Result<(RenderOutput, ClusterReport), Error> {
    render_local_with(scene, ranks, settings, &|_| RankOptions::default())
}

/// [`render_local`] with each rank's options given by `options(rank)` (threads, faults).
///
/// # Errors
///
/// The first error of a rank, by rank.
pub fn render_local_with(
    scene: &Scene,
    ranks: usize,
    settings: &Settings,
    options: &(dyn Fn(usize) -> RankOptions<'static> + Sync),
) -> Result<(RenderOutput, ClusterReport), Error> {
    if ranks == 0 {
        return Err(Error::Setting {
            name: "ranks",
            message: "at least one rank".into(),
        });
    }
    let started = Instant::now();
    let plan = Plan::for_scene(scene);
    let results: Vec<Result<Option<Gathered>, Error>> = std::thread::scope(|s| {
        let handles: Vec<_> = transport::local_cluster(ranks)
            .into_iter()
            .enumerate()
            .map(|(rank, t)| {
                let plan = &plan;
                s.spawn(move || {
                    let pipeline = match Pipeline::new(scene, &Cpu, plan) {
                        Ok(p) => p,
                        Err(e) => {
                            station::tell_failure(&t, &e.to_string());
                            return Err(e.into());
                        }
                    };
                    let opts = RankOptions {
                        started,
                        ..options(rank)
                    };
                    run_rank(&t, &pipeline, settings, &opts)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| {
                h.join()
                    .unwrap_or_else(|_| Err(Error::Transport("a rank's thread panicked".into())))
            })
            .collect()
    });
    let mut gathered = None;
    let mut first_error: Option<Error> = None;
    for r in results {
        match r {
            Ok(Some(g)) => gathered = Some(g),
            Ok(None) => {}
            // The cause rather than its symptoms: a rank's own failure before another's
            // report of it, and either before a timeout.
            Err(e) => {
                let rank_of = |e: &Error| match e {
                    Error::Silent { .. } => 2,
                    Error::Failed { .. } => 1,
                    _ => 0,
                };
                if first_error
                    .as_ref()
                    .is_none_or(|f| rank_of(&e) < rank_of(f))
                {
                    first_error = Some(e);
                }
            }
        }
    }
    match (gathered, first_error) {
        (Some(g), None) => Ok((g.output, g.report)),
        (_, Some(e)) => Err(e),
        (None, None) => Err(Error::Transport("rank 0 returned no render".into())),
    }
}
