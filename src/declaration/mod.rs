//! The declaration file, `wgsl-variants.toml`: shaders, passes and keyword sets for trees
//! whose sources do not declare them: naga_oil's dialect (Bevy 0.19's trees) and WESL's
//! (Bevy's main branch). `dialect` is `"naga-oil"` or `"wesl"`; without it, a tree whose
//! entries are `.wesl` files is WESL and any other naga_oil.
//!
//! It says in TOML what a `#shader`/`#pass` block says with `#pragma` lines, with the same
//! meaning (Unity's `multi_compile` builds every option, `shader_feature` only what materials
//! use; `_` is the "none" option), and every rule and diagnostic of those pragmas applies:
//! the file becomes the same pass declarations the `#pass` parser makes, with spans into the TOML, and goes through
//! the same checks ([`crate::shader::Pass`]).
//!
//! ```toml
//! dialect = "naga-oil"
//! exclude = ["meshlet/dummy.wgsl"]  # files or folders left out (e.g. one of two alternatives)
//! profile = "desktop"              # the device: webgpu (default), webgl2, desktop, or naga's capability names; or a list (["webgpu", "desktop"]), one verdict each
//!
//! [constants]                      # shader defs every variant gets
//! MAX_LIGHTS = { uint = 4 }        # naga_oil's ShaderDefValue::UInt
//! TONEMAP = true                   # Bool; a plain integer is Int
//!
//! [packages]                       # WESL trees of several packages: name = folder
//! bevy_render = "bevy_render/src"  # `bevy_render::maths` is `bevy_render/src/maths.wesl`
//!
//! [wesl]                           # `wesl`'s compile options (WESL trees only)
//! visibility = false               # as Bevy 0.20 composes (default: true, wesl's default)
//!
//! [[shader]]
//! name = "pbr"
//! entry = "render/pbr.wgsl"        # the module composed for each variant
//!
//! [[shader.pass]]
//! name = "Forward"
//! # entry = "render/pbr_forward.wgsl"   # a pass may compose its own entry module
//! # profile = "webgl2"             # a pass may name its own device(s), overriding the tree's
//! multi_compile = [["_", "SKINNED"], ["_", "MORPH_TARGETS"]]
//! shader_feature = [["_", "VERTEX_UVS"]]
//! require = [["VERTEX_TANGENTS", "VERTEX_UVS"]]   # the first needs the others on
//! exclude = [["SKINNED", "MORPH_TARGETS"]]        # at most one of them on
//! skip_variants = []
//! tags = { LightMode = "Forward" }
//! constants = { PREPASS = false }  # this pass's own constants (override the tree's)
//! ```
//!
//! What an engine pushes together is said once:
//!
//! ```toml
//! [options]                        # a keyword that sets several defs (and valued defs)
//! TONEMAP_ACES = ["TONEMAP_IN_SHADER", "TONEMAP_METHOD_ACES_FITTED"]
//! TONEMAP_TONY = { TONEMAP_IN_SHADER = true, TONEMAP_METHOD_TONY_MC_MAPFACE = true, LUT_BINDING = { uint = 18 } }
//!
//! [blocks.tonemapping]             # keyword sets, constraints and options passes share
//! multi_compile = [["_", "TONEMAP_ACES", "TONEMAP_TONY"]]
//! require = [["DEBAND_DITHER", "TONEMAP_ACES"]]
//!
//! [modules."render/view.wgsl".constants]   # defs set on one module: every pass that
//! MAX_LIGHTS = { uint = 10 }               # composes it gets them
//!
//! [[shader.pass]]
//! name = "Forward"
//! use = ["tonemapping"]            # the block's sets follow the pass's own
//! options = { FOG_ON = ["DISTANCE_FOG", "FOG_TINT"] }   # options of this pass only
//! ```
//!
//! A keyword an option names sets the option's defs instead of the def of its own name
//! ([`Pass::keyword_defs`](crate::Pass::keyword_defs)); the variant's keywords stay the option
//! names. An option is declared once (the tree's `[options]`, a block's or a pass's `options`;
//! the same name twice must set the same defs). A module's defs reach every pass whose entry
//! imports it, directly or not, as naga_oil applies a composable module's `shader_defs` and
//! Bevy 0.20 the `ShaderSettings` of the modules a shader composes; a def with two values in
//! one pass, or one that a keyword of the pass also sets, is refused. In a naga_oil tree a def
//! set to `false` that a module tests with `#ifdef` is a warning: `#ifdef` asks whether the
//! def is set, not its value.
//!
//! Valued sets give a def one of several values, one variant per value:
//!
//! ```toml
//! values = { MAX_CASCADES = { uint = [1, 2, 4] }, BLUR_TAPS = [4, 8, 16, 32] }
//! ```
//!
//! Their keywords are `NAME=VALUE` (`MAX_CASCADES=4u`, `BLUR_TAPS=8`; see [`def_of`]), and
//! they have no "none" option. Keyword sets are declared in this order: `multi_compile`,
//! `multi_compile_local`, `values`, `shader_feature`, `shader_feature_local`, each in the order
//! written (values by name); that order is the order variants are enumerated in.

