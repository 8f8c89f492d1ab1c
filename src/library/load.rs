//! Loading: decode files, parse every module, resolve imports, check the import graph, and
//! assemble shaders.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::diagnostic::SourceFiles;
use crate::diagnostic::suggest;
use crate::preprocess::tree::{ImportRef, Node, ParsedModule, ShaderDecl};
use crate::preprocess::{Dialect, ParseError, ParseLimits, parse_module_in};
use crate::shader::{Pass, Shader};
use crate::source::{self, RawFile};

use super::error::{LinkError, LoadError, LoadProblem};

/// Limits applied while loading a library. Each has a clear error when passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LoadOptions {
    /// `#if` and expression nesting limits.
    pub parse: ParseLimits,
    /// Longest chain of imports.
    pub max_import_depth: usize,
    /// Most module files in a tree.
    pub max_files: usize,
    /// Most bytes of source in total.
    pub max_total_bytes: usize,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            parse: ParseLimits::default(),
            max_import_depth: 64,
            max_files: 100_000,
            max_total_bytes: 256 << 20,
        }
    }
}

/// Everything a library is made of once loaded.
pub(crate) struct Loaded {
    /// The dialect the modules are written in.
    pub dialect: Dialect,
    /// How `wesl` composes a WESL tree.
    pub wesl: crate::declaration::WeslSettings,
    /// The devices the declaration file names (`profile`); empty: WebGPU.
    pub profiles: Vec<crate::validator::Profile>,
    /// What loads but is probably not meant (declared keywords no module reads).
    pub warnings: Vec<crate::diagnostic::Diagnostic>,
    pub files: SourceFiles,
    pub modules: Vec<ParsedModule>,
    pub paths: Vec<String>,
    pub resolved: Vec<Vec<usize>>,
    pub shaders: Vec<Shader>,
}

pub(crate) fn load(
    raw: Vec<RawFile>,
    escaping: &[String],
    options: &LoadOptions,
) -> Result<Loaded, LoadError> {
    // `.wesl` files are modules of WESL trees only (which have a declaration file).
    let (wesl, raw): (Vec<RawFile>, Vec<RawFile>) =
        raw.into_iter().partition(|f| f.path.ends_with(".wesl"));
    let (files, paths, mut modules) = parse_all(raw, Dialect::WgslVariants, options)?;
    let mut problems = Vec::new();
    let resolved = resolve_paths(&modules, &paths, escaping, &mut problems);
    if problems.is_empty() {
        problems.extend(
            check_graph(
                &modules,
                &paths,
                &resolved,
                options.max_import_depth,
                Cycles::Refused,
            )
            .into_iter()
            .map(Into::into),
        );
    }
    let decls = modules
        .iter_mut()
        .enumerate()
        .filter_map(|(id, m)| m.shader.take().map(|d| (d, m.file, id)))
        .collect();
    let mut loaded = assemble(files, paths, modules, resolved, decls, problems)?;
    if let Some(first) = wesl.first() {
        loaded.warnings.push(
            crate::diagnostic::Diagnostic::new(format!(
                "{} `.wesl` file(s) left out (`{}`…): a WESL tree is read with a declaration file, `{}` with `dialect = \"wesl\"`, at its root",
                wesl.len(),
                first.path,
                crate::declaration::FILE_NAME
            ))
            .warning(),
        );
    }
    Ok(loaded)
}

