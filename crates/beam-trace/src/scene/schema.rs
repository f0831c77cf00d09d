//! The scene file's shape: the `Raw*` structs that serde fills from the TOML text, unknown
//! keys refused. Checked and built into a [`Scene`](super::Scene) by the other modules.

use std::collections::BTreeMap;

use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawScene {
    pub(super) camera: RawCamera,
    pub(super) background: Option<[f64; 3]>,
    pub(super) ambient: Option<f64>,
    #[serde(default)]
    pub(super) surfaces: Vec<RawSurface>,
    #[serde(default)]
    pub(super) csg: Vec<RawCsg>,
    #[serde(default)]
    pub(super) meshes: Vec<RawMesh>,
    #[serde(default)]
    pub(super) lights: Vec<RawLight>,
    #[serde(default)]
    pub(super) render: RawRender,
    /// Read by [`Animation`](super::Animation); a frame's file keeps it.
    #[allow(dead_code)]
    pub(super) animation: Option<serde::de::IgnoredAny>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCamera {
    pub(super) eye: Option<[f64; 3]>,
    pub(super) look_at: Option<[f64; 3]>,
    pub(super) up: Option<[f64; 3]>,
    pub(super) fov: Option<f64>,
    pub(super) width: Option<i64>,
    pub(super) height: Option<i64>,
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawSurface {
    pub(super) name: Option<String>,
    pub(super) formula: Option<String>,
    pub(super) catalog: Option<String>,
    pub(super) vm: Option<String>,
    #[serde(default)]
    pub(super) params: BTreeMap<String, f64>,
    pub(super) bounds: Option<[[f64; 3]; 2]>,
    pub(super) transform: Option<RawTransform>,
    pub(super) clip: Option<bool>,
    #[serde(default)]
    pub(super) material: RawMaterial,
    pub(super) visible: Option<bool>,
}

/// A triangle mesh: an OBJ file or inline polygons.
#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMesh {
    pub(super) name: Option<String>,
    pub(super) obj: Option<String>,
    pub(super) polygons: Option<Vec<Vec<[f64; 3]>>>,
    pub(super) transform: Option<RawTransform>,
    #[serde(default)]
    pub(super) material: RawMaterial,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawTransform {
    pub(super) translate: Option<[f64; 3]>,
    pub(super) rotate: Option<RawRotate>,
    pub(super) scale: Option<RawScale>,
}

#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "[x, y, z] (degrees about x, then y, then z) or { axis = [x, y, z], angle = degrees }"
)]
pub(super) enum RawRotate {
    Euler([f64; 3]),
    Axis(RawAxisAngle),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawAxisAngle {
    pub(super) axis: [f64; 3],
    pub(super) angle: f64,
}

#[derive(Deserialize)]
#[serde(untagged, expecting = "a number or [sx, sy, sz]")]
pub(super) enum RawScale {
    Uniform(f64),
    Axes([f64; 3]),
}

#[derive(Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub(super) struct RawMaterial {
    pub(super) color: Option<[f64; 3]>,
    pub(super) specular: Option<f64>,
    pub(super) shininess: Option<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct RawCsg {
    pub(super) name: String,
    pub(super) op: CsgOp,
    pub(super) children: Vec<String>,
    pub(super) visible: Option<bool>,
}

#[derive(Deserialize, Copy, Clone, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
pub(super) enum CsgOp {
    Union,
    Intersection,
    Difference,
}

/// A light of the file; a new light type is a new variant (`type = "..."`).
#[derive(Deserialize)]
#[serde(tag = "type", rename_all = "kebab-case", deny_unknown_fields)]
pub(super) enum RawLight {
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
pub(super) struct RawRender {
    pub(super) root_finder: Option<String>,
    pub(super) epsilon: Option<f64>,
    pub(super) max_steps: Option<i64>,
    pub(super) sampling_step: Option<f64>,
    pub(super) lipschitz: Option<f64>,
    pub(super) aa: Option<String>,
    pub(super) iaa_depth: Option<i64>,
    pub(super) iaa_threshold: Option<f64>,
    pub(super) iaa_limit_rays: Option<i64>,
    pub(super) primary: Option<String>,
    pub(super) rays_per_undecided: Option<i64>,
    pub(super) undecided_depth: Option<i64>,
    pub(super) rays_per_pixel: Option<i64>,
    pub(super) t_final_width: Option<f64>,
    pub(super) grid: Option<i64>,
    pub(super) shadows: Option<bool>,
    pub(super) shadow_method: Option<String>,
    pub(super) precision: Option<String>,
    pub(super) escalate: Option<bool>,
}
