#shader standard
// Catlike Coding's "My First Lighting Shader" (Rendering 13, Deferred Shading), metallic workflow:
// a forward base pass (1536 variants), a forward add pass for each extra per-pixel light (1920)
// and a G-buffer pass for the deferred path (3072 variants). The program is
// standard/my_lighting; the passes differ only in their keyword sets and in which of
// FORWARD_BASE_PASS / FORWARD_ADD_PASS / DEFERRED_PASS they define.

#pass ForwardBase
#tag LightMode ForwardBase
#pragma shader_feature _ _RENDERING_CUTOUT _RENDERING_FADE _RENDERING_TRANSPARENT
#pragma shader_feature _METALLIC_MAP
#pragma shader_feature _ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC
#pragma shader_feature _NORMAL_MAP
#pragma shader_feature _OCCLUSION_MAP
#pragma shader_feature _EMISSION_MAP
#pragma shader_feature _DETAIL_MASK
#pragma shader_feature _DETAIL_ALBEDO_MAP
#pragma shader_feature _DETAIL_NORMAL_MAP
#define FORWARD_BASE_PASS
#import standard/my_lighting
#endpass

// One draw per extra pixel light, blended One / One onto the ForwardBase result (SrcAlpha / One
// with _RENDERING_FADE or _RENDERING_TRANSPARENT): the light's direct term only, no ambient,
// reflections or emission, so the occlusion and emission maps have no keyword here.
#pass ForwardAdd
#tag LightMode ForwardAdd
#pragma shader_feature _ _RENDERING_CUTOUT _RENDERING_FADE _RENDERING_TRANSPARENT
#pragma shader_feature _METALLIC_MAP
#pragma shader_feature _ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC
#pragma shader_feature _NORMAL_MAP
#pragma shader_feature _DETAIL_MASK
#pragma shader_feature _DETAIL_ALBEDO_MAP
#pragma shader_feature _DETAIL_NORMAL_MAP
#pragma multi_compile DIRECTIONAL DIRECTIONAL_COOKIE POINT POINT_COOKIE SPOT
#define FORWARD_ADD_PASS
#import standard/my_lighting
#endpass

#pass Deferred
#tag LightMode Deferred
#pragma exclude_renderers nomrt
#pragma shader_feature _RENDERING_CUTOUT
#pragma shader_feature _METALLIC_MAP
#pragma shader_feature _ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC
#pragma shader_feature _NORMAL_MAP
#pragma shader_feature _OCCLUSION_MAP
#pragma shader_feature _EMISSION_MAP
#pragma shader_feature _DETAIL_MASK
#pragma shader_feature _DETAIL_ALBEDO_MAP
#pragma shader_feature _DETAIL_NORMAL_MAP
#pragma multi_compile _ UNITY_HDR_ON
#pragma multi_compile _ UNITY_ENABLE_REFLECTION_BUFFERS
#define DEFERRED_PASS
#import standard/my_lighting
#endpass
