//! Rays and beams (thesis 5.4.1), and the evaluator that restricts a scene function to one.
//!
//! A [`Ray`] is a point origin and a point direction; a [`Beam`] is the set of rays whose
//! origin lies in a box and whose direction lies in a box (the eye and a screen area for a
//! primary beam, a surface patch and a light for a shadow beam). Points on a ray are
//! `origin + t · dir`; for a beam, `origin + T · dir` encloses the points of every ray.
//!
//! [`RayFn`] is `g(t) = f(origin + t · dir)` and `g'(t)` of one ray or beam, all that the
//! root finders see; [`BeamEval`] implements it over a scene function.

use std::cmp::Ordering;
use std::fmt;
use std::str::FromStr;

use glam::DVec3;
use implicit_expr::{RayEvaluator, RayFunction, Tape};
use interval_core::{DdInterval, Interval};

use crate::centred::Centred;

pub use crate::ibox::{IBox, ipoint, ival, point_box};

/// `g` and `g'` of one ray or beam, as inclusion functions of the ray parameter.
///
/// The renderer implements it over implicit-expr's ray evaluators; tests implement it with
/// closures. Implementations must be sound: for every `t` in `T` (and every ray of the
/// beam), `g(t) ∈ g(T)` and `g'(t) ∈ g'(T)` wherever `g` is defined.
pub trait RayFn {
    /// An enclosure of `g` over `t` (every ray of the beam).
    fn g(&mut self, t: Interval<f64>) -> Interval<f64>;

    /// Enclosures of `g` and `g'` over `t`. A derivative that is undefined somewhere in
    /// the region is the whole line, never empty.
    fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>);

    /// `g` over `t` and whether `g` is proven continuous there (every operation defined on
    /// all of its arguments, no step function). A sign change proves a root only then.
    fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool);

    /// The floating-point value of `g` at the point `t` for the central ray, rounded to
    /// nearest: for the unreliable baselines only.
    fn g_point(&mut self, t: f64) -> f64;

    /// Enclosures of `g` over `t` on each side of the boundary of a formula's domain
    /// ([`implicit_expr::BinaryOp::Domain`]), `(inside, outside)`, where exactly one such
    /// boundary may cross the beam over `t`; `None` otherwise (the default: no domains).
    /// Every ray's `g` at every parameter of `t` lies in one of the two.
    fn g_sides(&mut self, _t: Interval<f64>) -> Option<(Interval<f64>, Interval<f64>)> {
        None
    }

    /// `t` narrowed to the parameters where `g` may vanish for some ray of the set (a
    /// contractor such as HC4-revise): every root in `t` must stay in the result. `None`
    /// proves that `t` holds no root. The default narrows nothing.
    fn contract(&mut self, t: Interval<f64>) -> Option<Interval<f64>> {
        Some(t)
    }

    /// Announces that the following interval evaluations all lie inside `t`, which lies
    /// inside the region of the current scope (the whole ray or beam, or an earlier
    /// restriction), so that an implementation may specialise `g` to it (prune its tape).
    /// The default does nothing. Enclosures must stay as sound as without it.
    fn restrict(&mut self, _t: Interval<f64>) {}

    /// Returns to the whole `g` of the ray or beam set (no restriction).
    fn unrestrict(&mut self) {}

    /// Raises the precision of the following interval evaluations one step (`f32 → f64 →
    /// dd`, [`Precision::escalated`]) for the ray or beam set; returns the precision to give
    /// back to [`restore`](RayFn::restore), or `None` when there is no higher one (the
    /// default: no escalation).
    fn escalate(&mut self) -> Option<Precision> {
        None
    }

    /// Returns to `previous` after [`escalate`](RayFn::escalate), with the ray or beam of
    /// that precision as it was (its restriction may have been undone in between: the whole
    /// `g`, valid everywhere, is evaluated then).
    fn restore(&mut self, _previous: Precision) {}

    /// Whether a higher precision may decide the beam over `piece` (the first piece its
    /// search left undecided, where `g`'s enclosure is `now`, in a range ending at `end`),
    /// so that the search is worth
    /// running again from there ([`escalate`](RayFn::escalate)): rounding dominates on the
    /// beam's central ray ([`rounding_dominates`], tolerance `epsilon`), or the centred form
    /// of double-double evaluations over the beam ([`crate::centred`]) is much narrower than
    /// the enclosure over `piece` now (large terms that cancel, whose natural extension is
    /// as wide as the terms vary over the beam, in any precision). The beam and its
    /// restriction stay set. The default: `false` (no escalation).
    ///
    /// [`rounding_dominates`]: crate::root::rounding_dominates
    fn escalation_helps(
        &mut self,
        _piece: Interval<f64>,
        _now: Interval<f64>,
        _end: f64,
        _epsilon: f64,
        _counters: &mut crate::root::RootCounters,
    ) -> bool {
        false
    }

    /// A handle of the current restriction, to return to it with
    /// [`set_scope`](RayFn::set_scope) after evaluations elsewhere (`None`: nothing to
    /// return to, the default).
    fn scope(&self) -> Option<Tape> {
        None
    }

    /// Whether `g` as evaluated now (its current restriction) is proven defined and
    /// continuous at every point by its form ([`Tape::is_continuous_everywhere`]), so that
    /// a continuity proof over a range needs no decorated evaluation. The default: `false`.
    fn continuous_everywhere(&self) -> bool {
        false
    }

    /// Returns to a restriction that [`scope`](RayFn::scope) gave for the same ray or beam;
    /// only parameters inside its region may be asked then.
    fn set_scope(&mut self, _scope: &Tape) {}
}

