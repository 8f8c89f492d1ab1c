//! Draws into one or more colour targets, read back to the CPU: full-screen draws driven by
//! `@builtin(vertex_index)`, or meshes from vertex buffers ([`VertexBuffer`]); targets start
//! cleared or with given contents ([`ColorTarget::with_initial`]), so that blending onto an
//! earlier result can be checked.

use std::collections::BTreeSet;

use super::bindings::Slot;
use super::context::GpuContext;
use super::error::GpuError;
use super::format::TargetFormat;
use super::pass::{PipelineDesc, bind, create_pipeline};
use super::readback::{encode_texture_readback, finish_readbacks};
use super::resources::{BoundResource, GpuResources};

/// One colour target of a [`RenderJob`].
#[derive(Debug, Clone, PartialEq)]
pub struct ColorTarget {
    /// Texture format of the target.
    pub format: TargetFormat,
    /// Clear colour (RGBA) applied before the draw (unless `initial` is set).
    pub clear: [f64; 4],
    /// Blend state; `None` replaces the destination.
    pub blend: Option<wgpu::BlendState>,
    /// Initial contents (tightly packed rows of the target's format) uploaded before the draw
    /// and loaded instead of clearing, e.g. an earlier target read back; `None` clears to
    /// `clear`.
    pub initial: Option<Vec<u8>>,
}

impl ColorTarget {
    /// A target of `format` cleared to transparent black, without blending.
    pub fn new(format: TargetFormat) -> Self {
        Self {
            format,
            clear: [0.0; 4],
            blend: None,
            initial: None,
        }
    }

    /// Sets the clear colour.
    pub fn with_clear(mut self, clear: [f64; 4]) -> Self {
        self.clear = clear;
        self
    }

    /// Sets the blend state.
    pub fn with_blend(mut self, blend: wgpu::BlendState) -> Self {
        self.blend = Some(blend);
        self
    }

    /// Starts the target with `bytes` (tightly packed rows, `width · height` pixels of the
    /// target's format) instead of clearing it: blending then composes onto these contents.
    pub fn with_initial(mut self, bytes: Vec<u8>) -> Self {
        self.initial = Some(bytes);
        self
    }
}

/// One vertex buffer of a [`RenderJob`]: per-vertex data and the layout the vertex shader
/// reads it with (`@location`s of its attributes).
#[derive(Debug, Clone, PartialEq)]
pub struct VertexBuffer {
    /// Bytes from one vertex to the next.
    pub stride: u64,
    /// The attributes: format, offset within a vertex, and shader `@location`.
    pub attributes: Vec<wgpu::VertexAttribute>,
    /// The vertex data, `stride` bytes per vertex.
    pub data: Vec<u8>,
}

impl VertexBuffer {
    /// A vertex buffer of `f32` attributes packed back to back in the given order: each entry
    /// is `(location, components)` with 1 to 4 components, and `vertices` holds the values of
    /// each vertex in that order.
    ///
    /// ```
    /// use wgsl_variants_gpu::VertexBuffer;
    /// // position vec3f at @location(0), uv vec2f at @location(1): 5 floats per vertex.
    /// let vb = VertexBuffer::from_f32(&[(0, 3), (1, 2)], &[[0.0, 0.0, 0.0, 0.0, 1.0]]);
    /// assert_eq!((vb.stride, vb.data.len()), (20, 20));
    /// assert_eq!(vb.attributes[1].offset, 12);
    /// ```
    ///
    /// # Panics
    /// When a component count is not 1 to 4.
    pub fn from_f32<const N: usize>(layout: &[(u32, u32)], vertices: &[[f32; N]]) -> Self {
        let mut offset = 0u64;
        let attributes = layout
            .iter()
            .map(|&(location, components)| {
                let format = match components {
                    1 => wgpu::VertexFormat::Float32,
                    2 => wgpu::VertexFormat::Float32x2,
                    3 => wgpu::VertexFormat::Float32x3,
                    4 => wgpu::VertexFormat::Float32x4,
                    n => panic!("a vertex attribute has 1 to 4 components, not {n}"),
                };
                let attribute = wgpu::VertexAttribute {
                    format,
                    offset,
                    shader_location: location,
                };
                offset += u64::from(components) * 4;
                attribute
            })
            .collect();
        Self {
            stride: offset,
            attributes,
            data: vertices
                .iter()
                .flat_map(|v| v.iter().flat_map(|x| x.to_le_bytes()))
                .collect(),
        }
    }
}

/// One draw of `vertex_count` vertices as a triangle list, one instance, no depth buffer, no
/// culling. Without vertex buffers the vertex shader derives positions from
/// `@builtin(vertex_index)` (3 vertices for a full-screen triangle, 6 for a quad); with
/// `vertex_buffers`, buffer `i` is bound at vertex-buffer slot `i`.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderJob {
    /// Label used for the pipeline and in errors (usually the variant name).
    pub label: String,
    /// Complete WGSL source containing both entry points.
    pub wgsl: String,
    /// Name of the `@vertex` entry point.
    pub vertex_entry: String,
    /// Name of the `@fragment` entry point.
    pub fragment_entry: String,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Colour targets, in `@location` order.
    pub targets: Vec<ColorTarget>,
    /// Number of vertices to draw.
    pub vertex_count: u32,
    /// Vertex buffers, in slot order (empty for a draw from `@builtin(vertex_index)` alone).
    pub vertex_buffers: Vec<VertexBuffer>,
    /// Resources for bind groups 0..N. Resources the shader does not use are skipped.
    pub resources: Vec<BoundResource>,
}

