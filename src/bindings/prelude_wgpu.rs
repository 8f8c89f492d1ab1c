/// The interfaces as wgpu's types (written with the `wgpu` option of the generator: this
/// module then depends on `wgpu` 30, whose API it is written for).
impl Interface {
    /// Bind groups the pipeline layout holds: one past the highest `@group` used.
    pub fn group_count(&self) -> u32 {
        self.bindings.iter().map(|b| b.group + 1).max().unwrap_or(0)
    }

    /// The layout entries of `@group(group)`, by binding, for `create_bind_group_layout`
    /// (empty for a group the variant does not use). They are what wgpu derives for the
    /// variant with `layout: None`.
    pub fn bind_group_layout_entries(&self, group: u32) -> Vec<wgpu::BindGroupLayoutEntry> {
        self.bindings
            .iter()
            .filter(|b| b.group == group)
            .map(|b| b.to_wgpu())
            .collect()
    }

    /// The vertex inputs as wgpu's attributes of one buffer, for [`Interface::vertex_buffer_layout`].
    pub fn wgpu_vertex_attributes(&self) -> Vec<wgpu::VertexAttribute> {
        self.vertex_attributes
            .iter()
            .map(|a| wgpu::VertexAttribute {
                format: a.format.to_wgpu(),
                offset: a.offset,
                shader_location: a.location,
            })
            .collect()
    }

    /// The one vertex buffer of [`Interface::vertex_stride`] bytes per vertex, over `attributes`
    /// (from [`Interface::wgpu_vertex_attributes`]).
    pub fn vertex_buffer_layout<'a>(
        &self,
        attributes: &'a [wgpu::VertexAttribute],
    ) -> wgpu::VertexBufferLayout<'a> {
        wgpu::VertexBufferLayout {
            array_stride: self.vertex_stride,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes,
        }
    }

    /// The colour targets in `@location` order (a location no output has is `None`), with
    /// `formats[i]` for the i-th of [`Interface::color_targets`], no blending and every channel
    /// written. The shader fixes each target's component type, not its format: a format of
    /// another type (a `Uint` format for an `f32` output) or a count that differs is an error.
    pub fn color_target_states(
        &self,
        formats: &[wgpu::TextureFormat],
    ) -> Result<Vec<Option<wgpu::ColorTargetState>>, ColorTargetError> {
        if formats.len() != self.color_targets.len() {
            return Err(ColorTargetError::Count {
                targets: self.color_targets.len(),
                formats: formats.len(),
            });
        }
        let len = self
            .color_targets
            .iter()
            .map(|t| t.location + 1)
            .max()
            .unwrap_or(0);
        let mut states = vec![None; len as usize];
        for (target, &format) in self.color_targets.iter().zip(formats) {
            if !target.accepts(format) {
                return Err(ColorTargetError::Format {
                    location: target.location,
                    kind: target.kind,
                    format,
                });
            }
            states[target.location as usize] = Some(wgpu::ColorTargetState {
                format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            });
        }
        Ok(states)
    }
}

/// Why [`Interface::color_target_states`] refused the formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorTargetError {
    /// Not one format per colour target.
    Count {
        /// Colour targets of the variant.
        targets: usize,
        /// Formats given.
        formats: usize,
    },
    /// A format whose sample type is not the output's component type.
    Format {
        /// The target's `@location`.
        location: u32,
        /// The output's component type.
        kind: ColorKind,
        /// The format given.
        format: wgpu::TextureFormat,
    },
}

impl core::fmt::Display for ColorTargetError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ColorTargetError::Count { targets, formats } => {
                write!(f, "{formats} formats for {targets} colour targets")
            }
            ColorTargetError::Format {
                location,
                kind,
                format,
            } => write!(
                f,
                "{format:?} cannot hold the {kind:?} output at @location({location})"
            ),
        }
    }
}

impl std::error::Error for ColorTargetError {}

