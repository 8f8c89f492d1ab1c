// lighting/lightmap: Unity's baked and realtime lightmaps as the built-in ForwardBase and Deferred
// passes read them (docs/shading.md §14). Pure functions, no bindings; standard/bindings binds
// the lightmaps and standard/my_lighting composes the indirect diffuse light from them.
//
// The Lightmap record is laid out for a uniform buffer (4 × vec4f = 64 bytes):
//   st              Unity's unity_LightmapST: lightmap uv = uv · st.xy + st.zw (LIGHTMAP_ON)
//   dynamic_st      unity_DynamicLightmapST, the same for the realtime lightmap (DYNAMICLIGHTMAP_ON)
//   decode          unity_Lightmap_HDR, the baked lightmap's decode instructions (x, y, _, w):
//                   rgb · (x · α^y), α = w · (a - 1) + 1 (deferred/probe's RGBM decode): RGBM
//                   (34.49, 2.2, 0, 1) in linear colour space, HDR (1, 1, 0, 0), dLDR (4.59, 1, 0, 0)
//   dynamic_decode  unity_DynamicLightmap_HDR: realtime rgb = pow(x · a · rgb, y)
//
// Provides:
//   struct Lightmap
//   fn lightmap_decode_realtime(texel: vec4f, decode: vec4f) -> vec3f   Unity's DecodeRealtimeLightmap
//   fn lightmap_directional(color: vec3f, dir: vec4f, n: vec3f) -> vec3f   Unity's
//       DecodeDirectionalLightmap: color · (dot(n, dir.xyz - 0.5) + 0.5) / max(1e-4, dir.w)

struct Lightmap {
    st: vec4f,
    dynamic_st: vec4f,
    decode: vec4f,
    dynamic_decode: vec4f,
}

// The realtime (Enlighten) lightmap: pow((x · a) · rgb, y) per channel.
fn lightmap_decode_realtime(texel: vec4f, decode: vec4f) -> vec3f {
    return pow((decode.x * texel.a) * texel.rgb, vec3f(decode.y));
}

// The directional lightmap's half-Lambert term over its "rebalancing coefficient" dir.w; the
// direction dir.xyz - 0.5 is not unit length on purpose (its length is the directionality).
fn lightmap_directional(color: vec3f, dir: vec4f, n: vec3f) -> vec3f {
    let half_lambert = dot(n, dir.xyz - 0.5) + 0.5;
    return color * half_lambert / max(1e-4, dir.w);
}