/// Loads a tree whose keywords a declaration file declares (`declaration`: its path and
/// bytes), written in the file's dialect: imports resolve by `#define_import_path` names,
/// and each shader's passes compose its entry module.
pub(crate) fn load_declared(
    raw: Vec<RawFile>,
    declaration: RawFile,
    read_include: &dyn Fn(&str) -> Result<Vec<u8>, String>,
    options: &LoadOptions,
) -> Result<Loaded, LoadError> {
    // The declaration's file id comes after the modules'; its `exclude` list decides how many
    // modules there are, so it is parsed once for the list and again with its final id.
    let text = String::from_utf8_lossy(&declaration.bytes).into_owned();
    // The files it includes (their blocks complete it), each read once, in the order written.
    type Included = (String, std::ops::Range<usize>, Result<Vec<u8>, String>);
    let mut includes: Vec<Included> = Vec::new();
    for (path, range) in crate::declaration::include_list(&text) {
        if !includes.iter().any(|(p, _, _)| *p == path) {
            let bytes = read_include(&path);
            includes.push((path, range, bytes));
        }
    }
    let lossy: Vec<String> = includes
        .iter()
        .filter_map(|(_, _, b)| b.as_ref().ok())
        .map(|b| String::from_utf8_lossy(b).into_owned())
        .collect();
    let early: Vec<(crate::diagnostic::FileId, &str)> = lossy
        .iter()
        .enumerate()
        .map(|(i, t)| (raw.len() + 1 + i, t.as_str()))
        .collect();
    let (exclude, dialect, packages) = crate::declaration::parse(raw.len(), &text, &early)
        .map(|d| (d.exclude, d.dialect, d.packages))
        .unwrap_or((Vec::new(), Dialect::NagaOil, Vec::new()));
    let excludes = |path: &str, e: &str| {
        path == e || path.starts_with(&format!("{}/", e.trim_end_matches('/')))
    };
    // Entries that leave out nothing: a misspelt path is a warning, not silence.
    let unmatched: Vec<String> = exclude
        .iter()
        .filter(|(e, _)| !raw.iter().any(|f| excludes(&f.path, e)))
        .map(|(e, _)| e.clone())
        .collect();
    let wesl_stems: Vec<&str> = raw
        .iter()
        .filter_map(|f| f.path.strip_suffix(".wesl"))
        .collect();
    // WESL reads `x.wesl` before `x.wgsl`; other dialects have no `.wesl` modules.
    let keep: Vec<bool> = raw
        .iter()
        .map(|f| match dialect {
            Dialect::Wesl => f
                .path
                .strip_suffix(".wgsl")
                .is_none_or(|stem| !wesl_stems.contains(&stem)),
            _ => !f.path.ends_with(".wesl"),
        })
        .collect();
    let raw: Vec<RawFile> = raw
        .into_iter()
        .zip(keep)
        .filter(|(f, keep)| *keep && !exclude.iter().any(|(e, _)| excludes(&f.path, e)))
        .map(|(f, _)| f)
        .collect();
    let (mut files, paths, mut modules) = parse_all(raw, dialect, options)?;
    if dialect == Dialect::Wesl {
        wesl_module_paths(&mut modules, &paths, &packages);
    }
    let (ids, errors) = source::decode(vec![declaration], &mut files);
    if let Some(e) = errors.into_iter().next() {
        return Err(LoadError {
            files,
            problems: vec![e.into()],
        });
    }
    let mut included = Vec::new();
    let mut problems: Vec<LoadProblem> = Vec::new();
    for (path, range, bytes) in includes {
        match bytes {
            Ok(bytes) => {
                let (id, errors) = source::decode(vec![RawFile { path, bytes }], &mut files);
                problems.extend(errors.into_iter().map(Into::into));
                included.extend(id);
            }
            Err(why) => problems.push(
                crate::declaration::DeclarationError {
                    message: format!("include `{path}`: {why}"),
                    span: crate::diagnostic::Span::new(ids[0], range),
                }
                .into(),
            ),
        }
    }
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    let texts: Vec<(crate::diagnostic::FileId, &str)> =
        included.iter().map(|&id| (id, files.text(id))).collect();
    let decl = match crate::declaration::parse(ids[0], files.text(ids[0]), &texts) {
        Ok(d) => d,
        Err(errors) => {
            return Err(LoadError {
                files,
                problems: errors.into_iter().map(Into::into).collect(),
            });
        }
    };
    let decl_wesl = decl.wesl;
    // Each shader's entry module, and each pass's own where it names one.
    let mut decl = decl;
    let decl_profiles = std::mem::take(&mut decl.profiles);
    let mut entries = Vec::new();
    let mut find = |shader: &str, (entry, span): &(String, crate::diagnostic::Span)| {
        let stem = entry
            .strip_suffix(".wgsl")
            .or_else(|| entry.strip_suffix(".wesl"))
            .unwrap_or(entry);
        // The module of that name, if it is the very file named: `lit.wesl` is not `lit.wgsl`.
        let module = paths.iter().position(|p| p == stem);
        let read = module.map(|m| files.path(modules[m].file));
        let found = module.filter(|_| stem == entry || read == Some(entry.as_str()));
        if found.is_none() {
            let hint = match read {
                Some(other) => format!(
                    "; the module `{stem}` of this tree is `{other}` ({} trees read `.{}` files{})",
                    dialect.name(),
                    extension(dialect),
                    if dialect == Dialect::Wesl {
                        ", and `.wesl` first"
                    } else {
                        "; a WESL tree says `dialect = \"wesl\"`"
                    }
                ),
                None if entry.ends_with(".wesl") && dialect != Dialect::Wesl => format!(
                    "; `.wesl` files are modules of WESL trees only (`dialect = \"wesl\"`), and this tree is read as {}",
                    dialect.name()
                ),
                None => suggest(stem, paths.iter().map(String::as_str))
                    .map(|s| format!("; did you mean `{s}.{}`?", extension(dialect)))
                    .unwrap_or_default(),
            };
            problems.push(
                LinkError::UnknownEntry {
                    shader: shader.to_string(),
                    path: entry.clone(),
                    hint,
                    span: *span,
                }
                .into(),
            );
        }
        found
    };
    for shader in &mut decl.shaders {
        let id = find(&shader.name, &shader.entry);
        for pass in &mut shader.passes {
            pass.module = match &pass.entry {
                Some(entry) => find(&shader.name, entry),
                None => id,
            };
        }
        entries.push(id);
    }
    let roots: Vec<usize> = decl
        .shaders
        .iter()
        .zip(&entries)
        .flat_map(|(s, id)| s.passes.iter().map(|p| p.module).chain([*id]))
        .flatten()
        .collect();
    let names = import_names(&modules);
    for module in &mut modules {
        inline_imports(module, files.text(module.file), &names, dialect);
    }
    let resolved = resolve_names(&modules, &names, &roots, dialect, &mut problems);
    if problems.is_empty() {
        let cycles = if dialect == Dialect::Wesl {
            Cycles::Allowed
        } else {
            Cycles::Refused
        };
        problems.extend(
            check_graph(
                &modules,
                &paths,
                &resolved,
                options.max_import_depth,
                cycles,
            )
            .into_iter()
            .map(Into::into),
        );
    }
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    let tree = super::declared::Tree {
        modules: &modules,
        resolved: &resolved,
        files: &files,
    };
    let mut warnings = super::declared::apply_module_constants(&mut decl, &tree, &mut problems);
    warnings.extend(super::declared::unread_keywords(
        &decl,
        &tree,
        &mut problems,
    ));
    if dialect == Dialect::NagaOil {
        warnings.extend(super::declared::false_ifdefs(&decl, &tree));
    }
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    for (path, span) in decl.exclude.iter().filter(|(e, _)| unmatched.contains(e)) {
        warnings.push(
            crate::diagnostic::Diagnostic::new(format!(
                "exclude entry `{path}` matches no file or folder of the tree"
            ))
            .warning()
            .at(*span, "leaves out nothing"),
        );
    }
    let decls = decl
        .shaders
        .into_iter()
        .zip(entries)
        .map(|(shader, id)| {
            // Every entry was found (no problem so far).
            let id = id.unwrap_or_default();
            let passes = shader
                .passes
                .into_iter()
                .map(|mut p| {
                    p.body = modules[p.module.unwrap_or(id)].body.clone();
                    p
                })
                .collect();
            let decl = ShaderDecl {
                name: shader.name,
                span: shader.span,
                passes,
            };
            (decl, modules[id].file, id)
        })
        .collect();
    let mut loaded = assemble(files, paths, modules, resolved, decls, problems)?;
    loaded.warnings = warnings;
    loaded.dialect = dialect;
    loaded.wesl = decl_wesl;
    loaded.profiles = decl_profiles;
    Ok(loaded)
}

