//! Triangle meshes in scenes: a mesh renders, shadows and is proven like the implicit
//! surface of the same shape, beside implicit surfaces.

use beam_trace::{NoProgress, Scene, render};
use glam::DVec3;

/// A unit cube `[-0.5, 0.5]³` as six quads.
const CUBE_POLYGONS: &str = r#"polygons = [
    [[-0.5, -0.5, -0.5], [-0.5, 0.5, -0.5], [0.5, 0.5, -0.5], [0.5, -0.5, -0.5]],
    [[-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]],
    [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, -0.5, 0.5], [-0.5, -0.5, 0.5]],
    [[-0.5, 0.5, -0.5], [-0.5, 0.5, 0.5], [0.5, 0.5, 0.5], [0.5, 0.5, -0.5]],
    [[-0.5, -0.5, -0.5], [-0.5, -0.5, 0.5], [-0.5, 0.5, 0.5], [-0.5, 0.5, -0.5]],
    [[0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [0.5, 0.5, 0.5], [0.5, -0.5, 0.5]],
]"#;

const TRANSFORM: &str = "transform = { translate = [0.2, -0.3, 0.1], rotate = [20.0, 35.0, 0.0] }";

/// The scene: a floor, a ball and the cube, as a mesh or as an implicit surface.
fn scene(cube_as_mesh: bool, extra: &str) -> Scene {
    let cube = if cube_as_mesh {
        format!("[[meshes]]\nname = \"cube\"\n{CUBE_POLYGONS}\n{TRANSFORM}\n")
    } else {
        format!(
            "[[surfaces]]\nname = \"cube\"\nformula = \"max(abs(x), abs(y), abs(z)) - 0.5\"\n\
             bounds = [[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]\n{TRANSFORM}\n"
        )
    };
    let text = format!(
        r#"
        [camera]
        eye = [0.5, 2.5, 4.0]
        look_at = [0.0, -0.4, 0.0]
        width = 64
        height = 48

        [[surfaces]]
        name = "floor"
        formula = "y + 1.0"
        bounds = [[-3.0, -1.2, -3.0], [3.0, -1.0, 3.0]]
        clip = true

        [[surfaces]]
        name = "ball"
        formula = "x^2 + y^2 + z^2 - 0.16"
        bounds = [[-0.4, -0.4, -0.4], [0.4, 0.4, 0.4]]
        transform = {{ translate = [-1.0, -0.5, -0.5] }}

        {cube}

        [[lights]]
        type = "point"
        position = [1.0, 4.0, 2.0]

        [render]
        aa = "none"
        {extra}
        "#
    );
    Scene::from_toml(&text, "cube.toml", None).unwrap()
}

/// Whether the ray from `eye` through `p` meets the transformed cube: the slab test in the
/// cube's own coordinates (for pixels proven one way or the other, far from the edges).
fn meets_cube(scene: &Scene, x: u32, y: u32) -> bool {
    let ray = scene.camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
    let m = &scene.meshes[0];
    // The cube's frame from three of its vertices' triangles: centre and axes.
    let pts: Vec<DVec3> = m.triangles.iter().flat_map(|t| t.v).collect();
    let centre = pts.iter().copied().sum::<DVec3>() / pts.len() as f64;
    let t0 = m.triangles[0].v;
    // Face 0 is z = -0.5: its edges are the x and y axes.
    let ax = [
        (t0[2] - t0[1]).normalize(),
        (t0[1] - t0[0]).normalize(),
        (t0[1] - t0[0]).cross(t0[2] - t0[1]).normalize(),
    ];
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for a in ax {
        let o = (ray.origin - centre).dot(a);
        let d = ray.dir.dot(a);
        let (t1, t2) = ((-0.5 - o) / d, (0.5 - o) / d);
        lo = lo.max(t1.min(t2));
        hi = hi.min(t1.max(t2));
    }
    lo <= hi
}

/// Whether the ray through the centre of pixel `(x, y)` meets the floor's slab or the ball.
fn meets_others(scene: &Scene, x: u32, y: u32) -> bool {
    let ray = scene.camera.ray(f64::from(x) + 0.5, f64::from(y) + 0.5);
    let (o, d) = (ray.origin, ray.dir);
    let floor = {
        let t = (-1.0 - o.y) / d.y;
        let p = o + t * d;
        t > 0.0 && p.x.abs() <= 3.0 && p.z.abs() <= 3.0
    };
    let c = o - DVec3::new(-1.0, -0.5, -0.5);
    let (qa, qb, qc) = (d.dot(d), 2.0 * c.dot(d), c.dot(c) - 0.16);
    floor || qb * qb - 4.0 * qa * qc >= 0.0
}

