// Interval arithmetic over f32 with outward rounding emulated from the accuracy that the
// WGSL specification guarantees (WGSL has no rounding modes).
//
// Representation. `Interval(lo, hi)` stands for the reals x with lo' <= x <= hi', where
// lo' = -inf when lo == -BIG and hi' = +inf when hi == BIG (BIG = the largest finite f32):
// the library never relies on infinities or NaNs, which WGSL lets an implementation assume
// absent. Every bound the library produces is zero, normal or +-BIG, never subnormal, so a
// GPU that flushes subnormals to zero reads every bound as it was written. An interval with
// lo > hi is empty (`i_empty()`).
//
// Rounding. Each raw operation is guarded so that its exact result is finite and either zero
// or normal, then its rounded result is moved outward by the operation's error bound in
// units in the last place (ULP), by stepping the bit pattern; a step that would leave the
// normal range lands on +-TINY (the smallest normal) or 0, or saturates to +-BIG.
//
// The override FLUSH_SUBNORMALS makes every raw operation flush its operands and result as
// a GPU without subnormals may: the tests run both ways.

struct Interval {
    lo: f32,
    hi: f32,
}

override FLUSH_SUBNORMALS: bool = false;

const BIG: f32 = 0x1.fffffep+127f;
// The largest finite bound that is not infinity: lower bounds stay at or below it, upper
// bounds at or above its negative (+BIG as a lower bound would mean +inf).
const BELOW_BIG: f32 = 0x1.fffffcp+127f;
const TINY: f32 = 0x1p-126f;
// Magnitudes below which a sum of two values cannot overflow.
const ADD_SAFE: f32 = 0x1p+126f;

// --- raw operations (what the hardware computes) -----------------------------------------

fn flush(x: f32) -> f32 {
    if FLUSH_SUBNORMALS && abs(x) < TINY {
        return 0.0f * x;
    }
    return x;
}

fn raw_add(a: f32, b: f32) -> f32 { return flush(flush(a) + flush(b)); }
fn raw_mul(a: f32, b: f32) -> f32 { return flush(flush(a) * flush(b)); }
fn raw_div(a: f32, b: f32) -> f32 { return flush(flush(a) / flush(b)); }
fn raw_sqrt(a: f32) -> f32 { return flush(sqrt(flush(a))); }

// --- stepping ----------------------------------------------------------------------------

// The bound `x` moved `n` ULPs up: never subnormal (values in (-TINY, TINY) step to TINY or
// to 0 from below), saturating at BIG.
fn step_up(x: f32, n: u32) -> f32 {
    if x >= BIG {
        return BIG;
    }
    if abs(x) < TINY {
        return TINY;
    }
    let u = bitcast<u32>(x);
    if x > 0.0f {
        // Positive: larger magnitude. 0x7f7fffff is BIG.
        return bitcast<f32>(min(u + n, 0x7f7fffffu));
    }
    // Negative: smaller magnitude; below TINY in magnitude it becomes 0.
    let m = u & 0x7fffffffu;
    if m <= 0x00800000u + n {
        return 0.0f;
    }
    return bitcast<f32>(u - n);
}

// The bound `x` moved `n` ULPs down (the mirror of `step_up`).
fn step_down(x: f32, n: u32) -> f32 {
    return -step_up(-x, n);
}

// --- helpers on bounds -------------------------------------------------------------------

// A computed bound made valid: a lower bound never +BIG (it would mean +inf), an upper
// bound never -BIG. Lowering a lower bound (raising an upper one) is always sound.
fn finish(x: f32, up: bool) -> f32 {
    if up {
        return max(x, -BELOW_BIG);
    }
    return min(x, BELOW_BIG);
}

fn is_neg_inf(lo: f32) -> bool { return lo <= -BIG; }
fn is_pos_inf(hi: f32) -> bool { return hi >= BIG; }

// The unbiased binary exponent of a normal `x` (floor(log2|x|)); -127 for zero.
fn exponent(x: f32) -> i32 {
    return i32((bitcast<u32>(x) >> 23u) & 0xffu) - 127;
}

