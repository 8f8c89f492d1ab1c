//! Shaders and passes: the structure of Unity's `Shader { Pass { … } }`.

use std::collections::HashMap;

use num_bigint::BigUint;

use crate::diagnostic::{FileId, Span};
use crate::keywords::SetKind;
use crate::keywords::{Constraint, KeywordError, KeywordSet};
use crate::preprocess::tree::{Node, PassDecl, Pragma};

/// A shader: a named set of passes declared by one `#shader` file.
#[derive(Clone, Debug)]
pub struct Shader {
    /// Shader name (`#shader NAME`).
    pub name: String,
    /// Passes in file order.
    pub passes: Vec<Pass>,
    /// The shader file.
    pub file: FileId,
}

impl Shader {
    /// The pass with this name.
    pub fn pass(&self, name: &str) -> Option<&Pass> {
        self.passes.iter().find(|p| p.name == name)
    }
}

/// A pass with its variant counts (one entry of [`ShaderListing::passes`]).
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct PassListing<'l> {
    /// The pass.
    #[serde(flatten)]
    pub pass: &'l Pass,
    /// Size of the full space.
    #[serde(serialize_with = "crate::json::exact_count")]
    pub full_space: BigUint,
    /// Size of the space after `skip_variants`.
    #[serde(serialize_with = "crate::json::exact_count")]
    pub after_skip: BigUint,
    /// Size of the build set (for the materials given).
    #[serde(serialize_with = "crate::json::exact_count")]
    pub build_set: BigUint,
}

/// A shader with its passes and their counts (one entry of [`Listing::shaders`]).
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct ShaderListing<'l> {
    /// Shader name.
    pub name: &'l str,
    /// Path of the shader file.
    pub file: &'l str,
    /// Its passes, in file order.
    pub passes: Vec<PassListing<'l>>,
}

/// The shaders of a library with their passes, keyword sets and variant counts (what
/// `list --json` prints); see [`Library::listing`](crate::Library::listing).
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct Listing<'l> {
    /// Every shader, in library order.
    pub shaders: Vec<ShaderListing<'l>>,
}

/// One pass: its tags, keyword sets, pragmas and body.
///
/// Serialized (in `list --json`) as its declaration: `name`, `tags`, `keyword_sets`,
/// `skip_variants` and `exclude_renderers`.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Pass {
    /// Name of the shader the pass belongs to.
    #[serde(skip)]
    pub shader: String,
    /// Pass name (`#pass NAME`).
    pub name: String,
    /// `#tag KEY VALUE` pairs.
    pub tags: Vec<(String, String)>,
    /// Keyword sets in declaration order.
    #[serde(rename = "keyword_sets")]
    pub sets: Vec<KeywordSet>,
    /// `#pragma skip_variants` keywords.
    pub skip_variants: Vec<String>,
    /// `#pragma exclude_renderers` names, kept as metadata.
    pub exclude_renderers: Vec<String>,
    /// `#pragma require` / `#pragma exclude` constraints, one per pair of keywords, in order.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<Constraint>,
    /// Shader defs with a fixed value in every variant (declaration files' `constants`;
    /// none in this crate's own dialect, whose modules `#define` them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub constants: Vec<crate::declaration::Constant>,
    /// Keywords that set several defs (declaration files' `options`), each with its defs;
    /// any other keyword sets its own def ([`def_of`](crate::declaration::def_of)). See
    /// [`Pass::keyword_defs`].
    #[serde(skip_serializing_if = "std::collections::BTreeMap::is_empty")]
    pub options: std::collections::BTreeMap<String, Vec<crate::declaration::Constant>>,
    /// Where the pass is declared.
    #[serde(skip)]
    pub span: Span,
    #[serde(skip)]
    pub(crate) body: Vec<Node>,
    /// Module id of the shader file the pass's body belongs to.
    #[serde(skip)]
    pub(crate) module: usize,
    /// keyword → (set index, option index)
    #[serde(skip)]
    index: HashMap<String, (usize, usize)>,
    /// The devices the declaration file names for this pass (`profile`); empty: the tree's
    /// (see [`crate::Library::pass_profiles`]).
    #[serde(skip)]
    pub(crate) profiles: Vec<crate::validator::Profile>,
    /// The pipeline stage the pass composes, when its declaration splits it into stages
    /// (`stages`: the pass is then named `PASS/STAGE`, and the keywords whose defs Bevy's
    /// pipeline does not push to this stage are options that set no def). `None`: the whole
    /// pipeline from one module.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<crate::stage::PipelineStage>,
}