/// Where the rounding of `g` at one point of a beam's central ray is at least this many
/// units of the precision's rounding (`2^-52` in `f64`, `2^-23` in `f32`) times the
/// magnitude of `g` there and at the end of the range, the formula loses that many units in
/// the last place to cancellation (large terms `K` round to `K²·2^-52` while `g` stays near
/// its own scale), and [`RayFn::escalation_helps`] looks further; ordinary formulas lose a
/// few. One or two evaluations of the restricted `g` on the central ray are all an
/// undecided beam of an ordinary scene pays.
const LOSSY_ULPS: f64 = 4096.0;

/// A beam escalates for its centred form ([`RayFn::escalation_helps`]) where that form is at
/// most this fraction of the enclosure's width now (large terms that cancel give about
/// `1/K`).
const ESCALATE_NARROWER: f64 = 0.25;

/// A ray `origin + t · dir`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Ray {
    /// Origin.
    pub origin: DVec3,
    /// Direction (not necessarily unit length).
    pub dir: DVec3,
}

impl Ray {
    /// The point at parameter `t`.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }

    /// The ray as a beam of one ray.
    pub fn beam(&self) -> Beam {
        Beam {
            origin: point_box(self.origin),
            dir: point_box(self.dir),
        }
    }
}

/// A beam: every ray with origin in `origin` and direction in `dir`.
#[derive(Copy, Clone, Debug, PartialEq)]
pub struct Beam {
    /// Box of origins (a point box for primary beams).
    pub origin: IBox,
    /// Box of directions.
    pub dir: IBox,
}

impl Beam {
    /// An enclosure of the points of every ray of the beam for `t ∈ t`.
    pub fn points(&self, t: Interval<f64>) -> IBox {
        // By sign cases (the same interval as `×`): the parameters of a search are not
        // negative, so the branches predict, and two directed products replace `×`'s eight
        // (the searches ask this of every piece). In the instruction set of the evaluators
        // ([`interval_core::isa::dispatch`]): the directed products' fused multiply-adds
        // are then instructions, not calls (the same bits either way). Written out, since
        // an inner closure would be compiled out of line, in the baseline set.
        let (o, d) = (&self.origin, &self.dir);
        interval_core::isa::dispatch(
            #[inline(always)]
            || {
                [
                    o[0] + t.mul_sign_cases(d[0]),
                    o[1] + t.mul_sign_cases(d[1]),
                    o[2] + t.mul_sign_cases(d[2]),
                ]
            },
        )
    }

