// universal/main_light_shadow: URP's main-light shadow as the forward pass and the deferred
// main light read it (docs/urp.md §9; URP's Shadows.hlsl: MainLightRealtimeShadow,
// SampleScreenSpaceShadowmap, GetMainLightShadowFade; Lighting.hlsl's MainLightShadow with the
// baked shadow 1). Its bindings exist with _MAIN_LIGHT_SHADOWS, _MAIN_LIGHT_SHADOWS_CASCADE or
// _MAIN_LIGHT_SHADOWS_SCREEN, without _RECEIVE_SHADOWS_OFF (a material keyword of the forward
// pass; the deferred pass reads the texel's flag instead):
//
//   group 0: _MAIN_LIGHT_SHADOWS, _MAIN_LIGHT_SHADOWS_CASCADE: 10-12, 14, 15 the map or the
//              cascades (universal/main_light_shadow_map);
//            _MAIN_LIGHT_SHADOWS_SCREEN: 16 main_light_screen_shadow (texture_2d<f32>, the
//              camera-sized target URP's ScreenSpaceShadows pass wrote, its r read at the pixel);
//            all three: 13 main_light_shadow_params (vec4f, URP's _MainLightShadowParams:
//              x the strength — read by _MAIN_LIGHT_SHADOWS_SCREEN, the map and cascades carry
//              theirs —, y unused here, z the fade's scale, w its bias)
//
// Provides:
//   fn urp_main_light_shadow(p: vec3f, camera: vec3f, pixel: vec2i) -> vec2f
//       x the main light's shadow attenuation at p (the fragment at pixel) seen from camera
//       (1 without a shadow), y the shadow's strength (0 without a shadow)

#if (defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE) || defined(_MAIN_LIGHT_SHADOWS_SCREEN)) && !defined(_RECEIVE_SHADOWS_OFF)
#if defined(_MAIN_LIGHT_SHADOWS_SCREEN)
@group(0) @binding(16) var main_light_screen_shadow: texture_2d<f32>;
#else
#import universal/main_light_shadow_map
#endif
#import universal/lighting
@group(0) @binding(13) var<uniform> main_light_shadow_params: vec4f;
#endif

// The realtime shadow faded towards the baked shadow, 1 here. With _MAIN_LIGHT_SHADOWS_SCREEN the
// realtime shadow is the screen-space pass's value at this pixel (URP samples it point-clamped
// at the pixel's centre: this texel), strength and filtering already applied there; the fade is
// the receiver's in every mode.
fn urp_main_light_shadow(p: vec3f, camera: vec3f, pixel: vec2i) -> vec2f {
#if (defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE) || defined(_MAIN_LIGHT_SHADOWS_SCREEN)) && !defined(_RECEIVE_SHADOWS_OFF)
#if defined(_MAIN_LIGHT_SHADOWS_SCREEN)
    let realtime = vec2f(textureLoad(main_light_screen_shadow, pixel, 0).r, main_light_shadow_params.x);
#else
    let realtime = urp_main_light_realtime_shadow(p);
#endif
    return vec2f(mix(realtime.x, 1.0, urp_shadow_fade(p, camera, main_light_shadow_params.zw)), realtime.y);
#else
    return vec2f(1.0, 0.0);
#endif
}
