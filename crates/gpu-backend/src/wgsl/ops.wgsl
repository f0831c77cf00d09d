// Runs one interval library function on many inputs (the library is pasted before this).
// Input i is four f32 bit patterns: a.lo, a.hi, b.lo, b.hi (for i_pown, b.lo holds the
// exponent as an i32). Bounds are sanitized from their bits first (the library's input
// contract: no NaN, no infinity, no subnormal).

struct Params {
    op: u32,
    count: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> inputs: array<vec4<u32>>;
@group(0) @binding(2) var<storage, read_write> outputs: array<vec2<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    let v = inputs[i];
    let a = i_from_bits(v.x, v.y);
    let b = i_from_bits(v.z, v.w);
    var r = i_entire();
    switch params.op {
        case 0u: { r = i_add(a, b); }
        case 1u: { r = i_sub(a, b); }
        case 2u: { r = i_mul(a, b); }
        case 3u: { r = i_div(a, b); }
        case 4u: { r = i_min(a, b); }
        case 5u: { r = i_max(a, b); }
        case 6u: { r = i_pown(a, bitcast<i32>(v.z)); }
        case 7u: { r = i_neg(a); }
        case 8u: { r = i_abs(a); }
        case 9u: { r = i_sqr(a); }
        case 10u: { r = i_sqrt(a); }
        case 11u: { r = i_recip(a); }
        case 12u: { r = i_floor(a); }
        case 13u: { r = i_ceil(a); }
        case 14u: { r = i_exp(a); }
        case 15u: { r = i_ln(a); }
        case 16u: { r = i_log10(a); }
        case 17u: { r = i_sin(a); }
        case 18u: { r = i_cos(a); }
        case 19u: { r = i_tan(a); }
        case 20u: { r = i_asin(a); }
        case 21u: { r = i_acos(a); }
        case 22u: { r = i_atan(a); }
        case 23u: { r = i_pow(a, b); }
        case 24u: { r = i_round(a); }
        case 25u: { r = i_not(a); }
        case 26u: { r = i_slope_floor(a); }
        case 27u: { r = i_slope_round(a); }
        case 28u: { r = i_slope_not(a); }
        default: {}
    }
    outputs[i] = vec2<f32>(r.lo, r.hi);
}
