#shader universal_lit
// Unity URP's Lit shader: the UniversalGBuffer pass (docs/urp.md), the UniversalForward pass
// (docs/urp.md §11), the ShadowCaster pass (docs/urp.md §10) and the DepthOnly pass (docs/urp.md
// §13). Material
// keywords are shader_feature_local as in URP's Lit.shader; the pipeline keywords that change
// what the G-buffer pass writes are multi_compile. G-buffer: 2^10 · 2^6 = 65536 combinations, of which
// 49152 are variants: URP's mixed-lighting setup is one of None, ShadowMask and Subtractive
// (its `MixedLightingSetup` enum), so the pipeline never sets both keywords of the exclusion.

#pass UniversalGBuffer
#tag LightMode UniversalGBuffer
#tag UniversalMaterialType Lit
#pragma shader_feature_local _NORMALMAP
#pragma shader_feature_local _ALPHATEST_ON
#pragma shader_feature_local _EMISSION
#pragma shader_feature_local _METALLICSPECGLOSSMAP
#pragma shader_feature_local _SPECULAR_SETUP
#pragma shader_feature_local _OCCLUSIONMAP
#pragma shader_feature_local _SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A
#pragma shader_feature_local _RECEIVE_SHADOWS_OFF
#pragma shader_feature_local _SPECULARHIGHLIGHTS_OFF
#pragma shader_feature_local _ENVIRONMENTREFLECTIONS_OFF
#pragma multi_compile _ _GBUFFER_NORMALS_OCT
#pragma multi_compile _ _RENDER_PASS_ENABLED
#pragma multi_compile _ _WRITE_RENDERING_LAYERS
#pragma multi_compile _ _MIXED_LIGHTING_SUBTRACTIVE
#pragma multi_compile _ SHADOWS_SHADOWMASK
#pragma multi_compile _ LIGHTMAP_ON
#pragma exclude _MIXED_LIGHTING_SUBTRACTIVE SHADOWS_SHADOWMASK
#import universal/lit_gbuffer_pass
#endpass

#pass UniversalForward
#tag LightMode UniversalForward
// URP Lit's forward pass: the same material keywords; the pipeline keywords of the main
// light's shadow (none, one map, cascades, hard or soft; or the screen-space pass's texel),
// the additional lights (none, per vertex, per pixel) and their shadows, light layers, baked
// lighting (a lightmap, with subtractive mixing), light cookies and the screen-space
// occlusion. The additional lights' shadows and subtractive mixing change nothing without the
// keyword they refine (only the per-pixel lights read their shadows), so they require it:
// 1024 · 4 · 2 · (3 + 1) · 2 · 3 · 2 · 2 = 786432 variants. _SHADOWS_SOFT softens the main
// light's map or cascades and the additional lights' shadows, so it is declared on its own as
// URP declares it; a pairwise require cannot say
// "a main-light map, the cascades or additional shadows", and the variants where it changes
// nothing (no map read) are identical code, which audit's distinct count shows.
#pragma shader_feature_local _NORMALMAP
#pragma shader_feature_local _ALPHATEST_ON
#pragma shader_feature_local _EMISSION
#pragma shader_feature_local _METALLICSPECGLOSSMAP
#pragma shader_feature_local _SPECULAR_SETUP
#pragma shader_feature_local _OCCLUSIONMAP
#pragma shader_feature_local _SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A
#pragma shader_feature_local _RECEIVE_SHADOWS_OFF
#pragma shader_feature_local _SPECULARHIGHLIGHTS_OFF
#pragma shader_feature_local _ENVIRONMENTREFLECTIONS_OFF
#pragma multi_compile _ _MAIN_LIGHT_SHADOWS _MAIN_LIGHT_SHADOWS_CASCADE _MAIN_LIGHT_SHADOWS_SCREEN
#pragma multi_compile _ _SHADOWS_SOFT
#pragma multi_compile _ _ADDITIONAL_LIGHTS_VERTEX _ADDITIONAL_LIGHTS
#pragma multi_compile _ _ADDITIONAL_LIGHT_SHADOWS
#pragma multi_compile _ _LIGHT_LAYERS
#pragma multi_compile _ _MIXED_LIGHTING_SUBTRACTIVE
#pragma multi_compile _ LIGHTMAP_ON
#pragma multi_compile _ _LIGHT_COOKIES
#pragma multi_compile _ _SCREEN_SPACE_OCCLUSION
#pragma require _ADDITIONAL_LIGHT_SHADOWS _ADDITIONAL_LIGHTS
#pragma require _MIXED_LIGHTING_SUBTRACTIVE LIGHTMAP_ON
#import universal/lit_forward_pass
#endpass

#pass ShadowCaster
#tag LightMode ShadowCaster
// URP Lit's ShadowCaster: depth only; the smoothness-in-albedo-alpha keyword changes the alpha
// (so the cutout) only with _ALPHATEST_ON (without it, two pairs of variants render alike);
// _CASTING_PUNCTUAL_LIGHT_SHADOW biases along the direction to a point or spot light.
#pragma shader_feature_local _ALPHATEST_ON
#pragma shader_feature_local _SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A
#pragma multi_compile _ _CASTING_PUNCTUAL_LIGHT_SHADOW
#import universal/shadow_caster_pass
#endpass

#pass DepthOnly
#tag LightMode DepthOnly
// URP Lit's depth prepass: the camera's depth, the alpha test as in the ShadowCaster (the
// smoothness-in-albedo-alpha keyword matters only with _ALPHATEST_ON). URP's LOD cross-fade
// and instancing keywords are not built.
#pragma shader_feature_local _ALPHATEST_ON
#pragma shader_feature_local _SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A
#import universal/depth_only_pass
#endpass
