// standard/my_lighting: Catlike Coding's "My Lighting" program for the standard shader's
// ForwardBase (FORWARD_BASE_PASS), ForwardAdd (FORWARD_ADD_PASS) and Deferred (DEFERRED_PASS)
// passes (docs/shading.md §4-§7, §10).
//
// Provides the entry points:
//   @vertex   vs_main(VertexInput) -> VertexOutput
//   @fragment fs_main(VertexOutput) -> GBufferOutput        (DEFERRED_PASS: RT0..RT3, and RT4
//                                                            with SHADOWS_SHADOWMASK)
//   @fragment fs_main(VertexOutput) -> @location(0) vec4f   (FORWARD_BASE_PASS, FORWARD_ADD_PASS)

#import standard/bindings
#import standard/surface
#import lighting/brdf
#if defined(FORWARD_BASE_PASS)
#import lighting/direct
#endif
#import deferred/probe
#import deferred/gbuffer
#if defined(FORWARD_ADD_PASS)
#import lighting/light_bindings
#elif defined(FORWARD_BASE_PASS) && defined(SHADOWS_SCREEN)
#import lighting/screen_shadow
#import lighting/shadow_fade
#endif

struct VertexInput {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}

struct VertexOutput {
    @builtin(position) clip_position: vec4f,
    @location(0) world_position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}

@vertex
fn vs_main(in: VertexInput) -> VertexOutput {
    var out: VertexOutput;
    let world = object.model * vec4f(in.position, 1.0);
    out.clip_position = camera.view_proj * world;
    out.world_position = world.xyz;
    out.normal = (object.normal_matrix * vec4f(in.normal, 0.0)).xyz;
    out.tangent = vec4f((object.model * vec4f(in.tangent.xyz, 0.0)).xyz, in.tangent.w);
    out.uv = in.uv;
    return out;
}

#if defined(FORWARD_BASE_PASS) || (defined(DEFERRED_PASS) && !UNITY_ENABLE_REFLECTION_BUFFERS)
// Two probes per object, blended by probe 0's weight t = box_min.w; probe 1 is sampled only
// when t < 0.99999. The result is not yet multiplied by occlusion.
fn my_lighting_probe_env(r: vec3f, p: vec3f, smoothness: f32) -> vec3f {
    let mip = probe_mip_from_smoothness(smoothness);
    let probe0 = probes.probe0;
    let e0 = probe_sample(probe_cube0, probe_sampler, probe_box_project(r, p, probe0), mip, probe0.hdr);
    let t = probe0.box_min.w;
    var env = e0;
    if t < PROBE_BLEND_ONLY_FIRST {
        let probe1 = probes.probe1;
        let e1 = probe_sample(probe_cube1, probe_sampler, probe_box_project(r, p, probe1), mip, probe1.hdr);
        env = probe_forward_blend(e0, e1, t);
    }
    return env;
}
#endif

#if defined(FORWARD_BASE_PASS) || defined(DEFERRED_PASS)
// The indirect diffuse light before occlusion (Unity's UnityGI_Base): the ambient SH for an
// object without lightmaps (Unity's LIGHTPROBE_SH objects), else the baked lightmap
// (LIGHTMAP_ON) plus the realtime one (DYNAMICLIGHTMAP_ON), each through its directional map's
// half-Lambert term with DIRLIGHTMAP_COMBINED. The lightmap uvs are the mesh uv through
// unity_LightmapST / unity_DynamicLightmapST (our vertex format has one uv set).
fn my_lighting_ambient(n: vec3f, uv: vec2f) -> vec3f {
#if !defined(LIGHTMAP_ON) && !defined(DYNAMICLIGHTMAP_ON)
    return brdf_sh_ambient(n, lighting.sh_r, lighting.sh_g, lighting.sh_b);
#else
    var d = vec3f(0.0);
#if defined(LIGHTMAP_ON)
    let luv = uv * lightmap.st.xy + lightmap.st.zw;
    let baked = probe_rgbm_decode(textureSample(lightmap_tex, lightmap_sampler, luv), lightmap.decode);
#if defined(DIRLIGHTMAP_COMBINED)
    d += lightmap_directional(baked, textureSample(lightmap_dir, lightmap_sampler, luv), n);
#else
    d += baked;
#endif
#endif
#if defined(DYNAMICLIGHTMAP_ON)
    let duv = uv * lightmap.dynamic_st.xy + lightmap.dynamic_st.zw;
    let realtime = lightmap_decode_realtime(textureSample(dynamic_lightmap, lightmap_sampler, duv), lightmap.dynamic_decode);
#if defined(DIRLIGHTMAP_COMBINED)
    d += lightmap_directional(realtime, textureSample(dynamic_lightmap_dir, lightmap_sampler, duv), n);
#else
    d += realtime;
#endif
#endif
    return d;
#endif
}
#endif

