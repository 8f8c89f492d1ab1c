//! Shader resources (buffers, textures, samplers) described on the CPU and uploaded once.

use std::collections::BTreeMap;

use super::bindings::Slot;
use super::context::GpuContext;
use super::error::GpuError;

/// A resource to bind at some `@group/@binding`.
#[derive(Debug, Clone, PartialEq)]
pub enum Resource {
    /// A uniform buffer with these contents (zero-padded to a multiple of 16 bytes).
    Uniform(Vec<u8>),
    /// A storage buffer with these contents (zero-padded to a multiple of 4 bytes).
    Storage(Vec<u8>),
    /// A 2D texture with one mip level; `data` holds tightly packed rows.
    Texture2d {
        /// Texel format.
        format: wgpu::TextureFormat,
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
        /// Tightly packed texel rows.
        data: Vec<u8>,
    },
    /// A cube texture, bound as a cube view.
    TextureCube {
        /// Texel format.
        format: wgpu::TextureFormat,
        /// Edge length of mip level 0 in texels.
        size: u32,
        /// Mip levels, base level first (each halves the size, minimum 1). Each level holds
        /// the six faces in +X, -X, +Y, -Y, +Z, -Z order as tightly packed rows. At least one.
        levels: Vec<[Vec<u8>; 6]>,
    },
    /// A filtering (linear) or non-filtering (nearest) sampler with clamp-to-edge addressing.
    Sampler {
        /// Use nearest filtering (a non-filtering sampler) instead of linear.
        nearest: bool,
    },
    /// Like [`Resource::Sampler`], with the given addressing mode on all three axes (e.g.
    /// [`wgpu::AddressMode::Repeat`] for tiled detail maps).
    SamplerAddressed {
        /// Use nearest filtering (a non-filtering sampler) instead of linear.
        nearest: bool,
        /// Addressing mode for u, v and w.
        address_mode: wgpu::AddressMode,
    },
    /// A comparison sampler (`sampler_comparison`), clamp-to-edge addressing: with `nearest`
    /// each lookup compares one texel (0 or 1), otherwise the hardware filters the 2 × 2
    /// comparisons bilinearly.
    ComparisonSampler {
        /// The comparison function.
        compare: wgpu::CompareFunction,
        /// Nearest filtering instead of linear.
        nearest: bool,
    },
}

/// A [`Resource`] together with the slot it is bound at.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundResource {
    /// The `@group` index.
    pub group: u32,
    /// The `@binding` index.
    pub binding: u32,
    /// The resource.
    pub resource: Resource,
}

impl BoundResource {
    /// Binds `resource` at `@group(group) @binding(binding)`.
    pub fn new(group: u32, binding: u32, resource: Resource) -> Self {
        Self {
            group,
            binding,
            resource,
        }
    }
}

/// One uploaded resource (handles: cloning shares the GPU object).
#[derive(Clone, Debug)]
enum GpuResource {
    Buffer(wgpu::Buffer),
    Texture {
        view: wgpu::TextureView,
        // Kept alive for the view's sake.
        _texture: wgpu::Texture,
    },
    Sampler(wgpu::Sampler),
    /// A view of a texture already on the GPU (an earlier pass's target), not uploaded here.
    View(wgpu::TextureView),
}

/// Resources uploaded to the GPU once, to be bound by any number of pipelines
/// (see [`crate::render_with`]).
#[derive(Debug, Default)]
pub struct GpuResources {
    slots: BTreeMap<Slot, GpuResource>,
}

impl GpuResources {
    /// Creates and uploads every resource (via `Queue::write_buffer` / `write_texture`).
    ///
    /// Texture data that is too short for the declared size, duplicate slots and wgpu errors
    /// are reported as [`GpuError::Validation`] labelled `label`.
    pub fn upload(
        ctx: &GpuContext,
        label: &str,
        resources: &[BoundResource],
    ) -> Result<Self, GpuError> {
        Self::upload_pooled(ctx, label, resources, &mut ResourcePool::default())
    }

