//! `exp`, `sin` and `cos` of double-double intervals, self-validating: argument reduction
//! and a Taylor polynomial evaluated in [`DdInterval`] arithmetic (outward), plus an
//! interval bound of the Taylor remainder, so every enclosure is as sound as `+ − × /`.
//!
//! * `exp(x) = 2^k · exp(r)²⁸` with `r = (x − k·ln 2) / 2⁸`, `|r| ≤ 0.0014` (`k·ln 2` from an
//!   exact expansion of `k` times three doubles of `ln 2`): eleven Taylor
//!   terms and a remainder below `10⁻³⁸`; the eight squarings multiply the relative error
//!   by 2⁸, so the bounds are within about `2^-94` (relative).
//! * `sin` and `cos`: `r = x − k·π/2`, `|r| ≤ 0.8` (for `|x| ≤ 2^20`), Taylor to degree 31
//!   and 32 with a remainder below `10⁻⁴⁰` (bounded by `10⁻³⁸`), the quadrant from `k`;
//!   within about `2^-100` of the exact values (the reduction `x − k·π/2` is an exact
//!   expansion with three doubles of `π/2`).
//! * `ln x = y₀ + ln(x·e^{−y₀})` with `y₀` the `f64` logarithm, the second term by a short
//!   Taylor sum (within about `2^-90`, absolute); `log₁₀ = ln / ln 10`; `pow(a, b) =
//!   exp(b·ln a)` for `a > 0`.
//! * `tan x = sin x / cos x` at the ends of an interval that holds no pole (a pole it may
//!   hold gives the `f64` path, the whole line).
//! * `atan x = y₀ + atan δ` with `y₀` the `f64` arctangent, `δ = (x − tan y₀)/(1 + x·tan y₀)`
//!   (about `10⁻¹⁶`) and `atan δ = δ − δ³/3` plus a remainder below `|δ|⁵/5`; for `|x| > 1`,
//!   `atan x = ±π/2 − atan(1/x)`. `asin x = atan(x / √((1 − x)(1 + x)))` and
//!   `acos x = 2·atan(√((1 − x)/(1 + x)))`, with `±π/2` and `π` at the ends of the domain;
//!   within about `2^-95` absolute.
//! * Over an interval, `exp`, `ln`, `tan` (between poles), `atan` and `asin` are increasing,
//!   `acos` decreasing; `sin` and `cos` take the hull of the end values
//!   and of the extremes `±1` at the multiples of `π/2` the interval may hold.
//! * Out of these ranges (`|x| > 700` for `exp`, or a result whose trailing part would be
//!   subnormal, below about `2^-960`; `|x| > 2^20`
//!   for `sin`/`cos`), on infinite
//!   bounds, and where a reduction is too wide to decide the quadrant, the `f64` hull path.

use std::sync::OnceLock;

use super::expansion::Expansion;
use super::interval::DdInterval;
use super::number::Dd;
use crate::Interval;

/// ln 2 as a sum of three doubles (within `10⁻⁴⁹`).
const LN2: [f64; 3] = [
    core::f64::consts::LN_2,
    2.3190468138462996e-17,
    5.707708438416212e-34,
];
/// π / 2 as a sum of three doubles (within `10⁻⁴⁹`).
const HALF_PI: [f64; 3] = [
    core::f64::consts::FRAC_PI_2,
    6.123233995736766e-17,
    -1.4973849048591698e-33,
];

/// ln 10 as a sum of two doubles, and a bound of the error of their sum.
const LN10: [f64; 2] = [core::f64::consts::LN_10, -2.1707562233822494e-16];
const LN10_ERROR: f64 = 1e-32;

/// π / 2 as a sum of two doubles, and a bound of the error of their sum (the third double of
/// [`HALF_PI`] and beyond).
const HALF_PI_ERROR: f64 = 2e-33;

/// An enclosure of `c[0] + c[1] ± error`: the trailing part moved outward by at least one
/// unit in its last place (an `error` below half of that unit would otherwise round away,
/// leaving a point where the constant is irrational).
fn constant(c: [f64; 2], error: f64) -> Option<DdInterval> {
    let lo = Dd::from_sum(c[0], (c[1] - error).next_down())?;
    let hi = Dd::from_sum(c[0], (c[1] + error).next_up())?;
    DdInterval::new(lo, hi).ok()
}

