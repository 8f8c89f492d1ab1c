// universal/light_cookie: the main light's cookie (docs/urp.md §9; URP's LightCookie.hlsl:
// ComputeLightCookieUVDirectional without wrapping and SampleMainLightCookie, with
// LightCookieInput.hlsl's texture formats). A cookie tints the light's colour with the texture
// projected along the light. Read by the deferred main light (StencilDeferred's
// GetStencilLight multiplies the main light's colour by it under _LIGHT_COOKIES); its bindings
// exist with _LIGHT_COOKIES:
//
//   group 0: 20 main_light_cookie (MainLightCookie),
//            21 main_light_cookie_texture (texture_2d<f32>),
//            22 main_light_cookie_sampler (the host's filter and address modes: URP binds the
//               cookie texture's own sampler and leaves the main light's coordinate unwrapped)
//
// Provides:
//   fn urp_main_light_cookie(p: vec3f) -> vec3f
//       the colour the main light's cookie multiplies the light's by at world position p

#if defined(_LIGHT_COOKIES)
// world_to_light: URP's _MainLightWorldToLight, the light's world-to-local transform with an
// orthographic projection of the cookie's size and offset (light space x, y in [-1, 1] over
// the cookie); format.x: URP's _MainLightCookieTextureFormat (0 RGB, 1 alpha, 2 red).
struct MainLightCookie {
    world_to_light: mat4x4f,
    format: vec4f,
}

@group(0) @binding(20) var<uniform> main_light_cookie: MainLightCookie;
@group(0) @binding(21) var main_light_cookie_texture: texture_2d<f32>;
@group(0) @binding(22) var main_light_cookie_sampler: sampler;

// The texel's colour as the cookie's format reads it: rgb, the alpha or the red channel alone.
fn urp_cookie_color(texel: vec4f, format: f32) -> vec3f {
    if format == 1.0 {
        return texel.aaa;
    }
    if format == 2.0 {
        return texel.rrr;
    }
    return texel.rgb;
}

fn urp_main_light_cookie(p: vec3f) -> vec3f {
    // ComputeLightCookieUVDirectional: light space x, y from [-1, 1] to [0, 1]; the whole
    // texture (atlas rect (1, 1, 0, 0)), no wrapping in the shader.
    let uv = (main_light_cookie.world_to_light * vec4f(p, 1.0)).xy * 0.5 + 0.5;
    let texel = textureSampleLevel(main_light_cookie_texture, main_light_cookie_sampler, uv, 0.0);
    return urp_cookie_color(texel, main_light_cookie.format.x);
}
#endif
