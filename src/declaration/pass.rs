//! A `[[shader.pass]]` of the declaration file, with the keyword blocks it uses and the
//! options its keywords name, turned into the pass declaration the `#pass` parser makes.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use super::{Constant, DeclarationError, DefValue, ValueToml, constants, value_of};
use crate::diagnostic::{FileId, Span};
use crate::keywords::{ConstraintKind, SetKind};
use crate::preprocess::tree::{PassDecl, Pragma};

pub(super) type Names = Spanned<Vec<Spanned<String>>>;

/// A keyword that sets several defs: a list of def names (each `true`) or a table of defs with
/// their values, as `[constants]` writes them.
#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum OptionToml {
    Names(Vec<String>),
    Defs(BTreeMap<String, ValueToml>),
}

#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum ValuesToml {
    Bools(Vec<bool>),
    Ints(Vec<i64>),
    UInts { uint: Vec<i64> },
}

pub(super) type OptionsToml = BTreeMap<Spanned<String>, Spanned<OptionToml>>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PassToml {
    name: Spanned<String>,
    entry: Option<Spanned<String>>,
    profile: Option<Spanned<super::profile::ProfileToml>>,
    #[serde(default)]
    tags: BTreeMap<String, String>,
    #[serde(default, rename = "use")]
    pub(super) uses: Vec<Spanned<String>>,
    #[serde(default)]
    pub(super) stages: StagesToml,
    #[serde(default)]
    multi_compile: Vec<Names>,
    #[serde(default)]
    multi_compile_local: Vec<Names>,
    #[serde(default)]
    shader_feature: Vec<Names>,
    #[serde(default)]
    shader_feature_local: Vec<Names>,
    #[serde(default)]
    require: Vec<Names>,
    #[serde(default)]
    exclude: Vec<Names>,
    #[serde(default)]
    skip_variants: Vec<Spanned<String>>,
    #[serde(default)]
    pub(super) constants: BTreeMap<Spanned<String>, Spanned<ValueToml>>,
    #[serde(default)]
    values: BTreeMap<Spanned<String>, Spanned<ValuesToml>>,
    #[serde(default)]
    options: OptionsToml,
}

/// A `[shader.pass.stages.NAME]` table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct StageToml {
    /// The stage's entry module (default: the pass's).
    pub(super) entry: Option<Spanned<String>>,
    /// Keywords whose defs reach the stage (a valued set by its def name).
    pub(super) keywords: Option<Vec<Spanned<String>>>,
    /// Blocks (among those the pass uses) whose keywords' defs reach the stage.
    #[serde(default, rename = "use")]
    pub(super) uses: Vec<Spanned<String>>,
}

/// The `stages` table of a pass, by stage name as written.
pub(super) type StagesToml = BTreeMap<Spanned<String>, StageToml>;

/// A `[blocks.NAME]` table: keyword sets, constraints and options that passes share with
/// `use = ["NAME"]` (one tonemapping block for every pass that tonemaps).
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct BlockToml {
    /// The stages the block's keywords' defs reach in a pass split into stages (default:
    /// every stage): Bevy's material defs go to the fragment stage only.
    pub(super) stages: Option<Spanned<Vec<Spanned<String>>>>,
    #[serde(default)]
    multi_compile: Vec<Names>,
    #[serde(default)]
    multi_compile_local: Vec<Names>,
    #[serde(default)]
    shader_feature: Vec<Names>,
    #[serde(default)]
    shader_feature_local: Vec<Names>,
    #[serde(default)]
    require: Vec<Names>,
    #[serde(default)]
    exclude: Vec<Names>,
    #[serde(default)]
    values: BTreeMap<Spanned<String>, Spanned<ValuesToml>>,
    #[serde(default)]
    options: OptionsToml,
}

/// What a pass and a block both declare.
struct Sets<'t> {
    multi_compile: &'t [Names],
    multi_compile_local: &'t [Names],
    values: &'t BTreeMap<Spanned<String>, Spanned<ValuesToml>>,
    shader_feature: &'t [Names],
    shader_feature_local: &'t [Names],
    require: &'t [Names],
    exclude: &'t [Names],
    options: &'t OptionsToml,
}

impl PassToml {
    fn sets(&self) -> Sets<'_> {
        Sets {
            multi_compile: &self.multi_compile,
            multi_compile_local: &self.multi_compile_local,
            values: &self.values,
            shader_feature: &self.shader_feature,
            shader_feature_local: &self.shader_feature_local,
            require: &self.require,
            exclude: &self.exclude,
            options: &self.options,
        }
    }
}

