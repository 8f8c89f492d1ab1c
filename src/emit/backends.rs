//! Every naga back end for a validated variant: WGSL, SPIR-V, GLSL, HLSL and MSL.
//!
//! A variant is composed, validated, compacted (unused types, constants and functions
//! removed) and validated again ([`compile`](crate::validate::compile)); the back ends write that module. Resource
//! slots follow fixed rules so that every output of a variant binds the same way:
//!
//! - WGSL and SPIR-V keep `@group`/`@binding` (SPIR-V: `DescriptorSet`/`Binding`).
//! - HLSL: `register(<class><binding>, space<group>)` (naga's default mapping).
//! - GLSL and MSL have flat slot spaces. Slots are assigned per resource class, counting up
//!   from 0 in (group, binding) order over the bindings the variant uses (so all of its
//!   entry points agree; a binding that a keyword removes shifts the later slots of its
//!   class): GLSL uniform blocks, storage blocks, textures and images each count on their own
//!   (samplers are combined with their textures); MSL buffers, textures and samplers count on
//!   their own. [`slots`] lists the assignment, and `manifest.json` records it per file.
//!
//! Outputs are byte-identical across runs and thread counts.

use std::fmt;

use crate::error::VariantError;
use crate::library::{Library, Variant};

use crate::reflect::{EntryPoint, Stage, entry_points};

/// A naga back end and its language version.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    /// WGSL, written by naga from the compacted module.
    Wgsl,
    /// SPIR-V 1.0 words (feature `spv-out`).
    #[cfg(feature = "spv-out")]
    SpirV,
    /// GLSL, one output per entry point (feature `glsl-out`).
    #[cfg(feature = "glsl-out")]
    Glsl(naga::back::glsl::Version),
    /// HLSL for a shader model, every entry point in one output (feature `hlsl-out`).
    #[cfg(feature = "hlsl-out")]
    Hlsl(naga::back::hlsl::ShaderModel),
    /// Metal Shading Language `(major, minor)`, every entry point in one output (feature
    /// `msl-out`).
    #[cfg(feature = "msl-out")]
    Msl(u8, u8),
}

/// The back ends by name, for command lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TargetKind {
    /// `wgsl`
    Wgsl,
    /// `spirv`
    SpirV,
    /// `glsl`
    Glsl,
    /// `hlsl`
    Hlsl,
    /// `msl`
    Msl,
}

impl Target {
    /// Default GLSL version: 450 core.
    #[cfg(feature = "glsl-out")]
    pub const GLSL_DEFAULT: naga::back::glsl::Version = naga::back::glsl::Version::Desktop(450);
    /// Default shader model: 5.1 (naga's default).
    #[cfg(feature = "hlsl-out")]
    pub const HLSL_DEFAULT: naga::back::hlsl::ShaderModel = naga::back::hlsl::ShaderModel::V5_1;
    /// Default MSL version: 2.0.
    #[cfg(feature = "msl-out")]
    pub const MSL_DEFAULT: (u8, u8) = (2, 0);

    /// The back end.
    pub fn kind(&self) -> TargetKind {
        match self {
            Target::Wgsl => TargetKind::Wgsl,
            #[cfg(feature = "spv-out")]
            Target::SpirV => TargetKind::SpirV,
            #[cfg(feature = "glsl-out")]
            Target::Glsl(_) => TargetKind::Glsl,
            #[cfg(feature = "hlsl-out")]
            Target::Hlsl(_) => TargetKind::Hlsl,
            #[cfg(feature = "msl-out")]
            Target::Msl(..) => TargetKind::Msl,
        }
    }

    /// `wgsl`, `spirv`, `glsl`, `hlsl` or `msl`.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }

