//! A catalog surface set up for ray casting, as the root finder comparisons use it (the
//! `root-finders` example and the `root_finders` benchmark): its function with the
//! parameters bound to their defaults (not clipped), a camera looking at its bounding box
//! from the direction `(1, 0.8, 2.2)` with a 40° field of view, and rays clipped to the box.
//! (A full scene of a catalog surface, clipped and lit, is `beam_trace::Scene::catalog`.)

use beam_trace::Camera;
use beam_trace::Error;
use beam_trace::ray::{IBox, Ray};
use beam_trace::scene::{Csg, Geometry, Leaf};
use glam::DVec3;
use implicit_expr::{Context, catalog};
use interval_core::Interval;

/// The surfaces of thesis Table 4.1, in its order.
pub const TABLE_4_1: [&str; 8] = [
    "sphere",
    "drop",
    "chubs",
    "crosscap",
    "gumdrop-torus",
    "horned-cube",
    "mcmullen-k3",
    "kusner-schmitt",
];

/// One catalog surface, ready to cast rays at.
#[derive(Clone, Debug)]
pub struct CatalogView {
    /// The surface's catalog name.
    pub name: &'static str,
    /// Its geometry (one unclipped leaf).
    pub geometry: Geometry,
    /// The camera, `size × size` pixels.
    pub camera: Camera,
    /// The surface's bounding box, where rays are searched.
    pub bounds: IBox,
}

impl CatalogView {
    /// The view of catalog surface `name` at `size × size` pixels.
    ///
    /// Returns an error for an unknown name or a surface that cannot be compiled.
    pub fn new(name: &str, size: u32) -> Result<Self, Error> {
        let s = catalog::get(name)?;
        let mut ctx = Context::new();
        let f = s.build(&mut ctx)?;
        let mut map = Vec::new();
        for &(p, v) in s.params {
            let var = ctx.find_var(p).ok_or_else(|| Error::Setting {
                name: name.to_string(),
                message: format!("parameter {p} not declared"),
            })?;
            map.push((var, ctx.constant(v)?));
        }
        let f = ctx.substitute(f, &map);
        // The bound parameters' slots are still declared in `ctx`; a fresh context holds
        // only x, y, z and what f uses.
        let (ctx, f) = ctx.extract(f);
        let bounds = s.bounding_box();
        let leaf = Leaf {
            name: s.name.to_string(),
            node: f,
            material: Default::default(),
            bounds,
            clipped: false,
        };
        let geometry = Geometry::new(ctx, vec![leaf], vec![Csg::Leaf(0)])?;
        let lo = DVec3::new(bounds[0].inf(), bounds[1].inf(), bounds[2].inf());
        let hi = DVec3::new(bounds[0].sup(), bounds[1].sup(), bounds[2].sup());
        let center = (lo + hi) * 0.5;
        let fov: f64 = 40.0;
        let distance = (hi - lo).length() * 0.5 / (fov.to_radians() * 0.5).sin();
        let eye = center + DVec3::new(1.0, 0.8, 2.2).normalize() * distance;
        let camera = Camera::new(eye, center, DVec3::Y, fov, size, size)?;
        Ok(Self {
            name: s.name,
            geometry,
            camera,
            bounds,
        })
    }

    /// The ray through the centre of pixel `(i, j)` and its parameter range inside the
    /// bounding box from `t = 0` on (outward rounded), or `None` when it misses the box.
    pub fn ray(&self, i: u32, j: u32) -> (Ray, Option<Interval<f64>>) {
        let ray = self.camera.ray(f64::from(i) + 0.5, f64::from(j) + 0.5);
        let forward = Interval::new_unchecked(0.0, f64::INFINITY);
        let t = ray.beam().t_range_within(&self.bounds, forward);
        (ray, t)
    }
}
