//! What a draw writes to and reads its mesh from: colour targets ([`ColorTarget`], cleared or
//! started with given contents, so blending onto an earlier result can be checked) and vertex
//! buffers ([`VertexBuffer`]), with the checks, uploads, views and attachments that
//! [`RenderJob`](super::RenderJob)s and [`DrawPass`](super::DrawPass)es share.

use crate::context::GpuContext;
use crate::error::GpuError;
use crate::format::TargetFormat;

/// One colour target of a [`RenderJob`](crate::RenderJob).
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

/// One vertex buffer of a [`RenderJob`](crate::RenderJob): per-vertex data and the layout the vertex shader
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
            let size = crate::readback::align_up(vb.data.len() as u64, 4).max(4);
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