#[test]
fn a_mesh_cube_looks_like_the_implicit_cube_and_its_proofs_hold() {
    let mesh = scene(true, "");
    let implicit = scene(false, "");
    let a = render(&mesh, &NoProgress).unwrap();
    let b = render(&implicit, &NoProgress).unwrap();
    let (w, h) = (64u32, 48u32);
    let differ = differing(&a.image, &b.image);
    // Only edge pixels (the cube's outline is about 80 pixels long) may differ.
    assert!(differ < 60, "{differ} pixels differ");
    // Pixels proven missed see no surface; the cube's proven pixels really see it or the
    // other surfaces.
    let mut cube_pixels = 0;
    let mut proven_cube = 0;
    for y in 0..h {
        for x in 0..w {
            let cov = a.coverage[(y * w + x) as usize];
            let cube = meets_cube(&mesh, x, y);
            if cov.possible == 0.0 {
                assert!(!cube, "pixel ({x}, {y}) proven empty");
            }
            if cov.proven == 1.0 {
                assert!(
                    cube || meets_others(&mesh, x, y),
                    "pixel ({x}, {y}) proven covered"
                );
                proven_cube += usize::from(cube);
            }
            cube_pixels += usize::from(cube);
        }
    }
    assert!(cube_pixels > 100, "{cube_pixels}");
    // Beams inside one triangle are proven to hit it.
    assert!(
        proven_cube > cube_pixels / 3,
        "{proven_cube} of {cube_pixels}"
    );
}

