//! The TOML scene file format: [`Scene::from_toml`] (whose documentation describes the
//! format in full), [`Scene::load`], the built-in [`DEFAULT_SCENE`] and [`Scene::catalog`].
//!
//! Loading has three stages: the TOML text is parsed into a syntax tree with spans
//! (`toml::de::DeTable`), deserialised into the file's shape (`Raw*` structs, unknown keys
//! refused), then checked and built into a [`Scene`]. Errors of the second stage carry
//! only a byte span; the field path is recovered by finding the key or value of the tree
//! whose span matches it. Errors of the third stage know their field path, and the line
//! and column are looked up in the tree.
//!
//! The stages live in modules of their own: the file's shape in `schema`, spans, field
//! paths and value checks in `diagnostics`, and the building of the parts in `surface`,
//! `transform`, `csg`, `camera`, `lights` and `settings`; this module ties them together.

use std::collections::HashMap;
use std::path::Path;

use glam::DVec3;
use implicit_expr::Context;
use serde::Deserialize;

use super::animation::Animation;
use super::camera::camera;
use super::csg::{Ref, csg_tree, ref_path, resolve_csg};
use super::diagnostics::Doc;
use super::geometry::{Csg, Geometry, Leaf};
use super::lights::lights;
use super::mesh::with_meshes;
use super::mesh_file::build_meshes;
use super::model::{Light, PointLight, Scene};
use super::schema::{RawCamera, RawRender, RawScene, RawSurface};
use super::settings::render_settings;
use super::surface::{build_surface, material, place};
use super::transform::Affine;
use super::transform::transform;
use crate::error::Error;

/// The built-in default scene (TOML): the catalog's chubs, a sphere and a cube with a
/// spherical hole (a CSG difference) on a floor slab, one point light, shadows on.
pub const DEFAULT_SCENE: &str = include_str!("../../scenes/default.toml");

/// Builds and checks the whole scene. Also returns the automatic light position when the
/// camera is automatic.
fn build(
    doc: &Doc<'_>,
    raw: &RawScene,
    base: Option<&Path>,
    time: Option<f64>,
) -> Result<(Scene, Option<DVec3>), Error> {
    let background = match raw.background {
        Some(c) => doc.color("background", c)?,
        None => [0.08, 0.09, 0.12],
    };
    let ambient = match raw.ambient {
        Some(v) => doc.unit("ambient", v)? as f32,
        None => 0.15,
    };
    let settings = render_settings(doc, &raw.render)?;
    if raw.surfaces.is_empty() {
        return Err(doc.err(
            "surfaces",
            "the scene has no surfaces (add a [[surfaces]] or [[meshes]] table)",
        ));
    }
    // Surfaces: source, parameters, bounds, transform, material.
    let mut built = Vec::with_capacity(raw.surfaces.len());
    for (i, s) in raw.surfaces.iter().enumerate() {
        let b = build_surface(doc, i, s, base, time)?;
        let aff = match &s.transform {
            Some(t) => transform(doc, &format!("surfaces[{i}].transform"), t)?,
            None => Affine::new([0.0; 3], None, [1.0; 3])
                .ok_or_else(|| doc.err("surfaces", "internal error: identity"))?,
        };
        let m = material(doc, &format!("surfaces[{i}].material"), &s.material)?;
        built.push((b, aff, m));
    }
    // Names: one namespace for surfaces and csg nodes.
    let mut names: HashMap<&str, Ref> = HashMap::new();
    let mut order_names: Vec<&str> = Vec::new();
    let entries = built
        .iter()
        .enumerate()
        .map(|(i, b)| (b.0.name.as_str(), Ref::Surface(i)))
        .chain(
            raw.csg
                .iter()
                .enumerate()
                .map(|(j, c)| (c.name.as_str(), Ref::Csg(j))),
        );
    for (name, r) in entries {
        if let Some(&prev) = names.get(name) {
            let path = match r {
                Ref::Surface(i) if raw.surfaces[i].name.is_none() => ref_path(r),
                _ => format!("{}.name", ref_path(r)),
            };
            return Err(doc.err(
                &path,
                format!(
                    "duplicate name '{name}' (also the name of {}); give each surface and csg \
                     node its own name",
                    ref_path(prev)
                ),
            ));
        }
        names.insert(name, r);
        order_names.push(name);
    }
    let (kids, _) = resolve_csg(doc, &raw.csg, &names, &order_names)?;
    let meshes = build_meshes(doc, &raw.meshes, base, &order_names)?;
    // Which nodes are drawn on their own, and which surfaces are used at all.
    let mut used_surface = vec![false; raw.surfaces.len()];
    let mut used_csg = vec![false; raw.csg.len()];
    for k in &kids {
        for r in k {
            match *r {
                Ref::Surface(i) => used_surface[i] = true,
                Ref::Csg(j) => used_csg[j] = true,
            }
        }
    }
    let mut tops: Vec<Ref> = Vec::new();
    for (i, s) in raw.surfaces.iter().enumerate() {
        if s.visible.unwrap_or(true) && !used_surface[i] {
            tops.push(Ref::Surface(i));
        }
    }
    for (j, c) in raw.csg.iter().enumerate() {
        if c.visible.unwrap_or(true) && !used_csg[j] {
            tops.push(Ref::Csg(j));
        }
    }
    if tops.is_empty() {
        return Err(doc.err(
            "surfaces",
            "nothing to draw: every surface and csg node has visible = false",
        ));
    }
    let mut drawn = vec![false; raw.surfaces.len()];
    let mut stack = tops.clone();
    let mut seen_csg = vec![false; raw.csg.len()];
    while let Some(r) = stack.pop() {
        match r {
            Ref::Surface(i) => drawn[i] = true,
            Ref::Csg(j) if !seen_csg[j] => {
                seen_csg[j] = true;
                stack.extend(kids[j].iter().copied());
            }
            Ref::Csg(_) => {}
        }
    }
    // Leaves: the drawn surfaces, placed in one context.
    let mut geo = Context::new();
    let mut leaves = Vec::new();
    let mut leaf_of = vec![usize::MAX; raw.surfaces.len()];
    for (i, (b, aff, m)) in built.iter_mut().enumerate() {
        if !drawn[i] {
            continue;
        }
        let (node, bounds) = place(doc, i, b, aff, &mut geo)?;
        leaf_of[i] = leaves.len();
        leaves.push(Leaf {
            name: b.name.clone(),
            node,
            material: *m,
            bounds,
            clipped: b.clip,
        });
    }
    let objects: Vec<Csg> = tops
        .iter()
        .map(|r| match *r {
            Ref::Surface(i) => Csg::Leaf(leaf_of[i]),
            Ref::Csg(j) => csg_tree(j, &raw.csg, &kids, &leaf_of),
        })
        .collect();
    let geometry = Geometry::new(geo, leaves, objects).map_err(|e| doc.err("", e))?;
    let (camera, auto_light) = camera(doc, &raw.camera, &with_meshes(geometry.bounds(), &meshes))?;
    let lights = lights(doc, &raw.lights)?;
    Ok((
        Scene {
            name: doc.file.to_string(),
            camera,
            background,
            ambient,
            lights,
            geometry,
            meshes,
            settings,
            proofs: None,
        },
        auto_light,
    ))
}