impl BlockToml {
    fn sets(&self) -> Sets<'_> {
        Sets {
            multi_compile: &self.multi_compile,
            multi_compile_local: &self.multi_compile_local,
            values: &self.values,
            shader_feature: &self.shader_feature,
            shader_feature_local: &self.shader_feature_local,
            require: &self.require,
            exclude: &self.exclude,
            options: &self.options,
        }
    }
}

/// The keywords a block declares (a valued set's as `NAME=VALUE`), `_` left out.
pub(super) fn keyword_names(
    block: &BlockToml,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
) -> Vec<String> {
    let mut pragmas = Vec::new();
    // The block's own errors are reported where the passes using it are built.
    keyword_pragmas(&block.sets(), at, &mut Vec::new(), &mut pragmas);
    declared_keywords(&pragmas)
}

/// The keywords `pragmas` declare, in order, `_` left out.
pub(super) fn declared_keywords(pragmas: &[Pragma]) -> Vec<String> {
    pragmas
        .iter()
        .filter_map(|p| match p {
            Pragma::Keywords { names, .. } => Some(names),
            _ => None,
        })
        .flatten()
        .map(|(n, _)| n.to_string())
        .filter(|n| n != "_")
        .collect()
}

/// Whether `name` can be a keyword: a def name (letters, digits and `_`, not starting with a
/// digit) or `_`.
pub(super) fn is_keyword_name(name: &str) -> bool {
    let mut chars = name.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The tree's shared parts a pass may draw on: `[options]` and `[blocks]`, of the declaration
/// file and of the files it includes, each with the file it is written in.
pub(super) struct Shared<'t> {
    pub options: Vec<(FileId, &'t OptionsToml)>,
    pub blocks: Vec<SharedBlock<'t>>,
}

/// A `[blocks.NAME]` table and where it is written.
#[derive(Clone, Copy)]
pub(super) struct SharedBlock<'t> {
    pub file: FileId,
    pub name: &'t Spanned<String>,
    pub block: &'t BlockToml,
}

impl<'t> Shared<'t> {
    /// The block named `name`.
    pub fn block(&self, name: &str) -> Option<SharedBlock<'t>> {
        self.blocks
            .iter()
            .copied()
            .find(|b| b.name.get_ref() == name)
    }
}

/// Spans into `file`.
pub(super) fn at_file(file: FileId) -> impl Fn(std::ops::Range<usize>) -> Span + Copy {
    move |r| Span::new(file, r)
}

/// The pass declaration of `p`: its own sets, then those of each block it uses (in `use`
/// order), with the options its keywords name.
pub(super) fn pass_decl(
    p: PassToml,
    shared: &Shared<'_>,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
    errors: &mut Vec<DeclarationError>,
) -> PassDecl {
    let main = at(0..0).file;
    let mut parts = vec![(p.sets(), main)];
    for name in &p.uses {
        match shared.block(name.get_ref()) {
            Some(b) => parts.push((b.block.sets(), b.file)),
            None => {
                let hint = crate::diagnostic::did_you_mean(
                    name.get_ref(),
                    shared.blocks.iter().map(|b| b.name.get_ref().as_str()),
                );
                errors.push(DeclarationError {
                    message: format!(
                        "pass `{}` uses block `{}`, which no `[blocks.{}]` table declares{hint}",
                        p.name.get_ref(),
                        name.get_ref(),
                        name.get_ref()
                    ),
                    span: at(name.span()),
                });
            }
        }
    }
    let mut pragmas = Vec::new();
    for (sets, file) in &parts {
        keyword_pragmas(sets, at_file(*file), errors, &mut pragmas);
    }
    for (sets, file) in &parts {
        constraint_pragmas(sets, at_file(*file), &mut pragmas);
    }
    if !p.skip_variants.is_empty() {
        pragmas.push(Pragma::SkipVariants(
            p.skip_variants
                .iter()
                .map(|s| (Box::from(s.get_ref().as_str()), at(s.span())))
                .collect(),
        ));
    }
    let declared: Vec<&str> = pragmas
        .iter()
        .filter_map(|p| match p {
            Pragma::Keywords { names, .. } => Some(names),
            _ => None,
        })
        .flatten()
        .map(|(n, _)| &**n)
        .collect();
    let sources = shared
        .options
        .iter()
        .copied()
        .chain(parts.iter().map(|(s, file)| (*file, s.options)));
    let options = options(sources, &declared, errors);
    PassDecl {
        name: p.name.get_ref().clone(),
        span: at(p.name.span()),
        tags: p.tags.into_iter().collect(),
        pragmas,
        body: Vec::new(),
        constants: Vec::new(),
        options,
        entry: p.entry.map(|e| (e.get_ref().clone(), at(e.span()))),
        module: None,
        profiles: super::profile::profiles(p.profile.as_ref(), at, errors),
        stage: None,
    }
}

