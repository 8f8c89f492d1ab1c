#shader standard
// Catlike Coding's "My First Lighting Shader" (Rendering 13, Deferred Shading), metallic workflow,
// lit with Unity's Standard BRDF in its three tiers: a forward base pass (9216 variants), a
// forward add pass for each extra per-pixel light (18432), a G-buffer pass for the deferred path
// (18432 variants) and the shadow caster (8). The program is
// standard/my_lighting; the lit passes differ only in their keyword sets and in which of
// FORWARD_BASE_PASS / FORWARD_ADD_PASS / DEFERRED_PASS they define. The caster is
// standard/shadow_caster.

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
// Unity's multi_compile_fwdbase, of which the main directional light's screen-space shadow.
#pragma multi_compile _ SHADOWS_SCREEN
// Unity's Standard BRDF per graphics tier (UNITY_PBS_USE_BRDF1/2/3, which Unity's tier settings
// select; docs/shading.md §5): no keyword is BRDF1, the desktop tiers' choice.
#pragma multi_compile _ UNITY_PBS_USE_BRDF2 UNITY_PBS_USE_BRDF3
// Unity's lightmap keywords (multi_compile_fwdbase / multi_compile_prepassfinal): the baked
// lightmap, its directional map, the realtime (Enlighten) lightmap (docs/shading.md §14).
// DIRLIGHTMAP_COMBINED needs a lightmap; `require` takes the baked one (Unity also builds it
// with the realtime lightmap alone, a departure stated in §9).
#pragma multi_compile _ LIGHTMAP_ON
#pragma multi_compile _ DIRLIGHTMAP_COMBINED
#pragma multi_compile _ DYNAMICLIGHTMAP_ON
#pragma require DIRLIGHTMAP_COMBINED LIGHTMAP_ON
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
// Unity's multi_compile_fwdadd_fullshadows: the lighting pass's shadow keywords and pairings.
#pragma multi_compile _ SHADOWS_DEPTH SHADOWS_CUBE SHADOWS_SCREEN
#pragma multi_compile _ SHADOWS_SOFT
#pragma exclude SHADOWS_SCREEN POINT
#pragma exclude SHADOWS_SCREEN POINT_COOKIE
#pragma exclude SHADOWS_SCREEN SPOT
#pragma exclude SHADOWS_DEPTH POINT
#pragma exclude SHADOWS_DEPTH POINT_COOKIE
#pragma exclude SHADOWS_DEPTH DIRECTIONAL
#pragma exclude SHADOWS_DEPTH DIRECTIONAL_COOKIE
#pragma exclude SHADOWS_CUBE SPOT
#pragma exclude SHADOWS_CUBE DIRECTIONAL
#pragma exclude SHADOWS_CUBE DIRECTIONAL_COOKIE
#pragma exclude SHADOWS_SOFT DIRECTIONAL
#pragma exclude SHADOWS_SOFT DIRECTIONAL_COOKIE
#pragma multi_compile _ UNITY_PBS_USE_BRDF2 UNITY_PBS_USE_BRDF3
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
// Unity's multi_compile_prepassfinal shadowmask keyword (the Shadowmask and Distance Shadowmask
// lighting modes): a fifth target, RT4, holds the object's baked occlusion of up to four lights.
#pragma multi_compile _ SHADOWS_SHADOWMASK
// The tier changes the indirect specular only, so with UNITY_ENABLE_REFLECTION_BUFFERS its
// variants are duplicates (as Unity builds them).
#pragma multi_compile _ UNITY_PBS_USE_BRDF2 UNITY_PBS_USE_BRDF3
// Unity's lightmap keywords (multi_compile_fwdbase / multi_compile_prepassfinal): the baked
// lightmap, its directional map, the realtime (Enlighten) lightmap (docs/shading.md §14).
// DIRLIGHTMAP_COMBINED needs a lightmap; `require` takes the baked one (Unity also builds it
// with the realtime lightmap alone, a departure stated in §9).
#pragma multi_compile _ LIGHTMAP_ON
#pragma multi_compile _ DIRLIGHTMAP_COMBINED
#pragma multi_compile _ DYNAMICLIGHTMAP_ON
#pragma require DIRLIGHTMAP_COMBINED LIGHTMAP_ON
#define DEFERRED_PASS
#import standard/my_lighting
#endpass

// Renders the shadow maps (Unity's multi_compile_shadowcaster: SHADOWS_DEPTH SHADOWS_CUBE) with
// the camera binding set to the light's: depth only for a spot's 2D map; for a point light's
// cube, each face writes |p - light| / range (docs/shading.md §11). Of the material keywords
// only those that change which fragments are discarded: _RENDERING_CUTOUT, and
// _SMOOTHNESS_ALBEDO (main_tex.a is smoothness, not alpha). Without cutout the latter changes
// nothing (2 duplicate variants, as Unity would build them).
#pass ShadowCaster
#tag LightMode ShadowCaster
#pragma shader_feature _RENDERING_CUTOUT
#pragma shader_feature _SMOOTHNESS_ALBEDO
#pragma multi_compile SHADOWS_DEPTH SHADOWS_CUBE
#define SHADOW_CASTER_PASS
#import standard/shadow_caster
#endpass
