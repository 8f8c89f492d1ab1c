//! Putting shards back together: the outputs of `validate`, `emit --out` and `check-gpu` run
//! as `--shard K/N` on N machines, merged into exactly what one machine would have produced.
//!
//! Every output records a [`fingerprint`] of what it was made from (the library's sources,
//! the selection and options, this crate's and naga's versions) and, when sharded, its shard
//! `K/N`. [`order_shards`] checks that the inputs are shards `1..N` of the same fingerprint,
//! each once; [`validate::merge_reports`] and [`manifest::merge_folders`] do the merging.
//!
//! ```
//! use wgsl_variants::merge::{ShardInfo, order_shards};
//!
//! let info = |k: u64| ShardInfo {
//!     name: format!("shard-{k}.json"),
//!     shard: Some(format!("{k}/2").parse().unwrap()),
//!     fingerprint: "f".into(),
//! };
//! assert_eq!(order_shards(&[info(2), info(1)]).unwrap(), [1, 0]);
//! let err = order_shards(&[info(1), info(1)]).unwrap_err();
//! assert!(err.to_string().contains("shard-1.json"));
//! ```

pub mod manifest;
pub mod validate;

use crate::variants::Shard;

pub use crate::fingerprint::fingerprint;
pub use crate::variants::shard_text;

/// Why shard outputs could not be merged. Every variant names the shard input at fault.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MergeError {
    /// Nothing to merge.
    #[error("no shard outputs given")]
    Empty,
    /// An input could not be read.
    #[error("cannot read `{shard}`: {source}")]
    Read {
        /// The input (file or folder).
        shard: String,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// An input is not JSON.
    #[error("cannot read `{shard}`: not JSON: {source}")]
    NotJson {
        /// The input.
        shard: String,
        /// The JSON parser's error.
        #[source]
        source: serde_json::Error,
    },
    /// An input is not the kind of output being merged.
    #[error("`{shard}` is not {expected}: {message}")]
    Kind {
        /// The input.
        shard: String,
        /// What was expected (`a validate --json report`, ...).
        expected: &'static str,
        /// What is wrong with it.
        message: String,
    },
    /// An input records no shard (it is a whole run).
    #[error("`{shard}` is not a shard: it records no `shard` (run with --shard K/N)")]
    NotSharded {
        /// The input.
        shard: String,
    },
    /// An input is a shard of a different count.
    #[error(
        "`{shard}` is shard {found}, but `{first}` is shard {expected_of}: every shard must be K/{count}"
    )]
    Count {
        /// The input.
        shard: String,
        /// Its shard.
        found: Shard,
        /// The first input.
        first: String,
        /// The first input's shard.
        expected_of: Shard,
        /// The first input's shard count.
        count: u64,
    },
    /// Two inputs are the same shard.
    #[error("`{shard}` repeats shard {number}, already given by `{first}`")]
    Repeated {
        /// The second input with this shard.
        shard: String,
        /// The first input with it.
        first: String,
        /// The shard, `K/N`.
        number: Shard,
    },
    /// Shards are missing.
    #[error("missing shard(s) {} of {count}: give all {count} shard outputs", list(.missing))]
    Missing {
        /// The missing shard numbers, 1-based.
        missing: Vec<u64>,
        /// N.
        count: u64,
    },
    /// An input was made from another library, selection, options or version.
    #[error(
        "`{shard}` has fingerprint {found}, but `{first}` has {expected}: it was made from another library, selection, options or version of wgsl-variants/naga"
    )]
    Fingerprint {
        /// The input.
        shard: String,
        /// Its fingerprint.
        found: String,
        /// The first input.
        first: String,
        /// The first input's fingerprint.
        expected: String,
    },
    /// Inputs agree on their fingerprint but not on their contents.
    #[error("`{shard}` does not fit the other shards: {message}")]
    Mismatch {
        /// The input.
        shard: String,
        /// What differs.
        message: String,
    },
    /// The merged output could not be written.
    #[error("cannot write `{path}`: {source}")]
    Write {
        /// The path (`<stdout>` for a report).
        path: String,
        /// The OS error (or serde_json's, as an `io::Error` that displays the same).
        #[source]
        source: std::io::Error,
    },
}

