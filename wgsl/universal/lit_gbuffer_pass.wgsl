// universal/lit_gbuffer_pass: URP Lit's UniversalGBuffer program (URP's LitGBufferPass.hlsl,
// GlobalIllumination.hlsl, UnityGBuffer.hlsl BRDFDataToGbuffer; docs/urp.md).
//
// Provides the entry points:
//   @vertex   vs_main(UrpVertexInput) -> UrpVertexOutput
//   @fragment fs_main(UrpVertexOutput) -> UrpGBufferOutput

#import universal/bindings
#import universal/surface
#import universal/gbuffer

struct UrpVertexInput {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
#if defined(LIGHTMAP_ON)
    @location(4) lightmap_uv: vec2f,
#endif
}

struct UrpVertexOutput {
    @builtin(position) clip_position: vec4f,
    @location(0) world_position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
#if defined(LIGHTMAP_ON)
    @location(4) lightmap_uv: vec2f,
#endif
}

@vertex
fn vs_main(in: UrpVertexInput) -> UrpVertexOutput {
    var out: UrpVertexOutput;
    let world = object.model * vec4f(in.position, 1.0);
    out.clip_position = camera.view_proj * world;
    out.world_position = world.xyz;
    out.normal = normalize((object.normal_matrix * vec4f(in.normal, 0.0)).xyz);
    out.tangent = vec4f(normalize((object.model * vec4f(in.tangent.xyz, 0.0)).xyz), in.tangent.w);
    out.uv = in.uv;
#if defined(LIGHTMAP_ON)
    // OUTPUT_LIGHTMAP_UV: uv1 · unity_LightmapST.xy + unity_LightmapST.zw.
    out.lightmap_uv = in.lightmap_uv * object.lightmap_st.xy + object.lightmap_st.zw;
#endif
    return out;
}

// The main light's realtime shadow attenuation: 1 with _RECEIVE_SHADOWS_OFF (URP's
// MainLightRealtimeShadow), else the scene's stand-in for a shadow-map sample.
fn urp_main_light_shadow() -> f32 {
#if defined(_RECEIVE_SHADOWS_OFF)
    return 1.0;
#else
    return lighting.main_light_shadow.x;
#endif
}

// Baked GI: the lightmap texel (linear HDR, as a full-HDR lightmap) with LIGHTMAP_ON, else
// max(0, L0 + L1 spherical harmonics). With LIGHTMAP_ON and _MIXED_LIGHTING_SUBTRACTIVE the
// main light's estimated contribution is subtracted where it is shadowed (URP's
// SubtractDirectMainLightFromLightmap).
fn urp_baked_gi(in: UrpVertexOutput, n: vec3f) -> vec3f {
#if defined(LIGHTMAP_ON)
    var gi = textureSample(lightmap, lightmap_sampler, in.lightmap_uv).rgb;
#if defined(_MIXED_LIGHTING_SUBTRACTIVE)
    let lambert = lighting.main_light_color.rgb * saturate(dot(lighting.main_light_dir.xyz, n));
    let subtracted = gi - lambert * (1.0 - urp_main_light_shadow());
    let realtime_shadow = mix(gi, max(subtracted, lighting.subtractive_shadow_color.rgb), lighting.main_light_shadow.y);
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

@fragment
fn fs_main(in: UrpVertexOutput) -> UrpGBufferOutput {
    let s = urp_surface(in.uv);
    let b = urp_brdf(s);
    let n = urp_world_normal(s.normal_ts, normalize(in.normal), in.tangent);
    let v = normalize(camera.position.xyz - in.world_position);

    // URP's GlobalIllumination: (gi · diffuse + env · surfaceReduction ·
    // mix(specular, grazing, (1 − N·V)^4)) · occlusion.
    let n_dot_v = saturate(dot(n, v));
    let fresnel = pow(1.0 - n_dot_v, 4.0);
    let env = urp_glossy_environment(reflect(-v, n), b.perceptual_roughness);
    let surface_reduction = 1.0 / (b.roughness2 + 1.0);
    let gi = urp_baked_gi(in, n) * b.diffuse
        + env * surface_reduction * mix(b.specular, vec3f(b.grazing), fresnel);
    let color = gi * s.occlusion;

    var flags = 0u;
#if defined(_RECEIVE_SHADOWS_OFF)
    flags |= URP_FLAG_RECEIVE_SHADOWS_OFF;
#endif
#if defined(_SPECULAR_SETUP)
    flags |= URP_FLAG_SPECULAR_SETUP;
    var packed_specular = b.specular;
#else
    var packed_specular = vec3f(b.reflectivity, 0.0, 0.0);
#endif
#if defined(_SPECULARHIGHLIGHTS_OFF)
    flags |= URP_FLAG_SPECULAR_HIGHLIGHTS_OFF;
    packed_specular = vec3f(0.0);
#endif
#if defined(LIGHTMAP_ON) && defined(_MIXED_LIGHTING_SUBTRACTIVE)
    flags |= URP_FLAG_SUBTRACTIVE_MIXED_LIGHTING;
#endif

    var out: UrpGBufferOutput;
    out.gbuffer0 = vec4f(s.albedo, urp_pack_flags(flags));
    out.gbuffer1 = vec4f(packed_specular, s.occlusion);
    out.gbuffer2 = vec4f(urp_pack_normal(n), s.smoothness);
    out.gbuffer3 = vec4f(s.emission + color, 1.0);
#if defined(_RENDER_PASS_ENABLED)
    out.depth_as_color = in.clip_position.z;
#endif
#if defined(SHADOWS_SHADOWMASK) && defined(LIGHTMAP_ON)
    out.shadow_mask = textureSample(shadowmask_map, lightmap_sampler, in.lightmap_uv);
#elif (defined(SHADOWS_SHADOWMASK) || (defined(_MIXED_LIGHTING_SUBTRACTIVE) && !defined(LIGHTMAP_ON)))
    // URP's OUTPUT_SHADOWMASK: a dynamic object under subtractive lighting stores its
    // probe occlusion too.
    out.shadow_mask = lighting.probes_occlusion;
#endif
#if defined(_WRITE_RENDERING_LAYERS)
    out.rendering_layers = object.rendering_layers.x;
#endif
    return out;
}
