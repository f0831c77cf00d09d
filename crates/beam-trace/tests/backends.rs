//! The backend contract seen from outside: a backend may cut a batch however it likes and
//! may decline query kinds, and the pipeline's output does not change.
//!
//! * A backend that answers every batch in pieces of 7 queries gives the CPU's images and
//!   counters bit for bit: answers depend on their query alone.
//! * A backend that declines some kinds gets them routed to the CPU, the routing names
//!   them with the reason, and the output is again the CPU's.

use beam_trace::backend::{
    Answers, Backend, BeamQuery, CellQuery, Classified, HitQuery, Prepared, Queries, QueryKind,
    RayQuery, SegmentQuery, ShadeBatch, SoftAnswers, Support, VariationQuery,
};
use beam_trace::frustum::TileCells;
use beam_trace::progress::Progress;
use beam_trace::root::RootResult;
use beam_trace::shadow::hard::Visibility;
use beam_trace::shadow::{ShadowQuery, ShadowSpec, ShadowWork};
use beam_trace::{Cpu, Error, Hit, NoProgress, Plan, Routing, Scene, render, render_on};
use glam::DVec3;

/// The CPU, answering every batch in pieces of `piece` queries, and declining `declined`.
struct Pieces {
    piece: usize,
    declined: Vec<QueryKind>,
}

struct PieceQueries<'a> {
    inner: Box<dyn Queries + 'a>,
    piece: usize,
}

impl Backend for Pieces {
    fn name(&self) -> String {
        "pieces".into()
    }

    fn support(&self, kind: QueryKind, _: &Scene, _: &Plan) -> Support {
        if self.declined.contains(&kind) {
            Support::No("declined by the test".into())
        } else {
            Support::Yes
        }
    }

    fn prepare<'a>(
        &'a self,
        scene: &'a Scene,
        plan: &'a Plan,
        kinds: &[QueryKind],
    ) -> Result<Prepared<'a>, Error> {
        let p = Cpu.prepare(scene, plan, kinds)?;
        Ok(Prepared {
            queries: Box::new(PieceQueries {
                inner: p.queries,
                piece: self.piece,
            }),
            passes: p.passes,
        })
    }
}

impl PieceQueries<'_> {
    fn pieces<Q, T>(
        &self,
        q: &[Q],
        f: impl Fn(&[Q]) -> Result<Answers<T>, Error>,
    ) -> Result<Answers<T>, Error> {
        let mut out = Answers::free(Vec::new());
        for chunk in q.chunks(self.piece) {
            let a = f(chunk)?;
            out.values.extend(a.values);
            out.cost.extend(a.cost);
            out.search.add(&a.search);
        }
        Ok(out)
    }
}

impl Queries for PieceQueries<'_> {
    fn beams(&self, q: &[BeamQuery]) -> Result<Answers<Classified>, Error> {
        self.pieces(q, |c| self.inner.beams(c))
    }
    fn first_cells(
        &self,
        q: &[CellQuery],
        progress: &dyn Progress,
    ) -> Result<Answers<TileCells>, Error> {
        self.pieces(q, |c| self.inner.first_cells(c, progress))
    }
    fn roots(&self, q: &[RayQuery]) -> Result<Answers<RootResult>, Error> {
        self.pieces(q, |c| self.inner.roots(c))
    }
    fn hit_points(&self, q: &[HitQuery]) -> Result<Answers<Hit>, Error> {
        self.pieces(q, |c| self.inner.hit_points(c))
    }
    fn shading_variation(&self, q: &[VariationQuery]) -> Result<Answers<f64>, Error> {
        self.pieces(q, |c| self.inner.shading_variation(c))
    }
    fn normals(&self, p: &[DVec3]) -> Result<Answers<Option<DVec3>>, Error> {
        self.pieces(p, |c| self.inner.normals(c))
    }
    fn segments(&self, q: &[SegmentQuery]) -> Result<Answers<Visibility>, Error> {
        self.pieces(q, |c| self.inner.segments(c))
    }
    fn soft_shadows(&self, m: &ShadowSpec, q: &[ShadowQuery]) -> Result<SoftAnswers, Error> {
        let mut out = SoftAnswers {
            visibility: Vec::new(),
            work: ShadowWork::default(),
        };
        for chunk in q.chunks(self.piece) {
            let a = self.inner.soft_shadows(m, chunk)?;
            out.visibility.extend(a.visibility);
            out.work.add(&a.work);
        }
        Ok(out)
    }
    fn shade(&self, b: &ShadeBatch<'_>) -> Result<Answers<[f32; 3]>, Error> {
        let nl = b.lights.len();
        let mut out = Answers::free(Vec::new());
        for (k, samples) in b.samples.chunks(self.piece).enumerate() {
            let start = k * self.piece * nl;
            let a = self.inner.shade(&ShadeBatch {
                samples,
                fractions: &b.fractions[start..start + samples.len() * nl],
                ..*b
            })?;
            out.values.extend(a.values);
        }
        Ok(out)
    }
}

