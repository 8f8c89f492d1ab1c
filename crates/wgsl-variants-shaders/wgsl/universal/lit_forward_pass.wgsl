// universal/lit_forward_pass: URP Lit's UniversalForward program (URP's LitForwardPass.hlsl,
// Lighting.hlsl UniversalFragmentPBR, RealtimeLights.hlsl; docs/urp.md §11): the surface lit
// in one pass — global illumination (universal/gi), the main directional light with its
// shadow, the additional point and spot lights per pixel (_ADDITIONAL_LIGHTS, with their
// shadows under _ADDITIONAL_LIGHT_SHADOWS) or per vertex (_ADDITIONAL_LIGHTS_VERTEX), the main
// and the per-pixel lights tinted by their cookies under _LIGHT_COOKIES, the screen-space
// occlusion under _SCREEN_SPACE_OCCLUSION, and the emission — into the HDR camera target.
//
//   group 0-2: universal/bindings (camera, lighting, environment; material; object, lightmap)
//   group 0:   4 forward_lights (ForwardLights; with _ADDITIONAL_LIGHTS,
//                _ADDITIONAL_LIGHTS_VERTEX or _LIGHT_LAYERS),
//              10-16 the main light's shadow (universal/main_light_shadow),
//              17-19 the additional lights' shadows (universal/additional_light_shadow),
//              20-25 the lights' cookies (universal/light_cookie: _LIGHT_COOKIES),
//              27 the screen-space occlusion (universal/ambient_occlusion:
//                _SCREEN_SPACE_OCCLUSION; its direct strength is lighting's
//                ambient_occlusion_params.w)
//
// Provides the entry points:
//   @vertex   vs_main(UrpVertexInput) -> UrpVertexOutput
//   @fragment fs_main(UrpVertexOutput) -> @location(0) vec4f   (rgb: radiance; a: 1, opaque)

#import universal/bindings
#import universal/surface
#import universal/lit_vertex
#import universal/gi
#import universal/lighting
#import universal/main_light_shadow
#import universal/additional_light_shadow
#import universal/light_cookie
#import universal/ambient_occlusion

// URP's limit of additional lights per object in the forward path.
const URP_MAX_ADDITIONAL_LIGHTS: u32 = 8u;

// params.x: how many of `lights` are used (at most 8); params.y: the main light's
// rendering-layer mask (_LIGHT_LAYERS).
struct ForwardLights {
    params: vec4u,
    lights: array<UrpLight, 8>,
}

#if defined(_ADDITIONAL_LIGHTS) || defined(_ADDITIONAL_LIGHTS_VERTEX) || defined(_LIGHT_LAYERS)
@group(0) @binding(4) var<uniform> forward_lights: ForwardLights;
#endif

// Whether a light with this rendering-layer mask lights the mesh (_LIGHT_LAYERS: any layer in
// common with the mesh's; URP's IsMatchingLightLayer).
fn urp_lights_mesh(layer_mask: u32) -> bool {
#if defined(_LIGHT_LAYERS)
    return (layer_mask & object.rendering_layers.x) != 0u;
#else
    return true;
#endif
}

// An additional light at p: xyz the unit direction to it, w its distance times angle
// attenuation (a point light's angle terms (0, 1) give 1; URP's GetAdditionalPerObjectLight).
fn urp_additional_light(light: UrpLight, p: vec3f) -> vec4f {
    var s = urp_punctual_sample(light, p);
    s.w *= urp_angle_attenuation(light.direction.xyz, s.xyz, light.attenuation.zw);
    return s;
}

@vertex
fn vs_main(in: UrpVertexInput) -> UrpVertexOutput {
    var out = urp_vertex(in);
#if defined(_ADDITIONAL_LIGHTS_VERTEX)
    // URP's VertexLighting: each additional light's Lambert term at the vertex (no shadow, no
    // specular), interpolated; the fragment multiplies it by the diffuse colour.
    var lit = vec3f(0.0);
    let count = min(forward_lights.params.x, URP_MAX_ADDITIONAL_LIGHTS);
    for (var i = 0u; i < count; i++) {
        let light = forward_lights.lights[i];
        if urp_lights_mesh(light.layer_mask.x) {
            let s = urp_additional_light(light, out.world_position);
            lit += light.color.rgb * s.w * saturate(dot(out.normal, s.xyz));
        }
    }
    out.vertex_lighting = lit;
#endif
    return out;
}