    /// The largest width of the beam's directions over the length of the longest: about
    /// the angle it spans, in radians (NaN for a beam without length).
    pub fn angular_spread(&self) -> f64 {
        self.dir.iter().map(|d| d.wid()).fold(0.0, f64::max)
            / self.dir.iter().map(|d| d.mag()).fold(0.0, f64::max)
    }

    /// The slab test on one axis: an enclosure, rounded outward, of the parameters `t ∈ t`
    /// at which some ray of the beam has its coordinate on `axis` in `slab`. Empty when no
    /// ray of the beam reaches the slab for `t ∈ t`.
    ///
    /// Solves `o + t·d ∈ slab` for `o ∈ origin[axis]`, `d ∈ dir[axis]` with the extended
    /// division (`t ∈ (slab − o) / d`): a direction interval holding 0 gives up to two
    /// unbounded pieces, each is clipped to `t` before their hull is taken; a zero direction
    /// gives every `t` when the origin lies in the slab and none otherwise (rays parallel
    /// to the slab).
    pub fn slab_t(&self, axis: usize, slab: Interval<f64>, t: Interval<f64>) -> Interval<f64> {
        let v = slab - self.origin[axis];
        let (p, q) = self.dir[axis].mul_rev_to_pair(v);
        p.intersection(t).convex_hull(q.intersection(t))
    }

    /// An enclosure, rounded outward, of the parameters `t ∈ t` at which some ray of the
    /// beam is inside the box `b` (the intersection of the three slab tests of
    /// [`Beam::slab_t`]); `None` when it is empty, a proof that no ray of the beam is in
    /// `b` for `t ∈ t`. For a beam of many rays it is a hull: different rays may be inside
    /// at different parameters.
    pub fn t_range_within(&self, b: &IBox, t: Interval<f64>) -> Option<Interval<f64>> {
        let mut r = t;
        for (axis, slab) in b.iter().enumerate() {
            r = self.slab_t(axis, *slab, r);
            if r.is_empty() {
                return None;
            }
        }
        Some(r)
    }

    /// [`Beam::t_range_within`] over every parameter (negative ones included).
    pub fn t_range(&self, b: &IBox) -> Option<Interval<f64>> {
        self.t_range_within(b, Interval::ENTIRE)
    }

    /// The central ray (midpoints of the boxes).
    pub fn central_ray(&self) -> Ray {
        Ray {
            origin: DVec3::new(
                self.origin[0].mid(),
                self.origin[1].mid(),
                self.origin[2].mid(),
            ),
            dir: DVec3::new(self.dir[0].mid(), self.dir[1].mid(), self.dir[2].mid()),
        }
    }
}

/// The floating-point format the interval evaluations of `g` and `g'` run in.
///
/// [`Precision::F32`] evaluates the scene function in single precision, as a GPU does: the
/// beam's boxes and the parameter interval are rounded outward to `f32` intervals, the
/// enclosure is computed with `Interval<f32>` (outward rounding in `f32`), and the result is
/// converted back to `f64` exactly. The enclosures stay sound, only wider.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Precision {
    /// Double precision (`Interval<f64>`), the default.
    #[default]
    F64,
    /// Single precision (`Interval<f32>`).
    F32,
    /// Double-double (`DdInterval`, about 106 bits): for large terms that cancel, where
    /// `f64` rounding alone keeps the enclosures wide. Several times slower than `f64`; the
    /// renderer escalates to it per query ([`Precision::escalated`]).
    Dd,
}

impl Precision {
    /// Every precision, in the order of [`Precision::name`]'s accepted names.
    pub const ALL: [Precision; 3] = [Precision::F64, Precision::F32, Precision::Dd];

