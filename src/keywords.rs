//! Keyword sets with Unity's semantics.
//!
//! A set is one `#pragma multi_compile …` or `#pragma shader_feature …` line; exactly one of its
//! options is on in a variant. An option written only with underscores (`_`, `__`) means "none
//! of this set" and defines nothing. `shader_feature K` with a single name means `_ K`;
//! `multi_compile K` with a single name is a one-option set (K always on), as in Unity.

use std::fmt;
use std::str::FromStr;

use crate::diagnostic::{Diagnostic, Span};

/// Which Unity keyword pragma declared a set.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum SetKind {
    /// `#pragma multi_compile`: every option is built.
    MultiCompile,
    /// `#pragma shader_feature`: only options some material uses are built.
    ShaderFeature,
}

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
    /// A set with more options than a variant can index (65,535): its count and its
    /// variants would otherwise be silently wrong.
    #[error("a keyword set has {options} options, past the limit of {}", u16::MAX)]
    TooManyOptions {
        /// The options the set would have.
        options: usize,
        /// The set's pragma.
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
    /// `#pragma require` or `#pragma exclude` names a keyword no set of the pass declares.
    #[error("`{constraint}` names `{keyword}`, which no keyword set of pass `{pass}` declares")]
    UnknownConstraintKeyword {
        /// The constraint as written, e.g. `require A B`.
        constraint: String,
        /// The keyword.
        keyword: String,
        /// The pass.
        pass: String,
        /// Where the keyword is written.
        span: Span,
    },
    /// The constraints of a pass leave a keyword they name never on (e.g. `require A B`
    /// with `exclude A B`, or `require A B` with A and B in one set).
    #[error(
        "contradictory constraints in pass `{pass}`: with `{constraint}`, keyword `{keyword}` is on in no variant"
    )]
    Contradictory {
        /// The first constraint that names the keyword.
        constraint: String,
        /// The keyword that can never be on.
        keyword: String,
        /// The pass.
        pass: String,
        /// Where the constraint is written.
        span: Span,
    },
    /// Constraints chain so many keyword sets together that their combinations are too many
    /// to list.
    #[error(
        "the constraints of pass `{pass}` couple keyword sets with {combinations} combinations (at most {limit}); split them"
    )]
    TooCoupled {
        /// The pass.
        pass: String,
        /// Product of the sizes of the coupled sets.
        combinations: u128,
        /// The limit.
        limit: u128,
        /// Where one of the constraints is written.
        span: Span,
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
            | KeywordError::TooManyOptions { span, .. }
            | KeywordError::TwoPlaceholders { span, .. }
            | KeywordError::UnknownSkip { span, .. }
            | KeywordError::UnknownConstraintKeyword { span, .. }
            | KeywordError::TooCoupled { span, .. } => {
                Diagnostic::new(self.to_string()).at(*span, "here")
            }
            KeywordError::Contradictory { span, .. } => Diagnostic::new(self.to_string())
                .at(*span, "this constraint")
                .note("a keyword that is never on builds nothing: drop it or the constraint"),
            KeywordError::InTwoSets { span, first, .. } => Diagnostic::new(self.to_string())
                .at(*span, "declared again here")
                .also(*first, "first declared here")
                .note(
                    "a keyword belongs to one set: exactly one option of a set is on in a variant",
                ),
        }
    }
}

/// The two kinds of keyword constraint a pass may declare.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ConstraintKind {
    /// `#pragma require A B`: a variant with A on has B on (`require A B C` with B and C
    /// options of one set: one of them on).
    Require,
    /// `#pragma exclude A B`: no variant has both A and B on.
    Exclude,
}

