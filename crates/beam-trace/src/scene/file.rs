//! The TOML scene file format: [`Scene::from_toml`] (whose documentation describes the
//! format in full), [`Scene::load`], the built-in [`DEFAULT_SCENE`] and [`Scene::catalog`].
//!
//! Loading has three stages: the TOML text is parsed into a syntax tree with spans
//! (`toml::de::DeTable`), deserialised into the file's shape (`Raw*` structs, unknown keys
//! refused), then checked and built into a [`Scene`]. Errors of the second stage carry
//! only a byte span; the field path is recovered by finding the key or value of the tree
//! whose span matches it. Errors of the third stage know their field path, and the line
//! and column are looked up in the tree.

use std::collections::{BTreeMap, HashMap};
use std::fmt::Display;
use std::io::Read;
use std::ops::Range;
use std::path::Path;
use std::str::FromStr;

use glam::DVec3;
use implicit_expr::parse::{is_valid_param, parse, suggest};
use implicit_expr::vm::import_vm;
use implicit_expr::{Context, NodeId, catalog};
use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

use super::MAX_GRID_RESOLUTION;
use super::transform::{Affine, Rotation};
use super::{
    AaMode, AreaLight, Csg, Geometry, Leaf, Light, Material, PointLight, PrimaryMode,
    RenderSettings, Scene,
};
use crate::camera::Camera;
use crate::error::Error;
use crate::ibox::{IBox, ival};
use crate::shadow::Patch;

/// The built-in default scene (TOML): the catalog's chubs, a sphere and a cube with a
/// spherical hole (a CSG difference) on a floor slab, one point light, shadows on.
pub const DEFAULT_SCENE: &str = r#"# The built-in default scene of beam-trace: a catalog surface, a sphere given by its
# formula and a CSG difference standing on a floor slab, lit by one point light.

background = [0.08, 0.09, 0.12]
ambient = 0.15

[camera]
eye = [0.0, 2.6, 8.5]
look_at = [0.0, -0.2, 0.0]
up = [0.0, 1.0, 0.0]
fov = 40.0
width = 640
height = 480

[[surfaces]]
name = "chubs"
catalog = "chubs"
transform = { translate = [-2.6, 0.0, 0.0], rotate = [0.0, 25.0, 0.0] }
material = { color = [0.85, 0.45, 0.25], specular = 0.4, shininess = 40.0 }

[[surfaces]]
name = "ball"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
material = { color = [0.3, 0.55, 0.85], specular = 0.6, shininess = 64.0 }

[[surfaces]]
name = "cube"
formula = "max(abs(x), abs(y), abs(z)) - 0.8"
bounds = [[-0.8, -0.8, -0.8], [0.8, 0.8, 0.8]]
transform = { translate = [2.6, -0.45, 0.0], rotate = [0.0, 35.0, 0.0] }
material = { color = [0.45, 0.75, 0.4], specular = 0.3, shininess = 24.0 }

[[surfaces]]
name = "hole"
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
transform = { translate = [2.6, -0.45, 0.0] }
material = { color = [0.9, 0.85, 0.4], specular = 0.3, shininess = 24.0 }

[[surfaces]]
name = "floor"
formula = "y + 1.25"
bounds = [[-6.0, -1.5, -4.0], [6.0, -1.25, 3.0]]
clip = true
material = { color = [0.7, 0.7, 0.68], specular = 0.05, shininess = 8.0 }

[[csg]]
name = "holed-cube"
op = "difference"
children = ["cube", "hole"]

[[lights]]
type = "point"
position = [-5.0, 8.0, 6.0]
color = [1.0, 1.0, 1.0]
intensity = 1.0

[render]
root_finder = "newton-alefeld-hansen"
aa = "none"
shadows = true
"#;

// ---------------------------------------------------------------------------------------
// The file's shape (serde).

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    camera: RawCamera,
    background: Option<[f64; 3]>,
    ambient: Option<f64>,
    #[serde(default)]
    surfaces: Vec<RawSurface>,
    #[serde(default)]
    csg: Vec<RawCsg>,
    #[serde(default)]
    lights: Vec<RawLight>,
    #[serde(default)]
    render: RawRender,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    eye: Option<[f64; 3]>,
    look_at: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fov: Option<f64>,
    width: Option<i64>,
    height: Option<i64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawSurface {
    name: Option<String>,
    formula: Option<String>,
    catalog: Option<String>,
    vm: Option<String>,
    #[serde(default)]
    params: BTreeMap<String, f64>,
    bounds: Option<[[f64; 3]; 2]>,
    transform: Option<RawTransform>,
    clip: Option<bool>,
    #[serde(default)]
    material: RawMaterial,
    visible: Option<bool>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTransform {
    translate: Option<[f64; 3]>,
    rotate: Option<RawRotate>,
    scale: Option<RawScale>,
}

#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "[x, y, z] (degrees about x, then y, then z) or { axis = [x, y, z], angle = degrees }"
)]
enum RawRotate {
    Euler([f64; 3]),
    Axis(RawAxisAngle),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawAxisAngle {
    axis: [f64; 3],
    angle: f64,
}

#[derive(Deserialize)]
#[serde(untagged, expecting = "a number or [sx, sy, sz]")]
enum RawScale {
    Uniform(f64),
    Axes([f64; 3]),
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    color: Option<[f64; 3]>,
    specular: Option<f64>,
    shininess: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCsg {
    name: String,
    op: CsgOp,
    children: Vec<String>,
    visible: Option<bool>,
}

#[derive(Deserialize, Copy, Clone, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum CsgOp {
    Union,
    Intersection,
    Difference,
}

/// A light of the file; a new light type is a new variant (`type = "..."`).
#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
enum RawLight {
    Point {
        position: [f64; 3],
        color: Option<[f64; 3]>,
        intensity: Option<f64>,
    },
    /// An axis-aligned square (`center`, `size`, `normal` axis) or a parallelogram
    /// (`corner`, `edge_u`, `edge_v`).
    Area {
        center: Option<[f64; 3]>,
        size: Option<f64>,
        normal: Option<String>,
        corner: Option<[f64; 3]>,
        edge_u: Option<[f64; 3]>,
        edge_v: Option<[f64; 3]>,
        color: Option<[f64; 3]>,
        intensity: Option<f64>,
    },
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
struct RawRender {
    root_finder: Option<String>,
    epsilon: Option<f64>,
    max_steps: Option<i64>,
    sampling_step: Option<f64>,
    lipschitz: Option<f64>,
    aa: Option<String>,
    iaa_depth: Option<i64>,
    iaa_threshold: Option<f64>,
    primary: Option<String>,
    rays_per_undecided: Option<i64>,
    rays_per_pixel: Option<i64>,
    t_final_width: Option<f64>,
    grid: Option<i64>,
    shadows: Option<bool>,
    shadow_method: Option<String>,
    precision: Option<String>,
}

// ---------------------------------------------------------------------------------------
// Settings parsed from strings (also for command lines).

impl FromStr for PrimaryMode {
    type Err = String;

