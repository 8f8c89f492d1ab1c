#shader deferred_shading
// Unity's Internal-DeferredShading lighting pass (docs/shading.md §10): one draw per light adds
// its direct light to RT3, read from the G-buffer and the depth buffer.
//   group 0: 0 rt0, 1 rt1, 2 rt2 (the G-buffer, read with textureLoad),
//            3 depth (the depth buffer's depth aspect, or an R32Float copy, read with textureLoad),
//            4 camera (DeferredCamera), 5 rt4 (the baked occlusion, SHADOWS_SHADOWMASK),
//            6-15 the light and its shadow (lighting/light_bindings),
//            16 occlusion_mask_selector (vec4f: the light's RT4 channel, one-hot;
//               SHADOWS_SHADOWMASK; Unity's unity_OcclusionMaskSelector),
//            17 brdf_lut (UNITY_PBS_USE_BRDF3; lighting/brdf_lut),
//            18 shadow_fade (ShadowFade; with a realtime shadow keyword; lighting/shadow_fade)
// The host blends DstColor / Zero onto the Rgb10a2Unorm exp2(-c) RT3 (LDR: src = exp2(-light),
// a = 1) or One / One onto the Rgba16Float RT3 (UNITY_HDR_ON: src = light, a = 0); both leave
// RT3's alpha of 1 as it is. The result at a pixel does not depend on how the light was drawn
// (docs/shading.md §10, "Light volumes"); two vertex entry points share the one fragment stage:
//   vs_main    a full-screen triangle (3 vertices, no vertex buffer): directional lights and
//              volumes crossing the near or far plane;
//   vs_volume  the light's volume (icosphere / pyramid), world positions at @location(0),
//              drawn with Cull Front, depth test GreaterEqual and stencil NotEqual 1 after
//              internal/stencil_write marked the pixels whose geometry lies in front of it.
// An entry point, not a keyword: the fragment code is the same, so a keyword would double the
// variants for a pipeline setting like the blend state.

#pass Lighting
#pragma multi_compile POINT DIRECTIONAL SPOT POINT_COOKIE DIRECTIONAL_COOKIE
// Shadows as Unity pairs them with the light types (lighting/light_bindings): a 2D map for
// spots, a cube for points, SHADOWS_SOFT for either (with no shadow keyword it changes nothing:
// those 6 variants are duplicates, as in Unity), the screen-space mask for directional lights
// (SHADOWS_SCREEN; its SHADOWS_SOFT is the mask pass's).
#pragma multi_compile _ SHADOWS_DEPTH SHADOWS_CUBE SHADOWS_SCREEN
#pragma multi_compile _ SHADOWS_SOFT
#pragma exclude SHADOWS_SCREEN POINT
#pragma exclude SHADOWS_SCREEN POINT_COOKIE
#pragma exclude SHADOWS_SCREEN SPOT
#pragma exclude SHADOWS_DEPTH POINT
#pragma exclude SHADOWS_DEPTH POINT_COOKIE
#pragma exclude SHADOWS_DEPTH DIRECTIONAL
#pragma exclude SHADOWS_DEPTH DIRECTIONAL_COOKIE
#pragma exclude SHADOWS_CUBE SPOT
#pragma exclude SHADOWS_CUBE DIRECTIONAL
#pragma exclude SHADOWS_CUBE DIRECTIONAL_COOKIE
#pragma exclude SHADOWS_SOFT DIRECTIONAL
#pragma exclude SHADOWS_SOFT DIRECTIONAL_COOKIE
// The Shadowmask lighting modes (the rest of multi_compile_lightpass): SHADOWS_SHADOWMASK reads
// the light's baked occlusion from RT4; LIGHTMAP_SHADOW_MIXING (the Shadowmask mode, without
// it Distance Shadowmask) decides how it mixes with a realtime shadow (light_mix_shadows).
// Without SHADOWS_SHADOWMASK, LIGHTMAP_SHADOW_MIXING changes nothing, as in Unity. 128
// variants per tier, 84 distinct: LIGHTMAP_SHADOW_MIXING leaves the text alone without a
// realtime shadow keyword.
#pragma multi_compile _ SHADOWS_SHADOWMASK
#pragma multi_compile _ LIGHTMAP_SHADOW_MIXING
#pragma multi_compile _ UNITY_HDR_ON
// The Standard BRDF's tier (docs/shading.md §5; UNITY_PBS_USE_BRDF3 binds the lookup table at
// group 0 binding 17, lighting/brdf_lut).
#pragma multi_compile _ UNITY_PBS_USE_BRDF2 UNITY_PBS_USE_BRDF3
#import internal/fullscreen
#import deferred/gbuffer
#import deferred/ldr
#import deferred/depth
#import lighting/light_bindings

@group(0) @binding(0) var rt0: texture_2d<f32>;
@group(0) @binding(1) var rt1: texture_2d<f32>;
@group(0) @binding(2) var rt2: texture_2d<f32>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;
#if defined(SHADOWS_SHADOWMASK)
@group(0) @binding(5) var rt4: texture_2d<f32>;
@group(0) @binding(16) var<uniform> occlusion_mask_selector: vec4f;
#endif

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@vertex
fn vs_volume(@location(0) world_position: vec3f) -> @builtin(position) vec4f {
    return deferred_camera.view_proj * vec4f(world_position, 1.0);
}

// The light: the Standard BRDF's direct term with diffuse = RT0.rgb, spec colour = RT1.rgb,
// smoothness = RT1.a, n = decode(RT2.rgb), at the position rebuilt from depth. (The BRDF's
// 1 - max(spec.rgb) only weighs indirect terms, which this pass leaves out; occlusion RT0.a
// only darkens indirect light, as in Unity.)
@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
    let gbuffer0 = textureLoad(rt0, pixel, 0);
    let gbuffer1 = textureLoad(rt1, pixel, 0);
    let gbuffer2 = textureLoad(rt2, pixel, 0);
    let p = depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel);

    let n = gbuffer_decode_normal(gbuffer2.rgb);
    let v = brdf_view_dir(deferred_camera.position.xyz, p);
#if defined(SHADOWS_SHADOWMASK)
    // Unity's UnityDeferredSampleShadowMask: the light's channel of RT4.
    let baked = saturate(dot(textureLoad(rt4, pixel, 0), occlusion_mask_selector));
#else
    let baked = 1.0;
#endif
    let s = light_at_pixel(p, pixel, baked);
    let c = light_direct(gbuffer0.rgb, gbuffer1.rgb, gbuffer1.a, n, v, light, s);
#if UNITY_HDR_ON
    // One / One: RT3 += c (alpha 0 leaves RT3's a = 1).
    return vec4f(c, 0.0);
#else
    // DstColor / Zero: RT3 · exp2(-c), so the light adds in the exponent (alpha 1 keeps a = 1).
    return vec4f(ldr_encode(c), 1.0);
#endif
}
#endpass
