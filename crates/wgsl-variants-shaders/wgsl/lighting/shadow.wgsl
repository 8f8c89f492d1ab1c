// lighting/shadow: the shadow math of the per-pixel lights (docs/shading.md §11), pure functions
// shared by lighting/light_bindings (the receivers: deferred_shading Lighting, standard
// ForwardAdd). standard/shadow_caster writes the maps these functions read.
//
// The shadow record is laid out for a uniform buffer (mat4x4f + vec4f = 80 bytes):
//   world_to_shadow  SHADOWS_DEPTH: the spot light's view-projection (world to the map's clip
//                    space; depth 0..1 as wgpu's)
//   params.x         strength: shadow = mix(1 - strength, 1, visibility)
//   params.y         bias: SHADOWS_DEPTH subtracts it from the receiver's depth; SHADOWS_CUBE
//                    multiplies the receiver's distance by it (Unity's 0.97)
//   params.w         1 / range (SHADOWS_CUBE: the map stores |p - light| / range)
//
// Provides:
//   struct Shadow
//   fn shadow_mix(strength: f32, visibility: f32) -> f32
//   fn shadow_coords(world_to_shadow: mat4x4f, p: vec3f) -> vec3f   map uv (row 0 at the top), depth
//   fn shadow_map_visibility(map, sampler, uv: vec2f, z: f32) -> f32
//       a 2D map's visibility at uv for receiver depth z (bias already subtracted): one
//       LessEqual tap, or with SHADOWS_SOFT (URP: _SHADOWS_SOFT) the 3 x 3 tent (1 2 1) x (1 2 1) / 16. The spot's
//       SHADOWS_DEPTH (lighting/light_bindings) and the directional light's screen-space pass
//       (internal/screen_space_shadows) both read their maps through it, and so does URP's main
//       light in internal/stencil_deferred (_MAIN_LIGHT_SHADOWS).
//   fn shadow_map_tent(map, sampler, uv: vec2f, z: f32) -> f32
//       the 3 x 3 tent whatever the keywords (URP's additional lights choose it per light)

struct Shadow {
    world_to_shadow: mat4x4f,
    params: vec4f,
}

// Unity's lerp(_LightShadowData.r, 1, visibility) with _LightShadowData.r = 1 - strength.
fn shadow_mix(strength: f32, visibility: f32) -> f32 {
    return mix(1.0 - strength, 1.0, visibility);
}

// Clip -> NDC -> texture space: u = x / 2 + 1/2, v = 1/2 - y / 2 (texture rows run down),
// z = the NDC depth the caster wrote.
fn shadow_coords(world_to_shadow: mat4x4f, p: vec3f) -> vec3f {
    let q = world_to_shadow * vec4f(p, 1.0);
    let ndc = q.xyz / q.w;
    return vec3f(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z);
}

fn shadow_map_visibility(map: texture_depth_2d, map_sampler: sampler_comparison, uv: vec2f, z: f32) -> f32 {
#if defined(SHADOWS_SOFT) || defined(_SHADOWS_SOFT)
    return shadow_map_tent(map, map_sampler, uv, z);
#else
    return textureSampleCompareLevel(map, map_sampler, uv, z);
#endif
}

// The 3 x 3 tent whatever the keywords say: URP's additional lights choose it per light.
fn shadow_map_tent(map: texture_depth_2d, map_sampler: sampler_comparison, uv: vec2f, z: f32) -> f32 {
    var v = 0.0;
    v += textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(-1, -1));
    v += 2.0 * textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(0, -1));
    v += textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(1, -1));
    v += 2.0 * textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(-1, 0));
    v += 4.0 * textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(0, 0));
    v += 2.0 * textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(1, 0));
    v += textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(-1, 1));
    v += 2.0 * textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(0, 1));
    v += textureSampleCompareLevel(map, map_sampler, uv, z, vec2i(1, 1));
    return v / 16.0;
}