use std::collections::BTreeMap;

use serde::Deserialize;
use toml::Spanned;

use crate::diagnostic::{Diagnostic, FileId, Span};
use crate::preprocess::tree::PassDecl;

mod pass;
mod profile;
mod stage;

/// The declaration file's name, at the root of a tree.
pub const FILE_NAME: &str = "wgsl-variants.toml";

pub use crate::keywords::{Constant, DefValue, def_of};

/// One `[[shader]]` of the file, its passes turned into declarations.
#[derive(Clone, Debug)]
pub(crate) struct ShaderSpec {
    /// The shader's name.
    pub name: String,
    /// Where the name is written.
    pub span: Span,
    /// The entry module's path (relative to the root, with `.wgsl`) and where it is written.
    pub entry: (String, Span),
    /// Its passes, their constants the tree's overridden by the pass's.
    pub passes: Vec<PassDecl>,
}

/// A parsed declaration file.
#[derive(Clone, Debug)]
pub(crate) struct Declaration {
    /// The dialect of the tree's modules.
    pub dialect: crate::preprocess::Dialect,
    /// Paths (files or folders, relative to the root) left out of the tree, with where each
    /// is written.
    pub exclude: Vec<(String, Span)>,
    /// WESL packages: each name with its folder (relative to the root, no trailing `/`).
    pub packages: Vec<(String, String)>,
    /// How `wesl` composes the tree (`[wesl]`).
    pub wesl: WeslSettings,
    /// The devices the tree is validated for (`profile`, one or a list; empty: WebGPU).
    pub profiles: Vec<crate::validator::Profile>,
    /// The shaders, in file order.
    pub shaders: Vec<ShaderSpec>,
    /// Defs set on single modules (`[modules."PATH".constants]`), in path order.
    pub module_constants: Vec<ModuleConstants>,
}

/// The defs a `[modules."PATH"]` table sets: every pass whose entry reaches the module gets
/// them, as naga_oil applies a composable module's `shader_defs` and Bevy 0.20 a module's
/// `ShaderSettings` (the defs of every module of the composed closure).
#[derive(Clone, Debug)]
pub(crate) struct ModuleConstants {
    /// The module's path relative to the root, with its extension, as written.
    pub path: String,
    /// Where the path is written.
    pub span: Span,
    /// The defs.
    pub constants: Vec<Constant>,
}

/// The `[wesl]` table: the options of `wesl`'s compiler a tree sets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct WeslSettings {
    /// WESL's visibility rules (`public`, `package`, `private`): on by default, as `wesl`
    /// compiles; Bevy 0.20 composes with them off (`bevy_shader` `ShaderCache::get`), so its
    /// modules import each other's items without `public`.
    pub visibility: bool,
}

