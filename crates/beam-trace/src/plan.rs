//! The effect plan: which passes a scene calls for, and with which settings.
//!
//! Primary visibility always runs; normals and shading only when the scene has lights;
//! hard shadow rays only for point lights and soft-shadow beams only for area lights, with
//! shadows on; interval anti-aliasing by default in the screen-boxes mode
//! ([`RenderSettings::aa_mode`](crate::scene::RenderSettings::aa_mode)).
//! A pass that is not planned costs nothing: its statistics stay zero.

use std::fmt;

use crate::beam::BeamSettings;
use crate::ray::Precision;
use crate::root::{RootMethod, RootSettings};
use crate::scene::{AaMode, Light, PrimaryMode, Scene, auto_grid_resolution};
use crate::shadow::ShadowSpec;

/// How primary visibility is computed.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Primary {
    /// Screen box structure (thesis 5.4): beams classify boxes; `1` ray per pixel in Hit
    /// boxes; the beam of an Undecided pixel is split in four until its parts are decided
    /// or `max_depth` is reached (the pixel-beams pass), so that whatever the beam may
    /// meet is kept.
    ScreenBoxes {
        /// Largest subdivision depth of an Undecided pixel's beam.
        max_depth: u32,
    },
    /// The thesis's screen box structure with point rays: `1` ray per pixel in Hit boxes,
    /// `rays_per_undecided` stratified rays in Undecided pixels.
    ScreenRays {
        /// Rays per pixel in Undecided boxes.
        rays_per_undecided: u32,
    },
    /// `rays_per_pixel` rays in every pixel (classic interval ray casting; supersampling).
    PerPixel {
        /// Rays per pixel (a square number).
        rays_per_pixel: u32,
    },
    /// The frustum octree ([`crate::frustum`]): each pixel's first cell where a surface may
    /// be, then `rays_per_undecided` stratified rays per covered pixel searched from there.
    Octree {
        /// Rays per pixel whose column of cells holds a surface.
        rays_per_undecided: u32,
    },
    /// Interval anti-aliasing (thesis 5.5.2) on the screen box structure: the beam of an
    /// Undecided pixel, or of a Hit pixel whose shading may vary by more than `threshold`,
    /// is split in four down to `max_depth` (the pixel-beams pass).
    Iaa {
        /// Largest subdivision depth.
        max_depth: u32,
        /// Largest spread of the shaded colour over a proven hit region for shading it once
        /// ([`shading_variation`](crate::aa::shading_variation)).
        threshold: f64,
        /// Rays per side of an undecided part at the depth limit.
        limit_rays: u32,
    },
}

/// The settings of the pixel-beams pass ([`Primary::pixel_beams`]).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct PixelBeams {
    /// Largest subdivision depth of a pixel's beam.
    pub max_depth: u32,
    /// The shading-variation threshold above which Hit beams are split too
    /// (anti-aliasing); `None`: Hit pixels are shaded once.
    pub threshold: Option<f64>,
    /// Rays per side of a part left undecided at the depth limit: `limit_rays²` stratified
    /// rays estimate the share of it its surface covers (1: its central ray).
    pub limit_rays: u32,
}

impl Primary {
    /// The settings of the pixel-beams pass; `None` for the ray modes.
    pub fn pixel_beams(&self) -> Option<PixelBeams> {
        match *self {
            Primary::ScreenBoxes { max_depth } => Some(PixelBeams {
                max_depth,
                threshold: None,
                limit_rays: 1,
            }),
            Primary::Iaa {
                max_depth,
                threshold,
                limit_rays,
            } => Some(PixelBeams {
                max_depth,
                threshold: Some(threshold),
                limit_rays,
            }),
            Primary::ScreenRays { .. } | Primary::PerPixel { .. } | Primary::Octree { .. } => None,
        }
    }
}

