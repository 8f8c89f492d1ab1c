// lighting/shadow_fade: the realtime shadows' distance fade and the mix of a realtime shadow with
// baked occlusion (docs/shading.md §11 "Shadow distance fade", §13). Imported by
// lighting/light_bindings (the lighting pass, ForwardAdd) and by standard/my_lighting for
// ForwardBase's main light, with the same binding:
//
//   group 0: 18 shadow_fade (ShadowFade; with SHADOWS_DEPTH, SHADOWS_CUBE or SHADOWS_SCREEN)
//
// The record (48 bytes):
//   center_and_type   Unity's unity_ShadowFadeCenterAndType: xyz the centre, w 0 = fade by
//                     view depth (Close Fit), 1 = by the distance to the centre (Stable Fit)
//   view_axis         the camera's forward axis, w = dot(forward, camera position): view depth
//                     = dot(p, xyz) - w
//   params            x, y: Unity's _LightShadowData.z, .w (scale and offset of the fade); zw 0
//
// Provides:
//   struct ShadowFade
//   fn shadow_fade_at(p: vec3f) -> f32   Unity's UnityComputeShadowFade(UnityComputeShadowFadeDistance)
//       at world position p, in [0, 1] (with a realtime shadow keyword)
//   fn light_mix_shadows(realtime: f32, baked: f32, fade: f32) -> f32   Unity's
//       UnityMixRealtimeAndBakedShadows

struct ShadowFade {
    center_and_type: vec4f,
    view_axis: vec4f,
    params: vec4f,
}

#if defined(SHADOWS_DEPTH) || defined(SHADOWS_CUBE) || defined(SHADOWS_SCREEN)
@group(0) @binding(18) var<uniform> shadow_fade: ShadowFade;

// Unity computes the view depth from its view matrix (forward) or the rebuilt view-space
// position (deferred); both are this dot product.
fn shadow_fade_at(p: vec3f) -> f32 {
    let z = dot(p, shadow_fade.view_axis.xyz) - shadow_fade.view_axis.w;
    let sphere = distance(p, shadow_fade.center_and_type.xyz);
    let d = mix(z, sphere, shadow_fade.center_and_type.w);
    return saturate(d * shadow_fade.params.x + shadow_fade.params.y);
}
#endif

// Without a realtime shadow keyword the baked value alone; the Shadowmask mode
// (LIGHTMAP_SHADOW_MIXING) takes the darker of the faded realtime shadow and the baked one;
// otherwise (Distance Shadowmask, or no shadowmask: baked = 1) the fade lerps from realtime to
// baked.
fn light_mix_shadows(realtime: f32, baked: f32, fade: f32) -> f32 {
#if !defined(SHADOWS_DEPTH) && !defined(SHADOWS_CUBE) && !defined(SHADOWS_SCREEN)
    return baked;
#elif defined(LIGHTMAP_SHADOW_MIXING)
    return min(saturate(realtime + fade), baked);
#else
    return mix(realtime, baked, fade);
#endif
}