    /// The language version, as the command line spells it (`450`, `300es`, `5_1`, `2.0`).
    pub fn version(&self) -> Option<String> {
        match self {
            Target::Wgsl => None,
            #[cfg(feature = "spv-out")]
            Target::SpirV => Some("1.0".into()),
            #[cfg(feature = "glsl-out")]
            Target::Glsl(v) => Some(match v {
                naga::back::glsl::Version::Desktop(n) => n.to_string(),
                naga::back::glsl::Version::Embedded { version, .. } => format!("{version}es"),
            }),
            #[cfg(feature = "hlsl-out")]
            Target::Hlsl(sm) => Some(sm.to_str().to_string()),
            #[cfg(feature = "msl-out")]
            Target::Msl(major, minor) => Some(format!("{major}.{minor}")),
        }
    }

    /// The file extension of an output (GLSL: by stage, glslang's `vert`/`frag`/`comp`).
    #[cfg_attr(not(feature = "glsl-out"), allow(unused_variables))]
    pub fn extension(&self, stage: Option<Stage>) -> &'static str {
        match self {
            Target::Wgsl => "wgsl",
            #[cfg(feature = "spv-out")]
            Target::SpirV => "spv",
            #[cfg(feature = "glsl-out")]
            Target::Glsl(_) => match stage {
                Some(Stage::Vertex) => "vert",
                Some(Stage::Fragment) => "frag",
                Some(Stage::Compute) => "comp",
                _ => "glsl",
            },
            #[cfg(feature = "hlsl-out")]
            Target::Hlsl(_) => "hlsl",
            #[cfg(feature = "msl-out")]
            Target::Msl(..) => "metal",
        }
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.version() {
            Some(v) if self.kind() != TargetKind::SpirV => write!(f, "{} {v}", self.name()),
            _ => f.write_str(self.name()),
        }
    }
}

impl TargetKind {
    /// Every back end.
    pub const ALL: [TargetKind; 5] = [
        TargetKind::Wgsl,
        TargetKind::SpirV,
        TargetKind::Glsl,
        TargetKind::Hlsl,
        TargetKind::Msl,
    ];

    /// `wgsl`, `spirv`, `glsl`, `hlsl` or `msl`.
    pub fn name(self) -> &'static str {
        match self {
            TargetKind::Wgsl => "wgsl",
            TargetKind::SpirV => "spirv",
            TargetKind::Glsl => "glsl",
            TargetKind::Hlsl => "hlsl",
            TargetKind::Msl => "msl",
        }
    }

    /// The cargo feature that compiles this back end in (WGSL is always in).
    pub fn feature(self) -> Option<&'static str> {
        match self {
            TargetKind::Wgsl => None,
            TargetKind::SpirV => Some("spv-out"),
            TargetKind::Glsl => Some("glsl-out"),
            TargetKind::Hlsl => Some("hlsl-out"),
            TargetKind::Msl => Some("msl-out"),
        }
    }

    /// The target with the default version, or [`Disabled`] when its cargo feature is off.
    pub fn with_defaults(self) -> Result<Target, Disabled> {
        match self {
            TargetKind::Wgsl => Ok(Target::Wgsl),
            #[cfg(feature = "spv-out")]
            TargetKind::SpirV => Ok(Target::SpirV),
            #[cfg(feature = "glsl-out")]
            TargetKind::Glsl => Ok(Target::Glsl(Target::GLSL_DEFAULT)),
            #[cfg(feature = "hlsl-out")]
            TargetKind::Hlsl => Ok(Target::Hlsl(Target::HLSL_DEFAULT)),
            #[cfg(feature = "msl-out")]
            TargetKind::Msl => Ok(Target::Msl(Target::MSL_DEFAULT.0, Target::MSL_DEFAULT.1)),
            #[allow(unreachable_patterns)] // reached when a back-end feature is off
            _ => Err(Disabled(self)),
        }
    }
}

/// A back end whose cargo feature is off in this build of the crate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "the {} back end is not compiled in: enable the `{}` feature of wgsl-variants",
    .0.name(),
    .0.feature().unwrap_or_default()
)]
pub struct Disabled(pub TargetKind);

impl TargetKind {}

