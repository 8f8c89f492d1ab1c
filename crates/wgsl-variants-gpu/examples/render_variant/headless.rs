//! One draw of a variant from its generated interface, in plain wgpu types: what the passes of
//! the example share. Each generated module has its own prelude types (`Interface`,
//! `BindingEntry`), so each pass module converts its interface into a [`Pipeline`] (the
//! `render_fn!` it invokes) and the rest never names a generated type.

use std::error::Error;

use glam::{Mat4, Vec4};
use wgsl_variants_gpu::{
    BoundResource, GpuContext, GpuResources, Resource, VertexBuffer, compile_scoped, read_texture,
};

/// Defines `pub fn render(ctx, lib, scene: &$scene)` in a pass module: draws the variant of
/// `$key` (a `Key` of the generated module `$module`) over what `$inputs(scene)` gives,
/// through the generated interface alone, and reads its targets back. A macro: every generated
/// module has its own `Interface` type.
macro_rules! render_fn {
    ($module:ident, $key:expr, $scene:ty, $inputs:path) => {
        /// Draws [`KEY`]'s variant over `scene` through the generated interface alone and
        /// reads its targets back: tightly packed rows each, in `@location` order.
        pub fn render(
            ctx: &wgsl_variants_gpu::GpuContext,
            lib: &wgsl_variants::Library,
            scene: &$scene,
        ) -> Result<Vec<Vec<u8>>, Box<dyn std::error::Error>> {
            let inputs = $inputs(scene);
            let key = $key;
            let interface = key.interface();
            let variant = lib.variant($module::SHADER, $module::PASS, &key.keywords())?;
            let label = variant.label();
            let wgsl = lib.wgsl(&variant);
            let attributes = interface.wgpu_vertex_attributes();
            let pipeline = crate::headless::Pipeline {
                label: &label,
                wgsl: &wgsl,
                groups: (0..interface.group_count())
                    .map(|group| interface.bind_group_layout_entries(group))
                    .collect(),
                bindings: interface
                    .bindings
                    .iter()
                    .map(|b| (b.group, b.binding, b.name))
                    .collect(),
                vertex_layout: interface.vertex_buffer_layout(&attributes),
                targets: interface.color_target_states(&inputs.formats)?,
            };
            crate::headless::render(ctx, &pipeline, &inputs)
        }
    };
}

/// What one draw takes from its scene.
pub struct Inputs {
    /// Every resource the variant binds: the buffers filled through the generated structs.
    pub resources: Vec<BoundResource>,
    /// The vertices, packed as the generated vertex layout says.
    pub vertices: VertexBuffer,
    /// The colour targets' formats, one per fragment output.
    pub formats: Vec<wgpu::TextureFormat>,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
}

/// What a variant's pipeline is built from: the generated interface as wgpu's types, and the
/// variant's composed WGSL.
pub struct Pipeline<'a> {
    /// Labels every wgpu object (the variant's label).
    pub label: &'a str,
    /// The variant's composed WGSL, with `vs_main` and `fs_main`.
    pub wgsl: &'a str,
    /// The layout entries of each bind group, `@group(0)` first.
    pub groups: Vec<Vec<wgpu::BindGroupLayoutEntry>>,
    /// Every binding the variant uses: `(group, binding, name)`.
    pub bindings: Vec<(u32, u32, &'a str)>,
    /// The one vertex buffer's layout.
    pub vertex_layout: wgpu::VertexBufferLayout<'a>,
    /// The colour targets in `@location` order.
    pub targets: Vec<Option<wgpu::ColorTargetState>>,
}

/// Packs `buffers` vertex by vertex into one buffer, each buffer's attributes after those of
/// the ones before it: the one buffer a generated vertex layout describes (inputs by location).
pub fn interleave(buffers: &[VertexBuffer]) -> VertexBuffer {
    let stride = buffers.iter().map(|b| b.stride).sum();
    let mut attributes = Vec::new();
    let mut offset = 0;
    for b in buffers {
        attributes.extend(b.attributes.iter().map(|a| wgpu::VertexAttribute {
            offset: a.offset + offset,
            ..*a
        }));
        offset += b.stride;
    }
    let vertices = buffers
        .first()
        .map_or(0, |b| b.data.len() as u64 / b.stride);
    let mut data = Vec::new();
    for v in 0..vertices {
        for b in buffers {
            let start = (v * b.stride) as usize;
            data.extend_from_slice(&b.data[start..start + b.stride as usize]);
        }
    }
    VertexBuffer {
        stride,
        attributes,
        data,
    }
}

