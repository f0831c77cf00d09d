//! Scene files: the `scenes/` folder, the built-in scene, catalog scenes, CSG and transform
//! mapping, and the corpus of malformed scenes in `tests/bad_scenes/` (each starts with a
//! line `# expect: <part of the error message>`).

use std::path::{Path, PathBuf};

use beam_trace::scene::{AaMode, Csg, DEFAULT_SCENE, PrimaryMode};
use beam_trace::{Error, Light, RootMethod, Scene};
use glam::DVec3;
use implicit_expr::catalog;

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn toml_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    files
}

/// The value of leaf `i` of the scene at `p`.
fn leaf_value(scene: &Scene, i: usize, p: DVec3) -> f64 {
    let g = &scene.geometry;
    g.context()
        .eval::<f64>(g.leaves()[i].node, &[p.x, p.y, p.z])
        .unwrap()
}

/// The value of the scene function at `p`.
fn scene_value(scene: &Scene, p: DVec3) -> f64 {
    let g = &scene.geometry;
    g.context().eval::<f64>(g.root(), &[p.x, p.y, p.z]).unwrap()
}

fn load_str(text: &str) -> Result<Scene, Error> {
    Scene::from_toml(text, "test.toml", None)
}

fn scene_error(text: &str) -> (String, String) {
    match load_str(text) {
        Err(Error::Scene { path, message, .. }) => (path, message),
        Err(e) => panic!("not a scene error: {e}"),
        Ok(_) => panic!("loaded: {text}"),
    }
}

#[test]
fn every_scene_file_loads() {
    let files = toml_files(&repo_root().join("scenes"));
    assert!(files.len() >= catalog::all().len() + 3, "{files:?}");
    for f in &files {
        let scene = Scene::load(f).unwrap_or_else(|e| panic!("{e}"));
        assert!(!scene.geometry.leaves().is_empty());
        assert!(!scene.lights.is_empty(), "{}", f.display());
        assert_eq!(scene.geometry.context().var_count(), 3);
    }
}

#[test]
fn one_scene_file_per_catalog_surface() {
    for s in catalog::all() {
        let path = repo_root().join("scenes").join(format!("{}.toml", s.name));
        let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let leaves = scene.geometry.leaves();
        assert_eq!(leaves.len(), 1);
        assert_eq!(leaves[0].name, s.name);
        // The camera looks at the centre of the box: the central ray passes near it.
        let b = s.bounding_box();
        let centre = DVec3::new(b[0].mid(), b[1].mid(), b[2].mid());
        let (w, h) = (scene.camera.width() as f64, scene.camera.height() as f64);
        let ray = scene.camera.ray(w / 2.0, h / 2.0);
        let d = ray.dir.normalize();
        let to_centre = centre - ray.origin;
        let miss = (to_centre - to_centre.dot(d) * d).length();
        assert!(miss < 0.02, "{}: {miss}", s.name);
    }
}

#[test]
fn default_scene_file_is_the_built_in_one() {
    let text = std::fs::read_to_string(repo_root().join("scenes/default.toml")).unwrap();
    assert_eq!(text, DEFAULT_SCENE);
}

#[test]
fn default_scene_loads() {
    let s = Scene::default_scene();
    assert_eq!(s.name, "<built-in>");
    assert_eq!((s.camera.width(), s.camera.height()), (640, 480));
    assert_eq!(s.lights.len(), 1);
    assert!(s.settings.shadows);
    assert_eq!(s.settings.aa, None);
    assert_eq!(s.settings.aa_mode(), AaMode::DEFAULT);
    assert_eq!(s.settings.root_finder, RootMethod::NewtonAlefeldHansen);
    let names: Vec<&str> = s
        .geometry
        .leaves()
        .iter()
        .map(|l| l.name.as_str())
        .collect();
    assert_eq!(names, ["chubs", "ball", "cube", "hole", "floor"]);
    // Drawn: chubs, ball, floor on their own, then the difference cube − hole.
    assert_eq!(
        s.geometry.objects(),
        &[
            Csg::Leaf(0),
            Csg::Leaf(1),
            Csg::Leaf(4),
            Csg::Difference(Box::new(Csg::Leaf(2)), Box::new(Csg::Leaf(3))),
        ]
    );
    // The sphere at the origin, the holed cube around (2.6, −0.45, 0).
    assert!(scene_value(&s, DVec3::ZERO) < 0.0);
    assert!(
        scene_value(&s, DVec3::new(2.6, -0.45, 0.0)) > 0.0,
        "inside the hole"
    );
    assert!(scene_value(&s, DVec3::new(2.6, -0.45 + 0.78, 0.05)) > 0.0);
    assert!(
        scene_value(&s, DVec3::new(2.6 + 0.75, -0.45 + 0.75, 0.0)) < 0.0,
        "a corner"
    );
}

