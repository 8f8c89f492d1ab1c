//! # wgsl-variants-shaders
//!
//! The shading library of [wgsl-variants](wgsl_variants): Unity's deferred shading paths —
//! the built-in pipeline's G-buffer, lighting, forward and shadow caster passes, and URP's Lit
//! shader with its StencilDeferred lighting — written as a WGSL keyword tree in
//! wgsl-variants' own dialect, and a CPU [`reference`](mod@reference) of their math.
//!
//! This crate is the *content*; the engine that builds and validates its variants is
//! `wgsl-variants`, and the GPU proof that the WGSL equals the [`reference`](mod@reference) per texel is
//! `wgsl-variants-gpu`. A renderer that uses these shaders depends on this crate and on the
//! engine; a build script that bakes them calls [`bake`].
//!
//! ```
//! use wgsl_variants::variants::Space;
//!
//! let lib = wgsl_variants_shaders::library().unwrap();
//! for pass in lib.passes() {
//!     println!("{}/{}: {} variants", pass.shader, pass.name, Space::full(pass).count());
//! }
//! let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
//! let (module, _info) = lib.naga_module(&v).unwrap();
//! # let _ = module;
//! ```
//!
//! The math each pass implements, with the Unity sources of every formula, is written down in
//! `docs/shading.md` (built-in) and `docs/urp.md` (URP) in the repository.

#![deny(missing_docs)]

pub mod brdf_lut;
pub mod reference;

use wgsl_variants::bake::Bake;
use wgsl_variants::source::RawFile;
use wgsl_variants::{Library, LoadError, LoadOptions};

mod embedded {
    include!(concat!(env!("OUT_DIR"), "/files.rs"));
}

/// How [`bake`] names this library in the files it generates.
const ORIGIN: &str = "the bundled library";

/// The library's module files (path relative to the crate's `wgsl/` folder, `/`-separated,
/// and contents), sorted by path.
///
/// ```
/// let files = wgsl_variants_shaders::files();
/// assert!(files.iter().any(|f| f.path == "standard.wgsl"));
/// assert!(files.windows(2).all(|w| w[0].path < w[1].path));
/// ```
pub fn files() -> Vec<RawFile> {
    embedded::FILES
        .iter()
        .map(|(path, bytes)| RawFile {
            path: (*path).to_string(),
            bytes: bytes.to_vec(),
        })
        .collect()
}

/// The library, loaded with the default limits.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// assert!(lib.shader("universal_lit").is_ok());
/// ```
pub fn library() -> Result<Library, LoadError> {
    library_with(&LoadOptions::default())
}

/// The library, loaded with explicit limits.
pub fn library_with(options: &LoadOptions) -> Result<Library, LoadError> {
    Library::from_raw(files(), options)
}

/// A [`Bake`] of this library for a `build.rs`: every variant of its build set built and
/// validated when the consuming crate compiles (see [`wgsl_variants::bake`]).
///
/// ```no_run
/// // build.rs
/// let baked = wgsl_variants_shaders::bake().materials("materials.toml").run();
/// println!("cargo:warning=baked {} variants", baked.variants);
/// ```
pub fn bake() -> Bake {
    Bake::from_files(files(), ORIGIN)
}