    /// Like [`GpuResources::upload`], but a resource equal to one already in `pool` is not
    /// uploaded again: its GPU object is shared (many draws of a frame bind the same camera,
    /// probes and cube maps). Storage buffers are never shared (a shader may write them).
    pub(crate) fn upload_pooled<'a>(
        ctx: &GpuContext,
        label: &str,
        resources: impl IntoIterator<Item = &'a BoundResource>,
        pool: &mut ResourcePool<'a>,
    ) -> Result<Self, GpuError> {
        ctx.check_device()?;
        let result = ctx.scoped(label, || {
            let mut slots = BTreeMap::new();
            for r in resources {
                let slot = (r.group, r.binding);
                if slots.contains_key(&slot) {
                    return Err(invalid(
                        label,
                        format!("@group({}) @binding({}) given twice", slot.0, slot.1),
                    ));
                }
                // The same object (a shared list) first: comparing contents is the slow path.
                let shareable = !matches!(r.resource, Resource::Storage(_));
                let shared = pool
                    .entries
                    .iter()
                    .find(|(known, _)| std::ptr::eq(*known, &r.resource))
                    .or_else(|| pool.entries.iter().find(|(known, _)| *known == &r.resource))
                    .filter(|_| shareable);
                let uploaded = match shared {
                    Some((_, gpu)) => gpu.clone(),
                    None => {
                        let gpu = upload_one(ctx, label, &r.resource)?;
                        if shareable {
                            pool.entries.push((&r.resource, gpu.clone()));
                        }
                        gpu
                    }
                };
                slots.insert(slot, uploaded);
            }
            Ok(Self { slots })
        });
        result?
    }

    /// Number of uploaded resources.
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    /// Whether nothing was uploaded.
    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// Whether a resource was uploaded for `(group, binding)`.
    pub fn contains(&self, slot: Slot) -> bool {
        self.slots.contains_key(&slot)
    }

    /// The binding resource for `slot`, if one was uploaded.
    pub fn binding_resource(&self, slot: Slot) -> Option<wgpu::BindingResource<'_>> {
        self.slots.get(&slot).map(|r| match r {
            GpuResource::Buffer(buffer) => buffer.as_entire_binding(),
            GpuResource::Texture { view, .. } => wgpu::BindingResource::TextureView(view),
            GpuResource::Sampler(sampler) => wgpu::BindingResource::Sampler(sampler),
            GpuResource::View(view) => wgpu::BindingResource::TextureView(view),
        })
    }

    /// Binds `view`, a texture already on the GPU, at `slot` (a G-buffer target the lighting
    /// pass reads where it was rendered: no copy through the CPU). A slot already holding a
    /// resource is a [`GpuError::Validation`] labelled `label`.
    pub(crate) fn insert_view(
        &mut self,
        label: &str,
        slot: Slot,
        view: wgpu::TextureView,
    ) -> Result<(), GpuError> {
        if self.slots.contains_key(&slot) {
            return Err(invalid(
                label,
                format!("@group({}) @binding({}) given twice", slot.0, slot.1),
            ));
        }
        self.slots.insert(slot, GpuResource::View(view));
        Ok(())
    }
}

/// Resources uploaded so far by [`GpuResources::upload_pooled`], by content.
#[derive(Debug, Default)]
pub(crate) struct ResourcePool<'a> {
    entries: Vec<(&'a Resource, GpuResource)>,
}

fn invalid(label: &str, message: String) -> GpuError {
    GpuError::Validation {
        label: label.to_owned(),
        message,
    }
}