impl ColorTarget {
    /// Whether a colour attachment of `format` can take this output: a colour format whose
    /// sample type is the output's component type.
    pub fn accepts(&self, format: wgpu::TextureFormat) -> bool {
        if format.is_depth_stencil_format() {
            return false;
        }
        matches!(
            (self.kind, format.sample_type(None, None)),
            (
                ColorKind::Float,
                Some(wgpu::TextureSampleType::Float { .. })
            ) | (ColorKind::Sint, Some(wgpu::TextureSampleType::Sint))
                | (ColorKind::Uint, Some(wgpu::TextureSampleType::Uint))
        )
    }
}

impl BindingEntry {
    /// This binding as a wgpu layout entry.
    pub fn to_wgpu(self) -> wgpu::BindGroupLayoutEntry {
        let ty = match self.kind {
            BindingKind::UniformBuffer { size, .. } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(size),
            },
            BindingKind::StorageBuffer {
                size, read_only, ..
            } => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(size),
            },
            BindingKind::Texture {
                sample_type,
                dimension,
                multisampled,
            } => wgpu::BindingType::Texture {
                sample_type: match sample_type {
                    SampleType::Float => wgpu::TextureSampleType::Float { filterable: true },
                    SampleType::UnfilterableFloat => {
                        wgpu::TextureSampleType::Float { filterable: false }
                    }
                    SampleType::Depth => wgpu::TextureSampleType::Depth,
                    SampleType::Sint => wgpu::TextureSampleType::Sint,
                    SampleType::Uint => wgpu::TextureSampleType::Uint,
                },
                view_dimension: dimension.to_wgpu(),
                multisampled,
            },
            BindingKind::StorageTexture {
                format,
                access,
                dimension,
            } => wgpu::BindingType::StorageTexture {
                access: match access {
                    TextureAccess::Read => wgpu::StorageTextureAccess::ReadOnly,
                    TextureAccess::Write => wgpu::StorageTextureAccess::WriteOnly,
                    TextureAccess::ReadWrite => wgpu::StorageTextureAccess::ReadWrite,
                    TextureAccess::Atomic => wgpu::StorageTextureAccess::Atomic,
                },
                format: storage_format(format),
                view_dimension: dimension.to_wgpu(),
            },
            BindingKind::Sampler { comparison } => wgpu::BindingType::Sampler(if comparison {
                wgpu::SamplerBindingType::Comparison
            } else {
                wgpu::SamplerBindingType::Filtering
            }),
            BindingKind::ExternalTexture => wgpu::BindingType::ExternalTexture,
            BindingKind::AccelerationStructure => wgpu::BindingType::AccelerationStructure {
                vertex_return: false,
            },
        };
        wgpu::BindGroupLayoutEntry {
            binding: self.binding,
            visibility: self
                .visibility
                .iter()
                .fold(wgpu::ShaderStages::NONE, |acc, s| acc | s.to_wgpu()),
            ty,
            count: self.count.and_then(core::num::NonZeroU32::new),
        }
    }
}

impl Stage {
    /// wgpu's flag of this stage (ray-tracing stages have none in a bind group layout).
    pub const fn to_wgpu(self) -> wgpu::ShaderStages {
        match self {
            Stage::Vertex => wgpu::ShaderStages::VERTEX,
            Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
            Stage::Compute => wgpu::ShaderStages::COMPUTE,
            Stage::Task => wgpu::ShaderStages::TASK,
            Stage::Mesh => wgpu::ShaderStages::MESH,
            Stage::RayTracing => wgpu::ShaderStages::NONE,
        }
    }
}

impl Dimension {
    /// wgpu's view dimension.
    pub const fn to_wgpu(self) -> wgpu::TextureViewDimension {
        match self {
            Dimension::D1 => wgpu::TextureViewDimension::D1,
            Dimension::D2 => wgpu::TextureViewDimension::D2,
            Dimension::D2Array => wgpu::TextureViewDimension::D2Array,
            Dimension::D3 => wgpu::TextureViewDimension::D3,
            Dimension::Cube => wgpu::TextureViewDimension::Cube,
            Dimension::CubeArray => wgpu::TextureViewDimension::CubeArray,
        }
    }
}