#[test]
fn catalog_scenes_load() {
    for s in catalog::all() {
        let scene = Scene::catalog(s.name, 64, 48).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.geometry.leaves().len(), 1);
        assert_eq!((scene.camera.width(), scene.camera.height()), (64, 48));
        assert_eq!(scene.lights.len(), 1);
        let b = s.bounding_box();
        let leaf = &scene.geometry.leaves()[0];
        let gb = scene.geometry.bounds();
        assert_eq!(leaf.clipped, s.is_clipped(), "{}", s.name);
        for k in 0..3 {
            let lb = leaf.bounds[k];
            assert_eq!((lb.inf(), lb.sup()), (b[k].inf(), b[k].sup()));
            // The search bounds are the box, with a margin around a clipped one.
            assert!(lb.subset(gb[k]), "{}", s.name);
            if !s.is_clipped() {
                assert_eq!((gb[k].inf(), gb[k].sup()), (b[k].inf(), b[k].sup()));
            }
        }
        // The light is above the camera and to its left.
        let Light::Point(l) = scene.lights[0] else {
            panic!("a point light")
        };
        let eye = scene.camera.eye();
        assert!(l.position.y > eye.y, "{}", s.name);
        let left = scene.camera.ray(0.0, 24.0).dir - scene.camera.ray(64.0, 24.0).dir;
        assert!((l.position - eye).dot(left) > 0.0, "{}", s.name);
        // The eye is outside the box.
        assert!((0..3).any(|k| !gb[k].contains(eye.to_array()[k])));
    }
    let e = Scene::catalog("sphre", 10, 10).unwrap_err().to_string();
    assert!(
        e.contains("unknown surface 'sphre'; did you mean 'sphere'?"),
        "{e}"
    );
    let e = Scene::catalog("sphere", 0, 10).unwrap_err().to_string();
    assert!(
        e.contains("camera.width: must be between 1 and 16384"),
        "{e}"
    );
}

#[test]
fn catalog_clipping_follows_the_catalog() {
    // The drop is clipped at x = 1: beyond it the clipped leaf is positive although the
    // formula is negative there.
    let drop = Scene::catalog("drop", 8, 8).unwrap();
    let p = DVec3::new(1.1, 0.0, 0.0);
    assert!(leaf_value(&drop, 0, p) > 0.0);
    let text = "[camera]\n[[surfaces]]\ncatalog = \"drop\"\nclip = false\n[[lights]]\ntype = \"point\"\nposition = [0.0, 5.0, 5.0]\n";
    let unclipped = load_str(text).unwrap();
    assert!(leaf_value(&unclipped, 0, p) < 0.0);
    // Inside the box both agree.
    let q = DVec3::new(0.5, 0.1, 0.0);
    assert_eq!(
        leaf_value(&drop, 0, q).signum(),
        leaf_value(&unclipped, 0, q).signum()
    );
}

