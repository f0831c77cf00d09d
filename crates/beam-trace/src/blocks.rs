//! Rendering an animation in blocks of frames (thesis 6.4–6.6).
//!
//! For a block of `n` frames the screen boxes are classified once, over the block's scene:
//! the frames' common geometry with each constant widened to its hull over the block
//! ([`Scene::block_of`]), the thesis's surface over a time interval, its *n-surface*. The
//! pieces of each beam that this classification proves root-free hold in every frame of
//! the block; each frame then runs its own passes and skips the rejection tests those
//! proofs decide ([`crate::free_ranges`]). Everything else, the root searches, normals,
//! shadows with that frame's lights and shading, runs per frame, as alone: every frame is
//! bit for bit the frame rendered on its own (given operations whose rounded enclosures
//! are inclusion isotone; skipping stays sound without it).
//!
//! **Fallback.** Frames whose graphs differ in more than constants, or whose camera or
//! settings differ, have no common block: the block is halved and each half tried again,
//! down to single frames. A block whose n-surface grows too much (more than
//! [`BlockSettings::max_growth`] times the pixels its first frame's screen boxes leave
//! open, that is Hit or Undecided) proves too little to be worth its pass: after its first
//! frame, the rest is rendered in two halves, each with a block of its own. With adaptive
//! sizes ([`BlockSettings::adaptive`]) the next block is halved after one whose proofs
//! spared less than its passes cost, and doubled after one that paid.

use std::ops::Range;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::backend::Backend;
use crate::backend::cpu::Cpu;
use crate::beam::BoxClass;
use crate::error::Error;
use crate::free_ranges::{BlockProofs, FreeRanges};
use crate::plan::Plan;
use crate::progress::Progress;
use crate::ray::Precision;
use crate::render::{RenderOutput, render_on, screen_box_pass};
use crate::scene::Scene;
use crate::stats::PassStats;

/// How an animation is cut into blocks.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct BlockSettings {
    /// Largest number of frames per block (1: every frame alone).
    pub size: usize,
    /// Largest ratio of the pixels a block's screen boxes leave open to those its first
    /// frame's leave open, above which the rest of the block is split.
    pub max_growth: f64,
    /// Whether the block size follows what the blocks save: halved after a block whose
    /// proofs saved fewer evaluations than its own pass cost, doubled (up to `size`) after
    /// one that saved more. Without it every block has `size` frames (but for splits).
    pub adaptive: bool,
}

impl Default for BlockSettings {
    fn default() -> Self {
        Self {
            size: 1,
            max_growth: 2.0,
            adaptive: true,
        }
    }
}

/// What one block did.
#[derive(Clone, Debug)]
pub struct BlockReport {
    /// Index of its first frame.
    pub first: usize,
    /// Number of frames it was meant for.
    pub frames: usize,
    /// Its own passes (the grid and the screen boxes of the block's scene); empty for a
    /// block that could not be formed.
    pub passes: Vec<PassStats>,
    /// Pieces proven root-free, and the beams they belong to.
    pub proven: (usize, usize),
    /// Pixels its screen boxes leave open (Hit or Undecided) over those of its first frame.
    pub growth: f64,
    /// Interval evaluations of its own passes.
    pub cost: u64,
    /// Rejection tests its frames skipped thanks to its proofs.
    pub saved: u64,
    /// Why the block was split, if it was.
    pub split: Option<String>,
    /// Time of its own passes.
    pub time: Duration,
}

impl BlockReport {
    /// Whether the block was formed (its own passes ran), rather than split at once.
    pub fn formed(&self) -> bool {
        !self.passes.is_empty()
    }
}

/// Whether `backend` reads a block's proofs: only the CPU's beam searches do, so on
/// another backend a block's passes would be spent for nothing.
pub fn reads_proofs(backend: &dyn Backend) -> bool {
    backend.name() == Cpu.name()
}

/// Pixels left open (Hit or Undecided) by screen-box classes.
fn open_pixels(classes: &[Option<BoxClass>]) -> usize {
    classes
        .iter()
        .filter(|c| !matches!(c, Some(BoxClass::Miss)))
        .count()
}

/// The grid and screen-box passes of a block's scene on the CPU, recording the pieces they
/// prove root-free; also the pixels they leave open.
fn prove(
    mut scene: Scene,
    progress: &dyn Progress,
) -> Result<(FreeRanges, Vec<PassStats>, usize), Error> {
    let recorder = Arc::new(BlockProofs::recorder());
    scene.proofs = Some(recorder.clone());
    let mut plan = Plan::for_scene(&scene);
    // Only rejections in the plan's precision are recorded: an escalated search would
    // prove nothing the frames can use.
    plan.beam.escalate = false;
    if plan.precision == Precision::Dd {
        // Double-double beams are narrowed by a centred form, which is not evaluated
        // operation by operation: the frames could not rely on its proofs.
        return Ok((FreeRanges::default(), Vec::new(), 0));
    }
    let (passes, classes) = screen_box_pass(&scene, &plan, progress)?;
    drop(scene);
    let recorded = Arc::try_unwrap(recorder)
        .map(BlockProofs::into_recorded)
        .unwrap_or_default();
    Ok((recorded, passes, open_pixels(&classes)))
}

/// Interval evaluations counted by passes.
fn evaluations(passes: &[PassStats]) -> u64 {
    passes
        .iter()
        .map(|p| p.counter("g_evals") + p.counter("dg_evals") + p.counter("leaf_evals"))
        .sum()
}

/// Frame `k`'s scene, and where its output goes.
pub trait Frames {
    /// The scene of frame `k` (`k < count`).
    ///
    /// # Errors
    ///
    /// Whatever building the scene reports.
    fn scene(&mut self, k: usize) -> Result<Scene, Error>;

