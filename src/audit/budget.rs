//! Variant budgets: a CI gate on the size of each pass's build set.
//!
//! A budget file is TOML. `default` applies to every pass not listed; keys of `[budgets]` are
//! `"shader/pass"` or `"shader"` (every pass of that shader); the most specific entry wins:
//!
//! ```toml
//! default = 100000
//!
//! [budgets]
//! "standard/Deferred" = 4000
//! "deferred_reflections" = 8
//! ```
//!
//! `--max-variants N` is a budget too: a pass passes when its build set fits both.

use std::collections::BTreeMap;
use std::path::Path;

use num_bigint::BigUint;
use serde::Deserialize;

use crate::data_file::{self, FileError, Format};
use crate::diagnostic::suggest;
use crate::library::Library;

use super::PassAudit;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    default: Option<u64>,
    #[serde(default)]
    budgets: BTreeMap<String, u64>,
}

/// Budgets read from a file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Budgets {
    /// The file, for messages.
    pub path: String,
    /// The budget of passes no entry names.
    pub default: Option<u64>,
    /// `"shader/pass"` or `"shader"` → budget.
    pub entries: BTreeMap<String, u64>,
}

/// A problem with a budget file.
#[derive(Debug, thiserror::Error)]
pub enum BudgetFileError {
    /// The file could not be read, or is not TOML of the expected shape.
    #[error(transparent)]
    File(#[from] FileError),
    /// A key names no shader or pass of the library.
    #[error(
        "budget file `{path}`: `{key}` names no {what} of the library{}",
        crate::diagnostic::hint(suggestion.as_deref())
    )]
    Unknown {
        /// The file.
        path: String,
        /// The key.
        key: String,
        /// "shader" or "pass".
        what: &'static str,
        /// The closest name.
        suggestion: Option<String>,
    },
}

/// The budget that applies to a pass, and where it comes from.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Limit {
    /// Most variants in the build set.
    pub limit: u64,
    /// Where the limit comes from, e.g. `--max-variants` or `budget.toml: "standard/Deferred"`.
    pub source: String,
}

/// The outcome of the gate for one pass.
///
/// Serialized as `limit`, `source` and `exceeded`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct Verdict {
    /// The tightest budget that applies.
    #[serde(flatten)]
    pub limit: Limit,
    /// The build set's size.
    #[serde(skip)]
    pub build_set: BigUint,
    /// Whether the build set is over the budget.
    pub exceeded: bool,
    /// `shader/pass: build set of N variants exceeds its budget of M (source)`, or the same
    /// with "fits".
    #[serde(skip)]
    pub message: String,
}

impl Budgets {
    /// Reads a budget file.
    pub fn load(path: &Path) -> Result<Budgets, BudgetFileError> {
        let text = data_file::read(path, "budget")?;
        Budgets::parse(&text, &path.display().to_string())
    }

    /// Parses a budget file's text; `path` is used in messages.
    ///
    /// ```
    /// use wgsl_variants::audit::budget::Budgets;
    /// let b = Budgets::parse("default = 10\n[budgets]\n\"standard/Deferred\" = 4000\n", "b.toml").unwrap();
    /// assert_eq!(b.limit_for("standard", "Deferred").unwrap().limit, 4000);
    /// assert_eq!(b.limit_for("standard", "ForwardBase").unwrap().limit, 10);
    /// ```
    pub fn parse(text: &str, path: &str) -> Result<Budgets, BudgetFileError> {
        let file: File = data_file::parse(text, Format::Toml, path)?;
        Ok(Budgets {
            path: path.to_string(),
            default: file.default,
            entries: file.budgets,
        })
    }

    /// Checks that every key names a shader or pass of `lib`.
    pub fn check(&self, lib: &Library) -> Result<(), BudgetFileError> {
        for key in self.entries.keys() {
            let unknown = |what, suggestion| BudgetFileError::Unknown {
                path: self.path.clone(),
                key: key.clone(),
                what,
                suggestion,
            };
            match key.split_once('/') {
                None => {
                    if lib.shader(key).is_err() {
                        let names = lib.shaders().iter().map(|s| s.name.as_str());
                        return Err(unknown("shader", suggest(key, names)));
                    }
                }
                Some((shader, pass)) => {
                    if lib.pass(shader, pass).is_err() {
                        let names: Vec<String> = lib
                            .passes()
                            .map(|p| format!("{}/{}", p.shader, p.name))
                            .collect();
                        return Err(unknown(
                            "pass",
                            suggest(key, names.iter().map(String::as_str)),
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// The file's budget for a pass: its own entry, else its shader's, else the default.
    pub fn limit_for(&self, shader: &str, pass: &str) -> Option<Limit> {
        let own = format!("{shader}/{pass}");
        let entry = |key: &str| {
            self.entries.get(key).map(|&limit| Limit {
                limit,
                source: format!("{}: \"{key}\"", self.path),
            })
        };
        entry(&own).or_else(|| entry(shader)).or_else(|| {
            self.default.map(|limit| Limit {
                limit,
                source: format!("{}: default", self.path),
            })
        })
    }
}

/// The gate for one pass: the tightest of `max_variants` and the file's budget.
pub(crate) fn verdict(
    audit: &PassAudit,
    max_variants: Option<u64>,
    budgets: Option<&Budgets>,
) -> Option<Verdict> {
    let mut limits: Vec<Limit> = Vec::new();
    if let Some(b) = budgets.and_then(|b| b.limit_for(&audit.shader, &audit.pass)) {
        limits.push(b);
    }
    if let Some(n) = max_variants {
        limits.push(Limit {
            limit: n,
            source: "--max-variants".to_string(),
        });
    }
    let limit = limits.into_iter().min_by_key(|l| l.limit)?;
    let exceeded = audit.build_set > BigUint::from(limit.limit);
    let message = format!(
        "{}/{}: build set of {} variants {} its budget of {} ({})",
        audit.shader,
        audit.pass,
        audit.build_set,
        if exceeded { "exceeds" } else { "fits" },
        limit.limit,
        limit.source
    );
    Some(Verdict {
        limit,
        build_set: audit.build_set.clone(),
        exceeded,
        message,
    })
}
