// Evaluates the surface's interval function on many boxes (the library and the generated
// function `surface` are pasted before this). Box i is six f32 bit patterns: x.lo, x.hi,
// y.lo, y.hi, z.lo, z.hi.

struct Params {
    count: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> boxes: array<array<u32, 6>>;
@group(0) @binding(2) var<storage, read_write> outputs: array<vec2<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= params.count {
        return;
    }
    let b = boxes[i];
    let r = surface(i_from_bits(b[0], b[1]), i_from_bits(b[2], b[3]), i_from_bits(b[4], b[5]));
    outputs[i] = vec2<f32>(r.lo, r.hi);
}