    /// The name `FromStr` accepts: `"f64"`, `"f32"` or `"dd"`.
    pub fn name(self) -> &'static str {
        match self {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
            Precision::Dd => "dd",
        }
    }

    /// The unit roundoff of the interval bounds' format: `2^-24` in `f32`, `2^-53` in `f64`
    /// and for double-double (whose operations outside `+ − × /` and the elementary
    /// functions round as `f64` does).
    pub fn unit_roundoff(self) -> f64 {
        match self {
            Precision::F32 => f64::from(f32::EPSILON) / 2.0,
            Precision::F64 | Precision::Dd => f64::EPSILON / 2.0,
        }
    }

    /// The next higher precision a query escalates to (`f32 → f64 → dd`), `None` after the
    /// highest.
    pub fn escalated(self) -> Option<Precision> {
        match self {
            Precision::F32 => Some(Precision::F64),
            Precision::F64 => Some(Precision::Dd),
            Precision::Dd => None,
        }
    }
}

impl fmt::Display for Precision {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Precision {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Precision::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| format!("unknown precision '{s}' (one of: f64, f32, dd)"))
    }
}

/// Evaluates `g` and `g'` of a [`RayFunction`] on one ray or beam at a time: the
/// renderer's [`RayFn`]. Owns its scratch space; make one per thread.
///
/// The interval evaluations ([`RayFn::g`], [`RayFn::g_dg`], [`RayFn::g_checked`]) run in
/// the [`Precision`] set by [`BeamEval::set_precision`] (default [`Precision::F64`]). The
/// point evaluation [`RayFn::g_point`] (unreliable baselines and shading searches) is always
/// rounded to nearest in `f64`, whatever the precision.
#[derive(Clone, Debug)]
pub struct BeamEval {
    precision: Precision,
    /// The beam last set (to set it again when the precision changes).
    origin: IBox,
    dir: IBox,
    interval: RayEvaluator<Interval<f64>>,
    interval32: RayEvaluator<Interval<f32>>,
    interval_dd: RayEvaluator<DdInterval>,
    point: RayEvaluator<f64>,
    /// The mean-value form of double-double evaluations over beams (made on first use).
    centred: Option<Box<Centred>>,
    /// The widest box of points over which an `f64` enclosure holding 0 is narrowed by
    /// the mean-value form (`None`: never; [`BeamEval::set_centred_fallback`]).
    centred_fallback: Option<f64>,
    /// [`BeamEval::centred_record`].
    centred_record: (u64, u64),
}

/// A parameter interval as a double-double interval (exact).
#[inline]
fn dd(t: Interval<f64>) -> DdInterval {
    DdInterval::from_interval(t)
}

/// A box as double-double intervals (exact).
#[inline]
fn box_dd(b: &IBox) -> [DdInterval; 3] {
    b.map(DdInterval::from_interval)
}

/// `natural` narrowed by `centred`, two enclosures of `g`'s values over one region (which
/// has some where `natural` is not empty, so they meet); `natural` should rounding say
/// otherwise.
#[inline]
fn meet(natural: Interval<f64>, centred: Interval<f64>) -> Interval<f64> {
    let both = natural.intersection(centred);
    if both.is_empty() { natural } else { both }
}

/// A box rounded outward to `f32` (each `f32` interval contains the `f64` one).
#[inline]
fn box32(b: &IBox) -> [Interval<f32>; 3] {
    [b[0].cast(), b[1].cast(), b[2].cast()]
}

impl BeamEval {
    /// An evaluator for `f` (a function without free parameters), in [`Precision::F64`].
    pub fn new(f: &RayFunction) -> Self {
        Self {
            precision: Precision::F64,
            origin: point_box(DVec3::ZERO),
            dir: point_box(DVec3::ZERO),
            interval: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
            interval32: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
            interval_dd: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
            point: RayEvaluator::new(f, &[]).expect("scene functions have no parameters"),
            centred: None,
            centred_fallback: None,
            centred_record: (0, 0),
        }
    }

    /// With `widest`, an `f64` interval evaluation of `g` over a beam ([`RayFn::g`],
    /// [`RayFn::g_checked`]) whose natural enclosure holds 0 is intersected with the
    /// mean-value form over the box of the beam's points ([`Centred::enclose_f64`]) where
    /// `g` is proven continuous there and the box is at most `widest` wide on every axis.
    /// Both enclose `g`'s values, so the result does too; it decides more beams where the
    /// natural extension of a formula with dependent terms (a torus' quartic seen along a
    /// beam) is several times wider than `g` varies, at the cost of a gradient evaluation
    /// where it is tried. Over wide boxes the form is as wide as `g` varies there and
    /// rarely decides anything, hence the limit. `None` (the default): never.
    pub fn set_centred_fallback(&mut self, widest: Option<f64>) {
        self.centred_fallback = widest;
    }

