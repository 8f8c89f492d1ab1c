// lighting/light_bindings: the resources of one per-pixel light and its evaluation under the
// light keywords of Unity's multi_compile_lightpass / multi_compile_fwdadd (docs/shading.md §10).
// Shared by internal/deferred_shading and standard ForwardAdd, so the binding numbers are the
// same in both (group 0, above the passes' own bindings 0-5):
//
//   group 0: 6 light (Light), 7 light_cookie (texture_2d, DIRECTIONAL_COOKIE),
//            8 light_cookie_cube (texture_cube, POINT_COOKIE),
//            9 light_cookie_sampler (DIRECTIONAL_COOKIE, POINT_COOKIE; repeat addressing),
//            10 shadow (Shadow; SHADOWS_DEPTH, SHADOWS_CUBE),
//            11 shadow_map (texture_depth_2d) + 12 shadow_map_sampler (sampler_comparison,
//               nearest, LessEqual, clamp to edge) (SHADOWS_DEPTH),
//            13 shadow_cube (texture_cube<f32>, r = |p - light| / range) + 14 shadow_cube_sampler
//               (nearest) (SHADOWS_CUBE),
//            15 screen_shadow (SHADOWS_SCREEN; lighting/screen_shadow),
//            18 shadow_fade (any realtime shadow keyword; lighting/shadow_fade)
//
// Shadow keywords (Unity's multi_compile_lightpass / multi_compile_fwdadd_fullshadows pairs):
// SHADOWS_DEPTH with SPOT only (a 2D map through the light's view-projection), SHADOWS_CUBE with
// POINT and POINT_COOKIE (a cube of distances), SHADOWS_SOFT filters either (docs/shading.md
// §11); SHADOWS_SCREEN with DIRECTIONAL and DIRECTIONAL_COOKIE (the mask
// internal/screen_space_shadows made from the light's map, SHADOWS_SOFT applied there); the
// passes' exclude pragmas drop every other pairing.
//
// Provides:
//   fn light_unshadowed(p: vec3f) -> LightSample   the light at world position p; exactly
//       one of DIRECTIONAL, DIRECTIONAL_COOKIE, POINT, POINT_COOKIE, SPOT is on (none: no light)
//   fn light_shadow(p: vec3f) -> f32       the shadow factor in [1 - strength, 1] (1 without one)
//   fn light_at_pixel(p: vec3f, pixel: vec2i, baked: f32) -> LightSample   the light at p
//       shadowed by light_mix_shadows(realtime, baked, fade) (lighting/shadow_fade): realtime
//       is light_shadow(p), or the SHADOWS_SCREEN mask at the pixel (the factor, strength
//       included); baked is the light's baked occlusion (1 where there is none); fade is the
//       shadow distance fade at p

#import lighting/light
#import lighting/shadow_fade
#if defined(SHADOWS_DEPTH) || defined(SHADOWS_CUBE)
#import lighting/shadow
#endif
#if defined(SHADOWS_SCREEN)
#import lighting/screen_shadow
#endif

@group(0) @binding(6) var<uniform> light: Light;
#if defined(DIRECTIONAL_COOKIE)
@group(0) @binding(7) var light_cookie: texture_2d<f32>;
#endif
#if defined(POINT_COOKIE)
@group(0) @binding(8) var light_cookie_cube: texture_cube<f32>;
#endif
#if defined(DIRECTIONAL_COOKIE) || defined(POINT_COOKIE)
@group(0) @binding(9) var light_cookie_sampler: sampler;
#endif
#if defined(SHADOWS_DEPTH) || defined(SHADOWS_CUBE)
@group(0) @binding(10) var<uniform> shadow: Shadow;
#endif
#if defined(SHADOWS_DEPTH)
@group(0) @binding(11) var shadow_map: texture_depth_2d;
@group(0) @binding(12) var shadow_map_sampler: sampler_comparison;
#endif
#if defined(SHADOWS_CUBE)
@group(0) @binding(13) var shadow_cube: texture_cube<f32>;
@group(0) @binding(14) var shadow_cube_sampler: sampler;
#endif

