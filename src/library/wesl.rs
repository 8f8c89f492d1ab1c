//! Composing variants of a WESL tree with the `wesl` crate itself (0.6, what Bevy 0.20
//! composes with; the `wesl` cargo feature): the program a WESL user's build gets for the same
//! features, so what we validate and emit is what they run. Errors are located in the user's
//! files.
//!
//! Facts about `wesl` 0.6 this relies on (from its sources and the WESL specification): a
//! program is compiled from a root module path (`package::a::b`, the file `a/b.wesl` of the
//! root package; `bevy_render::maths`, the module `maths` of the package `bevy_render`) with
//! modules supplied by a `Resolver`; inside a named package `package::` means that package,
//! and a package named from inside another comes to the resolver as `outer/inner`;
//! features are booleans (`CompileOptions::features`), a feature never set is off; numbers
//! reach a program through the virtual `constants` package (`import constants::N;` or
//! `constants::N` inline); the output keeps only the declarations the entry points reach and
//! renames the imported ones, and its source map names each renamed declaration's module and
//! item; errors of its own stages (parsing, imports, conditions, its checks) carry the module
//! and the byte span in that module's source.
//!
//! A variant's keywords are features (every other keyword of its pass off), `Bool`
//! constants are features too, and every def (constants and valued keywords) is also a
//! `const` of the `constants` package and a feature that is on (as Bevy's shader cache sets
//! them, `bevy_shader` 0.20 `ShaderCache::get`). The output is parsed and validated by naga;
//! naga's spans point into the output, so each is traced to the output declaration it is in,
//! that declaration to its module and item by the source map, and the spanned text is looked
//! up in the item's original text (the item itself when the text was rewritten).

use std::borrow::Cow;
use std::collections::HashMap;

use wesl::error::ResolveError;
use wesl::sourcemap::{BasicSourceMap, SourceMap};
use wesl::syntax::{ModulePath, PathOrigin};
use wesl::{CompileOptions, Resolver};
use wgsl_parse::SyntaxNode;

use crate::declaration::DefValue;
use crate::diagnostic::{SourceFiles, Span};
use crate::error::{Stage, VariantError};
use crate::preprocess::tree::ParsedModule;

use super::Variant;

/// naga's error on the compiled program: its stage, message, labels (ranges of the program)
/// and notes.
type NagaError = (
    Stage,
    String,
    Vec<(std::ops::Range<usize>, String)>,
    Vec<String>,
);

/// The module names of a WESL tree; composing needs nothing else kept between variants (the
/// `wesl` crate parses the modules a program imports on each compile).
#[derive(Debug)]
pub(crate) struct WeslEngine {
    /// `package::a::b` → module id.
    by_name: HashMap<String, usize>,
    /// The compile options the declaration file sets.
    settings: crate::declaration::WeslSettings,
}

/// Supplies the tree's modules (and the variant's `constants` package) to the compiler.
struct TreeResolver<'a> {
    files: &'a SourceFiles,
    modules: &'a [ParsedModule],
    by_name: &'a HashMap<String, usize>,
    constants: String,
}

impl TreeResolver<'_> {
    fn module(&self, path: &ModulePath) -> Option<usize> {
        module_name(path).and_then(|name| self.by_name.get(&name).copied())
    }
}

/// The name the loader gives the module a path of the compiler names: `package::a::b` for
/// the tree's own package, `bevy_render::maths` for a named package. A package imported
/// from inside another comes as `bevy_pbr/bevy_render` (how `wesl` 0.6 joins two package
/// paths): its last part is the package.
fn module_name(path: &ModulePath) -> Option<String> {
    let package = match &path.origin {
        PathOrigin::Absolute => "package",
        PathOrigin::Package(p) => p.rsplit('/').next().unwrap_or(p),
        PathOrigin::Relative(_) => return None,
    };
    Some(
        std::iter::once(package)
            .chain(path.components.iter().map(String::as_str))
            .collect::<Vec<_>>()
            .join("::"),
    )
}