/// One keyword constraint of a pass, as declared by `#pragma require A B C` (A requires B, and
/// A requires C; or, where B and C are options of one set, A requires one of them) or
/// `#pragma exclude A B C` (no two of A, B, C together). Unity users write these rules as
/// stripping code; here the full space, the build set, the covering set and the audit all
/// honour them.
///
/// ```
/// use wgsl_variants::{Library, Space};
/// let lib = Library::from_sources([(
///     "s.wgsl",
///     "#shader s\n#pass P\n#pragma shader_feature _NORMAL_MAP\n\
///      #pragma shader_feature _DETAIL_NORMAL_MAP\n\
///      #pragma require _DETAIL_NORMAL_MAP _NORMAL_MAP\n#endpass",
/// )])
/// .unwrap();
/// let pass = lib.pass("s", "P").unwrap();
/// assert_eq!(pass.constraints[0].to_string(), "require _DETAIL_NORMAL_MAP _NORMAL_MAP");
/// // Of the four variants, detail without the normal map is gone.
/// assert_eq!(Space::full(pass).count(), 3u32.into());
/// ```
///
/// Options of one set named after the first keyword are alternatives: soft shadows need one
/// of the shadow modes, whichever it is.
///
/// ```
/// use wgsl_variants::{Library, Space};
/// let lib = Library::from_sources([(
///     "s.wgsl",
///     "#shader s\n#pass P\n#pragma multi_compile _ SHADOWS CASCADES\n\
///      #pragma multi_compile _ SOFT\n#pragma require SOFT SHADOWS CASCADES\n#endpass",
/// )])
/// .unwrap();
/// let pass = lib.pass("s", "P").unwrap();
/// assert_eq!(pass.constraints.len(), 1);
/// assert_eq!(pass.constraints[0].to_string(), "require SOFT SHADOWS CASCADES");
/// // Of the six variants, soft without a shadow mode is gone.
/// assert_eq!(Space::full(pass).count(), 5u32.into());
/// ```
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Constraint {
    /// `require` or `exclude`.
    pub kind: ConstraintKind,
    /// The keywords: for `require`, the first needs one of the others (options of one set,
    /// usually just one); for `exclude`, the two that never meet.
    pub keywords: Vec<String>,
    /// The pragma's location.
    #[serde(skip)]
    pub span: Span,
    /// (set, option) of each keyword.
    #[serde(skip)]
    pub(crate) at: Vec<(usize, usize)>,
}

impl Constraint {
    /// The keyword sets the constraint involves (one or two: a requirement's alternatives
    /// share one set).
    pub fn sets(&self) -> [usize; 2] {
        [self.at[0].0, self.at[1].0]
    }

    /// Whether a variant (one option per set of the pass) satisfies the constraint.
    pub fn holds(&self, options: &[u16]) -> bool {
        let on = |(set, option): (usize, usize)| options[set] as usize == option;
        match self.kind {
            ConstraintKind::Require => !on(self.at[0]) || self.at[1..].iter().any(|&a| on(a)),
            ConstraintKind::Exclude => !(on(self.at[0]) && on(self.at[1])),
        }
    }
}

impl fmt::Display for Constraint {
    /// As written in a pragma, e.g. `require _DETAIL_NORMAL_MAP _NORMAL_MAP`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let kind = match self.kind {
            ConstraintKind::Require => "require",
            ConstraintKind::Exclude => "exclude",
        };
        write!(f, "{kind} {}", self.keywords.join(" "))
    }
}

/// A `require`/`exclude` pragma as parsed: its kind, names and span.
pub(crate) type ConstraintDecl = (ConstraintKind, Vec<(Box<str>, Span)>, Span);

/// Resolves constraint pragmas against a pass's keywords (`index`: keyword → (set, option)):
/// `require A B C` is A→B and A→C, or one A→(B or C) where B and C share a set (each set
/// named after A is one requirement, its options alternatives); `exclude A B C` is every pair
/// of A, B, C.
pub(crate) fn resolve_constraints(
    pass: &str,
    decls: &[ConstraintDecl],
    index: &std::collections::HashMap<String, (usize, usize)>,
) -> Result<Vec<Constraint>, Vec<KeywordError>> {
    let mut errors = Vec::new();
    let mut out = Vec::new();
    for (kind, names, span) in decls {
        let written = format!(
            "{} {}",
            match kind {
                ConstraintKind::Require => "require",
                ConstraintKind::Exclude => "exclude",
            },
            names.iter().map(|n| &*n.0).collect::<Vec<_>>().join(" ")
        );
        let mut at = Vec::new();
        for (name, name_span) in names {
            match index.get(&**name) {
                Some(&place) => at.push((name.to_string(), place)),
                None => errors.push(KeywordError::UnknownConstraintKeyword {
                    constraint: written.clone(),
                    keyword: name.to_string(),
                    pass: pass.to_string(),
                    span: *name_span,
                }),
            }
        }
        if at.len() != names.len() {
            continue;
        }
        // Each constraint as indices into `at`: the first keyword, then its partners.
        let groups: Vec<Vec<usize>> = match kind {
            ConstraintKind::Require => {
                let mut groups: Vec<Vec<usize>> = Vec::new();
                for j in 1..at.len() {
                    let set = at[j].1.0;
                    match groups.iter_mut().find(|g| at[g[1]].1.0 == set) {
                        Some(g) => g.push(j),
                        None => groups.push(vec![0, j]),
                    }
                }
                groups
            }
            ConstraintKind::Exclude => (0..at.len())
                .flat_map(|i| (i + 1..at.len()).map(move |j| vec![i, j]))
                .collect(),
        };
        out.extend(groups.into_iter().map(|g| Constraint {
            kind: *kind,
            keywords: g.iter().map(|&i| at[i].0.clone()).collect(),
            span: *span,
            at: g.iter().map(|&i| at[i].1).collect(),
        }));
    }
    if errors.is_empty() {
        Ok(out)
    } else {
        Err(errors)
    }
}