@fragment
#if defined(DEFERRED_PASS)
fn fs_main(in: VertexOutput) -> GBufferOutput {
#else
fn fs_main(in: VertexOutput) -> @location(0) vec4f {
#endif
    let uv = in.uv;
    let alpha = surface_alpha(uv);
    surface_clip(alpha);

    let n = surface_world_normal(uv, in.normal, in.tangent);
    let v = brdf_view_dir(camera.position.xyz, in.world_position);
    let albedo = surface_albedo(uv);
    let metallic = surface_metallic(uv);
    let smoothness = surface_smoothness(uv);
    let occlusion = surface_occlusion(uv);
    let emission = surface_emission(uv);

    let setup = brdf_metallic_setup(albedo, metallic);
    var diffuse = setup.diffuse;
    var out_alpha = alpha;
#if defined(_RENDERING_TRANSPARENT)
    diffuse = brdf_premultiply_diffuse(diffuse, alpha);
    out_alpha = brdf_premultiply_alpha(alpha, setup.one_minus_reflectivity);
#endif

#if defined(FORWARD_ADD_PASS)
    // One per-pixel light, nothing else: the same lighting code as the deferred lighting pass.
    let pixel = vec2i(in.clip_position.xy);
    // No baked occlusion here (1): the forward passes do not model the Shadowmask modes.
    let s = light_at_pixel(in.world_position, pixel, 1.0);
    let c = light_direct(diffuse, setup.spec_color, smoothness, n, v, light, s);
#else
    let indirect_diffuse = my_lighting_ambient(n, uv) * occlusion;
#if defined(DEFERRED_PASS) && UNITY_ENABLE_REFLECTION_BUFFERS
    // The per-pixel probes of internal/deferred_reflections add the indirect specular later.
    let indirect_specular = vec3f(0.0);
#else
    let env = my_lighting_probe_env(brdf_reflect_dir(v, n), in.world_position, smoothness) * occlusion;
    let indirect_specular =
        brdf_indirect_specular(env, setup.spec_color, smoothness, setup.one_minus_reflectivity, n, v);
#endif
    let c = emission + diffuse * indirect_diffuse + indirect_specular;
#endif

#if defined(DEFERRED_PASS)
    // No direct light here: the deferred light passes add it to RT3.
    var g = gbuffer_pack(diffuse, occlusion, setup.spec_color, smoothness, n, c);
#if defined(SHADOWS_SHADOWMASK)
    // RT4: the baked occlusion as stored (Unity's UnityGetRawBakedOcclusions); the lighting
    // pass picks the light's channel.
#if defined(LIGHTMAP_ON)
    // A lightmapped object's shadowmask shares its lightmap's uv layout (Unity's unity_ShadowMask).
    g.rt4 = textureSample(shadowmask_map, material_sampler, uv * lightmap.st.xy + lightmap.st.zw);
#else
    g.rt4 = textureSample(shadowmask_map, material_sampler, uv);
#endif
#endif
    return g;
#elif defined(FORWARD_ADD_PASS)
#if defined(_RENDERING_FADE) || defined(_RENDERING_TRANSPARENT)
    return vec4f(c, out_alpha);
#else
    return vec4f(c, 1.0);
#endif
#else
    var main_color = lighting.light_color.rgb;
#if defined(SHADOWS_SCREEN)
    // The main light's shadow: the screen-space mask at this pixel (lighting/screen_shadow),
    // faded by distance (lighting/shadow_fade; no baked occlusion in the forward passes).
    let realtime = light_screen_shadow(vec2i(in.clip_position.xy));
    main_color *= light_mix_shadows(realtime, 1.0, shadow_fade_at(in.world_position));
#endif
    let direct = brdf_direct(
        diffuse,
        setup.spec_color,
        smoothness,
        n,
        v,
        lighting.light_dir.xyz,
        main_color,
    );
#if defined(_RENDERING_FADE) || defined(_RENDERING_TRANSPARENT)
    return vec4f(c + direct, out_alpha);
#else
    return vec4f(c + direct, 1.0);
#endif
#endif
}