    /// `screen-boxes` or `per-pixel`.
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "screen-boxes" => Ok(PrimaryMode::ScreenBoxes),
            "per-pixel" => Ok(PrimaryMode::PerPixel),
            _ => {
                let names = ["screen-boxes", "per-pixel"];
                let hint = suggest::did_you_mean(s, names)
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                Err(format!(
                    "unknown primary mode '{s}'{hint} (one of: screen-boxes, per-pixel)"
                ))
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Locations: field paths and line/column numbers.

/// The document being loaded: its name, text and syntax tree (with spans), for messages.
struct Doc<'a> {
    file: &'a str,
    text: &'a str,
    tree: Option<Spanned<DeTable<'a>>>,
}

/// One step of a field path.
enum Seg<'p> {
    Key(&'p str),
    Index(usize),
}

/// `surfaces[0].params.a` → `surfaces`, `[0]`, `params`, `a`.
fn segments(path: &str) -> Vec<Seg<'_>> {
    let mut out = Vec::new();
    for part in path.split('.').filter(|p| !p.is_empty()) {
        let (key, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if !key.is_empty() {
            out.push(Seg::Key(key));
        }
        while let Some(r) = rest.strip_prefix('[') {
            let end = r.find(']').unwrap_or(r.len());
            if let Ok(i) = r[..end].parse() {
                out.push(Seg::Index(i));
            }
            rest = r.get(end + 1..).unwrap_or("");
        }
    }
    out
}

fn table_entry<'t, 'i>(t: &'t DeTable<'i>, key: &str) -> Option<&'t Spanned<DeValue<'i>>> {
    t.iter()
        .find(|(k, _)| k.get_ref().as_ref() == key)
        .map(|(_, v)| v)
}

/// A candidate field for an error span: (exact, width, depth, path).
type Candidate = (bool, usize, usize, String);

fn better(a: &Candidate, b: &Option<Candidate>) -> bool {
    match b {
        None => true,
        Some(b) => match (a.0, b.0) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => a.2 > b.2,
            (false, false) => a.1 < b.1 || (a.1 == b.1 && a.2 > b.2),
        },
    }
}

fn consider(
    span: Range<usize>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    let exact = span == *at;
    if exact || (span.start <= at.start && at.end <= span.end) {
        let c = (exact, span.end - span.start, depth, path.to_string());
        if better(&c, best) {
            *best = Some(c);
        }
    }
}

/// Visits every key and value of `v`, keeping the field whose span fits `at` best.
fn visit(
    v: &DeValue<'_>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    match v {
        DeValue::Table(t) => visit_table(t, at, depth, path, best),
        DeValue::Array(a) => {
            for (i, e) in a.iter().enumerate() {
                let p = format!("{path}[{i}]");
                consider(e.span(), at, depth + 1, &p, best);
                visit(e.get_ref(), at, depth + 1, &p, best);
            }
        }
        _ => {}
    }
}

fn visit_table(
    t: &DeTable<'_>,
    at: &Range<usize>,
    depth: usize,
    path: &str,
    best: &mut Option<Candidate>,
) {
    for (k, v) in t.iter() {
        let p = if path.is_empty() {
            k.get_ref().to_string()
        } else {
            format!("{path}.{}", k.get_ref())
        };
        consider(k.span(), at, depth + 1, &p, best);
        consider(v.span(), at, depth + 1, &p, best);
        visit(v.get_ref(), at, depth + 1, &p, best);
    }
}

/// A serde message with `'` quotes and a did-you-mean for unknown fields and variants.
fn polish(msg: &str) -> String {
    let quoted: Vec<&str> = msg.split('`').skip(1).step_by(2).collect();
    let mut out = msg.trim_end().replace('`', "'");
    if (msg.starts_with("unknown field") || msg.starts_with("unknown variant"))
        && quoted.len() >= 2
        && let Some(h) = suggest::did_you_mean(quoted[0], quoted[1..].iter().copied())
    {
        out.push_str("; ");
        out.push_str(&h);
    }
    out
}

impl<'a> Doc<'a> {
    /// A document without text (a scene built in code).
    fn detached(file: &'a str) -> Self {
        Doc {
            file,
            text: "",
            tree: None,
        }
    }

    /// 1-based line and column (in characters) of byte `offset`.
    fn line_col(&self, offset: usize) -> (usize, usize) {
        let mut offset = offset.min(self.text.len());
        while !self.text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
            .chars()
            .count()
            + 1;
        (line, col)
    }

    fn location(&self, offset: usize) -> String {
        let (line, col) = self.line_col(offset);
        format!(" (line {line}, column {col})")
    }

    /// The span where the field `path` is written, if it is.
    fn span_of(&self, path: &str) -> Option<Range<usize>> {
        let tree = self.tree.as_ref()?;
        let mut segs = segments(path).into_iter();
        let Some(Seg::Key(first)) = segs.next() else {
            return None;
        };
        let mut cur = table_entry(tree.get_ref(), first)?;
        for s in segs {
            cur = match (s, cur.get_ref()) {
                (Seg::Key(k), DeValue::Table(t)) => table_entry(t, k)?,
                (Seg::Index(i), DeValue::Array(a)) => a.get(i)?,
                _ => return None,
            };
        }
        Some(cur.span())
    }

    /// An error at the field `path` (its line and column added when it is written).
    fn err(&self, path: &str, message: impl Display) -> Error {
        self.err_detail(path, message, "")
    }

    /// [`Doc::err`] with `detail` (more lines) after the location.
    fn err_detail(&self, path: &str, message: impl Display, detail: &str) -> Error {
        let loc = self
            .span_of(path)
            .map(|s| self.location(s.start))
            .unwrap_or_default();
        Error::Scene {
            file: self.file.to_string(),
            path: path.to_string(),
            message: format!("{message}{loc}{detail}"),
        }
    }

    /// A TOML syntax error.
    fn syntax_error(&self, e: &toml::de::Error) -> Error {
        let loc = e.span().map(|s| self.location(s.start)).unwrap_or_default();
        Error::Scene {
            file: self.file.to_string(),
            path: String::new(),
            message: format!("invalid TOML{loc}: {}", polish(e.message())),
        }
    }

    /// A deserialisation error: the field path found from its span.
    fn serde_error(&self, e: &toml::de::Error) -> Error {
        let mut path = String::new();
        let mut loc = String::new();
        if let (Some(span), Some(tree)) = (e.span(), &self.tree)
            && !span.is_empty()
        {
            let mut best = None;
            visit_table(tree.get_ref(), &span, 0, "", &mut best);
            if let Some((_, _, _, p)) = best {
                path = p;
            }
            loc = self.location(span.start);
        }
        Error::Scene {
            file: self.file.to_string(),
            path,
            message: format!("{}{loc}", polish(e.message())),
        }
    }
}

// ---------------------------------------------------------------------------------------
// Validation helpers.

const MAX_IMAGE_SIDE: i64 = 16384;
/// Largest number of leaf references of one expanded csg tree.
const MAX_CSG_LEAVES: usize = 10_000;
/// Deepest csg nesting.
const MAX_CSG_DEPTH: usize = 64;
/// Largest `.vm` file read.
const MAX_VM_BYTES: u64 = 256 << 20;

fn fmt3(v: &[f64; 3]) -> String {
    format!("[{}, {}, {}]", v[0], v[1], v[2])
}

impl Doc<'_> {
    fn finite(&self, path: &str, v: f64) -> Result<f64, Error> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be a finite number, got {v}")))
        }
    }

    fn vec3(&self, path: &str, v: [f64; 3]) -> Result<DVec3, Error> {
        if v.iter().all(|x| x.is_finite()) {
            Ok(DVec3::from_array(v))
        } else {
            Err(self.err(path, format!("must be finite, got {}", fmt3(&v))))
        }
    }

    fn positive(&self, path: &str, v: f64) -> Result<f64, Error> {
        let v = self.finite(path, v)?;
        if v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(path, format!("must be positive, got {v}")))
        }
    }

    fn unit(&self, path: &str, v: f64) -> Result<f64, Error> {
        let v = self.finite(path, v)?;
        if (0.0..=1.0).contains(&v) {
            Ok(v)
        } else {
            Err(self.err(path, format!("must lie in [0, 1], got {v}")))
        }
    }

    fn color(&self, path: &str, v: [f64; 3]) -> Result<[f32; 3], Error> {
        self.vec3(path, v)?;
        if v.iter().all(|c| (0.0..=1.0).contains(c)) {
            Ok(v.map(|c| c as f32))
        } else {
            Err(self.err(
                path,
                format!("colour components must lie in [0, 1], got {}", fmt3(&v)),
            ))
        }
    }

    fn int_in(&self, path: &str, v: i64, lo: i64, hi: i64) -> Result<u32, Error> {
        if (lo..=hi).contains(&v) {
            Ok(v as u32)
        } else {
            Err(self.err(path, format!("must be between {lo} and {hi}, got {v}")))
        }
    }

    fn square(&self, path: &str, v: i64) -> Result<u32, Error> {
        let n = self.int_in(path, v, 1, 256)?;
        let r = (1..=16).find(|r| r * r >= n).unwrap_or(16);
        if r * r == n {
            Ok(n)
        } else {
            Err(self.err(
                path,
                format!("must be a square number (1, 4, 9, ..., 256), got {v}"),
            ))
        }
    }
}

