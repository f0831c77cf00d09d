// --- elementary functions ----------------------------------------------------------------
//
// Each uses the WGSL accuracy bound of the built-in it calls (WGSL "Floating Point
// Accuracy"): exp 3 + 2|x| ULP; log 3 ULP outside [0.5, 2] and an absolute 2^-21 inside;
// sin and cos an absolute 2^-11 on [-pi, pi] only; atan 4096 ULP. A bound of k ULPs of the
// exact value is at most 2k + 1 ULPs of a rounded result next to a power of two. The rest
// are compositions of sound interval operations: tan = sin / cos, asin and acos through
// atan and sqrt, pow through exp and ln, log10 = ln times 1 / ln 10.

// pi / 2 and 1 / ln 10, enclosed.
const HALF_PI_LO: f32 = 0x1.921fb4p+0f;
const HALF_PI_HI: f32 = 0x1.921fb6p+0f;
const PI_LO: f32 = 0x1.921fb4p+1f;
const INV_LN10_LO: f32 = 0x1.bcb7b0p-2f;
const INV_LN10_HI: f32 = 0x1.bcb7b2p-2f;

fn raw_exp(x: f32) -> f32 { return flush(exp(flush(x))); }
fn raw_log(x: f32) -> f32 { return flush(log(flush(x))); }
fn raw_sin(x: f32) -> f32 { return flush(sin(flush(x))); }
fn raw_cos(x: f32) -> f32 { return flush(cos(flush(x))); }
fn raw_atan(x: f32) -> f32 { return flush(atan(flush(x))); }

fn exp_bound(x: f32, up: bool) -> f32 {
    if x > 88.0f {
        // e^88 > 2^126.
        return select(0x1p126f, BIG, up);
    }
    if x < -87.0f {
        // e^-87 < 2^-125.
        return select(0.0f, 0x1p-125f, up);
    }
    let r = raw_exp(x);
    let n = 2u * (3u + 2u * u32(ceil(abs(x)))) + 1u;
    return finish(select(step_down(r, n), step_up(r, n), up), up);
}

fn i_exp(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(exp_bound(a.lo, false), exp_bound(a.hi, true));
}

// ln of a positive bound.
fn ln_bound(x: f32, up: bool) -> f32 {
    if x >= BIG {
        return select(88.0f, BIG, up);
    }
    let r = raw_log(x);
    if x >= 0.5f && x <= 2.0f {
        // Absolute error 2^-21 (then the sum's own rounding).
        return add_bound(r, select(-0x1p-21f, 0x1p-21f, up), up);
    }
    return finish(select(step_down(r, 7u), step_up(r, 7u), up), up);
}

// ln over the positive part of a.
fn i_ln(a: Interval) -> Interval {
    if i_is_empty(a) || a.hi <= 0.0f {
        return i_empty();
    }
    var lo = -BIG;
    if a.lo > 0.0f {
        lo = ln_bound(a.lo, false);
    }
    return Interval(lo, ln_bound(a.hi, true));
}

fn i_log10(a: Interval) -> Interval {
    return i_mul(i_ln(a), Interval(INV_LN10_LO, INV_LN10_HI));
}

// sin or cos of a bound inside [-pi, pi], widened by the absolute error and clamped.
fn trig_bound(r: f32, up: bool) -> f32 {
    return clamp(add_bound(r, select(-0x1p-11f, 0x1p-11f, up), up), -1.0f, 1.0f);
}

// Whether [lo, hi] may hold the point c enclosed by [c_lo, c_hi].
fn may_hold(lo: f32, hi: f32, c_lo: f32, c_hi: f32) -> bool {
    return lo <= c_hi && hi >= c_lo;
}

fn i_sin(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    // The accuracy is only specified on [-pi, pi] (PI_LO < pi keeps inside it).
    if a.lo < -PI_LO || a.hi > PI_LO {
        return Interval(-1.0f, 1.0f);
    }
    // On [-pi, pi], sin rises on [-pi/2, pi/2] and falls outside it: the range is spanned
    // by the end values and by 1 or -1 where the interval may hold pi/2 or -pi/2.
    let s0 = raw_sin(a.lo);
    let s1 = raw_sin(a.hi);
    var lo = min(trig_bound(s0, false), trig_bound(s1, false));
    var hi = max(trig_bound(s0, true), trig_bound(s1, true));
    if may_hold(a.lo, a.hi, HALF_PI_LO, HALF_PI_HI) {
        hi = 1.0f;
    }
    if may_hold(a.lo, a.hi, -HALF_PI_HI, -HALF_PI_LO) {
        lo = -1.0f;
    }
    return Interval(lo, hi);
}

fn i_cos(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    if a.lo < -PI_LO || a.hi > PI_LO {
        return Interval(-1.0f, 1.0f);
    }
    // On [-pi, pi], cos rises up to 0 and falls after it.
    let c0 = raw_cos(a.lo);
    let c1 = raw_cos(a.hi);
    let lo = min(trig_bound(c0, false), trig_bound(c1, false));
    var hi = max(trig_bound(c0, true), trig_bound(c1, true));
    if a.lo <= 0.0f && a.hi >= 0.0f {
        hi = 1.0f;
    }
    return Interval(lo, hi);
}

