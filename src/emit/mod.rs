//! Taking the validated variants into other renderers.
//!
//! - [`backends`]: every naga back end (WGSL, SPIR-V, GLSL, HLSL, MSL) for one variant.
//! - [`set`]: a whole build set written to a folder with a `manifest.json`.
//! - [`reflect`]: the bind groups and bindings a variant uses, from naga's IR (and, with the
//!   `gpu` feature, as wgpu `BindGroupLayoutEntry` values).
//! - [`bake`]: a `build.rs` API that validates a build set at compile time and generates Rust
//!   with the baked variants and a strict lookup.
//! - [`export`]: one module (with its imports) on its own, as self-contained WGSL under a name
//!   prefix, or in naga_oil's dialect ([`naga_oil`]).
//!
//! ```
//! use wgsl_variants::emit::backends::{Target, translate_variant};
//!
//! let lib = wgsl_variants::Library::bundled().unwrap();
//! let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
//! let outputs = translate_variant(&lib, &v, &Target::SpirV).unwrap();
//! assert_eq!(outputs[0].contents.to_bytes()[..4], 0x0723_0203u32.to_le_bytes());
//! ```

pub mod backends;
pub mod bake;
pub mod export;
pub mod naga_oil;
pub mod reflect;
pub mod set;

use std::path::Path;

/// Writes `bytes` to `path` unless the file already holds them, so that an unchanged output
/// keeps its modification time (and does not make `cargo` or other build tools rebuild).
pub(crate) fn write_if_changed(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    if std::fs::read(path).is_ok_and(|old| old == bytes) {
        return Ok(());
    }
    std::fs::write(path, bytes)
}