/// The grid's resolution (cells on the longest side, unless the scene sets one) where it
/// serves only the frustum octree of an unlit scene: its cells then bound each tile's
/// range of the ray parameter (and leave the rays the octree does not decide to the root
/// finder), while the octree prunes the scene function per cell of its own, so a fine grid
/// costs more to build than it saves. At 512 × 512 and 1024 × 1024 on 2 threads (whole
/// process, `perf stat -r 3`): csg3d-2k 161 and 338 ms with 8 cells a side, 184 and 352
/// with the 30 its length gives; csg3d-660 87 and 225 against 94 and 231.
const OCTREE_GRID: u32 = 8;

/// The passes of a render and their settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Grid resolution, when the regular grid is built.
    pub grid: Option<u32>,
    /// Primary visibility.
    pub primary: Primary,
    /// Normals and Phong shading (the scene has lights).
    pub shading: bool,
    /// Whether the ray of a Hit pixel narrows the box's `T_final` to a root proven unique
    /// to the root finder's epsilon. The shading needs it (the normal and the shadow rays
    /// start at the root), and so does an unlit scene whose objects differ in colour (the
    /// colour is the first root's object's). Without it, in an unlit scene of one colour,
    /// `T_final` is the root's enclosure: the inclusion test proved a root in it for every
    /// ray of the pixel, and no root before it ([`Proof::Exists`](crate::root::Proof)).
    pub narrow_hits: bool,
    /// Number of point lights that cast hard shadows (0: no shadow pass).
    pub hard_shadow_lights: usize,
    /// Number of area lights that cast soft shadows (0: no soft-shadow pass).
    pub soft_shadow_lights: usize,
    /// The soft-shadow method.
    pub shadow_method: ShadowSpec,
    /// Root finder of ray searches.
    pub root_finder: RootMethod,
    /// Its settings.
    pub root: RootSettings,
    /// Settings of the beam tests.
    pub beam: BeamSettings,
    /// Largest width of `T_final`, absolute, for a Hit box not to be split (aliasing).
    pub t_final_width: f64,
    /// Floating-point format of the interval evaluations of `g` and `g'` on rays and beams.
    pub precision: Precision,
}

/// The passes of the render pipeline, in the order they run.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Pass {
    /// The regular grid of interval-classified cells (built by the CPU backend).
    Grid,
    /// The screen box structure: beams over image rectangles (thesis 5.4).
    ScreenBoxes,
    /// Ray-based primary visibility (per pixel, or in undecided screen boxes).
    PrimaryRays,
    /// Pixels resolved by their beams: Undecided pixels (and, anti-aliased, Hit pixels of
    /// varying shading) split in four (thesis 5.5.2), one central ray per decided part.
    PixelBeams,
    /// Surface normals of the hit samples.
    Normals,
    /// Hard shadows from point lights.
    HardShadows,
    /// Soft shadows from area lights.
    SoftShadows,
    /// Phong shading and pixel colours.
    Shading,
}

impl Pass {
    /// Every pass, in the order they run.
    pub const ALL: [Pass; 8] = [
        Pass::Grid,
        Pass::ScreenBoxes,
        Pass::PrimaryRays,
        Pass::PixelBeams,
        Pass::Normals,
        Pass::HardShadows,
        Pass::SoftShadows,
        Pass::Shading,
    ];

