//! Phong shading (thesis 2.3, eq. 2.6).

use glam::DVec3;

use crate::scene::Material;

/// The light arriving at a point from one light: its direction and colour (zero when
/// shadowed).
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Incoming {
    /// Unit vector from the point to the light.
    pub dir: DVec3,
    /// Light colour `c_l` times the visible fraction.
    pub color: [f32; 3],
}

/// `c = c_r (c_a + Σ c_l max(0, n·l)) + Σ k_s c_l max(0, e·r)^p` with `r = 2(l·n)n − l`
/// (eq. 2.6, summed over lights, with a highlight weight `k_s`). `n` is turned to face the
/// viewer `e` (unit vector from the point to the eye), so open surfaces shade from both
/// sides.
pub fn phong(
    material: &Material,
    ambient: f32,
    normal: DVec3,
    to_eye: DVec3,
    lights: &[Incoming],
) -> [f32; 3] {
    let n = if normal.dot(to_eye) < 0.0 {
        -normal
    } else {
        normal
    };
    let mut diffuse = [ambient; 3];
    let mut highlight = [0.0f32; 3];
    for l in lights {
        let nl = n.dot(l.dir);
        if nl <= 0.0 {
            continue;
        }
        let r = 2.0 * nl * n - l.dir;
        let spec = (to_eye.dot(r).max(0.0) as f32).powf(material.shininess) * material.specular;
        for c in 0..3 {
            diffuse[c] += l.color[c] * nl as f32;
            highlight[c] += l.color[c] * spec;
        }
    }
    std::array::from_fn(|c| material.color[c] * diffuse[c] + highlight[c])
}
