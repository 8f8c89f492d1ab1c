// standard/bindings: the resources of the standard shader's passes (ForwardBase, ForwardAdd,
// Deferred). Binding numbers are stable across variants; a keyword that is off removes its
// texture binding entirely, the probes are bound only where the pass samples them (ForwardBase,
// and Deferred without UNITY_ENABLE_REFLECTION_BUFFERS), the ambient + main light only where it
// is used (ForwardBase, Deferred), and the per-pixel light only in ForwardAdd. ShadowCaster
// binds the camera (the light's view), the material, main_tex and the object.
//
//   group 0: 0 camera, 1 lighting, 2 probes, 3 probe_cube0, 4 probe_cube1, 5 probe_sampler,
//            6-15 the per-pixel light and its shadow (ForwardAdd; lighting/light_bindings),
//            15 screen_shadow (ForwardBase's main light with SHADOWS_SCREEN; lighting/screen_shadow),
//            17 brdf_lut (ForwardBase and ForwardAdd with UNITY_PBS_USE_BRDF3; lighting/brdf_lut),
//            18 shadow_fade (ForwardAdd with a realtime shadow keyword, ForwardBase with
//               SHADOWS_SCREEN; lighting/shadow_fade)
//   group 1: 0 material, 1 material_sampler, 2 main_tex, 3 metallic_map (_METALLIC_MAP),
//            4 normal_map (_NORMAL_MAP), 5 occlusion_map (_OCCLUSION_MAP),
//            6 emission_map (_EMISSION_MAP), 7 detail_mask (_DETAIL_MASK),
//            8 detail_albedo (_DETAIL_ALBEDO_MAP), 9 detail_normal (_DETAIL_NORMAL_MAP)
//   group 2: 0 object, 1 shadowmask_map (Deferred with SHADOWS_SHADOWMASK: the object's baked
//            occlusion, Unity's unity_ShadowMask, sampled with material_sampler at the uv, or
//            at the lightmap uv with LIGHTMAP_ON),
//            2 lightmap (Lightmap; LIGHTMAP_ON or DYNAMICLIGHTMAP_ON; lighting/lightmap),
//            3 lightmap_tex (LIGHTMAP_ON: Unity's unity_Lightmap),
//            4 lightmap_dir (LIGHTMAP_ON with DIRLIGHTMAP_COMBINED: unity_LightmapInd),
//            5 dynamic_lightmap (DYNAMICLIGHTMAP_ON: unity_DynamicLightmap),
//            6 dynamic_lightmap_dir (DYNAMICLIGHTMAP_ON with DIRLIGHTMAP_COMBINED:
//              unity_DynamicDirectionality),
//            7 lightmap_sampler (LIGHTMAP_ON or DYNAMICLIGHTMAP_ON; Unity filters bilinearly)

#import deferred/probe
#if defined(LIGHTMAP_ON) || defined(DYNAMICLIGHTMAP_ON)
#import lighting/lightmap
#endif

struct Camera {
    view_proj: mat4x4f,
    position: vec4f,
}

// Unity's unity_SHAr/g/b (L0+L1) and one directional light; light_dir is the unit direction
// TO the light (w unused), light_color.rgb its colour (a unused).
struct Lighting {
    sh_r: vec4f,
    sh_g: vec4f,
    sh_b: vec4f,
    light_dir: vec4f,
    light_color: vec4f,
}

struct Probes {
    probe0: Probe,
    probe1: Probe,
}

struct Material {
    tint: vec4f,        // Unity _Color
    emission: vec4f,    // rgb
    params: vec4f,      // x metallic, y smoothness, z cutoff, w occlusion_strength
    bump: vec4f,        // x bump_scale, y detail_bump_scale
    detail_st: vec4f,   // xy detail tiling, zw detail offset
}

struct Object {
    model: mat4x4f,
    normal_matrix: mat4x4f,
}

@group(0) @binding(0) var<uniform> camera: Camera;
#if defined(FORWARD_BASE_PASS) || defined(DEFERRED_PASS)
@group(0) @binding(1) var<uniform> lighting: Lighting;
#endif
#if defined(FORWARD_BASE_PASS) || (defined(DEFERRED_PASS) && !UNITY_ENABLE_REFLECTION_BUFFERS)
@group(0) @binding(2) var<uniform> probes: Probes;
@group(0) @binding(3) var probe_cube0: texture_cube<f32>;
@group(0) @binding(4) var probe_cube1: texture_cube<f32>;
@group(0) @binding(5) var probe_sampler: sampler;
#endif

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var material_sampler: sampler;
@group(1) @binding(2) var main_tex: texture_2d<f32>;
#if defined(_METALLIC_MAP)
@group(1) @binding(3) var metallic_map: texture_2d<f32>;
#endif
#if defined(_NORMAL_MAP)
@group(1) @binding(4) var normal_map: texture_2d<f32>;
#endif
#if defined(_OCCLUSION_MAP)
@group(1) @binding(5) var occlusion_map: texture_2d<f32>;
#endif
#if defined(_EMISSION_MAP)
@group(1) @binding(6) var emission_map: texture_2d<f32>;
#endif
#if defined(_DETAIL_MASK)
@group(1) @binding(7) var detail_mask: texture_2d<f32>;
#endif
#if defined(_DETAIL_ALBEDO_MAP)
@group(1) @binding(8) var detail_albedo: texture_2d<f32>;
#endif
#if defined(_DETAIL_NORMAL_MAP)
@group(1) @binding(9) var detail_normal: texture_2d<f32>;
#endif

@group(2) @binding(0) var<uniform> object: Object;
#if defined(DEFERRED_PASS) && defined(SHADOWS_SHADOWMASK)
@group(2) @binding(1) var shadowmask_map: texture_2d<f32>;
#endif
#if defined(LIGHTMAP_ON) || defined(DYNAMICLIGHTMAP_ON)
@group(2) @binding(2) var<uniform> lightmap: Lightmap;
@group(2) @binding(7) var lightmap_sampler: sampler;
#endif
#if defined(LIGHTMAP_ON)
@group(2) @binding(3) var lightmap_tex: texture_2d<f32>;
#endif
#if defined(LIGHTMAP_ON) && defined(DIRLIGHTMAP_COMBINED)
@group(2) @binding(4) var lightmap_dir: texture_2d<f32>;
#endif
#if defined(DYNAMICLIGHTMAP_ON)
@group(2) @binding(5) var dynamic_lightmap: texture_2d<f32>;
#endif
#if defined(DYNAMICLIGHTMAP_ON) && defined(DIRLIGHTMAP_COMBINED)
@group(2) @binding(6) var dynamic_lightmap_dir: texture_2d<f32>;
#endif
