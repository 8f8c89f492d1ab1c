//! A variant's pipeline interface as plain data: its bindings (from [`crate::reflect`], so
//! the same facts `reflect` prints), the vertex entry point's inputs and the fragment entry
//! point's outputs, and the Rust literal of each.

use crate::reflect::{
    Binding, BindingKind, BufferAccess, Dimension, SampleType, SamplerType, Stage, TextureAccess,
};

use super::BindingsError;

/// One vertex input: `@location`, name, wgpu's format name and size in bytes.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct VertexInput {
    /// `@location`.
    pub location: u32,
    /// The argument's or member's name.
    pub name: String,
    /// wgpu's name of its format (`Float32x3`).
    pub format: String,
    /// Its size in bytes.
    pub size: u64,
}

/// One fragment output: `@location`, name, component count and kind (`Float`, `Sint`, `Uint`).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FragmentOutput {
    /// `@location`.
    pub location: u32,
    /// The member's name (empty for a bare result).
    pub name: String,
    /// Components (1 to 4).
    pub components: u32,
    /// `Float`, `Sint` or `Uint`.
    pub kind: &'static str,
}

/// `(location, name, type)` of each `@location` argument (or member of a struct argument) of a
/// function's arguments, or of its result.
fn located(
    module: &naga::Module,
    items: &[(
        Option<String>,
        naga::Handle<naga::Type>,
        Option<naga::Binding>,
    )],
) -> Vec<(u32, String, naga::Handle<naga::Type>)> {
    let mut out = Vec::new();
    for (name, ty, binding) in items {
        match binding {
            Some(naga::Binding::Location {
                location,
                blend_src,
                ..
            }) => {
                // The second source of dual-source blending is no target of its own.
                if blend_src.unwrap_or(0) == 0 {
                    out.push((*location, name.clone().unwrap_or_default(), *ty));
                }
            }
            Some(naga::Binding::BuiltIn(_)) => {}
            None => {
                if let naga::TypeInner::Struct { members, .. } = &module.types[*ty].inner {
                    let members: Vec<_> = members
                        .iter()
                        .map(|m| (m.name.clone(), m.ty, m.binding.clone()))
                        .collect();
                    out.extend(located(module, &members));
                }
            }
        }
    }
    out.sort_by_key(|(location, _, _)| *location);
    out
}

/// The inputs of the module's first vertex entry point, by location.
pub fn vertex_inputs(module: &naga::Module) -> Result<Vec<VertexInput>, BindingsError> {
    let Some(ep) = module
        .entry_points
        .iter()
        .find(|ep| ep.stage == naga::ShaderStage::Vertex)
    else {
        return Ok(Vec::new());
    };
    let args: Vec<_> = ep
        .function
        .arguments
        .iter()
        .map(|a| (a.name.clone(), a.ty, a.binding.clone()))
        .collect();
    located(module, &args)
        .into_iter()
        .map(|(location, name, ty)| {
            let (kind, width, count) = components(&module.types[ty].inner).ok_or_else(|| {
                BindingsError::UnsupportedType {
                    ty: name.clone(),
                    reason: "a vertex input that is not a scalar or vector".into(),
                }
            })?;
            let bits = width * 8;
            let format = match count {
                1 => format!("{kind}{bits}"),
                n => format!("{kind}{bits}x{n}"),
            };
            const KNOWN: &[&str] = &[
                "Float16x2",
                "Float16x4",
                "Float32",
                "Float32x2",
                "Float32x3",
                "Float32x4",
                "Float64",
                "Float64x2",
                "Float64x3",
                "Float64x4",
                "Sint32",
                "Sint32x2",
                "Sint32x3",
                "Sint32x4",
                "Uint32",
                "Uint32x2",
                "Uint32x3",
                "Uint32x4",
            ];
            if !KNOWN.contains(&format.as_str()) {
                return Err(BindingsError::UnsupportedType {
                    ty: name,
                    reason: format!("no vertex format holds a {kind}{bits} x{count} input"),
                });
            }
            Ok(VertexInput {
                location,
                name,
                format,
                size: u64::from(width * count),
            })
        })
        .collect()
}

/// The outputs of the module's first fragment entry point, by location.
pub fn fragment_outputs(module: &naga::Module) -> Vec<FragmentOutput> {
    let Some(result) = module
        .entry_points
        .iter()
        .find(|ep| ep.stage == naga::ShaderStage::Fragment)
        .and_then(|ep| ep.function.result.as_ref())
    else {
        return Vec::new();
    };
    located(module, &[(None, result.ty, result.binding.clone())])
        .into_iter()
        .filter_map(|(location, name, ty)| {
            let (kind, _, components) = components(&module.types[ty].inner)?;
            Some(FragmentOutput {
                location,
                name,
                components,
                kind,
            })
        })
        .collect()
}

