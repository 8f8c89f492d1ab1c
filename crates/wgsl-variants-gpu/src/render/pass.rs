//! Several draws into the same colour targets and depth buffer, in one render pass: the
//! objects of a frame (each its own variant, mesh and resources) with the depth test, then
//! lights blended onto what they left.
//!
//! [`render`](super::render()) draws one variant; a frame needs many: [`render_pass`]
//! takes a [`DrawPass`] of [`Draw`]s, compiles each distinct pipeline once (same text, entry
//! points, blend, depth test and vertex layout), uploads each distinct resource once (draws
//! share equal ones: the camera, the probes, a light's uniform), records every
//! draw in order into one pass and reads back the colour targets and, with
//! [`DrawPass::depth`], the `Depth32Float` buffer (cleared to 1, the far plane) — with
//! [`DEPTH_STENCIL_FORMAT`], its depth and its stencil (cleared to 0), which draws mark and
//! test with a [`StencilTest`].
//!
//! ```no_run
//! use std::sync::Arc;
//! use wgsl_variants_gpu::{ColorTarget, DepthTest, Draw, DrawPass, GpuContext, TargetFormat, render_pass};
//! # fn main() -> Result<(), wgsl_variants_gpu::GpuError> {
//! let ctx = GpuContext::new(None)?;
//! let wgsl: Arc<str> = Arc::from(
//!     "@vertex fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
//!          let p = vec2f(f32(i % 2u) * 4.0 - 1.0, f32(i / 2u) * 4.0 - 1.0);
//!          return vec4f(p, 0.5, 1.0);
//!      }
//!      @fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }",
//! );
//! let mut pass = DrawPass::new("two draws", 8, 8, vec![ColorTarget::new(TargetFormat::Rgba8Unorm)]);
//! pass.depth = true;
//! let draw = Draw::fullscreen("white", &wgsl, "vs", "fs").with_depth(DepthTest::OPAQUE);
//! pass.draws = vec![draw.clone(), draw];
//! let out = render_pass(&ctx, &pass)?;
//! assert_eq!(out.depth.unwrap()[0], 0.5);
//! # Ok(()) }
//! ```

use std::collections::BTreeSet;
use std::sync::Arc;

use super::pipeline::{PipelineDesc, bind, create_pipeline};
use super::target::{
    ColorTarget, VertexBuffer, check_targets, check_vertex_buffers, color_attachments,
    create_targets, upload_vertex_buffers, vertex_layouts, views,
};
use crate::bindings::Slot;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::readback::{encode_aspect_readback, encode_texture_readback, finish_readbacks};
use crate::resources::{BoundResource, GpuResources, ResourcePool};

/// The depth buffer's format: 32-bit float, so the depth a deferred pass rebuilds positions
/// from is the rasterizer's own value, not a 16- or 24-bit rounding of it.
pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The depth-stencil format of a pass whose draws mark or test stencil bits: 32-bit float
/// depth, like [`DEPTH_FORMAT`], plus 8 stencil bits (the device needs
/// `DEPTH32FLOAT_STENCIL8`, which [`GpuContext::OPTIONAL_FEATURES`] asks for). Both aspects
/// can be read back, which `Depth24PlusStencil8`'s depth cannot.
pub const DEPTH_STENCIL_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32FloatStencil8;

/// How a draw tests and writes the stencil bits of a pass with [`DEPTH_STENCIL_FORMAT`]
/// (both faces alike).
///
/// The fragment passes where `(reference & read_mask) <compare> (stored & read_mask)`; the
/// operation of its outcome (stencil test failed, depth test failed, both passed) updates the
/// bits of `write_mask`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct StencilTest {
    /// The comparison of the reference with the stored value, both masked by `read_mask`.
    pub compare: wgpu::CompareFunction,
    /// What a fragment failing the stencil test does to the stored bits.
    pub fail_op: wgpu::StencilOperation,
    /// What a fragment passing the stencil test and failing the depth test does.
    pub depth_fail_op: wgpu::StencilOperation,
    /// What a fragment passing both tests does to the stored bits.
    pub pass_op: wgpu::StencilOperation,
    /// The bits the comparison reads.
    pub read_mask: u32,
    /// The bits `pass_op` may change.
    pub write_mask: u32,
    /// The draw's reference value (set per draw: draws differing only in it share a
    /// pipeline).
    pub reference: u32,
}

