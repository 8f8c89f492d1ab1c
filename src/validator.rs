//! naga's verdict on one composed text: the [`validator`] (every check, WebGPU's capabilities)
//! and [`validate_composed`], whose errors point into the original module files. The library
//! composes with it; [`crate::validate`] runs it over whole variant spaces.

use crate::diagnostic::Span;
use crate::error::{Stage, VariantError};
use crate::preprocess::Composed;

fn error_chain(e: &dyn std::error::Error) -> String {
    let mut message = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        message.push_str(": ");
        message.push_str(&s.to_string());
        source = s.source();
    }
    message
}

/// Parses and validates composed WGSL for WebGPU ([`Profile::WebGpu`]); `variant` names it
/// in errors.
pub fn validate_composed(
    composed: &Composed,
    variant: &str,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    validate_for(composed, variant, Profile::WebGpu)
}

/// Parses and validates composed WGSL for `profile`; `variant` names it in errors.
pub fn validate_for(
    composed: &Composed,
    variant: &str,
    profile: Profile,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    validate_with(composed, variant, &mut profile.validator(), profile)
}

/// The validator of the default profile, [`Profile::WebGpu`]: every check on, and the
/// capabilities WebGPU gives a shader by default (what wgpu accepts without optional
/// features).
pub fn validator() -> naga::valid::Validator {
    Profile::WebGpu.validator()
}

/// The device a tree is validated for: naga's capabilities, and for WebGL2 the resources and
/// stages its downlevel limits leave out. A variant valid on one profile may fail on another;
/// the library's profile is set by the declaration file (`profile = "desktop"`),
/// [`crate::Library::set_profile`] or the command line's `--profile`.
///
/// ```
/// use wgsl_variants::validate::Profile;
/// let desktop: Profile = "desktop".parse().unwrap();
/// assert!(desktop.capabilities().contains(naga::valid::Capabilities::TEXTURE_AND_SAMPLER_BINDING_ARRAY));
/// let listed: Profile = "CUBE_ARRAY_TEXTURES,FLOAT64".parse().unwrap();
/// assert_eq!(listed.capabilities().bits().count_ones(), 2);
/// assert!("webgl3".parse::<Profile>().is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Profile {
    /// WebGPU without optional features: naga's default capabilities (multisampled shading,
    /// cube array textures), what wgpu's `Limits::default()` device accepts.
    #[default]
    WebGpu,
    /// WebGL2 as wgpu's `downlevel_webgl2_defaults` and `DownlevelCapabilities` state it: no
    /// cube array textures, no per-sample shading, no storage buffers or storage textures
    /// (`max_storage_buffers_per_shader_stage` and `max_storage_textures_per_shader_stage`
    /// are 0), no compute shaders.
    WebGl2,
    /// A current Vulkan, Metal or DirectX 12 device with the features a desktop renderer
    /// turns on (Bevy's among them): WebGPU's capabilities plus binding arrays of every kind
    /// with non-uniform indexing, immediates (push constants), 64-bit floats, primitive
    /// index, clip and cull distances, multiview, early depth test, dual-source blending and
    /// subgroups.
    Desktop,
    /// An explicit set of naga capabilities (`CUBE_ARRAY_TEXTURES,FLOAT64`, naga's names).
    Capabilities(naga::valid::Capabilities),
}

impl Profile {
    /// naga's capabilities for this profile.
    pub fn capabilities(self) -> naga::valid::Capabilities {
        use naga::valid::Capabilities as C;
        match self {
            Profile::WebGpu => C::default(),
            Profile::WebGl2 => C::empty(),
            Profile::Desktop => {
                C::default()
                    | C::IMMEDIATES
                    | C::FLOAT64
                    | C::PRIMITIVE_INDEX
                    | C::TEXTURE_AND_SAMPLER_BINDING_ARRAY
                    | C::BUFFER_BINDING_ARRAY
                    | C::STORAGE_TEXTURE_BINDING_ARRAY
                    | C::STORAGE_BUFFER_BINDING_ARRAY
                    | C::TEXTURE_AND_SAMPLER_BINDING_ARRAY_NON_UNIFORM_INDEXING
                    | C::BUFFER_BINDING_ARRAY_NON_UNIFORM_INDEXING
                    | C::STORAGE_TEXTURE_BINDING_ARRAY_NON_UNIFORM_INDEXING
                    | C::STORAGE_BUFFER_BINDING_ARRAY_NON_UNIFORM_INDEXING
                    | C::CLIP_DISTANCES
                    | C::CULL_DISTANCE
                    | C::MULTIVIEW
                    | C::EARLY_DEPTH_TEST
                    | C::DUAL_SOURCE_BLENDING
                    | C::SUBGROUP
                    | C::SUBGROUP_BARRIER
            }
            Profile::Capabilities(c) => c,
        }
    }