/// `x − k·c` for an integer `k` (`|k| < 2^21`) and a constant `c` given by three doubles,
/// enclosed: the products are exact expansions, and the constant's own error (below
/// `2^-150`) is added as a radius.
fn reduce(x: Dd, k: f64, c: [f64; 3]) -> Option<DdInterval> {
    let mut e = Expansion::new();
    e.add_dd(x);
    for part in c {
        e.add_product(-k, part);
    }
    let radius = (k.abs() * f64::from_bits((1023 - 150) << 52)).next_up();
    let mut down = e.clone();
    down.add(-radius);
    let mut up = e;
    up.add(radius);
    DdInterval::new(down.round(false)?, up.round(true)?).ok()
}

/// `[-m, m]`.
fn symmetric(m: f64) -> DdInterval {
    DdInterval::from_interval(Interval::new_unchecked(-m, m))
}

/// `Σ c_i·r^i` (Horner, `c` from the highest degree down) plus `[-rem, rem]`.
fn taylor(r: DdInterval, coefficients: impl Iterator<Item = DdInterval>, rem: f64) -> DdInterval {
    let mut acc = DdInterval::point(0.0);
    for c in coefficients {
        acc = acc * r + c;
    }
    acc + symmetric(rem)
}

/// Highest degree of the Taylor sums here (`cos`).
const MAX_DEGREE: usize = 32;

/// `1 / n!` enclosed, for `n ≤ MAX_DEGREE`: computed once.
fn inv_factorial(n: usize) -> DdInterval {
    static TABLE: OnceLock<[DdInterval; MAX_DEGREE + 1]> = OnceLock::new();
    TABLE.get_or_init(|| {
        core::array::from_fn(|n| {
            let f: f64 = (1..=n as u32).map(f64::from).product();
            DdInterval::point(1.0) / DdInterval::point(f)
        })
    })[n]
}

/// The coefficients of the Taylor sum of `sin` (`cos` when `cosine`) to `degree`, from the
/// highest degree down: `±1/n!` on the odd (even) degrees, 0 elsewhere.
fn trig_coefficients(degree: usize, cosine: bool) -> impl Iterator<Item = DdInterval> {
    let first = usize::from(!cosine);
    (0..=degree).rev().map(move |n| match (n + 4 - first) % 4 {
        0 => inv_factorial(n),
        2 => -inv_factorial(n),
        _ => DdInterval::point(0.0),
    })
}

/// `exp(x)` for a point, enclosed; `None` outside the double-double range.
fn exp_point(x: Dd) -> Option<DdInterval> {
    if !x.is_finite() || x.hi().abs() > 700.0 {
        return None;
    }
    if x.signum() == 0 {
        return Some(DdInterval::point(1.0));
    }
    let k = (x.hi() / core::f64::consts::LN_2).round();
    let scale = f64::from_bits((1023 - 8) << 52);
    let r = reduce(x, k, LN2)? * DdInterval::point(scale);
    // Degree 10: |r| ≤ 0.0014 gives |r|^11 / 11! · e^|r| < 1e-39.
    if r.to_interval().mag().is_nan() || r.to_interval().mag() > 0.0014 {
        return None;
    }
    let mut e = taylor(r, (0..=10).rev().map(inv_factorial), 1e-38);
    for _ in 0..8 {
        e = e.sqr();
    }
    e.scaled(k as i32)
}

/// `ln x` for a positive point, enclosed: `y₀ = ln(hi)` in `f64`, then `ln x = y₀ + ln(1 + δ)`
/// with `1 + δ = x·e^{−y₀}` (from [`exp_point`]) and `ln(1 + δ) = δ − δ²/2 + δ³/3 − δ⁴/4`
/// plus a remainder below `|δ|⁵/(5(1 − |δ|))`, after taking out the binary exponent
/// (`ln x = e·ln 2 + ln m`, `m ∈ [1, 2)`); `None` for subnormal arguments.
fn ln_point(x: Dd) -> Option<DdInterval> {
    if x.is_finite() && x == Dd::from_f64(1.0) {
        return Some(DdInterval::point(0.0));
    }
    if !(x.is_finite() && x.hi() >= f64::MIN_POSITIVE) {
        return None;
    }
    // x = m·2^e with m in [1, 2) (exact scaling): ln x = e·ln 2 + ln m.
    let e = x.hi().log2().floor();
    if e != 0.0 {
        let f = 2f64.powi(-(e as i32));
        let (h, l) = (x.hi() * f, x.lo() * f);
        if l != 0.0 && l.abs() < f64::MIN_POSITIVE {
            return None;
        }
        let m = Dd::from_sum(h, l)?;
        return Some(reduce(Dd::ZERO, -e, LN2)? + ln_point(m)?);
    }
    let y0 = x.hi().ln();
    let z = DdInterval::new(x, x).ok()? * exp_point(Dd::from_f64(-y0))?;
    let d = z - DdInterval::point(1.0);
    // y0 is within a few ulps of ln x, so |δ| is about 1e-16: the remainder is below 1e-49.
    let m = d.to_interval().mag();
    if m.is_nan() || m > 1e-10 {
        return None;
    }
    let third = DdInterval::point(1.0) / DdInterval::point(3.0);
    let coefficients = [
        DdInterval::point(-0.25),
        third,
        DdInterval::point(-0.5),
        DdInterval::point(1.0),
        DdInterval::point(0.0),
    ];
    Some(DdInterval::point(y0) + taylor(d, coefficients.into_iter(), 1e-49))
}