fn scene(render: &str) -> Scene {
    let text = format!(
        r#"
[camera]
eye = [0.0, 2.0, 6.0]
look_at = [0.0, -0.5, 0.0]
width = 36
height = 28

[[surfaces]]
formula = "x^2 + y^2 + z^2 - 1"
bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]

[[surfaces]]
formula = "y + 1.2"
bounds = [[-3.0, -1.5, -3.0], [3.0, -1.2, 3.0]]
clip = true

[[lights]]
type = "area"
center = [-1.0, 4.0, 1.0]
size = 1.0
normal = "y"

[[lights]]
type = "point"
position = [3.0, 5.0, 2.0]

[render]
{render}
"#
    );
    Scene::from_toml(&text, "backends.toml", None).unwrap_or_else(|e| panic!("{e}"))
}

fn scenes() -> Vec<Scene> {
    vec![
        scene("shadow_method = \"beam:3\""),
        scene("shadow_method = \"beam-quadtree:4\"\naa = \"iaa\"\niaa_depth = 2"),
        scene("shadow_method = \"minkowski:stochastic:8\"\nprimary = \"per-pixel\""),
        scene("primary = \"octree\"\nrays_per_undecided = 4"),
    ]
}

#[test]
fn batches_cut_in_pieces_give_the_same_output() {
    let backend = Pieces {
        piece: 7,
        declined: Vec::new(),
    };
    for s in scenes() {
        let a = render(&s, &NoProgress).unwrap();
        let b = render_on(&s, &backend, &NoProgress).unwrap();
        assert_eq!(a.image.pixels, b.image.pixels);
        assert_eq!(a.classification().pixels, b.classification().pixels);
        assert_eq!(a.stats.work(), b.stats.work());
        let (sa, sb) = (a.shadows.unwrap(), b.shadows.unwrap());
        assert_eq!(sa.classes, sb.classes);
    }
}

#[test]
fn hits_the_pass_makes_itself_are_the_ones_a_backend_answers() {
    // Unlit, one surface: the CPU leaves the hit records to the primary pass
    // (`Queries::direct_hits`); a backend that does not answers every one of them.
    let backend = Pieces {
        piece: 7,
        declined: Vec::new(),
    };
    for primary in ["octree", "screen-rays", "per-pixel"] {
        let text = format!(
            "[camera]\neye = [0.0, 2.0, 6.0]\nlook_at = [0.0, -0.5, 0.0]\nwidth = 36\n\
             height = 28\n[[surfaces]]\nformula = \"x^2 + y^2 + z^2 - 1\"\n\
             bounds = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n[render]\n\
             primary = \"{primary}\"\nrays_per_undecided = 4\n"
        );
        let s = Scene::from_toml(&text, "unlit.toml", None).unwrap_or_else(|e| panic!("{e}"));
        let plan = Plan::for_scene(&s);
        assert!(!plan.narrow_hits, "{primary}: an unlit scene of one colour");
        let a = render(&s, &NoProgress).unwrap();
        let b = render_on(&s, &backend, &NoProgress).unwrap();
        assert_eq!(a.image.pixels, b.image.pixels, "{primary}");
        assert_eq!(a.classification().pixels, b.classification().pixels);
        assert_eq!(a.stats.work(), b.stats.work());
        assert!(
            a.image.pixels.iter().any(|p| p[0] > 0.5),
            "{primary}: the ball is seen"
        );
    }
}

#[test]
fn declined_kinds_run_on_the_cpu_and_the_routing_says_so() {
    let backend = Pieces {
        piece: 1000,
        declined: vec![QueryKind::Normals, QueryKind::SoftShadows],
    };
    let s = scene("shadow_method = \"beam:3\"");
    let plan = Plan::for_scene(&s);
    let routing = Routing::new(&backend, &s, &plan);
    let text = routing.to_string();
    assert!(
        text.contains("normals on the cpu (declined by the test)"),
        "{text}"
    );
    assert!(text.contains("beams on pieces"), "{text}");
    assert_eq!(
        routing.cpu_kinds(),
        vec![QueryKind::Normals, QueryKind::SoftShadows]
    );
    let a = render(&s, &NoProgress).unwrap();
    let b = render_on(&s, &backend, &NoProgress).unwrap();
    assert_eq!(a.image.pixels, b.image.pixels);
    // The CPU's set-up ran for the declined kinds: its grid pass follows the backend's.
    let grids = b.stats.passes.iter().filter(|p| p.name == "grid").count();
    assert_eq!(grids, 2);
}
