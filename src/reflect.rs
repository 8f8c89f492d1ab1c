//! Binding reflection from naga's IR: which bind groups and bindings a variant's entry points
//! use, with their kind, size and stage visibility — so a renderer never hand-writes layouts.
//!
//! The rules are the ones wgpu applies when it derives a layout itself (`layout: None`), so an
//! explicit layout built from a [`Reflection`] is interchangeable with wgpu's automatic one:
//!
//! - a binding is listed when at least one entry point of the variant statically uses it; its
//!   visibility is the set of stages of those entry points;
//! - uniform and storage buffers carry their minimum binding size (the size of the type; for a
//!   runtime-sized array, one element);
//! - a float texture is `float` (filterable) when some entry point samples it with a sampler,
//!   and `unfilterable_float` when it is only loaded (`textureLoad`), e.g. an `Rgba32Float`
//!   G-buffer target; samplers are `filtering` or `comparison`.
//!
//! ```
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let with = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
//! let without = lib.variant("standard", "Deferred", &[] as &[&str]).unwrap();
//! let has_normal_map = |r: &wgsl_variants::reflect::Reflection| {
//!     r.bindings.iter().any(|b| (b.group, b.binding) == (1, 4) && b.name == "normal_map")
//! };
//! assert!(has_normal_map(&lib.reflect(&with).unwrap()));
//! assert!(!has_normal_map(&lib.reflect(&without).unwrap()));
//! ```

use std::collections::BTreeMap;
use std::fmt;

use serde::Serialize;

use crate::error::VariantError;
use crate::library::{Library, Variant};

/// A shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stage {
    /// `@vertex`.
    Vertex,
    /// `@fragment`.
    Fragment,
    /// `@compute`.
    Compute,
    /// A task shader (mesh pipelines).
    Task,
    /// A mesh shader (mesh pipelines).
    Mesh,
    /// A ray-tracing stage (generation, miss, any hit, closest hit).
    RayTracing,
}

impl Stage {
    /// The stage of a naga entry point.
    pub fn from_naga(stage: naga::ShaderStage) -> Stage {
        match stage {
            naga::ShaderStage::Vertex => Stage::Vertex,
            naga::ShaderStage::Fragment => Stage::Fragment,
            naga::ShaderStage::Compute => Stage::Compute,
            naga::ShaderStage::Task => Stage::Task,
            naga::ShaderStage::Mesh => Stage::Mesh,
            _ => Stage::RayTracing,
        }
    }

    /// Lower-case name: `vertex`, `fragment`, `compute`, …
    pub fn name(self) -> &'static str {
        match self {
            Stage::Vertex => "vertex",
            Stage::Fragment => "fragment",
            Stage::Compute => "compute",
            Stage::Task => "task",
            Stage::Mesh => "mesh",
            Stage::RayTracing => "ray_tracing",
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An entry point of a module.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct EntryPoint {
    /// Its name.
    pub name: String,
    /// Its stage.
    pub stage: Stage,
    /// `@workgroup_size` of a compute-like entry point.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub workgroup_size: Option<[u32; 3]>,
}

/// How a storage buffer may be accessed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum BufferAccess {
    /// `var<storage, read>`.
    Read,
    /// `var<storage, read_write>`.
    ReadWrite,
}

/// How a storage texture may be accessed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum TextureAccess {
    /// `read`.
    Read,
    /// `write`.
    Write,
    /// `read_write`.
    ReadWrite,
    /// Atomic access.
    Atomic,
}

/// The sample type of a sampled texture (WebGPU's `GPUTextureSampleType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SampleType {
    /// `texture_*<f32>` sampled with a sampler somewhere: needs a filterable format.
    Float,
    /// `texture_*<f32>` that is only loaded: any float format, e.g. `Rgba32Float`.
    UnfilterableFloat,
    /// `texture_depth_*`.
    Depth,
    /// `texture_*<i32>`.
    Sint,
    /// `texture_*<u32>`.
    Uint,
}

/// A texture view dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Dimension {
    /// 1D.
    #[serde(rename = "1d")]
    D1,
    /// 2D.
    #[serde(rename = "2d")]
    D2,
    /// 2D array.
    #[serde(rename = "2d_array")]
    D2Array,
    /// 3D.
    #[serde(rename = "3d")]
    D3,
    /// Cube.
    #[serde(rename = "cube")]
    Cube,
    /// Cube array.
    #[serde(rename = "cube_array")]
    CubeArray,
}