/// A language version that a back end does not know, as given on a command line or in a
/// build script.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum VersionError {
    /// Not a GLSL version at all.
    #[error("`{0}` is not a GLSL version (e.g. 450, 330, 300es, 310es)")]
    NotGlsl(String),
    /// A GLSL version naga does not write.
    #[error(
        "GLSL {0} is not supported by naga (desktop: 140, 150, 330, 400, 410, 420, 430, 440, 450, 460; ES: 300es, 310es, 320es)"
    )]
    UnsupportedGlsl(String),
    /// Not an HLSL shader model naga knows.
    #[error("`{0}` is not a shader model (5_0, 5_1, 6_0 … 6_9)")]
    NotShaderModel(String),
    /// Not an MSL version naga knows.
    #[error("`{0}` is not an MSL version (e.g. 2.0, 2.4, 3.0)")]
    NotMsl(String),
}

/// Parses a GLSL version: `450` (desktop core: 140 to 460) or `300es` / `310es` / `320es`.
///
/// ```
/// use wgsl_variants::emit::backends::parse_glsl_version;
/// assert!(parse_glsl_version("300es").unwrap().is_es());
/// assert!(parse_glsl_version("451").is_err());
/// ```
#[cfg(feature = "glsl-out")]
pub fn parse_glsl_version(text: &str) -> Result<naga::back::glsl::Version, VersionError> {
    let t = text.trim().to_ascii_lowercase();
    let t = t.strip_suffix("core").unwrap_or(&t).trim();
    let (digits, es) = match t.strip_suffix("es") {
        Some(d) => (d.trim(), true),
        None => (t, false),
    };
    let number: u16 = digits
        .parse()
        .map_err(|_| VersionError::NotGlsl(text.to_string()))?;
    let version = if es {
        naga::back::glsl::Version::new_gles(number)
    } else {
        naga::back::glsl::Version::Desktop(number)
    };
    if !version.is_supported() {
        return Err(VersionError::UnsupportedGlsl(text.to_string()));
    }
    Ok(version)
}

/// Parses an HLSL shader model: `5_0`, `5_1`, `6_0` … `6_9` (`5.0` works too).
#[cfg(feature = "hlsl-out")]
pub fn parse_shader_model(text: &str) -> Result<naga::back::hlsl::ShaderModel, VersionError> {
    use naga::back::hlsl::ShaderModel as Sm;
    Ok(match text.trim().replace('.', "_").as_str() {
        "5_0" => Sm::V5_0,
        "5_1" => Sm::V5_1,
        "6_0" => Sm::V6_0,
        "6_1" => Sm::V6_1,
        "6_2" => Sm::V6_2,
        "6_3" => Sm::V6_3,
        "6_4" => Sm::V6_4,
        "6_5" => Sm::V6_5,
        "6_6" => Sm::V6_6,
        "6_7" => Sm::V6_7,
        "6_8" => Sm::V6_8,
        "6_9" => Sm::V6_9,
        _ => {
            return Err(VersionError::NotShaderModel(text.to_string()));
        }
    })
}

/// Parses a Metal Shading Language version `MAJOR.MINOR` (1.0 to 3.x).
#[cfg(feature = "msl-out")]
pub fn parse_msl_version(text: &str) -> Result<(u8, u8), VersionError> {
    let bad = || VersionError::NotMsl(text.to_string());
    let (major, minor) = text.trim().split_once('.').ok_or_else(bad)?;
    let major: u8 = major.parse().map_err(|_| bad())?;
    let minor: u8 = minor.parse().map_err(|_| bad())?;
    if !(1..=3).contains(&major) {
        return Err(bad());
    }
    Ok((major, minor))
}

/// Options shared by the back ends.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Options {
    /// Keep WGSL's coordinate space in SPIR-V and GLSL instead of adjusting it to the target
    /// API's (naga's `ADJUST_COORDINATE_SPACE`, on by default as in the `naga` CLI: flips Y
    /// and maps depth for Vulkan/GL). Set it when the output is fed back to wgpu.
    pub keep_coordinate_space: bool,
}

