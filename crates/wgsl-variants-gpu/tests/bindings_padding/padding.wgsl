#shader padding
// Every padding rule of WGSL's host-shareable layout, for the GPU round trip of the structs
// `wgsl_variants::bindings` generates (tests/gpu_bindings.rs): the host writes `Data` through
// the generated Rust, and this kernel writes every scalar it reads, bit-cast to u32, in
// declaration order.
//   group 0: 0 data (read), 1 output array<u32> (read_write)

#pass RoundTrip
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