impl RenderJob {
    /// A job with the given shader and entry points, a 16x16 single `Rgba8Unorm` target,
    /// a 3-vertex full-screen triangle and no resources.
    pub fn new(label: &str, wgsl: &str, vertex_entry: &str, fragment_entry: &str) -> Self {
        Self {
            label: label.to_owned(),
            wgsl: wgsl.to_owned(),
            vertex_entry: vertex_entry.to_owned(),
            fragment_entry: fragment_entry.to_owned(),
            width: 16,
            height: 16,
            targets: vec![ColorTarget::new(TargetFormat::Rgba8Unorm)],
            vertex_count: 3,
            vertex_buffers: Vec::new(),
            resources: Vec::new(),
        }
    }
}

/// Uploads `job.resources` and renders the job; see [`render_with`].
pub fn render(ctx: &GpuContext, job: &RenderJob) -> Result<Vec<Vec<u8>>, GpuError> {
    let resources = GpuResources::upload(ctx, &job.label, &job.resources)?;
    render_with(ctx, job, &resources)
}

/// Renders `job` binding the already uploaded `resources` (`job.resources` is ignored), and
/// returns the tightly packed bytes of each colour target, in target order.
///
/// Initial target contents ([`ColorTarget::initial`]) must hold exactly `width · height`
/// pixels of the target's format, and vertex buffers at least `vertex_count` vertices;
/// otherwise the job is a [`GpuError::Validation`].
///
/// Use this to render many variants against one set of resources without re-uploading them.
/// Only the slots the vertex and fragment entry points statically use are bound (wgpu's
/// automatic layout drops the others); a used slot without a resource is a
/// [`GpuError::Validation`]. Shader-module and pipeline errors are
/// [`GpuError::PipelineCompile`]. The wait is bounded by [`GpuContext::timeout`].
pub fn render_with(
    ctx: &GpuContext,
    job: &RenderJob,
    resources: &GpuResources,
) -> Result<Vec<Vec<u8>>, GpuError> {
    let label = job.label.as_str();
    check_targets(ctx, label, job.width, job.height, &job.targets, false)?;
    check_vertex_buffers(label, &job.vertex_buffers, job.vertex_count)?;
    let vertex_layouts = vertex_layouts(&job.vertex_buffers);
    let color_states: Vec<Option<wgpu::ColorTargetState>> = job
        .targets
        .iter()
        .map(|t| {
            Some(wgpu::ColorTargetState {
                format: t.format.wgpu_format(),
                blend: t.blend,
                write_mask: wgpu::ColorWrites::ALL,
            })
        })
        .collect();
    let (pipeline, used) = create_pipeline(
        ctx,
        &PipelineDesc {
            label,
            wgsl: &job.wgsl,
            vertex: &job.vertex_entry,
            fragment: Some(&job.fragment_entry),
            vertex_buffers: &vertex_layouts,
            cull: None,
            depth_stencil: None,
            targets: &color_states,
        },
    )?;
    let bind_groups = bind(ctx, label, &pipeline, &used, resources)?;

    let pending = ctx.scoped(label, || {
        let targets = create_targets(ctx, label, job.width, job.height, &job.targets);
        let vertex_buffers = upload_vertex_buffers(ctx, label, &job.vertex_buffers);
        let views = views(&targets);
        let attachments = color_attachments(&views, &job.targets);

        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            for (group, bind_group) in &bind_groups {
                pass.set_bind_group(*group, bind_group, &[]);
            }
            for (slot, buffer) in (0u32..).zip(&vertex_buffers) {
                pass.set_vertex_buffer(slot, buffer.slice(..));
            }
            pass.draw(0..job.vertex_count, 0..1);
        }
        let pending = targets
            .iter()
            .map(|t| encode_texture_readback(ctx, &mut encoder, t, label))
            .collect::<Result<Vec<_>, _>>();
        if pending.is_ok() {
            ctx.queue.submit([encoder.finish()]);
        }
        pending
    })??;
    finish_readbacks(ctx, label, pending)
}