/// The contents of one output.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Contents {
    /// Source text (WGSL, GLSL, HLSL, MSL).
    Text(String),
    /// SPIR-V words.
    SpirV(Vec<u32>),
}

impl Contents {
    /// The bytes of a file holding this output (SPIR-V: little-endian words).
    pub fn to_bytes(&self) -> Vec<u8> {
        match self {
            Contents::Text(t) => t.as_bytes().to_vec(),
            Contents::SpirV(words) => words.iter().flat_map(|w| w.to_le_bytes()).collect(),
        }
    }

    /// The text, for text outputs.
    pub fn as_text(&self) -> Option<&str> {
        match self {
            Contents::Text(t) => Some(t),
            Contents::SpirV(_) => None,
        }
    }
}

/// One output of a back end: the whole module, or (GLSL) one entry point.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    /// The entry point, for back ends that write one entry point per output.
    pub entry_point: Option<EntryPoint>,
    /// The contents.
    pub contents: Contents,
}

/// A back end failed on a valid module.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("naga's {target} back end failed{}: {message}", entry_point.as_ref().map(|e| format!(" on entry point `{e}`")).unwrap_or_default())]
pub struct BackendError {
    /// The target, e.g. `glsl 300es`.
    pub target: String,
    /// The entry point, when the failure is about one.
    pub entry_point: Option<String>,
    /// naga's message.
    pub message: String,
}

/// Why a variant could not be translated.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TranslateError {
    /// The variant is invalid.
    #[error(transparent)]
    Invalid(#[from] VariantError),
    /// A back end failed.
    #[error("{variant}: {error}")]
    Backend {
        /// `shader/pass {KEYWORDS}`.
        variant: String,
        /// The failure.
        error: BackendError,
    },
}

/// [`compile`](crate::validate::compile), then [`translate`] with default [`Options`].
pub fn translate_variant(
    lib: &Library,
    variant: &Variant<'_>,
    target: &Target,
) -> Result<Vec<Output>, TranslateError> {
    let all = translate_all(
        lib,
        variant,
        std::slice::from_ref(target),
        &Options::default(),
    )?;
    Ok(all.outputs.into_iter().map(|(_, output)| output).collect())
}

/// The outputs of one variant ([`translate_all`]).
#[derive(Clone, Debug, PartialEq)]
pub struct VariantOutputs {
    /// The variant's entry points.
    pub entry_points: Vec<EntryPoint>,
    /// Every output of every target, in target order.
    pub outputs: Vec<(Target, Output)>,
    /// For each target, in the order given: the flat slot of each binding ([`slots`]; empty
    /// but for GLSL and MSL).
    pub slots: Vec<Vec<Slot>>,
}

/// Every output of one variant for each target: [`compile`](crate::validate::compile) once,
/// then [`translate`] with each target in turn. The first failure is returned.
///
/// ```
/// use wgsl_variants::emit::backends::{Options, Target, translate_all};
///
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// # #[cfg(feature = "spv-out")] {
/// let all = translate_all(&lib, &v, &[Target::Wgsl, Target::SpirV], &Options::default()).unwrap();
/// assert_eq!(all.outputs.len(), 2);
/// assert!(all.slots.iter().all(Vec::is_empty));
/// # }
/// ```
pub fn translate_all(
    lib: &Library,
    variant: &Variant<'_>,
    targets: &[Target],
    options: &Options,
) -> Result<VariantOutputs, TranslateError> {
    let (module, info) = crate::validate::compile(lib, variant)?;
    let mut outputs = Vec::new();
    let mut target_slots = Vec::with_capacity(targets.len());
    for target in targets {
        let written = translate(&module, &info, target, options).map_err(|error| {
            TranslateError::Backend {
                variant: variant.label(),
                error,
            }
        })?;
        outputs.extend(written.into_iter().map(|o| (*target, o)));
        target_slots.push(slots(&module, &info, target));
    }
    Ok(VariantOutputs {
        entry_points: entry_points(&module),
        outputs,
        slots: target_slots,
    })
}

