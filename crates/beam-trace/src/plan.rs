//! The effect plan: which passes a scene calls for, and with which settings.
//!
//! Primary visibility always runs; normals and shading only when the scene has lights;
//! hard shadow rays only for point lights and soft-shadow beams only for area lights, with
//! shadows on; anti-aliasing only when asked.
//! A pass that is not planned costs nothing: its statistics stay zero.

use std::fmt;

use crate::beam::BeamSettings;
use crate::ray::Precision;
use crate::root::{RootMethod, RootSettings};
use crate::scene::{AaMode, Light, PrimaryMode, Scene};
use crate::shadow::ShadowSpec;

/// How primary visibility is computed.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Primary {
    /// Screen box structure (thesis 5.4): beams classify boxes; `1` ray per pixel in Hit
    /// boxes, `rays_per_undecided` in Undecided pixels.
    ScreenBoxes {
        /// Rays per pixel in Undecided boxes.
        rays_per_undecided: u32,
    },
    /// `rays_per_pixel` rays in every pixel (classic interval ray casting; supersampling).
    PerPixel {
        /// Rays per pixel (a square number).
        rays_per_pixel: u32,
    },
    /// Interval anti-aliasing (thesis 5.5.2): one beam per pixel, subdivided.
    Iaa {
        /// Largest subdivision depth.
        max_depth: u32,
        /// Largest normal-variation estimator for shading a sub-pixel once.
        threshold: f64,
    },
}

/// The passes of a render and their settings.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// Grid resolution, when the regular grid is built.
    pub grid: Option<u32>,
    /// Primary visibility.
    pub primary: Primary,
    /// Normals and Phong shading (the scene has lights).
    pub shading: bool,
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

/// Names of the passes, in the order they run.
pub const PASSES: [&str; 8] = [
    "grid",
    "screen-boxes",
    "primary-rays",
    "iaa",
    "normals",
    "hard-shadows",
    "soft-shadows",
    "shading",
];

impl Plan {
    /// The plan for `scene`.
    pub fn for_scene(scene: &Scene) -> Plan {
        let s = &scene.settings;
        let primary = match s.aa {
            AaMode::Iaa {
                max_depth,
                threshold,
            } => Primary::Iaa {
                max_depth,
                threshold,
            },
            AaMode::Supersample(n) => Primary::PerPixel {
                rays_per_pixel: n * n,
            },
            AaMode::None => match s.primary {
                PrimaryMode::ScreenBoxes => Primary::ScreenBoxes {
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
        let hard_shadow_lights = count(|l| l.as_point().is_some());
        let soft_shadow_lights = count(|l| l.as_area().is_some());
        Plan {
            grid: (s.grid_resolution > 0).then_some(s.grid_resolution),
            primary,
            shading,
            hard_shadow_lights,
            soft_shadow_lights,
            shadow_method: s.shadow_method,
            root_finder: s.root_finder,
            root: s.root,
            beam: BeamSettings {
                epsilon: (s.root.epsilon * 100.0).max(1e-3 * diagonal),
                ..BeamSettings::default()
            },
            t_final_width: s.t_final_width * diagonal,
            precision: s.precision,
        }
    }

    /// Whether the pass `name` runs.
    pub fn runs(&self, name: &str) -> bool {
        match name {
            "grid" => self.grid.is_some(),
            "screen-boxes" => matches!(self.primary, Primary::ScreenBoxes { .. }),
            "primary-rays" => !matches!(self.primary, Primary::Iaa { .. }),
            "iaa" => matches!(self.primary, Primary::Iaa { .. }),
            "normals" | "shading" => self.shading,
            "hard-shadows" => self.shading && self.hard_shadow_lights > 0,
            "soft-shadows" => self.shading && self.soft_shadow_lights > 0,
            _ => false,
        }
    }
}

impl fmt::Display for Plan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "plan:")?;
        for name in PASSES {
            let what = if !self.runs(name) {
                "skipped".to_string()
            } else {
                match name {
                    "grid" => format!("regular grid, {} cells on the longest side", self.grid.unwrap_or(0)),
                    "screen-boxes" => "beams over screen boxes: rejection + inclusion tests (Miss / Hit / Undecided)".to_string(),
                    "primary-rays" => match self.primary {
                        Primary::ScreenBoxes { rays_per_undecided } => format!(
                            "1 ray per pixel in Hit boxes (search in T_final), {rays_per_undecided} per pixel in Undecided ones; root finder {}, epsilon {:e}",
                            self.root_finder, self.root.epsilon
                        ),
                        Primary::PerPixel { rays_per_pixel } => format!(
                            "{rays_per_pixel} ray(s) per pixel; root finder {}, epsilon {:e}",
                            self.root_finder, self.root.epsilon
                        ),
                        Primary::Iaa { .. } => String::new(),
                    },
                    "iaa" => match self.primary {
                        Primary::Iaa { max_depth, threshold } => format!(
                            "interval anti-aliasing: a beam per pixel, split in four to depth {max_depth}, normal-variation threshold {threshold}"
                        ),
                        _ => String::new(),
                    },
                    "normals" => "surface normals from the gradient".to_string(),
                    "hard-shadows" => format!(
                        "shadow segments to {} point light(s), searched through the grid: a reliable \"no root\" proves the point lit",
                        self.hard_shadow_lights
                    ),
                    "soft-shadows" => format!(
                        "visible fraction of {} area light(s) by {}",
                        self.soft_shadow_lights, self.shadow_method
                    ),
                    "shading" => "Phong (ambient, diffuse, specular)".to_string(),
                    _ => String::new(),
                }
            };
            writeln!(f, "  {name:<13} {what}")?;
        }
        writeln!(
            f,
            "  {:<13} {} intervals for g and g' on rays and beams (root searches, beam tests)",
            "precision", self.precision
        )?;
        Ok(())
    }
}
