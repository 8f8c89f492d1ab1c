// universal/lit_gbuffer_pass: URP Lit's UniversalGBuffer program (URP's LitGBufferPass.hlsl,
// UnityGBuffer.hlsl BRDFDataToGbuffer; docs/urp.md): the surface, its global illumination
// (universal/gi) and the G-buffer packing.
//
// Provides the entry points:
//   @vertex   vs_main(UrpVertexInput) -> UrpVertexOutput
//   @fragment fs_main(UrpVertexOutput) -> UrpGBufferOutput

#import universal/bindings
#import universal/surface
#import universal/gbuffer
#import universal/lit_vertex
#import universal/gi

@vertex
fn vs_main(in: UrpVertexInput) -> UrpVertexOutput {
    return urp_vertex(in);
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

@fragment
fn fs_main(in: UrpVertexOutput) -> UrpGBufferOutput {
    let s = urp_surface(in.uv);
    let b = urp_brdf(s);
    let n = urp_world_normal(s.normal_ts, normalize(in.normal), in.tangent);
    let v = normalize(camera.position.xyz - in.world_position);
    let baked = urp_baked_gi(in, n, lighting.main_light_color.rgb, urp_main_light_shadow(), lighting.main_light_shadow.y);
    let color = urp_global_illumination(b, baked, n, v, s.occlusion);

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