impl Default for WeslSettings {
    fn default() -> Self {
        WeslSettings { visibility: true }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WeslToml {
    visibility: Option<bool>,
}

/// The declaration file is malformed: TOML syntax or types, an unknown dialect, a constant out
/// of range.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct DeclarationError {
    /// What is wrong (the TOML parser's message for syntax and type errors).
    pub message: String,
    /// Where in the file.
    pub span: Span,
}

impl DeclarationError {
    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        Diagnostic::new(format!("in the declaration file: {}", self.message)).at(self.span, "here")
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    dialect: Option<Spanned<String>>,
    #[serde(default)]
    include: Vec<Spanned<String>>,
    profile: Option<Spanned<profile::ProfileToml>>,
    #[serde(default)]
    exclude: Vec<Spanned<String>>,
    #[serde(default)]
    packages: BTreeMap<Spanned<String>, Spanned<String>>,
    wesl: Option<Spanned<WeslToml>>,
    #[serde(default)]
    constants: BTreeMap<Spanned<String>, Spanned<ValueToml>>,
    #[serde(default)]
    options: pass::OptionsToml,
    #[serde(default)]
    blocks: BTreeMap<Spanned<String>, pass::BlockToml>,
    #[serde(default)]
    modules: BTreeMap<Spanned<String>, ModuleToml>,
    #[serde(default, rename = "shader")]
    shaders: Vec<ShaderToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ShaderToml {
    name: Spanned<String>,
    entry: Spanned<String>,
    #[serde(default, rename = "pass")]
    passes: Vec<pass::PassToml>,
}

/// The `include` list of a declaration file, read before the rest (whose blocks may live in
/// the included files): each path with its byte range; empty when the text is not TOML (the
/// full parse reports why).
pub(crate) fn include_list(text: &str) -> Vec<(String, std::ops::Range<usize>)> {
    #[derive(Deserialize)]
    struct Only {
        #[serde(default)]
        include: Vec<Spanned<String>>,
    }
    toml::from_str::<Only>(text)
        .map(|o| {
            o.include
                .into_iter()
                .map(|i| (i.get_ref().clone(), i.span()))
                .collect()
        })
        .unwrap_or_default()
}

/// A file a declaration file includes (`include = ["PATH"]`): options and blocks that
/// several trees share.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct IncludeToml {
    #[serde(default)]
    options: pass::OptionsToml,
    #[serde(default)]
    blocks: BTreeMap<Spanned<String>, pass::BlockToml>,
}

/// A `[modules."PATH"]` table: what the declaration says about one module.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ModuleToml {
    #[serde(default)]
    constants: BTreeMap<Spanned<String>, Spanned<ValueToml>>,
}

#[derive(Deserialize)]
#[serde(untagged)]
pub(super) enum ValueToml {
    Bool(bool),
    Int(i64),
    UInt { uint: i64 },
}

