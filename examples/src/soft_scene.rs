//! Catalog surfaces lit by a square area light, as in the reliable soft-shadow paper's
//! experiments (shared by the `soft-shadows` and `gpu-vs-cpu` examples).

use beam_trace::scene::AreaLight;
use beam_trace::shadow::Patch;
use beam_trace::{Light, Scene};
use glam::DVec3;

/// The catalog surface `name` at `size × size`, its automatic point light replaced by an
/// axis-aligned horizontal square light at the same place whose area is `fraction` of the
/// view's area at the surface.
pub fn catalog_with_area_light(name: &str, size: u32, fraction: f64) -> Result<Scene, String> {
    let mut scene = Scene::catalog(name, size, size).map_err(|e| e.to_string())?;
    let position = scene
        .lights
        .iter()
        .find_map(Light::as_point)
        .ok_or("the catalog scene has no light")?
        .position;
    let cam = &scene.camera;
    let (w, h) = cam.view_size_at(cam.eye().distance(cam.look_at()));
    scene.lights = vec![square_light(position, (fraction * w * h).sqrt())];
    Ok(scene)
}

/// A white axis-aligned horizontal square light.
pub fn square_light(center: DVec3, side: f64) -> Light {
    Light::Area(AreaLight {
        patch: Patch::square(center, side, 1),
        color: [1.0; 3],
    })
}