/// Whether a name is a "none" placeholder: made only of underscores.
pub(crate) fn is_placeholder(name: &str) -> bool {
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
        // Linear in the set's size: sets of many thousands of options are refused or built at
        // once, not one quadratic scan at a time.
        let mut seen: std::collections::HashSet<&str> =
            std::collections::HashSet::with_capacity(names.len());
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
                if !seen.insert(name) {
                    return Err(KeywordError::DuplicateInSet {
                        keyword: name.to_string(),
                        span: *name_span,
                    });
                }
                options.push(Some(name.to_string()));
            }
        }
        // A variant holds one option index per set in 16 bits.
        if options.len() > usize::from(u16::MAX) {
            return Err(KeywordError::TooManyOptions {
                options: options.len(),
                span,
            });
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

/// The value of a shader def, as naga_oil types it (`ShaderDefValue`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DefValue {
    /// `true` / `false`.
    Bool(bool),
    /// A signed integer (a plain TOML integer).
    Int(i32),
    /// An unsigned integer (`{ uint = N }`).
    UInt(u32),
}

impl DefValue {
    /// The value the preprocessor's static analysis compares: booleans are 0 and 1.
    pub fn as_i64(self) -> i64 {
        match self {
            DefValue::Bool(b) => i64::from(b),
            DefValue::Int(i) => i64::from(i),
            DefValue::UInt(u) => i64::from(u),
        }
    }
}

impl std::fmt::Display for DefValue {
    /// As a valued keyword writes it (and naga_oil substitutes it): `true`, `-3`, `4u`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DefValue::Bool(b) => write!(f, "{b}"),
            DefValue::Int(i) => write!(f, "{i}"),
            DefValue::UInt(u) => write!(f, "{u}u"),
        }
    }
}

#[cfg(feature = "naga-oil")]
impl DefValue {
    /// naga_oil's type for the value (`ShaderDefValue`), as naga_oil receives a variant's defs.
    ///
    /// ```
    /// use wgsl_variants::declaration::DefValue;
    /// assert_eq!(DefValue::UInt(4).to_naga_oil(), naga_oil::compose::ShaderDefValue::UInt(4));
    /// ```
    pub fn to_naga_oil(self) -> naga_oil::compose::ShaderDefValue {
        use naga_oil::compose::ShaderDefValue;
        match self {
            DefValue::Bool(b) => ShaderDefValue::Bool(b),
            DefValue::Int(i) => ShaderDefValue::Int(i),
            DefValue::UInt(u) => ShaderDefValue::UInt(u),
        }
    }
}

/// The def a keyword sets: a keyword of a valued set, `NAME=VALUE` (`true`, `-3`, `4u`), sets
/// `NAME` to that value; any other keyword sets itself to `true`.
///
/// ```
/// use wgsl_variants::keywords::{DefValue, def_of};
/// assert_eq!(def_of("MAX_CASCADES=4u"), ("MAX_CASCADES", DefValue::UInt(4)));
/// assert_eq!(def_of("TAPS=-8"), ("TAPS", DefValue::Int(-8)));
/// assert_eq!(def_of("SKINNED"), ("SKINNED", DefValue::Bool(true)));
/// ```
pub fn def_of(keyword: &str) -> (&str, DefValue) {
    let valued = keyword.split_once('=').and_then(|(name, v)| {
        let value = match v {
            "true" => DefValue::Bool(true),
            "false" => DefValue::Bool(false),
            v => match v.strip_suffix('u') {
                Some(u) => DefValue::UInt(u32::from_str(u).ok()?),
                None => DefValue::Int(i32::from_str(v).ok()?),
            },
        };
        Some((name, value))
    });
    valued.unwrap_or((keyword, DefValue::Bool(true)))
}

/// A shader def with a fixed value in every variant of a pass.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Constant {
    /// The def's name.
    pub name: String,
    /// Its value.
    pub value: DefValue,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn placeholders() {
        assert!(is_placeholder("_") && is_placeholder("__"));
        assert!(!is_placeholder("_NORMAL_MAP"));
    }

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