impl Resolver for TreeResolver<'_> {
    fn resolve_source<'a>(&'a self, path: &ModulePath) -> Result<Cow<'a, str>, ResolveError> {
        if path.components.is_empty()
            && matches!(&path.origin, PathOrigin::Package(p) if p.rsplit('/').next() == Some("constants"))
        {
            return Ok(Cow::Borrowed(self.constants.as_str()));
        }
        match self.module(path) {
            Some(m) => Ok(Cow::Borrowed(self.files.text(self.modules[m].file))),
            None => Err(ResolveError::ModuleNotFound(
                path.clone(),
                "no module of the tree has this path".into(),
            )),
        }
    }

    fn display_name(&self, path: &ModulePath) -> Option<String> {
        self.module(path)
            .map(|m| self.files.path(self.modules[m].file).to_string())
    }

    fn canonical_path(&self, path: &ModulePath) -> ModulePath {
        match &path.origin {
            PathOrigin::Package(p) if p.contains('/') => ModulePath {
                origin: PathOrigin::Package(p.rsplit('/').next().unwrap_or(p).to_string()),
                components: path.components.clone(),
            },
            _ => path.clone(),
        }
    }
}

impl WeslEngine {
    /// An engine for a loaded WESL tree (module names set by the loader).
    pub(crate) fn new(
        modules: &[ParsedModule],
        settings: crate::declaration::WeslSettings,
    ) -> WeslEngine {
        let by_name = modules
            .iter()
            .enumerate()
            .filter_map(|(id, m)| m.import_name.as_ref().map(|(n, _)| (n.clone(), id)))
            .collect();
        WeslEngine { by_name, settings }
    }