/// A list of names with their spans.
fn names(n: &Names, at: impl Fn(std::ops::Range<usize>) -> Span) -> Vec<(Box<str>, Span)> {
    n.get_ref()
        .iter()
        .map(|s| (Box::from(s.get_ref().as_str()), at(s.span())))
        .collect()
}

/// The keyword sets of `sets` in declaration order: `multi_compile`, `multi_compile_local`,
/// `values`, `shader_feature`, `shader_feature_local`.
fn keyword_pragmas(
    sets: &Sets<'_>,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
    errors: &mut Vec<DeclarationError>,
    pragmas: &mut Vec<Pragma>,
) {
    for set in [
        sets.multi_compile,
        sets.multi_compile_local,
        sets.shader_feature,
        sets.shader_feature_local,
    ]
    .into_iter()
    .flatten()
    {
        for name in set.get_ref() {
            if !is_keyword_name(name.get_ref()) {
                errors.push(DeclarationError {
                    message: format!(
                        "`{}` is not a keyword: write a def name (letters, digits and `_`, not starting with a digit) or `_`",
                        name.get_ref()
                    ),
                    span: at(name.span()),
                });
            }
        }
    }
    keyword_sets(
        pragmas,
        sets.multi_compile,
        SetKind::MultiCompile,
        false,
        at,
    );
    keyword_sets(
        pragmas,
        sets.multi_compile_local,
        SetKind::MultiCompile,
        true,
        at,
    );
    // Valued sets: one option per value, `NAME=VALUE` (see `def_of`), no "none" option.
    for (name, values) in sets.values {
        let span = at(values.span());
        let texts: Option<Vec<String>> = match values.get_ref() {
            ValuesToml::Bools(v) => {
                Some(v.iter().map(|b| DefValue::Bool(*b).to_string()).collect())
            }
            ValuesToml::Ints(v) => v
                .iter()
                .map(|i| i32::try_from(*i).ok().map(|i| DefValue::Int(i).to_string()))
                .collect(),
            ValuesToml::UInts { uint } => uint
                .iter()
                .map(|u| {
                    u32::try_from(*u)
                        .ok()
                        .map(|u| DefValue::UInt(u).to_string())
                })
                .collect(),
        };
        match texts {
            Some(texts) if is_keyword_name(name.get_ref()) && !texts.is_empty() => {
                pragmas.push(Pragma::Keywords {
                    kind: SetKind::MultiCompile,
                    local: false,
                    names: texts
                        .iter()
                        .map(|v| (Box::from(format!("{}={v}", name.get_ref())), span))
                        .collect(),
                    span,
                })
            }
            _ => errors.push(DeclarationError {
                message: format!(
                    "`{}` needs a def name and at least one value, each an i32 (plain integers), a u32 (`{{ uint = [...] }}`) or a boolean",
                    name.get_ref()
                ),
                span: at(name.span()),
            }),
        }
    }
    keyword_sets(
        pragmas,
        sets.shader_feature,
        SetKind::ShaderFeature,
        false,
        at,
    );
    keyword_sets(
        pragmas,
        sets.shader_feature_local,
        SetKind::ShaderFeature,
        true,
        at,
    );
}

/// One pragma per set of `list`.
fn keyword_sets(
    pragmas: &mut Vec<Pragma>,
    list: &[Names],
    kind: SetKind,
    local: bool,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
) {
    for set in list {
        pragmas.push(Pragma::Keywords {
            kind,
            local,
            names: names(set, at),
            span: at(set.span()),
        });
    }
}

/// The `require` and `exclude` lists of `sets`.
fn constraint_pragmas(
    sets: &Sets<'_>,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
    pragmas: &mut Vec<Pragma>,
) {
    for (list, kind) in [
        (sets.require, ConstraintKind::Require),
        (sets.exclude, ConstraintKind::Exclude),
    ] {
        for c in list {
            pragmas.push(Pragma::Constraint {
                kind,
                names: names(c, at),
                span: at(c.span()),
            });
        }
    }
}

