//! The preprocessor: directive lines, `#if` expressions, and composition of one variant.
//!
//! Parsing (within [`ParseLimits`]; failures are [`ParseError`]s) happens once per module file
//! when a [`Library`](crate::Library) loads; composing one variant
//! ([`Library::compose`](crate::Library::compose)) walks the parsed tree for one keyword set and
//! copies WGSL lines into a [`Composed`] text, keeping a [`LineMap`] so errors in the output
//! point back at original files. The parsed tree, line splitting and `#if` expressions are
//! internal. The directive syntax is documented in the README.

pub(crate) mod compose;
mod error;
pub(crate) mod expr;
pub(crate) mod line_map;
pub(crate) mod lines;
pub(crate) mod parse;
pub(crate) mod tree;

pub use compose::Composed;
pub use error::ParseError;
pub use line_map::LineMap;
pub(crate) use parse::parse_module_in;
pub use parse::{Dialect, ParseLimits};

/// Parses `text` as an `#if` expression (nesting bounded to 256) and evaluates it; `value` gives
/// a name's value. Public, and hidden, only for the `expr` property of the fuzz-checks crate:
/// the expression tree is internal.
#[doc(hidden)]
pub fn eval_expr(text: &str, value: &dyn Fn(&str) -> Option<i64>) -> Result<i64, ParseError> {
    Ok(expr::parse(text, 0, 0, 256)?.eval(value))
}
