//! `serde` helpers for the JSON reports (`wgsl-variants … --json` prints the `serde_json`
//! serialization of the library's report types).

use num_bigint::BigUint;
use serde::{Serialize as _, Serializer};
use serde_json::value::RawValue;

/// Serializes an exact count as a JSON integer of any size (JSON numbers are unbounded; a
/// parser that cannot hold it still sees a number, never a rounded value). For
/// `#[serde(serialize_with = "wgsl_variants::json::exact_count")]`.
///
/// ```
/// #[derive(serde::Serialize)]
/// struct Counted {
///     #[serde(serialize_with = "wgsl_variants::json::exact_count")]
///     variants: num_bigint::BigUint,
/// }
/// let n = num_bigint::BigUint::from(2u32).pow(70);
/// let text = serde_json::to_string(&Counted { variants: n }).unwrap();
/// assert_eq!(text, r#"{"variants":1180591620717411303424}"#);
/// ```
pub fn exact_count<S: Serializer>(n: &BigUint, s: S) -> Result<S::Ok, S::Error> {
    RawValue::from_string(n.to_string())
        .expect("a decimal integer is valid JSON")
        .serialize(s)
}

/// Serializes a value as the string its `Display` writes.
pub fn display<T: std::fmt::Display, S: Serializer>(value: &T, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(value)
}

/// [`exact_count`] as a value, e.g. inside an `Option` or a tuple.
pub(crate) struct ExactCount<'a>(pub &'a BigUint);

impl serde::Serialize for ExactCount<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        exact_count(self.0, s)
    }
}