    /// A validator with every check on and this profile's capabilities.
    pub fn validator(self) -> naga::valid::Validator {
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), self.capabilities())
    }

    /// The profile's name: `webgpu`, `webgl2`, `desktop`, or the capabilities listed.
    pub fn name(self) -> String {
        match self {
            Profile::WebGpu => "webgpu".into(),
            Profile::WebGl2 => "webgl2".into(),
            Profile::Desktop => "desktop".into(),
            Profile::Capabilities(c) => {
                let names: Vec<&str> = c.iter_names().map(|(n, _)| n).collect();
                if names.is_empty() {
                    "none".into()
                } else {
                    names.join(",")
                }
            }
        }
    }

    /// What the profile refuses beyond naga's capabilities (WebGL2's missing storage
    /// resources and compute stage), with the span of the item in `module`.
    pub(crate) fn refuses(self, module: &naga::Module) -> Option<(String, naga::Span)> {
        if self != Profile::WebGl2 {
            return None;
        }
        for (handle, var) in module.global_variables.iter() {
            let storage_texture = matches!(
                module.types[var.ty].inner,
                naga::TypeInner::Image {
                    class: naga::ImageClass::Storage { .. },
                    ..
                }
            );
            let what = if matches!(var.space, naga::AddressSpace::Storage { .. }) {
                "a storage buffer"
            } else if storage_texture {
                "a storage texture"
            } else {
                continue;
            };
            let name = var.name.as_deref().unwrap_or("?");
            return Some((
                format!(
                    "`{name}` is {what}, which WebGL2 does not have (wgpu's downlevel WebGL2 limits allow 0 per shader stage)"
                ),
                module.global_variables.get_span(handle),
            ));
        }
        module
            .entry_points
            .iter()
            .find(|e| e.stage == naga::ShaderStage::Compute)
            .map(|e| {
                (
                    format!(
                        "`{}` is a compute entry point, which WebGL2 does not run (wgpu's downlevel WebGL2 capabilities have no compute shaders)",
                        e.name
                    ),
                    e.function
                        .expressions
                        .iter()
                        .next()
                        .map_or(naga::Span::default(), |(h, _)| e.function.expressions.get_span(h)),
                )
            })
    }
}

/// A profile name that is none of the profiles and not a list of naga's capability names.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "unknown profile `{0}`: a profile is `webgpu`, `webgl2`, `desktop`, or naga capability names joined by `,` (e.g. `CUBE_ARRAY_TEXTURES,FLOAT64`)"
)]
pub struct ProfileError(pub String);

impl std::str::FromStr for Profile {
    type Err = ProfileError;

    fn from_str(s: &str) -> Result<Profile, ProfileError> {
        match s {
            "webgpu" => Ok(Profile::WebGpu),
            "webgl2" => Ok(Profile::WebGl2),
            "desktop" => Ok(Profile::Desktop),
            "none" => Ok(Profile::Capabilities(naga::valid::Capabilities::empty())),
            list => list
                .split([',', '|', '+'])
                .map(|n| naga::valid::Capabilities::from_name(n.trim()))
                .try_fold(naga::valid::Capabilities::empty(), |all, c| {
                    c.map(|c| all | c)
                })
                .map(Profile::Capabilities)
                .ok_or_else(|| ProfileError(s.to_string())),
        }
    }
}

fn map_spans<'a>(
    composed: &Composed,
    spans: impl Iterator<Item = (naga::Span, &'a str)>,
) -> Vec<(Span, String)> {
    spans
        .filter_map(|(span, label)| {
            let range = span.to_range()?;
            let original = composed
                .map
                .to_original(range.start, range.end, &composed.text)?;
            Some((original, label.to_string()))
        })
        .collect()
}

/// naga's parse error message. Its internal errors ("internal WGSL front end error") carry what
/// went wrong in a note and have no location: the note joins the message, so every report
/// (text, JSON, `watch`) says which limit tripped.
fn parse_message(e: &naga::front::wgsl::ParseError) -> String {
    let message = e.message();
    if e.labels().next().is_some() {
        return message.to_string();
    }
    let notes: Vec<&str> = e.notes().collect();
    if notes.is_empty() {
        return message.to_string();
    }
    let hint = if notes.iter().any(|n| n.contains("recursion limit")) {
        " (naga's WGSL parser nests expressions, blocks and types at most 200 levels deep: split the nesting with `let` bindings or functions)"
    } else {
        ""
    };
    format!("{message}: {}{hint}", notes.join("; "))
}

pub(crate) fn validate_with(
    composed: &Composed,
    variant: &str,
    validator: &mut naga::valid::Validator,
    profile: Profile,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    if let Some(failure) = &composed.failure {
        return Err(VariantError {
            variant: variant.to_string(),
            ..(**failure).clone()
        });
    }
    let module = naga::front::wgsl::parse_str(&composed.text).map_err(|e| {
        VariantError {
            variant: variant.to_string(),
            stage: Stage::Parse,
            message: parse_message(&e),
            labels: map_spans(composed, e.labels()),
            notes: e.notes().map(str::to_string).collect(),
            source: None,
        }
        .with_source(e)
    })?;
    let info = validator.validate(&module).map_err(|e| {
        let mut labels = map_spans(composed, e.spans().map(|(s, l)| (*s, l.as_str())));
        // naga lists the enclosing function first; the narrowest span is where to look.
        labels.sort_by_key(|(span, _)| span.end - span.start);
        VariantError {
            variant: variant.to_string(),
            stage: Stage::Validate,
            message: error_chain(e.as_inner()),
            labels,
            notes: Vec::new(),
            source: None,
        }
        .with_source(e)
    })?;
    if let Some((message, span)) = profile.refuses(&module) {
        return Err(VariantError {
            variant: variant.to_string(),
            stage: Stage::Validate,
            message: format!("on profile `{}`: {message}", profile.name()),
            labels: map_spans(composed, std::iter::once((span, "here"))),
            notes: Vec::new(),
            source: None,
        });
    }
    Ok((module, info))
}
