//! The scene model: camera, lights, materials, surfaces combined by CSG, render settings.
//!
//! A [`Scene`] is what the renderer consumes. It is built from a TOML scene file
//! ([`Scene::from_toml`], [`Scene::load`]) or from the built-in default
//! ([`Scene::default_scene`]). Its geometry is compiled once into one expression graph:
//! each leaf surface (formula, `.vm` file or catalog name, with its parameters bound and its
//! affine transform applied), CSG nodes as `min`/`max` (union = `min`, intersection =
//! `max`, difference `a − b` = `max(a, −b)`: the point-set operations of thesis 6.3), and
//! the scene function the union of the top-level objects.

pub mod animation;
pub mod block;
mod camera;
mod csg;
mod diagnostics;
mod file;
pub mod geometry;
mod lights;
mod material;
mod mesh;
mod mesh_file;
mod model;
mod schema;
mod settings;
mod surface;
mod transform;

pub use animation::Animation;
pub use block::BlockMismatch;
pub use file::DEFAULT_SCENE;
pub use geometry::{Csg, Geometry, Leaf};
pub use material::Material;
pub use mesh::MeshSurface;
pub use model::{
    AaMode, AreaLight, Light, MAX_GRID_RESOLUTION, PointLight, PrimaryMode, RenderSettings, Scene,
    auto_grid_resolution,
};
