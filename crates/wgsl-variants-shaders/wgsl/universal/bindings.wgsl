// universal/bindings: the resources of URP's Lit UniversalGBuffer pass. Binding numbers are
// stable across variants; a keyword that is off removes the bindings only it uses.
//
//   group 0: 0 camera, 1 lighting,
//            2 environment (cube), 3 environment_sampler   (without _ENVIRONMENTREFLECTIONS_OFF)
//   group 1: 0 material, 1 material_sampler, 2 base_map, 3 bump_map (_NORMALMAP),
//            4 metallic_gloss_map (_METALLICSPECGLOSSMAP: URP's _MetallicGlossMap, or
//              _SpecGlossMap with _SPECULAR_SETUP), 5 occlusion_map (_OCCLUSIONMAP),
//            6 emission_map (_EMISSION)
//   group 2: 0 object, 1 lightmap, 2 shadowmask_map, 3 lightmap_sampler   (1-3: LIGHTMAP_ON;
//            2 only with SHADOWS_SHADOWMASK too)

struct Camera {
    view_proj: mat4x4f,
    position: vec4f,
}

// unity_SHAr/g/b (L0 + L1); the main light (direction TO the light, colour); the main light's
// shadow attenuation at this object (x, a stand-in for a shadow-map sample) and strength (y);
// _SubtractiveShadowColor; _GlossyEnvironmentColor; unity_ProbesOcclusion; URP's
// _AmbientOcclusionParam (w: the SSAO feature's direct lighting strength, which the forward pass
// reads under _SCREEN_SPACE_OCCLUSION; the deferred passes, which bind no Lighting, take it at
// their own binding: universal/ambient_occlusion).
struct Lighting {
    sh_r: vec4f,
    sh_g: vec4f,
    sh_b: vec4f,
    main_light_dir: vec4f,
    main_light_color: vec4f,
    main_light_shadow: vec4f,
    subtractive_shadow_color: vec4f,
    glossy_environment_color: vec4f,
    probes_occlusion: vec4f,
    ambient_occlusion_params: vec4f,
}

// URP Lit's properties: _BaseColor, _SpecColor (rgb), _EmissionColor (rgb);
// params: x _Metallic, y _Smoothness, z _Cutoff, w _BumpScale; extra: x _OcclusionStrength.
struct Material {
    base_color: vec4f,
    spec_color: vec4f,
    emission_color: vec4f,
    params: vec4f,
    extra: vec4f,
}

// model and normal matrices; unity_LightmapST (xy scale, zw offset); the mesh's rendering
// layer mask (x) for _WRITE_RENDERING_LAYERS.
struct Object {
    model: mat4x4f,
    normal_matrix: mat4x4f,
    lightmap_st: vec4f,
    rendering_layers: vec4u,
}

@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var<uniform> lighting: Lighting;
#if !defined(_ENVIRONMENTREFLECTIONS_OFF)
@group(0) @binding(2) var environment: texture_cube<f32>;
@group(0) @binding(3) var environment_sampler: sampler;
#endif

@group(1) @binding(0) var<uniform> material: Material;
@group(1) @binding(1) var material_sampler: sampler;
@group(1) @binding(2) var base_map: texture_2d<f32>;
#if defined(_NORMALMAP)
@group(1) @binding(3) var bump_map: texture_2d<f32>;
#endif
#if defined(_METALLICSPECGLOSSMAP)
@group(1) @binding(4) var metallic_gloss_map: texture_2d<f32>;
#endif
#if defined(_OCCLUSIONMAP)
@group(1) @binding(5) var occlusion_map: texture_2d<f32>;
#endif
#if defined(_EMISSION)
@group(1) @binding(6) var emission_map: texture_2d<f32>;
#endif

@group(2) @binding(0) var<uniform> object: Object;
#if defined(LIGHTMAP_ON)
@group(2) @binding(1) var lightmap: texture_2d<f32>;
#if defined(SHADOWS_SHADOWMASK)
@group(2) @binding(2) var shadowmask_map: texture_2d<f32>;
#endif
@group(2) @binding(3) var lightmap_sampler: sampler;
#endif
