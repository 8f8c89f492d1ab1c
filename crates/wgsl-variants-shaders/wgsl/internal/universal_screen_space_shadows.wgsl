#shader universal_screen_space_shadows
// URP's ScreenSpaceShadows (Hidden/Universal Render Pipeline/ScreenSpaceShadows; docs/urp.md §9):
// with the Screen Space Shadows renderer feature, a full-screen pass after the depth prepass
// writes the main light's realtime shadow per pixel, so the receivers' _MAIN_LIGHT_SHADOWS_SCREEN
// variants (UniversalForward, stencil_deferred/DirectionalLit) read one texel instead of the map.
// For each pixel it rebuilds the world position from the depth buffer, reads the map or the
// cascades as the receivers would (universal/main_light_shadow_map: URP's
// TransformWorldToShadowCoord and MainLightRealtimeShadow, strength and _SHADOWS_SOFT applied)
// and writes that value to every channel; the distance fade stays the receivers'. URP's own
// pass declares no "off" option: the feature runs only when the main light has a shadow.
//   group 0: 3 depth (R32Float copy of the depth buffer, textureLoad), 4 camera (DeferredCamera),
//            10-15 the map or the cascades (universal/main_light_shadow_map)
// Target: URP's R8_UNorm (or B8G8R8A8_UNorm where R8 cannot be rendered), camera-sized.

#pass ScreenSpaceShadows
#pragma multi_compile _MAIN_LIGHT_SHADOWS _MAIN_LIGHT_SHADOWS_CASCADE
#pragma multi_compile _ _SHADOWS_SOFT
#import internal/fullscreen
#import deferred/depth
#import universal/main_light_shadow_map

@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
    let p = depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel);
    return vec4f(urp_main_light_realtime_shadow(p).x);
}
#endpass
