// universal/gbuffer: URP's G-buffer layout (docs/urp.md §1-§4; URP's UnityGBuffer.hlsl).
//
//   0 GBuffer0 Rgba8UnormSrgb   base albedo (linear; the target encodes sRGB), a = flags / 255
//   1 GBuffer1 Rgba8Unorm       specular colour, or (reflectivity, 0, 0); a = occlusion
//   2 GBuffer2 Rgba8Unorm       octahedral normal 8:8:8 (_GBUFFER_NORMALS_OCT), else
//              Rgba8Snorm       the normal as is; a = smoothness
//   3 GBuffer3 Rg11b10Ufloat    emission + GI
//   next: R32Float depth as colour (_RENDER_PASS_ENABLED), R32Uint rendering layers
//         (_WRITE_RENDERING_LAYERS), Rgba8Unorm shadowmask (URP's OUTPUT_SHADOWMASK:
//         SHADOWS_SHADOWMASK, or _MIXED_LIGHTING_SUBTRACTIVE without LIGHTMAP_ON)
//
// Provides (no bindings):
//   const URP_FLAG_RECEIVE_SHADOWS_OFF / _SPECULAR_HIGHLIGHTS_OFF / _SUBTRACTIVE_MIXED_LIGHTING
//         / _SPECULAR_SETUP: the material-flags bits 0-3
//   struct UrpGBufferOutput
//   fn urp_oct_encode(n: vec3f) -> vec2f           PackNormalOctQuadEncode, in [-1, 1]^2
//   fn urp_pack_float2_to_888(f: vec2f) -> vec3f   two 12-bit codes as three bytes / 255
//   fn urp_pack_normal(n: vec3f) -> vec3f          GBuffer2.rgb
//   fn urp_pack_flags(flags: u32) -> f32           flags / 255
//   fn urp_unpack_normal(rgb: vec3f) -> vec3f      GBuffer2.rgb back to a unit normal
//   fn urp_unpack_flags(a: f32) -> u32             GBuffer0.a back to the flags byte

const URP_FLAG_RECEIVE_SHADOWS_OFF: u32 = 1u;
const URP_FLAG_SPECULAR_HIGHLIGHTS_OFF: u32 = 2u;
const URP_FLAG_SUBTRACTIVE_MIXED_LIGHTING: u32 = 4u;
const URP_FLAG_SPECULAR_SETUP: u32 = 8u;

// Optional targets take the next free locations, in this order.
struct UrpGBufferOutput {
    @location(0) gbuffer0: vec4f,
    @location(1) gbuffer1: vec4f,
    @location(2) gbuffer2: vec4f,
    @location(3) gbuffer3: vec4f,
#if defined(_RENDER_PASS_ENABLED)
    @location(4) depth_as_color: f32,
#endif
#if defined(_WRITE_RENDERING_LAYERS) && defined(_RENDER_PASS_ENABLED)
    @location(5) rendering_layers: u32,
#elif defined(_WRITE_RENDERING_LAYERS)
    @location(4) rendering_layers: u32,
#endif
#if (defined(SHADOWS_SHADOWMASK) || (defined(_MIXED_LIGHTING_SUBTRACTIVE) && !defined(LIGHTMAP_ON))) && defined(_RENDER_PASS_ENABLED) && defined(_WRITE_RENDERING_LAYERS)
    @location(6) shadow_mask: vec4f,
#elif (defined(SHADOWS_SHADOWMASK) || (defined(_MIXED_LIGHTING_SUBTRACTIVE) && !defined(LIGHTMAP_ON))) && (defined(_RENDER_PASS_ENABLED) || defined(_WRITE_RENDERING_LAYERS))
    @location(5) shadow_mask: vec4f,
#elif (defined(SHADOWS_SHADOWMASK) || (defined(_MIXED_LIGHTING_SUBTRACTIVE) && !defined(LIGHTMAP_ON)))
    @location(4) shadow_mask: vec4f,
#endif
}

// n / (|x| + |y| + |z|) (floored at 1e-6); the lower hemisphere folded out:
// xy += (xy >= 0 ? t : -t) with t = saturate(-z).
fn urp_oct_encode(n: vec3f) -> vec2f {
    let p = n / max(dot(abs(n), vec3f(1.0)), 1e-6);
    let t = saturate(-p.z);
    return p.xy + select(vec2f(-t), vec2f(t), p.xy >= vec2f(0.0));
}

// i = trunc(f · 4095.5); bytes (i.x & 255, i.y & 255, (i.x >> 8) | (i.y >> 8) << 4), / 255.
fn urp_pack_float2_to_888(f: vec2f) -> vec3f {
    let i = vec2u(f * 4095.5);
    let hi = i >> vec2u(8u);
    let lo = i & vec2u(255u);
    return vec3f(vec3u(lo, hi.x | (hi.y << 4u))) / 255.0;
}

fn urp_pack_normal(n: vec3f) -> vec3f {
#if defined(_GBUFFER_NORMALS_OCT)
    let remapped = saturate(urp_oct_encode(n) * 0.5 + 0.5);
    return urp_pack_float2_to_888(remapped);
#else
    return n;
#endif
}

fn urp_pack_flags(flags: u32) -> f32 {
    return f32(flags) / 255.0;
}

// --- Reading the G-buffer back (the StencilDeferred lighting passes) ---

// The 12-bit codes of three bytes / 255, each code / 4095 (Unpack888ToFloat2).
fn urp_unpack_888_to_float2(f: vec3f) -> vec2f {
    let b = vec3u(round(f * 255.0));
    let x = b.x | ((b.z & 15u) << 8u);
    let y = b.y | ((b.z >> 4u) << 8u);
    return vec2f(f32(x), f32(y)) / 4095.0;
}

// UnpackNormalOctQuadEncode: (f, 1 - |f.x| - |f.y|), the lower hemisphere unfolded, normalized.
fn urp_oct_decode(f: vec2f) -> vec3f {
    var n = vec3f(f, 1.0 - abs(f.x) - abs(f.y));
    let t = max(-n.z, 0.0);
    n.x += select(t, -t, n.x >= 0.0);
    n.y += select(t, -t, n.y >= 0.0);
    return normalize(n);
}

// The unit world normal of GBuffer2.rgb.
fn urp_unpack_normal(rgb: vec3f) -> vec3f {
#if defined(_GBUFFER_NORMALS_OCT)
    return urp_oct_decode(urp_unpack_888_to_float2(rgb) * 2.0 - 1.0);
#else
    return normalize(rgb);
#endif
}

// The flags byte of GBuffer0.a: floor(a * 255 + 0.5) (UnpackMaterialFlags).
fn urp_unpack_flags(a: f32) -> u32 {
    return u32(floor(a * 255.0 + 0.5));
}
