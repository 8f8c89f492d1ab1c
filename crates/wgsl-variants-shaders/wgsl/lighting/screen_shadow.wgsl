// lighting/screen_shadow: a directional light's screen-space shadow (SHADOWS_SCREEN,
// docs/shading.md §11). internal/screen_space_shadows renders the light's map into a mask of the
// camera's view before the light is drawn; a receiver reads the factor at its own pixel, so the
// filtering (SHADOWS_SOFT) and the strength are the mask pass's. Imported by
// lighting/light_bindings (the lighting pass, ForwardAdd) and by standard/my_lighting for
// ForwardBase's main light, with the same binding:
//
//   group 0: 15 screen_shadow (texture_2d<f32>, r = mix(1 - strength, 1, visibility); textureLoad)
//
// Provides:
//   fn light_screen_shadow(pixel: vec2i) -> f32   the mask's r at the pixel

@group(0) @binding(15) var screen_shadow: texture_2d<f32>;

// Unity's UnityDeferredComputeShadow / SHADOW_ATTENUATION for SHADOWS_SCREEN: the mask's r.
fn light_screen_shadow(pixel: vec2i) -> f32 {
    return textureLoad(screen_shadow, pixel, 0).r;
}
