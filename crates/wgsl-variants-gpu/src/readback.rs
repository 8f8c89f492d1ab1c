//! Copying textures and buffers back to the CPU with bounded waits.

use std::sync::mpsc;

use super::context::GpuContext;
use super::error::GpuError;

/// Rounds `value` up to a multiple of `align` (a power of two).
pub(crate) fn align_up(value: u64, align: u64) -> u64 {
    value.div_ceil(align) * align
}

/// A texture-to-buffer copy that has been encoded but not yet read back.
///
/// Created by [`encode_texture_readback`]; after the encoder has been submitted, hand it to
/// [`finish_readbacks`] (or [`PendingReadback::finish`]) to get tightly packed bytes.
#[derive(Debug)]
pub struct PendingReadback {
    /// `COPY_DST | MAP_READ` staging buffer the texture is copied into.
    buffer: wgpu::Buffer,
    /// Number of block rows copied.
    height: u32,
    /// Bytes of texel data per row.
    unpadded_bytes_per_row: u32,
    /// Row stride in the staging buffer (a multiple of 256).
    padded_bytes_per_row: u32,
}

impl PendingReadback {
    /// Maps the staging buffer (bounded wait) and returns the tightly packed texel rows.
    /// The encoder that recorded the copy must have been submitted.
    pub fn finish(self, ctx: &GpuContext, label: &str) -> Result<Vec<u8>, GpuError> {
        let mut out = finish_readbacks(ctx, label, vec![self])?;
        out.pop().ok_or_else(|| GpuError::Readback {
            label: label.to_owned(),
            message: String::from("no readback result"),
        })
    }
}

/// Records a copy of mip level 0 of a 2D `texture` into a new staging buffer, handling the
/// 256-byte row alignment.
///
/// The texture needs `COPY_SRC` usage and a format with a single copyable aspect
/// (no combined depth-stencil: [`encode_aspect_readback`] copies one aspect of those);
/// otherwise, or if the staging buffer would exceed the device's `max_buffer_size`, a
/// [`GpuError::Readback`] is returned and nothing is recorded.
pub fn encode_texture_readback(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    label: &str,
) -> Result<PendingReadback, GpuError> {
    encode_aspect_readback(ctx, encoder, texture, wgpu::TextureAspect::All, label)
}

/// [`encode_texture_readback`] of one `aspect` of the texture: `DepthOnly` (4 bytes a
/// texel for `Depth32FloatStencil8`) or `StencilOnly` (1 byte) of a combined depth-stencil
/// format; `All` for the others.
pub fn encode_aspect_readback(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    texture: &wgpu::Texture,
    aspect: wgpu::TextureAspect,
    label: &str,
) -> Result<PendingReadback, GpuError> {
    let fail = |message: String| GpuError::Readback {
        label: label.to_owned(),
        message,
    };
    if !texture.usage().contains(wgpu::TextureUsages::COPY_SRC) {
        return Err(fail(String::from("texture lacks COPY_SRC usage")));
    }
    if texture.dimension() != wgpu::TextureDimension::D2 {
        return Err(fail(format!(
            "only 2D textures can be read back, not {:?}",
            texture.dimension()
        )));
    }
    let format = texture.format();
    if aspect == wgpu::TextureAspect::All
        && format.has_depth_aspect()
        && format.has_stencil_aspect()
    {
        return Err(fail(format!(
            "cannot read back combined depth-stencil {format:?} whole: read one aspect"
        )));
    }
    let (block_w, block_h) = format.block_dimensions();
    let block_size = format
        .block_copy_size(Some(aspect))
        .ok_or_else(|| fail(format!("format {format:?} cannot be copied to a buffer")))?;
    let size = texture.size();
    let blocks_x = size.width.div_ceil(block_w);
    let rows = size.height.div_ceil(block_h);
    let unpadded = u64::from(blocks_x) * u64::from(block_size);
    let padded = align_up(unpadded, u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT));
    let total = padded * u64::from(rows);
    let max = ctx.device.limits().max_buffer_size;
    if total > max || padded > u64::from(u32::MAX) {
        return Err(fail(format!(
            "readback of {}x{} {format:?} needs {total} bytes, more than max_buffer_size {max}",
            size.width, size.height
        )));
    }
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: total.max(wgpu::COPY_BUFFER_ALIGNMENT),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    // Both fit in u32: checked against u32::MAX above.
    let padded_bytes_per_row = padded as u32;
    let unpadded_bytes_per_row = unpadded as u32;
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_bytes_per_row),
                rows_per_image: Some(rows),
            },
        },
        wgpu::Extent3d {
            width: size.width,
            height: size.height,
            depth_or_array_layers: 1,
        },
    );
    Ok(PendingReadback {
        buffer,
        height: rows,
        unpadded_bytes_per_row,
        padded_bytes_per_row,
    })
}