impl Pass {
    /// Builds a pass from its parsed declaration, checking Unity's keyword rules.
    pub(crate) fn new(
        shader: &str,
        module: usize,
        decl: PassDecl,
    ) -> Result<Pass, Vec<KeywordError>> {
        let mut errors = Vec::new();
        let mut sets: Vec<KeywordSet> = Vec::new();
        let mut index: HashMap<String, (usize, usize)> = HashMap::new();
        let mut first_span: HashMap<String, Span> = HashMap::new();
        let mut skip = Vec::new();
        let mut exclude = Vec::new();
        let mut constraint_decls = Vec::new();
        for pragma in &decl.pragmas {
            match pragma {
                Pragma::Keywords {
                    kind,
                    local,
                    names,
                    span,
                } => match KeywordSet::new(*kind, *local, names, *span) {
                    Ok(set) => {
                        let set_index = sets.len();
                        let spans: HashMap<&str, Span> =
                            names.iter().map(|(n, s)| (&**n, *s)).collect();
                        for (option, name) in set.options.iter().enumerate() {
                            let Some(name) = name else { continue };
                            let name_span = spans.get(name.as_str()).copied().unwrap_or(*span);
                            if let Some(first) = first_span.get(name) {
                                errors.push(KeywordError::InTwoSets {
                                    keyword: name.clone(),
                                    pass: decl.name.clone(),
                                    span: name_span,
                                    first: *first,
                                });
                            } else {
                                first_span.insert(name.clone(), name_span);
                                index.insert(name.clone(), (set_index, option));
                            }
                        }
                        sets.push(set);
                    }
                    Err(e) => errors.push(e),
                },
                Pragma::SkipVariants(names) => skip.extend(names.iter().cloned()),
                Pragma::ExcludeRenderers(names) => {
                    exclude.extend(names.iter().map(|n| n.to_string()))
                }
                Pragma::Constraint { kind, names, span } => {
                    constraint_decls.push((*kind, names.clone(), *span))
                }
            }
        }
        let constraints =
            crate::keywords::resolve_constraints(&decl.name, &constraint_decls, &index)
                .unwrap_or_else(|mut e| {
                    errors.append(&mut e);
                    Vec::new()
                });
        for (name, span) in &skip {
            if !index.contains_key(&**name) {
                errors.push(KeywordError::UnknownSkip {
                    keyword: name.to_string(),
                    pass: decl.name.clone(),
                    span: *span,
                });
            }
        }
        if !errors.is_empty() {
            return Err(errors);
        }
        let pass = Pass {
            shader: shader.to_string(),
            name: decl.name,
            tags: decl.tags,
            sets,
            skip_variants: skip.into_iter().map(|n| n.0.to_string()).collect(),
            exclude_renderers: exclude,
            constants: decl.constants,
            options: decl.options,
            span: decl.span,
            body: decl.body,
            module,
            index,
            constraints,
            profiles: decl.profiles,
            stage: decl.stage,
        };
        Ok(pass)
    }

    /// The shader defs of a variant with `keywords` on: the pass's constants, then each
    /// keyword's defs ([`Pass::keyword_defs`]). Later entries win when collected into a map.
    pub fn defs<'k>(
        &'k self,
        keywords: impl IntoIterator<Item = &'k str>,
    ) -> Vec<(&'k str, crate::declaration::DefValue)> {
        self.constants
            .iter()
            .map(|c| (c.name.as_str(), c.value))
            .chain(keywords.into_iter().flat_map(|k| self.keyword_defs(k)))
            .collect()
    }

    /// The defs one keyword sets: an option's defs (declaration files' `options`; none for a
    /// keyword whose defs the pipeline pushes to another [stage](Pass::stage) only), else the
    /// keyword's own def ([`def_of`](crate::declaration::def_of): `true`, or a valued
    /// keyword's value).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let pass = lib.pass("standard", "Deferred").unwrap();
    /// assert_eq!(
    ///     pass.keyword_defs("_NORMAL_MAP"),
    ///     [("_NORMAL_MAP", wgsl_variants::declaration::DefValue::Bool(true))]
    /// );
    /// ```
    pub fn keyword_defs<'k>(
        &'k self,
        keyword: &'k str,
    ) -> Vec<(&'k str, crate::declaration::DefValue)> {
        match self.options.get(keyword) {
            Some(defs) => defs.iter().map(|c| (c.name.as_str(), c.value)).collect(),
            None => vec![crate::declaration::def_of(keyword)],
        }
    }

    /// The module the pass composes, as an index into
    /// [`Library::module_paths`](crate::Library::module_paths): its shader file, or the entry
    /// module a declaration file names.
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let pass = lib.pass("standard", "Deferred").unwrap();
    /// assert_eq!(lib.module_paths()[pass.module()], "standard");
    /// ```
    pub fn module(&self) -> usize {
        self.module
    }

    /// The value of a tag, e.g. `tag("LightMode")`.
    pub fn tag(&self, key: &str) -> Option<&str> {
        self.tags.iter().find(|t| t.0 == key).map(|t| t.1.as_str())
    }

    /// Which set and option a keyword is, if the pass declares it.
    pub fn keyword(&self, name: &str) -> Option<(usize, usize)> {
        self.index.get(name).copied()
    }

    /// Every keyword the pass declares, in declaration order.
    pub fn keywords(&self) -> impl Iterator<Item = &str> {
        self.sets.iter().flat_map(KeywordSet::keywords)
    }

    /// Indices of the `multi_compile` sets.
    pub fn multi_compile_sets(&self) -> impl Iterator<Item = usize> + '_ {
        self.sets
            .iter()
            .enumerate()
            .filter(|s| s.1.kind == SetKind::MultiCompile)
            .map(|s| s.0)
    }

    /// Indices of the `shader_feature` sets.
    pub fn shader_feature_sets(&self) -> impl Iterator<Item = usize> + '_ {
        self.sets
            .iter()
            .enumerate()
            .filter(|s| s.1.kind == SetKind::ShaderFeature)
            .map(|s| s.0)
    }

    /// Whether an option is removed by `skip_variants`.
    pub fn is_skipped_option(&self, set: usize, option: usize) -> bool {
        self.sets[set].options[option]
            .as_ref()
            .is_some_and(|k| self.skip_variants.contains(k))
    }
}