    /// How many `f64` enclosures holding 0 the mean-value form was tried on since the
    /// evaluator was made ([`BeamEval::set_centred_fallback`]), and how many of them it
    /// decided (their sign proven): a caller may stop asking for it where it decides
    /// nothing.
    pub fn centred_record(&self) -> (u64, u64) {
        self.centred_record
    }

    /// `natural`, the `f64` enclosure of `g` over the beam set for `t`, narrowed by the
    /// mean-value form where [`set_centred_fallback`](Self::set_centred_fallback) asks it,
    /// `natural` holds 0 and a beam (not a ray) is set; `continuous` says `g` is proven
    /// continuous over the region.
    fn narrowed(
        &mut self,
        t: Interval<f64>,
        natural: Interval<f64>,
        continuous: bool,
    ) -> Interval<f64> {
        let Some(widest) = self.centred_fallback else {
            return natural;
        };
        if natural.is_empty() || natural.inf() > 0.0 || natural.sup() < 0.0 || !self.is_beam() {
            return natural;
        }
        let points = self.points(t);
        // A box of points that cannot be measured (NaN width) is not tried either.
        let within = |x: &Interval<f64>| {
            matches!(
                x.wid().partial_cmp(&widest),
                Some(Ordering::Less | Ordering::Equal)
            )
        };
        if !points.iter().all(within) {
            return natural;
        }
        // Borrowed, not cloned: the scope is often a tape every thread shares, whose count
        // of owners would go back and forth between their caches at every piece.
        let tape = self.interval.scope();
        let continuous = continuous || tape.is_continuous_everywhere();
        let forms = self
            .centred
            .get_or_insert_with(|| Box::new(Centred::new(tape)));
        self.centred_record.0 += 1;
        // First with the gradient of an enclosing piece (the one this piece was cut from):
        // a form that decides the sign decides it as this piece's own gradient would (that
        // form lies inside this one), without computing it.
        let reused = forms
            .enclose_f64_reused(tape, &points)
            .map(|c| meet(natural, c));
        let decided = match reused {
            Some(both) if crate::root::search::excludes_zero(both) => both,
            _ => forms
                .enclose_f64(tape, &points, continuous)
                .map_or(natural, |c| meet(natural, c)),
        };
        self.centred_record.1 += u64::from(crate::root::search::excludes_zero(decided));
        decided
    }

    /// The box of the points of the beam set, for the parameters `t`.
    fn points(&self, t: Interval<f64>) -> IBox {
        Beam {
            origin: self.origin,
            dir: self.dir,
        }
        .points(t)
    }

    /// An evaluator for `f` whose interval evaluations run in `precision`.
    pub fn with_precision(f: &RayFunction, precision: Precision) -> Self {
        let mut e = Self::new(f);
        e.set_precision(precision);
        e
    }

    /// Switches to another function without free parameters (a cell's pruned function,
    /// say); the ray or beam set before stays set, the precision too.
    pub fn set_function(&mut self, f: &RayFunction) {
        self.interval
            .set_function(f)
            .expect("scene functions have no parameters");
        self.interval32
            .set_function(f)
            .expect("scene functions have no parameters");
        self.interval_dd
            .set_function(f)
            .expect("scene functions have no parameters");
        self.point
            .set_function(f)
            .expect("scene functions have no parameters");
    }

    /// Sets the precision of the interval evaluations. The ray or beam set before stays set.
    pub fn set_precision(&mut self, precision: Precision) {
        self.precision = precision;
        let (origin, dir) = (self.origin, self.dir);
        self.set_interval_ray(origin, dir);
    }

    /// The precision of the interval evaluations.
    pub fn precision(&self) -> Precision {
        self.precision
    }

