//! One module on its own, for another engine's shader tree.
//!
//! [`export_prefixed`] composes a module with its imports (under the given keywords),
//! validates it with naga, renames every top-level name — structs, constants, overrides,
//! global variables, functions, entry points — to `PREFIX` + name in naga's IR, and writes
//! self-contained WGSL with naga's WGSL back end. Renaming in the IR is exact: struct members,
//! locals and parameters are untouched, and nothing in comments or strings can be hit.
//!
//! ```
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let wgsl = wgsl_variants::emit::export::export_prefixed(&lib, "deferred/gbuffer", "wv_", &["UNITY_HDR_ON"]).unwrap();
//! assert!(wgsl.contains("fn wv_gbuffer_pack("));
//! assert!(wgsl.contains("fn wv_ldr_encode(")); // from the import deferred/ldr
//! assert!(!wgsl.contains("fn gbuffer_pack("));
//! ```
//!
//! [`super::naga_oil`] exports modules in naga_oil's dialect instead.

use std::collections::{BTreeSet, HashMap};

use crate::diagnostic::Diagnostic;
use crate::diagnostic::suggest;
use crate::error::VariantError;
use crate::library::Library;
use crate::preprocess::Composed;
use crate::preprocess::compose::compose;

/// Why a module could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// No module has this path.
    #[error("no module `{path}`{}", suggestion.as_ref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default())]
    UnknownModule {
        /// The path asked for.
        path: String,
        /// The closest module path.
        suggestion: Option<String>,
    },
    /// The path is a shader file (`#shader`), not a module.
    #[error("`{0}` is a shader file; export a module it imports, or use `emit` for its passes")]
    ShaderFile(String),
    /// A keyword that no `#if` of the module or its imports reads.
    #[error("no `#if` in `{module}` or its imports reads `{keyword}`{}", suggestion.as_ref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default())]
    UnknownKeyword {
        /// The module.
        module: String,
        /// The keyword.
        keyword: String,
        /// The closest name that is read.
        suggestion: Option<String>,
    },
    /// The prefix is not the start of a WGSL identifier.
    #[error(
        "prefix `{0}` is not the start of a WGSL identifier (letters, digits, `_`; not starting with a digit or `__`)"
    )]
    BadPrefix(String),
    /// naga rejected the composed module.
    #[error(transparent)]
    Invalid(#[from] VariantError),
    /// The module no longer validates after its names were prefixed.
    #[error("naga's WGSL writer failed: after renaming: {}", .0.as_inner())]
    Renamed(Box<naga::WithSpan<naga::valid::ValidationError>>),
    /// naga's WGSL writer failed.
    #[error("naga's WGSL writer failed: {0}")]
    Writer(#[from] naga::back::wgsl::Error),
    /// A construct that naga_oil's dialect cannot express.
    #[error("{module}: {message}")]
    Inexpressible {
        /// The module.
        module: String,
        /// What cannot be expressed, and where.
        message: String,
    },
}

impl ExportError {
    /// A renderable report (naga errors point at the original files).
    pub fn diagnostic(&self) -> Diagnostic {
        match self {
            ExportError::Invalid(e) => e.diagnostic(),
            other => Diagnostic::new(other.to_string()),
        }
    }
}

/// The id of the module at `path` (library-relative, without `.wgsl`), refusing shader files.
pub(crate) fn module_index(lib: &Library, path: &str) -> Result<usize, ExportError> {
    let path = path.trim().trim_end_matches(".wgsl");
    let index = lib
        .module_paths()
        .iter()
        .position(|p| p == path)
        .ok_or_else(|| ExportError::UnknownModule {
            path: path.to_string(),
            suggestion: suggest(path, lib.module_paths().iter().map(String::as_str)),
        })?;
    if is_shader_file(lib, index) {
        return Err(ExportError::ShaderFile(path.to_string()));
    }
    Ok(index)
}

/// Whether module `index` is a shader file (`#shader`) rather than a plain module.
pub fn is_shader_file(lib: &Library, index: usize) -> bool {
    let file = lib.module_graph().modules[index].file;
    lib.shaders().iter().any(|s| s.file == file)
}

/// Post-order over imports: `module` after every module it imports (each once), appended to
/// `order` — the order the dialect exports write modules in, imports first.
pub(crate) fn dependency_order(lib: &Library, module: usize, order: &mut Vec<usize>) {
    if order.contains(&module) {
        return;
    }
    // Cycles are rejected when the library loads, so this terminates.
    for &next in &lib.module_graph().resolved[module] {
        dependency_order(lib, next, order);
    }
    if !order.contains(&module) {
        order.push(module);
    }
}

/// Every module of the library but the shader files, each after its imports.
pub(crate) fn library_order(lib: &Library) -> Vec<usize> {
    let mut order = Vec::new();
    for m in 0..lib.module_graph().modules.len() {
        if !is_shader_file(lib, m) {
            dependency_order(lib, m, &mut order);
        }
    }
    order
}

/// A module and every module it imports, directly or not, in first-import order (the
/// module itself first).
pub(crate) fn import_closure(lib: &Library, module: usize) -> Vec<usize> {
    let graph = lib.module_graph();
    let mut order = vec![module];
    let mut i = 0;
    while i < order.len() {
        for &next in &graph.resolved[order[i]] {
            if !order.contains(&next) {
                order.push(next);
            }
        }
        i += 1;
    }
    order
}

/// Every name an `#if` of the module or its imports reads.
pub fn conditions_read(lib: &Library, module: usize) -> BTreeSet<String> {
    let graph = lib.module_graph();
    let mut names = BTreeSet::new();
    for m in import_closure(lib, module) {
        crate::preprocess::tree::names_read(&graph.modules[m].body, &mut names);
    }
    names
}

/// Composes a module (with its imports) with `keywords` defined as 1. A keyword that no `#if`
/// of the module or its imports reads is an error (a typo would otherwise pass silently).
pub(crate) fn compose_module(
    lib: &Library,
    path: &str,
    keywords: &[&str],
) -> Result<Composed, ExportError> {
    let index = module_index(lib, path)?;
    let read = conditions_read(lib, index);
    for k in keywords {
        if !read.contains(*k) {
            return Err(ExportError::UnknownKeyword {
                module: lib.module_paths()[index].clone(),
                keyword: k.to_string(),
                suggestion: suggest(k, read.iter().map(String::as_str)),
            });
        }
    }
    let graph = lib.module_graph();
    let defines: HashMap<Box<str>, i64> = keywords.iter().map(|k| (Box::from(*k), 1)).collect();
    Ok(compose(
        &graph,
        index,
        &graph.modules[index].body,
        defines,
        true,
    ))
}

fn check_prefix(prefix: &str) -> Result<(), ExportError> {
    let ok = !prefix.is_empty()
        && !prefix.starts_with("__")
        && !prefix.starts_with(|c: char| c.is_ascii_digit())
        && prefix
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else {
        Err(ExportError::BadPrefix(prefix.to_string()))
    }
}

/// Renames every top-level name of a module to `prefix` + name (predeclared `__` types are
/// left alone).
pub(crate) fn prefix_names(module: &mut naga::Module, prefix: &str) {
    let rename = |name: &mut Option<String>| {
        if let Some(n) = name
            && !n.starts_with("__")
        {
            *n = format!("{prefix}{n}");
        }
    };
    let structs: Vec<_> = module
        .types
        .iter()
        .filter(|(_, ty)| {
            matches!(ty.inner, naga::TypeInner::Struct { .. })
                && ty.name.as_ref().is_some_and(|n| !n.starts_with("__"))
        })
        .map(|(h, ty)| (h, ty.clone()))
        .collect();
    for (handle, mut ty) in structs {
        rename(&mut ty.name);
        module.types.replace(handle, ty);
    }
    for (_, c) in module.constants.iter_mut() {
        rename(&mut c.name);
    }
    for (_, o) in module.overrides.iter_mut() {
        rename(&mut o.name);
    }
    for (_, g) in module.global_variables.iter_mut() {
        rename(&mut g.name);
    }
    for (_, f) in module.functions.iter_mut() {
        rename(&mut f.name);
    }
    for ep in module.entry_points.iter_mut() {
        ep.name = format!("{prefix}{}", ep.name);
        rename(&mut ep.function.name);
    }
}

/// A module exported as self-contained WGSL (what `export MODULE --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct PrefixedModule {
    /// The module path as asked for.
    pub module: String,
    /// The WGSL text.
    pub source: String,
}

