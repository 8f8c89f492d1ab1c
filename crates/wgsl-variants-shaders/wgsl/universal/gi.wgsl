// universal/gi: URP Lit's global illumination, shared by the UniversalGBuffer pass (into
// GBuffer3) and the UniversalForward pass (URP's GlobalIllumination.hlsl; docs/urp.md §8).
// Samples textures: fragment only.
//
// Provides:
//   fn urp_baked_gi(in: UrpVertexOutput, n: vec3f, main_color: vec3f, shadow: f32, shadow_strength: f32) -> vec3f
//   fn urp_glossy_environment(r: vec3f, perceptual_roughness: f32) -> vec3f
//   fn urp_global_illumination(b: UrpBrdf, baked: vec3f, n: vec3f, v: vec3f, occlusion: f32) -> vec3f

#import universal/bindings
#import universal/surface
#import universal/lit_vertex

// Baked GI: the lightmap texel (linear HDR, as a full-HDR lightmap) with LIGHTMAP_ON, else
// max(0, L0 + L1 spherical harmonics). With LIGHTMAP_ON and _MIXED_LIGHTING_SUBTRACTIVE the
// main light's estimated contribution is subtracted where it is shadowed (URP's
// SubtractDirectMainLightFromLightmap); `main_color` is the main light's colour as GetMainLight
// gives it (times its cookie in the forward pass), `shadow` its realtime shadow attenuation at
// the pixel, `shadow_strength` the shadow's strength.
fn urp_baked_gi(in: UrpVertexOutput, n: vec3f, main_color: vec3f, shadow: f32, shadow_strength: f32) -> vec3f {
#if defined(LIGHTMAP_ON)
    var gi = textureSample(lightmap, lightmap_sampler, in.lightmap_uv).rgb;
#if defined(_MIXED_LIGHTING_SUBTRACTIVE)
    let lambert = main_color * saturate(dot(lighting.main_light_dir.xyz, n));
    let subtracted = gi - lambert * (1.0 - shadow);
    let realtime_shadow = mix(gi, max(subtracted, lighting.subtractive_shadow_color.rgb), shadow_strength);
    gi = min(gi, realtime_shadow);
#endif
    return gi;
#else
    let n1 = vec4f(n, 1.0);
    return max(vec3f(0.0), vec3f(dot(lighting.sh_r, n1), dot(lighting.sh_g, n1), dot(lighting.sh_b, n1)));
#endif
}

// GlossyEnvironmentReflection: the environment cube at mip pr · (1.7 − 0.7 · pr) · 6, or
// _GlossyEnvironmentColor with _ENVIRONMENTREFLECTIONS_OFF.
fn urp_glossy_environment(r: vec3f, perceptual_roughness: f32) -> vec3f {
#if defined(_ENVIRONMENTREFLECTIONS_OFF)
    return lighting.glossy_environment_color.rgb;
#else
    let mip = perceptual_roughness * (1.7 - 0.7 * perceptual_roughness) * 6.0;
    return textureSampleLevel(environment, environment_sampler, r, mip).rgb;
#endif
}

// URP's GlobalIllumination: (baked · diffuse + env · surfaceReduction ·
// mix(specular, grazing, (1 − N·V)^4)) · occlusion.
fn urp_global_illumination(b: UrpBrdf, baked: vec3f, n: vec3f, v: vec3f, occlusion: f32) -> vec3f {
    let n_dot_v = saturate(dot(n, v));
    let fresnel = pow(1.0 - n_dot_v, 4.0);
    let env = urp_glossy_environment(reflect(-v, n), b.perceptual_roughness);
    let surface_reduction = 1.0 / (b.roughness2 + 1.0);
    let gi = baked * b.diffuse + env * surface_reduction * mix(b.specular, vec3f(b.grazing), fresnel);
    return gi * occlusion;
}
