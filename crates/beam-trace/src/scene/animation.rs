//! Animated scene files: an `[animation]` table with a frame range and rate, and numbers
//! written as formulas of the frame time `t` wherever the file has a number.
//!
//! ```toml
//! [animation]
//! frames = [0, 99]       # t = 0, 1, …, 99 (inclusive)
//! rate = 25              # frames per second of the animated file
//! block = 5              # frames per block (optional, default 1: every frame alone)
//!
//! [[surfaces]]
//! catalog = "orthocircle"
//! params = { a = "0.075 + 0.0005*t" }
//! transform = { rotate = ["30 + 5*t", 0, 0] }
//!
//! [[surfaces]]
//! formula = "x^2 + y^2 + z^2 - (0.5 + 0.01*t)^2"   # `t` in formulas too
//! bounds = [[-1.5, -1.5, -1.5], [1.5, 1.5, 1.5]]
//!
//! [[lights]]
//! type = "point"
//! position = ["3*cos(t/10)", 4, "3*sin(t/10)"]
//! ```
//!
//! A string in place of a number is a formula of `t` alone, in the syntax of surface
//! formulas; a string that is not one (a name, a formula of `x`, `y`, `z`, a method name)
//! stays a string, and a string that is not valid formula syntax stays a string too (where
//! the file needs a number, the error then says a string was found). Frame `t` is the file with every such string replaced by its value at
//! `t` (rounded to nearest in `f64`), and `t` bound in the surface formulas: exactly the
//! scene a static file with those numbers describes, so a frame renders as that file does.
//! [`Scene::from_toml`] on an animated file builds its first frame.

use std::ops::{Range, RangeInclusive};
use std::path::{Path, PathBuf};

use implicit_expr::tape::Opcode;
use implicit_expr::{Context, Evaluator, Tape};
use serde::Deserialize;
use toml::de::{DeTable, DeValue};

use super::diagnostics::Doc;
use super::model::Scene;
use crate::error::Error;

/// The name of the frame time in the scene file's formulas.
pub const TIME: &str = "t";

/// Keys whose string values are never formulas of `t` (names, formulas of `x y z`, methods).
const STRING_KEYS: [&str; 13] = [
    "name",
    "formula",
    "catalog",
    "vm",
    "normal",
    "type",
    "op",
    "children",
    "root_finder",
    "aa",
    "primary",
    "shadow_method",
    "precision",
];

/// The `[animation]` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAnimation {
    frames: [i64; 2],
    rate: Option<f64>,
    block: Option<u32>,
}

/// Only the `[animation]` table of a file (the rest is read per frame).
#[derive(Deserialize)]
struct AnimationOnly {
    animation: Option<RawAnimation>,
}

/// A number of the file written as a formula of `t`.
#[derive(Clone, Debug)]
struct TimeValue {
    /// Where the string literal is in the text (quotes included).
    span: Range<usize>,
    /// Its field path, for messages.
    path: String,
    /// The formula, compiled (variable slot 3 is `t`).
    tape: Tape,
}

/// An animated scene file: its frames and how to build each one.
#[derive(Clone, Debug)]
pub struct Animation {
    text: String,
    file: String,
    base: Option<PathBuf>,
    frames: RangeInclusive<i64>,
    rate: f64,
    block: usize,
    values: Vec<TimeValue>,
}

impl Animation {
    /// Reads the animation of a scene file's text: `Ok(None)` when it has no `[animation]`
    /// table (a static scene).
    ///
    /// # Errors
    ///
    /// [`Error::Scene`] naming the field: invalid TOML, a frame range that is empty or
    /// beyond `±10⁹`, a rate that is not positive, or a formula of `t` whose value at the
    /// first frame is not a finite number.
    pub fn from_toml(
        text: &str,
        file: &str,
        base_dir: Option<&Path>,
    ) -> Result<Option<Animation>, Error> {
        let doc = Doc::parse(file, text)?;
        if !doc.has_key("animation") {
            return Ok(None);
        }
        Animation::from_doc(&doc, base_dir).map(Some)
    }

    /// The animation of a parsed document that has an `[animation]` table.
    pub(super) fn from_doc(doc: &Doc<'_>, base_dir: Option<&Path>) -> Result<Animation, Error> {
        let tree = doc.tree.as_ref().expect("a parsed document");
        let only = AnimationOnly::deserialize(toml::Deserializer::from(tree.clone()))
            .map_err(|e| doc.serde_error(&e))?;
        let Some(raw) = only.animation else {
            return Err(doc.err("animation", "expected an [animation] table"));
        };
        let [first, last] = raw.frames;
        const LIMIT: std::ops::RangeInclusive<i64> = -1_000_000_000..=1_000_000_000;
        if first > last || !LIMIT.contains(&first) || !LIMIT.contains(&last) {
            return Err(doc.err(
                "animation.frames",
                format!(
                    "a frame range [first, last] with first <= last within ±1e9, got [{first}, {last}]"
                ),
            ));
        }
        let rate = raw.rate.unwrap_or(25.0);
        if !(rate.is_finite() && rate > 0.0) {
            return Err(doc.err(
                "animation.rate",
                format!("frames per second must be positive, got {rate}"),
            ));
        }
        let block = match raw.block {
            Some(0) => {
                return Err(doc.err(
                    "animation.block",
                    "frames per block must be at least 1 (1 renders every frame alone)",
                ));
            }
            Some(n) => n as usize,
            None => 1,
        };
        let mut values = Vec::new();
        collect(tree.get_ref(), "", &mut values);
        values.sort_by_key(|v| v.span.start);
        let animation = Animation {
            text: doc.text.to_string(),
            file: doc.file.to_string(),
            base: base_dir.map(Path::to_path_buf),
            frames: first..=last,
            rate,
            block,
            values,
        };
        // Every formula of `t` must give a number at the first frame.
        animation.frame_text(first)?;
        Ok(animation)
    }

