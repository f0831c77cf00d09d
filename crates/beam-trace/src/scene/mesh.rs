//! A triangle mesh of a scene (built from the file's `[[meshes]]` by `mesh_file`).

use super::material::Material;
use crate::ibox::{IBox, hull};
use crate::mesh::{Triangle, bounds_of};

/// A triangle mesh of the scene, its transform applied.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSurface {
    /// Its name (the file's stem, or `mesh-N`).
    pub name: String,
    /// The triangles in world coordinates: the vertices as computed in `f64` from the
    /// file's and the transform's numbers are the mesh that is rendered. Triangles without
    /// area (three vertices on a line, decided exactly) are left out.
    pub triangles: Vec<Triangle>,
    /// Its Phong material.
    pub material: Material,
}

/// The box `bounds` (of the implicit surfaces) grown to hold every mesh's vertices.
pub(super) fn with_meshes(bounds: IBox, meshes: &[MeshSurface]) -> IBox {
    meshes
        .iter()
        .filter_map(|m| bounds_of(&m.triangles))
        .fold(bounds, |b, m| hull(&b, &m))
}
