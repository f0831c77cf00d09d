//! Animations rendered in blocks of frames (thesis 6.4): every frame bit for bit the frame
//! rendered alone, the block's geometry an enclosure of each frame's, and blocks split
//! where the frames change form or the n-surface grows.

use beam_trace::backend::cpu::Cpu;
use beam_trace::blocks::{BlockReport, BlockSettings, Frames, render_blocks};
use beam_trace::scene::Animation;
use beam_trace::stats::PassStats;
use beam_trace::{Error, Geometry, IBox, NoProgress, RenderOutput, Scene, render_on};
use implicit_expr::Evaluator;
use interval_core::Interval;
use proptest::prelude::*;

/// A scene file around `surfaces` (TOML) with `frames` and a light at `light`.
fn animated(frames: &str, surfaces: &str, light: &str) -> String {
    format!(
        r#"
[animation]
frames = {frames}

[camera]
eye = [0.0, 1.5, 5.0]
look_at = [0.0, 0.0, 0.0]
fov = 40
width = 48
height = 36

{surfaces}

[[lights]]
type = "point"
position = {light}
"#
    )
}

/// An orthocircle turning about two axes (never through a right angle), with its
/// parameters changing, above a floor.
fn rotating(frames: &str) -> String {
    animated(
        frames,
        r#"
[[surfaces]]
catalog = "orthocircle"
params = { a = "0.075 + 0.002*t", b = "3 - 0.05*t" }
transform = { rotate = ["10 + 6*t", "7 + 3*t", 0], translate = [0, 0.1, 0] }

[[surfaces]]
formula = "y + 1.3"
bounds = [[-3, -1.5, -3], [3, -1.3, 3]]
clip = true
"#,
        "[2, 4, 3]",
    )
}

/// A morph from chubs to McMullen's K3 surface, `t` in the formula.
fn morph(frames: &str) -> String {
    animated(
        frames,
        r#"
[[surfaces]]
formula = "(1 - s)*(x^4 + y^4 + z^4 - x^2 - y^2 - z^2 + 0.5) + s*((1 + x^2)*(1 + y^2)*(1 + z^2) + 8*x*y*z - 2)"
params = { s = "0.05 + 0.1*t" }
bounds = [[-2, -2, -2], [2, 2, 2]]
"#,
        "[2, 4, 3]",
    )
}

/// A fixed sphere on a floor under a light that circles: only shading and shadows change.
fn moving_light(frames: &str) -> String {
    animated(
        frames,
        r#"
[[surfaces]]
formula = "x^2 + y^2 + z^2 - 0.8"
bounds = [[-1, -1, -1], [1, 1, 1]]

[[surfaces]]
formula = "y + 1"
bounds = [[-3, -1.2, -3], [3, -1, 3]]
clip = true
"#,
        r#"["3*cos(0.4*t)", 4, "3*sin(0.4*t)"]"#,
    )
}

/// The frames of an animation, kept.
struct Kept {
    scenes: Vec<Scene>,
    outputs: Vec<RenderOutput>,
    reports: Vec<BlockReport>,
}

impl Frames for Kept {
    fn scene(&mut self, k: usize) -> Result<Scene, Error> {
        Ok(self.scenes[k].clone())
    }
    fn done(&mut self, k: usize, out: RenderOutput) -> Result<(), Error> {
        assert_eq!(k, self.outputs.len(), "frames come in order");
        self.outputs.push(out);
        Ok(())
    }
    fn block(&mut self, report: &BlockReport) {
        self.reports.push(report.clone());
    }
}

fn frames_of(text: &str) -> Vec<Scene> {
    let a = Animation::from_toml(text, "test.toml", None)
        .expect("the animation reads")
        .expect("an animation");
    a.frames()
        .map(|t| a.scene(t).expect("the frame builds"))
        .collect()
}

fn render_in_blocks(scenes: &[Scene], settings: BlockSettings) -> Kept {
    let mut kept = Kept {
        scenes: scenes.to_vec(),
        outputs: Vec::new(),
        reports: Vec::new(),
    };
    let reports = render_blocks(scenes.len(), &mut kept, settings, &Cpu, &NoProgress)
        .expect("the blocks render");
    assert_eq!(reports.len(), kept.reports.len(), "every block is reported");
    kept
}

