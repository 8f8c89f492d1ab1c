//! Passes whose targets stay on the GPU: a chain of render passes where each reads what the
//! one before wrote, with no copy through the CPU, prepared once and recorded as often as a
//! timed frame needs.
//!
//! [`render_pass`](super::render_pass) uploads what a pass starts from and reads back what it
//! left, which is what a per-texel proof needs and what a renderer never does between passes.
//! Here a [`GpuTexture`] is created once; a [`ResidentPass`] renders into some of them (clearing
//! or loading each), may use one as a read-only depth attachment (the G-buffer's depth, which a
//! light volume's depth test reads) and binds others as textures at given slots (the G-buffer
//! the Lighting pass samples); [`prepare`] compiles and uploads everything its draws need, and
//! [`PreparedPass::encode`] records it, optionally with timestamp writes.

use super::pass::{Draw, PreparedDraws, prepare_draws};
use super::target::ColorTarget;
use crate::bindings::Slot;
use crate::context::GpuContext;
use crate::error::GpuError;
use crate::format::TargetFormat;
use crate::readback::read_texture;

/// A 2D texture that lives on the GPU across passes: a render target of one pass, a bound
/// texture or a depth attachment of the next, copied back only when asked
/// ([`GpuTexture::read`]).
#[derive(Debug)]
pub(crate) struct GpuTexture {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    /// The view a shader binds: the depth aspect alone of a depth-stencil format.
    bind_view: wgpu::TextureView,
}

impl GpuTexture {
    /// A `width × height` texture of `format`, usable as a render attachment, as a bound
    /// texture and as a copy source.
    pub(crate) fn new(
        ctx: &GpuContext,
        label: &str,
        width: u32,
        height: u32,
        format: wgpu::TextureFormat,
    ) -> Result<GpuTexture, GpuError> {
        let texture = ctx.scoped(label, || {
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
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT
                    | wgpu::TextureUsages::TEXTURE_BINDING
                    | wgpu::TextureUsages::COPY_SRC
                    | wgpu::TextureUsages::COPY_DST,
                view_formats: &[],
            })
        })?;
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_view = if format.has_stencil_aspect() {
            texture.create_view(&wgpu::TextureViewDescriptor {
                aspect: wgpu::TextureAspect::DepthOnly,
                ..Default::default()
            })
        } else {
            view.clone()
        };
        Ok(GpuTexture {
            texture,
            view,
            bind_view,
        })
    }

    /// Width and height in texels.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.texture.width(), self.texture.height())
    }

    /// The texture's format.
    pub(crate) fn format(&self) -> wgpu::TextureFormat {
        self.texture.format()
    }

    /// Bytes of one texel as a shader or a blend reads it (a depth format's depth aspect).
    pub(crate) fn texel_bytes(&self) -> u64 {
        let format = self.format();
        let aspect = format
            .has_depth_aspect()
            .then_some(wgpu::TextureAspect::DepthOnly);
        u64::from(format.block_copy_size(aspect).unwrap_or(0))
    }

    /// Copies the texture back (one submission, bounded wait): tightly packed rows.
    pub(crate) fn read(&self, ctx: &GpuContext, label: &str) -> Result<Vec<u8>, GpuError> {
        read_texture(ctx, label, &self.texture)
    }
}

/// How a [`ResidentPass`] uses its depth texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum DepthUse {
    /// Cleared to 1 (the far plane; a stencil aspect to 0), written by the draws, stored.
    Clear,
    /// Loaded and never written: a later pass testing against an earlier pass's depth, which
    /// it may also bind as a texture at the same time (both uses only read).
    ReadOnly,
    /// Depth as [`DepthUse::ReadOnly`]; the stencil loaded, written by the draws and stored
    /// (the Lighting pass: its volumes' stencil pre-passes mark what the lights then clear).
    ReadDepthWriteStencil,
}

/// One colour attachment of a [`ResidentPass`].
#[derive(Debug)]
pub(crate) struct ResidentColor<'a> {
    /// The texture rendered into.
    pub(crate) texture: &'a GpuTexture,
    /// `Some(colour)`: cleared to it; `None`: its contents are loaded (an earlier pass's).
    pub(crate) clear: Option<[f64; 4]>,
    /// Blend state for draws that set none.
    pub(crate) blend: Option<wgpu::BlendState>,
}