/// The loaded library: its shaders built from `decls` (each with its file and the module its
/// passes compose) when no problem was found so far, or every problem.
fn assemble(
    files: SourceFiles,
    paths: Vec<String>,
    modules: Vec<ParsedModule>,
    resolved: Vec<Vec<usize>>,
    decls: Vec<(ShaderDecl, crate::diagnostic::FileId, usize)>,
    mut problems: Vec<LoadProblem>,
) -> Result<Loaded, LoadError> {
    let shaders = if problems.is_empty() {
        build_shaders(decls, &mut problems)
    } else {
        Vec::new()
    };
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    Ok(Loaded {
        dialect: Dialect::WgslVariants,
        wesl: Default::default(),
        profiles: Vec::new(),
        warnings: Vec::new(),
        files,
        modules,
        paths,
        resolved,
        shaders,
    })
}

/// Decodes and parses every module file in `dialect`; module ids are file ids.
fn parse_all(
    raw: Vec<RawFile>,
    dialect: Dialect,
    options: &LoadOptions,
) -> Result<(SourceFiles, Vec<String>, Vec<ParsedModule>), LoadError> {
    let mut files = SourceFiles::new();
    let total: usize = raw.iter().map(|f| f.bytes.len()).sum();
    if total > options.max_total_bytes {
        let problems = vec![LoadProblem::Link(LinkError::TooLarge {
            bytes: total,
            limit: options.max_total_bytes,
        })];
        return Err(LoadError { files, problems });
    }
    let paths: Vec<String> = raw
        .iter()
        .map(|f| {
            f.path
                .strip_suffix(".wgsl")
                .or_else(|| f.path.strip_suffix(".wesl"))
                .unwrap_or(&f.path)
                .to_string()
        })
        .collect();
    let (ids, decode_errors) = source::decode(raw, &mut files);
    let mut problems: Vec<LoadProblem> = decode_errors.into_iter().map(Into::into).collect();
    let parsed: Vec<Result<ParsedModule, Vec<ParseError>>> = ids
        .par_iter()
        .map(|&id| parse_module_in(dialect, id, files.text(id), options.parse))
        .collect();
    let mut modules = Vec::with_capacity(parsed.len());
    for result in parsed {
        match result {
            Ok(m) => modules.push(m),
            Err(errs) => problems.extend(errs.into_iter().map(Into::into)),
        }
    }
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    Ok((files, paths, modules))
}

