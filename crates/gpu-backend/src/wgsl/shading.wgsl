// Phong shading of many samples (thesis eq. 2.6, as beam-trace's `phong`):
// c = c_r (c_a + sum c_l max(0, n.l)) + sum k_s c_l max(0, e.r)^p, r = 2 (l.n) n - l, with
// n turned to face the eye, and each light's colour times its visible fraction.

const MAX_LIGHTS: u32 = 8u;

struct Lights {
    // position (xyz) of each light (an area light's centre)
    position: array<vec4<f32>, 8>,
    // colour times intensity (rgb)
    color: array<vec4<f32>, 8>,
    // count, number of samples, unused x2
    ints: vec4<u32>,
    // ambient, unused x3
    ambient: vec4<f32>,
}

// A sample: point (3), normal (3), to_eye (3), material colour (3), specular, shininess,
// then the visible fraction of each of the lights (8).
struct ShadingSample {
    point: vec4<f32>,
    normal: vec4<f32>,
    to_eye: vec4<f32>,
    // colour rgb, specular
    material: vec4<f32>,
    // shininess, unused x3
    shininess: vec4<f32>,
    fraction: array<vec4<f32>, 2>,
}

@group(0) @binding(0) var<uniform> lights: Lights;
@group(0) @binding(1) var<storage, read> samples: array<ShadingSample>;
@group(0) @binding(2) var<storage, read_write> colors: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i >= lights.ints.y {
        return;
    }
    let s = samples[i];
    var n = s.normal.xyz;
    let e = s.to_eye.xyz;
    if dot(n, e) < 0.0 {
        n = -n;
    }
    var diffuse = vec3<f32>(lights.ambient.x);
    var highlight = vec3<f32>(0.0);
    for (var k = 0u; k < min(lights.ints.x, MAX_LIGHTS); k++) {
        let to_light = lights.position[k].xyz - s.point.xyz;
        let len = length(to_light);
        if len == 0.0 {
            continue;
        }
        let l = to_light / len;
        let nl = dot(n, l);
        if nl <= 0.0 {
            continue;
        }
        let c = lights.color[k].rgb * s.fraction[k / 4u][k % 4u];
        let r = 2.0 * nl * n - l;
        let spec = pow(max(dot(e, r), 0.0), s.shininess.x) * s.material.w;
        diffuse += c * nl;
        highlight += c * spec;
    }
    colors[i] = vec4<f32>(s.material.rgb * diffuse + highlight, 1.0);
}