    /// Sets the boxes of the interval evaluator of the current precision.
    #[inline]
    fn set_interval_ray(&mut self, origin: IBox, dir: IBox) {
        self.origin = origin;
        self.dir = dir;
        match self.precision {
            Precision::F64 => self.interval.set_ray(origin, dir),
            Precision::F32 => self.interval32.set_ray(box32(&origin), box32(&dir)),
            Precision::Dd => self.interval_dd.set_ray(box_dd(&origin), box_dd(&dir)),
        }
    }

    /// Sets the beam of the interval evaluations alone, with `g` restricted to `scope` (a
    /// tape [`RayFn::scope`] returned for a beam holding this one, asked only about
    /// parameters it holds for), or the whole `g` without one. The point evaluations keep
    /// the ray they had: for searches that evaluate intervals only (the frustum octree).
    pub fn set_interval_beam(&mut self, beam: &Beam, scope: Option<&Tape>) {
        self.set_interval_ray_within(beam.origin, beam.dir, scope);
    }

    /// Sets the beam the following evaluations are about.
    pub fn set_beam(&mut self, beam: &Beam) {
        self.set_interval_ray(beam.origin, beam.dir);
        let c = beam.central_ray();
        self.point.set_ray(c.origin.to_array(), c.dir.to_array());
    }

    /// Sets a single ray.
    pub fn set_ray(&mut self, ray: &Ray) {
        self.set_interval_ray(point_box(ray.origin), point_box(ray.dir));
        self.point
            .set_ray(ray.origin.to_array(), ray.dir.to_array());
    }

    /// Whether a beam (not a single ray) is set.
    fn is_beam(&self) -> bool {
        self.origin
            .iter()
            .chain(&self.dir)
            .any(|x| x.inf() != x.sup())
    }

    /// The double-double enclosure `natural` of `g` over `t` for the beam set, narrowed by
    /// the mean-value form over the box of the beam's points ([`Centred`]): over a beam the
    /// natural extension of large terms that cancel is as wide as the terms vary, in any
    /// precision, while the centred form is as wide as `g` varies. Rays keep `natural`.
    fn centred_dd(&mut self, t: Interval<f64>, natural: DdInterval) -> Interval<f64> {
        let natural = natural.to_interval();
        if natural.is_empty() || !self.is_beam() {
            return natural;
        }
        let tape = self.interval_dd.scope().clone();
        self.centred_form(&tape, t)
            .map_or(natural, |c| meet(natural, c.to_interval()))
    }

    /// The centred form ([`Centred::enclose`]) of `tape`, a restriction of `g` valid on the
    /// beam over `t`, over the box of the beam's points for `t`.
    fn centred_form(&mut self, tape: &Tape, t: Interval<f64>) -> Option<DdInterval> {
        let points = self.points(t);
        self.centred
            .get_or_insert_with(|| Box::new(Centred::new(tape)))
            .enclose(tape, &points)
    }

    /// [`RayFn::g`], recording the `min`/`max` choices of the evaluation in `f64` (the other
    /// precisions evaluate plainly), so that [`BeamEval::restrict_traced`] to the same `t`
    /// right after prunes without evaluating again. The same enclosure as `g`.
    pub fn g_traced(&mut self, t: Interval<f64>) -> Interval<f64> {
        match self.precision {
            Precision::F64 => {
                let natural = self.interval.g_traced(t);
                self.narrowed(t, natural, false)
            }
            Precision::F32 | Precision::Dd => self.g(t),
        }
    }

    /// [`RayFn::restrict`] to `t`, by the choices of the last [`BeamEval::g_traced`] where
    /// it was over `t` with the tape and beam set now ([`RayEvaluator::restrict_traced`]).
    pub fn restrict_traced(&mut self, t: Interval<f64>) {
        match self.precision {
            Precision::F64 => self.interval.restrict_traced(t),
            Precision::F32 | Precision::Dd => self.restrict(t),
        }
    }

