#shader check_gbuffer
// Compute kernels over deferred/gbuffer for the GPU check (src/gpu/check/kernels.rs).
//   group 0: 0 input array<vec4f>, 1 output array<vec4f> (check/io)

#pass EncodeNormal
// in: n.xyz -> out: gbuffer_encode_normal(n)
#import check/io
#import deferred/gbuffer

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(1u) {
        return;
    }
    output[i] = vec4f(gbuffer_encode_normal(input[i].xyz), 0.0);
}
#endpass

#pass DecodeNormal
// in: rgb -> out: gbuffer_decode_normal(rgb)
#import check/io
#import deferred/gbuffer

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(1u) {
        return;
    }
    output[i] = vec4f(gbuffer_decode_normal(input[i].xyz), 0.0);
}
#endpass

#pass Pack
// in: (diffuse, occlusion), (specular, smoothness), normal, c
// out: rt0, rt1, rt2, rt3, then pack4x8unorm(rt0) and pack4x8unorm(rt1) as 16-bit halves
//      (lo0, hi0, lo1, hi1), exact in f32.
#pragma multi_compile _ UNITY_HDR_ON
#import check/io
#import deferred/gbuffer

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(4u) {
        return;
    }
    let a = input[4u * i];
    let b = input[4u * i + 1u];
    let g = gbuffer_pack(a.xyz, a.w, b.xyz, b.w, input[4u * i + 2u].xyz, input[4u * i + 3u].xyz);
    output[5u * i] = g.rt0;
    output[5u * i + 1u] = g.rt1;
    output[5u * i + 2u] = g.rt2;
    output[5u * i + 3u] = g.rt3;
    let p0 = pack4x8unorm(g.rt0);
    let p1 = pack4x8unorm(g.rt1);
    output[5u * i + 4u] = vec4f(f32(p0 & 0xffffu), f32(p0 >> 16u), f32(p1 & 0xffffu), f32(p1 >> 16u));
}
#endpass