/// A flat slot of one binding in GLSL or MSL (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Slot {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The class the slot counts in: GLSL `uniform_block`, `storage_block`, `texture`,
    /// `image`, `sampler` (combined, no slot of its own); MSL `buffer`, `texture`, `sampler`.
    pub class: &'static str,
    /// The slot, or `None` for a GLSL sampler.
    pub slot: Option<u8>,
}

/// The GLSL or MSL slot of every binding the module's entry points use (other targets:
/// empty). `info` must be `module`'s validation result.
pub fn slots(module: &naga::Module, info: &naga::valid::ModuleInfo, target: &Target) -> Vec<Slot> {
    // The other targets bind by group and binding: no need to collect the bindings.
    if !matches!(target.kind(), TargetKind::Glsl | TargetKind::Msl) {
        return Vec::new();
    }
    flat_slots(module, info, target)
}

/// Without the GLSL and MSL back ends, no target has flat slots.
#[cfg(not(any(feature = "glsl-out", feature = "msl-out")))]
fn flat_slots(_: &naga::Module, _: &naga::valid::ModuleInfo, _: &Target) -> Vec<Slot> {
    Vec::new()
}

#[cfg(any(feature = "glsl-out", feature = "msl-out"))]
fn flat_slots(module: &naga::Module, info: &naga::valid::ModuleInfo, target: &Target) -> Vec<Slot> {
    use crate::reflect::{BindingKind, bindings};
    use std::collections::BTreeMap;
    let mut counters: BTreeMap<&'static str, u8> = BTreeMap::new();
    let mut next = |class: &'static str| {
        let n = counters.entry(class).or_insert(0);
        let slot = *n;
        *n = n.saturating_add(1);
        Some(slot)
    };
    bindings(module, info)
        .into_iter()
        .filter_map(|b| {
            let (class, slot) = match (target, &b.kind) {
                #[cfg(feature = "glsl-out")]
                (Target::Glsl(_), BindingKind::UniformBuffer { .. }) => {
                    ("uniform_block", next("uniform_block"))
                }
                #[cfg(feature = "glsl-out")]
                (Target::Glsl(_), BindingKind::StorageBuffer { .. }) => {
                    ("storage_block", next("storage_block"))
                }
                #[cfg(feature = "glsl-out")]
                (Target::Glsl(_), BindingKind::StorageTexture { .. }) => ("image", next("image")),
                #[cfg(feature = "glsl-out")]
                (Target::Glsl(_), BindingKind::Sampler { .. }) => ("sampler", None),
                #[cfg(feature = "glsl-out")]
                (Target::Glsl(_), _) => ("texture", next("texture")),
                #[cfg(feature = "msl-out")]
                (
                    Target::Msl(..),
                    BindingKind::UniformBuffer { .. } | BindingKind::StorageBuffer { .. },
                ) => ("buffer", next("buffer")),
                #[cfg(feature = "msl-out")]
                (Target::Msl(..), BindingKind::Sampler { .. }) => ("sampler", next("sampler")),
                #[cfg(feature = "msl-out")]
                (Target::Msl(..), _) => ("texture", next("texture")),
                _ => return None,
            };
            Some(Slot {
                group: b.group,
                binding: b.binding,
                class,
                slot,
            })
        })
        .collect()
}

fn backend_error(
    target: &Target,
    entry_point: Option<&str>,
    message: impl fmt::Display,
) -> BackendError {
    BackendError {
        target: target.to_string(),
        entry_point: entry_point.map(str::to_string),
        message: message.to_string(),
    }
}