// URP's BRDFData for direct light: InitializeBRDFData's roughness terms (4r + 2, r² − 1).
fn urp_direct_brdf(b: UrpBrdf) -> UrpBrdfData {
    let roughness = max(b.perceptual_roughness * b.perceptual_roughness, URP_HALF_MIN_SQRT);
    return UrpBrdfData(b.diffuse, b.specular, b.roughness2, roughness * 4.0 + 2.0, b.roughness2 - 1.0);
}

@fragment
fn fs_main(in: UrpVertexOutput) -> @location(0) vec4f {
    let s = urp_surface(in.uv);
    let b = urp_brdf(s);
    let direct = urp_direct_brdf(b);
    let n = urp_world_normal(s.normal_ts, normalize(in.normal), in.tangent);
    let p = in.world_position;
    let v = normalize(camera.position.xyz - p);
#if defined(_SPECULARHIGHLIGHTS_OFF)
    let specular_off = true;
#else
    let specular_off = false;
#endif

    // The fragment's pixel: where a _MAIN_LIGHT_SHADOWS_SCREEN variant reads its shadow and a
    // _SCREEN_SPACE_OCCLUSION one its occlusion.
    let pixel = vec2i(floor(in.clip_position.xy));
    let shadow = urp_main_light_shadow(p, camera.position.xyz, pixel);
#if defined(_LIGHT_COOKIES)
    // GetMainLight: the main light's colour times its cookie, for the direct light and the
    // subtractive lightmap's estimate of it alike.
    let cookie_color = lighting.main_light_color.rgb * urp_main_light_cookie(p);
#else
    let cookie_color = lighting.main_light_color.rgb;
#endif
#if defined(_SCREEN_SPACE_OCCLUSION)
    // CreateAmbientOcclusionFactor: the global illumination takes the smaller of the SSAO's
    // indirect part and the surface's occlusion; GetMainLight and GetAdditionalLight multiply
    // the colours by the direct part (the subtractive estimate reads the main light's too).
    let ssao = urp_screen_space_ambient_occlusion(pixel);
    let direct_occlusion = urp_direct_occlusion(ssao, lighting.ambient_occlusion_params.w);
    let occlusion = min(ssao, s.occlusion);
    let main_color = cookie_color * direct_occlusion;
#else
    let occlusion = s.occlusion;
    let main_color = cookie_color;
#endif
    var color = urp_global_illumination(b, urp_baked_gi(in, n, main_color, shadow.x, shadow.y), n, v, occlusion);

#if defined(_LIGHT_LAYERS)
    let main_layers = forward_lights.params.y;
#else
    let main_layers = 0xffffffffu;
#endif
    if urp_lights_mesh(main_layers) {
        color += urp_lighting_physically_based(direct, main_color, shadow.x, lighting.main_light_dir.xyz, n, v, specular_off);
    }

#if defined(_ADDITIONAL_LIGHTS)
    let count = min(forward_lights.params.x, URP_MAX_ADDITIONAL_LIGHTS);
    for (var i = 0u; i < count; i++) {
        let light = forward_lights.lights[i];
        if urp_lights_mesh(light.layer_mask.x) {
            let a = urp_additional_light(light, p);
            // URP's light.distanceAttenuation * light.shadowAttenuation.
            let shadowed = a.w * urp_additional_light_shadow(i, p, a.xyz, camera.position.xyz);
#if defined(_LIGHT_COOKIES)
            // GetAdditionalLight (the per-pixel form; the per-vertex lights take no cookie and
            // no occlusion).
            let cookie_light = light.color.rgb * urp_additional_light_cookie(i, p);
#else
            let cookie_light = light.color.rgb;
#endif
#if defined(_SCREEN_SPACE_OCCLUSION)
            let light_color = cookie_light * direct_occlusion;
#else
            let light_color = cookie_light;
#endif
            color += urp_lighting_physically_based(direct, light_color, shadowed, a.xyz, n, v, specular_off);
        }
    }
#endif
#if defined(_ADDITIONAL_LIGHTS_VERTEX)
    color += in.vertex_lighting * b.diffuse;
#endif
    return vec4f(color + s.emission, 1.0);
}
