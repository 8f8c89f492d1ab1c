// universal/lighting: URP's direct lighting of one light (docs/urp.md §9; URP's
// RealtimeLights.hlsl, BRDF.hlsl, Lighting.hlsl): the attenuation, the BRDF data rebuilt from the
// G-buffer and the minimalist Cook-Torrance specular. Pure functions, no bindings.
//
// Provides:
//   struct UrpLight        one light as the StencilDeferred passes read it
//   fn urp_punctual_sample(light: UrpLight, p: vec3f) -> vec4f
//       xyz: unit direction to a point or spot light; w: its distance attenuation
//   fn urp_angle_attenuation(spot_direction: vec3f, l: vec3f, a: vec2f) -> f32   a spot's cone
//   struct UrpBrdfData
//   fn urp_brdf_from_gbuffer(albedo: vec3f, specular: vec3f, smoothness: f32,
//                            specular_setup: bool) -> UrpBrdfData
//   fn urp_lighting_physically_based(brdf: UrpBrdfData, color: vec3f, attenuation: f32,
//       l: vec3f, n: vec3f, v: vec3f, specular_highlights_off: bool) -> vec3f
//   fn urp_shadow_fade(p: vec3f, camera: vec3f, scale_bias: vec2f) -> f32
//       URP's shadow distance fade (the main light's and the additional lights')

// position.xyz (punctual); color.rgb; attenuation: x 1/range², z, w the spot's scale and
// offset (0, 1 for a point light); direction.xyz: to the light (directional) or the spot's
// axis reversed; layer_mask.x: the rendering layers it lights.
struct UrpLight {
    position: vec4f,
    color: vec4f,
    attenuation: vec4f,
    direction: vec4f,
    layer_mask: vec4u,
}

const URP_HALF_MIN: f32 = 6.103515625e-5;
const URP_HALF_MIN_SQRT: f32 = 0.0078125;
const URP_DIELECTRIC_SPEC: f32 = 0.04;

// 1/d² · saturate(1 - (d² / range²)²)².
fn urp_distance_attenuation(distance_sqr: f32, inv_range_sq: f32) -> f32 {
    let factor = distance_sqr * inv_range_sq;
    let smooth_factor = saturate(1.0 - factor * factor);
    return (1.0 / distance_sqr) * smooth_factor * smooth_factor;
}

// saturate(dot(spot_direction, l) · a.x + a.y)².
fn urp_angle_attenuation(spot_direction: vec3f, l: vec3f, a: vec2f) -> f32 {
    let t = saturate(dot(spot_direction, l) * a.x + a.y);
    return t * t;
}

// A point or spot light at p: xyz the unit direction to it, w its distance attenuation (the
// spot's angle term is the caller's: urp_angle_attenuation).
fn urp_punctual_sample(light: UrpLight, p: vec3f) -> vec4f {
    let to_light = light.position.xyz - p;
    let distance_sqr = max(dot(to_light, to_light), URP_HALF_MIN);
    let l = to_light * inverseSqrt(distance_sqr);
    return vec4f(l, urp_distance_attenuation(distance_sqr, light.attenuation.x));
}

struct UrpBrdfData {
    diffuse: vec3f,
    specular: vec3f,
    roughness2: f32,
    normalization_term: f32,
    roughness2_minus_one: f32,
}

// BRDFDataFromGbuffer + InitializeBRDFDataDirect. Specular setup: reflectivity = max(specular);
// metallic: reflectivity = GBuffer1.r, metallic = (reflectivity - 0.04) / 0.96,
// specular = mix(0.04, albedo, metallic). diffuse = albedo · (1 - reflectivity) in both.
fn urp_brdf_from_gbuffer(albedo: vec3f, specular: vec3f, smoothness: f32, specular_setup: bool) -> UrpBrdfData {
    var b: UrpBrdfData;
    var reflectivity: f32;
    if specular_setup {
        reflectivity = max(specular.r, max(specular.g, specular.b));
        b.specular = specular;
    } else {
        reflectivity = specular.r;
        let metallic = (reflectivity - URP_DIELECTRIC_SPEC) / (1.0 - URP_DIELECTRIC_SPEC);
        b.specular = mix(vec3f(URP_DIELECTRIC_SPEC), albedo, metallic);
    }
    b.diffuse = albedo * (1.0 - reflectivity);
    let perceptual_roughness = 1.0 - smoothness;
    let roughness = max(perceptual_roughness * perceptual_roughness, URP_HALF_MIN_SQRT);
    b.roughness2 = max(roughness * roughness, URP_HALF_MIN);
    b.normalization_term = roughness * 4.0 + 2.0;
    b.roughness2_minus_one = b.roughness2 - 1.0;
    return b;
}

// SafeNormalize: v · rsqrt(max(FLT_MIN, v·v)).
fn urp_safe_normalize(v: vec3f) -> vec3f {
    return v * inverseSqrt(max(1.175494351e-38, dot(v, v)));
}

// DirectBRDFSpecular: r² / (d² · max(0.1, (l·h)²) · (4r + 2)), d = (n·h)² (r² - 1) + 1.00001.
fn urp_direct_specular(b: UrpBrdfData, n: vec3f, l: vec3f, v: vec3f) -> f32 {
    let h = urp_safe_normalize(l + v);
    let n_dot_h = saturate(dot(n, h));
    let l_dot_h = saturate(dot(l, h));
    let d = n_dot_h * n_dot_h * b.roughness2_minus_one + 1.00001;
    return b.roughness2 / ((d * d) * max(0.1, l_dot_h * l_dot_h) * b.normalization_term);
}

// LightingPhysicallyBased: (diffuse + specular · term) · color · attenuation · saturate(n·l).
fn urp_lighting_physically_based(b: UrpBrdfData, color: vec3f, attenuation: f32, l: vec3f, n: vec3f, v: vec3f, specular_highlights_off: bool) -> vec3f {
    let radiance = color * (attenuation * saturate(dot(n, l)));
    var brdf = b.diffuse;
    if !specular_highlights_off {
        brdf += b.specular * urp_direct_specular(b, n, l, v);
    }
    return brdf * radiance;
}

// GetMainLightShadowFade and GetAdditionalLightShadowFade: saturate(|p - camera|² · scale + bias),
// a ramp in the squared distance from the camera that the host sets to end at the shadow
// distance (_MainLightShadowParams.zw, _AdditionalShadowFadeParams.xy).
fn urp_shadow_fade(p: vec3f, camera: vec3f, scale_bias: vec2f) -> f32 {
    let d = p - camera;
    return saturate(dot(d, d) * scale_bias.x + scale_bias.y);
}
