//! What a scene is: its lights, render settings and the [`Scene`] itself.

use std::sync::Arc;

use glam::DVec3;

use super::geometry::Geometry;
use super::material::Material;
use super::mesh::{MeshSurface, with_meshes};
use crate::camera::Camera;
use crate::free_ranges::BlockProofs;
use crate::ray::Precision;
use crate::root::{RootMethod, RootSettings};
use crate::shadow::{Patch, ShadowSpec};

/// A point light.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct PointLight {
    /// Position.
    pub position: DVec3,
    /// Colour times intensity (`c_l` per channel).
    pub color: [f32; 3],
}

/// An area light: a parallelogram of uniform emission (soft shadows).
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct AreaLight {
    /// Its shape.
    pub patch: Patch,
    /// Colour times intensity (`c_l` per channel), for the whole light.
    pub color: [f32; 3],
}

/// A light source.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub enum Light {
    /// A point light: hard shadows.
    Point(PointLight),
    /// An area light: soft shadows.
    Area(AreaLight),
}

impl Light {
    /// The light as a point light: a point light, or an area light of size zero (which
    /// behaves exactly as a point light at its corner).
    pub fn as_point(&self) -> Option<PointLight> {
        match self {
            Light::Point(p) => Some(*p),
            Light::Area(a) if a.patch.is_point() => Some(PointLight {
                position: a.patch.corner,
                color: a.color,
            }),
            Light::Area(_) => None,
        }
    }

    /// The light as an area light of non-zero size.
    pub fn as_area(&self) -> Option<AreaLight> {
        match self {
            Light::Area(a) if !a.patch.is_point() => Some(*a),
            _ => None,
        }
    }

    /// The point shading takes the light's direction from (an area light's centre).
    pub fn center(&self) -> DVec3 {
        match self {
            Light::Point(p) => p.position,
            Light::Area(a) => a.patch.center(),
        }
    }

    /// Colour times intensity.
    pub fn color(&self) -> [f32; 3] {
        match self {
            Light::Point(p) => p.color,
            Light::Area(a) => a.color,
        }
    }
}

/// Anti-aliasing mode.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub enum AaMode {
    /// One ray per pixel (the screen box structure traces more in undecided boxes).
    None,
    /// Interval anti-aliasing (thesis 5.5.2): one beam per pixel, split in four where the
    /// beam is undecided or the normals vary, to `max_depth`.
    Iaa {
        /// Largest subdivision depth (thesis: 4).
        max_depth: u32,
        /// Largest spread of the shaded colour over a proven hit region for it to be shaded
        /// once ([`shading_variation`](crate::aa::shading_variation)).
        threshold: f64,
        /// Rays per side of an undecided part at the depth limit: the share of the part
        /// its surface covers is estimated from `limit_rays²` stratified rays (1: from its
        /// central ray, 15/16 or 1/16).
        limit_rays: u32,
    },
    /// `n × n` stratified rays per pixel (point-sampling supersampling).
    Supersample(u32),
}

impl AaMode {
    /// The anti-aliasing of a render that names none, in the screen-boxes primary mode with
    /// the default `undecided_depth` of 1: `iaa:1:0.1:2`, interval anti-aliasing with Hit
    /// pixels split once where their shaded colour may spread by more than 0.1, and `2 × 2`
    /// rays in each part left undecided at the limit. On the default scene it takes about
    /// 1.9 times the time of the render without anti-aliasing, with a lower edge error than
    /// supersampling at that time (`docs/anti-aliasing.md`, made by `aa-cost`).
    pub const DEFAULT: AaMode = AaMode::default_to(1);

    /// [`DEFAULT`](Self::DEFAULT) with the depth limit `depth` (the screen-boxes mode's
    /// `undecided_depth`, which the default anti-aliasing splits to).
    pub const fn default_to(depth: u32) -> AaMode {
        AaMode::Iaa {
            max_depth: depth,
            threshold: 0.1,
            limit_rays: 2,
        }
    }

    /// Default IAA depth limit of `iaa` (thesis 5.5.2: 4).
    pub const IAA_DEPTH: u32 = 4;
    /// Default IAA shading-variation threshold (a spread of the colour, channels in `[0, 1]`).
    pub const IAA_THRESHOLD: f64 = 0.05;
    /// Default rays per side of an IAA part left undecided at the depth limit.
    pub const IAA_LIMIT_RAYS: u32 = 2;
    /// Most rays per side of an undecided part at the depth limit.
    pub const MAX_LIMIT_RAYS: u32 = 16;
}

impl std::str::FromStr for AaMode {
    type Err = String;