fn list(numbers: &[u64]) -> String {
    numbers
        .iter()
        .map(u64::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// What a shard output says about itself.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ShardInfo {
    /// The input's name in errors (its path).
    pub name: String,
    /// Its shard, if it is one.
    pub shard: Option<Shard>,
    /// Its fingerprint.
    pub fingerprint: String,
}

/// Checks that `inputs` are shards `1..N` of one fingerprint, each given once, and returns
/// the input indices in shard order.
pub fn order_shards(inputs: &[ShardInfo]) -> Result<Vec<usize>, MergeError> {
    let first = inputs.first().ok_or(MergeError::Empty)?;
    let first_shard = first.shard.ok_or_else(|| MergeError::NotSharded {
        shard: first.name.clone(),
    })?;
    let count = first_shard.count;
    let mut slots: std::collections::BTreeMap<u64, usize> = std::collections::BTreeMap::new();
    for (i, input) in inputs.iter().enumerate() {
        let shard = input.shard.ok_or_else(|| MergeError::NotSharded {
            shard: input.name.clone(),
        })?;
        if shard.count != count {
            return Err(MergeError::Count {
                shard: input.name.clone(),
                found: shard,
                first: first.name.clone(),
                expected_of: first_shard,
                count,
            });
        }
        if input.fingerprint != first.fingerprint {
            return Err(MergeError::Fingerprint {
                shard: input.name.clone(),
                found: input.fingerprint.clone(),
                first: first.name.clone(),
                expected: first.fingerprint.clone(),
            });
        }
        if let Some(&j) = slots.get(&shard.index) {
            return Err(MergeError::Repeated {
                shard: input.name.clone(),
                first: inputs[j].name.clone(),
                number: shard,
            });
        }
        slots.insert(shard.index, i);
    }
    if slots.len() as u64 != count {
        // At most 100 listed: N may be huge.
        let missing: Vec<u64> = (0..count)
            .filter(|k| !slots.contains_key(k))
            .map(|k| k + 1)
            .take(100)
            .collect();
        return Err(MergeError::Missing { missing, count });
    }
    Ok(slots.into_values().collect())
}

/// Parses the optional `K/N` field of input `name`.
pub fn parse_shard(name: &str, text: Option<&str>) -> Result<Option<Shard>, MergeError> {
    text.map(|t| {
        t.parse()
            .map_err(|e: crate::variants::ShardError| MergeError::Mismatch {
                shard: name.to_string(),
                message: e.to_string(),
            })
    })
    .transpose()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn info(name: &str, shard: &str, fingerprint: &str) -> ShardInfo {
        ShardInfo {
            name: name.into(),
            shard: Some(shard.parse().unwrap()),
            fingerprint: fingerprint.into(),
        }
    }

    #[test]
    fn shards_in_order_whatever_the_input_order() {
        let inputs = [
            info("c", "3/3", "f"),
            info("a", "1/3", "f"),
            info("b", "2/3", "f"),
        ];
        assert_eq!(order_shards(&inputs).unwrap(), [1, 2, 0]);
    }

    #[test]
    fn each_mismatch_names_the_shard() {
        let missing = order_shards(&[info("a", "1/3", "f"), info("c", "3/3", "f")]).unwrap_err();
        assert!(matches!(&missing, MergeError::Missing { missing, count: 3 } if missing == &[2]));
        let repeated = order_shards(&[info("a", "1/2", "f"), info("b", "1/2", "f")]).unwrap_err();
        assert!(
            matches!(&repeated, MergeError::Repeated { shard, first, .. } if shard == "b" && first == "a")
        );
        let other = order_shards(&[info("a", "1/2", "f"), info("b", "2/2", "g")]).unwrap_err();
        assert!(matches!(&other, MergeError::Fingerprint { shard, .. } if shard == "b"));
        let count = order_shards(&[info("a", "1/2", "f"), info("b", "2/3", "f")]).unwrap_err();
        assert!(count.to_string().contains("`b` is shard 2/3"), "{count}");
        let whole = ShardInfo {
            shard: None,
            ..info("w", "1/1", "f")
        };
        assert!(
            matches!(order_shards(&[whole]), Err(MergeError::NotSharded { shard }) if shard == "w")
        );
        assert!(matches!(order_shards(&[]), Err(MergeError::Empty)));
        // A huge N with few inputs is reported missing, not allocated.
        let huge = order_shards(&[info("a", "1/18446744073709551615", "f")]).unwrap_err();
        assert!(matches!(huge, MergeError::Missing { .. }));
    }
}
