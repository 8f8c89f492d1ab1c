//! The preprocessor: directive lines, `#if` expressions, and composition of one variant.
//!
//! Parsing ([`parse::parse_module`]) happens once per module file; composing
//! ([`compose::compose`]) walks the parsed tree for one keyword set and copies WGSL lines,
//! keeping a [`line_map::LineMap`] so errors in the output point back at original files.
//! The directive syntax is documented in the README.

pub mod compose;
pub mod error;
pub mod expr;
pub mod line_map;
pub mod lines;
pub mod parse;
pub mod tree;

pub use compose::Composed;
pub use error::ParseError;
pub use parse::{ParseLimits, parse_module};