impl VertexFormat {
    /// wgpu's vertex format of the same name.
    pub const fn to_wgpu(self) -> wgpu::VertexFormat {
        match self {
            VertexFormat::Float16x2 => wgpu::VertexFormat::Float16x2,
            VertexFormat::Float16x4 => wgpu::VertexFormat::Float16x4,
            VertexFormat::Float32 => wgpu::VertexFormat::Float32,
            VertexFormat::Float32x2 => wgpu::VertexFormat::Float32x2,
            VertexFormat::Float32x3 => wgpu::VertexFormat::Float32x3,
            VertexFormat::Float32x4 => wgpu::VertexFormat::Float32x4,
            VertexFormat::Float64 => wgpu::VertexFormat::Float64,
            VertexFormat::Float64x2 => wgpu::VertexFormat::Float64x2,
            VertexFormat::Float64x3 => wgpu::VertexFormat::Float64x3,
            VertexFormat::Float64x4 => wgpu::VertexFormat::Float64x4,
            VertexFormat::Sint32 => wgpu::VertexFormat::Sint32,
            VertexFormat::Sint32x2 => wgpu::VertexFormat::Sint32x2,
            VertexFormat::Sint32x3 => wgpu::VertexFormat::Sint32x3,
            VertexFormat::Sint32x4 => wgpu::VertexFormat::Sint32x4,
            VertexFormat::Uint32 => wgpu::VertexFormat::Uint32,
            VertexFormat::Uint32x2 => wgpu::VertexFormat::Uint32x2,
            VertexFormat::Uint32x3 => wgpu::VertexFormat::Uint32x3,
            VertexFormat::Uint32x4 => wgpu::VertexFormat::Uint32x4,
        }
    }
}

/// wgpu's format of a WGSL storage texel format (`rgba8unorm`); the generator writes only
/// formats naga accepts, each of which wgpu has.
fn storage_format(format: &str) -> wgpu::TextureFormat {
    use wgpu::TextureFormat as F;
    match format {
        "r8unorm" => F::R8Unorm,
        "r8snorm" => F::R8Snorm,
        "r8uint" => F::R8Uint,
        "r8sint" => F::R8Sint,
        "r16uint" => F::R16Uint,
        "r16sint" => F::R16Sint,
        "r16float" => F::R16Float,
        "rg8unorm" => F::Rg8Unorm,
        "rg8snorm" => F::Rg8Snorm,
        "rg8uint" => F::Rg8Uint,
        "rg8sint" => F::Rg8Sint,
        "r32uint" => F::R32Uint,
        "r32sint" => F::R32Sint,
        "r32float" => F::R32Float,
        "rg16uint" => F::Rg16Uint,
        "rg16sint" => F::Rg16Sint,
        "rg16float" => F::Rg16Float,
        "rgba8unorm" => F::Rgba8Unorm,
        "rgba8snorm" => F::Rgba8Snorm,
        "rgba8uint" => F::Rgba8Uint,
        "rgba8sint" => F::Rgba8Sint,
        "bgra8unorm" => F::Bgra8Unorm,
        "rgb10a2uint" => F::Rgb10a2Uint,
        "rgb10a2unorm" => F::Rgb10a2Unorm,
        "rg11b10ufloat" => F::Rg11b10Ufloat,
        "r64uint" => F::R64Uint,
        "rg32uint" => F::Rg32Uint,
        "rg32sint" => F::Rg32Sint,
        "rg32float" => F::Rg32Float,
        "rgba16uint" => F::Rgba16Uint,
        "rgba16sint" => F::Rgba16Sint,
        "rgba16float" => F::Rgba16Float,
        "rgba32uint" => F::Rgba32Uint,
        "rgba32sint" => F::Rgba32Sint,
        "rgba32float" => F::Rgba32Float,
        "r16unorm" => F::R16Unorm,
        "r16snorm" => F::R16Snorm,
        "rg16unorm" => F::Rg16Unorm,
        "rg16snorm" => F::Rg16Snorm,
        "rgba16unorm" => F::Rgba16Unorm,
        "rgba16snorm" => F::Rgba16Snorm,
        // The generator refuses any other format when it writes this module.
        other => panic!("storage texel format `{other}` has no wgpu TextureFormat"),
    }
}