// Lower and upper bounds of a + b for bounds a, b (lower: `up = false`).
fn add_bound_unchecked(a: f32, b: f32, up: bool) -> f32 {
    if up {
        if is_pos_inf(a) || is_pos_inf(b) {
            return BIG;
        }
    } else if is_neg_inf(a) || is_neg_inf(b) {
        return -BIG;
    }
    if a == 0.0f {
        return b;
    }
    if b == 0.0f {
        return a;
    }
    if abs(a) < ADD_SAFE && abs(b) < ADD_SAFE {
        let s = raw_add(a, b);
        // One ULP covers the correctly rounded sum; a sum in the subnormal range may have
        // been flushed, and stepping from there lands on +-TINY or 0.
        return select(step_down(s, 1u), step_up(s, 1u), up);
    }
    // Large operands: halve them (exact for normals; a tiny operand's half may be flushed,
    // an absolute error below the large one's ULP), add, widen by two ULPs, double.
    let h = raw_add(a * 0.5f, b * 0.5f);
    let w = select(step_down(h, 2u), step_up(h, 2u), up);
    if abs(w) >= 0x1p127f {
        return select(-BIG, BIG, w > 0.0f);
    }
    return w * 2.0f;
}

// The product of bounds a and b rounded down (up = false) or up, with 0 * inf = 0.
fn mul_bound_unchecked(a: f32, b: f32, up: bool) -> f32 {
    if a == 0.0f || b == 0.0f {
        return 0.0f;
    }
    let negative = (a < 0.0f) != (b < 0.0f);
    if abs(a) >= BIG || abs(b) >= BIG {
        return select(BIG, -BIG, negative);
    }
    let e = exponent(a) + exponent(b);
    if e >= 126 {
        // |a b| >= 2^126: may exceed BIG. Saturate away from zero; towards zero, the
        // product is at least 2^e in magnitude, and 2^126 is a valid bound.
        if negative == up {
            return select(0x1p126f, -0x1p126f, negative);
        }
        return select(BIG, -BIG, negative);
    }
    if e <= -127 {
        // |a b| < 2^-125: 0 towards zero, 2^-125 away from it.
        if negative == up {
            return 0.0f;
        }
        return select(0x1p-125f, -0x1p-125f, negative);
    }
    let p = raw_mul(a, b);
    return select(step_down(p, 1u), step_up(p, 1u), up);
}

// The quotient of bounds a / b rounded down or up, for b != 0 of the same sign as the
// divisor interval; |b| >= BIG counts as infinite.
fn div_bound_unchecked(a: f32, b: f32, up: bool) -> f32 {
    if a == 0.0f {
        return 0.0f;
    }
    let negative = (a < 0.0f) != (b < 0.0f);
    if abs(b) >= BIG {
        // a / inf: 0, or the smallest magnitude away from zero.
        if negative == up {
            return 0.0f;
        }
        return select(TINY, -TINY, negative);
    }
    if abs(a) >= BIG {
        return select(BIG, -BIG, negative);
    }
    let e = exponent(a) - exponent(b);
    if e >= 126 {
        if negative == up {
            return select(0x1p125f, -0x1p125f, negative);
        }
        return select(BIG, -BIG, negative);
    }
    if e <= -125 {
        if negative == up {
            return 0.0f;
        }
        return select(0x1p-123f, -0x1p-123f, negative);
    }
    // WGSL: 2.5 ULP for |b| in [2^-126, 2^126]. Scale b into that range by a power of two
    // (exact) when it is outside, moving the factor to a (exact: a's exponent leaves room).
    var x = a;
    var y = b;
    if abs(y) > 0x1p126f {
        y = y * 0x1p-4f;
        x = x * 0x1p-4f;
    }
    let q = raw_div(x, y);
    // 2.5 ULP of the exact quotient is at most 5 ULP of a rounded result near a power of
    // two; step 6.
    return select(step_down(q, 6u), step_up(q, 6u), up);
}

fn add_bound(a: f32, b: f32, up: bool) -> f32 { return finish(add_bound_unchecked(a, b, up), up); }
fn mul_bound(a: f32, b: f32, up: bool) -> f32 { return finish(mul_bound_unchecked(a, b, up), up); }
fn div_bound(a: f32, b: f32, up: bool) -> f32 { return finish(div_bound_unchecked(a, b, up), up); }

