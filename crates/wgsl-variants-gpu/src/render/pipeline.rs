//! Render pipelines with wgpu's automatic layout, and their bind groups from uploaded
//! resources: the step every draw shares, whether one [`RenderJob`](super::RenderJob), a
//! [`DrawPass`](super::DrawPass) or the depth and stencil passes of the checks.

use std::collections::BTreeSet;

use crate::bindings::{Slot, used_bindings};
use crate::compile::{compile_scoped, wgsl_module};
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::resources::{BoundResource, GpuResources};

/// What a render pipeline is made of, for [`create_pipeline`].
pub(crate) struct PipelineDesc<'a> {
    pub(crate) label: &'a str,
    pub(crate) wgsl: &'a str,
    pub(crate) vertex: &'a str,
    /// `None`: no fragment stage (depth and stencil only).
    pub(crate) fragment: Option<&'a str>,
    pub(crate) vertex_buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    pub(crate) cull: Option<wgpu::Face>,
    pub(crate) depth_stencil: Option<wgpu::DepthStencilState>,
    pub(crate) targets: &'a [Option<wgpu::ColorTargetState>],
}

/// Compiles a render pipeline with wgpu's automatic layout (errors are
/// [`GpuError::PipelineCompile`]) and returns it with the slots its entry points use (what
/// its bind groups must hold).
pub(crate) fn create_pipeline(
    ctx: &GpuContext,
    desc: &PipelineDesc<'_>,
) -> Result<(wgpu::RenderPipeline, BTreeSet<Slot>), GpuError> {
    let entries: Vec<&str> = std::iter::once(desc.vertex).chain(desc.fragment).collect();
    let used = used_bindings(desc.label, desc.wgsl, &entries)?;
    let pipeline = compile_scoped(ctx, desc.label, || {
        let module = wgsl_module(ctx, desc.label, desc.wgsl);
        ctx.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(desc.label),
                layout: None,
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(desc.vertex),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    buffers: desc.vertex_buffers,
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode: desc.cull,
                    ..wgpu::PrimitiveState::default()
                },
                depth_stencil: desc.depth_stencil.clone(),
                multisample: wgpu::MultisampleState::default(),
                fragment: desc.fragment.map(|entry| wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: wgpu::PipelineCompilationOptions::default(),
                    targets: desc.targets,
                }),
                multiview_mask: None,
                cache: None,
            })
    })?;
    Ok((pipeline, used))
}

/// The bind groups of `pipeline` for the `used` slots, from `resources`; a used slot without a
/// resource is a [`GpuError::Validation`].
pub(crate) fn bind(
    ctx: &GpuContext,
    label: &str,
    pipeline: &wgpu::RenderPipeline,
    used: &BTreeSet<Slot>,
    resources: &GpuResources,
) -> Result<Vec<(u32, wgpu::BindGroup)>, GpuError> {
    if let Some((group, binding)) = used.iter().find(|&&slot| !resources.contains(slot)) {
        return Err(GpuError::Validation {
            label: label.to_owned(),
            message: format!(
                "shader uses @group({group}) @binding({binding}) but no resource was given for it"
            ),
        });
    }
    ctx.scoped(label, || {
        create_bind_groups(ctx, label, pipeline, used, resources)
    })
}

/// A render pipeline over `wgsl`'s `vertex` / `fragment` entry points (no fragment stage:
/// depth and stencil only), its bind groups from `resources`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn pipeline(
    ctx: &GpuContext,
    label: &str,
    wgsl: &str,
    (vertex, fragment): (&str, Option<&str>),
    vertex_buffers: &[Option<wgpu::VertexBufferLayout<'_>>],
    cull: Option<wgpu::Face>,
    depth_stencil: wgpu::DepthStencilState,
    targets: &[Option<wgpu::ColorTargetState>],
    resources: &[BoundResource],
) -> Result<(wgpu::RenderPipeline, Vec<(u32, wgpu::BindGroup)>), GpuError> {
    let (pipeline, used) = create_pipeline(
        ctx,
        &PipelineDesc {
            label,
            wgsl,
            vertex,
            fragment,
            vertex_buffers,
            cull,
            depth_stencil: Some(depth_stencil),
            targets,
        },
    )?;
    let uploaded = GpuResources::upload(ctx, label, resources)?;
    let groups = bind(ctx, label, &pipeline, &used, &uploaded)?;
    Ok((pipeline, groups))
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