    /// Takes frame `k`'s output (frames come in order).
    ///
    /// # Errors
    ///
    /// Whatever writing it reports; the render stops there.
    fn done(&mut self, k: usize, out: RenderOutput) -> Result<(), Error>;

    /// Hears what a block did, when it is done or split (nothing by default).
    fn block(&mut self, _report: &BlockReport) {}
}

/// Renders the `count` frames of `frames` in blocks of up to `settings.size` frames (thesis
/// 6.4; on a backend other than the CPU, whose beams do not read the proofs, every frame
/// alone), handing each frame's output to [`Frames::done`] in order as soon as it is
/// rendered; returns what each block did. Only one block's scenes are held at a time.
///
/// Each block's screen boxes are classified once over [`Scene::block_of`] its frames, and
/// each frame skips the rejection tests those proofs decide ([`crate::free_ranges`]):
/// every frame is bit for bit the frame rendered alone. Blocks split where the frames
/// differ in form, where the n-surface grows past `settings.max_growth`, and (adaptive)
/// where a block's proofs spared less than its passes cost.
///
/// # Errors
///
/// The first error of a render or of `frames`.
pub fn render_blocks(
    count: usize,
    frames: &mut dyn Frames,
    settings: BlockSettings,
    backend: &dyn Backend,
    progress: &dyn Progress,
) -> Result<Vec<BlockReport>, Error> {
    let mut reports = Vec::new();
    let max = if reads_proofs(backend) {
        settings.size.max(1)
    } else {
        1
    };
    let mut size = max;
    let mut alone = 0;
    let mut first = 0;
    while first < count {
        let end = (first + size).min(count);
        let scenes = (first..end)
            .map(|k| frames.scene(k))
            .collect::<Result<Vec<_>, _>>()?;
        let before = reports.len();
        let n = scenes.len();
        let mut run = Run {
            scenes,
            offset: first,
            settings,
            backend,
            progress,
            frames,
            reports: &mut reports,
        };
        run.block(0..n)?;
        if settings.adaptive {
            let done = &reports[before..];
            let (saved, cost) = done
                .iter()
                .fold((0, 0), |(s, c), r| (s + r.saved, c + r.cost));
            let formed = done.iter().any(BlockReport::formed);
            if size == 1 {
                // After `max` frames alone, try a block again.
                alone += 1;
                if alone >= max && max > 1 {
                    (size, alone) = (2, 0);
                }
            } else if !formed || saved < cost {
                // No block could be formed, or its proofs spared less than it cost.
                size = (size / 2).max(1);
            } else {
                size = (size * 2).min(max);
            }
        }
        first = end;
    }
    Ok(reports)
}

/// The blocks of one run of scenes.
struct Run<'a, 'f> {
    scenes: Vec<Scene>,
    offset: usize,
    settings: BlockSettings,
    backend: &'a dyn Backend,
    progress: &'a dyn Progress,
    frames: &'f mut dyn Frames,
    reports: &'a mut Vec<BlockReport>,
}

impl Run<'_, '_> {
    fn report(&mut self, report: BlockReport) {
        self.frames.block(&report);
        self.reports.push(report);
    }

    /// Renders scene `k` with `proofs`, hands it on, and returns the rejection tests the
    /// proofs saved and the pixels its screen boxes left open.
    fn frame(
        &mut self,
        k: usize,
        proofs: Option<&Arc<BlockProofs>>,
    ) -> Result<(u64, usize), Error> {
        let scene = &mut self.scenes[k];
        scene.proofs = proofs.cloned();
        let out = render_on(scene, self.backend, self.progress)?;
        scene.proofs = None;
        let saved = out
            .stats
            .passes
            .iter()
            .map(|p| p.counter("block_proven"))
            .sum();
        let open = open_pixels(&out.box_classes());
        self.frames.done(self.offset + k, out)?;
        Ok((saved, open))
    }

    /// Renders the scenes `range` as one block, or in smaller ones where it must split.
    fn block(&mut self, range: Range<usize>) -> Result<(), Error> {
        let (a, b) = (range.start, range.end);
        if b - a == 1 {
            return self.frame(a, None).map(|_| ());
        }
        let mut report = BlockReport {
            first: self.offset + a,
            frames: b - a,
            passes: Vec::new(),
            proven: (0, 0),
            growth: 0.0,
            cost: 0,
            saved: 0,
            split: None,
            time: Duration::ZERO,
        };
        let block = match Scene::block_of(&self.scenes[a..b]) {
            Ok(s) => s,
            Err(why) => {
                report.split = Some(why.to_string());
                self.report(report);
                let mid = a + (b - a) / 2;
                self.block(a..mid)?;
                return self.block(mid..b);
            }
        };
        let t0 = Instant::now();
        let (proven, passes, open) = prove(block, self.progress)?;
        report.time = t0.elapsed();
        report.cost = evaluations(&passes);
        report.passes = passes;
        report.proven = (proven.len(), proven.beams());
        let proofs = Arc::new(BlockProofs::reuse(proven));
        let (saved, first_open) = self.frame(a, Some(&proofs))?;
        report.saved = saved;
        report.growth = open as f64 / first_open.max(1) as f64;
        if report.growth > self.settings.max_growth && b - a > 2 {
            report.split = Some(format!(
                "the n-surface grows {:.2}x (more than {:.2}x)",
                report.growth, self.settings.max_growth
            ));
            self.report(report);
            let mid = a + 1 + (b - a - 1) / 2;
            self.block(a + 1..mid)?;
            return self.block(mid..b);
        }
        for k in a + 1..b {
            report.saved += self.frame(k, Some(&proofs))?.0;
        }
        self.report(report);
        Ok(())
    }
}
