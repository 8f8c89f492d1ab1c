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
use std::collections::{HashMap, HashSet};
use std::sync::{Mutex, OnceLock};

use wesl::error::{Diagnostic, ResolveError};
use wesl::pass::{self, CompilerDriver, Module, UsedItems};
use wesl::sourcemap::{BasicSourceMap, SourceMap, SourceMapper};
use wesl::syntax::{ModulePath, PathOrigin};
use wesl::{CompileOptions, Mangler, Resolver};
use wgsl_parse::SyntaxNode;
use wgsl_parse::syntax::{GlobalDeclaration, Ident, TranslationUnit, Visibility};

use crate::declaration::DefValue;
use crate::diagnostic::{SourceFiles, Span};
use crate::error::{Stage, VariantError};
use crate::preprocess::tree::ParsedModule;

use super::Variant;

mod check;
mod copy;
mod memo;

use copy::{Retargeted, fresh_copy};

/// naga's error on the compiled program: its stage, message, labels (ranges of the program)
/// and notes.
type NagaError = (
    Stage,
    String,
    Vec<(std::ops::Range<usize>, String)>,
    Vec<String>,
);

/// The module names of a WESL tree, and each module's syntax tree, parsed once: `wesl::compile`
/// parses every module a program imports on each compile; this engine runs the same
/// compilation passes ([`CachedDriver`]) on a copy of the tree parsed at the module's first
/// use. A loaded tree's texts never change (`watch` loads a changed tree anew, with a new
/// engine), so a parse is never stale.
#[derive(Debug)]
pub(crate) struct WeslEngine {
    /// `package::a::b` → module id.
    by_name: HashMap<String, usize>,
    /// The compile options the declaration file sets.
    settings: crate::declaration::WeslSettings,
    /// Per module id: its text as `wgsl-parse` parses it (`None`: it does not parse), made at
    /// its first use (by any thread) and kept for the engine's life.
    parsed: Vec<OnceLock<Option<TranslationUnit>>>,
    /// Per module id: the identifiers its text has (a superset of the features its `@if`
    /// conditions read), found at its first use.
    words: Vec<OnceLock<HashSet<String>>>,
    /// The modules `wesl`'s own check of a loaded module (`validate_wesl`) found valid, each
    /// with the features it reads: module id and those features' values
    /// ([`WeslEngine::feature_key`]). What the check sees is the module as its conditions
    /// leave it, a function of the module's text and of those values alone.
    checked: Mutex<HashSet<(usize, String)>>,
    /// The programs compiled so far, for variants that compile to one of them.
    programs: memo::Programs,
    /// Per module id and feature values ([`WeslEngine::feature_key`]): the module's parse as
    /// `wesl`'s conditions leave it (`condcomp`) and `retarget_idents` points its names,
    /// made at its first use.
    conditioned: Mutex<HashMap<(usize, String), std::sync::Arc<Retargeted>>>,
}

/// Most entries [`WeslEngine::checked`] keeps before it starts again (memory stays bounded
/// over huge spaces).
const CHECKED_MAX: usize = 1 << 16;

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

/// `wesl::compile` (0.6.0, `frontend.rs`) with the modules of the tree taken from `tree` (a
/// copy of the module's parse, [`copy`]) rather than parsed from the resolver's text, and
/// `wesl`'s check of a loaded module skipped where it found the same module valid before: the same
/// passes in the same order, the same source map (the resolver still supplies each module's
/// text, which the source map records), the same errors. Options the engine never sets
/// (no stripping, `keep`, `keep_main`, no source map) go to `wesl::compile` itself. With the
/// result, the tree modules the compile loaded (`None` where `wesl::compile` ran).
fn compile(
    main_path: &ModulePath,
    options: &CompileOptions,
    resolver: &TreeResolver<'_>,
    tree: &TreeModules<'_>,
) -> (Result<wesl::CompileResult, wesl::Error>, Option<Vec<usize>>) {
    if !options.strip || options.keep.is_some() || options.keep_main || !options.sourcemap {
        return (wesl::compile(main_path, options, resolver), None);
    }
    let mangler = Box::<dyn Mangler>::from(options.mangler);
    let sourcemapper = SourceMapper::new(main_path.clone(), resolver, &mangler);
    let mut driver = CachedDriver {
        main_path,
        options,
        resolver: &sourcemapper,
        mangler: &sourcemapper,
        tree,
        loaded: Vec::new(),
    };
    let res = CompilerDriver::compile(&mut driver);
    let loaded = std::mem::take(&mut driver.loaded);
    let sourcemap = sourcemapper.finish();
    let res = res
        .map_err(|e| Diagnostic::from(e).with_sourcemap(&sourcemap).into())
        .map(|res| wesl::CompileResult {
            syntax: res.syntax,
            modules: res.modules,
            sourcemap: Some(sourcemap),
            used_items: res.used_items,
        });
    (res, Some(loaded))
}