impl StencilTest {
    /// Marks every fragment the draw leaves: the stored value becomes `bits` (all eight bits
    /// written, so a nearer surface's marks replace a farther one's, zero included).
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::mark(0b0101);
    /// assert_eq!((t.reference, t.write_mask), (0b0101, 0xff));
    /// ```
    pub const fn mark(bits: u32) -> StencilTest {
        StencilTest {
            compare: wgpu::CompareFunction::Always,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Replace,
            read_mask: 0xff,
            write_mask: 0xff,
            reference: bits,
        }
    }

    /// Draws only where none of `bits` is set (`(stored & bits) == 0`), writing nothing.
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::none_of(0b0010);
    /// assert_eq!((t.reference, t.read_mask, t.write_mask), (0, 0b0010, 0));
    /// ```
    pub const fn none_of(bits: u32) -> StencilTest {
        StencilTest::equal(0, bits)
    }

    /// Draws only where the stored bits under `read_mask` equal `value` (`(stored & read_mask)
    /// == value`), writing nothing: URP's lighting passes testing the material type the
    /// G-buffer pass stamped.
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::equal(0x20, 0x60);
    /// assert_eq!((t.reference, t.read_mask, t.write_mask), (0x20, 0x60, 0));
    /// assert_eq!(t.compare, wgpu::CompareFunction::Equal);
    /// ```
    pub const fn equal(value: u32, read_mask: u32) -> StencilTest {
        StencilTest {
            compare: wgpu::CompareFunction::Equal,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Keep,
            read_mask,
            write_mask: 0,
            reference: value,
        }
    }

    /// Sets `bits` wherever the fragment stage does not discard (the other bits stay).
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::set(0b1000);
    /// assert_eq!((t.reference, t.write_mask), (0b1000, 0b1000));
    /// ```
    pub const fn set(bits: u32) -> StencilTest {
        StencilTest {
            compare: wgpu::CompareFunction::Always,
            fail_op: wgpu::StencilOperation::Keep,
            depth_fail_op: wgpu::StencilOperation::Keep,
            pass_op: wgpu::StencilOperation::Replace,
            read_mask: 0xff,
            write_mask: bits,
            reference: bits,
        }
    }

    /// Sets `bits` where the depth test fails (the other bits stay): the stencil pre-pass of
    /// a light volume (Unity's `Internal-StencilWrite`), whose front faces fail where the
    /// scene lies in front of the volume.
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::set_where_depth_fails(0x80);
    /// assert_eq!(t.depth_fail_op, wgpu::StencilOperation::Replace);
    /// assert_eq!(t.pass_op, wgpu::StencilOperation::Keep);
    /// ```
    pub const fn set_where_depth_fails(bits: u32) -> StencilTest {
        StencilTest {
            depth_fail_op: wgpu::StencilOperation::Replace,
            pass_op: wgpu::StencilOperation::Keep,
            ..StencilTest::set(bits)
        }
    }

    /// The same test, also clearing `bits` on every fragment it rasterizes, whatever the
    /// outcome: a light volume's draw leaving the stencil as its pre-pass found it.
    ///
    /// ```
    /// use wgsl_variants_gpu::StencilTest;
    /// let t = StencilTest::none_of(0b1000_0011).clearing(0b1000_0000);
    /// assert_eq!((t.read_mask, t.write_mask), (0b1000_0011, 0b1000_0000));
    /// assert_eq!(t.fail_op, wgpu::StencilOperation::Zero);
    /// ```
    pub const fn clearing(self, bits: u32) -> StencilTest {
        StencilTest {
            fail_op: wgpu::StencilOperation::Zero,
            depth_fail_op: wgpu::StencilOperation::Zero,
            pass_op: wgpu::StencilOperation::Zero,
            write_mask: bits,
            ..self
        }
    }