/// The implicit surface of a scene of meshes alone: `f = 1` (no point of it) over a small
/// box at the origin, so that the implicit searches end at once.
fn empty_implicit_surface() -> RawSurface {
    RawSurface {
        name: Some("no-implicit-surface".into()),
        formula: Some("1".into()),
        bounds: Some([[-1e-3; 3], [1e-3; 3]]),
        ..RawSurface::default()
    }
}

impl Scene {
    /// Reads a scene from TOML text.
    ///
    /// `file` names the text in messages; `base_dir` is the folder against which relative
    /// `.vm` paths are resolved (the working directory when `None`). Never panics, whatever
    /// the text.
    ///
    /// # Example
    ///
    /// ```toml
    /// background = [0.08, 0.09, 0.12]   # optional, default [0.08, 0.09, 0.12]
    /// ambient = 0.15                    # optional, default 0.15
    ///
    /// [camera]                          # required (may be empty: an automatic camera)
    /// eye = [0.0, 2.0, 7.0]             # eye and look_at: both or neither
    /// look_at = [0.0, 0.0, 0.0]
    /// up = [0.0, 1.0, 0.0]              # default [0, 1, 0]
    /// fov = 40.0                        # vertical, degrees, default 40
    /// width = 640                       # default 640
    /// height = 480                      # default 480
    ///
    /// [[surfaces]]
    /// name = "knot"                     # default: the catalog name, the .vm file stem, or surface-N
    /// catalog = "orthocircle"           # exactly one of catalog, formula, vm
    /// params = { a = 0.1 }              # overrides the catalog's defaults
    /// transform = { translate = [-2.0, 0.0, 0.0], rotate = [0.0, 30.0, 0.0], scale = 1.2 }
    /// material = { color = [0.9, 0.5, 0.2], specular = 0.4, shininess = 40.0 }
    ///
    /// [[surfaces]]
    /// name = "ball"
    /// formula = "x^2 + y^2 + z^2 - r^2"
    /// params = { r = 1.0 }
    /// bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]   # required for formula and vm
    /// visible = false                   # only used by the csg node below
    ///
    /// [[surfaces]]
    /// name = "cube"
    /// formula = "max(abs(x), abs(y), abs(z)) - 0.8"
    /// bounds = [[-0.8, -0.8, -0.8], [0.8, 0.8, 0.8]]
    ///
    /// [[csg]]
    /// name = "holed-cube"
    /// op = "difference"                 # union | intersection | difference
    /// children = ["cube", "ball"]       # surfaces or other csg nodes
    ///
    /// [[lights]]
    /// type = "point"
    /// position = [-4.0, 6.0, 5.0]
    /// color = [1.0, 1.0, 1.0]           # default white
    /// intensity = 1.0                   # default 1
    ///
    /// [render]                          # optional; every key optional
    /// root_finder = "newton-alefeld-hansen"
    /// epsilon = 1e-6
    /// max_steps = 100000
    /// aa = "iaa:1:0.1:2"                # none | iaa | iaa:D | iaa:D:T | iaa:D:T:M | ss:N (N × N rays per pixel, N ≤ 16);
    ///                                   # default iaa:D:0.1:2 with primary = "screen-boxes" (D: undecided_depth;
    ///                                   # none at 0), none with the other primary modes
    /// iaa_depth = 4
    /// iaa_threshold = 0.05
    /// iaa_limit_rays = 2                # iaa: M × M rays in a part left undecided at the depth limit
    /// primary = "screen-boxes"          # screen-boxes | screen-rays | per-pixel | octree
    /// undecided_depth = 1               # screen-boxes: Undecided pixels' beams split to this depth
    /// rays_per_undecided = 9            # screen-rays: point rays per Undecided pixel
    /// rays_per_pixel = 1
    /// t_final_width = 0.05
    /// grid = 16
    /// shadows = true
    /// precision = "f64"                 # f64 | f32 (interval evaluation of the scene function)
    /// ```
    ///
    /// An `[animation]` table (`frames = [first, last]`, `rate = 25`) makes the file an
    /// animation whose numbers may be formulas of the frame time `t`
    /// ([`Animation`](super::Animation), `docs/animation.md`); this function builds its
    /// first frame.
    ///
    /// # Reference
    ///
    /// Unknown keys are errors everywhere. Numbers must be finite (TOML's `nan` and `inf` are
    /// refused); integers are accepted where a float is expected. Colours are `[r, g, b]` in
    /// `[0, 1]`.
    ///
    /// **Top level**: `background` (colour), `ambient` (in `[0, 1]`), the tables `camera`,
    /// `render`, and the arrays of tables `surfaces`, `csg`, `meshes` and `lights` (at least
    /// one surface or mesh; a scene of meshes alone gets the empty implicit surface `f = 1`
    /// over a small box at the origin, named `no-implicit-surface`).
    ///
    /// **`[camera]`**: `eye` and `look_at` (points), `up` (not zero, not parallel to the view
    /// direction), `fov` (in `(0, 180)`), `width` and `height` (1 to 16384). Without `eye`
    /// and `look_at` the camera looks at the centre of the scene bounds from the direction
    /// `(1, 0.8, 2.2)`, far enough for the bounding sphere to fit the field of view.
    ///
    /// **`[[surfaces]]`**: a leaf surface `f = 0`, solid where `f < 0`.
    /// * the source, exactly one of: `formula` (the formula language of
    ///   [`implicit_expr::parse`] in `x`, `y`, `z` and the names of `params`), `catalog` (a
    ///   name of [`implicit_expr::catalog`]), or `vm` (a `.vm` file, see [`implicit_expr::vm`];
    ///   a relative path is resolved against the scene file's folder).
    /// * `params`: a table of numbers. For a formula it declares its parameters; for a catalog
    ///   surface it overrides the defaults (unknown names are errors); a `.vm` file has none.
    ///   Values are the doubles nearest the decimals written, bound as constants.
    /// * `bounds = [[x0, y0, z0], [x1, y1, z1]]` with `x0 < x1` etc., in the surface's own
    ///   coordinates: the box that holds the surface (required for `formula` and `vm`; the
    ///   catalog's box by default). Rays search for the scene's surfaces only inside the hull of
    ///   the boxes, so a surface reaching outside its box may be cut there.
    /// * `clip`: intersect the solid with its box, `max(f, b)` with the box function
    ///   `b = max(x0 − x, x − x1, y0 − y, y − y1, z0 − z, z − z1)` (exact constants, zero set
    ///   inside the closed box). Default: the catalog's [`is_clipped`], else `false`.
    /// * `transform = { translate = [..], rotate = .., scale = .. }`, each optional: the surface
    ///   is scaled (`scale = s` or `[sx, sy, sz]`, no zero factor), then rotated (`rotate =
    ///   [ax, ay, az]`: degrees about `x`, then `y`, then `z`; or `{ axis = [..], angle = deg }`),
    ///   then translated: `p_world = M · p + t` with `M = R · S`. The leaf is `f(A · p + b)` with
    ///   `A ≈ M⁻¹`, `b ≈ −A · t` computed in `f64`: the rendered surface is the zero set for
    ///   those `f64` coefficients (exact at multiples of 90°), and its world box is proven to
    ///   enclose it (see `transform.rs`).
    /// * `material = { color, specular, shininess }`: Phong material; `specular` in `[0, 1]`,
    ///   `shininess` positive (defaults: [`Material::default`](super::Material::default)).
    /// * `visible` (default `true`): `false` keeps the surface out of the picture unless a csg
    ///   node uses it. A surface that a csg node uses is never drawn on its own.
    ///
    /// **`[[csg]]`**: `name`, `op` (`union` and `intersection`: 2 or more children;
    /// `difference`: exactly 2, the first minus the second), `children` (names of surfaces or
    /// csg nodes, in any order; cycles are errors), `visible` as for surfaces. The drawn
    /// objects are the visible surfaces and csg nodes that no csg node uses; each leaf keeps
    /// its own material. Names of surfaces and csg nodes share one namespace and are unique.
    ///
    /// **`[[meshes]]`**: a triangle mesh beside the implicit surfaces
    /// ([`crate::mesh`]). Exactly one of `obj` (a Wavefront OBJ file, relative to the scene
    /// file's folder; polygons split into fans) and `polygons` (a list of polygons, each a
    /// list of at least 3 `[x, y, z]` vertices, split into fans from the first vertex);
    /// `transform` and `material` as for surfaces; `name` (default: the OBJ file's stem or
    /// `mesh-N`) in the surfaces' namespace. The vertices as computed in `f64` (`M · p + t`)
    /// are the rendered mesh; triangles without area are left out, and a mesh with none is
    /// an error. Meshes are not csg children.
    ///
    /// **`[[lights]]`**: `type = "point"` with `position`, `color` and `intensity` (`≥ 0`);
    /// the light's colour is `color · intensity`. `type = "area"` with the same `color` and
    /// `intensity` is a uniform parallelogram: an axis-aligned square `center`, `size`
    /// (`≥ 0`), `normal` (`"x"`, `"y"` or `"z"`), or `corner`, `edge_u`, `edge_v`. An area
    /// light of size zero is a point light.
    ///
    /// **`[render]`**: `root_finder` (a [`RootMethod`] name), `epsilon` (positive),
    /// `max_steps` (at least 1), `sampling_step` (in `(0, 1]`) and `lipschitz` (positive) for
    /// the unreliable baselines, `aa` (see [`AaMode`]'s [`FromStr`]; where absent,
    /// [`AaMode::DEFAULT`](super::AaMode::DEFAULT) in the screen-boxes primary mode and none
    /// in the others; where set, it decides the primary pass: IAA resolves the screen boxes'
    /// pixels by their beams, `ss:N` traces `N × N` rays per pixel), `iaa_depth` (1 to 8),
    /// `iaa_threshold` (positive) and `iaa_limit_rays` (1 to 16) for the IAA mode the render
    /// uses, `primary` (see [`PrimaryMode`]'s
    /// [`FromStr`]), `undecided_depth` (0 to 8), `rays_per_undecided` and `rays_per_pixel`
    /// (square numbers 1 to 256),
    /// `t_final_width` (positive), `grid` (0 to 256; 0: no grid), `shadows`,
    /// `shadow_method` (see [`ShadowSpec`](crate::shadow::ShadowSpec); default
    /// `certified:1:1024:64`),
    /// `precision` (`"f64"` or `"f32"`, see [`Precision`](crate::ray::Precision); default
    /// `"f64"`).
    ///
    /// # Errors
    ///
    /// Every problem is an [`Error::Scene`] naming the file, the field path
    /// (`lights[1].position`, `surfaces[0].params.a`, `csg[2].children[1]`) and the problem,
    /// with the line and column where the field is written:
    ///
    /// ```
    /// use beam_trace::Scene;
    ///
    /// let text = "[camera]\n[[surfaces]]\ncatalog = \"sphre\"\n";
    /// let err = Scene::from_toml(text, "my.toml", None).unwrap_err();
    /// assert_eq!(
    ///     err.to_string(),
    ///     "my.toml: surfaces[0].catalog: unknown surface 'sphre'; did you mean 'sphere'? \
    ///      (line 3, column 11)"
    /// );
    /// ```
    ///
    /// [`is_clipped`]: implicit_expr::catalog::Surface::is_clipped
    /// [`AaMode`]: super::AaMode
    /// [`PrimaryMode`]: super::PrimaryMode
    /// [`FromStr`]: std::str::FromStr
    /// [`RootMethod`]: crate::root::RootMethod
    pub fn from_toml(text: &str, file: &str, base_dir: Option<&Path>) -> Result<Scene, Error> {
        let doc = Doc::parse(file, text)?;
        if doc.has_key("animation") {
            let a = Animation::from_doc(&doc, base_dir)?;
            return a.scene(*a.frames().start());
        }
        Scene::from_doc(&doc, base_dir, None)
    }