#[test]
fn csg_maps_to_the_tree() {
    let s = Scene::load(&repo_root().join("scenes/csg.toml")).unwrap();
    let names: Vec<&str> = s
        .geometry
        .leaves()
        .iter()
        .map(|l| l.name.as_str())
        .collect();
    assert_eq!(names, ["cube", "ball", "drill-x", "drill-y", "drill-z"]);
    use Csg::*;
    assert_eq!(
        s.geometry.objects(),
        &[Difference(
            Box::new(Intersection(vec![Leaf(0), Leaf(1)])),
            Box::new(Union(vec![Leaf(2), Leaf(3), Leaf(4)])),
        )]
    );
    // The drills run along x, y and z.
    for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
        assert!(scene_value(&s, 0.9 * axis) > 0.0, "drilled at {axis}");
    }
    assert!(
        scene_value(&s, DVec3::new(0.9, 0.9, 0.0)) < 0.0,
        "material between drills"
    );
    assert!(
        scene_value(&s, DVec3::splat(0.99)) > 0.0,
        "the corner is rounded off"
    );
}

#[test]
fn csg_order_and_visibility() {
    // A csg node may name a later one; an invisible surface that nothing uses is no leaf;
    // an invisible csg node is not drawn.
    let text = r#"
[camera]
[[csg]]
name = "outer"
op = "union"
children = ["inner", "c"]
[[csg]]
name = "inner"
op = "intersection"
children = ["a", "b"]
[[csg]]
name = "hidden"
op = "union"
children = ["a", "d"]
visible = false
[[surfaces]]
name = "a"
catalog = "sphere"
[[surfaces]]
name = "b"
catalog = "chubs"
[[surfaces]]
name = "unused"
catalog = "steiner"
visible = false
[[surfaces]]
name = "c"
catalog = "blobby"
[[surfaces]]
name = "d"
catalog = "drop"
[[surfaces]]
name = "e"
catalog = "twist"
"#;
    let s = load_str(text).unwrap();
    let names: Vec<&str> = s
        .geometry
        .leaves()
        .iter()
        .map(|l| l.name.as_str())
        .collect();
    assert_eq!(names, ["a", "b", "c", "e"]);
    use Csg::*;
    assert_eq!(
        s.geometry.objects(),
        &[
            Leaf(3),
            Union(vec![Intersection(vec![Leaf(0), Leaf(1)]), Leaf(2)]),
        ]
    );
    assert!(s.lights.is_empty());
}

/// `R = Rz(c) · Ry(b) · Rx(a)` in degrees.
fn euler(a: f64, b: f64, c: f64) -> glam::DMat3 {
    glam::DMat3::from_rotation_z(c.to_radians())
        * glam::DMat3::from_rotation_y(b.to_radians())
        * glam::DMat3::from_rotation_x(a.to_radians())
}

#[test]
fn transforms_move_the_surface() {
    let formula = "x^2 + 2*y^2 + 3*z^2 + x*y - z - 1";
    let local = |p: DVec3| p.x * p.x + 2.0 * p.y * p.y + 3.0 * p.z * p.z + p.x * p.y - p.z - 1.0;
    let cases: [(&str, glam::DMat3, DVec3); 4] = [
        (
            "translate = [1.0, -2.0, 0.5]",
            glam::DMat3::IDENTITY,
            DVec3::new(1.0, -2.0, 0.5),
        ),
        (
            "rotate = [10.0, 20.0, 30.0], scale = 2.0",
            euler(10.0, 20.0, 30.0) * 2.0,
            DVec3::ZERO,
        ),
        (
            "translate = [0.5, 0.25, -3.0], rotate = { axis = [1.0, 1.0, 0.0], angle = 45.0 }, \
             scale = [1.0, 0.5, 3.0]",
            glam::DMat3::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 45f64.to_radians())
                * glam::DMat3::from_diagonal(DVec3::new(1.0, 0.5, 3.0)),
            DVec3::new(0.5, 0.25, -3.0),
        ),
        (
            "rotate = [0.0, 0.0, 90.0], scale = -1.5",
            euler(0.0, 0.0, 90.0) * -1.5,
            DVec3::ZERO,
        ),
    ];
    for (t, m, shift) in cases {
        let text = format!(
            "[camera]\n[[surfaces]]\nformula = \"{formula}\"\n\
             bounds = [[-2.0, -1.5, -1.0], [2.0, 1.5, 1.5]]\ntransform = {{ {t} }}\n"
        );
        let s = load_str(&text).unwrap_or_else(|e| panic!("{e}"));
        let world = s.geometry.leaves()[0].bounds;
        for k in 0..40 {
            let p = DVec3::new(
                (k as f64 * 0.37).sin() * 1.9,
                (k as f64 * 0.91).cos() * 1.4,
                (k as f64 * 0.53).sin() * 1.2 + 0.2,
            );
            let w = m * p + shift;
            let (fw, fl) = (leaf_value(&s, 0, w), local(p));
            assert!(
                (fw - fl).abs() <= 1e-9 * (1.0 + fl.abs()),
                "{t}: {fw} vs {fl}"
            );
            // Every point of the local box lands in the world box.
            for (i, c) in w.to_array().into_iter().enumerate() {
                assert!(world[i].contains(c), "{t}: {w} outside {world:?}");
            }
        }
    }
}