    /// The pipeline's stencil state (everything but the reference).
    fn state(&self) -> wgpu::StencilState {
        let face = wgpu::StencilFaceState {
            compare: self.compare,
            fail_op: self.fail_op,
            depth_fail_op: self.depth_fail_op,
            pass_op: self.pass_op,
        };
        wgpu::StencilState {
            front: face,
            back: face,
            read_mask: self.read_mask,
            write_mask: self.write_mask,
        }
    }
}

/// How a draw tests and writes the pass's depth buffer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct DepthTest {
    /// The comparison against the stored depth (the fragment passes when
    /// `fragment <compare> stored`).
    pub compare: wgpu::CompareFunction,
    /// Whether passing fragments write their depth.
    pub write: bool,
}

impl DepthTest {
    /// Opaque geometry: `Less`, writing (Unity's `ZTest LEqual` on a cleared buffer draws the
    /// same pixels; `Less` keeps the first of two equal depths, deterministic in draw order).
    pub const OPAQUE: DepthTest = DepthTest {
        compare: wgpu::CompareFunction::Less,
        write: true,
    };

    /// A later pass over geometry already in the buffer (Unity's ForwardAdd: `ZTest LEqual`,
    /// `ZWrite Off`): only the fragments of the nearest surface pass.
    pub const SAME_SURFACE: DepthTest = DepthTest {
        compare: wgpu::CompareFunction::LessEqual,
        write: false,
    };

    /// The background at the far plane (Unity's skybox): [`DepthTest::SAME_SURFACE`]'s
    /// `ZTest LEqual`, `ZWrite Off`, drawn only where the buffer still holds its clear value, 1.
    pub const BACKGROUND: DepthTest = DepthTest::SAME_SURFACE;

    /// Semi-transparent geometry (Unity's transparent queue): [`DepthTest::SAME_SURFACE`]'s
    /// `ZTest LEqual`, `ZWrite Off`, in front of the opaque surfaces, leaving the buffer to them.
    pub const TRANSPARENT: DepthTest = DepthTest::SAME_SURFACE;
}

/// One draw of a [`DrawPass`]: a variant's text and entry points, its mesh and resources, and
/// the pipeline state that differs between draws of a frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Draw {
    /// Label used for the pipeline and in errors (usually the variant name).
    pub label: String,
    /// Complete WGSL source containing both entry points; shared, as many draws of a frame
    /// (one per light) use the same text.
    pub wgsl: Arc<str>,
    /// Name of the `@vertex` entry point.
    pub vertex_entry: String,
    /// Name of the `@fragment` entry point.
    pub fragment_entry: String,
    /// Number of vertices (a triangle list, one instance).
    pub vertex_count: u32,
    /// Vertex buffers in slot order (empty: positions from `@builtin(vertex_index)`).
    pub vertex_buffers: Vec<VertexBuffer>,
    /// Resources for bind groups 0..N; those the entry points do not use are skipped.
    pub resources: Vec<BoundResource>,
    /// More resources, in lists many draws share (a frame's camera and probes, an object's
    /// material, the G-buffer a light reads): shared lists cost neither a copy per draw nor
    /// a comparison of their contents.
    pub shared: Vec<Arc<[BoundResource]>>,
    /// Blend state for every colour target; `None` uses each [`ColorTarget::blend`].
    pub blend: Option<wgpu::BlendState>,
    /// Depth test; `None` draws without testing or writing depth.
    pub depth: Option<DepthTest>,
    /// Stencil test and marks (the pass needs [`DEPTH_STENCIL_FORMAT`]); `None` neither
    /// tests nor writes stencil.
    pub stencil: Option<StencilTest>,
    /// Faces culled (`None`: none).
    pub cull: Option<wgpu::Face>,
    /// Which channels of every colour target the draw writes; empty for a draw that only
    /// fills the depth buffer (its shader then needs no colour output).
    pub color_writes: wgpu::ColorWrites,
}