/// Parses the declaration file `file` (its text `text`).
///
/// # Errors
/// Every problem found: TOML syntax and types (unknown fields included), an unknown dialect,
/// constants out of range. Keyword rules are checked later, when the passes are built, with
/// spans into this file.
pub(crate) fn parse(
    file: FileId,
    text: &str,
    included: &[(FileId, &str)],
) -> Result<Declaration, Vec<DeclarationError>> {
    let at = |range: std::ops::Range<usize>| Span::new(file, range);
    let parsed: FileToml = toml::from_str(text).map_err(|e| {
        vec![DeclarationError {
            message: toml_message(e.message()),
            span: at(e.span().unwrap_or(0..text.len().min(1))),
        }]
    })?;
    let mut errors = Vec::new();
    let mut includes_parsed = Vec::new();
    for &(id, text) in included {
        match toml::from_str::<IncludeToml>(text) {
            Ok(inc) => includes_parsed.push((id, inc)),
            Err(e) => errors.push(DeclarationError {
                message: format!(
                    "{} (an included file holds `[options]` and `[blocks]` only)",
                    toml_message(e.message())
                ),
                span: Span::new(id, e.span().unwrap_or(0..text.len().min(1))),
            }),
        }
    }
    let wesl_entries = parsed
        .shaders
        .iter()
        .any(|s| s.entry.get_ref().ends_with(".wesl"));
    let dialect = match &parsed.dialect {
        None if wesl_entries => crate::preprocess::Dialect::Wesl,
        None => crate::preprocess::Dialect::NagaOil,
        Some(d) => match d.get_ref().as_str() {
            "naga-oil" => crate::preprocess::Dialect::NagaOil,
            "wesl" => crate::preprocess::Dialect::Wesl,
            other => {
                errors.push(DeclarationError {
                    message: format!(
                        "unknown dialect `{other}`: a declaration file declares a `naga-oil` or a `wesl` tree (trees in this crate's own dialect declare their keywords in their sources)"
                    ),
                    span: at(d.span()),
                });
                crate::preprocess::Dialect::NagaOil
            }
        },
    };
    let tree_constants = constants(&parsed.constants, at, &mut errors);
    let mut shared = pass::Shared {
        options: vec![(file, &parsed.options)],
        blocks: Vec::new(),
    };
    let tables = std::iter::once((file, &parsed.blocks))
        .chain(includes_parsed.iter().map(|(id, inc)| (*id, &inc.blocks)));
    for (id, blocks) in tables {
        for (name, block) in blocks {
            if let Some(first) = shared.block(name.get_ref()) {
                errors.push(DeclarationError {
                    message: format!(
                        "block `{}` is declared twice (first at {}): a block has one home",
                        name.get_ref(),
                        if first.file == file {
                            "the declaration file"
                        } else {
                            "an included file"
                        }
                    ),
                    span: Span::new(id, name.span()),
                });
                continue;
            }
            shared.blocks.push(pass::SharedBlock {
                file: id,
                name,
                block,
            });
        }
    }
    shared
        .options
        .extend(includes_parsed.iter().map(|(id, inc)| (*id, &inc.options)));
    stage::check_block_stages(&shared, &mut errors);
    let shaders = parsed
        .shaders
        .into_iter()
        .map(|s| ShaderSpec {
            name: s.name.get_ref().clone(),
            span: at(s.name.span()),
            entry: (s.entry.get_ref().clone(), at(s.entry.span())),
            passes: s
                .passes
                .into_iter()
                .flat_map(|mut p| {
                    let merged = pass::merged_constants(&tree_constants, &p, at, &mut errors);
                    let stages = std::mem::take(&mut p.stages);
                    let uses = p.uses.clone();
                    let mut decl = pass::pass_decl(p, &shared, at, &mut errors);
                    pass::shadowed_keywords(&decl, &merged, &mut errors);
                    decl.constants = merged;
                    stage::split(decl, stages, &uses, &shared, at, &mut errors)
                })
                .collect(),
        })
        .collect();
    let module_constants = parsed
        .modules
        .iter()
        .map(|(path, m)| ModuleConstants {
            path: path.get_ref().clone(),
            span: at(path.span()),
            constants: constants(&m.constants, at, &mut errors),
        })
        .collect();
    let includes: Vec<(String, Span)> = parsed
        .include
        .iter()
        .map(|e| (e.get_ref().clone(), at(e.span())))
        .collect();
    for (path, span) in &includes {
        if let Some(why) = not_a_tree_path(path) {
            errors.push(DeclarationError {
                message: format!(
                    "include entry `{path}` {why}: entries are paths of files relative to the root"
                ),
                span: *span,
            });
        }
    }
    let exclude: Vec<(String, Span)> = parsed
        .exclude
        .iter()
        .map(|e| (e.get_ref().clone(), at(e.span())))
        .collect();
    for (path, span) in &exclude {
        if let Some(why) = not_a_tree_path(path) {
            errors.push(DeclarationError {
                message: format!(
                    "exclude entry `{path}` {why}: entries are paths of files or folders relative to the root, not patterns"
                ),
                span: *span,
            });
        }
    }
    let packages = packages(&parsed.packages, dialect, at, &mut errors);
    let profiles = profile::profiles(parsed.profile.as_ref(), at, &mut errors);
    let mut wesl = WeslSettings::default();
    if let Some(table) = &parsed.wesl {
        if dialect != crate::preprocess::Dialect::Wesl {
            errors.push(DeclarationError {
                message: "`[wesl]` sets how `wesl` composes a WESL tree: this tree is not WESL (`dialect = \"wesl\"`)".into(),
                span: at(table.span()),
            });
        }
        if let Some(v) = table.get_ref().visibility {
            wesl.visibility = v;
        }
    }
    if errors.is_empty() {
        Ok(Declaration {
            dialect,
            exclude,
            packages,
            wesl,
            profiles,
            shaders,
            module_constants,
        })
    } else {
        Err(errors)
    }
}