/// [`export_prefixed`], with the module path it was asked for.
pub fn export_prefixed_module(
    lib: &Library,
    path: &str,
    prefix: &str,
    keywords: &[&str],
) -> Result<PrefixedModule, ExportError> {
    Ok(PrefixedModule {
        module: path.to_string(),
        source: export_prefixed(lib, path, prefix, keywords)?,
    })
}

/// Exports a module with its imports as self-contained WGSL, every top-level name prefixed
/// (see the [module docs](self)).
pub fn export_prefixed(
    lib: &Library,
    path: &str,
    prefix: &str,
    keywords: &[&str],
) -> Result<String, ExportError> {
    check_prefix(prefix)?;
    let composed = compose_module(lib, path, keywords)?;
    let path = path.trim().trim_end_matches(".wgsl");
    let label = format!("module {path} {{{}}}", keywords.join(", "));
    let (mut module, _) = crate::validator::validate_for(&composed, &label, lib.profile())?;
    prefix_names(&mut module, prefix);
    let info = lib
        .profile()
        .validator()
        .validate(&module)
        .map_err(|e| ExportError::Renamed(Box::new(e)))?;
    let body =
        naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty())?;
    let imports: Vec<String> = import_closure(lib, module_index(lib, path)?)
        .into_iter()
        .skip(1)
        .map(|m| lib.module_paths()[m].clone())
        .collect();
    Ok(format!(
        "// {path}{} exported by wgsl-variants {} with prefix `{prefix}`{}.\n// Self-contained: every top-level name is prefixed; validated by naga.\n\n{body}",
        if keywords.is_empty() {
            String::new()
        } else {
            format!(" {{{}}}", keywords.join(", "))
        },
        env!("CARGO_PKG_VERSION"),
        if imports.is_empty() {
            String::new()
        } else {
            format!(", with its imports {}", imports.join(", "))
        },
    ))
}