/// `sin(x)` and `cos(x)` for a point, enclosed; `None` outside the reduction's range.
fn sin_cos_point(x: Dd) -> Option<(DdInterval, DdInterval)> {
    if !x.is_finite() || x.hi().abs() > 1_048_576.0 {
        return None;
    }
    let k = (x.hi() / core::f64::consts::FRAC_PI_2).round();
    let r = reduce(x, k, HALF_PI)?;
    // |r| ≤ 0.8 (π/4 and the reduction's error): degree 31 (sin; its degree-32 term is 0)
    // and 32 (cos) leave at most |r|^33 / 33! < 1e-40.
    if r.to_interval().mag().is_nan() || r.to_interval().mag() > 0.8 {
        return None;
    }
    let s = taylor(r, trig_coefficients(MAX_DEGREE - 1, false), 1e-38);
    let c = taylor(r, trig_coefficients(MAX_DEGREE, true), 1e-38);
    Some(match (k as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    })
}

/// `π/2` enclosed.
fn half_pi() -> Option<DdInterval> {
    constant([HALF_PI[0], HALF_PI[1]], HALF_PI_ERROR)
}

/// `atan(x)` for a finite point, enclosed: `y₀ + atan δ` near `x` (see the module
/// documentation), and `±π/2 − atan(1/x)` for `|x| > 1`.
fn atan_point(x: Dd) -> Option<DdInterval> {
    if !x.is_finite() {
        return None;
    }
    if x.signum() == 0 {
        return Some(DdInterval::point(0.0));
    }
    let p = DdInterval::new(x, x).ok()?;
    if x.hi().abs() > 1.0 {
        // atan x = sign(x)·π/2 − atan(1/x), with |1/x| < 1.
        let inverse = atan_interval(DdInterval::point(1.0) / p)?;
        let quarter = half_pi()?;
        return Some(if x.signum() > 0 {
            quarter - inverse
        } else {
            -quarter - inverse
        });
    }
    let y0 = x.hi().atan();
    let (s, c) = sin_cos_point(Dd::from_f64(y0))?;
    let t0 = s / c;
    let d = (p - t0) / (DdInterval::point(1.0) + p * t0);
    let m = d.to_interval().mag();
    // tan y₀ is within a few ulps of x: |δ| is about 1e-16, and |δ|⁵/5 below 1e-50.
    if m.is_nan() || m > 1e-10 {
        return None;
    }
    let third = DdInterval::point(1.0) / DdInterval::point(3.0);
    let coefficients = [
        -third,
        DdInterval::point(0.0),
        DdInterval::point(1.0),
        DdInterval::point(0.0),
    ];
    Some(DdInterval::point(y0) + taylor(d, coefficients.into_iter(), 1e-49))
}

/// `atan` over an interval of finite bounds (increasing).
fn atan_interval(x: DdInterval) -> Option<DdInterval> {
    let (lo, hi) = x.bounds()?;
    let (a, _) = atan_point(lo)?.bounds()?;
    let (_, b) = atan_point(hi)?.bounds()?;
    DdInterval::new(a, b).ok()
}

/// `asin(x)` for a point of `[−1, 1]`, enclosed.
fn asin_point(x: Dd) -> Option<DdInterval> {
    let one = Dd::from_f64(1.0);
    if x == one {
        return half_pi();
    }
    if x == -one {
        return Some(-half_pi()?);
    }
    let p = DdInterval::new(x, x).ok()?;
    let u = DdInterval::point(1.0);
    let root = ((u - p) * (u + p)).sqrt();
    atan_interval(p / root)
}