    /// The pass's name in plans and statistics (`screen-boxes`).
    pub fn name(self) -> &'static str {
        match self {
            Pass::Grid => "grid",
            Pass::ScreenBoxes => "screen-boxes",
            Pass::PrimaryRays => "primary-rays",
            Pass::PixelBeams => "pixel-beams",
            Pass::Normals => "normals",
            Pass::HardShadows => "hard-shadows",
            Pass::SoftShadows => "soft-shadows",
            Pass::Shading => "shading",
        }
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Plan {
    /// The root settings of primary rays (the pixels' rays, their sub-rays and the rays of
    /// undecided pixels): [`root`](Self::root), without narrowing a root proven unique
    /// where hits are not narrowed ([`narrow_hits`](Self::narrow_hits) off: the image
    /// needs only whether each ray meets a surface, and no point on it).
    pub fn ray_root(&self) -> RootSettings {
        if self.narrow_hits {
            self.root
        } else {
            self.root.existence()
        }
    }

    /// The plan for `scene`.
    pub fn for_scene(scene: &Scene) -> Plan {
        let s = &scene.settings;
        let primary = match s.aa_mode() {
            AaMode::Iaa {
                max_depth,
                threshold,
                limit_rays,
            } => Primary::Iaa {
                max_depth,
                threshold,
                limit_rays,
            },
            AaMode::Supersample(n) => Primary::PerPixel {
                rays_per_pixel: n * n,
            },
            AaMode::None => match s.primary {
                PrimaryMode::ScreenBoxes => Primary::ScreenBoxes {
                    max_depth: s.undecided_depth,
                },
                PrimaryMode::ScreenRays => Primary::ScreenRays {
                    rays_per_undecided: s.rays_per_undecided,
                },
                PrimaryMode::Octree => Primary::Octree {
                    rays_per_undecided: s.rays_per_undecided,
                },
                PrimaryMode::PerPixel => Primary::PerPixel {
                    rays_per_pixel: s.rays_per_pixel,
                },
            },
        };
        let diagonal = scene.geometry.diagonal();
        let shading = !scene.lights.is_empty();
        let count = |f: fn(&Light) -> bool| {
            if s.shadows {
                scene.lights.iter().filter(|l| f(l)).count()
            } else {
                0
            }
        };
        let leaves = scene.geometry.leaves();
        let first_colour = leaves[0].material.color;
        let one_colour = leaves
            .iter()
            .map(|l| l.material.color)
            .chain(scene.meshes.iter().map(|m| m.material.color))
            .all(|c| c == first_colour);
        let hard_shadow_lights = count(|l| l.as_point().is_some());
        let soft_shadow_lights = count(|l| l.as_area().is_some());
        Plan {
            grid: (s.grid_resolution > 0).then(|| {
                let octree_only = matches!(primary, Primary::Octree { .. }) && !shading;
                if !s.grid_auto {
                    s.grid_resolution
                } else if octree_only {
                    OCTREE_GRID.min(s.grid_resolution)
                } else {
                    auto_grid_resolution(s.grid_resolution, scene.geometry.tape().len())
                }
            }),
            primary,
            shading,
            narrow_hits: shading || !one_colour,
            hard_shadow_lights,
            soft_shadow_lights,
            shadow_method: s.shadow_method,
            root_finder: s.root_finder,
            root: s.root,
            beam: BeamSettings {
                epsilon: (s.root.epsilon * 100.0).max(1e-3 * diagonal),
                escalate: s.root.escalate,
                ..BeamSettings::default()
            },
            t_final_width: s.t_final_width * diagonal,
            precision: s.precision,
        }
    }

    /// Whether `pass` runs.
    pub fn runs(&self, pass: Pass) -> bool {
        match pass {
            Pass::Grid => self.grid.is_some(),
            Pass::ScreenBoxes => !matches!(self.primary, Primary::PerPixel { .. }),
            Pass::PrimaryRays => self.primary.pixel_beams().is_none(),
            Pass::PixelBeams => self.primary.pixel_beams().is_some(),
            Pass::Normals | Pass::Shading => self.shading,
            Pass::HardShadows => self.shading && self.hard_shadow_lights > 0,
            Pass::SoftShadows => self.shading && self.soft_shadow_lights > 0,
        }
    }

    /// What `pass` does under this plan, in words (empty when it does not run).
    pub fn describe(&self, pass: Pass) -> String {
        let mut what = self.describe_settings(pass);
        if !self.narrow_hits && matches!(pass, Pass::PrimaryRays | Pass::PixelBeams) {
            what.push_str(
                "; unlit, one colour: a Hit pixel's root is the one its T_final is proven to \
                 hold (no search)",
            );
        }
        what
    }

    /// [`describe`](Self::describe) without the note on Hit pixels.
    fn describe_settings(&self, pass: Pass) -> String {
        if !self.runs(pass) {
            return String::new();
        }
        match pass {
            Pass::Grid => format!(
                "regular grid, {} cells on the longest side",
                self.grid.unwrap_or(0)
            ),
            Pass::ScreenBoxes => {
                let boxes =
                    "beams over screen boxes: rejection + inclusion tests (Miss / Hit / Undecided)";
                match self.primary {
                    Primary::Octree { .. } => "frustum octree: cells of pixels x parameter \
                        ranges, nearest first, rejection tests on tapes pruned per cell; each \
                        pixel's first cell (Miss; Hit where its inclusion test passes; else \
                        Undecided)"
                        .to_string(),
                    Primary::Iaa { .. } => format!(
                        "{boxes}; the shading of each Hit box of more than one pixel judged once"
                    ),
                    _ => boxes.to_string(),
                }
            }
            Pass::PrimaryRays => match self.primary {
                Primary::ScreenRays { rays_per_undecided } => format!(
                    "1 ray per pixel in Hit boxes (search in T_final), {rays_per_undecided} per pixel in Undecided ones; root finder {}, epsilon {:e}",
                    self.root_finder, self.root.epsilon
                ),
                Primary::PerPixel { rays_per_pixel } => format!(
                    "{rays_per_pixel} ray(s) per pixel; root finder {}, epsilon {:e}",
                    self.root_finder, self.root.epsilon
                ),
                Primary::Octree { rays_per_undecided } => format!(
                    "{rays_per_undecided} ray(s) per pixel whose column of cells may hold a surface, from its first cell (one ray: the octree's trace of it where that decided it); root finder {}, epsilon {:e}",
                    self.root_finder, self.root.epsilon
                ),
                Primary::ScreenBoxes { .. } | Primary::Iaa { .. } => String::new(),
            },
            Pass::PixelBeams => {
                let Some(PixelBeams {
                    max_depth,
                    threshold,
                    limit_rays,
                }) = self.primary.pixel_beams()
                else {
                    return String::new();
                };
                let limit = match limit_rays {
                    1 => "one central ray per part".to_string(),
                    m => format!(
                        "one central ray per decided part, {m} x {m} per part left undecided at the limit"
                    ),
                };
                match threshold {
                    None => format!(
                        "1 ray per pixel in Hit boxes (search in T_final); Undecided pixels' beams split in four to depth {max_depth}; {limit}"
                    ),
                    Some(threshold) => format!(
                        "interval anti-aliasing: Undecided pixels' beams, and Hit pixels' whose shading may vary by more than {threshold}, split in four to depth {max_depth}; {limit}"
                    ),
                }
            }
            Pass::Normals => "surface normals from the gradient".to_string(),
            Pass::HardShadows => format!(
                "shadow segments to {} point light(s), searched through the grid: a reliable \"no root\" proves the point lit",
                self.hard_shadow_lights
            ),
            Pass::SoftShadows => format!(
                "visible fraction of {} area light(s) by {}",
                self.soft_shadow_lights, self.shadow_method
            ),
            Pass::Shading => "Phong (ambient, diffuse, specular)".to_string(),
        }
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "plan:")?;
        for pass in Pass::ALL {
            let what = if self.runs(pass) {
                self.describe(pass)
            } else {
                "skipped".to_string()
            };
            writeln!(f, "  {:<13} {what}", pass.name())?;
        }
        writeln!(
            f,
            "  {:<13} {} intervals for g and g' on rays and beams (root searches, beam tests)",
            "precision", self.precision
        )?;
        if self.root.escalate {
            writeln!(
                f,
                "  {:<13} open root searches and undecided beams that rounding or cancelling terms keep open run again in the next precision, up to dd (a GPU backend sends them to the CPU)",
                "escalation"
            )?;
        }
        Ok(())
    }
}