// --- the library (the functions implicit-expr's WGSL output calls) ------------------------

fn i_empty() -> Interval { return Interval(BIG, -BIG); }
fn i_is_empty(a: Interval) -> bool { return a.lo > a.hi; }
fn i_entire() -> Interval { return Interval(-BIG, BIG); }
fn i_at_least(lo: f32) -> Interval { return Interval(lo, BIG); }
fn i_at_most(hi: f32) -> Interval { return Interval(-BIG, hi); }

fn i_add(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) {
        return i_empty();
    }
    return Interval(add_bound(a.lo, b.lo, false), add_bound(a.hi, b.hi, true));
}

fn i_neg(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(-a.hi, -a.lo);
}

fn i_sub(a: Interval, b: Interval) -> Interval {
    return i_add(a, i_neg(b));
}

fn i_mul(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) {
        return i_empty();
    }
    let lo = min(min(mul_bound(a.lo, b.lo, false), mul_bound(a.lo, b.hi, false)),
                 min(mul_bound(a.hi, b.lo, false), mul_bound(a.hi, b.hi, false)));
    let hi = max(max(mul_bound(a.lo, b.lo, true), mul_bound(a.lo, b.hi, true)),
                 max(mul_bound(a.hi, b.lo, true), mul_bound(a.hi, b.hi, true)));
    return Interval(lo, hi);
}

fn i_sqr(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    let m = max(abs(a.lo), abs(a.hi));
    var lo = 0.0f;
    if a.lo > 0.0f {
        lo = mul_bound(a.lo, a.lo, false);
    } else if a.hi < 0.0f {
        lo = mul_bound(a.hi, a.hi, false);
    }
    return Interval(lo, mul_bound(m, m, true));
}

fn i_abs(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    if a.lo >= 0.0f {
        return a;
    }
    if a.hi <= 0.0f {
        return i_neg(a);
    }
    return Interval(0.0f, max(-a.lo, a.hi));
}

fn i_min(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) {
        return i_empty();
    }
    return Interval(min(a.lo, b.lo), min(a.hi, b.hi));
}

fn i_max(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) {
        return i_empty();
    }
    return Interval(max(a.lo, b.lo), max(a.hi, b.hi));
}

// domain(d, f): f where d <= 0, the absent object (+inf, as [BELOW_BIG, BIG]) where d > 0,
// and f joined with +inf where d takes both signs or is empty.
fn i_domain(d: Interval, f: Interval) -> Interval {
    if !i_is_empty(d) && d.hi <= 0.0f {
        return f;
    }
    if i_is_empty(f) || (!i_is_empty(d) && d.lo > 0.0f) {
        return Interval(BELOW_BIG, BIG);
    }
    return Interval(f.lo, BIG);
}

// 1 / a over the nonzero part of a (IEEE 1788 set-based: the empty set for a = [0, 0]).
fn i_recip(a: Interval) -> Interval {
    return i_div(Interval(1.0f, 1.0f), a);
}

fn i_div(a: Interval, b: Interval) -> Interval {
    if i_is_empty(a) || i_is_empty(b) || (b.lo == 0.0f && b.hi == 0.0f) {
        return i_empty();
    }
    if b.lo < 0.0f && b.hi > 0.0f {
        // The divisor straddles zero: every real (the hull of the two pieces).
        return i_entire();
    }
    if b.lo >= 0.0f {
        // b in [+0, hi]: a lower bound 0 of b stands for the positive reals near 0.
        if b.lo == 0.0f {
            if a.lo >= 0.0f {
                return Interval(div_bound(a.lo, b.hi, false), BIG);
            }
            if a.hi <= 0.0f {
                return Interval(-BIG, div_bound(a.hi, b.hi, true));
            }
            return i_entire();
        }
    } else if b.hi == 0.0f {
        if a.lo >= 0.0f {
            return Interval(-BIG, div_bound(a.lo, b.lo, true));
        }
        if a.hi <= 0.0f {
            return Interval(div_bound(a.hi, b.lo, false), BIG);
        }
        return i_entire();
    }
    // 0 not in b: the four quotients.
    let lo = min(min(div_bound(a.lo, b.lo, false), div_bound(a.lo, b.hi, false)),
                 min(div_bound(a.hi, b.lo, false), div_bound(a.hi, b.hi, false)));
    let hi = max(max(div_bound(a.lo, b.lo, true), div_bound(a.lo, b.hi, true)),
                 max(div_bound(a.hi, b.lo, true), div_bound(a.hi, b.hi, true)));
    return Interval(lo, hi);
}

