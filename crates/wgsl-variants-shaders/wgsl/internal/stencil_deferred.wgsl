#shader stencil_deferred
// URP's StencilDeferred lighting (Hidden/Universal Render Pipeline/StencilDeferred; docs/urp.md
// §9): after universal_lit's UniversalGBuffer pass, one draw per light adds its direct light to
// GBuffer3 (Rg11b10Ufloat, blend One One), reading GBuffer0-2 and the depth buffer. Point and
// spot lights are drawn as their volumes (vs_volume) after a stencil pass marks the pixels inside
// (internal/stencil_write's vertex stage with URP's stencil ops, docs/urp.md §9), and test the
// stencil's material-type bits (Lit = 0b01 << 5); directional lights cover the screen (vs_main)
// and blend One SrcAlpha. The program is universal/stencil_deferred_pass; each pass is one of
// URP's. _SCREEN_SPACE_OCCLUSION (URP's SSAO renderer feature, docs/urp.md §14): the direct
// occlusion dims every light; the indirect one scales GBuffer3 once, through the first
// directional light (_DEFERRED_FIRST_LIGHT) or, in a frame without one, the SSAOOnly pass.

#pass PunctualLit
#tag UniversalMaterialType Lit
// _ADDITIONAL_LIGHT_SHADOWS: the light's shadow from the additional lights' atlas; soft per
// light under _SHADOWS_SOFT, which changes nothing without it (URP strips those variants).
// _LIGHT_COOKIES: the light's colour times its cookie, its rect of the additional lights' atlas.
// _SCREEN_SPACE_OCCLUSION: the light times the direct occlusion at the pixel.
#pragma multi_compile _POINT _SPOT
#pragma multi_compile _ _ADDITIONAL_LIGHT_SHADOWS
#pragma multi_compile _ _SHADOWS_SOFT
#pragma multi_compile _ _GBUFFER_NORMALS_OCT
#pragma multi_compile _ _LIGHT_LAYERS
#pragma multi_compile _ _LIGHT_COOKIES
#pragma multi_compile _ _SCREEN_SPACE_OCCLUSION
#pragma require _SHADOWS_SOFT _ADDITIONAL_LIGHT_SHADOWS
#import universal/stencil_deferred_pass
#endpass

#pass DirectionalLit
#tag UniversalMaterialType Lit
// _DEFERRED_MAIN_LIGHT: this draw is the frame's main light (its own uniform, its shadows and
// its cookie); the main light's shadow keywords and _LIGHT_COOKIES change nothing without it
// (URP's other directional lights take no cookie here), so they require it (URP strips those
// variants instead). _DEFERRED_FIRST_LIGHT: the first directional light drawn, which also
// applies the indirect occlusion to GBuffer3 (its alpha); it changes nothing without
// _SCREEN_SPACE_OCCLUSION, so it requires it.
#pragma multi_compile _DIRECTIONAL
#pragma multi_compile _ _DEFERRED_MAIN_LIGHT
#pragma multi_compile _ _MAIN_LIGHT_SHADOWS _MAIN_LIGHT_SHADOWS_CASCADE _MAIN_LIGHT_SHADOWS_SCREEN
#pragma multi_compile _ _SHADOWS_SOFT
#pragma multi_compile _ _GBUFFER_NORMALS_OCT
#pragma multi_compile _ _LIGHT_LAYERS
#pragma multi_compile _ _LIGHT_COOKIES
#pragma multi_compile _ _SCREEN_SPACE_OCCLUSION
#pragma multi_compile _ _DEFERRED_FIRST_LIGHT
#pragma require _DEFERRED_FIRST_LIGHT _SCREEN_SPACE_OCCLUSION
#pragma require _LIGHT_COOKIES _DEFERRED_MAIN_LIGHT
#pragma require _MAIN_LIGHT_SHADOWS _DEFERRED_MAIN_LIGHT
#pragma require _MAIN_LIGHT_SHADOWS_CASCADE _DEFERRED_MAIN_LIGHT
#pragma require _MAIN_LIGHT_SHADOWS_SCREEN _DEFERRED_MAIN_LIGHT
#pragma require _SHADOWS_SOFT _MAIN_LIGHT_SHADOWS _MAIN_LIGHT_SHADOWS_CASCADE
#import universal/stencil_deferred_pass
#endpass

#pass SSAOOnly
// URP's "SSAOOnly": the indirect occlusion applied to GBuffer3 before the lights where no
// directional light will (universal/ssao_only_pass); full screen, blend One SrcAlpha, no
// stencil test. Without _SCREEN_SPACE_OCCLUSION it draws nothing (URP's _SSAO_ONLY vertex
// keyword is this pass itself).
#pragma multi_compile _ _SCREEN_SPACE_OCCLUSION
#import universal/ssao_only_pass
#endpass