    /// The number of instructions `g` is evaluated with now at the precision set (the
    /// length of [`RayFn::scope`], without a handle to the tape).
    pub fn scope_len(&self) -> usize {
        match self.precision {
            Precision::F64 => self.interval.g_len(),
            Precision::F32 => self.interval32.g_len(),
            Precision::Dd => self.interval_dd.g_len(),
        }
    }

    /// The share of the tape's `min`/`max` operations whose choice the last
    /// [`BeamEval::g_traced`] decided, where it was over `t` with the tape and beam set now
    /// and recorded them ([`RayEvaluator::decided_share`]); `None` otherwise.
    pub fn decided_share(&self, t: Interval<f64>) -> Option<f64> {
        match self.precision {
            Precision::F64 => self.interval.decided_share(t),
            Precision::F32 | Precision::Dd => None,
        }
    }

    /// Sets the interval evaluator's ray or beam with the restriction `scope` (which must
    /// hold for it, as for [`RayFn::set_scope`]), without loading the whole `g` in between;
    /// the whole `g` without one.
    fn set_interval_ray_within(&mut self, origin: IBox, dir: IBox, scope: Option<&Tape>) {
        let Some(scope) = scope else {
            self.set_interval_ray(origin, dir);
            return;
        };
        self.origin = origin;
        self.dir = dir;
        match self.precision {
            Precision::F64 => self.interval.set_ray_within(origin, dir, scope),
            Precision::F32 => self
                .interval32
                .set_ray_within(box32(&origin), box32(&dir), scope),
            Precision::Dd => self
                .interval_dd
                .set_ray_within(box_dd(&origin), box_dd(&dir), scope),
        }
    }
}

impl RayFn for BeamEval {
    /// One HC4-revise pass over `g`'s graph in `f64`
    /// ([`RayEvaluator::contract`](implicit_expr::RayEvaluator::contract)); at the other
    /// precisions nothing is narrowed.
    fn contract(&mut self, t: Interval<f64>) -> Option<Interval<f64>> {
        match self.precision {
            Precision::F64 => self.interval.contract(t),
            Precision::F32 | Precision::Dd => Some(t),
        }
    }

    #[inline]
    fn g(&mut self, t: Interval<f64>) -> Interval<f64> {
        match self.precision {
            Precision::F64 => {
                let natural = self.interval.g(t);
                self.narrowed(t, natural, false)
            }
            Precision::F32 => self.interval32.g(t.cast()).cast(),
            Precision::Dd => {
                let natural = self.interval_dd.g(dd(t));
                self.centred_dd(t, natural)
            }
        }
    }

    #[inline]
    fn g_dg(&mut self, t: Interval<f64>) -> (Interval<f64>, Interval<f64>) {
        match self.precision {
            Precision::F64 => self.interval.g_dg(t),
            Precision::F32 => {
                let (g, dg) = self.interval32.g_dg(t.cast());
                (g.cast(), dg.cast())
            }
            Precision::Dd => {
                let (g, dg) = self.interval_dd.g_dg(dd(t));
                (g.to_interval(), dg.to_interval())
            }
        }
    }

    #[inline]
    fn g_checked(&mut self, t: Interval<f64>) -> (Interval<f64>, bool) {
        match self.precision {
            Precision::F64 => {
                let (natural, continuous) = self.interval.g_checked(t);
                (self.narrowed(t, natural, continuous), continuous)
            }
            Precision::F32 => {
                let (g, ok) = self.interval32.g_checked(t.cast());
                (g.cast(), ok)
            }
            Precision::Dd => {
                let (g, ok) = self.interval_dd.g_checked(dd(t));
                (self.centred_dd(t, g), ok)
            }
        }
    }

    #[inline]
    fn g_point(&mut self, t: f64) -> f64 {
        self.point.g(t)
    }

    fn g_sides(&mut self, t: Interval<f64>) -> Option<(Interval<f64>, Interval<f64>)> {
        match self.precision {
            Precision::F64 => self.interval.g_sides(t),
            Precision::F32 => {
                let (inside, outside) = self.interval32.g_sides(t.cast())?;
                Some((inside.cast(), outside.cast()))
            }
            Precision::Dd => {
                let (inside, outside) = self.interval_dd.g_sides(dd(t))?;
                Some((inside.to_interval(), outside.to_interval()))
            }
        }
    }

