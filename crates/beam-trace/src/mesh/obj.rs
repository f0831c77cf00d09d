//! Triangles from Wavefront OBJ files (read by `tobj`).

use std::path::Path;

use glam::DVec3;

use super::triangle::Triangle;

/// The triangles of every object of the OBJ file at `path`: polygons are split into fans,
/// points and lines are ignored. Errors name the problem (an unreadable file, an index
/// out of range, a coordinate that is not finite, no triangle at all).
pub fn read_obj(path: &Path) -> Result<Vec<Triangle>, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj(path, &options).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    for m in &models {
        let p = &m.mesh.positions;
        let vertex = |i: u32| -> Result<DVec3, String> {
            let k = i as usize * 3;
            let v = p.get(k..k + 3).ok_or_else(|| {
                format!("object {:?}: vertex index {} out of range", m.name, i + 1)
            })?;
            let v = DVec3::new(v[0], v[1], v[2]);
            if !v.is_finite() {
                return Err(format!(
                    "object {:?}: vertex {} is not finite",
                    m.name,
                    i + 1
                ));
            }
            Ok(v)
        };
        for f in m.mesh.indices.chunks_exact(3) {
            out.push(Triangle::new(vertex(f[0])?, vertex(f[1])?, vertex(f[2])?));
        }
    }
    if out.is_empty() {
        return Err("no triangle in the file".into());
    }
    Ok(out)
}