impl Dimension {
    fn from_naga(dim: naga::ImageDimension, arrayed: bool) -> Dimension {
        match (dim, arrayed) {
            (naga::ImageDimension::D1, _) => Dimension::D1,
            (naga::ImageDimension::D2, false) => Dimension::D2,
            (naga::ImageDimension::D2, true) => Dimension::D2Array,
            (naga::ImageDimension::D3, _) => Dimension::D3,
            (naga::ImageDimension::Cube, false) => Dimension::Cube,
            (naga::ImageDimension::Cube, true) => Dimension::CubeArray,
        }
    }
}

/// The type of a sampler binding (WebGPU's `GPUSamplerBindingType`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SamplerType {
    /// `sampler`.
    Filtering,
    /// `sampler_comparison`.
    Comparison,
}

/// What is bound at a slot.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum BindingKind {
    /// `var<uniform>`.
    UniformBuffer {
        /// Minimum binding size in bytes.
        size: u64,
    },
    /// `var<storage, …>`.
    StorageBuffer {
        /// Minimum binding size in bytes (one element of a runtime-sized array).
        size: u64,
        /// Access mode.
        access: BufferAccess,
    },
    /// A sampled texture.
    Texture {
        /// Sample type.
        sample_type: SampleType,
        /// View dimension.
        dimension: Dimension,
        /// `texture_multisampled_*`.
        multisampled: bool,
    },
    /// A storage texture.
    StorageTexture {
        /// Texel format, as WGSL spells it (`rgba8unorm`).
        format: String,
        /// Access mode.
        access: TextureAccess,
        /// View dimension.
        dimension: Dimension,
    },
    /// A sampler.
    Sampler {
        /// Filtering or comparison.
        sampler_type: SamplerType,
    },
    /// `texture_external`.
    ExternalTexture,
    /// A ray-tracing acceleration structure.
    AccelerationStructure,
}

impl fmt::Display for BindingKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let dim = |d: &Dimension| match d {
            Dimension::D1 => "1d",
            Dimension::D2 => "2d",
            Dimension::D2Array => "2d array",
            Dimension::D3 => "3d",
            Dimension::Cube => "cube",
            Dimension::CubeArray => "cube array",
        };
        match self {
            BindingKind::UniformBuffer { size } => write!(f, "uniform buffer, {size} bytes"),
            BindingKind::StorageBuffer { size, access } => write!(
                f,
                "storage buffer ({}), {size} bytes",
                match access {
                    BufferAccess::Read => "read",
                    BufferAccess::ReadWrite => "read_write",
                }
            ),
            BindingKind::Texture {
                sample_type,
                dimension,
                multisampled,
            } => write!(
                f,
                "texture {}{} {}",
                dim(dimension),
                if *multisampled { " multisampled" } else { "" },
                match sample_type {
                    SampleType::Float => "float",
                    SampleType::UnfilterableFloat => "unfilterable float",
                    SampleType::Depth => "depth",
                    SampleType::Sint => "sint",
                    SampleType::Uint => "uint",
                }
            ),
            BindingKind::StorageTexture {
                format,
                access,
                dimension,
            } => write!(
                f,
                "storage texture {} {format} ({})",
                dim(dimension),
                match access {
                    TextureAccess::Read => "read",
                    TextureAccess::Write => "write",
                    TextureAccess::ReadWrite => "read_write",
                    TextureAccess::Atomic => "atomic",
                }
            ),
            BindingKind::Sampler { sampler_type } => f.write_str(match sampler_type {
                SamplerType::Filtering => "sampler (filtering)",
                SamplerType::Comparison => "sampler (comparison)",
            }),
            BindingKind::ExternalTexture => f.write_str("external texture"),
            BindingKind::AccelerationStructure => f.write_str("acceleration structure"),
        }
    }
}

/// One `@group/@binding` resource a variant uses.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct Binding {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The variable's name.
    pub name: String,
    /// What is bound.
    #[serde(flatten)]
    pub kind: BindingKind,
    /// The stages whose entry points use it, in stage order.
    pub visibility: Vec<Stage>,
    /// `binding_array<…, N>`: the element count (unbounded arrays: `None` with `array`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub count: Option<u32>,
}