// sqrt over the nonnegative part of a.
fn i_sqrt(a: Interval) -> Interval {
    if i_is_empty(a) || a.hi < 0.0f {
        return i_empty();
    }
    var lo = 0.0f;
    if a.lo > 0.0f {
        lo = finish(sqrt_bound_unchecked(a.lo, false), false);
    }
    return Interval(lo, sqrt_bound_unchecked(a.hi, true));
}

// sqrt of a bound. WGSL inherits sqrt's accuracy from 1.0 / inverseSqrt(x) (inverseSqrt:
// 2 ULP; the division: 2.5 ULP): a relative error below 4.5 * 2^-23, at most 9 ULPs of the
// rounded result; step 10.
fn sqrt_bound_unchecked(x: f32, up: bool) -> f32 {
    if x >= BIG {
        return BIG;
    }
    if x < TINY {
        // sqrt of [0, TINY) lies in [0, 2^-63).
        return select(0.0f, 0x1p-63f, up);
    }
    let r = raw_sqrt(x);
    return select(step_down(r, 10u), step_up(r, 10u), up);
}

// a^n for an integer n by repeated outward multiplication (exact ops: min, max).
fn i_pown(a: Interval, n: i32) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    if n == 0 {
        return Interval(1.0f, 1.0f);
    }
    // |n| as u32 (exact for i32::MIN too, where abs(n) would stay negative).
    var k: u32 = select(bitcast<u32>(n), 0u - bitcast<u32>(n), n < 0);
    // Even powers of an interval straddling 0 start from |a|.
    var base = a;
    if k % 2u == 0u {
        base = i_abs(a);
    }
    var r = Interval(1.0f, 1.0f);
    var b = base;
    loop {
        if (k & 1u) == 1u {
            r = i_mul(r, b);
        }
        k = k >> 1u;
        if k == 0u {
            break;
        }
        b = i_sqr(b);
    }
    if n < 0 {
        return i_recip(r);
    }
    return r;
}

fn i_floor(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(floor(a.lo), floor(a.hi));
}

fn i_ceil(a: Interval) -> Interval {
    if i_is_empty(a) {
        return i_empty();
    }
    return Interval(ceil(a.lo), ceil(a.hi));
}

// --- input from bits ---------------------------------------------------------------------

// A bound from its bit pattern, widened outward (`up`: an upper bound) so that the result
// is zero, normal or +-BIG: infinities become +-BIG, NaN the infinite end, subnormals 0 or
// +-TINY. Integer operations only, so a GPU that flushes subnormals reads the bits as they
// are.
fn bound_from_bits(u: u32, up: bool) -> f32 {
    let mag = u & 0x7fffffffu;
    let neg = (u >> 31u) == 1u;
    if mag > 0x7f800000u {
        return select(-BIG, BIG, up);
    }
    if mag > 0x7f7fffffu {
        // An infinity: +-BIG.
        return select(BIG, -BIG, neg);
    }
    if mag == 0x7f7fffffu {
        // The finite value +-BIG: infinity on its own side, the finite BELOW_BIG on the
        // other (as a lower bound, +BIG would mean +inf and drop the value).
        if neg {
            return select(-BIG, -BELOW_BIG, up);
        }
        return select(BELOW_BIG, BIG, up);
    }
    if mag == 0u {
        return 0.0f;
    }
    if mag < 0x00800000u {
        if neg {
            return select(-TINY, 0.0f, up);
        }
        return select(0.0f, TINY, up);
    }
    return bitcast<f32>(u);
}

// The interval [lo, hi] from the bit patterns of its bounds (empty when lo > hi, or when
// lo is +inf or hi is -inf: no real lies there).
fn i_from_bits(lo: u32, hi: u32) -> Interval {
    if lo == 0x7f800000u || hi == 0xff800000u {
        return i_empty();
    }
    return Interval(bound_from_bits(lo, false), bound_from_bits(hi, true));
}
