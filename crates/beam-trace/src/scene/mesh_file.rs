//! The scene file's `[[meshes]]`: an OBJ file or inline polygons, placed by a transform,
//! with a material.

use std::path::Path;

use glam::DVec3;

use super::diagnostics::Doc;
use super::mesh::MeshSurface;
use super::schema::RawMesh;
use super::surface::{material, resolve};
use super::transform::transform;
use crate::error::Error;
use crate::mesh::{Triangle, read_obj};

/// Builds the meshes of the file; `surface_names` are the names already taken by
/// surfaces and csg nodes.
pub(super) fn build_meshes(
    doc: &Doc<'_>,
    raw: &[RawMesh],
    base: Option<&Path>,
    surface_names: &[&str],
) -> Result<Vec<MeshSurface>, Error> {
    let mut out: Vec<MeshSurface> = Vec::with_capacity(raw.len());
    for (i, m) in raw.iter().enumerate() {
        let at = |field: &str| format!("meshes[{i}].{field}");
        let (local, default_name) = match (&m.obj, &m.polygons) {
            (Some(file), None) => {
                let full = resolve(file, base);
                let tris = read_obj(&full).map_err(|e| {
                    doc.err(&at("obj"), format!("cannot read '{}': {e}", full.display()))
                })?;
                let stem = full
                    .file_stem()
                    .map_or_else(|| format!("mesh-{i}"), |s| s.to_string_lossy().into_owned());
                (tris, stem)
            }
            (None, Some(polys)) => (polygons(doc, &at("polygons"), polys)?, format!("mesh-{i}")),
            _ => {
                return Err(doc.err(
                    &format!("meshes[{i}]"),
                    "give exactly one of obj (a Wavefront OBJ file) and polygons (a list of \
                     polygons, each a list of [x, y, z] vertices)",
                ));
            }
        };
        let place = match &m.transform {
            Some(t) => Some(transform(doc, &at("transform"), t)?),
            None => None,
        };
        let triangles: Vec<Triangle> = local
            .iter()
            .map(|t| match &place {
                Some(a) => Triangle {
                    v: t.v.map(|p| a.map_point(p)),
                },
                None => *t,
            })
            .filter(|t| !t.is_degenerate())
            .collect();
        if let Some(t) = triangles.iter().find(|t| !t.is_finite()) {
            return Err(doc.err(
                &at("transform"),
                format!("the transform takes a vertex out of range: {:?}", t.v),
            ));
        }
        if triangles.is_empty() {
            return Err(doc.err(
                &format!("meshes[{i}]"),
                "every triangle of the mesh has three vertices on one line (no area)",
            ));
        }
        let name = m.name.clone().unwrap_or(default_name);
        let taken = surface_names.contains(&name.as_str()) || out.iter().any(|o| o.name == name);
        if taken {
            return Err(doc.err(
                &at("name"),
                format!(
                    "duplicate name '{name}'; give each surface, csg node and mesh its own name"
                ),
            ));
        }
        out.push(MeshSurface {
            name,
            triangles,
            material: material(doc, &at("material"), &m.material)?,
        });
    }
    Ok(out)
}

/// The triangles of inline polygons: each a fan from its first vertex (a convex polygon
/// is covered exactly once; the fan of a non-convex one is what is rendered).
fn polygons(doc: &Doc<'_>, path: &str, polys: &[Vec<[f64; 3]>]) -> Result<Vec<Triangle>, Error> {
    let mut out = Vec::new();
    for (j, p) in polys.iter().enumerate() {
        if p.len() < 3 {
            return Err(doc.err(
                &format!("{path}[{j}]"),
                format!(
                    "a polygon needs at least 3 vertices, this one has {}",
                    p.len()
                ),
            ));
        }
        let v: Vec<DVec3> = p
            .iter()
            .enumerate()
            .map(|(k, &x)| doc.vec3(&format!("{path}[{j}][{k}]"), x))
            .collect::<Result<_, _>>()?;
        out.extend((1..v.len() - 1).map(|k| Triangle::new(v[0], v[k], v[k + 1])));
    }
    if out.is_empty() {
        return Err(doc.err(path, "no polygon"));
    }
    Ok(out)
}