#[test]
fn right_angle_rotations_are_exact() {
    // Rotating x^3 by 90° about z: the local x is the world y (exactly, no tiny terms).
    let text = "[camera]\n[[surfaces]]\nformula = \"x^3 - 0.5\"\nbounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\ntransform = { rotate = [0.0, 0.0, -90.0] }\n";
    let s = load_str(text).unwrap();
    let b = s.geometry.leaves()[0].bounds;
    // Local x = (M⁻¹p).x with M = Rz(−90°): local x = −world y.
    assert_eq!(
        leaf_value(&s, 0, DVec3::new(0.3, -0.5, 0.7)),
        0.5f64.powi(3) - 0.5
    );
    assert_eq!(leaf_value(&s, 0, DVec3::new(0.9, 0.0, -0.2)), -0.5);
    for iv in b {
        assert!(iv.inf() <= -1.0 && iv.sup() >= 1.0 && iv.wid() < 2.0 + 1e-9);
    }
}

#[test]
fn parameters_are_bound() {
    let default = load_str("[camera]\n[[surfaces]]\ncatalog = \"orthocircle\"\n").unwrap();
    let thick =
        load_str("[camera]\n[[surfaces]]\ncatalog = \"orthocircle\"\nparams = { a = 0.2 }\n")
            .unwrap();
    let p = DVec3::new(1.0, 0.6, 0.0);
    assert!(leaf_value(&default, 0, p) > 0.0, "outside the thin tube");
    assert!(leaf_value(&thick, 0, p) < 0.0, "inside the thick tube");
    assert_eq!(thick.geometry.context().var_count(), 3);
    let ball = load_str(
        "[camera]\n[[surfaces]]\nformula = \"x^2 + y^2 + z^2 - r^2\"\nparams = { r = 2 }\nbounds = [[-2, -2, -2], [2, 2, 2]]\n",
    )
    .unwrap();
    assert_eq!(leaf_value(&ball, 0, DVec3::new(2.0, 0.0, 0.0)), 0.0);
    assert_eq!(leaf_value(&ball, 0, DVec3::ZERO), -4.0);
}

