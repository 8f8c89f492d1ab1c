// deferred/gbuffer: the built-in deferred path's G-buffer layout (docs/shading.md §1, §2, §7).
//
//   RT0 Rgba8Unorm    diffuse colour rgb, occlusion a
//   RT1 Rgba8Unorm    specular colour rgb, smoothness a
//   RT2 Rgb10a2Unorm  world normal · 0.5 + 0.5, a = 1
//   RT3 Rgb10a2Unorm  exp2(-c) (LDR), or Rgba16Float c with UNITY_HDR_ON; a = 1
//   RT4 Rgba8Unorm    baked occlusion of up to four lights, one per channel (SHADOWS_SHADOWMASK
//                     only: the Shadowmask lighting modes; the writer fills it, gbuffer_pack
//                     does not)
//
// Provides (no bindings):
//   struct GBufferOutput { rt0, rt1, rt2, rt3: vec4f at @location(0..3);
//                          rt4 at @location(4) with SHADOWS_SHADOWMASK }
//   fn gbuffer_encode_normal(n: vec3f) -> vec3f   normalize(n) · 0.5 + 0.5; zero or non-finite -> (0.5, 0.5, 1)
//   fn gbuffer_decode_normal(rgb: vec3f) -> vec3f normalize(rgb · 2 - 1)
//   fn gbuffer_pack(diffuse: vec3f, occlusion: f32, specular: vec3f, smoothness: f32,
//                   normal: vec3f, c: vec3f) -> GBufferOutput
//       RT3 = c under UNITY_HDR_ON, else ldr_encode(c).

#import deferred/ldr

struct GBufferOutput {
    @location(0) rt0: vec4f,
    @location(1) rt1: vec4f,
    @location(2) rt2: vec4f,
    @location(3) rt3: vec4f,
#if defined(SHADOWS_SHADOWMASK)
    @location(4) rt4: vec4f,
#endif
}

// normalize(n) · 0.5 + 0.5. The normal is first scaled by the power of two that brings its
// largest |component| into [0.5, 1), so that tiny and huge normals (whose squared length under-
// or overflows f32) normalize like any other. ldexp is exact; dividing by the largest component
// is not safe: GPUs divide through the reciprocal, a denormal for a huge divisor, which may be
// flushed to zero (NVIDIA's driver does) and leave a zero vector to normalize. A zero normal,
// and one with an infinite or NaN component, encodes as (0, 0, 1) -> (0.5, 0.5, 1). Integer
// tests on the bits: comparisons with NaN may be folded by compilers.
fn gbuffer_encode_normal(n: vec3f) -> vec3f {
    let magnitude = bitcast<vec3u>(n) & vec3u(0x7fffffffu);
    let finite = all(magnitude < vec3u(0x7f800000u));
    // For finite values the bit patterns order like the magnitudes.
    let largest = bitcast<f32>(max(max(magnitude.x, magnitude.y), magnitude.z));
    if !finite || largest == 0.0 {
        return vec3f(0.5, 0.5, 1.0);
    }
    return normalize(ldexp(n, vec3i(-frexp(largest).exp))) * 0.5 + 0.5;
}

// normalize(rgb · 2 - 1), as stored in RT2.
fn gbuffer_decode_normal(rgb: vec3f) -> vec3f {
    return normalize(rgb * 2.0 - 1.0);
}

// The four G-buffer targets of the Deferred pass: c is emission + ambient (+ reflections).
fn gbuffer_pack(
    diffuse: vec3f,
    occlusion: f32,
    specular: vec3f,
    smoothness: f32,
    normal: vec3f,
    c: vec3f,
) -> GBufferOutput {
    var out: GBufferOutput;
    out.rt0 = vec4f(diffuse, occlusion);
    out.rt1 = vec4f(specular, smoothness);
    out.rt2 = vec4f(gbuffer_encode_normal(normal), 1.0);
#if UNITY_HDR_ON
    out.rt3 = vec4f(c, 1.0);
#else
    out.rt3 = vec4f(ldr_encode(c), 1.0);
#endif
    return out;
}
