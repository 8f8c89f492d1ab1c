//! Headless wgpu harness: compile WGSL variants into real pipelines, run compute dispatches
//! and full-screen draws, and read the results back, on any adapter including Mesa's
//! software Vulkan driver lavapipe (`apt-get install mesa-vulkan-drivers`).
//!
//! - [`GpuContext`] owns instance, adapter, device and queue; create it once.
//! - [`run_compute`] dispatches a compute shader over one input and one output storage buffer.
//! - [`render`] / [`render_with`] draw a [`RenderJob`] into up to eight colour targets and
//!   return their bytes; [`TargetFormat`] decodes them.
//! - [`check`] is the GPU proof of the bundled library built on these: every variant of the
//!   standard passes, the deferred reflection and final passes, and compute kernels, compared
//!   with [`crate::reference`] (the `check-gpu` and `render` commands).
//! - Every wgpu error is captured with error scopes and returned as a [`GpuError`]; nothing
//!   panics through wgpu's default handler, and every wait is bounded by
//!   [`GpuContext::timeout`].

mod bindings;
mod compile;
mod compute;
mod context;
mod error;
mod format;
mod readback;
mod render;
mod resources;

pub mod check;

pub use bindings::{Slot, used_bindings, used_bindings_in};
pub use compile::{compile_scoped, wgsl_module};
pub use compute::run_compute;
pub use context::{DEFAULT_TIMEOUT, GpuContext, error_message};
pub use error::GpuError;
pub use format::{TargetFormat, f16_to_f32};
pub use readback::{
    PendingReadback, encode_texture_readback, finish_readbacks, map_buffers, read_texture,
};
pub use render::{ColorTarget, RenderJob, VertexBuffer, render, render_with};
pub use resources::{BoundResource, GpuResources, Resource};
