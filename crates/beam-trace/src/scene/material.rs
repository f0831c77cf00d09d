//! The surface material.

/// Phong material (thesis eq. 2.6).
#[derive(Copy, Clone, Debug, PartialEq, serde::Serialize)]
pub struct Material {
    /// Diffuse reflectance `c_r` per channel, in `[0, 1]`.
    pub color: [f32; 3],
    /// Weight of the highlight term.
    pub specular: f32,
    /// Highlight exponent `p`.
    pub shininess: f32,
}

impl Default for Material {
    fn default() -> Self {
        Self {
            color: [0.8, 0.8, 0.8],
            specular: 0.3,
            shininess: 32.0,
        }
    }
}
