//! Taking the validated variants into other renderers.
//!
//! - [`backends`]: every naga back end (WGSL, SPIR-V, GLSL, HLSL, MSL) for one variant.
//! - [`set`]: a whole build set written to a folder with a `manifest.json`.
//!
//! Reflection ([`crate::reflect`]) and `build.rs` baking ([`crate::bake`]) are stages of their
//! own that use these back ends.
//! - [`export`]: one module (with its imports) on its own, as self-contained WGSL under a name
//!   prefix, in naga_oil's dialect ([`naga_oil`]) or in WESL's ([`wesl`]).
//!
//! ```
//! use wgsl_variants::emit::backends::{Target, translate_variant};
//!
//! # #[cfg(feature = "spv-out")] {
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
//! let outputs = translate_variant(&lib, &v, &Target::SpirV).unwrap();
//! assert_eq!(outputs[0].contents.to_bytes()[..4], 0x0723_0203u32.to_le_bytes());
//! # }
//! ```

pub mod backends;
pub mod export;
pub mod naga_oil;
mod scan;
pub mod set;
pub mod wesl;

use std::path::Path;

use crate::error::VariantError;
use crate::library::{Library, Variant};

/// One variant's composed WGSL, as written (what `emit SHADER PASS --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct VariantSource {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Keywords that are on, in set order.
    pub keywords: Vec<String>,
    /// The composed text.
    pub wgsl: String,
}

/// Composes a variant, and validates the text with naga when `validate` is set (a variant
/// naga_oil could not compose is an error either way: there is no text).
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// let source = wgsl_variants::emit::variant_source(&lib, &v, true).unwrap();
/// assert_eq!(source.keywords, ["_NORMAL_MAP"]);
/// ```
pub fn variant_source(
    lib: &Library,
    variant: &Variant<'_>,
    validate: bool,
) -> Result<VariantSource, VariantError> {
    let composed = lib.compose(variant);
    // A variant that could not be composed (naga_oil's error) has no text to give, validated
    // or not.
    if validate || composed.failure.is_some() {
        crate::validator::validate_for(
            &composed,
            &variant.label(),
            lib.pass_profile(variant.pass),
        )?;
    }
    Ok(VariantSource {
        shader: variant.pass.shader.clone(),
        pass: variant.pass.name.clone(),
        keywords: variant.keywords().into_iter().map(str::to_string).collect(),
        wgsl: composed.text,
    })
}

/// Writes `bytes` to `path` unless the file already holds them, so that an unchanged output
/// keeps its modification time (and does not make `cargo` or other build tools rebuild).
pub(crate) fn write_if_changed(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    std::fs::write(path, bytes)
}