/// The entry points and bindings of a variant (or of any validated naga module).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct Reflection {
    /// Shader name (empty for a module reflected on its own).
    pub shader: String,
    /// Pass name (empty for a module reflected on its own).
    pub pass: String,
    /// The keywords that are on, in set order.
    pub keywords: Vec<String>,
    /// Entry points in declaration order.
    pub entry_points: Vec<EntryPoint>,
    /// Bindings used by the entry points, sorted by (group, binding).
    pub bindings: Vec<Binding>,
}

/// A binding naga reports that cannot be reflected (e.g. a storage format wgpu lacks).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("@group({group}) @binding({binding}) `{name}`: {message}")]
pub struct ReflectError {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The variable's name.
    pub name: String,
    /// What is wrong.
    pub message: String,
}

fn binding_kind(
    module: &naga::Module,
    var: &naga::GlobalVariable,
    filterable: bool,
) -> Option<(BindingKind, Option<u32>)> {
    let mut ty = &module.types[var.ty].inner;
    let mut count = None;
    if let naga::TypeInner::BindingArray { base, size } = ty {
        count = match size {
            naga::ArraySize::Constant(n) => Some(n.get()),
            _ => Some(0),
        };
        ty = &module.types[*base].inner;
    }
    let kind = match var.space {
        naga::AddressSpace::Uniform => BindingKind::UniformBuffer {
            size: u64::from(ty.size(module.to_ctx())),
        },
        naga::AddressSpace::Storage { access } => BindingKind::StorageBuffer {
            size: u64::from(ty.size(module.to_ctx())),
            access: if access.contains(naga::StorageAccess::STORE) {
                BufferAccess::ReadWrite
            } else {
                BufferAccess::Read
            },
        },
        naga::AddressSpace::Handle => match ty {
            naga::TypeInner::Sampler { comparison } => BindingKind::Sampler {
                sampler_type: if *comparison {
                    SamplerType::Comparison
                } else {
                    SamplerType::Filtering
                },
            },
            naga::TypeInner::Image {
                dim,
                arrayed,
                class,
            } => {
                let dimension = Dimension::from_naga(*dim, *arrayed);
                match class {
                    naga::ImageClass::Sampled { kind, multi } => BindingKind::Texture {
                        sample_type: match kind {
                            naga::ScalarKind::Sint => SampleType::Sint,
                            naga::ScalarKind::Uint => SampleType::Uint,
                            _ if filterable => SampleType::Float,
                            _ => SampleType::UnfilterableFloat,
                        },
                        dimension,
                        multisampled: *multi,
                    },
                    naga::ImageClass::Depth { multi } => BindingKind::Texture {
                        sample_type: SampleType::Depth,
                        dimension,
                        multisampled: *multi,
                    },
                    naga::ImageClass::Storage { format, access } => BindingKind::StorageTexture {
                        format: format!("{format:?}").to_lowercase(),
                        access: if access.contains(naga::StorageAccess::ATOMIC) {
                            TextureAccess::Atomic
                        } else if access
                            .contains(naga::StorageAccess::LOAD | naga::StorageAccess::STORE)
                        {
                            TextureAccess::ReadWrite
                        } else if access.contains(naga::StorageAccess::STORE) {
                            TextureAccess::Write
                        } else {
                            TextureAccess::Read
                        },
                        dimension,
                    },
                    naga::ImageClass::External => BindingKind::ExternalTexture,
                }
            }
            naga::TypeInner::AccelerationStructure { .. } => BindingKind::AccelerationStructure,
            _ => return None,
        },
        _ => return None,
    };
    Some((kind, count))
}

/// The entry points of a module, in declaration order.
pub(crate) fn entry_points(module: &naga::Module) -> Vec<EntryPoint> {
    module
        .entry_points
        .iter()
        .map(|ep| {
            let stage = Stage::from_naga(ep.stage);
            EntryPoint {
                name: ep.name.clone(),
                stage,
                workgroup_size: ep.stage.compute_like().then_some(ep.workgroup_size),
            }
        })
        .collect()
}

