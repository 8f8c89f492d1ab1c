//! The G-buffer of one `standard/Deferred` variant over the GPU check's test scene, drawn
//! through generated code alone (`standard_deferred.rs`, `wgsl-variants bindings standard
//! Deferred --wgpu`): the typed key picks the variant, the generated structs fill every
//! uniform buffer, and the generated interface gives the bind group layouts, the vertex buffer
//! layout and the colour targets. Shared by the example and `tests/gpu_bindings.rs`, which
//! compares its texels with the GPU check's G-buffer of the same variant.

use wgsl_variants_gpu::BoundResource;
use wgsl_variants_gpu::check::TestScene;

/// The typed module of `standard/Deferred`, with the wgpu option.
#[allow(dead_code)]
pub mod standard_deferred {
    include!("standard_deferred.rs");
}

use standard_deferred as sd;
use standard_deferred::structs;

use crate::headless::{Inputs, interleave, with_scene_textures};

/// The variant drawn: every map of a plain metallic material, LDR, no reflection buffers.
pub const KEY: sd::Key = sd::Key::checked(sd::Keywords {
    metallic_map: true,
    normal_map: true,
    occlusion_map: true,
    emission_map: true,
    ..sd::Keywords::DEFAULT
});

/// The G-buffer's formats (Unity's): RT0 albedo and occlusion, RT1 specular and smoothness,
/// RT2 normal, RT3 emission and ambient (`Rgba16Float` with `UNITY_HDR_ON`), RT4 the baked
/// occlusion (`SHADOWS_SHADOWMASK`).
pub fn gbuffer_formats(keywords: &sd::Keywords) -> Vec<wgpu::TextureFormat> {
    use wgpu::TextureFormat as F;
    let rt3 = if keywords.unity_hdr_on {
        F::Rgba16Float
    } else {
        F::Rgb10a2Unorm
    };
    let mut formats = vec![F::Rgba8Unorm, F::Rgba8Unorm, F::Rgb10a2Unorm, rt3];
    if keywords.shadows_shadowmask {
        formats.push(F::Rgba8Unorm);
    }
    formats
}

/// Fills the scene's uniform buffers through the generated structs of `$structs` (the
/// `structs` module of a `standard/Deferred` module: this one, or a bake's), by slot: a macro,
/// since each generated module has its own types.
macro_rules! deferred_uniforms {
    ($structs:ident, $scene:expr) => {{
        use $crate::headless::{m4, uniform, v4};
        let scene: &wgsl_variants_gpu::check::TestScene = $scene;
        let s = &scene.scene;
        let m = &scene.material;
        let probe = |p: &wgsl_variants_shaders::reference::probe::Probe| $structs::Probe {
            position: v4(p.position.extend(0.0)),
            // The forward pass's weight rides in `box_min.w`.
            box_min: v4(p.box_min.extend(p.forward_weight)),
            box_max: v4(p.box_max.extend(0.0)),
            hdr: [p.hdr.x, p.hdr.y, 0.0, p.hdr.z],
            params: [
                if p.box_projection { 1.0 } else { 0.0 },
                p.blend_distance,
                p.importance as f32,
                0.0,
            ],
        };
        let camera = $structs::Camera {
            view_proj: m4(scene.view_proj),
            position: v4(s.camera_position.extend(1.0)),
        };
        let lighting = $structs::Lighting {
            sh_r: v4(s.sh_r),
            sh_g: v4(s.sh_g),
            sh_b: v4(s.sh_b),
            light_dir: v4(s.light_dir.extend(0.0)),
            light_color: v4(s.light_color.extend(1.0)),
        };
        let probes = $structs::Probes {
            probe0: probe(&s.probes[0]),
            probe1: probe(&s.probes[1]),
        };
        let material = $structs::Material {
            tint: v4(m.tint),
            emission: v4(m.emission.extend(0.0)),
            params: [m.metallic, m.smoothness, m.cutoff, m.occlusion_strength],
            bump: [m.bump_scale, m.detail_bump_scale, 0.0, 0.0],
            detail_st: v4(scene.detail_st),
        };
        let object = $structs::Object {
            model: m4(scene.model),
            normal_matrix: m4(scene.normal_matrix),
        };
        vec![
            uniform(0, 0, &camera),
            uniform(0, 1, &lighting),
            uniform(0, 2, &probes),
            uniform(1, 0, &material),
            uniform(2, 0, &object),
        ]
    }};
}

/// The uniform buffers of the scene, each filled through its generated struct, by slot.
pub fn uniforms(scene: &TestScene) -> Vec<BoundResource> {
    deferred_uniforms!(structs, scene)
}

/// What [`render`] draws: the scene's buffers through the generated structs, its quad, and
/// the G-buffer's formats for [`KEY`].
pub fn inputs(scene: &TestScene) -> Inputs {
    Inputs {
        resources: with_scene_textures(uniforms(scene), scene.standard_resources()),
        vertices: interleave(&[scene.quad()]),
        formats: gbuffer_formats(&KEY.get()),
        width: scene.width,
        height: scene.height,
    }
}

render_fn!(sd, KEY, TestScene, inputs);
