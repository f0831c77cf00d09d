//! A ball written as a formula, whose ray intersections are known exactly: the scene and
//! the exact first intersection shared by the tests of hit points and of the frustum octree.

use beam_trace::Scene;
use glam::DVec3;

/// The view of a ball: its centre and radius, the eye, the square image side and the
/// vertical field of view in degrees.
#[derive(Copy, Clone, Debug)]
pub struct Ball {
    pub centre: [f64; 3],
    pub r: f64,
    pub eye: [f64; 3],
    pub size: u32,
    pub fov: f64,
}

impl Ball {
    /// The scene: the camera looking at the centre, the ball `|p − c|² − r²` with bounds
    /// twice its radius around it, and `tail` (tables such as `[render]` or `[[lights]]`)
    /// after it.
    pub fn scene(&self, tail: &str) -> Scene {
        let ([cx, cy, cz], r) = (self.centre, self.r);
        let bounds = (
            [cx - 2.0 * r, cy - 2.0 * r, cz - 2.0 * r],
            [cx + 2.0 * r, cy + 2.0 * r, cz + 2.0 * r],
        );
        let formula = format!(
            "(x - {cx:?})^2 + (y - {cy:?})^2 + (z - {cz:?})^2 - {:?}",
            r * r
        );
        self.view(&formula, bounds, tail)
    }

    /// A scene seen as this ball is (the camera at the eye looking at the centre, with the
    /// field of view and image side), of the surface `formula` within `bounds` (lower and
    /// upper corners), and `tail` after it.
    pub fn view(&self, formula: &str, (lo, hi): ([f64; 3], [f64; 3]), tail: &str) -> Scene {
        let ([cx, cy, cz], [ex, ey, ez]) = (self.centre, self.eye);
        let text = format!(
            "[camera]\neye = [{ex:?}, {ey:?}, {ez:?}]\nlook_at = [{cx:?}, {cy:?}, {cz:?}]\n\
             fov = {:?}\nwidth = {}\nheight = {}\n\n[[surfaces]]\n\
             formula = \"{formula}\"\nbounds = [{lo:?}, {hi:?}]\n\n{tail}\n",
            self.fov, self.size, self.size,
        );
        Scene::from_toml(&text, "ball.toml", None).unwrap_or_else(|e| panic!("{e}"))
    }

    /// The exact first intersection parameter of `origin + t·dir` with the ball, if any.
    pub fn exact_t(&self, origin: DVec3, dir: DVec3) -> Option<f64> {
        let oc = origin - DVec3::from(self.centre);
        let (a, b, c) = (dir.dot(dir), oc.dot(dir), oc.dot(oc) - self.r * self.r);
        let disc = b * b - a * c;
        (disc >= 0.0).then(|| (-b - disc.sqrt()) / a)
    }
}