/// Writes a validated module with one back end. `info` must be `module`'s validation result.
#[cfg_attr(
    not(any(feature = "spv-out", feature = "glsl-out")),
    allow(unused_variables)
)]
pub fn translate(
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    target: &Target,
    options: &Options,
) -> Result<Vec<Output>, BackendError> {
    let whole = |contents| {
        vec![Output {
            entry_point: None,
            contents,
        }]
    };
    match target {
        Target::Wgsl => {
            let text = naga::back::wgsl::write_string(
                module,
                info,
                naga::back::wgsl::WriterFlags::empty(),
            )
            .map_err(|e| backend_error(target, None, e))?;
            Ok(whole(Contents::Text(text)))
        }
        #[cfg(feature = "spv-out")]
        Target::SpirV => {
            use naga::back::spv;
            // Explicit flags: naga's default adds DEBUG only in debug builds, and outputs must
            // not depend on the build profile. DEBUG (names) is always on.
            let mut flags = spv::WriterFlags::DEBUG
                | spv::WriterFlags::LABEL_VARYINGS
                | spv::WriterFlags::CLAMP_FRAG_DEPTH;
            if !options.keep_coordinate_space {
                flags |= spv::WriterFlags::ADJUST_COORDINATE_SPACE;
            }
            let spv_options = spv::Options {
                lang_version: (1, 0),
                flags,
                ..spv::Options::default()
            };
            let words = spv::write_vec(module, info, &spv_options, None)
                .map_err(|e| backend_error(target, None, e))?;
            Ok(whole(Contents::SpirV(words)))
        }
        #[cfg(feature = "glsl-out")]
        Target::Glsl(version) => {
            use naga::back::glsl;
            let mut binding_map = glsl::BindingMap::default();
            for slot in slots(module, info, target) {
                if let Some(n) = slot.slot {
                    binding_map.insert(
                        naga::ResourceBinding {
                            group: slot.group,
                            binding: slot.binding,
                        },
                        n,
                    );
                }
            }
            let glsl_options = glsl::Options {
                version: *version,
                writer_flags: if options.keep_coordinate_space {
                    glsl::WriterFlags::empty()
                } else {
                    glsl::WriterFlags::ADJUST_COORDINATE_SPACE
                },
                binding_map,
                zero_initialize_workgroup_memory: true,
            };
            let mut outputs = Vec::new();
            for (ep, reflected) in module.entry_points.iter().zip(entry_points(module)) {
                let pipeline = glsl::PipelineOptions {
                    shader_stage: ep.stage,
                    entry_point: ep.name.clone(),
                    multiview: None,
                };
                let mut text = String::new();
                let mut writer = glsl::Writer::new(
                    &mut text,
                    module,
                    info,
                    &glsl_options,
                    &pipeline,
                    naga::proc::BoundsCheckPolicies::default(),
                )
                .map_err(|e| backend_error(target, Some(&ep.name), e))?;
                writer
                    .write()
                    .map_err(|e| backend_error(target, Some(&ep.name), e))?;
                outputs.push(Output {
                    entry_point: Some(reflected),
                    contents: Contents::Text(text),
                });
            }
            Ok(outputs)
        }
        #[cfg(feature = "hlsl-out")]
        Target::Hlsl(shader_model) => {
            use naga::back::hlsl;
            let hlsl_options = hlsl::Options {
                shader_model: *shader_model,
                ..hlsl::Options::default()
            };
            let pipeline = hlsl::PipelineOptions::default();
            let mut text = String::new();
            let reflection = hlsl::Writer::new(&mut text, &hlsl_options, &pipeline)
                .write(module, info, None)
                .map_err(|e| backend_error(target, None, e))?;
            for (ep, name) in module
                .entry_points
                .iter()
                .zip(&reflection.entry_point_names)
            {
                if let Err(e) = name {
                    return Err(backend_error(target, Some(&ep.name), e));
                }
            }
            Ok(whole(Contents::Text(text)))
        }
        #[cfg(feature = "msl-out")]
        Target::Msl(major, minor) => {
            use naga::back::msl;
            let mut resources = msl::BindingMap::default();
            let mut buffers = 0u8;
            for slot in slots(module, info, target) {
                let key = naga::ResourceBinding {
                    group: slot.group,
                    binding: slot.binding,
                };
                let var = module
                    .global_variables
                    .iter()
                    .find(|(_, v)| v.binding == Some(key))
                    .map(|(_, v)| v);
                let mutable = matches!(
                    var.map(|v| v.space),
                    Some(naga::AddressSpace::Storage { access }) if access.contains(naga::StorageAccess::STORE)
                );
                let mut bind = msl::BindTarget {
                    mutable,
                    ..msl::BindTarget::default()
                };
                match slot.class {
                    "buffer" => {
                        bind.buffer = slot.slot;
                        buffers = buffers.max(slot.slot.unwrap_or(0) + 1);
                    }
                    "sampler" => bind.sampler = slot.slot.map(msl::BindSamplerTarget::Resource),
                    _ => bind.texture = slot.slot,
                }
                resources.insert(key, bind);
            }
            let per_entry_point_map = module
                .entry_points
                .iter()
                .map(|ep| {
                    (
                        ep.name.clone(),
                        msl::EntryPointResources {
                            resources: resources.clone(),
                            immediates_buffer: None,
                            sizes_buffer: Some(buffers),
                        },
                    )
                })
                .collect();
            let msl_options = msl::Options {
                lang_version: (*major, *minor),
                per_entry_point_map,
                fake_missing_bindings: false,
                ..msl::Options::default()
            };
            let (text, translation) =
                msl::write_string(module, info, &msl_options, &msl::PipelineOptions::default())
                    .map_err(|e| backend_error(target, None, e))?;
            for (ep, name) in module
                .entry_points
                .iter()
                .zip(&translation.entry_point_names)
            {
                if let Err(e) = name {
                    return Err(backend_error(target, Some(&ep.name), e));
                }
            }
            Ok(whole(Contents::Text(text)))
        }
    }
}