    /// The variant's program as the `wesl` crate compiles it, validated by naga.
    pub(crate) fn compose(
        &self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        variant: &Variant<'_>,
        profile: crate::validator::Profile,
    ) -> Result<String, VariantError> {
        let defs = variant.pass.defs(variant.keywords());
        let mut constants = String::new();
        for (i, (name, value)) in defs.iter().enumerate() {
            // Two options of one variant may set the same def (Bevy pushes a def from several
            // places): one `const`, not a duplicate declaration.
            if defs[..i].contains(&(*name, *value)) {
                continue;
            }
            constants.push_str(&format!("public const {name} = {value};\n"));
        }
        let resolver = TreeResolver {
            files,
            modules,
            by_name: &self.by_name,
            constants,
        };
        // `wesl`'s defaults (imports, conditions, visibility, stripping, a source map) but for
        // what the declaration sets; a feature never set is off.
        let mut options = CompileOptions {
            visibility: self.settings.visibility,
            ..CompileOptions::default()
        };
        for k in variant.pass.keywords() {
            for (name, _) in variant.pass.keyword_defs(k) {
                options.features.set(name, false);
            }
        }
        // A valued def is also a feature that is on, as Bevy's shader cache sets it.
        for (name, value) in &defs {
            let on = match value {
                DefValue::Bool(on) => *on,
                _ => true,
            };
            options.features.set(name, on);
        }
        let root_name = modules[variant.pass.module]
            .import_name
            .as_ref()
            .map_or("package", |n| n.0.as_str());
        let root: ModulePath = root_name.parse().map_err(|e| {
            super::unlocated(variant, Stage::Compose, format!("module path: {e:?}"))
        })?;
        // The compiler may panic on input it does not expect: one variant's failure.
        let compiled = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            wesl::compile(&root, &options, &resolver)
        }))
        .map_err(|panic| super::composer_panicked(variant, "the wesl crate", panic))?
        .map_err(|e| self.wesl_error(&e, files, modules, variant))?;
        let compiled = canonical(compiled, &root);
        let text = compiled.to_string();
        let module = naga::front::wgsl::parse_str(&text).map_err(|e| {
            let labels = e
                .labels()
                .map(|(s, m)| (s.to_range().unwrap_or(0..0), m.to_string()))
                .collect();
            self.output_error(
                (Stage::Parse, e.message().to_string(), labels, Vec::new()),
                (&text, &compiled),
                (files, modules),
                variant,
            )
        })?;
        if let Err(invalid) = profile.validator().validate(&module) {
            let labels = invalid
                .spans()
                .map(|(s, m)| (s.to_range().unwrap_or(0..0), m.clone()))
                .collect();
            let mut notes = Vec::new();
            let mut at = std::error::Error::source(invalid.as_inner());
            while let Some(s) = at {
                notes.push(s.to_string());
                at = s.source();
            }
            return Err(self.output_error(
                (
                    Stage::Validate,
                    invalid.as_inner().to_string(),
                    labels,
                    notes,
                ),
                (&text, &compiled),
                (files, modules),
                variant,
            ));
        }
        Ok(text)
    }

    /// The file of a module path the compiler names.
    fn file_of(
        &self,
        path: &ModulePath,
        modules: &[ParsedModule],
    ) -> Option<crate::diagnostic::FileId> {
        let name = module_name(path)?;
        self.by_name.get(&name).map(|&m| modules[m].file)
    }

    /// An error of the `wesl` crate's own stages, located in the module it names.
    fn wesl_error(
        &self,
        e: &wesl::Error,
        files: &SourceFiles,
        modules: &[ParsedModule],
        variant: &Variant<'_>,
    ) -> VariantError {
        let (inner, detail) = match e {
            wesl::Error::Error(d) => (&*d.error, Some(&d.detail)),
            other => (other, None),
        };
        let stage = match inner {
            wesl::Error::ParseError(_) => Stage::Parse,
            wesl::Error::ValidateError(_) => Stage::Validate,
            _ => Stage::Compose,
        };
        let mut labels = Vec::new();
        let mut notes = Vec::new();
        if let Some(detail) = detail {
            let file = detail
                .module_path
                .as_ref()
                .and_then(|p| self.file_of(p, modules));
            match (file, &detail.span) {
                (Some(file), Some(span)) => {
                    let text = files.text(file);
                    let r = span.range();
                    let start = r.start.min(text.len());
                    labels.push((
                        Span::new(file, start..r.end.clamp(start, text.len())),
                        String::new(),
                    ));
                }
                (Some(file), None) => notes.push(format!("in `{}`", files.path(file))),
                (None, _) => {
                    if let Some(p) = &detail.module_path {
                        notes.push(format!("in module `{p}`"));
                    }
                }
            }
            if let Some(decl) = &detail.declaration {
                notes.push(format!("in declaration `{decl}`"));
            }
        }
        // `wesl`'s own checks (a name no declaration has, declarations that depend on
        // themselves) name the declaration but give no span: point at the name in that
        // declaration, in the module named (any module of the tree when none is).
        if labels.is_empty()
            && let Some(decl) = detail.and_then(|d| d.declaration.as_ref())
        {
            let (word, label) = match inner {
                wesl::Error::ValidateError(wesl::error::ValidateError::UndefinedSymbol(name)) => {
                    (name.as_str(), "not declared")
                }
                _ => (decl.as_str(), "here"),
            };
            let named = detail
                .and_then(|d| d.module_path.as_ref())
                .and_then(|p| self.file_of(p, modules));
            let found = modules
                .iter()
                .map(|m| m.file)
                .filter(|f| named.is_none_or(|n| n == *f))
                .find_map(|file| {
                    let text = files.text(file);
                    locate(text, decl, word)
                        .filter(|r| text.get(r.clone()) == Some(word))
                        .map(|r| (file, r))
                });
            if let Some((file, range)) = found {
                labels.push((Span::new(file, range), label.into()));
                notes.retain(|n| !n.starts_with("in `"));
            }
        }
        // An item a variant's conditions removed has no span of its own: point at the
        // imports that name it.
        if let wesl::Error::UsageError(wesl::error::UsageError::NotFound(path, item)) = inner {
            let path = module_name(path).unwrap_or_else(|| path.to_string());
            let full = format!("{path}::{item}");
            for m in modules {
                for import in m.imports.iter().filter(|i| i.path == full) {
                    labels.push((
                        import.span,
                        format!("imported here; this variant's `{path}` has no `{item}`"),
                    ));
                }
            }
        }
        VariantError {
            variant: variant.label(),
            stage,
            message: format!("wesl: {inner}"),
            labels,
            notes,
            source: None,
        }
    }

    /// naga's error on the compiled program, its labels traced back to the user's files.
    fn output_error(
        &self,
        (stage, message, raw, notes): NagaError,
        (text, compiled): (&str, &wesl::CompileResult),
        (files, modules): (&SourceFiles, &[ParsedModule]),
        variant: &Variant<'_>,
    ) -> VariantError {
        let map = compiled.sourcemap.as_ref();
        let unmangle = |s: &str| match map {
            Some(map) => unmangle(s, map),
            None => s.to_string(),
        };
        // The output's declarations, with their spans in the output.
        let output: Option<wgsl_parse::syntax::TranslationUnit> = text.parse().ok();
        let mut labels = Vec::new();
        let mut notes: Vec<String> = notes.iter().map(|n| unmangle(n)).collect();
        for (range, label) in raw {
            let located = output.as_ref().and_then(|unit| {
                let decl = unit
                    .global_declarations
                    .iter()
                    .find(|d| d.span().range().contains(&range.start))?;
                let name = decl.ident()?.name().to_string();
                let (module, item) = match map
                    .and_then(|m| m.item(&name))
                    .map(|e| (&e.path, e.name.as_str()))
                {
                    Some((path, item)) => (self.file_of(path, modules)?, item.to_string()),
                    None => (modules[variant.pass.module].file, name.clone()),
                };
                let snippet = text.get(range.clone()).unwrap_or("");
                locate(files.text(module), &item, snippet).map(|r| Span::new(module, r))
            });
            match located {
                Some(span) => labels.push((span, unmangle(&label))),
                None => notes.push(format!(
                    "at `{}` of the compiled program",
                    unmangle(text.get(range).unwrap_or(""))
                )),
            }
        }
        VariantError {
            variant: variant.label(),
            stage,
            message: format!("naga (on wesl's output): {}", unmangle(&message)),
            labels,
            notes,
            source: None,
        }
    }
}