/// Resolves `#import path/of/file` by path (this crate's dialect).
fn resolve_paths(
    modules: &[ParsedModule],
    paths: &[String],
    escaping: &[String],
    problems: &mut Vec<LoadProblem>,
) -> Vec<Vec<usize>> {
    let by_path: HashMap<&str, usize> = paths
        .iter()
        .enumerate()
        .map(|(i, p)| (p.as_str(), i))
        .collect();
    let mut resolved = Vec::with_capacity(modules.len());
    for module in modules {
        let mut targets = Vec::with_capacity(module.imports.len());
        for import in &module.imports {
            match by_path.get(import.path.as_str()) {
                Some(&t) => targets.push(t),
                None => {
                    let file = format!("{}.wgsl", import.path);
                    let error = if escaping
                        .iter()
                        .any(|e| *e == file || import.path.starts_with(&format!("{e}/")))
                    {
                        LinkError::LeavesRoot {
                            path: import.path.clone(),
                            span: import.span,
                        }
                    } else {
                        let dir = format!("{}/", import.path);
                        let reason = if paths.iter().any(|p| p.starts_with(&dir)) {
                            format!("`{}` is a directory, not a module", import.path)
                        } else {
                            let hint = crate::diagnostic::did_you_mean(
                                &import.path,
                                paths.iter().map(String::as_str),
                            );
                            format!("no file `{file}` in the library{hint}")
                        };
                        LinkError::MissingImport {
                            path: import.path.clone(),
                            reason,
                            span: import.span,
                        }
                    };
                    problems.push(error.into());
                    targets.push(usize::MAX);
                }
            }
        }
        resolved.push(targets);
    }
    resolved
}

