// universal/surface: URP Lit's surface inputs and BRDF data (URP's LitInput.hlsl
// InitializeStandardLitSurfaceData, SampleMetallicSpecGloss, SampleOcclusion, SampleEmission,
// SampleNormal; BRDF.hlsl InitializeBRDFData). Samples with material_sampler: fragment only.
//
// Provides:
//   struct UrpSurface { albedo, alpha, metallic, specular, smoothness, occlusion, emission, normal_ts }
//   fn urp_alpha(albedo_alpha: f32) -> f32          URP's Alpha(): _ALPHATEST_ON discards here
//   fn urp_surface(uv: vec2f) -> UrpSurface
//   struct UrpBrdf { diffuse, specular, reflectivity, perceptual_roughness, roughness2, grazing }
//   fn urp_brdf(s: UrpSurface) -> UrpBrdf
//   fn urp_world_normal(normal_ts: vec3f, normal: vec3f, tangent: vec4f) -> vec3f

#import universal/bindings

struct UrpSurface {
    albedo: vec3f,
    alpha: f32,
    metallic: f32,
    specular: vec3f,
    smoothness: f32,
    occlusion: f32,
    emission: vec3f,
    normal_ts: vec3f,
}

struct UrpBrdf {
    diffuse: vec3f,
    specular: vec3f,
    reflectivity: f32,
    perceptual_roughness: f32,
    roughness2: f32,
    grazing: f32,
}

// URP's Alpha(): the base map's alpha times _BaseColor.a (_BaseColor.a alone when the base
// map's alpha holds the smoothness); _ALPHATEST_ON discards alpha < _Cutoff (clip(alpha -
// cutoff): alpha == cutoff is kept). Fragment stage only.
fn urp_alpha(albedo_alpha: f32) -> f32 {
#if defined(_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A)
    let alpha = material.base_color.a;
#else
    let alpha = albedo_alpha * material.base_color.a;
#endif
#if defined(_ALPHATEST_ON)
    if alpha < material.params.z {
        discard;
    }
#endif
    return alpha;
}

fn urp_surface(uv: vec2f) -> UrpSurface {
    var s: UrpSurface;
    let albedo_alpha = textureSample(base_map, material_sampler, uv);
    s.albedo = albedo_alpha.rgb * material.base_color.rgb;
    s.alpha = urp_alpha(albedo_alpha.a);

#if defined(_METALLICSPECGLOSSMAP)
    var spec_gloss = textureSample(metallic_gloss_map, material_sampler, uv);
#if defined(_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A)
    spec_gloss.a = albedo_alpha.a * material.params.y;
#else
    spec_gloss.a *= material.params.y;
#endif
#else
#if defined(_SPECULAR_SETUP)
    var spec_gloss = vec4f(material.spec_color.rgb, 1.0);
#else
    var spec_gloss = vec4f(vec3f(material.params.x), 1.0);
#endif
#if defined(_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A)
    spec_gloss.a = albedo_alpha.a * material.params.y;
#else
    spec_gloss.a = material.params.y;
#endif
#endif

#if defined(_SPECULAR_SETUP)
    s.metallic = 1.0;
    s.specular = spec_gloss.rgb;
#else
    s.metallic = spec_gloss.r;
    s.specular = vec3f(0.0);
#endif
    s.smoothness = spec_gloss.a;

#if defined(_OCCLUSIONMAP)
    s.occlusion = mix(1.0, textureSample(occlusion_map, material_sampler, uv).g, material.extra.x);
#else
    s.occlusion = 1.0;
#endif

#if defined(_EMISSION)
    s.emission = textureSample(emission_map, material_sampler, uv).rgb * material.emission_color.rgb;
#else
    s.emission = vec3f(0.0);
#endif

#if defined(_NORMALMAP)
    // UnpackNormalRGB: (rgb · 2 − 1) with xy scaled by _BumpScale, not normalized.
    let packed = textureSample(bump_map, material_sampler, uv).rgb * 2.0 - 1.0;
    s.normal_ts = vec3f(packed.xy * material.params.w, packed.z);
#else
    s.normal_ts = vec3f(0.0, 0.0, 1.0);
#endif
    return s;
}

// Metallic: reflectivity = 1 − 0.96 · (1 − metallic), diffuse = albedo · (1 − reflectivity),
// specular = mix(0.04, albedo, metallic). _SPECULAR_SETUP: reflectivity = max component of the
// specular colour, diffuse = albedo · (1 − reflectivity) (current URP's BRDF.hlsl; older URP
// releases used albedo · (1 − specular) per channel). roughness = max(pr², 2^-7),
// roughness² = max(roughness², 2^-14), grazing = saturate(smoothness + reflectivity).
fn urp_brdf(s: UrpSurface) -> UrpBrdf {
    var b: UrpBrdf;
#if defined(_SPECULAR_SETUP)
    b.reflectivity = max(max(s.specular.r, s.specular.g), s.specular.b);
    b.diffuse = s.albedo * (1.0 - b.reflectivity);
    b.specular = s.specular;
#else
    let one_minus_reflectivity = 0.96 * (1.0 - s.metallic);
    b.reflectivity = 1.0 - one_minus_reflectivity;
    b.diffuse = s.albedo * one_minus_reflectivity;
    b.specular = mix(vec3f(0.04), s.albedo, s.metallic);
#endif
    b.perceptual_roughness = 1.0 - s.smoothness;
    let roughness = max(b.perceptual_roughness * b.perceptual_roughness, 0.0078125);
    b.roughness2 = max(roughness * roughness, 6.103515625e-5);
    b.grazing = saturate(s.smoothness + b.reflectivity);
    return b;
}

// normalize(T · t.x + B · t.y + N · t.z), B = cross(N, T) · tangent.w (URP's
// TransformTangentToWorld); without _NORMALMAP normalize(N).
fn urp_world_normal(normal_ts: vec3f, normal: vec3f, tangent: vec4f) -> vec3f {
#if defined(_NORMALMAP)
    let bitangent = cross(normal, tangent.xyz) * tangent.w;
    return normalize(normal_ts.x * tangent.xyz + normal_ts.y * bitangent + normal_ts.z * normal);
#else
    return normalize(normal);
#endif
}