    /// `none`, `iaa`, `iaa:D` (depth `D`, 1 to 8), `iaa:D:T` (and shading-variation
    /// threshold `T > 0`), `iaa:D:T:M` (and `M × M` rays in a part left undecided at the
    /// depth limit, `1 <= M <= 16`), or `ss:N` (`N × N` rays per pixel, `1 <= N <= 16`).
    fn from_str(s: &str) -> Result<Self, String> {
        if let Some(rest) = s.strip_prefix("iaa:") {
            let usage = || {
                format!(
                    "'{s}': write iaa:D, iaa:D:T or iaa:D:T:M with a depth D from 1 to 8, a \
                     threshold T > 0 and M from 1 to {} rays per side at the depth limit",
                    AaMode::MAX_LIMIT_RAYS
                )
            };
            let parts: Vec<&str> = rest.split(':').collect();
            if parts.len() > 3 {
                return Err(usage());
            }
            let max_depth = match parts[0].parse::<u32>() {
                Ok(d) if (1..=8).contains(&d) => d,
                _ => return Err(usage()),
            };
            let threshold = match parts.get(1).map(|t| t.parse::<f64>()) {
                None => AaMode::IAA_THRESHOLD,
                Some(Ok(t)) if t > 0.0 && t.is_finite() => t,
                Some(_) => {
                    return Err(format!(
                        "'{s}': the IAA threshold must be a positive number"
                    ));
                }
            };
            let limit_rays = match parts.get(2).map(|m| m.parse::<u32>()) {
                None => AaMode::IAA_LIMIT_RAYS,
                Some(Ok(m)) if (1..=AaMode::MAX_LIMIT_RAYS).contains(&m) => m,
                Some(_) => return Err(usage()),
            };
            return Ok(AaMode::Iaa {
                max_depth,
                threshold,
                limit_rays,
            });
        }
        match s {
            "none" => Ok(AaMode::None),
            "iaa" => Ok(AaMode::Iaa {
                max_depth: AaMode::IAA_DEPTH,
                threshold: AaMode::IAA_THRESHOLD,
                limit_rays: AaMode::IAA_LIMIT_RAYS,
            }),
            _ => match s.strip_prefix("ss:").map(str::parse::<u32>) {
                Some(Ok(n)) if (1..=16).contains(&n) => Ok(AaMode::Supersample(n)),
                Some(_) => Err(format!(
                    "'{s}': the supersampling count must be an integer from 1 to 16"
                )),
                None => Err(format!(
                    "unknown anti-aliasing mode '{s}' (one of: none, iaa, iaa:D, iaa:D:T, iaa:D:T:M, ss:N)"
                )),
            },
        }
    }
}

/// How primary visibility is computed.
#[derive(Copy, Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub enum PrimaryMode {
    /// The screen box structure of thesis 5.4 (beams classify boxes; 1 ray per pixel in
    /// Hit boxes), Undecided pixels resolved by splitting their beams to
    /// `undecided_depth`: the default.
    ScreenBoxes,
    /// The thesis's screen box structure with `rays_per_undecided` point rays in each
    /// Undecided pixel (a feature thinner than their spacing may be lost).
    ScreenRays,
    /// Classic interval ray casting: `rays_per_pixel` rays in every pixel.
    PerPixel,
    /// The frustum octree ([`crate::frustum`]): each pixel's first cell where a surface may
    /// be, then `rays_per_undecided` point rays per covered pixel from there.
    Octree,
}

/// Largest regular grid resolution (cells along the longest side): at most 256³ ≈ 16.8
/// million cells, a few hundred megabytes.
pub const MAX_GRID_RESOLUTION: u32 = 256;

/// Scene functions up to this many instructions keep the set grid resolution.
const AUTO_GRID_INSTRS: usize = 128;

/// The finest grid the automatic resolution chooses.
const AUTO_GRID_MAX: u32 = 128;

/// The grid resolution for a scene function of `instrs` instructions, starting from `base`:
/// `base` up to 128 instructions, then growing with the cube root of the
/// length (a cell's pruned function shrinks with the cell), at most 128. With
/// the grid classified block by block and the classes stored sparsely, a finer grid costs
/// little to build; what it saves is the length of every ray's function.
pub fn auto_grid_resolution(base: u32, instrs: usize) -> u32 {
    if instrs <= AUTO_GRID_INSTRS || base == 0 {
        return base;
    }
    let scale = (instrs as f64 / AUTO_GRID_INSTRS as f64).cbrt();
    ((f64::from(base) * scale).round() as u32).clamp(base, AUTO_GRID_MAX.max(base))
}