/// Draws `inputs` through `pipeline` into targets cleared to black, and reads every target
/// back: tightly packed rows each, in `@location` order. The vertices must be packed as
/// `pipeline.vertex_layout` says.
pub fn render(
    ctx: &GpuContext,
    pipeline: &Pipeline<'_>,
    inputs: &Inputs,
) -> Result<Vec<Vec<u8>>, Box<dyn Error>> {
    let (label, vertices) = (pipeline.label, &inputs.vertices);
    let (width, height) = (inputs.width, inputs.height);
    let layout = &pipeline.vertex_layout;
    if vertices.stride != layout.array_stride || vertices.attributes != layout.attributes {
        return Err(format!("{label}: the vertices are not packed as its vertex inputs").into());
    }
    let resources = GpuResources::upload(ctx, label, &inputs.resources)?;
    let (bind_groups, render_pipeline) = compile_scoped(ctx, label, || {
        let mut layouts = Vec::new();
        let mut bind_groups = Vec::new();
        for (group, entries) in (0u32..).zip(&pipeline.groups) {
            let layout = ctx
                .device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some(label),
                    entries,
                });
            let entries = pipeline
                .bindings
                .iter()
                .filter(|b| b.0 == group)
                .map(|&(group, binding, name)| {
                    let resource = resources
                        .binding_resource((group, binding))
                        .ok_or_else(|| format!("the scene has nothing for {name}"))?;
                    Ok(wgpu::BindGroupEntry { binding, resource })
                })
                .collect::<Result<Vec<_>, String>>()?;
            bind_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &layout,
                entries: &entries,
            }));
            layouts.push(layout);
        }
        let layouts: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let pipeline_layout = ctx
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &layouts,
                immediate_size: 0,
            });
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(pipeline.wgsl.into()),
            });
        let render_pipeline = ctx
            .device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &[Some(pipeline.vertex_layout.clone())],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &pipeline.targets,
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            });
        Ok::<_, String>((bind_groups, render_pipeline))
    })??;

    // A location without an output gets no texture (and no attachment).
    let textures: Vec<Option<wgpu::Texture>> = pipeline
        .targets
        .iter()
        .map(|target| {
            target.as_ref().map(|t| {
                ctx.device.create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d {
                        width,
                        height,
                        depth_or_array_layers: 1,
                    },
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: t.format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                })
            })
        })
        .collect();
    let vertex_buffer = wgpu::util::DeviceExt::create_buffer_init(
        &ctx.device,
        &wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: &vertices.data,
            usage: wgpu::BufferUsages::VERTEX,
        },
    );
    let vertex_count = (vertices.data.len() as u64 / vertices.stride) as u32;
    ctx.scoped(label, || {
        let views: Vec<Option<wgpu::TextureView>> = textures
            .iter()
            .map(|t| t.as_ref().map(|t| t.create_view(&Default::default())))
            .collect();
        let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
            .iter()
            .map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view: view.as_ref()?,
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
                label: Some(label),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&render_pipeline);
            for (group, bind_group) in (0u32..).zip(&bind_groups) {
                pass.set_bind_group(group, bind_group, &[]);
            }
            pass.set_vertex_buffer(0, vertex_buffer.slice(..));
            pass.draw(0..vertex_count, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
    })?;
    let mut out = Vec::new();
    for texture in textures.iter().flatten() {
        out.push(read_texture(ctx, label, texture)?);
    }
    Ok(out)
}

/// A uniform buffer at `@group(group) @binding(binding)` holding `value`'s bytes (a generated
/// struct's).
pub fn uniform<T: bytemuck::Pod>(group: u32, binding: u32, value: &T) -> BoundResource {
    BoundResource::new(
        group,
        binding,
        Resource::Uniform(bytemuck::bytes_of(value).to_vec()),
    )
}

/// `buffers` (filled through the generated structs) and the scene's textures and samplers
/// from `scene` (its buffers, packed by hand, left out).
pub fn with_scene_textures(
    mut buffers: Vec<BoundResource>,
    scene: Vec<BoundResource>,
) -> Vec<BoundResource> {
    buffers.extend(
        scene
            .into_iter()
            .filter(|r| !matches!(r.resource, Resource::Uniform(_) | Resource::Storage(_))),
    );
    buffers
}

/// A `vec4<f32>` field.
pub fn v4(v: Vec4) -> [f32; 4] {
    v.to_array()
}

/// A `mat4x4<f32>` field (columns).
pub fn m4(m: Mat4) -> [[f32; 4]; 4] {
    m.to_cols_array_2d()
}
