//! # wgsl-variants
//!
//! Unity-style shader **variants** for trees of WGSL modules: `#pragma multi_compile` and
//! `#pragma shader_feature` keyword sets, `#if` with boolean expressions and valued defines,
//! `#import` of modules — and **every** variant validated by naga, with errors that name the
//! original `file:line:col` and the keyword set of the variant.
//!
//! This crate is the engine. Its shading library (Unity's deferred paths as a WGSL keyword
//! tree, with a CPU reference of their math) is the `wgsl-variants-shaders` crate; the wgpu
//! harness that proves that WGSL against the reference is `wgsl-variants-gpu`, and the command
//! line is `wgsl-variants-cli`. This crate has no wgpu, clap, image or glam in its tree, so a
//! `build.rs` can depend on it cheaply.
//!
//! ```
//! use wgsl_variants::{Library, variants::Space};
//!
//! let lib = Library::from_sources([
//!     ("lib/tint.wgsl", "fn tint() -> vec4f {\n#if RED\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n#else\n    return vec4f(1.0);\n#endif\n}\n"),
//!     ("unlit.wgsl", "#shader unlit\n#pass Forward\n#pragma multi_compile _ RED\n#import lib/tint\n\
//!                     @fragment fn fs() -> @location(0) vec4f { return tint(); }\n#endpass\n"),
//! ])
//! .unwrap();
//! for pass in lib.passes() {
//!     println!("{}/{}: {} variants", pass.shader, pass.name, Space::full(pass).count());
//! }
//! let v = lib.variant("unlit", "Forward", &["RED"]).unwrap();
//! let (module, _info) = lib.naga_module(&v).unwrap();
//! assert_eq!(module.entry_points[0].name, "fs");
//! ```
//!
//! ## The pipeline, one module per stage, each importing only the stages below it
//!
//! 1. [`diagnostic`], [`error`] ([`VariantError`]: every stage's report of a variant),
//!    [`source`] (reading files), [`cache`] and [`stage`] (a pipeline's stages) are the ground
//!    floor.
//! 2. [`preprocess`] splits WGSL lines, parses directives and composes a variant;
//!    [`keywords`], [`shader`], [`variants`] ([`Space`], [`Choice`]), [`lookup`], [`covering`]
//!    and [`materials`] model Unity's keyword semantics; [`declaration`] reads the keywords of
//!    naga_oil and WESL trees.
//! 3. [`library`] loads and links a tree ([`LoadError`] holds every problem, typed) and
//!    composes variants; [`reach`] leaves out of a variant's text the items its entry points do
//!    not reach; [`validator`] is naga's verdict on one text.
//! 4. [`analysis`] reads a space without composing it (distinct texts, regions, unreached
//!    items); [`plan`] chooses what a command builds; [`fingerprint`] names what an output was
//!    made from.
//! 5. [`validate`] runs naga over plans ([`cache`] remembers valid texts); [`audit`] measures a
//!    variant explosion without building anything.
//! 6. [`emit`] writes every naga back end and whole build sets; [`reflect`] lists bindings;
//!    [`bindings`] writes typed Rust for a pass (variant key, buffer structs, layouts);
//!    [`bake`] does it all from a `build.rs`; [`snapshot`] serves insta tests; [`merge`] puts
//!    the outputs of `--shard K/N` runs back together, byte for byte; [`watch`] validates a
//!    tree again as it changes (`wgsl-variants watch`, hot reload).
//!
//! `docs/api.md` in the repository lists the main items of each stage.

#![deny(missing_docs)]

pub mod analysis;
pub mod audit;
pub mod bake;
pub mod bindings;
pub mod cache;
pub mod covering;
pub mod data_file;
pub mod declaration;
pub mod diagnostic;
pub mod emit;
pub mod error;
pub mod fingerprint;
pub(crate) mod json;
pub mod keywords;
pub mod library;
pub mod lookup;
pub mod materials;
pub mod merge;
pub mod plan;
pub mod preprocess;
pub mod reach;
pub mod reflect;
pub mod shader;
pub mod snapshot;
pub mod source;
pub mod stage;
pub mod validate;
pub mod validator;
pub mod variants;
pub mod watch;

pub use diagnostic::{Diagnostic, Location, Severity, SourceFiles, Span};
pub use error::VariantError;
pub use library::{Library, LoadError, LoadOptions, Variant};
pub use lookup::LookupError;
pub use preprocess::Dialect;
pub use shader::{Pass, Shader};
pub use stage::PipelineStage;
pub use variants::{Choice, Space};

/// `docs/api.md`: its example is compiled and run with the doc tests, so the page cannot drift
/// from the API.
#[cfg(doctest)]
#[doc = include_str!("../docs/api.md")]
pub struct ApiDoc;
