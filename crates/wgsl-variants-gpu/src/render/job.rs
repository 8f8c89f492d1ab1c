//! Draws into one or more colour targets, read back to the CPU: full-screen draws driven by
//! `@builtin(vertex_index)`, or meshes from vertex buffers ([`VertexBuffer`]); targets start
//! cleared or with given contents ([`ColorTarget::with_initial`]), so that blending onto an
//! earlier result can be checked.

use super::pipeline::{PipelineDesc, bind, create_pipeline};
use super::target::{
    ColorTarget, VertexBuffer, check_targets, check_vertex_buffers, color_attachments,
    create_targets, upload_vertex_buffers, vertex_layouts, views,
};
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::format::TargetFormat;
use crate::readback::{encode_texture_readback, finish_readbacks};
use crate::resources::{BoundResource, GpuResources};

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
