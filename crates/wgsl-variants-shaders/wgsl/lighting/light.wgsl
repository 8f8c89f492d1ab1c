// lighting/light: the per-pixel lights of the built-in path (docs/shading.md §10), one code path
// for the deferred lighting pass (internal/deferred_shading) and the forward add pass
// (standard ForwardAdd). Pure functions, no bindings; lighting/light_bindings adds the light's
// resources and picks the light type from its keyword.
//
// The light record is laid out for a uniform buffer (3 × vec4f + mat4x4f = 112 bytes):
//   color.rgb        the light's colour (a unused)
//   position.xyz     world position (POINT, SPOT; for the directional cookie, the cookie's origin)
//   position.w       1 / range² (POINT, SPOT)
//   direction.xyz    unit direction from the surface TO the light (DIRECTIONAL); w unused
//   world_to_light   Unity's unity_WorldToLight: DIRECTIONAL_COOKIE uv = (M·p).xy (repeat);
//                    POINT_COOKIE lookup direction = (M·p).xyz; SPOT projective q = M·p
//
// Provides:
//   struct Light
//   struct LightSample { l: vec3f, attenuation: f32 }
//   fn light_falloff(t: f32) -> f32                       distance falloff, t = |d|² / range²
//   fn light_spot_cookie(q: vec4f) -> f32                 the default spot cookie (a soft disk)
//   fn light_directional(light: Light) -> LightSample
//   fn light_point(light: Light, p: vec3f) -> LightSample
//   fn light_spot(light: Light, p: vec3f) -> LightSample
//   fn light_cookie_coords(light: Light, p: vec3f) -> vec4f  world_to_light · (p, 1)
//   fn light_direct(diffuse: vec3f, spec_color: vec3f, smoothness: f32, n: vec3f, v: vec3f,
//                   light: Light, s: LightSample) -> vec3f

#import lighting/direct

struct Light {
    color: vec4f,
    position: vec4f,
    direction: vec4f,
    world_to_light: mat4x4f,
}

// l: unit direction from the surface to the light (zero where it has none); attenuation: the
// light's falloff × cookie at the surface, in [0, 1].
struct LightSample {
    l: vec3f,
    attenuation: f32,
}

// 1 / (1 + 25 t) · saturate(5 (1 - t)) for t < 1, 0 from t = 1 on (and for NaN).
fn light_falloff(t: f32) -> f32 {
    if t < 1.0 {
        return saturate(5.0 * (1.0 - t)) / (1.0 + 25.0 * t);
    }
    return 0.0;
}

// The default spot cookie, evaluated analytically: behind the light (q.w <= 0) 0, else a disk
// of radius 1 in uv = q.xy / q.w with a soft rim, saturate(5 (1 - |uv|)).
fn light_spot_cookie(q: vec4f) -> f32 {
    if q.w <= 0.0 {
        return 0.0;
    }
    let uv = q.xy / q.w;
    return saturate(5.0 * (1.0 - length(uv)));
}

fn light_cookie_coords(light: Light, p: vec3f) -> vec4f {
    return light.world_to_light * vec4f(p, 1.0);
}

// DIRECTIONAL: l = direction, no distance attenuation.
fn light_directional(light: Light) -> LightSample {
    return LightSample(light.direction.xyz, 1.0);
}

// POINT: d = p - position, l = -d / |d| (zero at the light itself), attenuation =
// falloff(|d|² / range²).
fn light_point(light: Light, p: vec3f) -> LightSample {
    let d = p - light.position.xyz;
    let dist2 = dot(d, d);
    let l = select(vec3f(0.0), -d * inverseSqrt(dist2), dist2 > 0.0);
    return LightSample(l, light_falloff(dist2 * light.position.w));
}

// SPOT: the point light's l and falloff, times the default cookie at q = world_to_light · p.
fn light_spot(light: Light, p: vec3f) -> LightSample {
    var s = light_point(light, p);
    s.attenuation *= light_spot_cookie(light_cookie_coords(light, p));
    return s;
}

// The Standard BRDF's direct term (lighting/direct, in the variant's tier) with the light's
// colour × attenuation (indirect terms are
// the ForwardBase and G-buffer passes' business).
fn light_direct(
    diffuse: vec3f,
    spec_color: vec3f,
    smoothness: f32,
    n: vec3f,
    v: vec3f,
    light: Light,
    s: LightSample,
) -> vec3f {
    return brdf_direct(diffuse, spec_color, smoothness, n, v, s.l, light.color.rgb * s.attenuation);
}