/// The `[packages]` table: WESL only; each name a WESL package name (not one WESL reserves),
/// each folder a path of the tree.
fn packages(
    table: &BTreeMap<Spanned<String>, Spanned<String>>,
    dialect: crate::preprocess::Dialect,
    at: impl Fn(std::ops::Range<usize>) -> Span,
    errors: &mut Vec<DeclarationError>,
) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for (name, folder) in table {
        if dialect != crate::preprocess::Dialect::Wesl {
            errors.push(DeclarationError {
                message: "`[packages]` maps WESL package names to folders: this tree is not WESL (`dialect = \"wesl\"`)".into(),
                span: at(name.span()),
            });
            return Vec::new();
        }
        let n = name.get_ref();
        let identifier = n
            .chars()
            .next()
            .is_some_and(|c| c.is_alphabetic() || c == '_')
            && n.chars().all(|c| c.is_alphanumeric() || c == '_');
        if !identifier || ["package", "self", "super", "constants"].contains(&n.as_str()) {
            errors.push(DeclarationError {
                message: format!(
                    "package name `{n}`: a package is named by an identifier other than `package`, `self`, `super` and `constants` (which WESL reserves)"
                ),
                span: at(name.span()),
            });
        }
        let f = folder.get_ref();
        let why = if f.trim_matches('/').is_empty() {
            Some("is the root (the root is the tree's own package, `package::`)")
        } else {
            not_a_tree_path(f)
        };
        if let Some(why) = why {
            errors.push(DeclarationError {
                message: format!(
                    "package folder `{f}` {why}: a package is a folder of the tree, relative to the root"
                ),
                span: at(folder.span()),
            });
        }
        out.push((n.clone(), f.trim_matches('/').to_string()));
    }
    out
}

/// Why `path` cannot name a file or folder of the tree, if it cannot: empty, a pattern, or a
/// path that leaves the root.
fn not_a_tree_path(path: &str) -> Option<&'static str> {
    if path.trim_matches('/').is_empty() {
        return Some("is empty (it would leave out the whole tree)");
    }
    if path.contains(['*', '?', '[', ']', '{', '}']) {
        return Some("is a glob pattern");
    }
    if path.starts_with('/')
        || path.contains('\\')
        || path.split('/').any(|c| c == ".." || c == ".")
    {
        return Some("is not a plain relative path (no `/` at the start, `\\`, `.` or `..`)");
    }
    None
}

/// A constant's value, if it is in range (i32 for a plain integer, u32 for `{ uint = N }`).
pub(super) fn value_of(value: &ValueToml) -> Option<DefValue> {
    match value {
        ValueToml::Bool(b) => Some(DefValue::Bool(*b)),
        ValueToml::Int(i) => i32::try_from(*i).ok().map(DefValue::Int),
        ValueToml::UInt { uint } => u32::try_from(*uint).ok().map(DefValue::UInt),
    }
}

