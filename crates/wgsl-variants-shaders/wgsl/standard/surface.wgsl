// standard/surface: the surface inputs of Catlike Coding's "My Lighting" (docs/shading.md §4),
// metallic workflow. Every map keyword switches a real texture sample; the functions sample
// with material_sampler and so belong to fragment shaders.
//
// Provides:
//   fn surface_detail_uv(uv: vec2f) -> vec2f          uv · detail tiling + detail offset
//   fn surface_detail_mask(uv: vec2f) -> f32          detail_mask.a (_DETAIL_MASK), else 1
//   fn surface_albedo(uv: vec2f) -> vec3f
//   fn surface_alpha(uv: vec2f) -> f32
//   fn surface_metallic(uv: vec2f) -> f32
//   fn surface_smoothness(uv: vec2f) -> f32
//   fn surface_occlusion(uv: vec2f) -> f32
//   fn surface_emission(uv: vec2f) -> vec3f
//   fn surface_unpack_normal(texel: vec4f, scale: f32) -> vec3f   Unity's UnpackScaleNormal
//   fn surface_blend_normals(a: vec3f, b: vec3f) -> vec3f         Unity's BlendNormals
//   fn surface_tangent_normal(uv: vec2f) -> vec3f
//   fn surface_world_normal(uv: vec2f, normal: vec3f, tangent: vec4f) -> vec3f
//   fn surface_clip(alpha: f32)                       _RENDERING_CUTOUT: discard when alpha < cutoff

#import standard/bindings

fn surface_detail_uv(uv: vec2f) -> vec2f {
    return uv * material.detail_st.xy + material.detail_st.zw;
}

fn surface_detail_mask(uv: vec2f) -> f32 {
#if defined(_DETAIL_MASK)
    return textureSample(detail_mask, material_sampler, uv).a;
#else
    return 1.0;
#endif
}

// main_tex.rgb · tint.rgb; _DETAIL_ALBEDO_MAP: mix(albedo, albedo · detail.rgb · 2, mask).
fn surface_albedo(uv: vec2f) -> vec3f {
    var albedo = textureSample(main_tex, material_sampler, uv).rgb * material.tint.rgb;
#if defined(_DETAIL_ALBEDO_MAP)
    let details = textureSample(detail_albedo, material_sampler, surface_detail_uv(uv)).rgb * 2.0;
    albedo = mix(albedo, albedo * details, surface_detail_mask(uv));
#endif
    return albedo;
}

// tint.a, times main_tex.a unless _SMOOTHNESS_ALBEDO (then main_tex.a is the smoothness).
fn surface_alpha(uv: vec2f) -> f32 {
    var alpha = material.tint.a;
#if !defined(_SMOOTHNESS_ALBEDO)
    alpha *= textureSample(main_tex, material_sampler, uv).a;
#endif
    return alpha;
}

// metallic_map.r with _METALLIC_MAP, else the uniform metallic.
fn surface_metallic(uv: vec2f) -> f32 {
#if defined(_METALLIC_MAP)
    return textureSample(metallic_map, material_sampler, uv).r;
#else
    return material.params.x;
#endif
}

#if defined(_SMOOTHNESS_METALLIC)
// The smoothness source of _SMOOTHNESS_METALLIC: metallic_map.a, which exists only with
// _METALLIC_MAP; without the map the source is 1 (as in the tutorial's GetSmoothness).
fn surface_smoothness_metallic_source(uv: vec2f) -> f32 {
#if defined(_METALLIC_MAP)
    return textureSample(metallic_map, material_sampler, uv).a;
#else
    return 1.0;
#endif
}
#endif

// smoothness · (main_tex.a with _SMOOTHNESS_ALBEDO; metallic_map.a with _SMOOTHNESS_METALLIC
// and _METALLIC_MAP; else 1).
fn surface_smoothness(uv: vec2f) -> f32 {
    var source = 1.0;
#if defined(_SMOOTHNESS_ALBEDO)
    source = textureSample(main_tex, material_sampler, uv).a;
#elif defined(_SMOOTHNESS_METALLIC)
    source = surface_smoothness_metallic_source(uv);
#endif
    return material.params.y * source;
}

// mix(1, occlusion_map.g, occlusion_strength) with _OCCLUSION_MAP, else 1.
fn surface_occlusion(uv: vec2f) -> f32 {
#if defined(_OCCLUSION_MAP)
    return mix(1.0, textureSample(occlusion_map, material_sampler, uv).g, material.params.w);
#else
    return 1.0;
#endif
}

// emission_map.rgb · emission with _EMISSION_MAP, else emission (ForwardBase and Deferred).
fn surface_emission(uv: vec2f) -> vec3f {
#if defined(FORWARD_BASE_PASS) || defined(DEFERRED_PASS)
#if defined(_EMISSION_MAP)
    return textureSample(emission_map, material_sampler, uv).rgb * material.emission.rgb;
#else
    return material.emission.rgb;
#endif
#else
    return vec3f(0.0);
#endif
}

// Unity's UnpackScaleNormal, not normalized: ((r·2-1)·s, (g·2-1)·s, b·2-1).
fn surface_unpack_normal(texel: vec4f, scale: f32) -> vec3f {
    let n = texel.rgb * 2.0 - 1.0;
    return vec3f(n.xy * scale, n.z);
}

// Unity's BlendNormals: normalize((a.xy + b.xy, a.z · b.z)).
fn surface_blend_normals(a: vec3f, b: vec3f) -> vec3f {
    return normalize(vec3f(a.xy + b.xy, a.z * b.z));
}

// Tangent-space normal: (0, 0, 1); _NORMAL_MAP: unpack(normal_map, bump_scale);
// _DETAIL_NORMAL_MAP: blended with mix((0, 0, 1), unpack(detail_normal, detail_bump_scale), mask).
fn surface_tangent_normal(uv: vec2f) -> vec3f {
    var t = vec3f(0.0, 0.0, 1.0);
#if defined(_NORMAL_MAP)
    t = surface_unpack_normal(textureSample(normal_map, material_sampler, uv), material.bump.x);
#endif
#if defined(_DETAIL_NORMAL_MAP)
    let detail = surface_unpack_normal(
        textureSample(detail_normal, material_sampler, surface_detail_uv(uv)),
        material.bump.y,
    );
    let d = mix(vec3f(0.0, 0.0, 1.0), detail, surface_detail_mask(uv));
    t = surface_blend_normals(t, d);
#endif
    return t;
}

// World normal from the interpolated vertex frame: N = normalize(normal),
// T = normalize(tangent.xyz), B = cross(N, T) · tangent.w; n = normalize(t.x·T + t.y·B + t.z·N).
// Without a normal map t = (0, 0, 1), so n = normalize(normalize(N)): the same value, computed
// without T and B (a mesh without tangents cannot turn it into NaN).
fn surface_world_normal(uv: vec2f, normal: vec3f, tangent: vec4f) -> vec3f {
    let n = normalize(normal);
#if defined(_NORMAL_MAP) || defined(_DETAIL_NORMAL_MAP)
    let t = surface_tangent_normal(uv);
    let tan = normalize(tangent.xyz);
    let bin = cross(n, tan) * tangent.w;
    return normalize(t.x * tan + t.y * bin + t.z * n);
#else
    return normalize(n);
#endif
}

// _RENDERING_CUTOUT: discard the fragment when alpha < cutoff (alpha == cutoff is kept).
fn surface_clip(alpha: f32) {
#if defined(_RENDERING_CUTOUT)
    if alpha < material.params.z {
        discard;
    }
#endif
}
