// universal/ssao_only_pass: URP's StencilDeferred "SSAOOnly" pass (docs/urp.md §14): in a
// deferred frame without a directional light (so no _DEFERRED_FIRST_LIGHT draw), the screen-space
// occlusion still has to reach what the G-buffer pass wrote into GBuffer3 (emission and GI);
// this full-screen pass does it before the lights, blended One SrcAlpha. URP compiles it
// whether or not the SSAO feature is on, and without _SCREEN_SPACE_OCCLUSION its vertex stage
// puts the triangle outside the clip volume, so nothing is drawn.
//
//   group 0: 1 gbuffer1 (its a: the surface occlusion the G-buffer pass applied),
//            27 the screen-space occlusion (universal/ambient_occlusion)
//
// Provides the entry points:
//   @vertex   vs_main    a full-screen triangle (_SCREEN_SPACE_OCCLUSION), else one behind the
//                        near plane
//   @fragment fs_main    -> @location(0) (0, 0, 0, what GBuffer3 keeps)

#import internal/fullscreen
#import universal/ambient_occlusion

@group(0) @binding(1) var gbuffer1: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    var position = fullscreen_position(vertex_index);
#if !defined(_SCREEN_SPACE_OCCLUSION)
    // z / w = -2 lies outside the clip volume's [0, 1]: the triangle is clipped away.
    position.z = -2.0;
#endif
    return position;
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
    let ssao = urp_screen_space_ambient_occlusion(pixel);
    let surface = textureLoad(gbuffer1, pixel, 0).a;
    return vec4f(0.0, 0.0, 0.0, urp_deferred_indirect_occlusion(ssao, surface));
}
