// universal/stencil_deferred_pass: the fragment program of URP's StencilDeferred lighting passes
// (internal/stencil_deferred; URP's StencilDeferred.shader DeferredShading, docs/urp.md §9): one
// light added to GBuffer3 from GBuffer0-2 and the depth buffer.
//
//   group 0: 0 gbuffer0 (the Rgba8UnormSrgb target: reads linear albedo), 1 gbuffer1,
//            2 gbuffer2 (Rgba8Unorm with _GBUFFER_NORMALS_OCT, else Rgba8Snorm),
//            3 depth (R32Float copy of the depth buffer), 4 camera (DeferredCamera),
//            5 light (UrpLight; the additional light this draw shades),
//            6 rendering_layers (texture_2d<u32>, the G-buffer's R32Uint target; _LIGHT_LAYERS),
//            7 main_light (UrpLight; _DEFERRED_MAIN_LIGHT: the frame's main light),
//            8 shadow_light_index (vec4u, x: URP's _ShadowLightIndex, this light's record in
//              additional_shadows; _ADDITIONAL_LIGHT_SHADOWS),
//            10-16 the main light's shadow (universal/main_light_shadow: _MAIN_LIGHT_SHADOWS,
//               _MAIN_LIGHT_SHADOWS_CASCADE or _MAIN_LIGHT_SHADOWS_SCREEN; the sampler nearest,
//               LessEqual, clamp to edge),
//            17-19 the additional lights' shadows (universal/additional_light_shadow:
//               _ADDITIONAL_LIGHT_SHADOWS),
//            9 cookie_light_index (vec4u, x: URP's _CookieLightIndex, this light's record in
//              additional_light_cookies; _LIGHT_COOKIES without _DEFERRED_MAIN_LIGHT),
//            20-22 the main light's cookie (universal/light_cookie: _LIGHT_COOKIES with
//               _DEFERRED_MAIN_LIGHT),
//            23-25 the additional lights' cookie atlas (universal/light_cookie: _LIGHT_COOKIES
//               with _POINT or _SPOT),
//            26 ambient_occlusion_params (vec4f, URP's _AmbientOcclusionParam: w the SSAO's
//               direct lighting strength; _SCREEN_SPACE_OCCLUSION),
//            27 the screen-space occlusion (universal/ambient_occlusion: _SCREEN_SPACE_OCCLUSION)
// All G-buffer reads are textureLoad at the fragment's pixel.
//
// Provides the entry points:
//   @vertex   vs_main    a full-screen triangle (directional lights; volumes crossing the near plane)
//   @vertex   vs_volume  the light's volume (world positions at @location(0))
//   @fragment fs_main    -> @location(0) the light (rgb) and what GBuffer3 keeps (a): the host
//                        blends a punctual light One One and a directional one One SrcAlpha
//                        (URP's), so a is 1 but under _DEFERRED_FIRST_LIGHT with
//                        _SCREEN_SPACE_OCCLUSION, where it is the indirect occlusion's ratio

#import internal/fullscreen
#import deferred/depth
#import universal/gbuffer
#import universal/lighting
#import universal/main_light_shadow
#import universal/additional_light_shadow
#import universal/light_cookie
#import universal/ambient_occlusion

@group(0) @binding(0) var gbuffer0: texture_2d<f32>;
@group(0) @binding(1) var gbuffer1: texture_2d<f32>;
@group(0) @binding(2) var gbuffer2: texture_2d<f32>;
@group(0) @binding(3) var depth_tex: texture_2d<f32>;
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;
#if !defined(_DEFERRED_MAIN_LIGHT)
@group(0) @binding(5) var<uniform> light: UrpLight;
#endif
#if defined(_LIGHT_LAYERS)
@group(0) @binding(6) var rendering_layers: texture_2d<u32>;
#endif
#if defined(_DEFERRED_MAIN_LIGHT)
@group(0) @binding(7) var<uniform> main_light: UrpLight;
#endif
#if defined(_ADDITIONAL_LIGHT_SHADOWS)
@group(0) @binding(8) var<uniform> shadow_light_index: vec4u;
#endif
#if defined(_LIGHT_COOKIES) && !defined(_DEFERRED_MAIN_LIGHT)
@group(0) @binding(9) var<uniform> cookie_light_index: vec4u;
#endif
#if defined(_SCREEN_SPACE_OCCLUSION)
@group(0) @binding(26) var<uniform> ambient_occlusion_params: vec4f;
#endif

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@vertex
fn vs_volume(@location(0) world_position: vec3f) -> @builtin(position) vec4f {
    return deferred_camera.view_proj * vec4f(world_position, 1.0);
}