fn fixed(size: usize) -> BlockSettings {
    BlockSettings {
        size,
        max_growth: f64::INFINITY,
        adaptive: false,
    }
}

/// Renders the frames alone and in blocks of `size`; every image, classification and
/// coverage must be equal; returns the blocks' reports and the frames' outputs.
fn assert_blocks_match_frames(text: &str, size: usize) -> (Vec<BlockReport>, Vec<RenderOutput>) {
    let scenes = frames_of(text);
    let kept = render_in_blocks(&scenes, fixed(size));
    assert_eq!(kept.outputs.len(), scenes.len());
    for (k, (scene, out)) in scenes.iter().zip(&kept.outputs).enumerate() {
        let alone = render_on(scene, &Cpu, &NoProgress).expect("the frame renders");
        assert_eq!(
            alone.image.pixels, out.image.pixels,
            "frame {k}: the block's image differs from the frame rendered alone"
        );
        assert_eq!(
            alone.box_classes(),
            out.box_classes(),
            "frame {k}: box classes"
        );
        assert_eq!(
            alone.classification().pixels,
            out.classification().pixels,
            "frame {k}: classification"
        );
    }
    let formed: Vec<&BlockReport> = kept
        .reports
        .iter()
        .filter(|r| !r.passes.is_empty())
        .collect();
    assert!(
        !formed.is_empty(),
        "no block was formed: {:?}",
        kept.reports
    );
    (kept.reports, kept.outputs)
}

#[test]
fn a_rotating_surface_renders_in_blocks_as_frame_by_frame() {
    let (reports, _) = assert_blocks_match_frames(&rotating("[0, 5]"), 3);
    // The proofs were used: some rejection test was skipped.
    assert!(
        reports.iter().map(|r| r.saved).sum::<u64>() > 0,
        "{reports:?}"
    );
}

#[test]
fn a_morph_between_catalog_surfaces_renders_in_blocks_as_frame_by_frame() {
    assert_blocks_match_frames(&morph("[0, 5]"), 3);
}

#[test]
fn a_moving_light_renders_in_blocks_as_frame_by_frame() {
    let (reports, _) = assert_blocks_match_frames(&moving_light("[0, 3]"), 4);
    // Nothing but the light moves: the block's geometry is each frame's, the n-surface
    // does not grow.
    let r = reports
        .iter()
        .find(|r| !r.passes.is_empty())
        .expect("a block");
    assert!((r.growth - 1.0).abs() < 1e-12, "{r:?}");
}

#[test]
fn frames_whose_searches_escalate_render_in_blocks_as_frame_by_frame() {
    // A sphere written with terms of 1e11 that cancel (rounding keeps f64 searches open,
    // they escalate to double-double), with a moving hole cut out of it.
    let text = animated(
        "[0, 3]",
        r#"
[[surfaces]]
formula = "max((x + 1e11)^2 - 2e11*x - 1e22 + y^2 + z^2 - 1, 0.3 - (x - 0.2 - 0.05*t)^2 - (y - 0.1)^2 - (z - 0.9)^2)"
bounds = [[-1.25, -1.25, -1.25], [1.25, 1.25, 1.25]]
"#,
        "[2, 4, 3]",
    );
    let (reports, outputs) = assert_blocks_match_frames(&text, 4);
    let escalated =
        |passes: &[PassStats]| -> u64 { passes.iter().map(|p| p.counter("escalated")).sum() };
    // The frames escalate; the block's own pass does not (it records only plain proofs).
    assert!(
        outputs
            .iter()
            .map(|o| escalated(&o.stats.passes))
            .sum::<u64>()
            > 0
    );
    let block: u64 = reports.iter().map(|r| escalated(&r.passes)).sum();
    assert_eq!(block, 0, "{reports:?}");
}