/// The options the `declared` keywords name, from every table in `sources` (the tree's
/// `[options]`, the pass's, its blocks'). An option declared twice with different defs, a
/// name that cannot be a keyword, an option that sets no def or an invalid def are errors.
fn options<'t>(
    sources: impl Iterator<Item = (FileId, &'t OptionsToml)>,
    declared: &[&str],
    errors: &mut Vec<DeclarationError>,
) -> BTreeMap<String, Vec<Constant>> {
    let mut out: BTreeMap<String, (Vec<Constant>, Span)> = BTreeMap::new();
    for (file, table) in sources {
        let at = at_file(file);
        for (name, option) in table {
            let (n, span) = (name.get_ref(), at(option.span()));
            if !declared.contains(&n.as_str()) {
                continue;
            }
            let Some(defs) = option_defs(n, option.get_ref(), span, errors) else {
                continue;
            };
            match out.get(n) {
                Some((earlier, _)) if *earlier != defs => errors.push(DeclarationError {
                    message: format!(
                        "option `{n}` is declared twice with different defs ({} and {}): an option sets the same defs wherever a pass uses it",
                        list(earlier),
                        list(&defs)
                    ),
                    span,
                }),
                Some(_) => {}
                None => {
                    out.insert(n.clone(), (defs, span));
                }
            }
        }
    }
    out.into_iter().map(|(n, (defs, _))| (n, defs)).collect()
}

/// `A, B=4u` for error messages.
fn list(defs: &[Constant]) -> String {
    let parts: Vec<String> = defs
        .iter()
        .map(|c| match c.value {
            DefValue::Bool(true) => c.name.clone(),
            v => format!("{}={v}", c.name),
        })
        .collect();
    format!("`{}`", parts.join(", "))
}

/// The defs of option `name`, or why it has none.
fn option_defs(
    name: &str,
    option: &OptionToml,
    span: Span,
    errors: &mut Vec<DeclarationError>,
) -> Option<Vec<Constant>> {
    let mut fail = |message: String| {
        errors.push(DeclarationError { message, span });
        None
    };
    if name == "_" || !is_keyword_name(name) {
        return fail(format!(
            "option `{name}`: an option is named by a keyword (letters, digits and `_`, not starting with a digit), other than `_`"
        ));
    }
    let defs: Vec<Constant> = match option {
        OptionToml::Names(names) => names
            .iter()
            .map(|n| Constant {
                name: n.clone(),
                value: DefValue::Bool(true),
            })
            .collect(),
        OptionToml::Defs(table) => {
            let mut defs = Vec::new();
            for (n, v) in table {
                match value_of(v) {
                    Some(value) => defs.push(Constant {
                        name: n.clone(),
                        value,
                    }),
                    None => {
                        return fail(format!(
                            "option `{name}`: `{n}` is out of range (shader defs are i32 or u32)"
                        ));
                    }
                }
            }
            defs
        }
    };
    if defs.is_empty() {
        return fail(format!(
            "option `{name}` sets no def: an option lists the defs it sets (the \"none\" option is `_`)"
        ));
    }
    if let Some(bad) = defs
        .iter()
        .find(|c| !is_keyword_name(&c.name) || c.name == "_")
    {
        return fail(format!(
            "option `{name}`: `{}` is not a def name (letters, digits and `_`, not starting with a digit)",
            bad.name
        ));
    }
    let mut seen = std::collections::BTreeSet::new();
    if let Some(twice) = defs.iter().find(|c| !seen.insert(c.name.as_str())) {
        return fail(format!("option `{name}` sets `{}` twice", twice.name));
    }
    Some(defs)
}

/// Keywords whose defs are also constants of their pass: the constant would set the def in
/// every variant, whichever option the variant has, so the keyword would change nothing.
pub(super) fn shadowed_keywords(
    decl: &PassDecl,
    constants: &[Constant],
    errors: &mut Vec<DeclarationError>,
) {
    for pragma in &decl.pragmas {
        let Pragma::Keywords { names, .. } = pragma else {
            continue;
        };
        for (name, span) in names {
            let defs: Vec<&str> = match decl.options.get(&**name) {
                Some(defs) => defs.iter().map(|c| c.name.as_str()).collect(),
                None => vec![super::def_of(name).0],
            };
            for def in defs {
                if !constants.iter().any(|c| c.name == def) {
                    continue;
                }
                let message = if decl.options.contains_key(&**name) {
                    format!(
                        "`{def}` is both set by option `{name}` of pass `{}` and a constant: the constant would set it in every variant, so the option would not change it (remove one of them)",
                        decl.name
                    )
                } else {
                    format!(
                        "`{def}` is both a keyword of pass `{}` and a constant: the constant would set it in every variant, so the keyword would change nothing (remove one of them)",
                        decl.name
                    )
                };
                errors.push(DeclarationError {
                    message,
                    span: *span,
                });
            }
        }
    }
}

/// The constants of a pass: the tree's, overridden by the pass's own.
pub(super) fn merged_constants(
    tree: &[Constant],
    p: &PassToml,
    at: impl Fn(std::ops::Range<usize>) -> Span,
    errors: &mut Vec<DeclarationError>,
) -> Vec<Constant> {
    let mut merged = tree.to_vec();
    for c in constants(&p.constants, at, errors) {
        merged.retain(|m| m.name != c.name);
        merged.push(c);
    }
    merged
}