/// The extension of a dialect's module files.
fn extension(dialect: Dialect) -> &'static str {
    if dialect == Dialect::Wesl {
        "wesl"
    } else {
        "wgsl"
    }
}

/// WESL: a module's name is its package and its path in the package: `a/b.wesl` is
/// `package::a::b`, and in a tree whose declaration maps the package `bevy_render` to the
/// folder `bevy_render/src`, `bevy_render/src/maths.wesl` is `bevy_render::maths`. Its
/// imports are made absolute ([`wesl_absolute`]).
fn wesl_module_paths(
    modules: &mut [ParsedModule],
    paths: &[String],
    packages: &[(String, String)],
) {
    for (m, path) in modules.iter_mut().zip(paths) {
        // The deepest package folder holding the file.
        let package = packages
            .iter()
            .filter_map(|(name, folder)| {
                let rest = path.strip_prefix(folder.as_str())?.strip_prefix('/')?;
                Some((folder.len(), name.as_str(), rest))
            })
            .max_by_key(|(len, _, _)| *len);
        let name = match package {
            Some((_, package, rest)) => format!("{package}::{}", rest.replace('/', "::")),
            None => format!("package::{}", path.replace('/', "::")),
        };
        for import in &mut m.imports {
            import.path = wesl_absolute(&name, &import.path);
        }
        m.import_name = Some((name, crate::diagnostic::Span::new(m.file, 0..0)));
    }
}

/// A WESL path as written in the module named `module`, made absolute: `package::x` names
/// the module's own package, `self::` / `super::` are relative to the module's name (each
/// `super` drops one component, as `wesl` joins relative paths); other packages' paths are
/// already absolute.
fn wesl_absolute(module: &str, path: &str) -> String {
    let mut base: Vec<&str> = module.split("::").collect();
    if let Some(rest) = path.strip_prefix("package::") {
        return format!("{}::{rest}", base[0]);
    }
    let relative = path.starts_with("super::") || path.starts_with("self::");
    if !relative {
        return path.to_string();
    }
    let mut rest = path.strip_prefix("self::").unwrap_or(path);
    while let Some(r) = rest.strip_prefix("super::") {
        // A package itself has no parent: such a path names nothing.
        if base.len() > 1 {
            base.pop();
        }
        rest = r;
    }
    format!("{}::{rest}", base.join("::"))
}

/// naga_oil: the modules each `#define_import_path` name belongs to (more than one is an
/// error once a composed module imports the name).
fn import_names(modules: &[ParsedModule]) -> HashMap<String, Vec<usize>> {
    let mut names: HashMap<String, Vec<usize>> = HashMap::new();
    for (id, m) in modules.iter().enumerate() {
        if let Some((name, _)) = &m.import_name {
            names.entry(name.clone()).or_default().push(id);
        }
    }
    names
}