pub(super) fn constants(
    table: &BTreeMap<Spanned<String>, Spanned<ValueToml>>,
    at: impl Fn(std::ops::Range<usize>) -> Span,
    errors: &mut Vec<DeclarationError>,
) -> Vec<Constant> {
    let mut out = Vec::new();
    for (name, value) in table {
        match value_of(value.get_ref()) {
            Some(value) => out.push(Constant {
                name: name.get_ref().clone(),
                value,
            }),
            None => errors.push(DeclarationError {
                message: format!(
                    "`{}` is out of range: shader defs are i32 (a plain integer) or u32 (`{{ uint = N }}`)",
                    name.get_ref()
                ),
                span: at(value.span()),
            }),
        }
    }
    out
}

/// The TOML parser's message, with serde's words for a value of the wrong type ("did not match
/// any variant of untagged enum …") replaced by what the value may be.
fn toml_message(message: &str) -> String {
    if message.contains("untagged enum ValueToml") {
        "a constant's value is `true` or `false` (Bool), an integer (Int, i32) or `{ uint = N }` (UInt, u32)".into()
    } else if message.contains("untagged enum OptionToml") {
        "an option is a list of the defs it sets (`[\"A\", \"B\"]`) or a table of defs with their values (`{ A = true, N = { uint = 4 } }`)".into()
    } else if message.contains("untagged enum ValuesToml") {
        "a valued set's values are a list of integers (`[4, 8]`, Int) or `{ uint = [1, 2] }` (UInt), or `[true, false]`".into()
    } else {
        message.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preprocess::tree::Pragma;

    #[test]
    fn passes_become_pragmas_with_spans_into_the_file() {
        let text = r#"
[constants]
N = { uint = 4 }
B = true

[[shader]]
name = "pbr"
entry = "pbr.wgsl"

[[shader.pass]]
name = "Forward"
multi_compile = [["_", "SKINNED"]]
shader_feature = [["_", "UVS"]]
require = [["UVS", "SKINNED"]]
constants = { B = false }
"#;
        let d = parse(0, text, &[]).unwrap();
        let pass = &d.shaders[0].passes[0];
        let consts = &pass.constants;
        assert_eq!(pass.pragmas.len(), 3);
        let Pragma::Keywords { names, .. } = &pass.pragmas[0] else {
            panic!()
        };
        assert_eq!(&text[names[1].1.range()], "\"SKINNED\"");
        assert_eq!(
            consts,
            &[
                Constant {
                    name: "N".into(),
                    value: DefValue::UInt(4)
                },
                Constant {
                    name: "B".into(),
                    value: DefValue::Bool(false)
                }
            ]
        );
    }

    #[test]
    fn a_wrongly_typed_value_says_what_a_value_may_be() {
        let e = parse(0, "[constants]\nN = \"four\"\n", &[]).unwrap_err();
        assert!(
            e[0].message
                .contains("`true` or `false` (Bool), an integer (Int, i32) or `{ uint = N }`"),
            "{}",
            e[0].message
        );
        assert!(!e[0].message.contains("untagged"), "{}", e[0].message);
    }

    #[test]
    fn a_keyword_that_is_also_a_constant_is_refused() {
        let text = "[constants]\nFOG = true\n[[shader]]\nname = \"s\"\nentry = \"m.wgsl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"FOG\"]]\n";
        let e = parse(0, text, &[]).unwrap_err();
        assert!(
            e[0].message
                .contains("`FOG` is both a keyword of pass `P` and a constant"),
            "{}",
            e[0].message
        );
        assert_eq!(&text[e[0].span.range()], "\"FOG\"");
    }

    #[test]
    fn errors_are_located() {
        let e = parse(
            0,
            "[[shader]]\nname = \"a\"\nentry = \"a.wgsl\"\ncolour = 1\n",
            &[],
        )
        .unwrap_err();
        assert!(e[0].message.contains("unknown field `colour`"), "{e:?}");
        assert_eq!(e[0].span.range().start, 39);
        let e = parse(0, "dialect = \"glsl\"\n", &[]).unwrap_err();
        assert!(e[0].message.contains("unknown dialect `glsl`"));
        let e = parse(0, "[constants]\nX = 4294967296\n", &[]).unwrap_err();
        assert!(e[0].message.contains("out of range"));
    }
}
