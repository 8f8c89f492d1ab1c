//! Loading: decode files, parse every module, resolve imports, check the import graph, and
//! assemble shaders.

use std::collections::HashMap;

use rayon::prelude::*;

use crate::diagnostic::SourceFiles;
use crate::lookup::suggest;
use crate::preprocess::tree::ParsedModule;
use crate::preprocess::{ParseError, ParseLimits, parse_module};
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
        .map(|f| f.path.strip_suffix(".wgsl").unwrap_or(&f.path).to_string())
        .collect();
    let (ids, decode_errors) = source::decode(raw, &mut files);
    let mut problems: Vec<LoadProblem> = decode_errors.into_iter().map(Into::into).collect();
    let parsed: Vec<Result<ParsedModule, Vec<ParseError>>> = ids
        .par_iter()
        .map(|&id| parse_module(id, files.text(id), options.parse))
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
    // Module ids are file ids here: every file decoded and parsed.
    let by_path: HashMap<&str, usize> = paths
        .iter()
        .enumerate()
        .map(|(i, p)| (p.as_str(), i))
        .collect();
    let mut resolved = Vec::with_capacity(modules.len());
    for module in &modules {
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
                            let hint = suggest(&import.path, paths.iter().map(String::as_str))
                                .map(|s| format!("; did you mean `{s}`?"))
                                .unwrap_or_default();
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
    if problems.is_empty() {
        problems.extend(
            check_graph(&modules, &paths, &resolved, options.max_import_depth)
                .into_iter()
                .map(Into::into),
        );
    }
    let shaders = if problems.is_empty() {
        build_shaders(&mut modules, &mut problems)
    } else {
        Vec::new()
    };
    if !problems.is_empty() {
        return Err(LoadError { files, problems });
    }
    Ok(Loaded {
        files,
        modules,
        paths,
        resolved,
        shaders,
    })
}

/// Finds import cycles and chains deeper than `limit`, without recursion (trees can hold
/// thousands of modules).
fn check_graph(
    modules: &[ParsedModule],
    paths: &[String],
    resolved: &[Vec<usize>],
    limit: usize,
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

fn build_shaders(modules: &mut [ParsedModule], problems: &mut Vec<LoadProblem>) -> Vec<Shader> {
    let mut shaders: Vec<Shader> = Vec::new();
    let mut first_span = HashMap::new();
    for (id, module) in modules.iter_mut().enumerate() {
        let Some(decl) = module.shader.take() else {
            continue;
        };
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
            match Pass::new(&decl.name, id, pass) {
                Ok(p) => passes.push(p),
                Err(errs) => problems.extend(errs.into_iter().map(Into::into)),
            }
        }
        shaders.push(Shader {
            name: decl.name,
            passes,
            file: module.file,
        });
    }
    shaders
}
