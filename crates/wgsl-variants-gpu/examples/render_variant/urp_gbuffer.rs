//! The G-buffer of one `universal_lit/UniversalGBuffer` variant over the GPU check's URP scene,
//! drawn through generated code alone (`universal_gbuffer.rs`, `wgsl-variants bindings
//! universal_lit UniversalGBuffer --wgpu`), as `deferred.rs` draws `standard/Deferred`. Shared
//! by the example and `tests/gpu_bindings.rs`, which compares its texels with the GPU check's
//! rendering of the same variant.

use wgsl_variants_gpu::check::urp::UrpScene;
use wgsl_variants_gpu::{BoundResource, urp_gbuffer_formats};

/// The typed module of `universal_lit/UniversalGBuffer`, with the wgpu option.
#[allow(dead_code)]
pub mod universal_gbuffer {
    include!("universal_gbuffer.rs");
}

use universal_gbuffer as ug;
use universal_gbuffer::structs;

use crate::headless::{Inputs, interleave, with_scene_textures};

/// The variant drawn: every map of a metallic material, octahedral normals, a lightmap with a
/// shadowmask, and all three optional targets (depth as colour, rendering layers, shadowmask):
/// seven colour targets.
pub const KEY: ug::Key = ug::Key::checked(ug::Keywords {
    normalmap: true,
    emission: true,
    metallicspecglossmap: true,
    occlusionmap: true,
    gbuffer_normals_oct: true,
    render_pass_enabled: true,
    write_rendering_layers: true,
    shadows_shadowmask: true,
    lightmap_on: true,
    ..ug::Keywords::DEFAULT
});

/// Fills the URP scene's uniform buffers through the generated structs of `$structs` (the
/// `structs` module of a `universal_lit/UniversalGBuffer` module: this one, or a bake's), by
/// slot: a macro, since each generated module has its own types.
macro_rules! urp_uniforms {
    ($structs:ident, $urp:expr) => {{
        use wgsl_variants_gpu::check::urp::{LIGHTMAP_ST, RENDERING_LAYERS};
        use $crate::headless::{m4, uniform, v4};
        let urp: &wgsl_variants_gpu::check::urp::UrpScene = $urp;
        let s = &urp.scene;
        let l = &urp.lighting;
        let m = &urp.material;
        let camera = $structs::Camera {
            view_proj: m4(s.view_proj),
            position: v4(l.camera_position.extend(1.0)),
        };
        let lighting = $structs::Lighting {
            sh_r: v4(l.sh_r),
            sh_g: v4(l.sh_g),
            sh_b: v4(l.sh_b),
            main_light_dir: v4(l.main_light_dir.extend(0.0)),
            main_light_color: v4(l.main_light_color.extend(1.0)),
            main_light_shadow: [l.shadow_attenuation, l.shadow_strength, 0.0, 0.0],
            subtractive_shadow_color: v4(l.subtractive_shadow_color.extend(0.0)),
            glossy_environment_color: v4(l.glossy_environment_color.extend(0.0)),
            probes_occlusion: v4(l.probes_occlusion),
            // URP's _AmbientOcclusionParam as the GPU check sets it (only the forward pass's
            // SSAO reads it).
            ambient_occlusion_params:
                wgsl_variants_gpu::check::urp_occlusion::AMBIENT_OCCLUSION_PARAM,
        };
        let material = $structs::Material {
            base_color: v4(m.base_color),
            spec_color: v4(m.spec_color.extend(0.0)),
            emission_color: v4(m.emission_color.extend(0.0)),
            params: [m.metallic, m.smoothness, m.cutoff, m.bump_scale],
            extra: [m.occlusion_strength, 0.0, 0.0, 0.0],
        };
        let object = $structs::Object {
            model: m4(s.model),
            normal_matrix: m4(s.normal_matrix),
            lightmap_st: v4(LIGHTMAP_ST),
            rendering_layers: [RENDERING_LAYERS, 0, 0, 0],
        };
        vec![
            uniform(0, 0, &camera),
            uniform(0, 1, &lighting),
            uniform(1, 0, &material),
            uniform(2, 0, &object),
        ]
    }};
}

/// The uniform buffers of the URP scene, each filled through its generated struct, by slot.
pub fn uniforms(urp: &UrpScene) -> Vec<BoundResource> {
    urp_uniforms!(structs, urp)
}

/// What [`render`] draws: the URP scene's buffers through the generated structs, its quad
/// with the lightmap's UV set (`@location(4)`) after it, and URP's G-buffer formats for
/// [`KEY`]: GBuffer0..3, then depth, rendering layers and shadowmask.
pub fn inputs(urp: &UrpScene) -> Inputs {
    Inputs {
        resources: with_scene_textures(uniforms(urp), urp.resources()),
        vertices: interleave(&[urp.scene.quad(), urp.lightmap_uvs()]),
        formats: urp_gbuffer_formats(&KEY.keywords()),
        width: urp.scene.width,
        height: urp.scene.height,
    }
}

render_fn!(ug, KEY, UrpScene, inputs);