/// Render settings.
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct RenderSettings {
    /// Root finder of every ray search.
    #[serde(serialize_with = "serialize_display")]
    pub root_finder: RootMethod,
    /// Tolerances and limits of the root finder.
    #[serde(skip)]
    pub root: RootSettings,
    /// Primary visibility mode.
    pub primary: PrimaryMode,
    /// Anti-aliasing mode; `None`: the primary mode's own ([`RenderSettings::aa_mode`]).
    pub aa: Option<AaMode>,
    /// Rays per pixel in Undecided screen boxes of [`PrimaryMode::ScreenRays`] (a square
    /// number; thesis: 9).
    pub rays_per_undecided: u32,
    /// Largest subdivision depth of an Undecided pixel's beam in
    /// [`PrimaryMode::ScreenBoxes`] (parts of `4^-depth` of the pixel): also the depth
    /// limit of the default anti-aliasing ([`RenderSettings::aa_mode`]).
    pub undecided_depth: u32,
    /// Rays per pixel of [`PrimaryMode::PerPixel`] (a square number).
    pub rays_per_pixel: u32,
    /// Largest width of `T_final` (relative to the scene diagonal) for a Hit box not to be
    /// split further (aliasing regions, thesis 5.5.1).
    pub t_final_width: f64,
    /// Cells of the regular grid along the longest side of the scene bounds (0: no grid).
    pub grid_resolution: u32,
    /// Whether the grid may be finer than `grid_resolution` for a long scene function
    /// ([`auto_grid_resolution`]), or coarser (8 cells a side) where it serves only the
    /// frustum octree of an unlit scene: on unless the scene file or the caller set the
    /// resolution.
    pub grid_auto: bool,
    /// Whether lights cast shadows.
    pub shadows: bool,
    /// How area lights' soft shadows are computed.
    #[serde(serialize_with = "serialize_shadow")]
    pub shadow_method: ShadowSpec,
    /// Floating-point format of the interval evaluations of `g` and `g'` on rays and beams
    /// (root searches and beam tests; serialized as `"f64"` or `"f32"`).
    pub precision: Precision,
}

fn serialize_shadow<S: serde::Serializer>(m: &ShadowSpec, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&m.to_string())
}

fn serialize_display<S: serde::Serializer>(m: &RootMethod, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(m.name())
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            root_finder: RootMethod::NewtonAlefeldHansen,
            root: RootSettings::default(),
            primary: PrimaryMode::ScreenBoxes,
            aa: None,
            rays_per_undecided: 9,
            undecided_depth: 1,
            rays_per_pixel: 1,
            t_final_width: 0.05,
            grid_resolution: 16,
            grid_auto: true,
            shadows: true,
            shadow_method: ShadowSpec::default(),
            precision: Precision::F64,
        }
    }
}

impl RenderSettings {
    /// The anti-aliasing the render uses: [`aa`](Self::aa) where it is set, else the
    /// default interval anti-aliasing to [`undecided_depth`](Self::undecided_depth)
    /// ([`AaMode::default_to`]; [`AaMode::DEFAULT`] at the default depth; none at depth 0)
    /// in the screen-boxes primary mode, and none in the others, which trace their own rays.
    pub fn aa_mode(&self) -> AaMode {
        self.aa.unwrap_or(match self.primary {
            // Depth 0 splits nothing: the screen boxes' pixels as they are.
            PrimaryMode::ScreenBoxes if self.undecided_depth == 0 => AaMode::None,
            PrimaryMode::ScreenBoxes => AaMode::default_to(self.undecided_depth),
            PrimaryMode::ScreenRays | PrimaryMode::PerPixel | PrimaryMode::Octree => AaMode::None,
        })
    }
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Where the scene came from (a file name or `<built-in>`), for messages.
    pub name: String,
    /// The camera and image size.
    pub camera: Camera,
    /// Background colour.
    pub background: [f32; 3],
    /// Ambient light `c_a`.
    pub ambient: f32,
    /// Lights.
    pub lights: Vec<Light>,
    /// The compiled geometry.
    pub geometry: Geometry,
    /// Triangle meshes beside the implicit surfaces. Mesh `k` shades the samples of leaf
    /// `geometry.leaves().len() + k` ([`Scene::material_of`]).
    pub meshes: Vec<MeshSurface>,
    /// Render settings.
    pub settings: RenderSettings,
    /// Proofs shared with a block of animation frames: recorded while the block's scene is
    /// classified, reused by each frame's searches ([`crate::free_ranges`]). `None` for a
    /// scene rendered on its own; never changes the image. Set only by
    /// [`render_blocks`](crate::blocks::render_blocks), for scenes the block encloses
    /// ([`BlockProofs`] cannot be made elsewhere).
    pub proofs: Option<Arc<BlockProofs>>,
}

impl Scene {
    /// The material of the samples of leaf `leaf`: an implicit leaf's, or for
    /// `leaf = geometry.leaves().len() + k` mesh `k`'s (the default material for any other
    /// number).
    pub fn material_of(&self, leaf: u32) -> Material {
        let leaves = self.geometry.leaves();
        let i = leaf as usize;
        match leaves.get(i) {
            Some(l) => l.material,
            None => self
                .meshes
                .get(i - leaves.len())
                .map_or_else(Material::default, |m| m.material),
        }
    }

    /// The mesh that leaf `leaf` names, if it names one.
    pub fn mesh_of_leaf(&self, leaf: u32) -> Option<usize> {
        (leaf as usize)
            .checked_sub(self.geometry.leaves().len())
            .filter(|&k| k < self.meshes.len())
    }

    /// The length of the diagonal of the box of the implicit surfaces and the meshes (the
    /// scale of the shadow segments' offset, [`SHADOW_OFFSET`](crate::sample::SHADOW_OFFSET)).
    pub fn diagonal(&self) -> f64 {
        crate::ibox::diagonal(&with_meshes(self.geometry.bounds(), &self.meshes))
    }

    /// The leaf number of mesh `mesh`.
    pub fn mesh_leaf(&self, mesh: usize) -> u32 {
        (self.geometry.leaves().len() + mesh) as u32
    }
}