    /// Prunes the interval tape of `g` of the current precision to the beam over `t`
    /// ([`RayEvaluator::restrict`]); a new beam, ray or function undoes it.
    fn restrict(&mut self, t: Interval<f64>) {
        match self.precision {
            Precision::F64 => self.interval.restrict(t),
            Precision::F32 => self.interval32.restrict(t.cast()),
            Precision::Dd => self.interval_dd.restrict(dd(t)),
        }
    }

    /// Switches to the next precision with the beam set before, leaving the evaluator of
    /// the current one (its ray and its restriction) untouched for [`RayFn::restore`].
    fn escalate(&mut self) -> Option<Precision> {
        let previous = self.precision;
        let next = previous.escalated()?;
        self.precision = next;
        let (origin, dir) = (self.origin, self.dir);
        self.set_interval_ray(origin, dir);
        Some(previous)
    }

    fn restore(&mut self, previous: Precision) {
        self.precision = previous;
    }

    fn escalation_helps(
        &mut self,
        piece: Interval<f64>,
        now: Interval<f64>,
        end: f64,
        epsilon: f64,
        counters: &mut crate::root::RootCounters,
    ) -> bool {
        if self.precision.escalated().is_none() {
            return false;
        }
        let (origin, dir) = (self.origin, self.dir);
        let beam = Beam { origin, dir };
        let scope = self.scope();
        // On the central ray, with the current restriction: the rounding of `g` at `a`,
        // against the magnitude of `g` there and at the end of the range.
        let central = beam.central_ray();
        self.set_interval_ray_within(
            point_box(central.origin),
            point_box(central.dir),
            scope.as_ref(),
        );
        let unit = self.precision.unit_roundoff();
        let lost = |rounding: f64, scale: f64| {
            rounding > 0.0 && scale.is_finite() && rounding >= LOSSY_ULPS * unit * scale
        };
        let at = self.g(ipoint(piece.inf()));
        counters.g_evals += 1;
        // Most often `g(a)` alone is far larger than its rounding: one evaluation.
        let lossy = lost(at.wid(), at.mag()) && {
            let far = self.g(ipoint(end));
            counters.g_evals += 1;
            lost(at.wid(), far.mag())
        };
        let dominates =
            lossy && crate::root::rounding_dominates(self, piece.inf(), end, epsilon, counters);
        self.set_interval_ray_within(origin, dir, scope.as_ref());
        if !lossy || dominates || !self.is_beam() {
            return dominates;
        }
        // Large terms that cancel: the centred form in double-double, with the tape of the
        // current restriction.
        let Some(tape) = scope else {
            return false;
        };
        counters.g_evals += 2;
        counters.dg_evals += 1;
        self.centred_form(&tape, piece)
            .is_some_and(|c| c.to_interval().wid() <= ESCALATE_NARROWER * now.wid())
    }

    fn unrestrict(&mut self) {
        self.interval.unrestrict();
        self.interval32.unrestrict();
        self.interval_dd.unrestrict();
    }

    fn continuous_everywhere(&self) -> bool {
        match self.precision {
            Precision::F64 => self.interval.scope().is_continuous_everywhere(),
            Precision::F32 => self.interval32.scope().is_continuous_everywhere(),
            Precision::Dd => self.interval_dd.scope().is_continuous_everywhere(),
        }
    }

    fn scope(&self) -> Option<Tape> {
        Some(match self.precision {
            Precision::F64 => self.interval.scope().clone(),
            Precision::F32 => self.interval32.scope().clone(),
            Precision::Dd => self.interval_dd.scope().clone(),
        })
    }

    fn set_scope(&mut self, scope: &Tape) {
        match self.precision {
            Precision::F64 => self.interval.set_scope(scope),
            Precision::F32 => self.interval32.set_scope(scope),
            Precision::Dd => self.interval_dd.set_scope(scope),
        }
    }
}
