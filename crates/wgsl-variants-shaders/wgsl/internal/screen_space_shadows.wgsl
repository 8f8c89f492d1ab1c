#shader screen_space_shadows
// Unity's Internal-ScreenSpaceShadows ("collect shadows", docs/shading.md §11): before a
// directional light with SHADOWS_SCREEN is drawn, a full-screen pass turns the light's cascaded
// shadow map into a mask of the screen. For each pixel it rebuilds the world position from the
// depth buffer (as the lighting pass does), finds its cascade (lighting/cascades: by view depth,
// by split spheres with SHADOWS_SPLIT_SPHERES, cascade 0 with SHADOWS_SINGLE_CASCADE — Unity's
// multi_compile_shadowcollector), compares it with that cascade's tile of the atlas and writes
// the shadow factor mix(1 - strength, 1, visibility) into r. The lighting pass's SHADOWS_SCREEN
// variants read it at their pixel (lighting/light_bindings, binding 15), so the filtering is
// this pass's: SHADOWS_SOFT takes the 3 x 3 tent in the cascade's tile, as a spot's
// SHADOWS_DEPTH does (the same function, lighting/shadow).
//   group 0: 3 depth (R32Float, textureLoad), 4 camera (DeferredCamera: the lighting pass's
//            uniform), 10 cascades (CascadedShadow), 11 shadow_map (texture_depth_2d: the
//            atlas) + 12 shadow_map_sampler (sampler_comparison, nearest, LessEqual, clamp to
//            edge)
// Target: Rgba8Unorm (Unity's mask is an ARGB32 render texture), r = the factor, gba = 1.

#pass Collect
#pragma multi_compile _ SHADOWS_SOFT
#pragma multi_compile _ SHADOWS_SINGLE_CASCADE
#pragma multi_compile _ SHADOWS_SPLIT_SPHERES
#import internal/fullscreen
#import deferred/depth
#import lighting/shadow
#import lighting/cascades


@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;
@group(0) @binding(10) var<uniform> cascades: CascadedShadow;
@group(0) @binding(11) var shadow_map: texture_depth_2d;
@group(0) @binding(12) var shadow_map_sampler: sampler_comparison;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
    let p = depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel);
    // Lit where the receiver's depth minus the bias is <= the caster's (LessEqual).
    let c = cascade_coords(cascades, p);
    let visibility = shadow_map_visibility(shadow_map, shadow_map_sampler, c.xy, c.z - cascades.params.y);
    return vec4f(shadow_mix(cascades.params.x, visibility), 1.0, 1.0, 1.0);
}
#endpass
