#shader deferred_reflections
// Unity's Internal-DeferredReflections for UNITY_ENABLE_REFLECTION_BUFFERS (docs/shading.md §6, §7).
//
// Reflections: one draw per probe (the host orders them: larger box volume first, higher
//   importance later), into an Rgba16Float reflection buffer cleared to 0 with
//   SrcAlpha / OneMinusSrcAlpha blending: result = mix(previous, rgb, falloff). Drawn as
//   vs_box over the probe's grown box (world positions at @location(0), Cull Front, depth test
//   GreaterEqual), or full screen (vs_main) when the box crosses the near or far plane; outside
//   the grown box the falloff is 0 and the blend leaves the buffer as it is, so both give the
//   same result (docs/shading.md §6).
//   group 0: 0 rt0, 1 rt1, 2 rt2, 3 depth (R32Float copy of the depth buffer; the world position
//            is rebuilt from it, deferred/depth), 4 camera (DeferredCamera), 5 probe cube,
//            6 probe sampler, 7 probe (Probe).
// Add: one full-screen draw adding the reflection buffer (group 0 binding 0) to RT3; the host
//   blends One / One (UNITY_HDR_ON, src = refl, a = 0) or DstColor / Zero (LDR,
//   src = exp2(-max(refl, 0)), a = 1), which leaves RT3's alpha of 1 as it is.

#pass Reflections
// The Standard BRDF's tier of the indirect specular (docs/shading.md §5).
#pragma multi_compile _ UNITY_PBS_USE_BRDF2 UNITY_PBS_USE_BRDF3
#import internal/fullscreen
#import deferred/depth
#import deferred/probe
#import deferred/gbuffer
#import lighting/brdf

@group(0) @binding(0) var rt0: texture_2d<f32>;
@group(0) @binding(1) var rt1: texture_2d<f32>;
@group(0) @binding(2) var rt2: texture_2d<f32>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;
@group(0) @binding(5) var probe_cube: texture_cube<f32>;
@group(0) @binding(6) var probe_sampler: sampler;
@group(0) @binding(7) var<uniform> probe: Probe;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@vertex
fn vs_box(@location(0) world_position: vec3f) -> @builtin(position) vec4f {
    return deferred_camera.view_proj * vec4f(world_position, 1.0);
}

// rgb = the probe's indirect specular (§5 with env = sample · occlusion, occlusion = RT0.a,
// spec colour and smoothness from RT1, n from RT2; one_minus_reflectivity reconstructed from the
// spec colour, see brdf_one_minus_reflectivity_from_specular), a = the probe's falloff at p.
@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
    let gbuffer0 = textureLoad(rt0, pixel, 0);
    let gbuffer1 = textureLoad(rt1, pixel, 0);
    let gbuffer2 = textureLoad(rt2, pixel, 0);
    let p = depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel);

    let occlusion = gbuffer0.a;
    let spec_color = gbuffer1.rgb;
    let smoothness = gbuffer1.a;
    let n = gbuffer_decode_normal(gbuffer2.rgb);
    let v = brdf_view_dir(deferred_camera.position.xyz, p);
    let r = brdf_reflect_dir(v, n);

    let dir = probe_box_project_grown(r, p, probe);
    let env = probe_sample(probe_cube, probe_sampler, dir, probe_mip_from_smoothness(smoothness), probe.hdr)
        * occlusion;
    let one_minus_reflectivity = brdf_one_minus_reflectivity_from_specular(spec_color);
    let rgb = brdf_indirect_specular(env, spec_color, smoothness, one_minus_reflectivity, n, v);
    return vec4f(rgb, probe_falloff(p, probe));
}
#endpass

#pass Add
#pragma multi_compile _ UNITY_HDR_ON
#import internal/fullscreen
#import deferred/ldr

@group(0) @binding(0) var reflection_buffer: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let refl = textureLoad(reflection_buffer, fullscreen_pixel(frag_position), 0).rgb;
#if UNITY_HDR_ON
    // One / One: RT3 += refl (alpha 0 leaves RT3's a = 1).
    return vec4f(refl, 0.0);
#else
    // DstColor / Zero: RT3 · exp2(-max(refl, 0)) = ldr_accumulate(RT3, refl) (alpha 1 keeps a = 1).
    return vec4f(ldr_encode(refl), 1.0);
#endif
}
#endpass