#[test]
fn frames_that_change_form_split_the_block() {
    // Rotation by 90 t degrees: frame 0 is the identity, frame 1 exactly a right angle,
    // whose exact zeros drop terms from the graph; 2 and 3 do the same.
    let text = animated(
        "[0, 3]",
        r#"
[[surfaces]]
formula = "x^2 + 2*y^2 + 3*z^2 - 1"
bounds = [[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]
transform = { rotate = [0, 0, "90*t"] }
"#,
        "[2, 4, 3]",
    );
    let scenes = frames_of(&text);
    let kept = render_in_blocks(&scenes, fixed(4));
    let first = &kept.reports[0];
    assert_eq!((first.first, first.frames), (0, 4));
    assert!(first.passes.is_empty());
    assert!(
        first
            .split
            .as_deref()
            .is_some_and(|s| s.contains("changes form")),
        "{first:?}"
    );
    assert_eq!(kept.outputs.len(), 4);
}

#[test]
fn a_growing_n_surface_splits_the_block() {
    // A small ball crossing the view fast: over the block it sweeps a long tube.
    let text = animated(
        "[0, 5]",
        r#"
[[surfaces]]
formula = "x^2 + y^2 + z^2 - 0.04"
bounds = [[-0.3, -0.3, -0.3], [0.3, 0.3, 0.3]]
transform = { translate = ["-1.6 + 0.6*t", 0.05, 0.02] }
"#,
        "[2, 4, 3]",
    );
    let scenes = frames_of(&text);
    let settings = BlockSettings {
        size: 6,
        max_growth: 2.0,
        adaptive: false,
    };
    let kept = render_in_blocks(&scenes, settings);
    let first = &kept.reports[0];
    assert!(first.growth > 2.0, "{first:?}");
    assert!(
        first.split.as_deref().is_some_and(|s| s.contains("grows")),
        "{first:?}"
    );
    // The rest was rendered in smaller blocks, and every frame is still the frame alone.
    assert!(kept.reports.len() > 1);
    for (scene, out) in scenes.iter().zip(&kept.outputs) {
        let alone = render_on(scene, &Cpu, &NoProgress).expect("the frame renders");
        assert_eq!(alone.image.pixels, out.image.pixels);
    }
}

#[test]
fn an_adaptive_run_halves_blocks_that_do_not_pay() {
    let scenes = frames_of(&rotating("[0, 7]"));
    let settings = BlockSettings {
        size: 4,
        max_growth: f64::INFINITY,
        adaptive: true,
    };
    let kept = render_in_blocks(&scenes, settings);
    assert_eq!(kept.outputs.len(), 8);
    let first = kept
        .reports
        .iter()
        .find(|r| !r.passes.is_empty())
        .expect("a block");
    // The next block is half as long when the first did not pay, else as long (the most).
    let next = kept
        .reports
        .iter()
        .find(|r| r.first >= first.first + first.frames)
        .expect("frames after the first block");
    let expected = if first.saved < first.cost {
        first.frames / 2
    } else {
        first.frames
    };
    assert_eq!(next.frames, expected, "{:?}", kept.reports);
}

/// Interval value of `g`'s scene function over a box.
fn over(geometry: &Geometry, b: &IBox) -> Interval<f64> {
    let mut ev = Evaluator::<Interval<f64>>::new(geometry.tape());
    ev.eval(b).expect("the tape evaluates")
}

fn arb_box() -> impl Strategy<Value = IBox> {
    (
        proptest::array::uniform3(-1.6..1.6f64),
        proptest::array::uniform3(0.0..0.8f64),
    )
        .prop_map(|(lo, w)| std::array::from_fn(|k| Interval::new(lo[k], lo[k] + w[k]).unwrap()))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The block's scene function over any box encloses each frame's over the same box,
    /// and each frame's value at a point.
    #[test]
    fn the_block_geometry_encloses_every_frame(b in arb_box(), first in 0i64..4, text in prop::sample::select(vec![0usize, 1])) {
        let text = if text == 0 { rotating("[0, 9]") } else { morph("[0, 9]") };
        let scenes = frames_of(&text);
        let block = Scene::block_of(&scenes[first as usize..first as usize + 5]).expect("a block");
        let wide = over(&block.geometry, &b);
        for s in &scenes[first as usize..first as usize + 5] {
            let narrow = over(&s.geometry, &b);
            prop_assert!(narrow.is_empty() || narrow.subset(wide), "{narrow:?} not in {wide:?}");
            let p = [b[0].mid(), b[1].mid(), b[2].mid()];
            let mut point = Evaluator::<f64>::new(s.geometry.tape());
            let v = point.eval(&p).expect("the tape evaluates");
            let at = over(&block.geometry, &p.map(|x| Interval::new(x, x).unwrap()));
            prop_assert!(!v.is_finite() || at.contains(v), "{v} not in {at:?}");
        }
    }
}