/// Pixels whose colours differ by more than 0.1 in a channel.
fn differing(a: &beam_trace::Image, b: &beam_trace::Image) -> usize {
    let mut n = 0;
    for y in 0..48 {
        for x in 0..64 {
            let (p, q) = (a.get(x, y), b.get(x, y));
            if p.iter().zip(&q).any(|(u, v)| (u - v).abs() > 0.1) {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn a_mesh_casts_the_hard_shadow_of_the_implicit_cube() {
    let a = render(&scene(true, ""), &NoProgress).unwrap();
    let b = render(&scene(false, ""), &NoProgress).unwrap();
    // Dark pixels: the floor and the ball in the cube's shadow (ambient only), and the
    // sides of the objects turned away from the light.
    let dark = |img: &beam_trace::Image| {
        let mut n = 0usize;
        for y in 0..48 {
            for x in 0..64 {
                if img.get(x, y).iter().all(|&c| c < 0.2) {
                    n += 1;
                }
            }
        }
        n
    };
    let (da, db) = (dark(&a.image), dark(&b.image));
    assert!(db > 100, "{db}");
    assert!(da.abs_diff(db) <= db / 10, "{da} against {db} dark pixels");
    assert!(a.stats.pass("hard-shadows").unwrap().counter("occluded") > 50);
}

#[test]
fn every_primary_mode_but_the_octree_renders_a_mesh() {
    for mode in ["screen-boxes", "screen-rays", "per-pixel"] {
        let extra = format!("primary = \"{mode}\"");
        let a = render(&scene(true, &extra), &NoProgress).unwrap();
        let b = render(&scene(false, &extra), &NoProgress).unwrap();
        let n = differing(&a.image, &b.image);
        assert!(n < 60, "{mode}: {n} pixels differ");
    }
    let err = render(&scene(true, "primary = \"octree\""), &NoProgress).unwrap_err();
    assert!(
        err.to_string().contains("does not search triangle meshes"),
        "{err}"
    );
}

#[test]
fn soft_shadows_of_a_mesh_keep_their_proofs() {
    // An area light: certified bounds and the stochastic estimate of the same pixels.
    let area =
        "[[lights]]\ntype = \"area\"\ncenter = [0.5, 3.0, 1.0]\nsize = 1.0\nnormal = \"y\"\n";
    let with = |method: &str| {
        let mut text = format!("shadow_method = \"{method}\"");
        text.push('\n');
        let mut s = scene(true, &text);
        let light = Scene::from_toml(
            &format!("[camera]\n[[surfaces]]\ncatalog = \"sphere\"\n{area}"),
            "light.toml",
            None,
        )
        .unwrap()
        .lights[0];
        s.lights = vec![light];
        render(&s, &NoProgress).unwrap()
    };
    let certified = with("certified:0.05");
    let reference = with("stochastic:256");
    let c = certified.shadows.as_ref().unwrap();
    let r = reference.shadows.as_ref().unwrap();
    let mut checked = 0;
    for i in 0..c.lower[0].len() {
        let (lo, hi, f) = (c.lower[0][i], c.upper[0][i], r.fractions[0][i]);
        if f.is_nan() || lo.is_nan() {
            continue;
        }
        // 4 standard deviations of 256 samples.
        let sd = (f * (1.0 - f) / 256.0).sqrt().max(1.0 / 256.0);
        assert!(
            f >= lo - 4.0 * sd && f <= hi + 4.0 * sd,
            "pixel {i}: {f} outside [{lo}, {hi}]"
        );
        checked += 1;
    }
    assert!(checked > 1000, "{checked}");
}

#[test]
fn a_scene_of_meshes_alone_renders_and_casts_shadows() {
    let text = format!(
        r#"
        [camera]
        eye = [0.5, 2.5, 4.0]
        look_at = [0.0, -0.4, 0.0]
        width = 48
        height = 36

        [[meshes]]
        name = "floor"
        polygons = [[[-3.0, -1.0, -3.0], [-3.0, -1.0, 3.0], [3.0, -1.0, 3.0], [3.0, -1.0, -3.0]]]

        [[meshes]]
        name = "cube"
        {CUBE_POLYGONS}
        {TRANSFORM}

        [[lights]]
        type = "point"
        position = [1.0, 4.0, 2.0]

        [render]
        aa = "none"
        "#
    );
    let scene = Scene::from_toml(&text, "meshes-only.toml", None).unwrap();
    assert_eq!(scene.meshes.len(), 2);
    let out = render(&scene, &NoProgress).unwrap();
    let mut covered = 0;
    for y in 0..36 {
        for x in 0..48 {
            covered += usize::from(out.image.get(x, y) != scene.background);
        }
    }
    assert!(covered > 48 * 36 / 2, "{covered}");
    let shadows = out.stats.pass("hard-shadows").unwrap();
    assert!(shadows.counter("occluded") > 20, "{shadows:?}");
    assert!(shadows.counter("lit") > 500, "{shadows:?}");
}

mod exact {
    use beam_trace::backend::{Backend, QueryKind, SoftAnswers};
    use beam_trace::shadow::{Patch, ShadowQuery, ShadowSpec};
    use beam_trace::{Cpu, Plan, Scene};
    use glam::DVec3;

    /// A floor at `y = 0`, a square occluder of side 1 centred at `(0.2, 1, 0.1)` (two
    /// triangles, parallel to the floor), a ball off to the side, and a square light of side
    /// 1 at height 2 centred above the origin.
    fn scene(with_ball_in_the_way: bool) -> Scene {
        let ball = if with_ball_in_the_way {
            "[[surfaces]]\nname = \"ball\"\nformula = \"x^2 + y^2 + z^2 - 0.04\"\n\
             bounds = [[-0.2, -0.2, -0.2], [0.2, 0.2, 0.2]]\n\
             transform = { translate = [-0.9, 1.2, 0.0] }\n"
        } else {
            ""
        };
        floor_scene(&format!(
            "{ball}[[meshes]]\nname = \"square\"\npolygons = [[[-0.3, 1.0, -0.4], \
             [0.7, 1.0, -0.4], [0.7, 1.0, 0.6], [-0.3, 1.0, 0.6]]]\n"
        ))
    }

    /// The floor `y = 0` and the square light of side 1 at height 2 above the origin, with
    /// the scene text `occluders`.
    fn floor_scene(occluders: &str) -> Scene {
        let text = format!(
            r#"
            [camera]
            [[surfaces]]
            name = "floor"
            formula = "y"
            bounds = [[-4.0, -0.5, -4.0], [4.0, 0.0, 4.0]]
            clip = true
            {occluders}
            [[lights]]
            type = "area"
            center = [0.0, 2.0, 0.0]
            size = 1.0
            normal = "y"
            "#
        );
        Scene::from_toml(&text, "exact.toml", None).unwrap()
    }

    /// The visible fraction from `x` (below the occluder's plane) in closed form: the
    /// occluder projected from `x` onto the light's plane, overlapped with the light.
    fn closed_form(x: DVec3) -> f64 {
        let k = (2.0 - x.y) / (1.0 - x.y);
        let proj = |lo: f64, hi: f64, xc: f64| (xc + (lo - xc) * k, xc + (hi - xc) * k);
        let (ax0, ax1) = proj(-0.3, 0.7, x.x);
        let (az0, az1) = proj(-0.4, 0.6, x.z);
        let overlap = |a0: f64, a1: f64| (a1.min(0.5) - a0.max(-0.5)).max(0.0);
        1.0 - overlap(ax0, ax1) * overlap(az0, az1)
    }

    fn light(scene: &Scene) -> Patch {
        scene.lights[0].as_area().unwrap().patch
    }

    fn fractions(
        scene: &Scene,
        spec: &str,
        points: &[DVec3],
    ) -> Vec<beam_trace::shadow::LightVisibility> {
        answers(scene, spec, (points, DVec3::Y)).visibility
    }

    /// The answers of `spec` for the points, all on receivers of normal `normal`.
    fn answers(scene: &Scene, spec: &str, (points, normal): (&[DVec3], DVec3)) -> SoftAnswers {
        let plan = Plan::for_scene(scene);
        let prepared = Cpu
            .prepare(scene, &plan, &[QueryKind::SoftShadows])
            .unwrap();
        let spec: ShadowSpec = spec.parse().unwrap();
        let queries: Vec<ShadowQuery> = points
            .iter()
            .enumerate()
            .map(|(i, &origin)| ShadowQuery {
                origin,
                normal,
                light: light(scene),
                seed: i as u64 * 7919 + 1,
            })
            .collect();
        prepared.queries.soft_shadows(&spec, &queries).unwrap()
    }

    fn floor_points() -> Vec<DVec3> {
        let mut out = Vec::new();
        for i in 0..15 {
            for j in 0..15 {
                let (x, z) = (-1.6 + 0.23 * f64::from(i), -1.5 + 0.21 * f64::from(j));
                out.push(DVec3::new(x, 1e-3, z));
            }
        }
        out
    }

    #[test]
    fn the_exact_method_matches_the_closed_form_of_a_parallel_square() {
        let s = scene(false);
        let points = floor_points();
        let got = fractions(&s, "exact", &points);
        let mut penumbra = 0;
        for (p, v) in points.iter().zip(&got) {
            let want = closed_form(*p);
            assert!(
                (f64::from(v.fraction) - want).abs() < 1e-6,
                "at {p}: {} against {want}",
                v.fraction
            );
            // No certificate where a triangle is in the shaft; a proof where none is.
            assert!(v.lower <= v.fraction && v.fraction <= v.upper);
            penumbra += usize::from(want > 1e-9 && want < 1.0 - 1e-9);
        }
        assert!(penumbra > 20, "{penumbra}");
    }

    #[test]
    fn with_an_implicit_occluder_the_exact_method_agrees_with_sampling() {
        let s = scene(true);
        let points = floor_points();
        let exact = fractions(&s, "exact", &points);
        let reference = fractions(&s, "stochastic:4096", &points);
        let mut shaded_by_ball = 0;
        for ((p, e), r) in points.iter().zip(&exact).zip(&reference) {
            let sd = (r.fraction * (1.0 - r.fraction) / 4096.0)
                .sqrt()
                .max(1.0 / 4096.0);
            assert!(
                (e.fraction - r.fraction).abs() <= 4.0 * sd + 1e-3,
                "at {p}: exact {} against sampled {}",
                e.fraction,
                r.fraction
            );
            assert!(e.lower - 4.0 * sd <= r.fraction && r.fraction <= e.upper + 4.0 * sd);
            shaded_by_ball += usize::from((f64::from(r.fraction) - closed_form(*p)).abs() > 0.02);
        }
        assert!(shaded_by_ball > 5, "{shaded_by_ball}");
    }

    /// A wall `x = −2` under the light of [`floor_scene`], and a square occluder parallel to the
    /// wall, `x = −1.2`, `y` in `[0.6, 1.4]`, `z` in `[−0.4, 0.6]`: the light is at right
    /// angles to the receiver.
    fn wall_scene() -> Scene {
        floor_scene(
            "[[meshes]]\nname = \"square\"\npolygons = [[[-1.2, 0.6, -0.4], [-1.2, 0.6, 0.6], \
             [-1.2, 1.4, 0.6], [-1.2, 1.4, -0.4]]]\n",
        )
    }

    /// The visible fraction of the light from the wall point `p` in closed form: the light
    /// point `(X, 2, Z)` is hidden where the line from `p` crosses the plane `x = −1.2`
    /// inside the square. The line meets that plane at the share `s = 0.8 / (X + 2)` of
    /// its way, at height `y + s·(2 − y)` in `[0.6, 1.4]` for `X` in one interval; there,
    /// the hidden `Z` form one interval, whose length (continuous, smooth but for kinks) is
    /// integrated over it by composite Simpson with 20,000 intervals (error below 1e-8).
    fn wall_closed_form(p: DVec3) -> f64 {
        // The shares `s` of the way at which the line is at the square's heights (it
        // rises from `p.y` at `s = 0`), and the `X = 0.8 / s − 2` of their ends.
        let share = |height: f64| ((height - p.y) / (2.0 - p.y)).max(0.0);
        let (s_lo, s_hi) = (share(0.6), share(1.4));
        let x_of = |s: f64| {
            if s > 0.0 {
                0.8 / s - 2.0
            } else {
                f64::INFINITY
            }
        };
        let (a, b) = (x_of(s_hi).max(-0.5), x_of(s_lo).min(0.5));
        if a >= b {
            return 1.0;
        }
        let hidden = |x: f64| {
            let s = 0.8 / (x + 2.0);
            let (z0, z1) = (p.z + (-0.4 - p.z) / s, p.z + (0.6 - p.z) / s);
            (z1.min(0.5) - z0.max(-0.5)).max(0.0)
        };
        let n = 20_000;
        let h = (b - a) / f64::from(n);
        let mut sum = hidden(a) + hidden(b);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * hidden(a + f64::from(i) * h);
        }
        1.0 - sum * h / 3.0
    }

    #[test]
    fn points_of_a_wall_share_trees_by_their_tangent_plane_and_match_the_closed_form() {
        let s = wall_scene();
        // Column by column, so that neighbouring points are at different heights: only
        // the wall's plane holds a run of them (a group spreads over a twentieth of the
        // light's diagonal at most: about five points of a column).
        let mut points = Vec::new();
        for j in 0..15 {
            for i in 0..60 {
                let (y, z) = (0.05 + 0.015 * f64::from(i), -1.0 + 0.16 * f64::from(j));
                points.push(DVec3::new(-2.0, y, z));
            }
        }
        let grouped = answers(&s, "exact", (&points, DVec3::X));
        let single = answers(&s, "exact:8:1", (&points, DVec3::X));
        let mut penumbra = 0;
        for ((p, g), one) in points
            .iter()
            .zip(&grouped.visibility)
            .zip(&single.visibility)
        {
            let want = wall_closed_form(*p);
            for v in [g, one] {
                assert!(
                    (f64::from(v.fraction) - want).abs() < 1e-6,
                    "at {p}: {} against {want}",
                    v.fraction
                );
            }
            penumbra += usize::from(want > 1e-6 && want < 1.0 - 1e-6);
        }
        assert!(penumbra > 120, "{penumbra}");
        // The trees are shared: fewer nodes than one tree per point.
        let (g, one) = (grouped.work.bsp, single.work.bsp);
        assert_eq!((g.queries, one.queries), (900, 900));
        assert!(
            g.inner_nodes * 2 < one.inner_nodes,
            "{} against {}",
            g.inner_nodes,
            one.inner_nodes
        );
    }

    /// The box `[−0.3, 0.5] × [0.8, 1.2] × [−0.4, 0.4]` as a closed mesh, every face wound
    /// counter-clockwise seen from outside, above the floor of [`floor_scene`] under its light.
    fn box_scene() -> Scene {
        let (x0, x1, y0, y1, z0, z1) = (-0.3, 0.5, 0.8, 1.2, -0.4, 0.4);
        let faces = [
            [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
            [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
            [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
            [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
            [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
            [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
        ];
        let polygons: Vec<String> = faces
            .iter()
            .map(|f| {
                let v: Vec<String> = f
                    .iter()
                    .map(|(x, y, z)| format!("[{x}, {y}, {z}]"))
                    .collect();
                format!("[{}]", v.join(", "))
            })
            .collect();
        floor_scene(&format!(
            "[[meshes]]\nname = \"box\"\npolygons = [{}]\n",
            polygons.join(", ")
        ))
    }

    /// The visible fraction of the light from `x` (below the box) in closed form: the box
    /// projected from `x` onto the light's plane is the convex hull of its corners'
    /// projections; its overlap with the light is clipped by the light's four sides.
    fn box_closed_form(x: DVec3) -> f64 {
        let mut pts = Vec::new();
        for cx in [-0.3, 0.5] {
            for cy in [0.8, 1.2] {
                for cz in [-0.4, 0.4] {
                    let k = (2.0 - x.y) / (cy - x.y);
                    pts.push([x.x + (cx - x.x) * k, x.z + (cz - x.z) * k]);
                }
            }
        }
        // Convex hull (monotone chain), counter-clockwise.
        pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
            (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
        };
        let mut hull: Vec<[f64; 2]> = Vec::new();
        for pass in [pts.clone(), pts.iter().rev().copied().collect()] {
            let start = hull.len();
            for p in pass {
                while hull.len() >= start + 2
                    && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
                {
                    hull.pop();
                }
                hull.push(p);
            }
            hull.pop();
        }
        // Clipped by the light's sides: a·p ≤ c for (a, c) of each side.
        for (axis, sign) in [(0, 1.0), (0, -1.0), (1, 1.0), (1, -1.0)] {
            let inside = |p: &[f64; 2]| sign * p[axis] <= 0.5;
            let mut out = Vec::new();
            for i in 0..hull.len() {
                let (p, q) = (hull[i], hull[(i + 1) % hull.len()]);
                if inside(&p) {
                    out.push(p);
                }
                if inside(&p) != inside(&q) {
                    let t = (sign * 0.5 - p[axis]) / (q[axis] - p[axis]);
                    out.push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
                }
            }
            hull = out;
        }
        let area: f64 = (0..hull.len())
            .map(|i| {
                let (p, q) = (hull[i], hull[(i + 1) % hull.len()]);
                p[0] * q[1] - q[0] * p[1]
            })
            .sum::<f64>()
            / 2.0;
        1.0 - area.abs()
    }

    #[test]
    fn the_shadow_of_a_closed_box_matches_the_closed_form_without_its_faces_turned_away() {
        let s = box_scene();
        // The bottom faces are turned away from the light above: the trees do without them.
        let mesh = &s.meshes[0].triangles;
        let index = beam_trace::mesh::MeshIndex::new([mesh.as_slice()]);
        let patch = light(&s);
        let away = (0..mesh.len() as u32)
            .filter(|&t| index.turned_away(t, &patch.bounding_box(), &patch.corners()))
            .count();
        assert_eq!(away, 2);
        // The floor under the box, and two far edges of it that see the whole light.
        let mut points = floor_points();
        for i in 0..15 {
            let a = -3.5 + 0.5 * f64::from(i);
            points.push(DVec3::new(a, 1e-3, 3.6));
            points.push(DVec3::new(3.6, 1e-3, a));
        }
        let got = fractions(&s, "exact", &points);
        let (mut penumbra, mut proven_lit) = (0, 0);
        for (p, v) in points.iter().zip(&got) {
            let want = box_closed_form(*p);
            assert!(
                (f64::from(v.fraction) - want).abs() < 1e-6,
                "at {p}: {} against {want}",
                v.fraction
            );
            // A bound is proven only where it holds the closed form.
            assert!(
                f64::from(v.lower) <= want + 1e-12 && want <= f64::from(v.upper) + 1e-12,
                "at {p}: [{}, {}] against {want}",
                v.lower,
                v.upper
            );
            penumbra += usize::from(want > 1e-6 && want < 1.0 - 1e-6);
            proven_lit += usize::from(v.lower == 1.0);
        }
        assert!(penumbra > 20, "{penumbra}");
        assert!(proven_lit > 20, "{proven_lit}");
    }
}