/// `acos(x)` for a point of `[−1, 1]`, enclosed.
fn acos_point(x: Dd) -> Option<DdInterval> {
    if x == -Dd::from_f64(1.0) {
        let quarter = half_pi()?;
        return Some(quarter + quarter);
    }
    let p = DdInterval::new(x, x).ok()?;
    let u = DdInterval::point(1.0);
    let a = atan_interval(((u - p) / (u + p)).sqrt())?;
    Some(a + a)
}

/// The integers `q` that `x / (π/2)` may equal, as `[q0, q1]`; `None` when too many.
fn quarter_turns(x: DdInterval) -> Option<(i64, i64)> {
    let half_pi = Interval::new(HALF_PI[0].next_down(), HALF_PI[0].next_up()).ok()?;
    let q = x.to_interval() / half_pi;
    let (lo, hi) = q.bounds()?;
    if !(lo.is_finite() && hi.is_finite()) || hi - lo > 8.0 {
        return None;
    }
    Some((lo.ceil() as i64, hi.floor() as i64))
}

impl DdInterval {
    /// `eˣ` (monotone: the enclosures at the two ends).
    pub fn exp(self) -> Self {
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        match (exp_point(lo), exp_point(hi)) {
            (Some(a), Some(b)) => {
                let (Some((a, _)), Some((_, b))) = (a.bounds(), b.bounds()) else {
                    return self.map_f64(Interval::exp);
                };
                // eˣ > 0: a negative lower bound from the remainder is raised to 0.
                let a = if a.signum() < 0 { Dd::ZERO } else { a };
                Self::new(a, b).unwrap_or_else(|_| self.map_f64(Interval::exp))
            }
            _ => self.map_f64(Interval::exp),
        }
    }

    /// `ln x` over the positive part (empty where there is none; `−∞` below where the
    /// interval reaches 0).
    pub fn ln(self) -> Self {
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        if hi.signum() <= 0 {
            return Self::EMPTY;
        }
        let low = if lo.signum() <= 0 {
            Some(Dd::NEG_INFINITY)
        } else {
            ln_point(lo).and_then(|v| v.bounds()).map(|(l, _)| l)
        };
        let high = ln_point(hi).and_then(|v| v.bounds()).map(|(_, h)| h);
        match (low, high) {
            (Some(l), Some(h)) => Self::new(l, h).unwrap_or_else(|_| self.map_f64(Interval::ln)),
            _ => self.map_f64(Interval::ln),
        }
    }

    /// `log₁₀ x` (`ln x / ln 10`).
    pub fn log10(self) -> Self {
        match constant(LN10, LN10_ERROR) {
            Some(ln10) if !self.is_empty() => {
                let l = self.ln();
                if l.to_interval().is_common_interval() {
                    l / ln10
                } else {
                    self.map_f64(Interval::log10)
                }
            }
            _ => self.map_f64(Interval::log10),
        }
    }

    /// `self^b` for a real exponent (IEEE 1788 `pow`): `exp(b · ln self)` where `self > 0`,
    /// the `f64` path elsewhere (a base reaching 0).
    pub fn pow(self, b: Self) -> Self {
        match self.bounds() {
            Some((lo, _)) if lo.signum() > 0 && !b.is_empty() => {
                let l = self.ln();
                if l.to_interval().is_common_interval() && b.to_interval().is_common_interval() {
                    (b * l).exp()
                } else {
                    self.map2_f64(b, Interval::pow)
                }
            }
            _ => self.map2_f64(b, Interval::pow),
        }
    }

    /// `sin x`.
    pub fn sin(self) -> Self {
        self.trig(false)
    }

    /// `cos x`.
    pub fn cos(self) -> Self {
        self.trig(true)
    }

    /// `sin` or `cos` over the interval: the end values and the extremes it may hold.
    fn trig(self, cosine: bool) -> Self {
        let fallback = || {
            if cosine {
                self.map_f64(Interval::cos)
            } else {
                self.map_f64(Interval::sin)
            }
        };
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        let (Some(a), Some(b), Some((q0, q1))) =
            (sin_cos_point(lo), sin_cos_point(hi), quarter_turns(self))
        else {
            return fallback();
        };
        let pick = |v: (Self, Self)| if cosine { v.1 } else { v.0 };
        let mut out = pick(a).convex_hull(pick(b));
        // sin has its maximum at q ≡ 1 (mod 4) and its minimum at q ≡ 3; cos at 0 and 2.
        let (max_at, min_at) = if cosine { (0, 2) } else { (1, 3) };
        for q in q0..=q1 {
            match q.rem_euclid(4) {
                m if m == max_at => out = out.convex_hull(Self::point(1.0)),
                m if m == min_at => out = out.convex_hull(Self::point(-1.0)),
                _ => {}
            }
        }
        // The values lie in [−1, 1].
        out.intersection_unit()
    }

