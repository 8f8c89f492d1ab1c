//! # wgsl-variants-gpu
//!
//! The GPU side of [`wgsl_variants`]: bind group and pipeline layouts built from a variant's
//! reflection, and a headless wgpu harness that proves the bundled library on any adapter.
//!
//! Headless wgpu harness: compile WGSL variants into real pipelines, run compute dispatches
//! and full-screen draws, and read the results back, on any adapter including Mesa's
//! software Vulkan driver lavapipe (`apt-get install mesa-vulkan-drivers`).
//!
//! - [`create_bind_group_layouts`] / [`create_pipeline_layout`] turn a
//!   [`Reflection`](wgsl_variants::reflect::Reflection) into wgpu layouts.
//! - [`GpuContext`] owns instance, adapter, device and queue; create it once.
//! - [`run_compute`] dispatches a compute shader over one input and one output storage buffer.
//! - [`render()`] / [`render_with`] draw a [`RenderJob`] into up to eight colour targets and
//!   return their bytes; [`TargetFormat`] decodes them.
//! - [`render_pass`] records many [`Draw`]s (each its own variant, mesh and resources) into
//!   one pass over shared targets and a depth buffer: a frame.
//! - [`check::frame::ResidentFrame`] keeps a frame's targets on the GPU between passes and
//!   times each pass with timestamp queries ([`PassSpan`]): the frame bench.
//! - [`check`] is the GPU proof of the bundled library built on these: every variant of the
//!   standard passes, the deferred reflection and final passes, and compute kernels, compared
//!   with [`wgsl_variants_shaders::reference`] (the `check-gpu` and `render` commands).
//! - [`light_volume`] gives the mesh bounding a point or spot light and the rule choosing
//!   between a light volume with the stencil pre-pass and a full-screen draw.
//! - Every wgpu error is captured with error scopes and returned as a [`GpuError`]; nothing
//!   panics through wgpu's default handler, and every wait is bounded by
//!   [`GpuContext::timeout`].

#![deny(missing_docs)]

mod bindings;
mod compile;
mod compute;
mod context;
mod error;
mod format;
mod layout;
mod readback;
mod render;
mod resources;
mod urp;

pub mod check;
pub mod light_volume;

pub use bindings::{Slot, used_bindings, used_bindings_in};
pub use compile::{compile_scoped, wgsl_module};
pub use compute::run_compute;
pub use context::{DEFAULT_TIMEOUT, GpuContext, error_message};
pub use error::{CheckError, GpuError};
pub use format::TargetFormat;
pub use layout::{
    create_bind_group_layouts, create_pipeline_layout, layout_entries, layout_entry, stage_flags,
    storage_format, view_dimension,
};
pub use readback::{
    PendingReadback, encode_aspect_readback, encode_texture_readback, finish_readbacks,
    map_buffers, read_texture,
};
pub use render::{
    ColorTarget, DEPTH_FORMAT, DEPTH_STENCIL_FORMAT, DepthTest, Draw, DrawPass, PassOutput,
    PassSpan, RenderJob, StencilTest, VertexBuffer, render, render_pass, render_with,
};
pub use resources::{BoundResource, GpuResources, Resource};
pub use urp::urp_gbuffer_formats;