/// The module a naga_oil path names: its longest prefix that is an import path (`a::b::f`
/// is item `f` of module `a::b`).
fn module_of<'n>(path: &str, names: &'n HashMap<String, Vec<usize>>) -> Option<&'n [usize]> {
    let mut end = path.len();
    loop {
        if let Some(m) = names.get(&path[..end]) {
            return Some(m);
        }
        end = path[..end].rfind("::")?;
    }
}

/// naga_oil: resolves each `#import` of the modules the `entries` reach to the module its
/// path (or a prefix of it) names. Modules no entry reaches are not part of any declared
/// shader: their imports are left unresolved and unchecked (naga_oil never reads them).
fn resolve_names(
    modules: &[ParsedModule],
    names: &HashMap<String, Vec<usize>>,
    entries: &[usize],
    dialect: Dialect,
    problems: &mut Vec<LoadProblem>,
) -> Vec<Vec<usize>> {
    let mut resolved: Vec<Option<Vec<usize>>> = vec![None; modules.len()];
    // An ambiguous name is reported once, however many modules import it.
    let mut ambiguous: Vec<usize> = Vec::new();
    let mut queue: Vec<usize> = entries.to_vec();
    while let Some(m) = queue.pop() {
        if resolved[m].is_some() {
            continue;
        }
        let targets = modules[m]
            .imports
            .iter()
            .map(|import| match module_of(&import.path, names) {
                Some(&[t]) => t,
                Some(found) => {
                    if ambiguous.contains(&found[0]) {
                        return found[0];
                    }
                    ambiguous.push(found[0]);
                    let at = |t: usize| modules[t].import_name.as_ref().map_or(import.span, |n| n.1);
                    problems.push(
                        LinkError::DuplicateImportPath {
                            name: modules[found[0]]
                                .import_name
                                .as_ref()
                                .map_or_else(String::new, |n| n.0.clone()),
                            span: at(found[1]),
                            first: at(found[0]),
                        }
                        .into(),
                    );
                    found[0]
                }
                None => {
                    let hint = crate::diagnostic::did_you_mean(&import.path, names.keys().map(String::as_str));
                    let reason = match dialect {
                        Dialect::Wesl if names.keys().any(|n| n.split("::").next() == import.path.split("::").next()) => format!(
                            "no module of its package is this path or a prefix of it (`package::a::b` is the file `a/b.wesl` or `a/b.wgsl` of the module's package){hint}"
                        ),
                        Dialect::Wesl => {
                            // A misspelt package: the closest declared package name.
                            let (head, rest) =
                                import.path.split_once("::").unwrap_or((&import.path, ""));
                            let packages: std::collections::BTreeSet<&str> =
                                names.keys().filter_map(|n| n.split("::").next()).collect();
                            let hint = suggest(head, packages)
                                .map(|p| format!("; did you mean `{p}::{rest}`?"))
                                .unwrap_or(hint);
                            format!(
                                "no package of this name is declared (the declaration file's `[packages]` maps each package name to a folder of the tree){hint}"
                            )
                        }
                        _ => format!(
                            "no module of the tree has this `#define_import_path` or a prefix of it{hint}"
                        ),
                    };
                    problems.push(
                        LinkError::MissingImport {
                            path: import.path.clone(),
                            reason,
                            span: import.span,
                        }
                        .into(),
                    );
                    usize::MAX
                }
            })
            .collect::<Vec<usize>>();
        queue.extend(targets.iter().copied().filter(|&t| t != usize::MAX));
        resolved[m] = Some(targets);
    }
    resolved
        .into_iter()
        .map(Option::unwrap_or_default)
        .collect()
}

