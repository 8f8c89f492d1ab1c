#shader padding
// The passes of tests/gpu_bindings.rs, for the Rust `wgsl_variants::bindings` generates:
// RoundTrip has every padding rule of WGSL's host-shareable layout (the host writes `Data`
// through the generated Rust, and the kernel writes every scalar it reads, bit-cast to u32, in
// declaration order); Draw builds a render pipeline from the generated wgpu layouts.

#pass RoundTrip
//   group 0: 0 data (read), 1 output array<u32> (read_write)
#pragma multi_compile _ WIDE

// Size 16, aligned to 8: 4 bytes of trailing padding.
struct Inner {
    a: vec2<f32>,
    b: f32,
}

struct Params {
    // A vec3 then an f32: the f32 sits at 12.
    v: vec3<f32>,
    s: f32,
    // An array of vec3: a stride of 16.
    arr: array<vec3<f32>, 3>,
    // A nested struct.
    inner: Inner,
    // Columns 16 bytes apart.
    m: mat3x3<f32>,
    // An array of structs with trailing padding.
    items: array<Inner, 2>,
    // An integer vec3 then an i32, then padding up to the struct's alignment.
    u: vec3<u32>,
    i: i32,
    k: u32,
#if WIDE
    // A layout that exists only in some variants (`Params2`).
    w: vec4<f32>,
#endif
}

// A runtime-sized array of vec3 after a nested struct and a u32.
struct Data {
    params: Params,
    count: u32,
    lights: array<vec3<f32>>,
}

@group(0) @binding(0) var<storage, read> data: Data;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;

var<private> cursor: u32;

fn put(x: u32) {
    output[cursor] = x;
    cursor += 1u;
}

fn put_f(x: f32) {
    put(bitcast<u32>(x));
}

fn put_v2(v: vec2<f32>) {
    put_f(v.x);
    put_f(v.y);
}

fn put_v3(v: vec3<f32>) {
    put_f(v.x);
    put_f(v.y);
    put_f(v.z);
}

fn put_inner(x: Inner) {
    put_v2(x.a);
    put_f(x.b);
}

@compute @workgroup_size(1)
fn main() {
    put_v3(data.params.v);
    put_f(data.params.s);
    for (var i = 0u; i < 3u; i += 1u) {
        put_v3(data.params.arr[i]);
    }
    put_inner(data.params.inner);
    for (var c = 0u; c < 3u; c += 1u) {
        put_v3(data.params.m[c]);
    }
    for (var i = 0u; i < 2u; i += 1u) {
        put_inner(data.params.items[i]);
    }
    put(data.params.u.x);
    put(data.params.u.y);
    put(data.params.u.z);
    put(bitcast<u32>(data.params.i));
    put(data.params.k);
#if WIDE
    put_v2(data.params.w.xy);
    put_v2(data.params.w.zw);
#endif
    put(data.count);
    let n = arrayLength(&data.lights);
    put(n);
    for (var i = 0u; i < n; i += 1u) {
        put_v3(data.lights[i]);
    }
}
#endpass

#pass Draw
// A render pass for the wgpu types of generated bindings: bind groups with a uniform, a
// texture and a sampler, vertex inputs of three formats, colour targets of two component types
// with a hole at location 1.
struct Tint {
    color: vec3<f32>,
    scale: f32,
}

@group(0) @binding(0) var<uniform> tint: Tint;
@group(1) @binding(0) var tex: texture_2d<f32>;
@group(1) @binding(1) var samp: sampler;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
    @location(1) @interpolate(flat) id: u32,
}

@vertex
fn vs(@location(0) position: vec3<f32>, @location(1) uv: vec2<f32>, @location(2) id: u32) -> VertexOut {
    return VertexOut(vec4<f32>(position * tint.scale, 1.0), uv, id);
}

struct FragmentOut {
    @location(0) color: vec4<f32>,
    @location(2) id: vec4<u32>,
}

@fragment
fn fs(in: VertexOut) -> FragmentOut {
    let c = textureSample(tex, samp, in.uv).rgb * tint.color;
    return FragmentOut(vec4<f32>(c, 1.0), vec4<u32>(in.id));
}
#endpass
