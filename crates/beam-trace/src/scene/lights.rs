//! The lights of a scene file: point lights and area lights (squares or parallelograms).

use super::diagnostics::Doc;
use super::model::{AreaLight, Light, PointLight};
use super::schema::RawLight;
use crate::error::Error;
use crate::shadow::Patch;

pub(super) fn lights(doc: &Doc<'_>, raw: &[RawLight]) -> Result<Vec<Light>, Error> {
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
pub(super) fn area_patch(
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