// The light at p (at the pixel `pixel`), its realtime shadow (the maps, or with SHADOWS_SCREEN
// the screen-space mask there) faded by distance and mixed with the baked occlusion `baked`.
fn light_at_pixel(p: vec3f, pixel: vec2i, baked: f32) -> LightSample {
    var s = light_unshadowed(p);
#if defined(SHADOWS_SCREEN)
    s.attenuation *= light_mix_shadows(light_screen_shadow(pixel), baked, shadow_fade_at(p));
#elif defined(SHADOWS_DEPTH) || defined(SHADOWS_CUBE)
    s.attenuation *= light_mix_shadows(light_shadow(p), baked, shadow_fade_at(p));
#else
    s.attenuation *= light_mix_shadows(1.0, baked, 0.0);
#endif
    return s;
}

fn light_shadow(p: vec3f) -> f32 {
#if defined(SHADOWS_DEPTH)
    // Lit where the receiver's depth minus the bias is <= the caster's (the sampler's LessEqual).
    let c = shadow_coords(shadow.world_to_shadow, p);
    let z = c.z - shadow.params.y;
    let visibility = shadow_map_visibility(shadow_map, shadow_map_sampler, c.xy, z);
    return shadow_mix(shadow.params.x, visibility);
#elif defined(SHADOWS_CUBE)
    // Lit where the stored distance is >= the receiver's, both over the range (Unity's
    // SampleCubeDistance(vec) < mydist ? shadowed : lit, mydist biased by params.y).
    let d = p - light.position.xyz;
    let mydist = length(d) * shadow.params.w * shadow.params.y;
#if defined(SHADOWS_SOFT)
    // Unity's four taps: d moved by 1/128 (world units) along alternating diagonals, 1/4 each.
    let o = 1.0 / 128.0;
    let visibility = 0.25
        * (light_cube_lit(d + vec3f(o, o, o), mydist) + light_cube_lit(d + vec3f(-o, -o, o), mydist)
            + light_cube_lit(d + vec3f(-o, o, -o), mydist) + light_cube_lit(d + vec3f(o, -o, -o), mydist));
#else
    let visibility = light_cube_lit(d, mydist);
#endif
    return shadow_mix(shadow.params.x, visibility);
#else
    return 1.0;
#endif
}

#if defined(SHADOWS_CUBE)
// 1 where the cube's stored distance in direction d is >= mydist, else 0.
fn light_cube_lit(d: vec3f, mydist: f32) -> f32 {
    let stored = textureSampleLevel(shadow_cube, shadow_cube_sampler, d, 0.0).r;
    return select(0.0, 1.0, stored >= mydist);
}
#endif

fn light_unshadowed(p: vec3f) -> LightSample {
#if defined(DIRECTIONAL)
    return light_directional(light);
#elif defined(DIRECTIONAL_COOKIE)
    // The cookie's alpha at (world_to_light · p).xy; the sampler repeats it.
    var s = light_directional(light);
    let uv = light_cookie_coords(light, p).xy;
    s.attenuation *= textureSampleLevel(light_cookie, light_cookie_sampler, uv, 0.0).a;
    return s;
#elif defined(POINT)
    return light_point(light, p);
#elif defined(POINT_COOKIE)
    // The cube cookie's alpha in the direction (world_to_light · p).xyz.
    var s = light_point(light, p);
    let dir = light_cookie_coords(light, p).xyz;
    s.attenuation *= textureSampleLevel(light_cookie_cube, light_cookie_sampler, dir, 0.0).a;
    return s;
#elif defined(SPOT)
    return light_spot(light, p);
#else
    return LightSample(vec3f(0.0), 0.0);
#endif
}
