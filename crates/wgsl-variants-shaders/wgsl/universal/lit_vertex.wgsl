// universal/lit_vertex: the vertex stage URP Lit's UniversalGBuffer and UniversalForward passes
// share (URP's LitGBufferPass.hlsl / LitForwardPass.hlsl LitPassVertex; docs/urp.md).
//
// Provides:
//   struct UrpVertexInput    position @0, normal @1, tangent @2, uv @3, lightmap uv @4 (LIGHTMAP_ON)
//   struct UrpVertexOutput   world position, normal, tangent, uv, lightmap uv (LIGHTMAP_ON),
//                            per-vertex additional lights @5 (_ADDITIONAL_LIGHTS_VERTEX, written
//                            by the forward pass's entry point)
//   fn urp_vertex(in: UrpVertexInput) -> UrpVertexOutput

#import universal/bindings

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
#if defined(_ADDITIONAL_LIGHTS_VERTEX)
    @location(5) vertex_lighting: vec3f,
#endif
}

// Everything but the per-vertex lights: the world position, the unit world normal, the world
// tangent (w: the bitangent sign), the uvs.
fn urp_vertex(in: UrpVertexInput) -> UrpVertexOutput {
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
