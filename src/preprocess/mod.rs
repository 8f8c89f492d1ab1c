//! The preprocessor: directive lines, `#if` expressions, and composition of one variant.
//!
//! Parsing (within [`ParseLimits`]; failures are [`ParseError`]s) happens once per module file
//! when a [`Library`](crate::Library) loads; composing one variant
//! ([`Library::compose`](crate::Library::compose)) walks the parsed tree for one keyword set and
//! copies WGSL lines into a [`Composed`] text, keeping a [`LineMap`] so errors in the output
//! point back at original files. The parsed tree itself is internal. [`lines`] splits WGSL
//! lines and [`expr`] parses `#if` expressions. The directive syntax is documented in the
//! README.

pub(crate) mod compose;
pub mod error;
pub mod expr;
pub(crate) mod line_map;
pub mod lines;
pub(crate) mod parse;
pub(crate) mod tree;

pub use compose::Composed;
pub use error::ParseError;
pub use line_map::LineMap;
pub(crate) use parse::parse_module_in;
pub use parse::{Dialect, ParseLimits};