    /// `tan x`: the values at the ends where the interval holds no pole (`(2q + 1)·π/2`),
    /// else the `f64` path (the whole line).
    pub fn tan(self) -> Self {
        let fallback = || self.map_f64(Interval::tan);
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        let Some((q0, q1)) = quarter_turns(self) else {
            return fallback();
        };
        if (q0..=q1).any(|q| q.rem_euclid(2) == 1) {
            return fallback();
        }
        let end = |x: Dd| sin_cos_point(x).map(|(s, c)| s / c);
        match (end(lo), end(hi)) {
            (Some(a), Some(b)) => match (a.bounds(), b.bounds()) {
                (Some((a, _)), Some((_, b))) => Self::new(a, b).unwrap_or_else(|_| fallback()),
                _ => fallback(),
            },
            _ => fallback(),
        }
    }

    /// `atan x` (increasing; `±π/2` at infinite bounds).
    pub fn atan(self) -> Self {
        let fallback = || self.map_f64(Interval::atan);
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        let quarter = half_pi();
        let low = if lo.is_finite() {
            atan_point(lo).and_then(|v| v.bounds()).map(|(a, _)| a)
        } else {
            quarter.and_then(|q| (-q).bounds()).map(|(a, _)| a)
        };
        let high = if hi.is_finite() {
            atan_point(hi).and_then(|v| v.bounds()).map(|(_, b)| b)
        } else {
            quarter.and_then(|q| q.bounds()).map(|(_, b)| b)
        };
        match (low, high) {
            (Some(a), Some(b)) => Self::new(a, b).unwrap_or_else(|_| fallback()),
            _ => fallback(),
        }
    }

    /// `asin x` over the part of the interval in `[−1, 1]` (increasing; empty where there
    /// is none).
    pub fn asin(self) -> Self {
        self.inverse_trig(asin_point, false, Interval::asin)
    }

    /// `acos x` over the part of the interval in `[−1, 1]` (decreasing; empty where there
    /// is none).
    pub fn acos(self) -> Self {
        self.inverse_trig(acos_point, true, Interval::acos)
    }

    /// `asin` or `acos` (`decreasing`) over `self ∩ [−1, 1]`, from `point` at its ends.
    fn inverse_trig(
        self,
        point: fn(Dd) -> Option<DdInterval>,
        decreasing: bool,
        f64_op: fn(Interval<f64>) -> Interval<f64>,
    ) -> Self {
        let unit = self.intersection_unit();
        let Some((lo, hi)) = unit.bounds() else {
            return Self::EMPTY;
        };
        let (first, last) = if decreasing { (hi, lo) } else { (lo, hi) };
        let low = point(first).and_then(|v| v.bounds()).map(|(a, _)| a);
        let high = point(last).and_then(|v| v.bounds()).map(|(_, b)| b);
        match (low, high) {
            (Some(a), Some(b)) => Self::new(a, b).unwrap_or_else(|_| unit.map_f64(f64_op)),
            _ => unit.map_f64(f64_op),
        }
    }

    /// `self · 2^k`, exactly (`None` where a part would leave the normal range).
    fn scaled(self, k: i32) -> Option<Self> {
        let (lo, hi) = self.bounds()?;
        let f = 2f64.powi(k);
        let scale = |x: Dd| {
            let (h, l) = (x.hi() * f, x.lo() * f);
            let normal = |v: f64| v == 0.0 || (v.is_finite() && v.abs() >= f64::MIN_POSITIVE);
            (normal(h) && normal(l) && f.is_finite() && f != 0.0)
                .then(|| Dd::from_sum(h, l))
                .flatten()
        };
        Self::new(scale(lo)?, scale(hi)?).ok()
    }

    /// `self ∩ [−1, 1]`.
    fn intersection_unit(self) -> Self {
        let one = Dd::from_f64(1.0);
        let Some((lo, hi)) = self.bounds() else {
            return self;
        };
        let lo = if lo < -one { -one } else { lo };
        let hi = if hi > one { one } else { hi };
        Self::new(lo, hi).unwrap_or(Self::EMPTY)
    }
}
