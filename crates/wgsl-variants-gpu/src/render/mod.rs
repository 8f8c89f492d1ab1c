//! Drawing with wgpu and reading the results back: the one home of every draw the harness
//! makes.
//!
//! Two floors, so that nothing here imports in a loop:
//!
//! | module | what it holds |
//! |---|---|
//! | `target` | [`ColorTarget`] and [`VertexBuffer`]: what a draw writes to and reads its mesh from, and their checks, uploads and attachments |
//! | `pipeline` | render pipelines with wgpu's automatic layout and their bind groups |
//! | `job` | [`RenderJob`], [`render`] and [`render_with`]: one variant into up to eight colour targets |
//! | `pass` | [`DrawPass`], [`Draw`] and [`render_pass`]: many draws into one pass over shared targets and a depth buffer |
//! | `resident` | passes over textures that stay on the GPU (a frame's G-buffer read where it was written), prepared once, recorded as often as timed |
//! | `timing` | GPU time per pass from timestamp queries ([`PassSpan`]) |
//!
//! `job` and `pass` stand on `target` and `pipeline` and never on each other; `resident`
//! stands on `pass` (its draws are prepared the same way), `timing` on nothing here.

mod job;
mod pass;
mod pipeline;
pub(crate) mod resident;
mod target;
pub(crate) mod timing;

pub use job::{RenderJob, render, render_with};
pub use pass::{
    DEPTH_FORMAT, DEPTH_STENCIL_FORMAT, DepthTest, Draw, DrawPass, PassOutput, StencilTest,
    render_pass,
};
pub(crate) use pipeline::pipeline;
pub use target::{ColorTarget, VertexBuffer};
pub use timing::PassSpan;