#[test]
fn settings_are_read() {
    let text = r#"
background = [0.0, 0.5, 1.0]
ambient = 0.0
[camera]
eye = [0, 0, 5]
look_at = [0, 0, 0]
width = 32
height = 16
[[surfaces]]
catalog = "sphere"
material = { color = [0.1, 0.2, 0.3], specular = 0.0, shininess = 2 }
[[lights]]
type = "point"
position = [1, 2, 3]
color = [0.5, 1.0, 0.25]
intensity = 2.0
[[lights]]
type = "point"
position = [0, 0, 9]
intensity = 0.0
[render]
root_finder = "mitchell"
epsilon = 1e-8
max_steps = 77
aa = "iaa"
iaa_depth = 3
iaa_threshold = 0.2
iaa_limit_rays = 3
primary = "per-pixel"
rays_per_undecided = 16
rays_per_pixel = 4
t_final_width = 0.1
grid = 0
shadows = false
"#;
    let s = load_str(text).unwrap();
    assert_eq!(s.background, [0.0, 0.5, 1.0]);
    assert_eq!(s.ambient, 0.0);
    assert_eq!((s.camera.width(), s.camera.height()), (32, 16));
    let m = s.geometry.leaves()[0].material;
    assert_eq!(
        (m.color, m.specular, m.shininess),
        ([0.1, 0.2, 0.3], 0.0, 2.0)
    );
    let Light::Point(l) = s.lights[0] else {
        panic!("a point light")
    };
    assert_eq!(l.position, DVec3::new(1.0, 2.0, 3.0));
    assert_eq!(l.color, [1.0, 2.0, 0.5]);
    let Light::Point(l) = s.lights[1] else {
        panic!("a point light")
    };
    assert_eq!(l.color, [0.0; 3], "zero intensity is allowed");
    let r = s.settings;
    assert_eq!(r.root_finder, RootMethod::Mitchell);
    assert_eq!((r.root.epsilon, r.root.max_steps), (1e-8, 77));
    assert_eq!(
        r.aa,
        Some(AaMode::Iaa {
            max_depth: 3,
            threshold: 0.2,
            limit_rays: 3,
        })
    );
    assert_eq!(r.primary, PrimaryMode::PerPixel);
    assert_eq!((r.rays_per_undecided, r.rays_per_pixel), (16, 4));
    assert_eq!(
        (r.t_final_width, r.grid_resolution, r.shadows),
        (0.1, 0, false)
    );
    let ss = load_str("[camera]\n[[surfaces]]\ncatalog = \"sphere\"\n[render]\naa = \"ss:3\"\n")
        .unwrap();
    assert_eq!(ss.settings.aa, Some(AaMode::Supersample(3)));
}

#[test]
fn automatic_camera_frames_the_scene() {
    let s = load_str("[camera]\nfov = 30\n[[surfaces]]\ncatalog = \"twist\"\ntransform = { translate = [10, 0, 0] }\n").unwrap();
    let ray = s.camera.ray(320.0, 240.0);
    let to = DVec3::new(10.0, 0.0, 0.0) - ray.origin;
    let d = ray.dir.normalize();
    assert!((to - to.dot(d) * d).length() < 0.05);
    // No light is added to a file's scene.
    assert!(s.lights.is_empty());
}

#[test]
fn error_paths_are_exact() {
    let (path, message) = scene_error(
        "[camera]\n[[surfaces]]\ncatalog = \"sphere\"\n[[lights]]\ntype = \"point\"\nposition = [0, 1, 2]\n[[lights]]\ntype = \"point\"\nposition = [0, inf, 2]\n",
    );
    assert_eq!(path, "lights[1].position");
    assert!(
        message.contains("must be finite") && message.ends_with("(line 9, column 12)"),
        "{message}"
    );
    let (path, _) = scene_error(
        "[camera]\n[[surfaces]]\nname = \"a\"\ncatalog = \"sphere\"\n[[surfaces]]\nname = \"b\"\ncatalog = \"chubs\"\n[[csg]]\nname = \"u\"\nop = \"union\"\nchildren = [\"a\", \"b\"]\n[[csg]]\nname = \"v\"\nop = \"union\"\nchildren = [\"u\", \"a\", \"q\"]\n",
    );
    assert_eq!(path, "csg[1].children[2]");
    let (path, message) =
        scene_error("[camera]\nwidth = 64.0\n[[surfaces]]\ncatalog = \"sphere\"\n");
    assert_eq!(path, "camera.width");
    assert!(
        message.starts_with("invalid type: floating point"),
        "{message}"
    );
    let (path, message) = scene_error(
        "[camera]\n[[surfaces]]\ncatalog = \"sphere\"\ntransform = { translate = [0, 0, 0], spin = 3 }\n",
    );
    assert_eq!(path, "surfaces[0].transform.spin");
    assert!(message.contains("unknown field 'spin'"), "{message}");
}