/// A render pass over [`GpuTexture`]s.
#[derive(Debug)]
pub(crate) struct ResidentPass<'a> {
    /// The pass's label (errors name the draw's own where one draw is at fault).
    pub(crate) label: &'a str,
    /// Colour attachments, in `@location` order.
    pub(crate) colors: Vec<ResidentColor<'a>>,
    /// The depth attachment and how it is used.
    pub(crate) depth: Option<(&'a GpuTexture, DepthUse)>,
    /// Textures bound at their slots for every draw that uses the slot.
    pub(crate) inputs: Vec<(Slot, &'a GpuTexture)>,
    /// After the pass, the depth aspect of the depth attachment copied into this `R32Float`
    /// texture: what a later pass samples while it writes the attachment's stencil (WebGPU
    /// tracks a texture's uses as a whole, so a pass cannot sample the depth of the texture
    /// whose stencil it writes).
    pub(crate) copy_depth_to: Option<&'a GpuTexture>,
    /// The draws, in order (their own resources are uploaded once by [`prepare`]).
    pub(crate) draws: &'a [Draw],
}

/// A [`ResidentPass`] ready to record: attachments, pipelines, bind groups and buffers.
#[derive(Debug)]
pub(crate) struct PreparedPass {
    label: String,
    colors: Vec<(wgpu::TextureView, wgpu::LoadOp<wgpu::Color>)>,
    depth: Option<(wgpu::TextureView, DepthUse)>,
    /// Whether the depth attachment has a stencil aspect.
    stencil: bool,
    draws: PreparedDraws,
    /// The depth copy after the pass: the attachment, a staging buffer and the target.
    depth_copy: Option<DepthCopy>,
}

/// [`ResidentPass::copy_depth_to`], prepared: depth aspect → buffer → `R32Float` texture.
#[derive(Debug)]
struct DepthCopy {
    depth: wgpu::Texture,
    buffer: wgpu::Buffer,
    bytes_per_row: u32,
    target: wgpu::Texture,
}

/// Checks `pass` and prepares its draws ([`GpuError::Validation`] for a colour attachment
/// whose format is not a [`TargetFormat`], and every error of
/// [`render_pass`](super::render_pass)'s preparation).
pub(crate) fn prepare(ctx: &GpuContext, pass: &ResidentPass<'_>) -> Result<PreparedPass, GpuError> {
    let targets = pass
        .colors
        .iter()
        .map(|c| {
            let format = TargetFormat::from_wgpu(c.texture.format()).ok_or_else(|| {
                GpuError::Validation {
                    label: pass.label.to_owned(),
                    message: format!("{:?} is not a colour target format", c.texture.format()),
                }
            })?;
            Ok(ColorTarget {
                blend: c.blend,
                ..ColorTarget::new(format)
            })
        })
        .collect::<Result<Vec<_>, GpuError>>()?;
    let views: Vec<(Slot, wgpu::TextureView)> = pass
        .inputs
        .iter()
        .map(|(slot, t)| (*slot, t.bind_view.clone()))
        .collect();
    let depth_format = pass.depth.map(|(t, _)| t.format());
    let draws = prepare_draws(ctx, &targets, depth_format, pass.draws, &views)?;
    let depth_copy = match (pass.depth, pass.copy_depth_to) {
        (Some((depth, _)), Some(target)) => {
            let (w, h) = depth.size();
            let bytes_per_row = (w * 4).next_multiple_of(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT);
            let buffer = ctx.scoped(pass.label, || {
                ctx.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(pass.label),
                    size: u64::from(bytes_per_row) * u64::from(h),
                    usage: wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            })?;
            Some(DepthCopy {
                depth: depth.texture.clone(),
                buffer,
                bytes_per_row,
                target: target.texture.clone(),
            })
        }
        (None, Some(_)) => {
            return Err(GpuError::Validation {
                label: pass.label.to_owned(),
                message: String::from("a depth copy needs a depth attachment"),
            });
        }
        _ => None,
    };
    Ok(PreparedPass {
        label: pass.label.to_owned(),
        colors: pass
            .colors
            .iter()
            .map(|c| {
                let load = match c.clear {
                    Some([r, g, b, a]) => wgpu::LoadOp::Clear(wgpu::Color { r, g, b, a }),
                    None => wgpu::LoadOp::Load,
                };
                (c.texture.view.clone(), load)
            })
            .collect(),
        depth: pass.depth.map(|(t, use_)| (t.view.clone(), use_)),
        stencil: depth_format.is_some_and(|f| f.has_stencil_aspect()),
        draws,
        depth_copy,
    })
}

impl PreparedPass {
    /// The pass's label.
    pub(crate) fn label(&self) -> &str {
        &self.label
    }

    /// Number of draws.
    pub(crate) fn draws(&self) -> usize {
        self.draws.len()
    }

    /// Records the pass into `encoder`, with `timestamps` written at its start and end when
    /// given (the device needs `TIMESTAMP_QUERY`).
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamps: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) {
        let colors: Vec<Option<wgpu::RenderPassColorAttachment<'_>>> = self
            .colors
            .iter()
            .map(|(view, load)| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: *load,
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let depth =
            self.depth
                .as_ref()
                .map(|(view, use_)| wgpu::RenderPassDepthStencilAttachment {
                    view,
                    // No depth ops: a read-only attachment, which the same pass may also sample.
                    depth_ops: (*use_ == DepthUse::Clear).then_some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    // Likewise the stencil: cleared to 0 and marked, or only tested.
                    stencil_ops: match use_ {
                        _ if !self.stencil => None,
                        DepthUse::Clear => Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(0),
                            store: wgpu::StoreOp::Store,
                        }),
                        DepthUse::ReadDepthWriteStencil => Some(wgpu::Operations {
                            load: wgpu::LoadOp::Load,
                            store: wgpu::StoreOp::Store,
                        }),
                        DepthUse::ReadOnly => None,
                    },
                });
        let mut rp = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some(&self.label),
            color_attachments: &colors,
            depth_stencil_attachment: depth,
            timestamp_writes: timestamps,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        self.draws.record(&mut rp);
        drop(rp);
        if let Some(copy) = &self.depth_copy {
            let size = copy.depth.size();
            let layout = wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(copy.bytes_per_row),
                rows_per_image: Some(size.height),
            };
            encoder.copy_texture_to_buffer(
                wgpu::TexelCopyTextureInfo {
                    texture: &copy.depth,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::DepthOnly,
                },
                wgpu::TexelCopyBufferInfo {
                    buffer: &copy.buffer,
                    layout,
                },
                size,
            );
            encoder.copy_buffer_to_texture(
                wgpu::TexelCopyBufferInfo {
                    buffer: &copy.buffer,
                    layout,
                },
                wgpu::TexelCopyTextureInfo {
                    texture: &copy.target,
                    mip_level: 0,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                size,
            );
        }
    }
}