    /// [`Scene::from_toml`] of a static file, with the frame time `t` bound in the surface
    /// formulas when `time` is given (a frame of an [`Animation`]).
    pub(super) fn from_toml_at(
        text: &str,
        file: &str,
        base_dir: Option<&Path>,
        time: Option<f64>,
    ) -> Result<Scene, Error> {
        Scene::from_doc(&Doc::parse(file, text)?, base_dir, time)
    }

    /// The scene of a parsed static document (see [`Scene::from_toml_at`]).
    fn from_doc(doc: &Doc<'_>, base_dir: Option<&Path>, time: Option<f64>) -> Result<Scene, Error> {
        let tree = doc.tree.clone().expect("a parsed document");
        let mut raw = RawScene::deserialize(toml::Deserializer::from(tree))
            .map_err(|e| doc.serde_error(&e))?;
        if raw.surfaces.is_empty() && !raw.meshes.is_empty() {
            raw.surfaces.push(empty_implicit_surface());
        }
        build(doc, &raw, base_dir, time).map(|(s, _)| s)
    }

    /// Reads the scene file at `path`; relative `.vm` paths are resolved against its folder.
    ///
    /// # Errors
    /// [`Error::Io`] naming the path when it cannot be read, otherwise as
    /// [`Scene::from_toml`].
    pub fn load(path: &Path) -> Result<Scene, Error> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let name = path.display().to_string();
        Scene::from_toml(&text, &name, path.parent())
    }

    /// The built-in scene, [`DEFAULT_SCENE`].
    pub fn default_scene() -> Scene {
        Scene::from_toml(DEFAULT_SCENE, "<built-in>", None)
            .expect("the built-in scene is valid (checked by a test)")
    }

    /// A scene of the catalog surface `name` alone (default parameters, its box, clipped
    /// where the catalog says so, default material) with an automatic camera looking at its
    /// box (field of view 40°) and one white point light above-left of the camera.
    ///
    /// # Errors
    /// [`Error::Scene`] for an unknown name (with the closest name as a hint) or an image
    /// size outside 1 to 16384.
    pub fn catalog(name: &str, width: u32, height: u32) -> Result<Scene, Error> {
        let file = format!("catalog:{name}");
        let doc = Doc::detached(&file);
        let raw = RawScene {
            camera: RawCamera {
                width: Some(width.into()),
                height: Some(height.into()),
                ..RawCamera::default()
            },
            background: None,
            ambient: None,
            surfaces: vec![RawSurface {
                name: Some(name.to_string()),
                catalog: Some(name.to_string()),
                ..RawSurface::default()
            }],
            meshes: Vec::new(),
            csg: Vec::new(),
            lights: Vec::new(),
            render: RawRender::default(),
            animation: None,
        };
        let (mut scene, light) = build(&doc, &raw, None, None)?;
        if let Some(position) = light {
            scene.lights.push(Light::Point(PointLight {
                position,
                color: [1.0; 3],
            }));
        }
        Ok(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_of_serde_errors() {
        let text = "[camera]\n[[surfaces]]\ncatalog = 'sphere'\n[[surfaces]]\ncatalog = 'chubs'\nmaterial = { colour = [1, 1, 1] }\n";
        let e = Scene::from_toml(text, "t", None).unwrap_err();
        let Error::Scene { path, message, .. } = e else {
            panic!()
        };
        assert_eq!(path, "surfaces[1].material.colour");
        assert!(
            message.starts_with("unknown field 'colour', expected"),
            "{message}"
        );
        assert!(message.contains("did you mean 'color'?"), "{message}");
        assert!(message.ends_with("(line 6, column 14)"), "{message}");
    }
}
