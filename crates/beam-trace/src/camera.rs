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
use crate::screen::PixelRect;

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

    /// The rays through every position `(xs[i], ys[j])` (continuous pixel positions), with
    /// the terms of each column and row computed once ([`RayTable`]).
    pub fn ray_table(&self, xs: &[f64], ys: &[f64]) -> RayTable {
        let c = self.corner.to_array();
        let du = self.du.to_array();
        let dv = self.dv.to_array();
        RayTable {
            eye: self.eye,
            columns: xs
                .iter()
                .map(|&x| std::array::from_fn(|i| ipoint(c[i]) + ipoint(x) * ipoint(du[i])))
                .collect(),
            rows: ys
                .iter()
                .map(|&y| std::array::from_fn(|i| ipoint(y) * ipoint(dv[i])))
                .collect(),
        }
    }

    /// The beams of the pixel rectangles inside `area`, with the terms of each pixel edge
    /// computed once ([`EdgeBeams`]).
    pub fn edge_beams(&self, area: PixelRect) -> EdgeBeams {
        let c = self.corner.to_array();
        let du = self.du.to_array();
        let dv = self.dv.to_array();
        let columns = (area.x0..=area.x1)
            .map(|x| std::array::from_fn(|i| ipoint(c[i]) + ipoint(f64::from(x)) * ipoint(du[i])))
            .collect();
        let rows = (area.y0..=area.y1)
            .map(|y| std::array::from_fn(|i| ipoint(f64::from(y)) * ipoint(dv[i])))
            .collect();
        EdgeBeams {
            origin: point_box(self.eye),
            area,
            columns,
            rows,
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

/// The rays through a grid of continuous pixel positions, equal bit for bit to
/// [`Camera::ray`] at each: a ray's direction is the midpoint of `(c + x·du) + y·dv` in
/// interval arithmetic, whose first term depends on the column only and the product of the
/// second on the row only, so each is computed once.
#[derive(Clone, Debug)]
pub struct RayTable {
    eye: DVec3,
    /// `c + x·du` for every position `x`.
    columns: Vec<IBox>,
    /// `y·dv` for every position `y`.
    rows: Vec<IBox>,
}

impl RayTable {
    /// The ray through `(xs[i], ys[j])` of [`Camera::ray_table`].
    ///
    /// # Panics
    /// If `i` or `j` is out of range.
    pub fn ray(&self, i: usize, j: usize) -> Ray {
        let (x, y) = (&self.columns[i], &self.rows[j]);
        // Written out rather than by `array::from_fn`, whose closure was not inlined: a
        // call per coordinate (the primary-rays pass makes a ray per hit pixel).
        Ray {
            origin: self.eye,
            dir: DVec3::new(
                (x[0] + y[0]).mid(),
                (x[1] + y[1]).mid(),
                (x[2] + y[2]).mid(),
            ),
        }
    }
}

/// The beams of the pixel rectangles inside an area of the image, equal bit for bit to
/// [`Camera::beam`] of the same rectangles: a beam's directions are `c + x·du + y·dv` over
/// its rectangle, and in interval arithmetic (outward rounding is monotone) that is the
/// hull of the left and right edges' `c + x·du` plus the hull of the top and bottom
/// edges' `y·dv`, each computed once per edge of the area instead of once per beam.
#[derive(Clone, Debug)]
pub struct EdgeBeams {
    origin: IBox,
    area: PixelRect,
    /// `c + x·du` for every column edge `x` of the area.
    columns: Vec<IBox>,
    /// `y·dv` for every row edge `y`.
    rows: Vec<IBox>,
}

impl EdgeBeams {
    /// The beam of the pixels of `r`, which must lie inside the area.
    pub fn beam(&self, r: PixelRect) -> Beam {
        let a = self.area;
        debug_assert!(a.x0 <= r.x0 && r.x1 <= a.x1 && a.y0 <= r.y0 && r.y1 <= a.y1);
        let (left, right) = (
            &self.columns[(r.x0 - a.x0) as usize],
            &self.columns[(r.x1 - a.x0) as usize],
        );
        let (top, bottom) = (
            &self.rows[(r.y0 - a.y0) as usize],
            &self.rows[(r.y1 - a.y0) as usize],
        );
        Beam {
            origin: self.origin,
            dir: std::array::from_fn(|i| {
                left[i].convex_hull(right[i]) + top[i].convex_hull(bottom[i])
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wide view and a narrow, distant one (the benchmarks' near-orthographic view).
    fn cameras() -> [Camera; 2] {
        [
            Camera::new(
                DVec3::new(2.74, 2.19, 6.02),
                DVec3::ZERO,
                DVec3::Y,
                40.0,
                97,
                61,
            )
            .unwrap(),
            Camera::new(
                DVec3::new(0.0, 0.0, 1e5),
                DVec3::ZERO,
                DVec3::Y,
                0.001,
                64,
                64,
            )
            .unwrap(),
        ]
    }

    /// The ray table's rays are the camera's, bit for bit, at pixel centres, stratified
    /// offsets and corners.
    #[test]
    fn table_rays_are_the_camera_rays() {
        for cam in &cameras() {
            let offsets = [0.0, 0.5, 1.0 / 6.0, 5.0 / 6.0, 0.125];
            let (w, h) = (cam.width(), cam.height());
            let xs: Vec<f64> = (0..w)
                .flat_map(|x| offsets.map(|o| f64::from(x) + o))
                .collect();
            let ys: Vec<f64> = (0..h)
                .flat_map(|y| offsets.map(|o| f64::from(y) + o))
                .collect();
            let table = cam.ray_table(&xs, &ys);
            for (i, &x) in xs.iter().enumerate() {
                for (j, &y) in ys.iter().enumerate().step_by(7) {
                    let (a, b) = (table.ray(i, j), cam.ray(x, y));
                    assert_eq!(a.origin, b.origin);
                    for k in 0..3 {
                        assert_eq!(a.dir[k].to_bits(), b.dir[k].to_bits(), "({x}, {y})");
                    }
                }
            }
        }
    }

    /// Every rectangle of a few areas of two cameras: the edge beams are the camera's beams,
    /// bit for bit.
    #[test]
    fn edge_beams_are_the_camera_beams() {
        for cam in &cameras() {
            let area = PixelRect {
                x0: 3,
                y0: 5,
                x1: 3 + 17.min(cam.width() - 3),
                y1: 5 + 13.min(cam.height() - 5),
            };
            let edges = cam.edge_beams(area);
            for y0 in area.y0..area.y1 {
                for y1 in y0 + 1..=area.y1 {
                    for x0 in area.x0..area.x1 {
                        for x1 in x0 + 1..=area.x1 {
                            let r = PixelRect { x0, y0, x1, y1 };
                            let b = edges.beam(r);
                            let want = cam.beam(
                                f64::from(x0),
                                f64::from(y0),
                                f64::from(x1),
                                f64::from(y1),
                            );
                            assert_eq!(b.origin, want.origin);
                            for i in 0..3 {
                                assert_eq!(b.dir[i].inf().to_bits(), want.dir[i].inf().to_bits());
                                assert_eq!(b.dir[i].sup().to_bits(), want.dir[i].sup().to_bits());
                            }
                        }
                    }
                }
            }
        }
    }
}
