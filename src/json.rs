//! `serde` helpers for the JSON reports (`wgsl-variants … --json` prints the `serde_json`
//! serialization of the library's report types).

use num_bigint::BigUint;
use serde::{Serialize as _, Serializer};
use serde_json::value::RawValue;

/// Serializes an exact count as a JSON integer of any size (JSON numbers are unbounded; a
/// parser that cannot hold it still sees a number, never a rounded value). For
/// `#[serde(serialize_with = "crate::json::exact_count")]`.
pub(crate) fn exact_count<S: Serializer>(n: &BigUint, s: S) -> Result<S::Ok, S::Error> {
    RawValue::from_string(n.to_string())
        .expect("a decimal integer is valid JSON")
        .serialize(s)
}

/// [`exact_count`] as a value, e.g. inside an `Option` or a tuple.
pub(crate) struct ExactCount<'a>(pub &'a BigUint);

impl serde::Serialize for ExactCount<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        exact_count(self.0, s)
    }
}
