// universal/light_cookie: light cookies, the main light's and the additional lights' (docs/urp.md
// §9; URP's LightCookie.hlsl: ComputeLightCookieUVDirectional without wrapping,
// ComputeLightCookieUVSpot, ComputeLightCookieUVPoint, SampleMainLightCookie; LightCookieInput.hlsl's
// records and texture formats; SampleAdditionalLightCookie). A cookie tints the light's colour
// with a texture projected from the light. Read by the deferred lights (StencilDeferred's
// GetStencilLight multiplies the main light's colour by its cookie, and a point or spot light's
// by its rect of the additional lights' atlas) and by the forward pass's main and per-pixel
// lights (GetMainLight, GetAdditionalLight), under _LIGHT_COOKIES. Its bindings exist with _LIGHT_COOKIES (a pass keeps those its
// entry points reach):
//
//   group 0: 20 main_light_cookie (MainLightCookie),
//            21 main_light_cookie_texture (texture_2d<f32>),
//            22 main_light_cookie_sampler (the host's filter and address modes: URP binds the
//               cookie texture's own sampler and leaves the main light's coordinate unwrapped),
//            23 additional_light_cookies (AdditionalLightCookies),
//            24 additional_light_cookie_atlas (texture_2d<f32>: every additional light's cookie
//               in its own rect),
//            25 additional_light_cookie_sampler (the host's; URP's atlas is bilinear; the
//               coordinate never leaves the light's rect but on its edge)
//
// Provides:
//   fn urp_main_light_cookie(p: vec3f) -> vec3f
//       the colour the main light's cookie multiplies the light's by at world position p
//   fn urp_spot_light_cookie(light: u32, p: vec3f) -> vec3f
//   fn urp_point_light_cookie(light: u32, p: vec3f) -> vec3f
//       the colour additional light `light`'s cookie multiplies its colour by at p, the light
//       a spot (its perspective) or a point light (the octahedral map of the direction)
//   fn urp_additional_light_cookie(light: u32, p: vec3f) -> vec3f
//       the same by the light's type (SampleAdditionalLightCookie): white for an all-zero rect
//       (no cookie), the spot's projection for type 0, else the point light's (the forward
//       pass's additional lights are punctual)

#if defined(_LIGHT_COOKIES)
#import universal/gbuffer

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

// world_to_light[i]: URP's _AdditionalLightsWorldToLights (a spot's perspective, whose x, y
// over w run over [-1, 1] across the cone's square; a point light's world-to-local);
// atlas_uv_rect[i]: URP's _AdditionalLightsCookieAtlasUVRects, xy the rect's size and zw its
// offset in the atlas (all zero: the light has no cookie; the deferred passes draw such a light
// without _LIGHT_COOKIES); light_type[i].x: URP's _AdditionalLightsLightTypes (0 spot,
// 1 directional, 2 point); format.x: URP's _AdditionalLightsCookieAtlasTextureFormat. Eight
// lights, as the forward pass's.
struct AdditionalLightCookies {
    world_to_light: array<mat4x4f, 8>,
    atlas_uv_rect: array<vec4f, 8>,
    light_type: array<vec4f, 8>,
    format: vec4f,
}

@group(0) @binding(23) var<uniform> additional_light_cookies: AdditionalLightCookies;
@group(0) @binding(24) var additional_light_cookie_atlas: texture_2d<f32>;
@group(0) @binding(25) var additional_light_cookie_sampler: sampler;

fn urp_main_light_cookie(p: vec3f) -> vec3f {
    // ComputeLightCookieUVDirectional: light space x, y from [-1, 1] to [0, 1]; the whole
    // texture (atlas rect (1, 1, 0, 0)), no wrapping in the shader.
    let uv = (main_light_cookie.world_to_light * vec4f(p, 1.0)).xy * 0.5 + 0.5;
    let texel = textureSampleLevel(main_light_cookie_texture, main_light_cookie_sampler, uv, 0.0);
    return urp_cookie_color(texel, main_light_cookie.format.x);
}
// The colour of additional light `light`'s cookie at uv in [0, 1]^2 of its rect.
fn urp_additional_light_cookie_at(light: u32, uv: vec2f) -> vec3f {
    let rect = additional_light_cookies.atlas_uv_rect[light];
    let texel = textureSampleLevel(additional_light_cookie_atlas, additional_light_cookie_sampler, rect.xy * uv + rect.zw, 0.0);
    return urp_cookie_color(texel, additional_light_cookies.format.x);
}

// ComputeLightCookieUVSpot: the light's clip position's x, y over w from [-1, 1] to [0, 1],
// clamped.
fn urp_spot_light_cookie(light: u32, p: vec3f) -> vec3f {
    let q = additional_light_cookies.world_to_light[light] * vec4f(p, 1.0);
    return urp_additional_light_cookie_at(light, saturate(q.xy / q.w * 0.5 + 0.5));
}

// ComputeLightCookieUVPoint: the octahedral quad code of the light-space direction to p, from
// [-1, 1] to [0, 1], clamped.
fn urp_point_light_cookie(light: u32, p: vec3f) -> vec3f {
    let q = additional_light_cookies.world_to_light[light] * vec4f(p, 1.0);
    let dir = normalize(q.xyz / q.w);
    return urp_additional_light_cookie_at(light, saturate(urp_oct_encode(dir) * 0.5 + 0.5));
}

fn urp_additional_light_cookie(light: u32, p: vec3f) -> vec3f {
    if all(additional_light_cookies.atlas_uv_rect[light] == vec4f(0.0)) {
        return vec3f(1.0);
    }
    if additional_light_cookies.light_type[light].x == 0.0 {
        return urp_spot_light_cookie(light, p);
    }
    return urp_point_light_cookie(light, p);
}
#endif