/// naga_oil: items used by their full path (`my_lib::lighting::shade(…)`) import their module
/// without an `#import` line; each such use becomes an import before its run of lines, under
/// the same conditions, so the import graph and the audit see it.
fn inline_imports(
    module: &mut ParsedModule,
    text: &str,
    names: &HashMap<String, Vec<usize>>,
    dialect: Dialect,
) {
    let ParsedModule {
        file,
        body,
        lines,
        comment_only,
        imports,
        import_name,
        ..
    } = module;
    // WESL paths are relative to the module (`package::`, `super::`).
    let own = import_name
        .as_ref()
        .filter(|_| dialect == Dialect::Wesl)
        .map(|(n, _)| n.as_str());
    let absolute = |path: &str| own.map_or_else(|| path.to_string(), |m| wesl_absolute(m, path));
    add_inline(
        body,
        (*file, text),
        (lines, comment_only),
        imports,
        &|path| {
            let path = absolute(path);
            module_of(&path, names).map(|m| (m[0], path))
        },
    );
}

fn add_inline(
    nodes: &mut Vec<Node>,
    (file, text): (crate::diagnostic::FileId, &str),
    (lines, comment_only): (&[std::ops::Range<u32>], &[bool]),
    imports: &mut Vec<ImportRef>,
    module_of: &dyn Fn(&str) -> Option<(usize, String)>,
) {
    let mut out = Vec::with_capacity(nodes.len());
    for mut node in std::mem::take(nodes) {
        match &mut node {
            Node::Text(run) => {
                let mut seen = Vec::new();
                for (i, line) in lines[run.start as usize..run.end as usize]
                    .iter()
                    .enumerate()
                {
                    if comment_only[run.start as usize + i] {
                        continue;
                    }
                    let start = line.start as usize;
                    // Paths in comments import nothing.
                    let code = text[start..line.end as usize]
                        .split("//")
                        .next()
                        .unwrap_or("");
                    for (at, path) in qualified_paths(code) {
                        if let Some((m, full)) = module_of(path)
                            && !seen.contains(&m)
                        {
                            seen.push(m);
                            out.push(Node::Import(imports.len()));
                            imports.push(ImportRef {
                                path: full,
                                span: crate::diagnostic::Span::new(
                                    file,
                                    start + at..start + at + path.len(),
                                ),
                            });
                        }
                    }
                }
            }
            Node::If(cond) => {
                for (_, branch) in &mut cond.branches {
                    add_inline(
                        branch,
                        (file, text),
                        (lines, comment_only),
                        imports,
                        module_of,
                    );
                }
                add_inline(
                    &mut cond.otherwise,
                    (file, text),
                    (lines, comment_only),
                    imports,
                    module_of,
                );
            }
            _ => {}
        }
        out.push(node);
    }
    *nodes = out;
}