impl Draw {
    /// A full-screen draw: 3 vertices from `@builtin(vertex_index)`, no resources, no blend
    /// override, no depth test, no culling.
    pub fn fullscreen(
        label: &str,
        wgsl: &Arc<str>,
        vertex_entry: &str,
        fragment_entry: &str,
    ) -> Draw {
        Draw {
            label: label.to_owned(),
            wgsl: Arc::clone(wgsl),
            vertex_entry: vertex_entry.to_owned(),
            fragment_entry: fragment_entry.to_owned(),
            vertex_count: 3,
            vertex_buffers: Vec::new(),
            resources: Vec::new(),
            shared: Vec::new(),
            blend: None,
            depth: None,
            stencil: None,
            cull: None,
            color_writes: wgpu::ColorWrites::ALL,
        }
    }

    /// Draws `mesh` (all its vertices) instead of a full-screen triangle.
    pub fn with_mesh(mut self, mesh: VertexBuffer) -> Draw {
        self.vertex_count = (mesh.data.len() as u64 / mesh.stride.max(1)) as u32;
        self.vertex_buffers = vec![mesh];
        self
    }

    /// Sets the resources.
    pub fn with_resources(mut self, resources: Vec<BoundResource>) -> Draw {
        self.resources = resources;
        self
    }

    /// Adds a shared resource list.
    pub fn with_shared(mut self, shared: &Arc<[BoundResource]>) -> Draw {
        self.shared.push(Arc::clone(shared));
        self
    }

    /// Sets the blend state of every target.
    pub fn with_blend(mut self, blend: wgpu::BlendState) -> Draw {
        self.blend = Some(blend);
        self
    }

    /// Sets the depth test.
    pub fn with_depth(mut self, depth: DepthTest) -> Draw {
        self.depth = Some(depth);
        self
    }

    /// Sets the stencil test.
    pub fn with_stencil(mut self, stencil: StencilTest) -> Draw {
        self.stencil = Some(stencil);
        self
    }

    /// Culls `face`.
    pub fn with_cull(mut self, face: wgpu::Face) -> Draw {
        self.cull = Some(face);
        self
    }

    /// Writes no colour, only depth.
    pub fn depth_only(mut self) -> Draw {
        self.color_writes = wgpu::ColorWrites::empty();
        self
    }
}

/// Draws recorded in order into one render pass over shared targets.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawPass {
    /// Label of the pass (errors name the draw's own label where one draw is at fault).
    pub label: String,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
    /// Colour targets in `@location` order, cleared or started with their initial contents.
    pub targets: Vec<ColorTarget>,
    /// A depth buffer of [`DrawPass::depth_format`] cleared to 1 (the far plane; its stencil,
    /// if any, to 0), read back after the pass. Without it a draw's [`Draw::depth`] is an error; with it the pass may
    /// have no colour targets (a shadow map).
    pub depth: bool,
    /// The depth buffer's format: [`DEPTH_FORMAT`] unless set (`Depth16Unorm` for a shadow
    /// map the receivers compare against, [`DEPTH_STENCIL_FORMAT`] for stencil marks).
    pub depth_format: wgpu::TextureFormat,
    /// The draws, in order.
    pub draws: Vec<Draw>,
}

impl DrawPass {
    /// A pass of `width × height` over `targets`, no depth buffer, no draws yet.
    pub fn new(label: &str, width: u32, height: u32, targets: Vec<ColorTarget>) -> DrawPass {
        DrawPass {
            label: label.to_owned(),
            width,
            height,
            targets,
            depth: false,
            depth_format: DEPTH_FORMAT,
            draws: Vec::new(),
        }
    }
}