// The main light's shadow (universal/main_light_shadow) or a punctual light's
// (universal/additional_light_shadow; to_light: the unit direction to it), 1 for a texel whose
// material says ReceiveShadowsOff.
fn urp_deferred_shadow(p: vec3f, pixel: vec2i, flags: u32, to_light: vec3f) -> f32 {
    if (flags & URP_FLAG_RECEIVE_SHADOWS_OFF) != 0u {
        return 1.0;
    }
#if defined(_MAIN_LIGHT_SHADOWS) || defined(_MAIN_LIGHT_SHADOWS_CASCADE) || defined(_MAIN_LIGHT_SHADOWS_SCREEN)
    return urp_main_light_shadow(p, deferred_camera.position.xyz, pixel).x;
#elif defined(_ADDITIONAL_LIGHT_SHADOWS)
    return urp_additional_light_shadow(shadow_light_index.x, p, to_light, deferred_camera.position.xyz);
#else
    return 1.0;
#endif
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let pixel = fullscreen_pixel(frag_position);
#if defined(_DEFERRED_MAIN_LIGHT)
    let l = main_light;
#else
    let l = light;
#endif
#if defined(_LIGHT_LAYERS)
    // Not a discard: URP's pass must still clear the stencil bit of this pixel. URP returns
    // before the occlusion, so GBuffer3 is kept whole (alpha 1) here.
    if (l.layer_mask.x & textureLoad(rendering_layers, pixel, 0).r) == 0u {
        return vec4f(0.0, 0.0, 0.0, 1.0);
    }
#endif
    let g0 = textureLoad(gbuffer0, pixel, 0);
    let g1 = textureLoad(gbuffer1, pixel, 0);
    let g2 = textureLoad(gbuffer2, pixel, 0);
    let p = depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel);
    let flags = urp_unpack_flags(g0.a);

#if defined(_DIRECTIONAL)
    let s = vec4f(l.direction.xyz, 1.0);
#elif defined(_SPOT)
    var s = urp_punctual_sample(l, p);
    s.w *= urp_angle_attenuation(l.direction.xyz, s.xyz, l.attenuation.zw);
#else
    // _POINT: no cone (URP's angle term is 1 for a point light's attenuation (0, 1)).
    let s = urp_punctual_sample(l, p);
#endif
    let attenuation = s.w * urp_deferred_shadow(p, pixel, flags, s.xyz);
#if defined(_DEFERRED_MAIN_LIGHT) && defined(_LIGHT_COOKIES)
    // GetStencilLight: the main light's colour times its cookie.
    let cookie_color = l.color.rgb * urp_main_light_cookie(p);
#elif defined(_SPOT) && defined(_LIGHT_COOKIES)
    // A punctual light's colour times its rect of the atlas (no all-zero test: the keyword
    // says the light has a cookie).
    let cookie_color = l.color.rgb * urp_spot_light_cookie(cookie_light_index.x, p);
#elif defined(_POINT) && defined(_LIGHT_COOKIES)
    let cookie_color = l.color.rgb * urp_point_light_cookie(cookie_light_index.x, p);
#else
    let cookie_color = l.color.rgb;
#endif
    // The direct occlusion dims the light; the first directional light also scales what the
    // G-buffer pass left in GBuffer3 (its alpha, blended One SrcAlpha).
#if defined(_SCREEN_SPACE_OCCLUSION)
    let ssao = urp_screen_space_ambient_occlusion(pixel);
    let color = cookie_color * urp_direct_occlusion(ssao, ambient_occlusion_params.w);
#else
    let color = cookie_color;
#endif
#if defined(_DIRECTIONAL) && defined(_DEFERRED_FIRST_LIGHT) && defined(_SCREEN_SPACE_OCCLUSION)
    let alpha = urp_deferred_indirect_occlusion(ssao, g1.a);
#else
    let alpha = 1.0;
#endif
    let brdf = urp_brdf_from_gbuffer(g0.rgb, g1.rgb, g2.a, (flags & URP_FLAG_SPECULAR_SETUP) != 0u);
    let n = urp_unpack_normal(g2.rgb);
    let v = urp_safe_normalize(deferred_camera.position.xyz - p);
    let c = urp_lighting_physically_based(brdf, color, attenuation, s.xyz, n, v, (flags & URP_FLAG_SPECULAR_HIGHLIGHTS_OFF) != 0u);
    return vec4f(c, alpha);
}