/// Checks a pass's size against the device limits and each target's initial contents; a pass
/// without colour targets is allowed only when `depth_only` (it renders into a depth buffer).
pub(crate) fn check_targets(
    ctx: &GpuContext,
    label: &str,
    width: u32,
    height: u32,
    targets: &[ColorTarget],
    depth_only: bool,
) -> Result<(), GpuError> {
    let invalid = |message: String| GpuError::Validation {
        label: label.to_owned(),
        message,
    };
    let limits = ctx.device.limits();
    let max = limits.max_texture_dimension_2d;
    if width == 0 || height == 0 || width > max || height > max {
        return Err(invalid(format!(
            "render size {width}x{height} is outside 1..={max}"
        )));
    }
    if (targets.is_empty() && !depth_only) || targets.len() > limits.max_color_attachments as usize
    {
        return Err(invalid(format!(
            "{} colour targets; 1..={} are supported",
            targets.len(),
            limits.max_color_attachments
        )));
    }
    let pixels = u64::from(width) * u64::from(height);
    for (i, t) in targets.iter().enumerate() {
        if let Some(initial) = &t.initial {
            let needed = pixels * t.format.bytes_per_pixel() as u64;
            if initial.len() as u64 != needed {
                return Err(invalid(format!(
                    "initial contents of target {i} ({width}x{height} {:?}) need {needed} bytes, got {}",
                    t.format,
                    initial.len()
                )));
            }
        }
    }
    Ok(())
}

/// Checks that every vertex buffer holds `vertex_count` vertices.
pub(crate) fn check_vertex_buffers(
    label: &str,
    buffers: &[VertexBuffer],
    vertex_count: u32,
) -> Result<(), GpuError> {
    for (i, vb) in buffers.iter().enumerate() {
        let needed = vb.stride * u64::from(vertex_count);
        if vb.stride == 0 || (vb.data.len() as u64) < needed {
            return Err(GpuError::Validation {
                label: label.to_owned(),
                message: format!(
                    "vertex buffer {i} (stride {}) holds {} bytes; {vertex_count} vertices need {needed}",
                    vb.stride,
                    vb.data.len(),
                ),
            });
        }
    }
    Ok(())
}

/// The pipeline's vertex-buffer layouts for `buffers`, slot `i` for buffer `i`.
pub(crate) fn vertex_layouts(
    buffers: &[VertexBuffer],
) -> Vec<Option<wgpu::VertexBufferLayout<'_>>> {
    buffers
        .iter()
        .map(|vb| {
            Some(wgpu::VertexBufferLayout {
                array_stride: vb.stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &vb.attributes,
            })
        })
        .collect()
}

/// Creates the colour targets (readable and writable by copies) and uploads their initial
/// contents.
pub(crate) fn create_targets(
    ctx: &GpuContext,
    label: &str,
    width: u32,
    height: u32,
    targets: &[ColorTarget],
) -> Vec<wgpu::Texture> {
    targets
        .iter()
        .map(|t| {
            let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: t.format.wgpu_format(),
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            });
            if let Some(initial) = &t.initial {
                ctx.queue.write_texture(
                    texture.as_image_copy(),
                    initial,
                    wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(width * t.format.bytes_per_pixel() as u32),
                        rows_per_image: Some(height),
                    },
                    texture.size(),
                );
            }
            texture
        })
        .collect()
}

/// Uploads vertex buffers (padded to 4 bytes).
pub(crate) fn upload_vertex_buffers(
    ctx: &GpuContext,
    label: &str,
    buffers: &[VertexBuffer],
) -> Vec<wgpu::Buffer> {
    buffers
        .iter()
        .map(|vb| {
            let size = super::readback::align_up(vb.data.len() as u64, 4).max(4);
            let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut padded = vb.data.clone();
            padded.resize(size as usize, 0);
            ctx.queue.write_buffer(&buffer, 0, &padded);
            buffer
        })
        .collect()
}

/// Default views of `textures`.
pub(crate) fn views(textures: &[wgpu::Texture]) -> Vec<wgpu::TextureView> {
    textures
        .iter()
        .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()))
        .collect()
}

/// Colour attachments: loaded where the target has initial contents, cleared otherwise.
pub(crate) fn color_attachments<'a>(
    views: &'a [wgpu::TextureView],
    targets: &[ColorTarget],
) -> Vec<Option<wgpu::RenderPassColorAttachment<'a>>> {
    views
        .iter()
        .zip(targets)
        .map(|(view, t)| {
            let [r, g, b, a] = t.clear;
            let load = match t.initial {
                Some(_) => wgpu::LoadOp::Load,
                None => wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
            };
            Some(wgpu::RenderPassColorAttachment {
                view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load,
                    store: wgpu::StoreOp::Store,
                },
            })
        })
        .collect()
}

/// Creates one bind group per group index that has used slots, from the pipeline's
/// automatically derived layouts.
pub(crate) fn create_bind_groups(
    ctx: &GpuContext,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    used: &BTreeSet<Slot>,
    resources: &GpuResources,
) -> Vec<(u32, wgpu::BindGroup)> {
    let groups: BTreeSet<u32> = used.iter().map(|&(g, _)| g).collect();
    groups
        .into_iter()
        .map(|group| {
            let entries: Vec<wgpu::BindGroupEntry<'_>> = used
                .iter()
                .filter(|&&(g, _)| g == group)
                .filter_map(|&(g, binding)| {
                    resources
                        .binding_resource((g, binding))
                        .map(|resource| wgpu::BindGroupEntry { binding, resource })
                })
                .collect();
            let bind_group = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.get_bind_group_layout(group),
                entries: &entries,
            });
            (group, bind_group)
        })
        .collect()
}