    /// Reads an animated scene file (see [`Animation::from_toml`]).
    ///
    /// # Errors
    ///
    /// [`Error::Io`] when the file cannot be read, otherwise as [`Animation::from_toml`].
    pub fn load(path: &Path) -> Result<Option<Animation>, Error> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Animation::from_toml(&text, &path.display().to_string(), path.parent())
    }

    /// The frames, `t = first ..= last`.
    pub fn frames(&self) -> RangeInclusive<i64> {
        self.frames.clone()
    }

    /// Frames per second.
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// Frames per block ([`crate::blocks::render_blocks`]): `[animation] block`, 1 when
    /// absent (every frame alone).
    pub fn block(&self) -> usize {
        self.block
    }

    /// The number of fields written as formulas of `t`.
    pub fn time_values(&self) -> usize {
        self.values.len()
    }

    /// The scene of frame `t`.
    ///
    /// # Errors
    ///
    /// [`Error::Scene`] naming the field and the frame where a formula of `t` has no finite
    /// value, or where the frame's scene is invalid (as [`Scene::from_toml`] says).
    pub fn scene(&self, t: i64) -> Result<Scene, Error> {
        let text = self.frame_text(t)?;
        let file = format!("{} (frame {t})", self.file);
        Scene::from_toml_at(&text, &file, self.base.as_deref(), Some(t as f64))
    }

    /// The file's text with every formula of `t` replaced by its value at `t`.
    fn frame_text(&self, t: i64) -> Result<String, Error> {
        let doc = Doc::detached(&self.file);
        let mut out = String::with_capacity(self.text.len());
        let mut at = 0;
        let vars = [0.0, 0.0, 0.0, t as f64];
        for v in &self.values {
            let value = Evaluator::<f64>::new(&v.tape)
                .eval(&vars)
                .map_err(|e| doc.err(&v.path, e))?;
            if !value.is_finite() {
                return Err(doc.err(
                    &v.path,
                    format!("the formula of t is {value} at frame t = {t}"),
                ));
            }
            out.push_str(&self.text[at..v.span.start]);
            // Whole values as integers, which the integer fields (`width`, …) need and the
            // float fields accept; others in the shortest form that reads back exactly.
            if value.fract() == 0.0
                && value.abs() < 9.0e15
                && !(value == 0.0 && value.is_sign_negative())
            {
                out.push_str(&format!("{}", value as i64));
            } else {
                out.push_str(&format!("{value:?}"));
            }
            at = v.span.end;
        }
        out.push_str(&self.text[at..]);
        Ok(out)
    }
}

/// Whether a string of the file at `path` is a formula of `t` alone: its compiled tape,
/// `None` otherwise (a name, a formula of `x`, `y` or `z` such as a light's `normal = "y"`,
/// a method name). Strings under the keys of [`STRING_KEYS`] are never formulas of `t`,
/// except the values of a surface's `params`, whose keys are parameter names.
fn time_formula(path: &str, text: &str) -> Option<Tape> {
    let in_params = path.rsplit('.').nth(1) == Some("params");
    if !in_params && STRING_KEYS.contains(&last_key(path)) {
        return None;
    }
    let mut ctx = Context::new();
    let root = implicit_expr::parse::parse(&mut ctx, text, &[TIME]).ok()?;
    let tape = Tape::new(&ctx, &[root]).ok()?;
    // A formula of `t` alone reads no variable slot but `t`'s (slot 3).
    let reads_xyz = tape.instrs().iter().any(|i| i.op == Opcode::Var && i.a < 3);
    (!reads_xyz).then_some(tape)
}

/// The last key of a field path (`lights[0].position[1]` → `position`).
fn last_key(path: &str) -> &str {
    let key = path.rsplit('.').next().unwrap_or(path);
    key.split('[').next().unwrap_or(key)
}

/// Every string of the tree that is a formula of `t`, in the order of the text.
fn collect(table: &DeTable<'_>, path: &str, out: &mut Vec<TimeValue>) {
    fn value(v: &toml::Spanned<DeValue<'_>>, path: &str, out: &mut Vec<TimeValue>) {
        match v.get_ref() {
            DeValue::String(s) => {
                if let Some(tape) = time_formula(path, s) {
                    out.push(TimeValue {
                        span: v.span(),
                        path: path.to_string(),
                        tape,
                    });
                }
            }
            DeValue::Array(a) => {
                for (i, e) in a.iter().enumerate() {
                    value(e, &format!("{path}[{i}]"), out);
                }
            }
            DeValue::Table(t) => collect(t, path, out),
            _ => {}
        }
    }
    for (k, v) in table.iter() {
        let p = if path.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{path}.{}", k.get_ref())
        };
        if p == "animation" {
            continue;
        }
        value(v, &p, out);
    }
}
