// universal/main_light_shadow_map: URP's realtime main-light shadow read from the light's map
// or its cascades (docs/urp.md §9; URP's Shadows.hlsl: TransformWorldToShadowCoord,
// ComputeCascadeIndex, MainLightRealtimeShadow without _MAIN_LIGHT_SHADOWS_SCREEN and
// SampleShadowmap's LerpWhiteTo and BEYOND_SHADOW_FAR). Two readers: the receivers (universal/main_light_shadow, with
// _MAIN_LIGHT_SHADOWS or _MAIN_LIGHT_SHADOWS_CASCADE) and URP's ScreenSpaceShadows pass, which
// writes this value per pixel for the _MAIN_LIGHT_SHADOWS_SCREEN receivers
// (internal/universal_screen_space_shadows). Its bindings exist with _MAIN_LIGHT_SHADOWS or
// _MAIN_LIGHT_SHADOWS_CASCADE:
//
//   group 0: _MAIN_LIGHT_SHADOWS: 10 shadow (Shadow of lighting/shadow),
//              11 shadow_map (texture_depth_2d);
//            _MAIN_LIGHT_SHADOWS_CASCADE: 14 main_light_cascades (CascadedShadow of
//              lighting/cascades: URP's _MainLightWorldToShadow[i], _CascadeShadowSplitSpheres0-3
//              and _CascadeShadowSplitSphereRadii), 15 main_light_cascade_atlas
//              (texture_depth_2d, the cascades' tiles);
//            both: 12 shadow_map_sampler (sampler_comparison, nearest, LessEqual, clamp to edge)
//
// Provides:
//   fn urp_main_light_realtime_shadow(p: vec3f) -> vec2f
//       x the realtime attenuation at p, 1 - strength + strength · visibility (_SHADOWS_SOFT:
//       the 3 x 3 tent), 1 where p's map depth lies outside [0, 1] (BEYOND_SHADOW_FAR), before
//       the distance fade; y the shadow's strength

#if defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE)
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

// With _MAIN_LIGHT_SHADOWS_CASCADE the map is the atlas tile of the first cascade whose split
// sphere holds p (URP's ComputeCascadeIndex, the selection of lighting/cascades' split
// spheres); in none, URP's no-op fifth matrix gives the coordinate (0, 0, 0), in front of every
// caster: lit.
fn urp_main_light_realtime_shadow(p: vec3f) -> vec2f {
#if defined(_MAIN_LIGHT_SHADOWS_CASCADE)
    let c = cascade_coords(main_light_cascades, p);
    let params = main_light_cascades.params;
    let visibility = shadow_map_visibility(main_light_cascade_atlas, shadow_map_sampler, c.xy, c.z - params.y);
#else
    let c = shadow_coords(shadow.world_to_shadow, p);
    let params = shadow.params;
    let visibility = shadow_map_visibility(shadow_map, shadow_map_sampler, c.xy, c.z - params.y);
#endif
    // BEYOND_SHADOW_FAR: outside the light's depth range the map says nothing; lit.
    if c.z <= 0.0 || c.z >= 1.0 {
        return vec2f(1.0, params.x);
    }
    return vec2f(shadow_mix(params.x, visibility), params.x);
}
#endif