/// What a [`DrawPass`] left: each colour target's tightly packed bytes and the depth buffer
/// (one `f32` per pixel, row by row) when it had one.
#[derive(Clone, Debug, PartialEq)]
pub struct PassOutput {
    /// Colour targets, in target order.
    pub targets: Vec<Vec<u8>>,
    /// The depth buffer, with [`DrawPass::depth`] (a `Depth16Unorm` code `c` as `c / 65535`,
    /// exact in `f32`).
    pub depth: Option<Vec<f32>>,
    /// The stencil bits, one byte per pixel, with a [`DEPTH_STENCIL_FORMAT`] buffer.
    pub stencil: Option<Vec<u8>>,
}

/// What makes two draws' pipelines the same.
#[derive(PartialEq)]
struct PipelineKey<'a> {
    wgsl: &'a str,
    vertex_entry: &'a str,
    fragment_entry: &'a str,
    blend: Option<wgpu::BlendState>,
    depth: Option<DepthTest>,
    stencil: Option<wgpu::StencilState>,
    cull: Option<wgpu::Face>,
    color_writes: wgpu::ColorWrites,
    layouts: Vec<(u64, &'a [wgpu::VertexAttribute])>,
}

impl<'a> PipelineKey<'a> {
    fn of(draw: &'a Draw) -> Self {
        Self {
            wgsl: &draw.wgsl,
            vertex_entry: &draw.vertex_entry,
            fragment_entry: &draw.fragment_entry,
            blend: draw.blend,
            depth: draw.depth,
            stencil: draw.stencil.map(|s| s.state()),
            cull: draw.cull,
            color_writes: draw.color_writes,
            layouts: draw
                .vertex_buffers
                .iter()
                .map(|vb| (vb.stride, vb.attributes.as_slice()))
                .collect(),
        }
    }
}

/// Renders every draw of `pass` in order and reads the targets (and depth) back.
///
/// Each draw is checked like a [`RenderJob`](super::RenderJob): vertex buffers large
/// enough, a resource for every slot its entry points use ([`GpuError::Validation`] naming the
/// draw), shaders that compile ([`GpuError::PipelineCompile`]). The wait is bounded by
/// [`GpuContext::timeout`].
pub fn render_pass(ctx: &GpuContext, pass: &DrawPass) -> Result<PassOutput, GpuError> {
    let label = pass.label.as_str();
    check_targets(
        ctx,
        label,
        pass.width,
        pass.height,
        &pass.targets,
        pass.depth,
    )?;
    let prepared = prepare_draws(
        ctx,
        &pass.targets,
        pass.depth.then_some(pass.depth_format),
        &pass.draws,
        &[],
    )?;

    let pending = ctx.scoped(label, || {
        let targets = create_targets(ctx, label, pass.width, pass.height, &pass.targets);
        let views = views(&targets);
        let attachments = color_attachments(&views, &pass.targets);
        let depth = pass.depth.then(|| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: wgpu::Extent3d {
                    width: pass.width,
                    height: pass.height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format: pass.depth_format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        });
        let depth_view = depth
            .as_ref()
            .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()));
        let stencil = pass.depth_format.has_stencil_aspect();
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        {
            let mut rp = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &attachments,
                depth_stencil_attachment: depth_view.as_ref().map(|view| {
                    wgpu::RenderPassDepthStencilAttachment {
                        view,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: stencil.then_some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(0),
                            store: wgpu::StoreOp::Store,
                        }),
                    }
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            prepared.record(&mut rp);
        }
        let mut pending = targets
            .iter()
            .map(|t| encode_texture_readback(ctx, &mut encoder, t, label))
            .collect::<Result<Vec<_>, _>>();
        if let (Ok(pending), Some(depth)) = (&mut pending, &depth) {
            let aspects: &[wgpu::TextureAspect] = if stencil {
                &[
                    wgpu::TextureAspect::DepthOnly,
                    wgpu::TextureAspect::StencilOnly,
                ]
            } else {
                &[wgpu::TextureAspect::All]
            };
            for aspect in aspects {
                match encode_aspect_readback(ctx, &mut encoder, depth, *aspect, label) {
                    Ok(p) => pending.push(p),
                    Err(e) => return Err(e),
                }
            }
        }
        if pending.is_ok() {
            ctx.queue.submit([encoder.finish()]);
        }
        pending
    })??;
    let mut targets = finish_readbacks(ctx, label, pending)?;
    let stencil = (pass.depth && pass.depth_format.has_stencil_aspect())
        .then(|| targets.pop().unwrap_or_default());
    let depth = pass.depth.then(|| {
        let bytes = targets.pop().unwrap_or_default();
        match pass.depth_format {
            wgpu::TextureFormat::Depth16Unorm => bytes
                .chunks_exact(2)
                .map(|b| f32::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0)
                .collect(),
            _ => bytes
                .chunks_exact(4)
                .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect(),
        }
    });
    Ok(PassOutput {
        targets,
        depth,
        stencil,
    })
}