/// The compiled program with its declarations in one order. `wesl` appends each
/// imported module's declarations in an order that follows hash-map iteration, so the same
/// variant can come out in different orders from one run to the next; module-scope
/// declarations of WGSL do not depend on their order, so they are put in a fixed one: the
/// root module's first, then each imported module's by module path, each module's in its
/// source order (declarations without a name, `const_assert`s, last by text); directives
/// sorted.
fn canonical(mut compiled: wesl::CompileResult, root: &ModulePath) -> wesl::CompileResult {
    let map = compiled.sourcemap.as_ref();
    let key = |decl: &wgsl_parse::syntax::GlobalDeclarationNode| -> (u8, String) {
        match decl.ident() {
            Some(ident) => match map.and_then(|m| m.item(&ident.name()).map(|e| e.path.clone())) {
                Some(path) if path != *root => (1, path.to_string()),
                _ => (0, String::new()),
            },
            None => (2, decl.to_string()),
        }
    };
    let mut decls = std::mem::take(&mut compiled.syntax.global_declarations);
    decls.sort_by_cached_key(key);
    compiled.syntax.global_declarations = decls;
    compiled
        .syntax
        .global_directives
        .sort_by_cached_key(|d| d.to_string());
    compiled.syntax.global_directives.dedup();
    compiled
}

/// Bytes of `source` for `snippet` of the compiled program inside the declaration named
/// `item`: the snippet where the declaration has it verbatim, otherwise the declaration's
/// name.
fn locate(source: &str, item: &str, snippet: &str) -> Option<std::ops::Range<usize>> {
    let unit: wgsl_parse::syntax::TranslationUnit = source.parse().ok()?;
    let decl = unit
        .global_declarations
        .iter()
        .find(|d| d.ident().is_some_and(|i| *i.name() == item))?;
    let r = decl.span().range();
    let body = source.get(r.clone())?;
    if !snippet.trim().is_empty()
        && let Some(at) = body.find(snippet)
    {
        return Some(r.start + at..r.start + at + snippet.len());
    }
    let at = whole_word(body, item)?;
    Some(r.start + at..r.start + at + item.len())
}

/// The first place `word` appears in `text` as a whole identifier.
fn whole_word(text: &str, word: &str) -> Option<usize> {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(word).map(|(i, _)| i).find(|&i| {
        !text[..i].chars().next_back().is_some_and(ident)
            && !text[i + word.len()..].chars().next().is_some_and(ident)
    })
}

/// `text` with each renamed declaration written as `package::module::item`.
fn unmangle(text: &str, map: &BasicSourceMap) -> String {
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        match map.item(word) {
            Some(e) if e.name != word.as_str() => {
                let path = module_name(&e.path).unwrap_or_else(|| e.path.to_string());
                out.push_str(&format!("{path}::{}", e.name))
            }
            _ => out.push_str(word),
        }
        word.clear();
    };
    for c in text.chars() {
        if c.is_alphanumeric() || c == '_' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

impl super::engine::Engine for WeslEngine {
    fn compose(
        &self,
        tree: &crate::preprocess::compose::ModuleGraph<'_>,
        variant: &Variant<'_>,
        how: super::engine::How,
    ) -> crate::preprocess::Composed {
        super::engine::composed(self.compose(tree.files, tree.modules, variant, how.profile))
    }
}