// tan = sin / cos (the WGSL accuracy of tan is inherited from that quotient).
fn i_tan(a: Interval) -> Interval {
    return i_div(i_sin(a), i_cos(a));
}

fn atan_bound(x: f32, up: bool) -> f32 {
    if abs(x) >= BIG {
        return select(-HALF_PI_HI, HALF_PI_HI, x > 0.0f);
    }
    let r = raw_atan(x);
    let s = select(step_down(r, 8193u), step_up(r, 8193u), up);
    return clamp(finish(s, up), -HALF_PI_HI, HALF_PI_HI);
}

fn i_atan(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(atan_bound(a.lo, false), atan_bound(a.hi, true));
}

// a intersected with [-1, 1].
fn unit_part(a: Interval) -> Interval {
    return Interval(max(a.lo, -1.0f), min(a.hi, 1.0f));
}

// asin(x) = atan(x / sqrt(1 - x^2)) over the part of a in [-1, 1].
fn i_asin(a: Interval) -> Interval {
    let u = unit_part(a);
    if i_is_empty(a) || i_is_empty(u) {
        return i_empty();
    }
    let d = i_sqrt(i_sub(Interval(1.0f, 1.0f), i_sqr(u)));
    let r = i_atan(i_div(u, d));
    // x / sqrt(1 - x^2) is undefined at +-1, where asin is +-pi/2: add those values.
    var lo = r.lo;
    var hi = r.hi;
    if i_is_empty(r) {
        lo = BIG;
        hi = -BIG;
    }
    if u.lo <= -1.0f {
        lo = -HALF_PI_HI;
        hi = max(hi, -HALF_PI_LO);
    }
    if u.hi >= 1.0f {
        lo = min(lo, HALF_PI_LO);
        hi = HALF_PI_HI;
    }
    return Interval(max(lo, -HALF_PI_HI), min(hi, HALF_PI_HI));
}

// acos(x) = pi/2 - asin(x).
fn i_acos(a: Interval) -> Interval {
    let s = i_asin(a);
    if i_is_empty(s) {
        return i_empty();
    }
    let r = i_sub(Interval(HALF_PI_LO, HALF_PI_HI), s);
    return Interval(max(r.lo, 0.0f), r.hi);
}

// a^b = exp(b ln a) for a > 0, and 0 for a = 0 when b > 0 (IEEE 1788's pow).
fn i_pow(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) || a.hi < 0.0f {
        return i_empty();
    }
    var r = i_exp(i_mul(b, i_ln(Interval(max(a.lo, 0.0f), a.hi))));
    if a.lo <= 0.0f && b.hi > 0.0f {
        // The value 0 at a = 0.
        if i_is_empty(r) {
            r = Interval(0.0f, 0.0f);
        } else {
            r = Interval(min(r.lo, 0.0f), max(r.hi, 0.0f));
        }
    }
    return r;
}

// round(x), halves away from zero: trunc(x) plus the sign where |x - trunc(x)| >= 1/2
// (x - trunc(x) is exact).
fn round_away(x: f32) -> f32 {
    let t = trunc(x);
    if abs(x - t) >= 0.5f {
        return t + sign(x);
    }
    return t;
}

fn i_round(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(round_away(a.lo), round_away(a.hi));
}

// 1 where a = 0, else 0.
fn i_not(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    if a.lo == 0.0f && a.hi == 0.0f {
        return Interval(1.0f, 1.0f);
    }
    if a.lo > 0.0f || a.hi < 0.0f {
        return Interval(0.0f, 0.0f);
    }
    return Interval(0.0f, 1.0f);
}

fn slope(jump: bool) -> Interval {
    if jump {
        return i_entire();
    }
    return Interval(0.0f, 0.0f);
}

fn i_slope_floor(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    // An integer in [lo, hi] exactly when ceil(lo) <= hi (ceil is exact).
    return slope(ceil(a.lo) <= a.hi);
}

fn i_slope_round(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    if a.hi - a.lo >= 1.0f {
        return slope(true);
    }
    let f = floor(a.lo);
    if abs(f) >= 0x1p22f {
        // Every f32 there is a multiple of 1/2 or coarser: a half-integer lies between two
        // distinct values, or is the single value.
        return slope(a.hi > a.lo || fract(a.lo) == 0.5f);
    }
    // Width below 1: the half-integer candidates are f + 1/2 and f + 3/2 (exact).
    let h1 = f + 0.5f;
    let h2 = f + 1.5f;
    return slope((a.lo <= h1 && h1 <= a.hi) || (a.lo <= h2 && h2 <= a.hi));
}

fn i_slope_not(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return slope(a.lo <= 0.0f && a.hi >= 0.0f);
}
