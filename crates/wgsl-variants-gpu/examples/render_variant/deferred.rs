//! The G-buffer of one `standard/Deferred` variant over the GPU check's test scene, drawn
//! through generated code alone (`standard_deferred.rs`, `wgsl-variants bindings standard
//! Deferred --wgpu`): the typed key picks the variant, the generated structs fill every
//! uniform buffer, and the generated interface gives the bind group layouts, the vertex buffer
//! layout and the colour targets. Shared by the example and `tests/gpu_bindings.rs`, which
//! compares its texels with the GPU check's G-buffer of the same variant.

use std::error::Error;

use glam::{Mat4, Vec4};
use wgsl_variants::Library;
use wgsl_variants_gpu::check::TestScene;
use wgsl_variants_gpu::{
    BoundResource, GpuContext, GpuResources, Resource, compile_scoped, read_texture,
};
use wgsl_variants_shaders::reference::probe::Probe;

/// The typed module of `standard/Deferred`, with the wgpu option.
#[allow(dead_code)]
pub mod standard_deferred {
    include!("standard_deferred.rs");
}

use standard_deferred as sd;
use standard_deferred::structs;

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

fn v4(v: Vec4) -> [f32; 4] {
    v.to_array()
}

fn m4(m: Mat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d()
}

fn probe(p: &Probe) -> structs::Probe {
    structs::Probe {
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
    }
}

/// The uniform buffers of the scene, each filled through its generated struct, by slot.
pub fn uniforms(scene: &TestScene) -> Vec<BoundResource> {
    let s = &scene.scene;
    let m = &scene.material;
    let camera = structs::Camera {
        view_proj: m4(scene.view_proj),
        position: v4(s.camera_position.extend(1.0)),
    };
    let lighting = structs::Lighting {
        sh_r: v4(s.sh_r),
        sh_g: v4(s.sh_g),
        sh_b: v4(s.sh_b),
        light_dir: v4(s.light_dir.extend(0.0)),
        light_color: v4(s.light_color.extend(1.0)),
    };
    let probes = structs::Probes {
        probe0: probe(&s.probes[0]),
        probe1: probe(&s.probes[1]),
    };
    let material = structs::Material {
        tint: v4(m.tint),
        emission: v4(m.emission.extend(0.0)),
        params: [m.metallic, m.smoothness, m.cutoff, m.occlusion_strength],
        bump: [m.bump_scale, m.detail_bump_scale, 0.0, 0.0],
        detail_st: v4(scene.detail_st),
    };
    let object = structs::Object {
        model: m4(scene.model),
        normal_matrix: m4(scene.normal_matrix),
    };
    let uniform = |group, binding, bytes: &[u8]| {
        BoundResource::new(group, binding, Resource::Uniform(bytes.to_vec()))
    };
    vec![
        uniform(0, 0, bytemuck::bytes_of(&camera)),
        uniform(0, 1, bytemuck::bytes_of(&lighting)),
        uniform(0, 2, bytemuck::bytes_of(&probes)),
        uniform(1, 0, bytemuck::bytes_of(&material)),
        uniform(2, 0, bytemuck::bytes_of(&object)),
    ]
}

/// Draws [`KEY`]'s variant over `scene` and reads its G-buffer back: RT0..RT3 (and RT4),
/// tightly packed rows each.
pub fn render(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
) -> Result<Vec<Vec<u8>>, Box<dyn Error>> {
    let variant = lib.variant(sd::SHADER, sd::PASS, &KEY.keywords())?;
    let label = variant.label();
    let interface = KEY.interface();

    // The buffers from the generated structs; textures and samplers from the scene.
    let mut resources = uniforms(scene);
    resources.extend(
        scene
            .standard_resources()
            .into_iter()
            .filter(|r| !matches!(r.resource, Resource::Uniform(_))),
    );
    let resources = GpuResources::upload(ctx, &label, &resources)?;

    // The scene's quad must be packed as the generated vertex layout says.
    let quad = scene.quad();
    let attributes = interface.wgpu_vertex_attributes();
    if quad.stride != interface.vertex_stride || quad.attributes != attributes {
        return Err("the scene's quad is not packed as the variant's vertex inputs".into());
    }
    let formats = gbuffer_formats(&KEY.get());
    let targets = interface.color_target_states(&formats)?;

    let (bind_groups, pipeline) = compile_scoped(ctx, &label, || {
        let mut layouts = Vec::new();
        let mut bind_groups = Vec::new();
        for group in 0..interface.group_count() {
            let layout = ctx
                .device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(&label),
                    entries: &interface.bind_group_layout_entries(group),
                });
            let entries = interface
                .bindings
                .iter()
                .filter(|b| b.group == group)
                .map(|b| {
                    let resource = resources
                        .binding_resource((b.group, b.binding))
                        .ok_or_else(|| format!("the scene has nothing for {}", b.name))?;
                    Ok(wgpu::BindGroupEntry {
                        binding: b.binding,
                        resource,
                    })
                })
                .collect::<Result<Vec<_>, String>>()?;
            bind_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&label),
                layout: &layout,
                entries: &entries,
            }));
            layouts.push(layout);
        }
        let layouts: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let pipeline_layout = ctx
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&label),
                bind_group_layouts: &layouts,
                immediate_size: 0,
            });
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&label),
                source: wgpu::ShaderSource::Wgsl(lib.wgsl(&variant).into()),
            });
        let pipeline = ctx
            .device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(interface.vertex_buffer_layout(&attributes))],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            });
        Ok::<_, String>((bind_groups, pipeline))
    })??;

    let textures: Vec<wgpu::Texture> = formats
        .iter()
        .map(|&format| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&label),
                size: wgpu::Extent3d {
                    width: scene.width,
                    height: scene.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        })
        .collect();
    let vertices = wgpu::util::DeviceExt::create_buffer_init(
        &ctx.device,
        &wgpu::util::BufferInitDescriptor {
            label: Some(&label),
            contents: &quad.data,
            usage: wgpu::BufferUsages::VERTEX,
        },
    );
    let vertex_count = (quad.data.len() as u64 / quad.stride) as u32;
    ctx.scoped(&label, || {
        let views: Vec<wgpu::TextureView> = textures
            .iter()
            .map(|t| t.create_view(&Default::default()))
            .collect();
        let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
            .iter()
            .map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(&label),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            for (group, bind_group) in bind_groups.iter().enumerate() {
                pass.set_bind_group(group as u32, bind_group, &[]);
            }
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..vertex_count, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
    })?;
    let mut out = Vec::new();
    for texture in &textures {
        out.push(read_texture(ctx, &label, texture)?);
    }
    Ok(out)
}
