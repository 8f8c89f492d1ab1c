//! Layouts built from reflection are accepted by wgpu for real pipelines.

mod common;

use common::gpu::{adapter_filter, or_skip};
use wgsl_variants::Variant;
use wgsl_variants::snapshot::covering_set;
use wgsl_variants_gpu::{
    GpuContext, create_bind_group_layouts, create_pipeline_layout, urp_gbuffer_formats,
};

/// wgpu checks a pipeline against an explicit layout: every binding the shader uses must
/// be in it with a compatible type and visibility. Layouts built from the reflection pass
/// for the covering set of every bundled pass.
#[test]
fn wgpu_accepts_pipelines_with_layouts_from_reflection() {
    let Some(ctx) = or_skip(GpuContext::new(adapter_filter().as_deref()), "GPU context") else {
        return;
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let mut pipelines = 0;
    for pass in lib.passes() {
        for (which, choice) in covering_set(pass) {
            let v = Variant { pass, choice };
            let label = format!("{} ({which})", v.label());
            let reflection = lib.reflect(&v).unwrap();
            let wgsl = lib.wgsl(&v);
            let deferred = pass.name == "Deferred";
            let hdr = v.keywords().contains(&"UNITY_HDR_ON");
            let urp = pass.name == "UniversalGBuffer";
            let lightmap = v.keywords().contains(&"LIGHTMAP_ON");
            // URP's ShadowCaster writes depth only.
            let depth_only = pass.shader == "universal_lit" && pass.name == "ShadowCaster";
            let formats: Vec<wgpu::TextureFormat> = if urp {
                urp_gbuffer_formats(&v.keywords())
            } else if depth_only {
                Vec::new()
            } else if pass.name == "DepthOnly" {
                // URP's depth prepass writes the depth to its one channel too.
                vec![wgpu::TextureFormat::R32Float]
            } else if pass.shader == "stencil_deferred" || pass.name == "UniversalForward" {
                // URP's lighting passes add to GBuffer3; URP's forward pass draws into the
                // HDR camera target of URP's default format.
                vec![wgpu::TextureFormat::Rg11b10Ufloat]
            } else if deferred {
                vec![
                    wgpu::TextureFormat::Rgba8Unorm,
                    wgpu::TextureFormat::Rgba8Unorm,
                    wgpu::TextureFormat::Rgb10a2Unorm,
                    if hdr {
                        wgpu::TextureFormat::Rgba16Float
                    } else {
                        wgpu::TextureFormat::Rgb10a2Unorm
                    },
                ]
            } else {
                vec![wgpu::TextureFormat::Rgba16Float]
            };
            let has_mesh = pass.shader == "standard" || pass.shader == "universal_lit";
            // The light volumes' stencil pre-pass is depth-only: no fragment stage; the
            // lighting pass has a second vertex entry point for volumes. Both read world
            // positions at @location(0).
            let stencil_only = pass.name == "StencilWrite";
            let entries: &[&str] = match pass.name.as_str() {
                "Lighting" | "PunctualLit" | "DirectionalLit" => &["vs_main", "vs_volume"],
                _ => &["vs_main"],
            };
            for &entry in entries {
                let positions_in = stencil_only || entry == "vs_volume";
                let (_, error) = ctx.capture(|| {
                    let layouts =
                        create_bind_group_layouts(&ctx.device, &reflection, &label).unwrap();
                    let layout = create_pipeline_layout(&ctx.device, &layouts, &label);
                    let module = ctx
                        .device
                        .create_shader_module(wgpu::ShaderModuleDescriptor {
                            label: Some(&label),
                            source: wgpu::ShaderSource::Wgsl(wgsl.as_str().into()),
                        });
                    // URP's lightmapped variants read a second UV set (location 4).
                    let attributes = wgpu::vertex_attr_array![
                        0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x2, 4 => Float32x2
                    ];
                    let used = if lightmap { 5 } else { 4 };
                    let position = wgpu::vertex_attr_array![0 => Float32x3];
                    let mesh = [Some(wgpu::VertexBufferLayout {
                        array_stride: if lightmap { 56 } else { 48 },
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &attributes[..used],
                    })];
                    let volume = [Some(wgpu::VertexBufferLayout {
                        array_stride: 12,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &position,
                    })];
                    let buffers: &[Option<wgpu::VertexBufferLayout>] = if has_mesh {
                        &mesh
                    } else if positions_in {
                        &volume
                    } else {
                        &[]
                    };
                    let targets: Vec<Option<wgpu::ColorTargetState>> =
                        formats.iter().map(|&f| Some(f.into())).collect();
                    ctx.device
                        .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                            label: Some(&label),
                            layout: Some(&layout),
                            vertex: wgpu::VertexState {
                                module: &module,
                                entry_point: Some(entry),
                                compilation_options: Default::default(),
                                buffers,
                            },
                            fragment: (!stencil_only).then(|| wgpu::FragmentState {
                                module: &module,
                                entry_point: Some("fs_main"),
                                compilation_options: Default::default(),
                                targets: &targets,
                            }),
                            primitive: Default::default(),
                            depth_stencil: (stencil_only || depth_only).then(|| wgpu::DepthStencilState {
                                format: wgpu::TextureFormat::Depth24PlusStencil8,
                                depth_write_enabled: Some(false),
                                depth_compare: Some(wgpu::CompareFunction::LessEqual),
                                stencil: Default::default(),
                                bias: Default::default(),
                            }),
                            multisample: Default::default(),
                            multiview_mask: None,
                            cache: None,
                        })
                });
                assert!(
                    error.is_none(),
                    "{label} ({entry}): {}",
                    error.map(|e| e.to_string()).unwrap_or_default()
                );
                pipelines += 1;
            }
        }
    }
    println!("wgpu accepted {pipelines} pipelines with layouts from reflection");
    assert!(pipelines > 30);
}