/// One text output of [`Translation`]: a back end's module, or (GLSL) one entry point.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct TextOutput {
    /// The target as written (`glsl 450`, `hlsl 5_1`).
    pub target: String,
    /// The entry point, for back ends with one output per entry point (GLSL).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub entry_point: Option<String>,
    /// That entry point's stage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<Stage>,
    /// The text (empty for SPIR-V, which is binary).
    pub text: String,
}

/// One variant through several back ends, as text (what `emit --target … --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct Translation {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Keywords that are on, in set order.
    pub keywords: Vec<String>,
    /// The outputs, target by target in the order given.
    pub outputs: Vec<TextOutput>,
    /// The entry points of the module.
    #[serde(skip)]
    pub entry_points: Vec<EntryPoint>,
}

/// [`translate_all`], with every output as text (what `emit --target … --json` prints).
///
/// ```
/// use wgsl_variants::emit::backends::{Options, Target, translate_to_text};
///
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// let t = translate_to_text(&lib, &v, &[Target::Wgsl], &Options::default()).unwrap();
/// assert!(t.outputs[0].text.contains("fn fs_main"));
/// ```
pub fn translate_to_text(
    lib: &Library,
    variant: &Variant<'_>,
    targets: &[Target],
    options: &Options,
) -> Result<Translation, TranslateError> {
    let all = translate_all(lib, variant, targets, options)?;
    let outputs = all
        .outputs
        .into_iter()
        .map(|(target, output)| TextOutput {
            target: target.to_string(),
            entry_point: output.entry_point.as_ref().map(|e| e.name.clone()),
            stage: output.entry_point.as_ref().map(|e| e.stage),
            text: output.contents.as_text().unwrap_or_default().to_string(),
        })
        .collect();
    Ok(Translation {
        shader: variant.pass.shader.clone(),
        pass: variant.pass.name.clone(),
        keywords: variant.keywords().into_iter().map(str::to_string).collect(),
        outputs,
        entry_points: all.entry_points,
    })
}