/// The bindings a validated module's entry points use, sorted by (group, binding). `info`
/// must be the validation result of `module`.
pub(crate) fn bindings(module: &naga::Module, info: &naga::valid::ModuleInfo) -> Vec<Binding> {
    // Per global: the stages that use it, and whether some entry point samples it.
    let mut used: BTreeMap<naga::Handle<naga::GlobalVariable>, (Vec<Stage>, bool)> =
        BTreeMap::new();
    for (index, ep) in module.entry_points.iter().enumerate() {
        let function = info.get_entry_point(index);
        let stage = Stage::from_naga(ep.stage);
        for (handle, var) in module.global_variables.iter() {
            if var.binding.is_none() || function[handle].is_empty() {
                continue;
            }
            let entry = used.entry(handle).or_default();
            if !entry.0.contains(&stage) {
                entry.0.push(stage);
            }
            if function.sampling_set.iter().any(|key| key.image == handle) {
                entry.1 = true;
            }
        }
    }
    let mut out: Vec<Binding> = used
        .into_iter()
        .filter_map(|(handle, (mut stages, sampled))| {
            let var = &module.global_variables[handle];
            let slot = var.binding.as_ref()?;
            let (kind, count) = binding_kind(module, var, sampled)?;
            stages.sort();
            Some(Binding {
                group: slot.group,
                binding: slot.binding,
                name: var.name.clone().unwrap_or_default(),
                kind,
                visibility: stages,
                count,
            })
        })
        .collect();
    out.sort_by_key(|b| (b.group, b.binding));
    out
}

/// Reflects a validated module on its own (shader, pass and keywords left empty).
pub fn reflect_module(module: &naga::Module, info: &naga::valid::ModuleInfo) -> Reflection {
    Reflection {
        shader: String::new(),
        pass: String::new(),
        keywords: Vec::new(),
        entry_points: entry_points(module),
        bindings: bindings(module, info),
    }
}

impl Library {
    /// The entry points and bindings of a variant, validated first (the reflection stage:
    /// [`reflect`](crate::reflect)).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let v = lib.variant("deferred_final", "Final", &[] as &[&str]).unwrap();
    /// let r = lib.reflect(&v).unwrap();
    /// assert_eq!(r.bindings[0].name, "rt3");
    /// ```
    pub fn reflect(&self, variant: &Variant<'_>) -> Result<Reflection, VariantError> {
        reflect_variant(self, variant)
    }
}

/// The reflection of a variant, validated first (see [`Library::reflect`]).
pub(crate) fn reflect_variant(
    lib: &Library,
    variant: &Variant<'_>,
) -> Result<Reflection, VariantError> {
    let (module, info) = lib.naga_module(variant)?;
    Ok(Reflection {
        shader: variant.pass.shader.clone(),
        pass: variant.pass.name.clone(),
        keywords: variant.keywords().into_iter().map(str::to_string).collect(),
        ..reflect_module(&module, &info)
    })
}

impl Reflection {
    /// The groups used, from 0 to the highest, each with its bindings (a group in between
    /// that nothing uses is empty: a pipeline layout still needs a layout for it).
    pub fn groups(&self) -> Vec<Vec<&Binding>> {
        let count = self.bindings.iter().map(|b| b.group + 1).max().unwrap_or(0);
        let mut groups = vec![Vec::new(); count as usize];
        for b in &self.bindings {
            groups[b.group as usize].push(b);
        }
        groups
    }

    /// Plain-text listing, one line per binding, grouped.
    pub fn to_text(&self) -> String {
        use std::fmt::Write;
        let mut out = String::new();
        let _ = writeln!(
            out,
            "{}/{} {{{}}}",
            self.shader,
            self.pass,
            self.keywords.join(", ")
        );
        let eps: Vec<String> = self
            .entry_points
            .iter()
            .map(|e| format!("{} ({})", e.name, e.stage))
            .collect();
        let _ = writeln!(out, "entry points: {}", eps.join(", "));
        let width = self
            .bindings
            .iter()
            .map(|b| b.name.len())
            .max()
            .unwrap_or(0);
        for (group, bindings) in self.groups().iter().enumerate() {
            let _ = writeln!(out, "group {group}");
            for b in bindings {
                let stages: Vec<&str> = b.visibility.iter().map(|s| s.name()).collect();
                let count = match b.count {
                    Some(0) => " [unbounded array]".to_string(),
                    Some(n) => format!(" [array of {n}]"),
                    None => String::new(),
                };
                let _ = writeln!(
                    out,
                    "  binding {:<3} {:<width$}  {}{count}  [{}]",
                    b.binding,
                    b.name,
                    b.kind,
                    stages.join(", ")
                );
            }
        }
        out
    }
}
