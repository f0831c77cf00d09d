//! The pinhole camera: primary rays through pixel positions and primary beams over screen
//! areas (thesis 5.4.1: the apex at the eye, the base an area of the image).
//!
//! Directions are affine in the pixel coordinates, `d(px, py) = corner + px·du + py·dv`,
//! and both rays and beams evaluate that map in interval arithmetic, so the direction of
//! every ray traced inside a screen area lies in that area's beam.

use glam::DVec3;
use interval_core::Interval;

use crate::error::Error;
use crate::ibox::{IBox, ipoint, ival, point_box};
use crate::ray::{Beam, Ray};

/// A pinhole camera with its image size. Pixel coordinates are continuous: pixel `(i, j)`
/// covers `[i, i+1] × [j, j+1]`, `x` to the right and `y` down.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Camera {
    eye: DVec3,
    look_at: DVec3,
    up: DVec3,
    fov_deg: f64,
    corner: DVec3,
    du: DVec3,
    dv: DVec3,
    width: u32,
    height: u32,
}

impl Camera {
    /// A camera at `eye` looking at `look_at`, with `up` the upward direction, vertical
    /// field of view `fov_deg` degrees and an image of `width × height` pixels.
    ///
    /// Returns an error for a zero image size, a field of view outside `(0, 180)`, a
    /// non-finite vector, `look_at == eye`, or `up` parallel to the view direction.
    pub fn new(
        eye: DVec3,
        look_at: DVec3,
        up: DVec3,
        fov_deg: f64,
        width: u32,
        height: u32,
    ) -> Result<Self, Error> {
        let bad = |m: &str| Err(Error::Camera(m.to_string()));
        if width == 0 || height == 0 {
            return bad("the image must be at least 1 × 1 pixels");
        }
        if !(fov_deg > 0.0 && fov_deg < 180.0) {
            return bad("fov must lie strictly between 0 and 180 degrees");
        }
        if !(eye.is_finite() && look_at.is_finite() && up.is_finite()) {
            return bad("eye, look_at and up must be finite");
        }
        let forward = look_at - eye;
        if forward.length() == 0.0 {
            return bad("look_at must differ from eye");
        }
        let forward = forward.normalize();
        let right = forward.cross(up);
        if right.length() < 1e-12 * up.length() || up.length() == 0.0 {
            return bad("up must not be parallel to the view direction");
        }
        let right = right.normalize();
        let true_up = right.cross(forward);
        let half_h = (fov_deg.to_radians() * 0.5).tan();
        let half_w = half_h * width as f64 / height as f64;
        let du = right * (2.0 * half_w / width as f64);
        let dv = -true_up * (2.0 * half_h / height as f64);
        let corner = forward - right * half_w + true_up * half_h;
        Ok(Self {
            eye,
            look_at,
            up,
            fov_deg,
            corner,
            du,
            dv,
            width,
            height,
        })
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The eye.
    pub fn eye(&self) -> DVec3 {
        self.eye
    }

    /// The point looked at.
    pub fn look_at(&self) -> DVec3 {
        self.look_at
    }

    /// The vertical field of view in degrees.
    pub fn fov_deg(&self) -> f64 {
        self.fov_deg
    }

    /// The width and height, in scene units, of the view at distance `d` from the eye.
    pub fn view_size_at(&self, d: f64) -> (f64, f64) {
        let h = 2.0 * d * (0.5 * self.fov_deg.to_radians()).tan();
        (h * f64::from(self.width) / f64::from(self.height), h)
    }

    /// The image plane: `(corner, du, dv)`, where the ray through the continuous pixel
    /// position `(px, py)` has the direction `corner + px · du + py · dv` (a GPU kernel
    /// builds its beams from these).
    pub fn frame(&self) -> (DVec3, DVec3, DVec3) {
        (self.corner, self.du, self.dv)
    }

    /// The same camera with another image size (same field of view).
    pub fn resized(&self, width: u32, height: u32) -> Result<Self, Error> {
        Camera::new(self.eye, self.look_at, self.up, self.fov_deg, width, height)
    }

    fn dirs(&self, x: Interval<f64>, y: Interval<f64>) -> IBox {
        let c = self.corner.to_array();
        let du = self.du.to_array();
        let dv = self.dv.to_array();
        std::array::from_fn(|i| ipoint(c[i]) + x * ipoint(du[i]) + y * ipoint(dv[i]))
    }

    /// The ray through the continuous pixel position `(px, py)`.
    pub fn ray(&self, px: f64, py: f64) -> Ray {
        let d = self.dirs(ipoint(px), ipoint(py));
        Ray {
            origin: self.eye,
            dir: DVec3::new(d[0].mid(), d[1].mid(), d[2].mid()),
        }
    }

    /// The beam of every ray through the screen area `[x0, x1] × [y0, y1]` (pixel units).
    pub fn beam(&self, x0: f64, y0: f64, x1: f64, y1: f64) -> Beam {
        Beam {
            origin: point_box(self.eye),
            dir: self.dirs(ival(x0, x1), ival(y0, y1)),
        }
    }
}
