// universal/main_light_shadow: URP's main-light shadow as the forward pass and the deferred
// main light read it (docs/urp.md §9; URP's Shadows.hlsl: TransformWorldToShadowCoord,
// ComputeCascadeIndex, MainLightRealtimeShadow, GetMainLightShadowFade; Lighting.hlsl's
// MainLightShadow with the baked shadow 1). Its bindings exist with _MAIN_LIGHT_SHADOWS or
// _MAIN_LIGHT_SHADOWS_CASCADE, without _RECEIVE_SHADOWS_OFF (a material keyword of the
// forward pass; the deferred pass reads the texel's flag instead):
//
//   group 0: _MAIN_LIGHT_SHADOWS: 10 shadow (Shadow of lighting/shadow),
//              11 shadow_map (texture_depth_2d);
//            _MAIN_LIGHT_SHADOWS_CASCADE: 14 main_light_cascades (CascadedShadow of
//              lighting/cascades: URP's _MainLightWorldToShadow[i], _CascadeShadowSplitSpheres0-3
//              and _CascadeShadowSplitSphereRadii), 15 main_light_cascade_atlas
//              (texture_depth_2d, the cascades' tiles);
//            both: 12 shadow_map_sampler (sampler_comparison), 13 main_light_shadow_fade
//              (vec4f: x URP's fade scale, y its bias)
//
// Provides:
//   fn urp_main_light_shadow(p: vec3f, camera: vec3f) -> vec2f
//       x the main light's shadow attenuation at p seen from camera (1 without a shadow),
//       y the shadow's strength (0 without a shadow)

#if (defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE)) && !defined(_RECEIVE_SHADOWS_OFF)
#import lighting/shadow
#if defined(_MAIN_LIGHT_SHADOWS_CASCADE)
#import lighting/cascades
@group(0) @binding(14) var<uniform> main_light_cascades: CascadedShadow;
@group(0) @binding(15) var main_light_cascade_atlas: texture_depth_2d;
#else
@group(0) @binding(10) var<uniform> shadow: Shadow;
@group(0) @binding(11) var shadow_map: texture_depth_2d;
#endif
@group(0) @binding(12) var shadow_map_sampler: sampler_comparison;
@group(0) @binding(13) var<uniform> main_light_shadow_fade: vec4f;

// URP's GetMainLightShadowFade: saturate(|p - camera|² · scale + bias), a ramp in the squared
// distance from the camera that the host sets to end at the shadow distance
// (_MainLightShadowParams.zw).
fn urp_main_light_shadow_fade(p: vec3f, camera: vec3f) -> f32 {
    let d = p - camera;
    return saturate(dot(d, d) * main_light_shadow_fade.x + main_light_shadow_fade.y);
}
#endif

// The realtime shadow 1 - strength + strength · visibility (URP's LerpWhiteTo), faded towards
// the baked shadow, 1 here. With _MAIN_LIGHT_SHADOWS_CASCADE the map is the atlas tile of the
// first cascade whose split sphere holds p (URP's ComputeCascadeIndex, the selection of
// lighting/cascades' split spheres); in none, URP's no-op fifth matrix gives the coordinate
// (0, 0, 0), in front of every caster: lit.
fn urp_main_light_shadow(p: vec3f, camera: vec3f) -> vec2f {
#if (defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE)) && !defined(_RECEIVE_SHADOWS_OFF)
#if defined(_MAIN_LIGHT_SHADOWS_CASCADE)
    let c = cascade_coords(main_light_cascades, p);
    let params = main_light_cascades.params;
    let visibility = shadow_map_visibility(main_light_cascade_atlas, shadow_map_sampler, c.xy, c.z - params.y);
#else
    let c = shadow_coords(shadow.world_to_shadow, p);
    let params = shadow.params;
    let visibility = shadow_map_visibility(shadow_map, shadow_map_sampler, c.xy, c.z - params.y);
#endif
    let realtime = shadow_mix(params.x, visibility);
    return vec2f(mix(realtime, 1.0, urp_main_light_shadow_fade(p, camera)), params.x);
#else
    return vec2f(1.0, 0.0);
#endif
}