fn upload_one(ctx: &GpuContext, label: &str, resource: &Resource) -> Result<GpuResource, GpuError> {
    let device = &ctx.device;
    Ok(match resource {
        Resource::Uniform(data) | Resource::Storage(data) => {
            let (usage, align) = match resource {
                Resource::Uniform(_) => (wgpu::BufferUsages::UNIFORM, 16),
                _ => (wgpu::BufferUsages::STORAGE, 4),
            };
            let size = super::readback::align_up(data.len() as u64, align).max(align);
            let limits = device.limits();
            if size > limits.max_buffer_size {
                return Err(invalid(
                    label,
                    format!("buffer of {size} bytes exceeds max_buffer_size"),
                ));
            }
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: usage | wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let mut padded = data.clone();
            padded.resize(size as usize, 0);
            ctx.queue.write_buffer(&buffer, 0, &padded);
            GpuResource::Buffer(buffer)
        }
        Resource::Texture2d {
            format,
            width,
            height,
            data,
        } => {
            let texture = create_texture(ctx, label, *format, *width, *height, 1, 1)?;
            write_level(ctx, label, &texture, 0, 0, data)?;
            let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
            GpuResource::Texture {
                view,
                _texture: texture,
            }
        }
        Resource::TextureCube {
            format,
            size,
            levels,
        } => {
            let level_count = u32::try_from(levels.len()).unwrap_or(u32::MAX);
            let max_levels = 32 - (*size).max(1).leading_zeros();
            if level_count == 0 || level_count > max_levels {
                return Err(invalid(
                    label,
                    format!(
                        "cube texture of size {size} needs 1..={max_levels} mip levels, got {level_count}"
                    ),
                ));
            }
            let texture = create_texture(ctx, label, *format, *size, *size, 6, level_count)?;
            for (level, faces) in (0u32..).zip(levels) {
                for (layer, face) in (0u32..).zip(faces.iter()) {
                    write_level(ctx, label, &texture, level, layer, face)?;
                }
            }
            let view = texture.create_view(&wgpu::TextureViewDescriptor {
                dimension: Some(wgpu::TextureViewDimension::Cube),
                ..Default::default()
            });
            GpuResource::Texture {
                view,
                _texture: texture,
            }
        }
        Resource::Sampler { nearest } => GpuResource::Sampler(create_sampler(
            ctx,
            label,
            *nearest,
            wgpu::AddressMode::ClampToEdge,
        )),
        Resource::SamplerAddressed {
            nearest,
            address_mode,
        } => GpuResource::Sampler(create_sampler(ctx, label, *nearest, *address_mode)),
        Resource::ComparisonSampler { compare, nearest } => {
            let filter = if *nearest {
                wgpu::FilterMode::Nearest
            } else {
                wgpu::FilterMode::Linear
            };
            GpuResource::Sampler(device.create_sampler(&wgpu::SamplerDescriptor {
                label: Some(label),
                mag_filter: filter,
                min_filter: filter,
                compare: Some(*compare),
                ..Default::default()
            }))
        }
    })
}

/// A sampler with nearest or linear filtering (both for texels and mip levels) and one
/// addressing mode on all axes.
fn create_sampler(
    ctx: &GpuContext,
    label: &str,
    nearest: bool,
    address_mode: wgpu::AddressMode,
) -> wgpu::Sampler {
    let (filter, mipmap_filter) = if nearest {
        (wgpu::FilterMode::Nearest, wgpu::MipmapFilterMode::Nearest)
    } else {
        (wgpu::FilterMode::Linear, wgpu::MipmapFilterMode::Linear)
    };
    ctx.device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some(label),
        address_mode_u: address_mode,
        address_mode_v: address_mode,
        address_mode_w: address_mode,
        mag_filter: filter,
        min_filter: filter,
        mipmap_filter,
        ..Default::default()
    })
}

fn create_texture(
    ctx: &GpuContext,
    label: &str,
    format: wgpu::TextureFormat,
    width: u32,
    height: u32,
    layers: u32,
    mip_level_count: u32,
) -> Result<wgpu::Texture, GpuError> {
    let max = ctx.device.limits().max_texture_dimension_2d;
    if width == 0 || height == 0 || width > max || height > max {
        return Err(invalid(
            label,
            format!("texture size {width}x{height} is outside 1..={max}"),
        ));
    }
    Ok(ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(label),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: layers,
        },
        mip_level_count,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_DST
            | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    }))
}

/// Writes tightly packed `data` into one mip level of one array layer.
fn write_level(
    ctx: &GpuContext,
    label: &str,
    texture: &wgpu::Texture,
    level: u32,
    layer: u32,
    data: &[u8],
) -> Result<(), GpuError> {
    let format = texture.format();
    let width = (texture.width() >> level).max(1);
    let height = (texture.height() >> level).max(1);
    let (block_w, block_h) = format.block_dimensions();
    let block_size = format
        .block_copy_size(Some(wgpu::TextureAspect::All))
        .ok_or_else(|| invalid(label, format!("format {format:?} cannot be uploaded")))?;
    let bytes_per_row = width.div_ceil(block_w) * block_size;
    let rows = height.div_ceil(block_h);
    let needed = u64::from(bytes_per_row) * u64::from(rows);
    if (data.len() as u64) < needed {
        return Err(invalid(
            label,
            format!(
                "texture level {level} layer {layer} ({width}x{height} {format:?}) needs {needed} bytes, got {}",
                data.len()
            ),
        ));
    }
    ctx.queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: level,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect: wgpu::TextureAspect::All,
        },
        &data[..needed as usize],
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(bytes_per_row),
            rows_per_image: Some(rows),
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    Ok(())
}
