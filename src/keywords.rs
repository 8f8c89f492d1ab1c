//! Keyword sets with Unity's semantics.
//!
//! A set is one `#pragma multi_compile …` or `#pragma shader_feature …` line; exactly one of its
//! options is on in a variant. An option written only with underscores (`_`, `__`) means "none
//! of this set" and defines nothing. `shader_feature K` with a single name means `_ K`;
//! `multi_compile K` with a single name is a one-option set (K always on), as in Unity.

use std::fmt;

use crate::diagnostic::{Diagnostic, Span};
pub use crate::preprocess::tree::SetKind;

/// One keyword set of a pass (serialized as `kind`, `local` and `options`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct KeywordSet {
    /// `multi_compile` or `shader_feature`.
    pub kind: SetKind,
    /// Declared with the `_local` suffix.
    pub local: bool,
    /// The options in declaration order; `None` is the "none of this set" placeholder.
    pub options: Vec<Option<String>>,
    /// The pragma's location.
    #[serde(skip)]
    pub span: Span,
}

/// A problem in the keyword declarations of a pass.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum KeywordError {
    /// The same keyword twice in one set.
    #[error("keyword `{keyword}` appears twice in one set")]
    DuplicateInSet {
        /// The keyword.
        keyword: String,
        /// The second occurrence.
        span: Span,
    },
    /// Two placeholders (`_`, `__`) in one set would build the same variant twice.
    #[error("a keyword set has two \"none\" placeholders (`{placeholder}`)")]
    TwoPlaceholders {
        /// The second placeholder as written.
        placeholder: String,
        /// Where.
        span: Span,
    },
    /// One keyword declared in two sets of the same pass.
    #[error("keyword `{keyword}` is declared in two keyword sets of pass `{pass}`")]
    InTwoSets {
        /// The keyword.
        keyword: String,
        /// The pass.
        pass: String,
        /// The second declaration.
        span: Span,
        /// The first declaration.
        first: Span,
    },
    /// `#pragma skip_variants` names a keyword no set of the pass declares.
    #[error("`skip_variants` names `{keyword}`, which no keyword set of pass `{pass}` declares")]
    UnknownSkip {
        /// The keyword.
        keyword: String,
        /// The pass.
        pass: String,
        /// Where.
        span: Span,
    },
}

impl KeywordError {
    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        match self {
            KeywordError::DuplicateInSet { span, .. }
            | KeywordError::TwoPlaceholders { span, .. }
            | KeywordError::UnknownSkip { span, .. } => {
                Diagnostic::new(self.to_string()).at(*span, "here")
            }
            KeywordError::InTwoSets { span, first, .. } => Diagnostic::new(self.to_string())
                .at(*span, "declared again here")
                .also(*first, "first declared here")
                .note(
                    "a keyword belongs to one set: exactly one option of a set is on in a variant",
                ),
        }
    }
}

/// Whether a name is a "none" placeholder: made only of underscores.
///
/// ```
/// use wgsl_variants::keywords::is_placeholder;
/// assert!(is_placeholder("_") && is_placeholder("__"));
/// assert!(!is_placeholder("_NORMAL_MAP"));
/// ```
pub fn is_placeholder(name: &str) -> bool {
    !name.is_empty() && name.bytes().all(|b| b == b'_')
}

impl KeywordSet {
    /// Builds a set from a pragma's names with Unity's rules.
    pub fn new(
        kind: SetKind,
        local: bool,
        names: &[(Box<str>, Span)],
        span: Span,
    ) -> Result<KeywordSet, KeywordError> {
        let mut options: Vec<Option<String>> = Vec::with_capacity(names.len() + 1);
        if kind == SetKind::ShaderFeature && names.len() == 1 && !is_placeholder(&names[0].0) {
            options.push(None);
        }
        for (name, name_span) in names {
            if is_placeholder(name) {
                if options.contains(&None) {
                    return Err(KeywordError::TwoPlaceholders {
                        placeholder: name.to_string(),
                        span: *name_span,
                    });
                }
                options.push(None);
            } else {
                if options.iter().any(|o| o.as_deref() == Some(&**name)) {
                    return Err(KeywordError::DuplicateInSet {
                        keyword: name.to_string(),
                        span: *name_span,
                    });
                }
                options.push(Some(name.to_string()));
            }
        }
        Ok(KeywordSet {
            kind,
            local,
            options,
            span,
        })
    }

    /// Number of options (this set's factor in the variant space).
    pub fn len(&self) -> usize {
        self.options.len()
    }

    /// Whether the set has no options (never true for a parsed set).
    pub fn is_empty(&self) -> bool {
        self.options.is_empty()
    }

    /// Index of the "none" option, if the set has one.
    pub fn none_index(&self) -> Option<usize> {
        self.options.iter().position(Option::is_none)
    }

    /// The keywords of the set (placeholders left out).
    pub fn keywords(&self) -> impl Iterator<Item = &str> {
        self.options.iter().filter_map(|o| o.as_deref())
    }
}

impl fmt::Display for KeywordSet {
    /// As written in a pragma, e.g. `shader_feature _ _NORMAL_MAP`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match (self.kind, self.local) {
            (SetKind::MultiCompile, false) => "multi_compile",
            (SetKind::MultiCompile, true) => "multi_compile_local",
            (SetKind::ShaderFeature, false) => "shader_feature",
            (SetKind::ShaderFeature, true) => "shader_feature_local",
        };
        write!(f, "{kind}")?;
        for option in &self.options {
            write!(f, " {}", option.as_deref().unwrap_or("_"))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<(Box<str>, Span)> {
        list.iter()
            .map(|n| (Box::from(*n), Span::new(0, 0..1)))
            .collect()
    }

    fn set(kind: SetKind, list: &[&str]) -> Result<KeywordSet, KeywordError> {
        KeywordSet::new(kind, false, &names(list), Span::new(0, 0..1))
    }

    #[test]
    fn single_shader_feature_gets_a_none_option() {
        let s = set(SetKind::ShaderFeature, &["_NORMAL_MAP"]).unwrap();
        assert_eq!(s.options, vec![None, Some("_NORMAL_MAP".into())]);
    }

    #[test]
    fn single_multi_compile_is_always_on() {
        let s = set(SetKind::MultiCompile, &["A"]).unwrap();
        assert_eq!(s.options, vec![Some("A".into())]);
    }

    #[test]
    fn placeholders_mean_none() {
        let s = set(SetKind::ShaderFeature, &["__", "A", "B"]).unwrap();
        assert_eq!(s.options, vec![None, Some("A".into()), Some("B".into())]);
        assert_eq!(s.to_string(), "shader_feature _ A B");
        assert!(matches!(
            set(SetKind::MultiCompile, &["_", "__"]),
            Err(KeywordError::TwoPlaceholders { .. })
        ));
        assert!(matches!(
            set(SetKind::MultiCompile, &["A", "A"]),
            Err(KeywordError::DuplicateInSet { .. })
        ));
    }
}