// ---------------------------------------------------------------------------------------
// Building the scene.

/// The view of an automatic camera: eye, look-at point and a light above-left of the eye.
fn auto_view(bounds: &IBox, fov_deg: f64) -> (DVec3, DVec3, DVec3) {
    let lo = DVec3::new(bounds[0].inf(), bounds[1].inf(), bounds[2].inf());
    let hi = DVec3::new(bounds[0].sup(), bounds[1].sup(), bounds[2].sup());
    let centre = 0.5 * (lo + hi);
    let diag = (hi - lo).length();
    let dir = DVec3::new(1.0, 0.8, 2.2).normalize();
    let dist = 0.55 * diag / (0.5 * fov_deg.to_radians()).sin();
    let eye = centre + dist * dir;
    let right = (-dir).cross(DVec3::Y).normalize();
    let up = right.cross(-dir);
    let light = eye + diag * (1.2 * up - right);
    (eye, centre, light)
}

fn render_settings(doc: &Doc<'_>, r: &RawRender) -> Result<RenderSettings, Error> {
    let mut s = RenderSettings::default();
    if let Some(name) = &r.root_finder {
        s.root_finder = name.parse().map_err(|m| doc.err("render.root_finder", m))?;
    }
    if let Some(v) = r.epsilon {
        s.root.epsilon = doc.positive("render.epsilon", v)?;
    }
    if let Some(v) = r.max_steps {
        if v < 1 {
            return Err(doc.err("render.max_steps", format!("must be at least 1, got {v}")));
        }
        s.root.max_steps = v as u64;
    }
    if let Some(v) = r.sampling_step {
        let v = doc.positive("render.sampling_step", v)?;
        if v > 1.0 {
            return Err(doc.err(
                "render.sampling_step",
                format!("must be at most 1, got {v}"),
            ));
        }
        s.root.sampling_step = v;
    }
    if let Some(v) = r.lipschitz {
        s.root.lipschitz = doc.positive("render.lipschitz", v)?;
    }
    if let Some(a) = &r.aa {
        s.aa = a.parse().map_err(|m| doc.err("render.aa", m))?;
    }
    let depth = match r.iaa_depth {
        Some(v) => doc.int_in("render.iaa_depth", v, 1, 8)?,
        None => AaMode::IAA_DEPTH,
    };
    let threshold = match r.iaa_threshold {
        Some(v) => doc.positive("render.iaa_threshold", v)?,
        None => AaMode::IAA_THRESHOLD,
    };
    if let AaMode::Iaa { .. } = s.aa {
        s.aa = AaMode::Iaa {
            max_depth: depth,
            threshold,
        };
    }
    if let Some(p) = &r.primary {
        s.primary = p.parse().map_err(|m| doc.err("render.primary", m))?;
    }
    if let Some(v) = r.rays_per_undecided {
        s.rays_per_undecided = doc.square("render.rays_per_undecided", v)?;
    }
    if let Some(v) = r.rays_per_pixel {
        s.rays_per_pixel = doc.square("render.rays_per_pixel", v)?;
    }
    if let Some(v) = r.t_final_width {
        s.t_final_width = doc.positive("render.t_final_width", v)?;
    }
    if let Some(v) = r.grid {
        s.grid_resolution = doc.int_in("render.grid", v, 0, i64::from(MAX_GRID_RESOLUTION))?;
    }
    if let Some(v) = r.shadows {
        s.shadows = v;
    }
    if let Some(m) = &r.shadow_method {
        s.shadow_method = m.parse().map_err(|m| doc.err("render.shadow_method", m))?;
    }
    if let Some(p) = &r.precision {
        s.precision = p.parse().map_err(|m| doc.err("render.precision", m))?;
    }
    Ok(s)
}

fn material(doc: &Doc<'_>, path: &str, m: &RawMaterial) -> Result<Material, Error> {
    let mut out = Material::default();
    if let Some(c) = m.color {
        out.color = doc.color(&format!("{path}.color"), c)?;
    }
    if let Some(v) = m.specular {
        out.specular = doc.unit(&format!("{path}.specular"), v)? as f32;
    }
    if let Some(v) = m.shininess {
        let p = format!("{path}.shininess");
        let v = doc.positive(&p, v)?;
        if v > 1e4 {
            return Err(doc.err(&p, format!("must be at most 10000, got {v}")));
        }
        out.shininess = v as f32;
    }
    Ok(out)
}

fn transform(doc: &Doc<'_>, path: &str, t: &RawTransform) -> Result<Affine, Error> {
    let translate = match t.translate {
        Some(v) => doc.vec3(&format!("{path}.translate"), v)?.to_array(),
        None => [0.0; 3],
    };
    let rp = format!("{path}.rotate");
    let rotate = match &t.rotate {
        None => None,
        Some(RawRotate::Euler(a)) => Some(Rotation::Euler(doc.vec3(&rp, *a)?.to_array())),
        Some(RawRotate::Axis(aa)) => {
            let axis = doc.vec3(&format!("{rp}.axis"), aa.axis)?;
            if axis == DVec3::ZERO {
                return Err(doc.err(&format!("{rp}.axis"), "must not be zero"));
            }
            let angle = doc.finite(&format!("{rp}.angle"), aa.angle)?;
            Some(Rotation::Axis(axis.to_array(), angle))
        }
    };
    let sp = format!("{path}.scale");
    let scale = match t.scale {
        None => [1.0; 3],
        Some(RawScale::Uniform(s)) => [doc.finite(&sp, s)?; 3],
        Some(RawScale::Axes(s)) => doc.vec3(&sp, s)?.to_array(),
    };
    if scale.contains(&0.0) {
        return Err(doc.err(&sp, "scale factors must not be zero"));
    }
    Affine::new(translate, rotate, scale).ok_or_else(|| {
        doc.err(
            path,
            "the transform cannot be inverted in floating point (a scale factor too small \
             or too large)",
        )
    })
}