/// Maps the staging buffers of several readbacks with one bounded wait and returns the tightly
/// packed bytes of each, in order. The encoders that recorded the copies must have been
/// submitted.
pub fn finish_readbacks(
    ctx: &GpuContext,
    label: &str,
    pending: Vec<PendingReadback>,
) -> Result<Vec<Vec<u8>>, GpuError> {
    let buffers: Vec<&wgpu::Buffer> = pending.iter().map(|p| &p.buffer).collect();
    let raw = map_buffers(ctx, label, &buffers)?;
    Ok(pending
        .iter()
        .zip(raw)
        .map(|(p, bytes)| {
            let row = p.unpadded_bytes_per_row as usize;
            let stride = p.padded_bytes_per_row as usize;
            let mut out = Vec::with_capacity(row * p.height as usize);
            for chunk in bytes.chunks(stride).take(p.height as usize) {
                out.extend_from_slice(&chunk[..row.min(chunk.len())]);
            }
            out
        })
        .collect())
}

/// Copies mip level 0 of a 2D `texture` (which needs `COPY_SRC`) back to the CPU and returns
/// tightly packed rows. Submits its own command buffer and waits with the context's timeout.
pub fn read_texture(
    ctx: &GpuContext,
    label: &str,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, GpuError> {
    let (pending, error) = ctx.capture(|| {
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        let pending = encode_texture_readback(ctx, &mut encoder, texture, label);
        if pending.is_ok() {
            ctx.queue.submit([encoder.finish()]);
        }
        pending
    });
    if let Some(error) = error {
        return Err(GpuError::Readback {
            label: label.to_owned(),
            message: super::context::error_message(&error),
        });
    }
    pending?.finish(ctx, label)
}

/// Maps whole `MAP_READ` buffers for reading with one bounded wait and copies their contents
/// out. Work writing to the buffers must have been submitted already.
///
/// Buffers must not be mapped already. Each buffer is unmapped again before returning.
pub fn map_buffers(
    ctx: &GpuContext,
    label: &str,
    buffers: &[&wgpu::Buffer],
) -> Result<Vec<Vec<u8>>, GpuError> {
    let fail = |message: String| GpuError::Readback {
        label: label.to_owned(),
        message,
    };
    let mut receivers = Vec::with_capacity(buffers.len());
    for buffer in buffers {
        if !buffer.usage().contains(wgpu::BufferUsages::MAP_READ) {
            return Err(fail(String::from("buffer lacks MAP_READ usage")));
        }
        if buffer.size() % wgpu::COPY_BUFFER_ALIGNMENT != 0 {
            return Err(fail(format!(
                "buffer size {} is not a multiple of 4",
                buffer.size()
            )));
        }
        let (tx, rx) = mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |result| {
            // The receiver outlives the wait below; a send error only means we gave up.
            let _ = tx.send(result);
        });
        receivers.push(rx);
    }
    let waited = ctx.wait(label);
    let mut out = Vec::with_capacity(buffers.len());
    let mut first_error = waited.err();
    for (buffer, rx) in buffers.iter().zip(receivers) {
        // Unmap only buffers that are mapped or still waiting (which aborts the mapping):
        // unmapping an idle buffer is itself a wgpu error.
        let result = match rx.try_recv() {
            Ok(Ok(())) => {
                let bytes = match buffer.get_mapped_range(..) {
                    Ok(view) => Ok(view.to_vec()),
                    Err(e) => Err(fail(format!("get_mapped_range: {e}"))),
                };
                buffer.unmap();
                bytes
            }
            Ok(Err(e)) => Err(fail(format!("map_async: {e}"))),
            Err(_) => {
                buffer.unmap();
                Err(fail(String::from("buffer was not mapped after the wait")))
            }
        };
        match result {
            Ok(bytes) => out.push(bytes),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    match first_error {
        Some(e) => Err(e),
        None => Ok(out),
    }
}
