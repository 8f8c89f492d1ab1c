//! # wgsl-variants
//!
//! Unity-style shader **variants** for trees of WGSL modules: `#pragma multi_compile` and
//! `#pragma shader_feature` keyword sets, `#if` with boolean expressions and valued defines,
//! `#import` of modules — and **every** variant validated by naga, with errors that name the
//! original `file:line:col` and the keyword set of the variant.
//!
//! The crate also bundles a deferred-shading library (`wgsl/`: G-buffer pass, LDR `exp2(-c)`
//! encoding, reflection-probe blending) and a CPU [`reference`](mod@reference) of its math. The
//! wgpu harness that proves the WGSL against the reference is the `wgsl-variants-gpu` crate, and
//! the command line is `wgsl-variants-cli`: this crate has no wgpu, clap or image in its tree,
//! so a `build.rs` can depend on it cheaply.
//!
//! ```
//! use wgsl_variants::{Library, variants::Space};
//!
//! let lib = Library::bundled().unwrap();
//! for pass in lib.passes() {
//!     println!("{}/{}: {} variants", pass.shader, pass.name, Space::full(pass).count());
//! }
//! let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
//! let (module, _info) = lib.naga_module(&v).unwrap();
//! # let _ = module;
//! ```
//!
//! ## The pipeline, one module per stage
//!
//! 1. [`source`] reads files; [`preprocess`] splits WGSL lines, parses directives and composes
//!    a variant; [`library`] loads and links a tree ([`LoadError`] holds every problem, typed);
//!    [`reach`] leaves out of a variant's text the items its entry points do not reach.
//! 2. [`keywords`], [`shader`], [`variants`] ([`Space`], [`Choice`]), [`lookup`] and
//!    [`materials`] model Unity's keyword semantics; [`plan`] chooses what a command builds.
//! 3. [`validate`] runs naga ([`cache`] remembers valid texts); [`audit`] measures a variant
//!    explosion without building anything.
//! 4. [`emit`] writes every naga back end and whole build sets; [`reflect`] lists bindings;
//!    [`bake`] does it all from a `build.rs`; [`snapshot`] serves insta tests.
//!    [`merge`] puts the outputs of `--shard K/N` runs back together, byte for byte;
//!    [`watch`] validates a tree again as it changes (`wgsl-variants watch`, hot reload).
//! 5. [`diagnostic`] renders errors, [`json`] serializes exact counts, [`reference`](mod@reference) is the
//!    CPU math of the bundled library.
//!
//! `docs/api.md` in the repository lists the main items of each stage.

#![deny(missing_docs)]

pub mod audit;
pub mod bake;
pub mod cache;
pub mod covering;
pub mod data_file;
pub mod declaration;
pub mod diagnostic;
pub mod emit;
pub mod json;
pub mod keywords;
pub mod library;
pub mod lookup;
pub mod materials;
pub mod merge;
pub mod plan;
pub mod preprocess;
pub mod reach;
pub mod reference;
pub mod reflect;
pub mod shader;
pub mod snapshot;
pub mod source;
pub mod validate;
pub mod variants;
pub mod watch;

pub use diagnostic::{Diagnostic, Location, Severity, SourceFiles, Span};
pub use library::{Library, LoadError, LoadOptions, Variant};
pub use lookup::LookupError;
pub use preprocess::Dialect;
pub use shader::{Pass, Shader};
pub use validate::VariantError;
pub use variants::{Choice, Space};
