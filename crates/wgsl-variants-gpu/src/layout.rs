//! wgpu bind group layouts from a variant's [`Reflection`]: what a renderer writes by hand
//! otherwise.
//!
//! The entries follow the rules wgpu applies when it derives a layout itself (`layout: None`),
//! so a pipeline layout built from them is interchangeable with wgpu's automatic one.

use wgsl_variants::reflect::{
    Binding, BindingKind, BufferAccess, Dimension, ReflectError, Reflection, SampleType,
    SamplerType, Stage, TextureAccess,
};

/// The wgpu stage flag of a reflected stage (ray-tracing stages have none in a layout).
pub fn stage_flags(stage: Stage) -> wgpu::ShaderStages {
    match stage {
        Stage::Vertex => wgpu::ShaderStages::VERTEX,
        Stage::Fragment => wgpu::ShaderStages::FRAGMENT,
        Stage::Compute => wgpu::ShaderStages::COMPUTE,
        Stage::Task => wgpu::ShaderStages::TASK,
        Stage::Mesh => wgpu::ShaderStages::MESH,
        Stage::RayTracing => wgpu::ShaderStages::NONE,
    }
}

/// The wgpu view dimension of a reflected texture dimension.
pub fn view_dimension(dimension: Dimension) -> wgpu::TextureViewDimension {
    match dimension {
        Dimension::D1 => wgpu::TextureViewDimension::D1,
        Dimension::D2 => wgpu::TextureViewDimension::D2,
        Dimension::D2Array => wgpu::TextureViewDimension::D2Array,
        Dimension::D3 => wgpu::TextureViewDimension::D3,
        Dimension::Cube => wgpu::TextureViewDimension::Cube,
        Dimension::CubeArray => wgpu::TextureViewDimension::CubeArray,
    }
}

/// The wgpu format of a WGSL storage-texture format name (`rgba8unorm`, …), if wgpu has one.
pub fn storage_format(format: &str) -> Option<wgpu::TextureFormat> {
    use wgpu::TextureFormat as F;
    Some(match format {
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
        _ => return None,
    })
}

/// One binding as a wgpu layout entry (what wgpu's automatic layout would derive).
///
/// Fails for a storage format wgpu has no `TextureFormat` for.
pub fn layout_entry(binding: &Binding) -> Result<wgpu::BindGroupLayoutEntry, ReflectError> {
    let ty = match &binding.kind {
        BindingKind::UniformBuffer { size } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(*size),
        },
        BindingKind::StorageBuffer { size, access } => wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage {
                read_only: *access == BufferAccess::Read,
            },
            has_dynamic_offset: false,
            min_binding_size: wgpu::BufferSize::new(*size),
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
            view_dimension: view_dimension(*dimension),
            multisampled: *multisampled,
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
            format: storage_format(format).ok_or_else(|| ReflectError {
                group: binding.group,
                binding: binding.binding,
                name: binding.name.clone(),
                message: format!("storage format `{format}` has no wgpu equivalent"),
            })?,
            view_dimension: view_dimension(*dimension),
        },
        BindingKind::Sampler { sampler_type } => wgpu::BindingType::Sampler(match sampler_type {
            SamplerType::Filtering => wgpu::SamplerBindingType::Filtering,
            SamplerType::Comparison => wgpu::SamplerBindingType::Comparison,
        }),
        BindingKind::ExternalTexture => wgpu::BindingType::ExternalTexture,
        BindingKind::AccelerationStructure => wgpu::BindingType::AccelerationStructure {
            vertex_return: false,
        },
    };
    Ok(wgpu::BindGroupLayoutEntry {
        binding: binding.binding,
        visibility: binding
            .visibility
            .iter()
            .fold(wgpu::ShaderStages::NONE, |acc, s| acc | stage_flags(*s)),
        ty,
        count: binding.count.and_then(std::num::NonZeroU32::new),
    })
}

/// The wgpu layout entries of every group from 0 to the highest used (an unused group in
/// between is an empty list), ready for `create_bind_group_layout`.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// let groups = wgsl_variants_gpu::layout_entries(&lib.reflect(&v).unwrap()).unwrap();
/// assert_eq!(groups.len(), 3);
/// assert!(groups[1].iter().any(|e| e.binding == 4)); // normal_map
/// ```
pub fn layout_entries(
    reflection: &Reflection,
) -> Result<Vec<Vec<wgpu::BindGroupLayoutEntry>>, ReflectError> {
    reflection
        .groups()
        .into_iter()
        .map(|group| group.into_iter().map(layout_entry).collect())
        .collect()
}

/// Creates one bind group layout per group (see [`layout_entries`]), labelled
/// `label/group N`.
pub fn create_bind_group_layouts(
    device: &wgpu::Device,
    reflection: &Reflection,
    label: &str,
) -> Result<Vec<wgpu::BindGroupLayout>, ReflectError> {
    Ok(layout_entries(reflection)?
        .iter()
        .enumerate()
        .map(|(group, entries)| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(&format!("{label}/group {group}")),
                entries,
            })
        })
        .collect())
}

/// A pipeline layout over `bind_group_layouts` (group N at index N, as
/// [`create_bind_group_layouts`] returns them), with no immediates.
pub fn create_pipeline_layout(
    device: &wgpu::Device,
    bind_group_layouts: &[wgpu::BindGroupLayout],
    label: &str,
) -> wgpu::PipelineLayout {
    let refs: Vec<Option<&wgpu::BindGroupLayout>> = bind_group_layouts.iter().map(Some).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &refs,
        immediate_size: 0,
    })
}