/// The draws of a pass made ready to record: each distinct pipeline compiled once (same text,
/// entry points, blend, depth test and vertex layout), each distinct resource uploaded once,
/// and every draw's bind groups and vertex buffers. Recording them again costs no upload,
/// which is what a timed frame needs ([`crate::check::frame::timed`]).
#[derive(Debug)]
pub(crate) struct PreparedDraws {
    pipelines: Vec<wgpu::RenderPipeline>,
    draws: Vec<PreparedDraw>,
}

/// One draw of [`PreparedDraws`]: its pipeline's index, bind groups, vertex buffers and
/// vertex count.
#[derive(Debug)]
struct PreparedDraw {
    pipeline: usize,
    stencil_reference: u32,
    groups: Vec<(u32, wgpu::BindGroup)>,
    buffers: Vec<wgpu::Buffer>,
    vertex_count: u32,
}

/// Checks and prepares `draws` for a pass over `targets` (their formats and blends) and a
/// depth buffer of `depth_format` (`None`: no depth buffer). `views` bind textures already on
/// the GPU (an earlier pass's targets) at their slots for every draw whose entry points use
/// the slot, before the draw's own resources (a slot given twice is an error).
///
/// Errors as [`render_pass`]: a vertex buffer too small, a used slot without a resource, a
/// depth test without a depth buffer ([`GpuError::Validation`]), a shader that does not
/// compile ([`GpuError::PipelineCompile`]).
pub(crate) fn prepare_draws(
    ctx: &GpuContext,
    targets: &[ColorTarget],
    depth_format: Option<wgpu::TextureFormat>,
    draws: &[Draw],
    views: &[(Slot, wgpu::TextureView)],
) -> Result<PreparedDraws, GpuError> {
    let mut keys: Vec<PipelineKey<'_>> = Vec::new();
    let mut pipelines: Vec<(wgpu::RenderPipeline, BTreeSet<Slot>)> = Vec::new();
    let mut prepared = Vec::with_capacity(draws.len());
    let mut pool = ResourcePool::default();
    let mut meshes: Vec<(&VertexBuffer, wgpu::Buffer)> = Vec::new();
    for draw in draws {
        let dl = draw.label.as_str();
        check_vertex_buffers(dl, &draw.vertex_buffers, draw.vertex_count)?;
        if draw.depth.is_some() && depth_format.is_none() {
            return Err(GpuError::Validation {
                label: dl.to_owned(),
                message: String::from("the draw tests depth but the pass has no depth buffer"),
            });
        }
        if draw.stencil.is_some() && !depth_format.is_some_and(|f| f.has_stencil_aspect()) {
            return Err(GpuError::Validation {
                label: dl.to_owned(),
                message: format!(
                    "the draw tests stencil but the pass's depth buffer ({depth_format:?}) has no \
                     stencil (use {DEPTH_STENCIL_FORMAT:?})"
                ),
            });
        }
        let key = PipelineKey::of(draw);
        let index = match keys.iter().position(|k| *k == key) {
            Some(i) => i,
            None => {
                let color_states: Vec<Option<wgpu::ColorTargetState>> = targets
                    .iter()
                    .map(|t| {
                        Some(wgpu::ColorTargetState {
                            format: t.format.wgpu_format(),
                            blend: draw.blend.or(t.blend),
                            write_mask: draw.color_writes,
                        })
                    })
                    .collect();
                let depth_stencil = depth_format.map(|format| {
                    let test = draw.depth.unwrap_or(DepthTest {
                        compare: wgpu::CompareFunction::Always,
                        write: false,
                    });
                    depth_state(format, test, draw.stencil)
                });
                let compiled = create_pipeline(
                    ctx,
                    &PipelineDesc {
                        label: dl,
                        wgsl: &draw.wgsl,
                        vertex: &draw.vertex_entry,
                        fragment: Some(&draw.fragment_entry),
                        vertex_buffers: &vertex_layouts(&draw.vertex_buffers),
                        cull: draw.cull,
                        depth_stencil,
                        targets: &color_states,
                    },
                )?;
                keys.push(key);
                pipelines.push(compiled);
                pipelines.len() - 1
            }
        };
        let all = draw
            .shared
            .iter()
            .flat_map(|l| l.iter())
            .chain(&draw.resources);
        let mut resources = GpuResources::upload_pooled(ctx, dl, all, &mut pool)?;
        let (pipeline, used) = &pipelines[index];
        // A draw that brings its own resource for a slot keeps it (the stencil pre-pass's
        // camera where the Lighting draws read the G-buffer).
        let inputs: Vec<&(Slot, wgpu::TextureView)> = views
            .iter()
            .filter(|(slot, _)| used.contains(slot) && !resources.contains(*slot))
            .collect();
        for (slot, view) in inputs {
            resources.insert_view(dl, *slot, view.clone())?;
        }
        let groups = bind(ctx, dl, pipeline, used, &resources)?;
        let buffers = draw
            .vertex_buffers
            .iter()
            .map(|vb| match meshes.iter().find(|(known, _)| *known == vb) {
                Some((_, buffer)) => buffer.clone(),
                None => {
                    let buffer = upload_vertex_buffers(ctx, dl, std::slice::from_ref(vb)).remove(0);
                    meshes.push((vb, buffer.clone()));
                    buffer
                }
            })
            .collect::<Vec<_>>();
        prepared.push(PreparedDraw {
            pipeline: index,
            stencil_reference: draw.stencil.map_or(0, |s| s.reference),
            groups,
            buffers,
            vertex_count: draw.vertex_count,
        });
    }
    Ok(PreparedDraws {
        pipelines: pipelines.into_iter().map(|(p, _)| p).collect(),
        draws: prepared,
    })
}

impl PreparedDraws {
    /// Records every draw, in order, into `rp`.
    pub(crate) fn record(&self, rp: &mut wgpu::RenderPass<'_>) {
        for draw in &self.draws {
            rp.set_pipeline(&self.pipelines[draw.pipeline]);
            rp.set_stencil_reference(draw.stencil_reference);
            for (group, bind_group) in &draw.groups {
                rp.set_bind_group(*group, bind_group, &[]);
            }
            for (slot, buffer) in (0u32..).zip(&draw.buffers) {
                rp.set_vertex_buffer(slot, buffer.slice(..));
            }
            rp.draw(0..draw.vertex_count, 0..1);
        }
    }

    /// Number of draws.
    pub(crate) fn len(&self) -> usize {
        self.draws.len()
    }
}

/// The state of `test` and `stencil` (none: the stencil neither tested nor written) on a
/// buffer of `format`, no bias.
fn depth_state(
    format: wgpu::TextureFormat,
    test: DepthTest,
    stencil: Option<StencilTest>,
) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format,
        depth_write_enabled: Some(test.write),
        depth_compare: Some(test.compare),
        stencil: stencil.map_or_else(wgpu::StencilState::default, |s| s.state()),
        bias: wgpu::DepthBiasState::default(),
    }
}