/// (`Float`/`Sint`/`Uint`, scalar width, component count) of a scalar or vector.
fn components(ty: &naga::TypeInner) -> Option<(&'static str, u32, u32)> {
    let (scalar, count) = match ty {
        naga::TypeInner::Scalar(s) => (*s, 1),
        naga::TypeInner::Vector { size, scalar } => (*scalar, *size as u32),
        _ => return None,
    };
    let kind = match scalar.kind {
        naga::ScalarKind::Float => "Float",
        naga::ScalarKind::Sint => "Sint",
        naga::ScalarKind::Uint => "Uint",
        _ => return None,
    };
    Some((kind, u32::from(scalar.width), count))
}

fn stage(s: Stage) -> &'static str {
    match s {
        Stage::Vertex => "Stage::Vertex",
        Stage::Fragment => "Stage::Fragment",
        Stage::Compute => "Stage::Compute",
        Stage::Task => "Stage::Task",
        Stage::Mesh => "Stage::Mesh",
        Stage::RayTracing => "Stage::RayTracing",
    }
}

fn dimension(d: &Dimension) -> &'static str {
    match d {
        Dimension::D1 => "Dimension::D1",
        Dimension::D2 => "Dimension::D2",
        Dimension::D2Array => "Dimension::D2Array",
        Dimension::D3 => "Dimension::D3",
        Dimension::Cube => "Dimension::Cube",
        Dimension::CubeArray => "Dimension::CubeArray",
    }
}

/// The Rust literal of one `BindingEntry` (the generated prelude's type); `rust_type` is the
/// Rust type of a buffer's contents.
pub fn binding_literal(b: &Binding, rust_type: &str) -> String {
    let kind = match &b.kind {
        BindingKind::UniformBuffer { size } => {
            format!("BindingKind::UniformBuffer {{ size: {size}, rust_type: {rust_type:?} }}")
        }
        BindingKind::StorageBuffer { size, access } => format!(
            "BindingKind::StorageBuffer {{ size: {size}, read_only: {}, rust_type: {rust_type:?} }}",
            *access == BufferAccess::Read,
        ),
        BindingKind::Texture {
            sample_type,
            dimension: d,
            multisampled,
        } => format!(
            "BindingKind::Texture {{ sample_type: SampleType::{}, dimension: {}, multisampled: {multisampled} }}",
            match sample_type {
                SampleType::Float => "Float",
                SampleType::UnfilterableFloat => "UnfilterableFloat",
                SampleType::Depth => "Depth",
                SampleType::Sint => "Sint",
                SampleType::Uint => "Uint",
            },
            dimension(d)
        ),
        BindingKind::StorageTexture {
            format,
            access,
            dimension: d,
        } => format!(
            "BindingKind::StorageTexture {{ format: {format:?}, access: TextureAccess::{}, dimension: {} }}",
            match access {
                TextureAccess::Read => "Read",
                TextureAccess::Write => "Write",
                TextureAccess::ReadWrite => "ReadWrite",
                TextureAccess::Atomic => "Atomic",
            },
            dimension(d)
        ),
        BindingKind::Sampler { sampler_type } => format!(
            "BindingKind::Sampler {{ comparison: {} }}",
            *sampler_type == SamplerType::Comparison
        ),
        BindingKind::ExternalTexture => "BindingKind::ExternalTexture".to_string(),
        BindingKind::AccelerationStructure => "BindingKind::AccelerationStructure".to_string(),
    };
    let visibility: Vec<&str> = b.visibility.iter().map(|s| stage(*s)).collect();
    format!(
        "BindingEntry {{ group: {}, binding: {}, name: {:?}, kind: {kind}, visibility: &[{}], count: {:?} }}",
        b.group,
        b.binding,
        b.name,
        visibility.join(", "),
        b.count
    )
}

/// The Rust literal of a `&[VertexAttribute]` packing `vertex` in one buffer, and the stride.
pub fn vertex_literal(vertex: &[VertexInput]) -> (String, u64) {
    let mut items = Vec::new();
    let mut offset = 0;
    for v in vertex {
        items.push(format!(
            "VertexAttribute {{ location: {}, name: {:?}, format: VertexFormat::{}, offset: {offset} }}",
            v.location, v.name, v.format
        ));
        offset += v.size;
    }
    (format!("&[{}]", items.join(", ")), offset)
}

/// The Rust literal of a `&[ColorTarget]`.
pub fn targets_literal(targets: &[FragmentOutput]) -> String {
    let items: Vec<String> = targets
        .iter()
        .map(|t| {
            format!(
                "ColorTarget {{ location: {}, name: {:?}, components: {}, kind: ColorKind::{} }}",
                t.location, t.name, t.components, t.kind
            )
        })
        .collect();
    format!("&[{}]", items.join(", "))
}
