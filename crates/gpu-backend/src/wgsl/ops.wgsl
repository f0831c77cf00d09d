// Runs one interval library function on many inputs (the library and `run_op`, the switch
// over the operations that gpu-backend writes from implicit-expr's list, are pasted before
// this).
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
    let r = run_op(params.op, a, b, bitcast<i32>(v.z));
    outputs[i] = vec2<f32>(r.lo, r.hi);
}
