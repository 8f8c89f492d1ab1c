// lighting/light_bindings: the resources of one per-pixel light and its evaluation under the
// light keywords of Unity's multi_compile_lightpass / multi_compile_fwdadd (docs/shading.md §10).
// Shared by internal/deferred_shading and standard ForwardAdd, so the binding numbers are the
// same in both (group 0, above the passes' own bindings 0-5):
//
//   group 0: 6 light (Light), 7 light_cookie (texture_2d, DIRECTIONAL_COOKIE),
//            8 light_cookie_cube (texture_cube, POINT_COOKIE),
//            9 light_cookie_sampler (DIRECTIONAL_COOKIE, POINT_COOKIE; repeat addressing)
//
// Provides:
//   fn light_at(p: vec3f) -> LightSample   the light at world position p; exactly one of
//       DIRECTIONAL, DIRECTIONAL_COOKIE, POINT, POINT_COOKIE, SPOT is on (none: no light)

#import lighting/light

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

fn light_at(p: vec3f) -> LightSample {
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