/// `a::b::c` paths in a line of WGSL (names joined by `::`), with their byte offsets.
fn qualified_paths(line: &str) -> Vec<(usize, &str)> {
    let bytes = line.as_bytes();
    let is_name = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if is_name(bytes[i]) && (i == 0 || !is_name(bytes[i - 1])) {
            let start = i;
            let mut end = i;
            let mut parts = 0;
            loop {
                while end < bytes.len() && is_name(bytes[end]) {
                    end += 1;
                }
                parts += 1;
                if line[end..].starts_with("::") && bytes.get(end + 2).is_some_and(|&b| is_name(b))
                {
                    end += 2;
                } else {
                    break;
                }
            }
            if parts > 1 {
                out.push((start, &line[start..end]));
            }
            i = end.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// Whether modules may import each other in a circle: WESL's may, this crate's dialect's and
/// naga_oil's may not.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Cycles {
    Allowed,
    Refused,
}

/// Finds import cycles (where `cycles` refuses them) and chains deeper than `limit`, without
/// recursion (trees can hold thousands of modules).
fn check_graph(
    modules: &[ParsedModule],
    paths: &[String],
    resolved: &[Vec<usize>],
    limit: usize,
    cycles: Cycles,
) -> Vec<LinkError> {
    #[derive(Clone, Copy, PartialEq)]
    enum State {
        New,
        Open,
        Done,
    }
    let mut state = vec![State::New; modules.len()];
    let mut depth = vec![0usize; modules.len()];
    let mut errors = Vec::new();
    for root in 0..modules.len() {
        if state[root] != State::New {
            continue;
        }
        let mut stack: Vec<(usize, usize)> = vec![(root, 0)];
        state[root] = State::Open;
        while let Some(&mut (m, ref mut next)) = stack.last_mut() {
            if let Some(&t) = resolved[m].get(*next) {
                let import = *next;
                *next += 1;
                match state[t] {
                    State::New => {
                        state[t] = State::Open;
                        stack.push((t, 0));
                    }
                    // WESL modules may import each other (only declarations may not depend on
                    // themselves, which `wesl` checks); every walk of the graph includes a
                    // module once, so a cycle ends there.
                    State::Open if cycles == Cycles::Allowed => {}
                    State::Open => {
                        let from = stack.iter().position(|&(s, _)| s == t).unwrap_or(0);
                        let mut cycle: Vec<(String, _)> = stack[from..]
                            .iter()
                            .map(|&(s, n)| (paths[s].clone(), modules[s].imports[n - 1].span))
                            .collect();
                        if let Some(last) = cycle.last_mut() {
                            last.1 = modules[m].imports[import].span;
                        }
                        cycle.push((
                            paths[t].clone(),
                            modules[t]
                                .imports
                                .first()
                                .map_or(modules[m].imports[import].span, |i| i.span),
                        ));
                        errors.push(LinkError::Cycle { cycle });
                    }
                    State::Done => {
                        if depth[t] + 1 > limit && errors.is_empty() {
                            errors.push(LinkError::TooDeep {
                                limit,
                                span: modules[m].imports[import].span,
                            });
                        }
                        depth[m] = depth[m].max(depth[t] + 1);
                    }
                }
            } else {
                state[m] = State::Done;
                stack.pop();
                if let Some(&(parent, n)) = stack.last() {
                    depth[parent] = depth[parent].max(depth[m] + 1);
                    if depth[parent] > limit && errors.is_empty() {
                        errors.push(LinkError::TooDeep {
                            limit,
                            span: modules[parent].imports[n - 1].span,
                        });
                    }
                }
            }
        }
    }
    errors
}

/// Builds the shaders of `decls` (each with its file and the module its passes compose).
fn build_shaders(
    decls: Vec<(ShaderDecl, crate::diagnostic::FileId, usize)>,
    problems: &mut Vec<LoadProblem>,
) -> Vec<Shader> {
    let mut shaders: Vec<Shader> = Vec::new();
    let mut first_span = HashMap::new();
    for (decl, file, id) in decls {
        if let Some(&first) = first_span.get(&decl.name) {
            problems.push(
                LinkError::DuplicateShader {
                    name: decl.name.clone(),
                    span: decl.span,
                    first,
                }
                .into(),
            );
            continue;
        }
        first_span.insert(decl.name.clone(), decl.span);
        let mut passes: Vec<Pass> = Vec::new();
        let mut pass_spans = HashMap::new();
        for pass in decl.passes {
            if let Some(&first) = pass_spans.get(&pass.name) {
                problems.push(
                    LinkError::DuplicatePass {
                        shader: decl.name.clone(),
                        name: pass.name.clone(),
                        span: pass.span,
                        first,
                    }
                    .into(),
                );
                continue;
            }
            pass_spans.insert(pass.name.clone(), pass.span);
            // The constraints are checked against the pass's whole space, which only a built
            // pass has.
            match Pass::new(&decl.name, pass.module.unwrap_or(id), pass).and_then(|p| {
                crate::variants::check_constraints(&p)
                    .map(|()| p)
                    .map_err(|e| vec![e])
            }) {
                Ok(p) => passes.push(p),
                Err(errs) => problems.extend(errs.into_iter().map(Into::into)),
            }
        }
        shaders.push(Shader {
            name: decl.name,
            passes,
            file,
        });
    }
    shaders
}
