//! The camera of a scene file, given or automatic (framing the scene's bounds).

use glam::DVec3;

use super::diagnostics::Doc;
use super::schema::RawCamera;
use crate::camera::Camera;
use crate::error::Error;
use crate::ibox::IBox;

/// Largest image side, in pixels.
const MAX_IMAGE_SIDE: i64 = 16384;

/// The view of an automatic camera: eye, look-at point and a light above-left of the eye.
pub(super) fn auto_view(bounds: &IBox, fov_deg: f64) -> (DVec3, DVec3, DVec3) {
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

pub(super) fn camera(
    doc: &Doc<'_>,
    c: &RawCamera,
    bounds: &IBox,
) -> Result<(Camera, Option<DVec3>), Error> {
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