/// The text of a formula with its error span marked, for messages.
fn formula_snippet(formula: &str, e: &implicit_expr::Error) -> String {
    let implicit_expr::Error::Syntax { span, .. } = e else {
        return String::new();
    };
    let floor = |mut i: usize| {
        i = i.min(formula.len());
        while !formula.is_char_boundary(i) {
            i -= 1;
        }
        i
    };
    let start = floor(span.start);
    let end = floor(span.end.max(start));
    let line_start = formula[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = formula[start..]
        .find('\n')
        .map_or(formula.len(), |i| start + i);
    let end = end.min(line_end);
    const CONTEXT: usize = 40;
    let before: Vec<char> = formula[line_start..start].chars().collect();
    let cut = before.len().saturating_sub(CONTEXT);
    let mut text: String = if cut > 0 { "…".into() } else { String::new() };
    text.extend(&before[cut..]);
    let pad = text.chars().count();
    let marked = formula[start..end].chars().count().max(1);
    text.push_str(&formula[start..end]);
    let after: Vec<char> = formula[end..line_end].chars().collect();
    text.extend(after.iter().take(CONTEXT));
    if after.len() > CONTEXT {
        text.push('…');
    }
    format!(
        "\n    {text}\n    {}{}",
        " ".repeat(pad),
        "^".repeat(marked)
    )
}

/// The parts of a surface before it is placed in the scene's context.
struct Built {
    name: String,
    /// The surface in its own context (with its parameters as variables) and its root.
    ctx: Context,
    root: NodeId,
    /// The value of every variable slot from 3 on.
    params: Vec<f64>,
    bounds: [[f64; 3]; 2],
    clip: bool,
}

fn read_vm(doc: &Doc<'_>, path: &str, file: &str, base: Option<&Path>) -> Result<String, Error> {
    let mut full = Path::new(file).to_path_buf();
    if full.is_relative()
        && let Some(b) = base
    {
        full = b.join(full);
    }
    let fail = |m: String| doc.err(path, format!("cannot read '{}': {m}", full.display()));
    let meta = std::fs::metadata(&full).map_err(|e| fail(e.to_string()))?;
    if !meta.is_file() {
        return Err(fail("not a regular file".into()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(&full)
        .and_then(|f| f.take(MAX_VM_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| fail(e.to_string()))?;
    if bytes.len() as u64 > MAX_VM_BYTES {
        return Err(fail(format!("larger than {MAX_VM_BYTES} bytes")));
    }
    String::from_utf8(bytes).map_err(|_| fail("not UTF-8 text".into()))
}

fn build_surface(
    doc: &Doc<'_>,
    i: usize,
    s: &RawSurface,
    base: Option<&Path>,
) -> Result<Built, Error> {
    let at = |field: &str| format!("surfaces[{i}].{field}");
    let sources: Vec<&str> = [
        ("formula", s.formula.is_some()),
        ("catalog", s.catalog.is_some()),
        ("vm", s.vm.is_some()),
    ]
    .iter()
    .filter(|x| x.1)
    .map(|x| x.0)
    .collect();
    if sources.len() != 1 {
        let found = if sources.is_empty() {
            "none".to_string()
        } else {
            format!("'{}'", sources.join("' and '"))
        };
        return Err(doc.err(
            &format!("surfaces[{i}]"),
            format!("give exactly one of 'formula', 'catalog' or 'vm' (found {found})"),
        ));
    }
    for (k, v) in &s.params {
        doc.finite(&at(&format!("params.{k}")), *v)?;
    }
    let mut ctx = Context::new();
    let (root, name, default_bounds, default_clip) = if let Some(cat) = &s.catalog {
        let surf = catalog::get(cat).map_err(|e| doc.err(&at("catalog"), e))?;
        let names = surf.param_names();
        for k in s.params.keys() {
            if !names.contains(&k.as_str()) {
                let msg = if names.is_empty() {
                    format!("catalog surface '{cat}' has no parameters")
                } else {
                    let hint = suggest::did_you_mean(k, names.iter().copied())
                        .map(|h| format!("; {h}"))
                        .unwrap_or_default();
                    format!(
                        "unknown parameter '{k}' of catalog surface '{cat}'{hint} (parameters: {})",
                        names.join(", ")
                    )
                };
                return Err(doc.err(&at(&format!("params.{k}")), msg));
            }
        }
        let root = surf
            .build(&mut ctx)
            .map_err(|e| doc.err(&at("catalog"), e))?;
        (
            root,
            surf.name.to_string(),
            Some(surf.bounds),
            surf.is_clipped(),
        )
    } else if let Some(formula) = &s.formula {
        for k in s.params.keys() {
            let problem = if ["x", "y", "z"].contains(&k.as_str()) {
                "is a coordinate"
            } else if !is_valid_param(k) {
                "is not a parameter name (letters, digits and '_', not a function or constant)"
            } else {
                continue;
            };
            return Err(doc.err(&at(&format!("params.{k}")), format!("'{k}' {problem}")));
        }
        let names: Vec<&str> = s.params.keys().map(String::as_str).collect();
        let root = parse(&mut ctx, formula, &names)
            .map_err(|e| doc.err_detail(&at("formula"), &e, &formula_snippet(formula, &e)))?;
        (root, format!("surface-{i}"), None, false)
    } else {
        let file = s.vm.as_deref().unwrap_or_default();
        if let Some(k) = s.params.keys().next() {
            return Err(doc.err(
                &at(&format!("params.{k}")),
                "a .vm surface has no parameters",
            ));
        }
        let text = read_vm(doc, &at("vm"), file, base)?;
        let root = import_vm(&mut ctx, &text)
            .map_err(|e| doc.err(&at("vm"), format!("in '{file}': {e}")))?;
        let stem = Path::new(file).file_stem().map_or_else(
            || format!("surface-{i}"),
            |s| s.to_string_lossy().into_owned(),
        );
        (root, stem, None, false)
    };
    let bounds = match (s.bounds, default_bounds) {
        (Some([lo, hi]), _) => {
            doc.vec3(&at("bounds"), lo)?;
            doc.vec3(&at("bounds"), hi)?;
            if (0..3).any(|k| lo[k] >= hi[k]) {
                return Err(doc.err(
                    &at("bounds"),
                    format!(
                        "the first corner must be below the second on every axis, got {} and {}",
                        fmt3(&lo),
                        fmt3(&hi)
                    ),
                ));
            }
            [lo, hi]
        }
        (None, Some((lo, hi))) => [lo, hi],
        (None, None) => {
            return Err(doc.err(
                &format!("surfaces[{i}]"),
                format!(
                    "missing 'bounds' (required for a {} surface): \
                     bounds = [[x0, y0, z0], [x1, y1, z1]]",
                    sources[0]
                ),
            ));
        }
    };
    let mut params = Vec::new();
    for k in 3..ctx.var_count() {
        let var = &ctx.var_names()[k];
        let v = match &s.catalog {
            Some(cat) => s.params.get(var).copied().or_else(|| {
                catalog::get(cat)
                    .ok()
                    .and_then(|c| c.params.iter().find(|p| p.0 == var).map(|p| p.1))
            }),
            None => s.params.get(var).copied(),
        };
        let Some(v) = v else {
            return Err(doc.err(&at("params"), format!("no value for parameter '{var}'")));
        };
        params.push(v);
    }
    Ok(Built {
        name: s.name.clone().unwrap_or(name),
        ctx,
        root,
        params,
        bounds,
        clip: s.clip.unwrap_or(default_clip),
    })
}

/// `max(f, b)` with the exact box function `b` of `[lo, hi]`.
fn clip_to_box(ctx: &mut Context, f: NodeId, [lo, hi]: &[[f64; 3]; 2]) -> Result<NodeId, Error> {
    let vars = [ctx.x(), ctx.y(), ctx.z()];
    let mut out = f;
    for k in 0..3 {
        let l = ctx.constant(lo[k])?;
        let h = ctx.constant(hi[k])?;
        let below = ctx.sub(l, vars[k]);
        let above = ctx.sub(vars[k], h);
        out = ctx.max(out, below);
        out = ctx.max(out, above);
    }
    Ok(out)
}

/// The local coordinates `A · p + b` as nodes of `ctx`.
fn local_coordinates(ctx: &mut Context, aff: &Affine) -> Result<[NodeId; 3], Error> {
    let xyz = [ctx.x(), ctx.y(), ctx.z()];
    if aff.is_identity() {
        return Ok(xyz);
    }
    let mut out = xyz;
    for (i, o) in out.iter_mut().enumerate() {
        let mut acc: Option<NodeId> = None;
        for (j, &v) in xyz.iter().enumerate() {
            let c = aff.a[i][j];
            let term = if c == 0.0 {
                continue;
            } else if c == 1.0 {
                v
            } else if c == -1.0 {
                ctx.neg(v)
            } else {
                let k = ctx.constant(c)?;
                ctx.mul(k, v)
            };
            acc = Some(match acc {
                None => term,
                Some(a) => ctx.add(a, term),
            });
        }
        let mut e = match acc {
            Some(e) => e,
            None => ctx.constant(0.0)?,
        };
        if aff.b[i] != 0.0 {
            let k = ctx.constant(aff.b[i])?;
            e = ctx.add(e, k);
        }
        *o = e;
    }
    Ok(out)
}

/// Places a built surface in the scene context: parameters bound, clipped, transformed.
fn place(
    doc: &Doc<'_>,
    i: usize,
    b: &mut Built,
    aff: &Affine,
    geo: &mut Context,
) -> Result<(NodeId, IBox), Error> {
    let path = format!("surfaces[{i}]");
    let wrap = |e: Error| doc.err(&path, e);
    let mut root = b.root;
    if b.clip {
        root = clip_to_box(&mut b.ctx, root, &b.bounds).map_err(wrap)?;
    }
    let mut map = local_coordinates(geo, aff).map_err(wrap)?.to_vec();
    for &v in &b.params {
        map.push(geo.constant(v).map_err(|e| wrap(e.into()))?);
    }
    if map.len() != b.ctx.var_count() {
        return Err(doc.err(&path, "internal error: variable slots do not match"));
    }
    let node = geo.copy_graph(&b.ctx, root, |_, v| map[v.index()]);
    let [lo, hi] = b.bounds;
    let local: IBox = std::array::from_fn(|k| ival(lo[k], hi[k]));
    let world = if aff.is_identity() {
        Some(local)
    } else {
        aff.world_bounds(&local)
    };
    let world = world.ok_or_else(|| {
        doc.err(
            &format!("{path}.transform"),
            "the transformed bounds are not finite (or the map is nearly singular)",
        )
    })?;
    Ok((node, world))
}

/// What a csg child name refers to.
#[derive(Copy, Clone, PartialEq, Eq, Debug)]
enum Ref {
    Surface(usize),
    Csg(usize),
}

fn ref_path(r: Ref) -> String {
    match r {
        Ref::Surface(i) => format!("surfaces[{i}]"),
        Ref::Csg(j) => format!("csg[{j}]"),
    }
}

/// Checks the csg nodes: children exist, counts, no cycle, bounded size. Returns the
/// resolved children and a topological order (children first).
fn resolve_csg(
    doc: &Doc<'_>,
    csg: &[RawCsg],
    names: &HashMap<&str, Ref>,
    all_names: &[&str],
) -> Result<(Vec<Vec<Ref>>, Vec<usize>), Error> {
    let mut kids = Vec::with_capacity(csg.len());
    for (j, c) in csg.iter().enumerate() {
        let n = c.children.len();
        let bad = match c.op {
            CsgOp::Difference if n != 2 => Some("'difference' needs exactly 2 children"),
            CsgOp::Union | CsgOp::Intersection if n < 2 => Some("needs at least 2 children"),
            _ => None,
        };
        if let Some(m) = bad {
            return Err(doc.err(&format!("csg[{j}].children"), format!("{m}, got {n}")));
        }
        let mut refs = Vec::with_capacity(n);
        for (k, child) in c.children.iter().enumerate() {
            let Some(&r) = names.get(child.as_str()) else {
                let hint = suggest::did_you_mean(child, all_names.iter().copied())
                    .map(|h| format!("; {h}"))
                    .unwrap_or_default();
                return Err(doc.err(
                    &format!("csg[{j}].children[{k}]"),
                    format!("unknown surface or csg node '{child}'{hint}"),
                ));
            };
            refs.push(r);
        }
        kids.push(refs);
    }
    // Kahn's algorithm over the csg → csg edges: children before parents.
    let mut pending: Vec<usize> = kids
        .iter()
        .map(|k| k.iter().filter(|r| matches!(r, Ref::Csg(_))).count())
        .collect();
    let mut parents: Vec<Vec<usize>> = vec![Vec::new(); csg.len()];
    for (j, k) in kids.iter().enumerate() {
        for r in k {
            if let Ref::Csg(c) = r {
                parents[*c].push(j);
            }
        }
    }
    let mut order: Vec<usize> = (0..csg.len()).filter(|&j| pending[j] == 0).collect();
    let mut next = 0;
    while next < order.len() {
        let j = order[next];
        next += 1;
        for &p in &parents[j] {
            pending[p] -= 1;
            if pending[p] == 0 {
                order.push(p);
            }
        }
    }
    if order.len() < csg.len() {
        // Every remaining node lies on or leads to a cycle: walk to a repeat.
        let start = (0..csg.len()).find(|&j| pending[j] > 0).unwrap_or(0);
        let mut seen = vec![usize::MAX; csg.len()];
        let mut walk = vec![start];
        let mut j = start;
        loop {
            seen[j] = walk.len() - 1;
            let Some((k, c)) = kids[j].iter().enumerate().find_map(|(k, r)| match r {
                Ref::Csg(c) if pending[*c] > 0 => Some((k, *c)),
                _ => None,
            }) else {
                break;
            };
            if seen[c] != usize::MAX {
                let cycle: Vec<&str> = walk[seen[c]..]
                    .iter()
                    .chain(std::iter::once(&c))
                    .map(|&n| csg[n].name.as_str())
                    .collect();
                return Err(doc.err(
                    &format!("csg[{j}].children[{k}]"),
                    format!("csg cycle: {}", cycle.join(" -> ")),
                ));
            }
            walk.push(c);
            j = c;
        }
        return Err(doc.err(&format!("csg[{start}]"), "csg cycle"));
    }
    let mut size = vec![0usize; csg.len()];
    let mut depth = vec![0usize; csg.len()];
    for &j in &order {
        for r in &kids[j] {
            let (s, d) = match *r {
                Ref::Surface(_) => (1, 0),
                Ref::Csg(c) => (size[c], depth[c]),
            };
            size[j] = size[j].saturating_add(s);
            depth[j] = depth[j].max(d + 1);
        }
        if size[j] > MAX_CSG_LEAVES {
            return Err(doc.err(
                &format!("csg[{j}]"),
                format!("the tree expands to more than {MAX_CSG_LEAVES} leaves"),
            ));
        }
        if depth[j] > MAX_CSG_DEPTH {
            return Err(doc.err(
                &format!("csg[{j}]"),
                format!("csg nodes nest deeper than {MAX_CSG_DEPTH} levels"),
            ));
        }
    }
    Ok((kids, order))
}

fn csg_tree(j: usize, csg: &[RawCsg], kids: &[Vec<Ref>], leaf_of: &[usize]) -> Csg {
    let child = |r: &Ref| match *r {
        Ref::Surface(i) => Csg::Leaf(leaf_of[i]),
        Ref::Csg(c) => csg_tree(c, csg, kids, leaf_of),
    };
    let ch: Vec<Csg> = kids[j].iter().map(child).collect();
    match csg[j].op {
        CsgOp::Union => Csg::Union(ch),
        CsgOp::Intersection => Csg::Intersection(ch),
        CsgOp::Difference => {
            let mut it = ch.into_iter();
            match (it.next(), it.next()) {
                (Some(a), Some(b)) => Csg::Difference(Box::new(a), Box::new(b)),
                // Unreachable after `resolve_csg`; an empty union keeps this panic-free.
                _ => Csg::Union(Vec::new()),
            }
        }
    }
}

fn camera(doc: &Doc<'_>, c: &RawCamera, bounds: &IBox) -> Result<(Camera, Option<DVec3>), Error> {
    let fov = match c.fov {
        Some(v) => {
            let v = doc.finite("camera.fov", v)?;
            if !(v > 0.0 && v < 180.0) {
                return Err(doc.err(
                    "camera.fov",
                    format!("must lie strictly between 0 and 180 degrees, got {v}"),
                ));
            }
            v
        }
        None => 40.0,
    };
    let width = doc.int_in("camera.width", c.width.unwrap_or(640), 1, MAX_IMAGE_SIDE)?;
    let height = doc.int_in("camera.height", c.height.unwrap_or(480), 1, MAX_IMAGE_SIDE)?;
    let up = match c.up {
        Some(v) => doc.vec3("camera.up", v)?,
        None => DVec3::Y,
    };
    if up == DVec3::ZERO {
        return Err(doc.err("camera.up", "must not be zero"));
    }
    let (eye, look_at, light) = match (c.eye, c.look_at) {
        (Some(e), Some(l)) => (
            doc.vec3("camera.eye", e)?,
            doc.vec3("camera.look_at", l)?,
            None,
        ),
        (None, None) => {
            let (e, l, light) = auto_view(bounds, fov);
            (e, l, Some(light))
        }
        (Some(_), None) | (None, Some(_)) => {
            return Err(doc.err(
                "camera",
                "give both 'eye' and 'look_at', or neither for an automatic camera",
            ));
        }
    };
    if eye == look_at {
        return Err(doc.err("camera.look_at", "must differ from camera.eye"));
    }
    let forward = (look_at - eye).normalize();
    if !forward.is_finite() || forward.cross(up.normalize()).length() < 1e-9 {
        return Err(doc.err("camera.up", "must not be parallel to the view direction"));
    }
    let cam =
        Camera::new(eye, look_at, up, fov, width, height).map_err(|e| doc.err("camera", e))?;
    Ok((cam, light))
}

fn lights(doc: &Doc<'_>, raw: &[RawLight]) -> Result<Vec<Light>, Error> {
    let mut out = Vec::with_capacity(raw.len());
    for (i, l) in raw.iter().enumerate() {
        let at = |field: &str| format!("lights[{i}].{field}");
        let light_color = |color: &Option<[f64; 3]>, intensity: Option<f64>| {
            let color = doc.color(&at("color"), color.unwrap_or([1.0; 3]))?;
            let k = doc.finite(&at("intensity"), intensity.unwrap_or(1.0))?;
            if k < 0.0 {
                return Err(doc.err(&at("intensity"), format!("must not be negative, got {k}")));
            }
            let color = color.map(|c| c * k as f32);
            if !color.iter().all(|c| c.is_finite()) {
                return Err(doc.err(&at("intensity"), format!("is too large, got {k}")));
            }
            Ok(color)
        };
        match l {
            RawLight::Point {
                position,
                color,
                intensity,
            } => {
                let position = doc.vec3(&at("position"), *position)?;
                let color = light_color(color, *intensity)?;
                out.push(Light::Point(PointLight { position, color }));
            }
            RawLight::Area {
                center,
                size,
                normal,
                corner,
                edge_u,
                edge_v,
                color,
                intensity,
            } => {
                let color = light_color(color, *intensity)?;
                let patch = area_patch(
                    doc,
                    i,
                    *center,
                    *size,
                    normal.as_deref(),
                    *corner,
                    *edge_u,
                    *edge_v,
                )?;
                out.push(Light::Area(AreaLight { patch, color }));
            }
        }
    }
    Ok(out)
}

/// The shape of area light `i`: a square (`center`, `size`, `normal`) or a parallelogram
/// (`corner`, `edge_u`, `edge_v`), never a mix.
#[allow(clippy::too_many_arguments)]
fn area_patch(
    doc: &Doc<'_>,
    i: usize,
    center: Option<[f64; 3]>,
    size: Option<f64>,
    normal: Option<&str>,
    corner: Option<[f64; 3]>,
    edge_u: Option<[f64; 3]>,
    edge_v: Option<[f64; 3]>,
) -> Result<Patch, Error> {
    let at = |field: &str| format!("lights[{i}].{field}");
    let square = center.is_some() || size.is_some() || normal.is_some();
    let parallelogram = corner.is_some() || edge_u.is_some() || edge_v.is_some();
    let forms = "an area light is a square (center, size, normal) or a parallelogram \
                 (corner, edge_u, edge_v)";
    let missing = |f: &str| {
        doc.err(
            &format!("lights[{i}]"),
            format!("missing field '{f}' ({forms})"),
        )
    };
    match (square, parallelogram) {
        (true, true) => Err(doc.err(
            &at("corner"),
            format!("{forms}, not both: remove center/size/normal or corner/edge_u/edge_v"),
        )),
        (false, false) => Err(doc.err(&format!("lights[{i}]"), format!("{forms}; none given"))),
        (true, false) => {
            let c = doc.vec3(&at("center"), center.ok_or_else(|| missing("center"))?)?;
            let s = doc.finite(&at("size"), size.ok_or_else(|| missing("size"))?)?;
            if s < 0.0 {
                return Err(doc.err(&at("size"), format!("must not be negative, got {s}")));
            }
            let axis = match normal.ok_or_else(|| missing("normal"))? {
                "x" => 0,
                "y" => 1,
                "z" => 2,
                other => {
                    return Err(doc.err(
                        &at("normal"),
                        format!("must be the axis \"x\", \"y\" or \"z\", got \"{other}\""),
                    ));
                }
            };
            Ok(Patch::square(c, s, axis))
        }
        (false, true) => {
            let corner = doc.vec3(&at("corner"), corner.ok_or_else(|| missing("corner"))?)?;
            let edge_u = doc.vec3(&at("edge_u"), edge_u.ok_or_else(|| missing("edge_u"))?)?;
            let edge_v = doc.vec3(&at("edge_v"), edge_v.ok_or_else(|| missing("edge_v"))?)?;
            Ok(Patch {
                corner,
                edge_u,
                edge_v,
            })
        }
    }
}

/// Builds and checks the whole scene. Also returns the automatic light position when the
/// camera is automatic.
fn build(
    doc: &Doc<'_>,
    raw: &RawScene,
    base: Option<&Path>,
) -> Result<(Scene, Option<DVec3>), Error> {
    let background = match raw.background {
        Some(c) => doc.color("background", c)?,
        None => [0.08, 0.09, 0.12],
    };
    let ambient = match raw.ambient {
        Some(v) => doc.unit("ambient", v)? as f32,
        None => 0.15,
    };
    let settings = render_settings(doc, &raw.render)?;
    if raw.surfaces.is_empty() {
        return Err(doc.err(
            "surfaces",
            "the scene has no surfaces (add a [[surfaces]] table)",
        ));
    }
    // Surfaces: source, parameters, bounds, transform, material.
    let mut built = Vec::with_capacity(raw.surfaces.len());
    for (i, s) in raw.surfaces.iter().enumerate() {
        let b = build_surface(doc, i, s, base)?;
        let aff = match &s.transform {
            Some(t) => transform(doc, &format!("surfaces[{i}].transform"), t)?,
            None => Affine::new([0.0; 3], None, [1.0; 3])
                .ok_or_else(|| doc.err("surfaces", "internal error: identity"))?,
        };
        let m = material(doc, &format!("surfaces[{i}].material"), &s.material)?;
        built.push((b, aff, m));
    }
    // Names: one namespace for surfaces and csg nodes.
    let mut names: HashMap<&str, Ref> = HashMap::new();
    let mut order_names: Vec<&str> = Vec::new();
    let entries = built
        .iter()
        .enumerate()
        .map(|(i, b)| (b.0.name.as_str(), Ref::Surface(i)))
        .chain(
            raw.csg
                .iter()
                .enumerate()
                .map(|(j, c)| (c.name.as_str(), Ref::Csg(j))),
        );
    for (name, r) in entries {
        if let Some(&prev) = names.get(name) {
            let path = match r {
                Ref::Surface(i) if raw.surfaces[i].name.is_none() => ref_path(r),
                _ => format!("{}.name", ref_path(r)),
            };
            return Err(doc.err(
                &path,
                format!(
                    "duplicate name '{name}' (also the name of {}); give each surface and csg \
                     node its own name",
                    ref_path(prev)
                ),
            ));
        }
        names.insert(name, r);
        order_names.push(name);
    }
    let (kids, _) = resolve_csg(doc, &raw.csg, &names, &order_names)?;
    // Which nodes are drawn on their own, and which surfaces are used at all.
    let mut used_surface = vec![false; raw.surfaces.len()];
    let mut used_csg = vec![false; raw.csg.len()];
    for k in &kids {
        for r in k {
            match *r {
                Ref::Surface(i) => used_surface[i] = true,
                Ref::Csg(j) => used_csg[j] = true,
            }
        }
    }
    let mut tops: Vec<Ref> = Vec::new();
    for (i, s) in raw.surfaces.iter().enumerate() {
        if s.visible.unwrap_or(true) && !used_surface[i] {
            tops.push(Ref::Surface(i));
        }
    }
    for (j, c) in raw.csg.iter().enumerate() {
        if c.visible.unwrap_or(true) && !used_csg[j] {
            tops.push(Ref::Csg(j));
        }
    }
    if tops.is_empty() {
        return Err(doc.err(
            "surfaces",
            "nothing to draw: every surface and csg node has visible = false",
        ));
    }
    let mut drawn = vec![false; raw.surfaces.len()];
    let mut stack = tops.clone();
    let mut seen_csg = vec![false; raw.csg.len()];
    while let Some(r) = stack.pop() {
        match r {
            Ref::Surface(i) => drawn[i] = true,
            Ref::Csg(j) if !seen_csg[j] => {
                seen_csg[j] = true;
                stack.extend(kids[j].iter().copied());
            }
            Ref::Csg(_) => {}
        }
    }
    // Leaves: the drawn surfaces, placed in one context.
    let mut geo = Context::new();
    let mut leaves = Vec::new();
    let mut leaf_of = vec![usize::MAX; raw.surfaces.len()];
    for (i, (b, aff, m)) in built.iter_mut().enumerate() {
        if !drawn[i] {
            continue;
        }
        let (node, bounds) = place(doc, i, b, aff, &mut geo)?;
        leaf_of[i] = leaves.len();
        leaves.push(Leaf {
            name: b.name.clone(),
            node,
            material: *m,
            bounds,
            clipped: b.clip,
        });
    }
    let objects: Vec<Csg> = tops
        .iter()
        .map(|r| match *r {
            Ref::Surface(i) => Csg::Leaf(leaf_of[i]),
            Ref::Csg(j) => csg_tree(j, &raw.csg, &kids, &leaf_of),
        })
        .collect();
    let geometry = Geometry::new(geo, leaves, objects).map_err(|e| doc.err("", e))?;
    let (camera, auto_light) = camera(doc, &raw.camera, &geometry.bounds())?;
    let lights = lights(doc, &raw.lights)?;
    Ok((
        Scene {
            name: doc.file.to_string(),
            camera,
            background,
            ambient,
            lights,
            geometry,
            settings,
        },
        auto_light,
    ))
}

impl Scene {
    /// Reads a scene from TOML text.
    ///
    /// `file` names the text in messages; `base_dir` is the folder against which relative
    /// `.vm` paths are resolved (the working directory when `None`). Never panics, whatever
    /// the text.
    ///
    /// # Example
    ///
    /// ```toml
    /// background = [0.08, 0.09, 0.12]   # optional, default [0.08, 0.09, 0.12]
    /// ambient = 0.15                    # optional, default 0.15
    ///
    /// [camera]                          # required (may be empty: an automatic camera)
    /// eye = [0.0, 2.0, 7.0]             # eye and look_at: both or neither
    /// look_at = [0.0, 0.0, 0.0]
    /// up = [0.0, 1.0, 0.0]              # default [0, 1, 0]
    /// fov = 40.0                        # vertical, degrees, default 40
    /// width = 640                       # default 640
    /// height = 480                      # default 480
    ///
    /// [[surfaces]]
    /// name = "knot"                     # default: the catalog name, the .vm file stem, or surface-N
    /// catalog = "orthocircle"           # exactly one of catalog, formula, vm
    /// params = { a = 0.1 }              # overrides the catalog's defaults
    /// transform = { translate = [-2.0, 0.0, 0.0], rotate = [0.0, 30.0, 0.0], scale = 1.2 }
    /// material = { color = [0.9, 0.5, 0.2], specular = 0.4, shininess = 40.0 }
    ///
    /// [[surfaces]]
    /// name = "ball"
    /// formula = "x^2 + y^2 + z^2 - r^2"
    /// params = { r = 1.0 }
    /// bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]   # required for formula and vm
    /// visible = false                   # only used by the csg node below
    ///
    /// [[surfaces]]
    /// name = "cube"
    /// formula = "max(abs(x), abs(y), abs(z)) - 0.8"
    /// bounds = [[-0.8, -0.8, -0.8], [0.8, 0.8, 0.8]]
    ///
    /// [[csg]]
    /// name = "holed-cube"
    /// op = "difference"                 # union | intersection | difference
    /// children = ["cube", "ball"]       # surfaces or other csg nodes
    ///
    /// [[lights]]
    /// type = "point"
    /// position = [-4.0, 6.0, 5.0]
    /// color = [1.0, 1.0, 1.0]           # default white
    /// intensity = 1.0                   # default 1
    ///
    /// [render]                          # optional; every key optional
    /// root_finder = "newton-alefeld-hansen"
    /// epsilon = 1e-6
    /// max_steps = 100000
    /// aa = "none"                       # none | iaa | ss:N (N × N rays per pixel, N ≤ 16)
    /// iaa_depth = 4
    /// iaa_threshold = 0.05
    /// primary = "screen-boxes"          # screen-boxes | per-pixel
    /// rays_per_undecided = 9
    /// rays_per_pixel = 1
    /// t_final_width = 0.05
    /// grid = 16
    /// shadows = true
    /// precision = "f64"                 # f64 | f32 (interval evaluation of the scene function)
    /// ```
    ///
    /// # Reference
    ///
    /// Unknown keys are errors everywhere. Numbers must be finite (TOML's `nan` and `inf` are
    /// refused); integers are accepted where a float is expected. Colours are `[r, g, b]` in
    /// `[0, 1]`.
    ///
    /// **Top level**: `background` (colour), `ambient` (in `[0, 1]`), the tables `camera`,
    /// `render`, and the arrays of tables `surfaces` (at least one), `csg` and `lights`.
    ///
    /// **`[camera]`**: `eye` and `look_at` (points), `up` (not zero, not parallel to the view
    /// direction), `fov` (in `(0, 180)`), `width` and `height` (1 to 16384). Without `eye`
    /// and `look_at` the camera looks at the centre of the scene bounds from the direction
    /// `(1, 0.8, 2.2)`, far enough for the bounding sphere to fit the field of view.
    ///
    /// **`[[surfaces]]`**: a leaf surface `f = 0`, solid where `f < 0`.
    /// * the source, exactly one of: `formula` (the formula language of
    ///   [`implicit_expr::parse`] in `x`, `y`, `z` and the names of `params`), `catalog` (a
    ///   name of [`implicit_expr::catalog`]), or `vm` (a `.vm` file, see [`implicit_expr::vm`];
    ///   a relative path is resolved against the scene file's folder).
    /// * `params`: a table of numbers. For a formula it declares its parameters; for a catalog
    ///   surface it overrides the defaults (unknown names are errors); a `.vm` file has none.
    ///   Values are the doubles nearest the decimals written, bound as constants.
    /// * `bounds = [[x0, y0, z0], [x1, y1, z1]]` with `x0 < x1` etc., in the surface's own
    ///   coordinates: the box that holds the surface (required for `formula` and `vm`; the
    ///   catalog's box by default). Rays search for the scene's surfaces only inside the hull of
    ///   the boxes, so a surface reaching outside its box may be cut there.
    /// * `clip`: intersect the solid with its box, `max(f, b)` with the box function
    ///   `b = max(x0 − x, x − x1, y0 − y, y − y1, z0 − z, z − z1)` (exact constants, zero set
    ///   inside the closed box). Default: the catalog's [`is_clipped`], else `false`.
    /// * `transform = { translate = [..], rotate = .., scale = .. }`, each optional: the surface
    ///   is scaled (`scale = s` or `[sx, sy, sz]`, no zero factor), then rotated (`rotate =
    ///   [ax, ay, az]`: degrees about `x`, then `y`, then `z`; or `{ axis = [..], angle = deg }`),
    ///   then translated: `p_world = M · p + t` with `M = R · S`. The leaf is `f(A · p + b)` with
    ///   `A ≈ M⁻¹`, `b ≈ −A · t` computed in `f64`: the rendered surface is the zero set for
    ///   those `f64` coefficients (exact at multiples of 90°), and its world box is proven to
    ///   enclose it (see `transform.rs`).
    /// * `material = { color, specular, shininess }`: Phong material; `specular` in `[0, 1]`,
    ///   `shininess` positive (defaults: [`Material::default`]).
    /// * `visible` (default `true`): `false` keeps the surface out of the picture unless a csg
    ///   node uses it. A surface that a csg node uses is never drawn on its own.
    ///
    /// **`[[csg]]`**: `name`, `op` (`union` and `intersection`: 2 or more children;
    /// `difference`: exactly 2, the first minus the second), `children` (names of surfaces or
    /// csg nodes, in any order; cycles are errors), `visible` as for surfaces. The drawn
    /// objects are the visible surfaces and csg nodes that no csg node uses; each leaf keeps
    /// its own material. Names of surfaces and csg nodes share one namespace and are unique.
    ///
    /// **`[[lights]]`**: `type = "point"` with `position`, `color` and `intensity` (`≥ 0`);
    /// the light's colour is `color · intensity`. `type = "area"` with the same `color` and
    /// `intensity` is a uniform parallelogram: an axis-aligned square `center`, `size`
    /// (`≥ 0`), `normal` (`"x"`, `"y"` or `"z"`), or `corner`, `edge_u`, `edge_v`. An area
    /// light of size zero is a point light.
    ///
    /// **`[render]`**: `root_finder` (a [`RootMethod`] name), `epsilon` (positive),
    /// `max_steps` (at least 1), `sampling_step` (in `(0, 1]`) and `lipschitz` (positive) for
    /// the unreliable baselines, `aa` (see [`AaMode`]'s [`FromStr`]), `iaa_depth` (1 to 8) and
    /// `iaa_threshold` (positive) for `aa = "iaa"`, `primary` (see [`PrimaryMode`]'s
    /// [`FromStr`]), `rays_per_undecided` and `rays_per_pixel` (square numbers 1 to 256),
    /// `t_final_width` (positive), `grid` (0 to 256; 0: no grid), `shadows`,
    /// `shadow_method` (see [`ShadowSpec`](crate::shadow::ShadowSpec); default `beam:7`),
    /// `precision` (`"f64"` or `"f32"`, see [`Precision`](crate::ray::Precision); default
    /// `"f64"`).
    ///
    /// # Errors
    ///
    /// Every problem is an [`Error::Scene`] naming the file, the field path
    /// (`lights[1].position`, `surfaces[0].params.a`, `csg[2].children[1]`) and the problem,
    /// with the line and column where the field is written:
    ///
    /// ```
    /// use beam_trace::Scene;
    ///
    /// let text = "[camera]\n[[surfaces]]\ncatalog = \"sphre\"\n";
    /// let err = Scene::from_toml(text, "my.toml", None).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "my.toml: surfaces[0].catalog: unknown surface 'sphre'; did you mean 'sphere'? \
    ///      (line 3, column 11)"
    /// );
    /// ```
    ///
    /// [`is_clipped`]: implicit_expr::catalog::Surface::is_clipped
    /// [`RootMethod`]: crate::root::RootMethod
    pub fn from_toml(text: &str, file: &str, base_dir: Option<&Path>) -> Result<Scene, Error> {
        let mut doc = Doc {
            file,
            text,
            tree: None,
        };
        let tree = DeTable::parse(text).map_err(|e| doc.syntax_error(&e))?;
        doc.tree = Some(tree.clone());
        let raw = RawScene::deserialize(toml::Deserializer::from(tree))
            .map_err(|e| doc.serde_error(&e))?;
        build(&doc, &raw, base_dir).map(|(s, _)| s)
    }

    /// Reads the scene file at `path`; relative `.vm` paths are resolved against its folder.
    ///
    /// # Errors
    /// [`Error::Io`] naming the path when it cannot be read, otherwise as
    /// [`Scene::from_toml`].
    pub fn load(path: &Path) -> Result<Scene, Error> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let name = path.display().to_string();
        Scene::from_toml(&text, &name, path.parent())
    }

    /// The built-in scene, [`DEFAULT_SCENE`].
    pub fn default_scene() -> Scene {
        Scene::from_toml(DEFAULT_SCENE, "<built-in>", None)
            .expect("the built-in scene is valid (checked by a test)")
    }

    /// A scene of the catalog surface `name` alone (default parameters, its box, clipped
    /// where the catalog says so, default material) with an automatic camera looking at its
    /// box (field of view 40°) and one white point light above-left of the camera.
    ///
    /// # Errors
    /// [`Error::Scene`] for an unknown name (with the closest name as a hint) or an image
    /// size outside 1 to 16384.
    pub fn catalog(name: &str, width: u32, height: u32) -> Result<Scene, Error> {
        let file = format!("catalog:{name}");
        let doc = Doc::detached(&file);
        let raw = RawScene {
            camera: RawCamera {
                width: Some(width.into()),
                height: Some(height.into()),
                ..RawCamera::default()
            },
            background: None,
            ambient: None,
            surfaces: vec![RawSurface {
                name: Some(name.to_string()),
                catalog: Some(name.to_string()),
                ..RawSurface::default()
            }],
            csg: Vec::new(),
            lights: Vec::new(),
            render: RawRender::default(),
        };
        let (mut scene, light) = build(&doc, &raw, None)?;
        if let Some(position) = light {
            scene.lights.push(Light::Point(PointLight {
                position,
                color: [1.0; 3],
            }));
        }
        Ok(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_of_paths() {
        let s = segments("csg[2].children[1]");
        assert!(matches!(
            s[..],
            [
                Seg::Key("csg"),
                Seg::Index(2),
                Seg::Key("children"),
                Seg::Index(1)
            ]
        ));
        assert!(segments("").is_empty());
        assert_eq!(segments("a[x].b[").len(), 2);
    }

    #[test]
    fn aa_strings() {
        assert_eq!("none".parse::<AaMode>(), Ok(AaMode::None));
        assert_eq!("ss:3".parse::<AaMode>(), Ok(AaMode::Supersample(3)));
        assert!("ss:0".parse::<AaMode>().is_err());
        assert!("ss:17".parse::<AaMode>().is_err());
        assert!("ss:".parse::<AaMode>().is_err());
        assert!(matches!(
            "iaa".parse::<AaMode>(),
            Ok(AaMode::Iaa { max_depth: 4, .. })
        ));
        assert_eq!(
            "per-pixel".parse::<PrimaryMode>(),
            Ok(PrimaryMode::PerPixel)
        );
        assert!(
            "per_pixel"
                .parse::<PrimaryMode>()
                .unwrap_err()
                .contains("'per-pixel'")
        );
    }

    #[test]
    fn snippet_marks_the_span() {
        let e = parse(&mut Context::new(), "x + sine(y)", &[]).unwrap_err();
        assert_eq!(
            formula_snippet("x + sine(y)", &e),
            "\n    x + sine(y)\n        ^^^^"
        );
    }

    #[test]
    fn paths_of_serde_errors() {
        let text = "[camera]\n[[surfaces]]\ncatalog = 'sphere'\n[[surfaces]]\ncatalog = 'chubs'\nmaterial = { colour = [1, 1, 1] }\n";
        let e = Scene::from_toml(text, "t", None).unwrap_err();
        let Error::Scene { path, message, .. } = e else {
            panic!()
        };
        assert_eq!(path, "surfaces[1].material.colour");
        assert!(
            message.starts_with("unknown field 'colour', expected"),
            "{message}"
        );
        assert!(message.contains("did you mean 'color'?"), "{message}");
        assert!(message.ends_with("(line 6, column 14)"), "{message}");
    }
}