/// `wesl` 0.6.0's own compilation pass (`frontend.rs`, `CompilationPass`), for stripping
/// compiles without `keep`, loading the tree's modules from their parse.
struct CachedDriver<'a> {
    main_path: &'a ModulePath,
    options: &'a CompileOptions,
    resolver: &'a dyn Resolver,
    mangler: &'a dyn Mangler,
    tree: &'a TreeModules<'a>,
    /// The tree modules loaded so far.
    loaded: Vec<usize>,
}

/// The loaded tree's modules as [`CachedDriver`] reads them: parsed once, and `wesl`'s
/// check of each remembered per feature values ([`WeslEngine::checked`]).
struct TreeModules<'a> {
    engine: &'a WeslEngine,
    files: &'a SourceFiles,
    modules: &'a [ParsedModule],
    resolver: &'a TreeResolver<'a>,
}

impl CompilerDriver for CachedDriver<'_> {
    fn main_path(&self) -> &ModulePath {
        self.main_path
    }

    fn canonical_path(&self, path: &ModulePath) -> ModulePath {
        self.resolver.canonical_path(path)
    }

    fn main_entry_points(
        &self,
        main_module: &TranslationUnit,
    ) -> Result<HashSet<Ident>, wesl::Error> {
        Ok(pass::main_entry_points(main_module))
    }

    fn module_usage_analysis(
        &self,
        module: &Module,
        already_used: &mut UsedItems,
        to_analyze: &mut UsedItems,
    ) -> Result<(), wesl::Error> {
        pass::module_usage_analysis(module, already_used, to_analyze, !self.options.visibility)?;
        Ok(())
    }

    fn usage_analysis(
        &self,
        module: &Module,
        decl_name: &str,
        min_vis: Visibility,
        already_used: &mut UsedItems,
        to_analyze: &mut UsedItems,
    ) -> Result<(), wesl::Error> {
        pass::usage_analysis(
            module,
            decl_name,
            min_vis,
            already_used,
            to_analyze,
            !self.options.visibility,
        )?;
        Ok(())
    }

    fn load_module(&mut self, path: &ModulePath) -> Result<TranslationUnit, wesl::Error> {
        let engine = self.tree.engine;
        let m = self.tree.resolver.module(path);
        // The values of the features the module can read: what its conditions leave of it
        // and `wesl`'s check of it depend on nothing else.
        let key = m.filter(|_| self.options.condcomp).map(|m| {
            let key = engine.feature_key(
                self.tree.files,
                self.tree.modules,
                m,
                &self.options.features,
            );
            (m, key)
        });
        let parsed =
            m.and_then(|m| Some((m, engine.parsed(self.tree.files, self.tree.modules, m)?)));
        let (id, mut module, conditioned) = match parsed {
            Some((m, unit)) => {
                // The source map records the module's text, as when `wesl` parses it.
                self.resolver.resolve_source(path)?;
                self.loaded.push(m);
                let conditioned = key
                    .as_ref()
                    .and_then(|k| engine.conditioned(k, unit, &self.options.features));
                match conditioned {
                    Some(module) => (Some(m), module, true),
                    None => (Some(m), fresh_copy(unit), false),
                }
            }
            None => (None, pass::load_module(path, &self.resolver)?, false),
        };
        // A conditioned copy comes retargeted (`Retargeted`).
        if !conditioned {
            if self.options.condcomp {
                pass::condcomp(&mut module, &self.options.features)?;
            }
            pass::retarget_idents(&mut module);
        }
        if self.options.validate {
            // Found valid before with the same features: the same module, valid again.
            let key = key.filter(|_| id.is_some());
            let known = key
                .as_ref()
                .is_some_and(|k| engine.checked.lock().is_ok_and(|c| c.contains(k)));
            if !known {
                pass::validate_wesl(&module)?;
                if let (Some(k), Ok(mut checked)) = (key, engine.checked.lock()) {
                    if checked.len() >= CHECKED_MAX {
                        checked.clear();
                    }
                    checked.insert(k);
                }
            }
        }
        Ok(module)
    }

    fn link(
        &self,
        modules: &mut Vec<Module>,
        used_items: &UsedItems,
    ) -> Result<TranslationUnit, wesl::Error> {
        pass::retarget_modules(modules, used_items, &self.resolver);
        for module in modules.iter_mut() {
            if !self.options.mangle_main && module.path == *self.main_path {
                continue;
            }
            pass::mangle(&mut module.syntax, &module.path, &self.mangler);
        }
        let mut module = pass::link(modules, Some(used_items));
        if self.options.lower {
            pass::lower(&mut module)?;
        }
        if self.options.validate {
            check::validate_wgsl(&module)?;
        }
        Ok(module)
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
        WeslEngine {
            by_name,
            settings,
            parsed: modules.iter().map(|_| OnceLock::new()).collect(),
            words: modules.iter().map(|_| OnceLock::new()).collect(),
            checked: Mutex::new(HashSet::new()),
            programs: memo::Programs::default(),
            conditioned: Mutex::new(HashMap::new()),
        }
    }

    /// Module `m`'s syntax tree as `wgsl-parse` parses its text, parsed at its first use.
    fn parsed<'s>(
        &'s self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        m: usize,
    ) -> Option<&'s TranslationUnit> {
        self.parsed[m]
            .get_or_init(|| files.text(modules[m].file).parse().ok())
            .as_ref()
    }

    /// A copy of module `key.0`'s parse (`unit`) as `wesl`'s conditions leave it for the
    /// feature values `key.1` (those of `features`), after `retarget_idents`; `None` where the
    /// conditions fail (the caller runs them itself, for their error). The same as
    /// conditioning and retargeting a fresh copy of the parse, which is what `wesl` does with
    /// a new parse: conditions only remove nodes and attributes, and [`Retargeted::copy`]
    /// gives new identifiers to the same places, shared as retargeting shares them.
    fn conditioned(
        &self,
        key: &(usize, String),
        unit: &TranslationUnit,
        features: &wesl::Features,
    ) -> Option<TranslationUnit> {
        let known = self
            .conditioned
            .lock()
            .ok()
            .and_then(|c| c.get(key).cloned());
        let tree = match known {
            Some(tree) => tree,
            None => {
                let mut tree = unit.clone();
                pass::condcomp(&mut tree, features).ok()?;
                let tree = std::sync::Arc::new(Retargeted::new(&tree));
                if let Ok(mut c) = self.conditioned.lock() {
                    if c.len() >= CHECKED_MAX {
                        c.clear();
                    }
                    c.insert(key.clone(), tree.clone());
                }
                tree
            }
        };
        Some(tree.copy())
    }

    /// The values `features` gives the features module `m` can read (the feature names its
    /// text has as identifiers), as one key.
    fn feature_key(
        &self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        m: usize,
        features: &wesl::Features,
    ) -> String {
        let words = self.words[m].get_or_init(|| {
            files
                .text(modules[m].file)
                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                .filter(|w| !w.is_empty())
                .map(str::to_string)
                .collect()
        });
        let mut read: Vec<(&str, u8)> = features
            .flags
            .iter()
            .filter(|(name, _)| words.contains(name.as_str()))
            .map(|(name, value)| (name.as_str(), *value as u8))
            .collect();
        read.sort_unstable();
        let mut key = format!("{}", features.default as u8);
        for (name, value) in read {
            key.push_str(&format!(" {name}={value}"));
        }
        key
    }

    /// The syntax tree of the module whose file is `file` (parsed once).
    fn parsed_file<'s>(
        &'s self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        file: crate::diagnostic::FileId,
    ) -> Option<&'s TranslationUnit> {
        let m = modules.iter().position(|m| m.file == file)?;
        self.parsed(files, modules, m)
    }

    /// The variant's program as the `wesl` crate compiles it, validated by naga for
    /// `profile`, and whether `profile` takes it (nothing it refuses beyond naga's
    /// capabilities, [`crate::validator::Profile::refuses`]): then validating the text again
    /// for `profile` would find it valid.
    pub(crate) fn compose(
        &self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        variant: &Variant<'_>,
        profile: crate::validator::Profile,
    ) -> Result<(String, bool), VariantError> {
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
        // What `wesl::compile` parses is the tree's text, parsed once (the `constants` package,
        // which differs between variants, is parsed on each compile).
        let tree = TreeModules {
            engine: self,
            files,
            modules,
            resolver: &resolver,
        };
        let features = |m: usize| self.feature_key(files, modules, m, &options.features);
        let probe = memo::Probe {
            root: variant.pass.module,
            profile: format!("{profile:?}"),
            constants: &resolver.constants,
            features: &features,
        };
        if let Some(known) = self.programs.get(&probe) {
            return Ok(known);
        }
        // The compiler may panic on input it does not expect: one variant's failure.
        let (compiled, loaded) = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            compile(&root, &options, &resolver, &tree)
        }))
        .map_err(|panic| super::composer_panicked(variant, "the wesl crate", panic))?;
        let compiled = compiled.map_err(|e| self.wesl_error(&e, files, modules, variant))?;
        let compiled = canonical(compiled, &root);
        let (text, spans) = program_text(&compiled.syntax);
        let module = naga::front::wgsl::parse_str(&text).map_err(|e| {
            let labels = e
                .labels()
                .map(|(s, m)| (s.to_range().unwrap_or(0..0), m.to_string()))
                .collect();
            self.output_error(
                (Stage::Parse, e.message().to_string(), labels, Vec::new()),
                (&text, &spans, &compiled),
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
                (&text, &spans, &compiled),
                (files, modules),
                variant,
            ));
        }
        let taken = profile.refuses(&module).is_none();
        if let Some(loaded) = loaded {
            self.programs.put(&probe, &loaded, &text, taken);
        }
        Ok((text, taken))
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
                    let unit = self.parsed_file(files, modules, file)?;
                    locate(text, unit, decl, (word, 0))
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
        (text, spans, compiled): (&str, &[DeclSpan], &wesl::CompileResult),
        (files, modules): (&SourceFiles, &[ParsedModule]),
        variant: &Variant<'_>,
    ) -> VariantError {
        let map = compiled.sourcemap.as_ref();
        let unmangle = |s: &str| match map {
            Some(map) => unmangle(s, map),
            None => s.to_string(),
        };
        let mut labels = Vec::new();
        let mut notes: Vec<String> = notes.iter().map(|n| unmangle(n)).collect();
        for (range, label) in raw {
            let located = (|| {
                let (span, i) = spans.iter().find(|(r, _)| r.contains(&range.start))?;
                let decl = &compiled.syntax.global_declarations[*i];
                let name = decl.ident()?.name().to_string();
                let (module, item) = match map
                    .and_then(|m| m.item(&name))
                    .map(|e| (&e.path, e.name.as_str()))
                {
                    Some((path, item)) => (self.file_of(path, modules)?, item.to_string()),
                    None => (modules[variant.pass.module].file, name.clone()),
                };
                let snippet = text.get(range.clone()).unwrap_or("");
                // Which of the declaration's occurrences of the snippet naga points at.
                let before = text.get(span.start..range.start).unwrap_or("");
                let nth = occurrences(before, snippet).count();
                let unit = self.parsed_file(files, modules, module)?;
                locate(files.text(module), unit, &item, (snippet, nth))
                    .map(|r| Span::new(module, r))
            })();
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

/// A declaration's byte range in the program's text, and its index in the program's
/// declarations.
type DeclSpan = (std::ops::Range<usize>, usize);

/// The program's text exactly as its `Display` writes it (imports, directives, then each
/// declaration but the empty ones, a blank line apart), with each declaration's range in it:
/// what a parse of the text would give, without parsing it.
fn program_text(unit: &TranslationUnit) -> (String, Vec<DeclSpan>) {
    use std::fmt::Write;
    let mut text = String::new();
    let mut spans = Vec::new();
    for import in &unit.imports {
        let _ = writeln!(text, "{import}\n");
    }
    if !unit.global_directives.is_empty() {
        for (i, directive) in unit.global_directives.iter().enumerate() {
            if i > 0 {
                text.push('\n');
            }
            let _ = write!(text, "{directive}");
        }
        text.push_str("\n\n");
    }
    let decls = unit
        .global_declarations
        .iter()
        .enumerate()
        .filter(|(_, d)| !matches!(d.node(), GlobalDeclaration::Void));
    for (n, (i, decl)) in decls.enumerate() {
        if n > 0 {
            text.push_str("\n\n");
        }
        let start = text.len();
        let _ = write!(text, "{decl}");
        spans.push((start..text.len(), i));
    }
    text.push('\n');
    (text, spans)
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

/// Bytes of `source` (parsed: `unit`) for the `nth` occurrence of `snippet` in the
/// compiled program's declaration named `item`: the same occurrence of the snippet in the
/// source declaration (its last where the source has fewer: the branches the variant leaves
/// out only add occurrences), otherwise the declaration's name.
fn locate(
    source: &str,
    unit: &TranslationUnit,
    item: &str,
    (snippet, nth): (&str, usize),
) -> Option<std::ops::Range<usize>> {
    let decl = unit
        .global_declarations
        .iter()
        .find(|d| d.ident().is_some_and(|i| *i.name() == item))?;
    let r = decl.span().range();
    let body = source.get(r.clone())?;
    if !snippet.trim().is_empty() {
        let found: Vec<usize> = occurrences(body, snippet).collect();
        if let Some(&at) = found.get(nth).or(found.last()) {
            return Some(r.start + at..r.start + at + snippet.len());
        }
    }
    let at = whole_word(body, item)?;
    Some(r.start + at..r.start + at + item.len())
}

/// Where `snippet` appears in `text`: as a whole identifier when it is one (`uv` is not in
/// `ddx_uv`), anywhere otherwise.
fn occurrences<'t>(text: &'t str, snippet: &'t str) -> impl Iterator<Item = usize> + 't {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    let word = !snippet.is_empty() && snippet.chars().all(ident);
    text.match_indices(snippet)
        .map(|(i, _)| i)
        .filter(move |&i| {
            !word
                || (!text[..i].chars().next_back().is_some_and(ident)
                    && !text[i + snippet.len()..].chars().next().is_some_and(ident))
        })
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
        match self.compose(tree.files, tree.modules, variant, how.profile) {
            Ok((text, taken)) => crate::preprocess::Composed {
                text,
                validated: taken.then_some(how.profile),
                ..crate::preprocess::Composed::default()
            },
            Err(e) => crate::preprocess::Composed::failed(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The text with declaration ranges is the program's `Display`, and each range holds its
    /// declaration.
    #[test]
    fn program_text_is_the_display_with_each_declaration_located() {
        let unit: TranslationUnit = "enable f16;
            diagnostic(off, derivative_uniformity);
            @group(0) @binding(1) var<uniform> u: vec4f;
            ;
            struct S { a: f32 }
            const_assert 1 < 2;
            fn f(s: S) -> f32 { return s.a; }"
            .parse()
            .expect("parses");
        let (text, spans) = program_text(&unit);
        assert_eq!(text, unit.to_string());
        assert_eq!(spans.len(), 4, "the empty declaration has no range");
        for (range, i) in &spans {
            assert_eq!(
                &text[range.clone()],
                unit.global_declarations[*i].to_string()
            );
        }
    }
}
