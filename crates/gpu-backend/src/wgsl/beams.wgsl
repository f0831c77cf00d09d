// Beams (primary beams through pixels or screen boxes, rays, shadow segments, shadow beams
// over a light and its sub-beams: every set of rays `origin + t · dir` with the origin and
// the direction in boxes), each searched over its parameter range with the counter-based
// non-recursive bisection (levels `ns`, section `k`, as the CPU's `counter-bisection`), the
// rejection test on every section, and the inclusion test (a sign change of g at the two
// ends of a section for every ray, with g continuous and the ends inside the scene bounds,
// with the CPU's look-ahead) when the surface is total and continuous and the caller asks.
// The library and the generated function `surface` are pasted before this.

struct Scene {
    bounds_lo: vec4<f32>,
    bounds_hi: vec4<f32>,
    // epsilon (width of a final section, absolute), relative epsilon (of t), unused x2
    tol: vec4<f32>,
    // count, max_steps, inclusion (0/1), inclusion on final sections only (0/1)
    ints: vec4<u32>,
}

// A beam: origin lo/hi, direction lo/hi (x, y, z each) and the parameter range t0, t1, as
// f32 bit patterns (t1 < t0: nothing to search); two unused words.
@group(0) @binding(0) var<uniform> scene: Scene;
@group(0) @binding(1) var<storage, read> beams: array<array<u32, 16>>;
// class (0 miss, 1 hit, 2 undecided, 3 out of steps), t.lo, t.hi (bits), steps.
@group(0) @binding(2) var<storage, read_write> results: array<vec4<u32>>;

// Deepest level of the bisection: 2^22 sections.
const MAX_LEVEL: u32 = 22u;

struct Beam {
    e: array<Interval, 3>,
    d: array<Interval, 3>,
}

fn pt(x: f32) -> Interval {
    return Interval(x, x);
}

fn beam_points(b: Beam, t: Interval) -> array<Interval, 3> {
    return array<Interval, 3>(
        i_add(b.e[0], i_mul(t, b.d[0])),
        i_add(b.e[1], i_mul(t, b.d[1])),
        i_add(b.e[2], i_mul(t, b.d[2])),
    );
}

fn g(b: Beam, t: Interval) -> Interval {
    let p = beam_points(b, t);
    return surface(p[0], p[1], p[2]);
}

fn may_vanish(v: Interval) -> bool {
    return !i_is_empty(v) && v.lo <= 0.0f && v.hi >= 0.0f;
}

// Whether every ray of the beam is inside the scene bounds at the parameter t.
fn inside(b: Beam, t: f32) -> bool {
    let p = beam_points(b, pt(t));
    let lo = vec3<f32>(p[0].lo, p[1].lo, p[2].lo);
    let hi = vec3<f32>(p[0].hi, p[1].hi, p[2].hi);
    return all(lo >= scene.bounds_lo.xyz) && all(hi <= scene.bounds_hi.xyz);
}

// The end k of the sections of level ns of [lo, hi], rounded down (up = false) or up.
fn section_end(lo: f32, hi: f32, k: u32, ns: u32, up: bool) -> f32 {
    let j = k << (MAX_LEVEL - ns);
    if j == 0u {
        return lo;
    }
    if j >= (1u << MAX_LEVEL) {
        return hi;
    }
    let step = i_mul(i_sub(pt(hi), pt(lo)), pt(0x1p-22f));
    let e = i_add(pt(lo), i_mul(pt(f32(j)), step));
    return clamp(select(e.lo, e.hi, up), lo, hi);
}

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= scene.ints.x {
        return;
    }
    let r = beams[i];
    let t0 = bitcast<f32>(r[12]);
    let t1 = bitcast<f32>(r[13]);
    var out = vec4<u32>(0u, 0u, 0u, 0u);
    if t1 < t0 {
        results[i] = out;
        return;
    }
    var b: Beam;
    for (var a = 0; a < 3; a++) {
        b.e[a] = i_from_bits(r[2 * a], r[2 * a + 1]);
        b.d[a] = i_from_bits(r[6 + 2 * a], r[6 + 2 * a + 1]);
    }
    let eps = scene.tol.x;
    let max_steps = scene.ints.y;
    let inclusion = scene.ints.z == 1u;
    // A ray's search for its shading point: a proof on a wide section would not say where
    // the first root is inside it, so only final sections (and their look-ahead) count.
    let final_only = scene.ints.w == 1u;
    var ns = 0u;
    var k = 0u;
    var steps = 0u;
    loop {
        let lo = section_end(t0, t1, k, ns, false);
        let hi = section_end(t0, t1, k + 1u, ns, true);
        let t = Interval(lo, hi);
        steps += 1u;
        if may_vanish(g(b, t)) {
            let last = ns == MAX_LEVEL || hi - lo <= max(eps, scene.tol.y * lo);
            if inclusion && (last || !final_only) && inside(b, lo) && inside(b, hi) {
                let ga = g(b, pt(lo));
                let gb = g(b, pt(hi));
                if !i_is_empty(ga) && !i_is_empty(gb)
                    && max(ga.lo, gb.lo) >= 0.0f && min(ga.hi, gb.hi) <= 0.0f {
                    out = vec4<u32>(1u, bitcast<u32>(lo), bitcast<u32>(hi), steps);
                    break;
                }
            }
            if last {
                out = vec4<u32>(2u, bitcast<u32>(lo), bitcast<u32>(hi), steps);
                // Look-ahead (as the CPU's beams): every ray is root-free before `lo`, so a
                // sign change of g between `lo` and a point `b` a few widths further, with g
                // continuous, puts every ray's first root in [lo, b].
                if inclusion && inside(b, lo) {
                    let ga = g(b, pt(lo));
                    var w = hi - lo;
                    for (var j = 0; j < 8; j++) {
                        w = w * 2.0f;
                        let end = min(lo + w, t1);
                        let far = select(min(step_up(end, 1u), t1), end, end >= t1);
                        if !inside(b, far) {
                            break;
                        }
                        let gb = g(b, pt(far));
                        if !i_is_empty(ga) && !i_is_empty(gb)
                            && max(ga.lo, gb.lo) >= 0.0f && min(ga.hi, gb.hi) <= 0.0f {
                            out = vec4<u32>(1u, bitcast<u32>(lo), bitcast<u32>(far), steps);
                            break;
                        }
                        if end >= t1 {
                            break;
                        }
                    }
                }
                break;
            }
            if steps >= max_steps {
                out = vec4<u32>(3u, bitcast<u32>(lo), bitcast<u32>(t1), steps);
                break;
            }
            ns += 1u;
            k *= 2u;
        } else {
            if (k & 1u) == 0u {
                k += 1u;
            } else {
                ns -= 1u;
                k = (k + 1u) / 2u;
            }
            if k >= (1u << ns) {
                out = vec4<u32>(0u, 0u, 0u, steps);
                break;
            }
        }
    }
    results[i] = out;
}
