// universal/additional_light_shadow: URP's realtime shadows of the additional lights (docs/urp.md
// §9; URP's Shadows.hlsl: GetAdditionalLightShadowParams, AdditionalLightRealtimeShadow,
// SampleShadowmap, GetAdditionalLightShadowFade and AdditionalLightShadow with the baked shadow
// 1; the SRP core's CubeMapFaceID). Read by the forward pass's per-pixel lights and the deferred
// punctual lights. Its bindings exist with _ADDITIONAL_LIGHT_SHADOWS without
// _RECEIVE_SHADOWS_OFF:
//
//   group 0: 17 additional_shadows (AdditionalShadows),
//            18 additional_shadow_atlas (texture_depth_2d: every shadowed light's slices),
//            19 additional_shadow_sampler (sampler_comparison, nearest, LessEqual, clamp to edge)
//
// Provides:
//   fn urp_additional_light_shadow(light: u32, p: vec3f, to_light: vec3f, camera: vec3f) -> f32
//       the shadow attenuation of additional light `light` at p (to_light: the unit direction
//       from p to the light) seen from camera, faded; 1 without a shadow

#if defined(_ADDITIONAL_LIGHT_SHADOWS) && !defined(_RECEIVE_SHADOWS_OFF)
#import lighting/shadow
#import universal/lighting

// fade: URP's _AdditionalShadowFadeParams (x scale, y bias);
// params[light]: URP's _AdditionalShadowParams (x strength, y > 0 soft, z > 0 a point light,
//   w the first slice, -1 without a shadow), for the forward pass's eight lights;
// world_to_shadow[slice]: URP's _AdditionalLightsWorldToShadow, the light's view-projection
//   with the slice's atlas tile folded in (a point light's six in the order +X, -X, +Y, -Y,
//   +Z, -Z), 48 = eight point lights.
struct AdditionalShadows {
    fade: vec4f,
    params: array<vec4f, 8>,
    world_to_shadow: array<mat4x4f, 48>,
}

@group(0) @binding(17) var<uniform> additional_shadows: AdditionalShadows;
@group(0) @binding(18) var additional_shadow_atlas: texture_depth_2d;
@group(0) @binding(19) var additional_shadow_sampler: sampler_comparison;

// CubeMapFaceID: the face of dir's largest component (ties go to z, then y).
fn urp_cube_map_face_id(dir: vec3f) -> i32 {
    let a = abs(dir);
    if a.z >= a.x && a.z >= a.y {
        return select(4, 5, dir.z < 0.0);
    }
    if a.y >= a.x {
        return select(2, 3, dir.y < 0.0);
    }
    return select(0, 1, dir.x < 0.0);
}

// AdditionalLightRealtimeShadow: a point light reads the slice of the cube face from the light
// to p; the slice's matrix and the perspective divide give the atlas coordinate, compared with
// no receiver bias (URP biases the caster); 1 beyond the depth range (BEYOND_SHADOW_FAR).
fn urp_additional_light_realtime_shadow(light: u32, p: vec3f, to_light: vec3f) -> f32 {
    let params = additional_shadows.params[light];
    var slice = i32(params.w);
    if slice < 0 {
        return 1.0;
    }
    if params.z > 0.0 {
        slice += urp_cube_map_face_id(-to_light);
    }
    let c = shadow_coords(additional_shadows.world_to_shadow[slice], p);
#if defined(_SHADOWS_SOFT)
    var visibility: f32;
    if params.y > 0.0 {
        visibility = shadow_map_tent(additional_shadow_atlas, additional_shadow_sampler, c.xy, c.z);
    } else {
        visibility = textureSampleCompareLevel(additional_shadow_atlas, additional_shadow_sampler, c.xy, c.z);
    }
#else
    let visibility = textureSampleCompareLevel(additional_shadow_atlas, additional_shadow_sampler, c.xy, c.z);
#endif
    if c.z <= 0.0 || c.z >= 1.0 {
        return 1.0;
    }
    return shadow_mix(params.x, visibility);
}
#endif

fn urp_additional_light_shadow(light: u32, p: vec3f, to_light: vec3f, camera: vec3f) -> f32 {
#if defined(_ADDITIONAL_LIGHT_SHADOWS) && !defined(_RECEIVE_SHADOWS_OFF)
    let fade = urp_shadow_fade(p, camera, additional_shadows.fade.xy);
    return mix(urp_additional_light_realtime_shadow(light, p, to_light), 1.0, fade);
#else
    return 1.0;
#endif
}