#[test]
fn formula_errors_show_the_span() {
    let (path, message) = scene_error(
        "[camera]\n[[surfaces]]\nformula = \"x^2 + y^2 + (z - 1\"\nbounds = [[-1, -1, -1], [1, 1, 1]]\n",
    );
    assert_eq!(path, "surfaces[0].formula");
    let lines: Vec<&str> = message.lines().collect();
    assert_eq!(lines.len(), 3, "{message}");
    assert!(lines[0].ends_with("(line 3, column 11)"), "{message}");
    assert_eq!(lines[1], "    x^2 + y^2 + (z - 1");
    let caret = lines[2].find('^').unwrap();
    assert!(caret >= 4 + 10, "{message}");
}

#[test]
fn vm_paths_are_relative_to_the_scene() {
    let dir = std::env::temp_dir().join(format!("beam-trace-scene-vm-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("models")).unwrap();
    // x^2 + y^2 + z^2 - 1
    let vm = "_0 var-x\n_1 square _0\n_2 var-y\n_3 square _2\n_4 var-z\n_5 square _4\n\
              _6 add _1 _3\n_7 add _6 _5\n_8 const 1\n_9 sub _7 _8\n";
    std::fs::write(dir.join("models/ball.vm"), vm).unwrap();
    let scene = "[camera]\n[[surfaces]]\nvm = \"models/ball.vm\"\n\
                 bounds = [[-1, -1, -1], [1, 1, 1]]\ntransform = { translate = [0, 2, 0] }\n";
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let loaded = Scene::load(&dir.join("scene.toml"));
    let from_text = Scene::from_toml(scene, "scene.toml", Some(&dir));
    let elsewhere = Scene::from_toml(scene, "scene.toml", Some(&dir.join("models")));
    std::fs::remove_dir_all(&dir).unwrap();
    for s in [loaded.unwrap(), from_text.unwrap()] {
        assert_eq!(s.geometry.leaves()[0].name, "ball");
        assert_eq!(leaf_value(&s, 0, DVec3::new(0.0, 2.0, 0.0)), -1.0);
        assert_eq!(leaf_value(&s, 0, DVec3::new(0.0, 3.0, 0.0)), 0.0);
    }
    let e = elsewhere.unwrap_err().to_string();
    assert!(e.contains("surfaces[0].vm: cannot read"), "{e}");
}

#[test]
fn io_errors_name_the_path() {
    let missing = repo_root().join("scenes/no-such-scene.toml");
    let e = Scene::load(&missing).unwrap_err();
    assert!(matches!(e, Error::Io { .. }));
    assert!(e.to_string().contains("no-such-scene.toml"), "{e}");
}

#[test]
fn an_iaa_mode_keeps_its_settings_where_no_iaa_key_sets_them() {
    let text = |extra: &str| {
        format!(
            "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n[[surfaces]]\n\
             name = \"ball\"\ncatalog = \"sphere\"\n[render]\naa = \"iaa:2:0.3:4\"\n{extra}"
        )
    };
    let aa = |extra: &str| load_str(&text(extra)).unwrap().settings.aa_mode();
    assert_eq!(
        aa(""),
        AaMode::Iaa {
            max_depth: 2,
            threshold: 0.3,
            limit_rays: 4
        }
    );
    assert_eq!(
        aa("iaa_limit_rays = 1\n"),
        AaMode::Iaa {
            max_depth: 2,
            threshold: 0.3,
            limit_rays: 1
        }
    );
}

#[test]
fn malformed_scenes_are_refused() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenes");
    let files = toml_files(&dir);
    assert!(files.len() >= 25, "{} cases", files.len());
    let mut failures = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        let expect = text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("# expect: "))
            .unwrap_or_else(|| panic!("{}: no '# expect: ' line", f.display()));
        match Scene::load(f) {
            Ok(_) => failures.push(format!("{}: loaded", f.display())),
            Err(e) => {
                let shown = e.to_string();
                if !shown.contains(expect) {
                    failures.push(format!(
                        "{}:\n  expected {expect:?}\n  got      {shown:?}",
                        f.display()
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn arbitrary_text_never_panics() {
    // A few hostile inputs beyond the fuzz target's reach in a unit test.
    let nested = format!("[camera]\nx = {}{}\n", "[".repeat(200), "]".repeat(200));
    let mut chain = String::from("[camera]\n[[surfaces]]\nname = \"s\"\ncatalog = \"sphere\"\n");
    for i in 0..40 {
        let prev = if i == 0 {
            "s".to_string()
        } else {
            format!("n{}", i - 1)
        };
        chain += &format!(
            "[[csg]]\nname = \"n{i}\"\nop = \"union\"\nchildren = [\"{prev}\", \"{prev}\"]\n"
        );
    }
    let inputs = [
        "",
        "\u{feff}",
        "[camera]\n[[surfaces]]\nformula = \"\u{e9}\u{e9}\"\nbounds = [[0,0,0],[1,1,1]]\n",
        "[camera]\n[[surfaces]]\nvm = \"/dev/null\"\nbounds = [[0,0,0],[1,1,1]]\n",
        "[camera]\n[[surfaces]]\ncatalog = \"sphere\"\ntransform = { scale = 1e-300 }\n",
        "[camera]\n[[surfaces]]\ncatalog = \"sphere\"\ntransform = { scale = 1e300 }\n",
        "[camera]\n[[surfaces]]\ncatalog = \"sphere\"\ntransform = { translate = [1e308, 0, 0], scale = 1e10 }\n",
        "[camera]\neye = [0, 0, 0]\nlook_at = [0, 0, 0]\n[[surfaces]]\ncatalog = \"sphere\"\n",
        "[[surfaces]]\n[[surfaces]]\n[camera]\n",
        &nested,
        &chain,
    ];
    for text in inputs {
        let r = load_str(text);
        if let Err(e) = &r {
            assert!(matches!(e, Error::Scene { .. }), "{e:?}");
        }
    }
    // The doubling chain expands to 2^40 leaves: refused, not expanded.
    let e = load_str(&chain).unwrap_err().to_string();
    assert!(e.contains("expands to more than"), "{e}");
}

#[test]
fn the_grid_resolution_follows_the_scene_function_and_the_passes_unless_set() {
    use beam_trace::Plan;
    use beam_trace::scene::auto_grid_resolution;
    assert_eq!(auto_grid_resolution(16, 100), 16);
    assert_eq!(auto_grid_resolution(16, 1024), 32);
    assert_eq!(auto_grid_resolution(16, 1 << 20), 128);
    assert_eq!(auto_grid_resolution(0, 1 << 20), 0);
    let long: Vec<String> = (0..40)
        .map(|i| {
            format!(
                "sqrt((x - {})^2 + y^2 + z^2) - 0.05",
                -1.0 + 0.05 * f64::from(i)
            )
        })
        .collect();
    let formula = long
        .iter()
        .skip(1)
        .fold(long[0].clone(), |acc, t| format!("min({acc}, {t})"));
    let text = |render: &str| {
        format!(
            "[camera]\neye = [0.0, 0.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n\
             [[surfaces]]\nformula = \"{formula}\"\nbounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n{render}"
        )
    };
    let auto = Scene::from_toml(&text(""), "auto.toml", None).unwrap();
    let instrs = auto.geometry.tape().len();
    assert!(instrs > 128, "{instrs}");
    assert_eq!(
        Plan::for_scene(&auto).grid,
        Some(auto_grid_resolution(16, instrs))
    );
    assert!(Plan::for_scene(&auto).grid > Some(16));
    let set = Scene::from_toml(&text("[render]\ngrid = 16\n"), "set.toml", None).unwrap();
    assert_eq!(Plan::for_scene(&set).grid, Some(16));
    // Where the grid serves only the octree of an unlit scene: coarse, unless set.
    let plan = |render: &str| {
        let scene = Scene::from_toml(&text(render), "octree.toml", None).unwrap();
        Plan::for_scene(&scene).grid
    };
    let octree = "[render]\nprimary = \"octree\"\n";
    assert_eq!(plan(octree), Some(8));
    assert_eq!(plan(&format!("{octree}grid = 24\n")), Some(24));
    let lit = format!("{octree}[[lights]]\ntype = \"point\"\nposition = [3.0, 4.0, 6.0]\n");
    assert_eq!(plan(&lit), Some(auto_grid_resolution(16, instrs)));
}
