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
//!
//! `job` and `pass` stand on `target` and `pipeline` and never on each other.

mod job;
mod pass;
mod pipeline;
mod target;

pub use job::{RenderJob, render, render_with};
pub use pass::{DEPTH_FORMAT, DepthTest, Draw, DrawPass, PassOutput, render_pass};
pub(crate) use pipeline::pipeline;
pub use target::{ColorTarget, VertexBuffer};
