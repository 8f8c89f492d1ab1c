//! A declaration file checked against the tree it declares, once imports are resolved: the
//! defs set on single modules reach the passes that compose them, and keywords, options and
//! `false` defs that the modules do not read as declared are reported.

use std::collections::{BTreeMap, BTreeSet};

use crate::declaration::{Constant, Declaration, DeclarationError, DefValue};
use crate::diagnostic::{Diagnostic, SourceFiles, Span};
use crate::preprocess::tree::{ParsedModule, PassDecl, Pragma};

use super::error::LoadProblem;

/// The parsed tree a declaration is checked against.
pub(super) struct Tree<'t> {
    /// Every module.
    pub modules: &'t [ParsedModule],
    /// Each module's resolved imports.
    pub resolved: &'t [Vec<usize>],
    /// The source files.
    pub files: &'t SourceFiles,
}

impl Tree<'_> {
    /// The modules `entry` reaches, `entry` first.
    fn reach(&self, entry: usize) -> Vec<usize> {
        crate::preprocess::compose::reach(self.resolved, entry)
    }

    /// Whether `name` appears as a whole word in one of `modules`.
    fn mentions(&self, modules: &[usize], name: &str) -> bool {
        crate::preprocess::compose::ModuleGraph {
            modules: self.modules,
            resolved: self.resolved,
            files: self.files,
        }
        .mentions(modules, name)
    }
}

/// The declared keywords of a pass, with where each is written (`_` left out).
fn declared(pass: &PassDecl) -> impl Iterator<Item = &(Box<str>, Span)> {
    pass.pragmas
        .iter()
        .filter_map(|p| match p {
            Pragma::Keywords { names, .. } => Some(names),
            _ => None,
        })
        .flatten()
        .filter(|(k, _)| &**k != "_")
}

/// The defs keyword `k` of `pass` sets: its option's, or its own.
fn defs_of<'p>(pass: &'p PassDecl, k: &'p str) -> Vec<(&'p str, DefValue)> {
    match pass.options.get(k) {
        Some(defs) => defs.iter().map(|c| (c.name.as_str(), c.value)).collect(),
        None => vec![crate::declaration::def_of(k)],
    }
}

/// Adds the defs of each `[modules."PATH"]` table to the constants of every pass whose entry
/// reaches that module (naga_oil applies a module's `shader_defs` to every shader that
/// imports it; Bevy 0.20 those of the whole composed closure). A path that names no module, a
/// def that is also a keyword of such a pass, and two values for one def are errors; a module
/// no pass reaches is a warning.
pub(super) fn apply_module_constants(
    decl: &mut Declaration,
    tree: &Tree<'_>,
    problems: &mut Vec<LoadProblem>,
) -> Vec<Diagnostic> {
    let mut warnings = Vec::new();
    let module_constants = std::mem::take(&mut decl.module_constants);
    let mut fail = |message: String, span: Span| {
        problems.push(DeclarationError { message, span }.into());
    };
    let paths: Vec<&str> = tree
        .modules
        .iter()
        .map(|m| tree.files.path(m.file))
        .collect();
    for mc in &module_constants {
        let Some(module) = paths.iter().position(|p| *p == mc.path) else {
            let hint = crate::diagnostic::did_you_mean(&mc.path, paths.iter().copied());
            fail(
                format!(
                    "`[modules.\"{}\"]` names no module of the tree (a path relative to the root, with its extension){hint}",
                    mc.path
                ),
                mc.span,
            );
            continue;
        };
        let mut reached_by = 0;
        for shader in &mut decl.shaders {
            for pass in &mut shader.passes {
                let Some(entry) = pass.module else { continue };
                if !tree.reach(entry).contains(&module) {
                    continue;
                }
                reached_by += 1;
                for c in &mc.constants {
                    let keyword = declared(pass)
                        .find(|(k, _)| defs_of(pass, k).iter().any(|(d, _)| *d == c.name));
                    if let Some((k, _)) = keyword {
                        fail(
                            format!(
                                "`{}` is set on module `{}` and by keyword `{k}` of `{}/{}`, which composes it: the module's value would hold in every variant",
                                c.name, mc.path, shader.name, pass.name
                            ),
                            mc.span,
                        );
                        continue;
                    }
                    match pass.constants.iter().find(|p| p.name == c.name) {
                        Some(p) if p.value != c.value => fail(
                            format!(
                                "`{}` is {} on module `{}` and {} for `{}/{}`, which composes it: a def has one value per composition (naga_oil refuses the two)",
                                c.name, c.value, mc.path, p.value, shader.name, pass.name
                            ),
                            mc.span,
                        ),
                        Some(_) => {}
                        None => pass.constants.push(Constant {
                            name: c.name.clone(),
                            value: c.value,
                        }),
                    }
                }
            }
        }
        if reached_by == 0 {
            warnings.push(
                Diagnostic::new(format!(
                    "no pass composes module `{}`: its defs change nothing",
                    mc.path
                ))
                .warning()
                .at(mc.span, "reached by no pass"),
            );
        }
    }
    warnings
}

/// Declared keywords that set no def a module of their pass reads (in a directive or a
/// substitution): they change no variant. A def (of a keyword or an option) within two edits
/// of a name the modules' conditions read, which the pass does not set, is a typo: an error
/// naming the name read (`problems`). The rest are one warning per group of passes, every such
/// keyword labelled: probably a def of another tree. An option with one def read changes
/// variants and is not reported (an engine pushes defs some trees do not read), nor is a
/// keyword of a block that one of the passes using it reads (a block is shared by passes, or
/// stages, that read different parts of it).
pub(super) fn unread_keywords(
    decl: &Declaration,
    tree: &Tree<'_>,
    problems: &mut Vec<LoadProblem>,
) -> Vec<Diagnostic> {
    // Per keyword as written (a block's keyword is written once for every pass using it):
    // the passes declaring it, and for those that read none of its defs the typo, if any.
    let mut found: BTreeMap<(Span, String), Unread> = BTreeMap::new();
    for shader in &decl.shaders {
        for pass in &shader.passes {
            let Some(entry) = pass.module else { continue };
            let reached = tree.reach(entry);
            // Names the conditions read that the pass neither declares nor sets.
            let mut read = BTreeSet::new();
            for &m in &reached {
                crate::preprocess::tree::names_read(&tree.modules[m].body, &mut read);
            }
            for (k, _) in declared(pass) {
                for (d, _) in defs_of(pass, k) {
                    read.remove(d);
                }
            }
            for c in &pass.constants {
                read.remove(c.name.as_str());
            }
            let label = format!("{}/{}", shader.name, pass.name);
            for (k, span) in declared(pass) {
                let defs = defs_of(pass, k);
                // A keyword whose defs go to another stage only is judged there.
                if defs.is_empty() {
                    continue;
                }
                let unread: Vec<&str> = defs
                    .iter()
                    .map(|(d, _)| *d)
                    .filter(|d| !tree.mentions(&reached, d))
                    .collect();
                let entry = found.entry((*span, k.to_string())).or_default();
                entry.declared += 1;
                if unread.is_empty() {
                    continue;
                }
                let option = pass.options.contains_key(&**k);
                for def in &unread {
                    let typo = read
                        .iter()
                        .map(|r| (strsim::levenshtein(def, r), r))
                        .filter(|(d, _)| *d <= 2)
                        .min();
                    if let Some((_, name)) = typo {
                        let what = if option {
                            format!("def `{def}` of option `{k}`")
                        } else {
                            format!("keyword `{k}`")
                        };
                        entry.typos.push(format!(
                            "{what} of `{label}` is read by none of the modules it composes, which read `{name}`: a typo?"
                        ));
                    }
                }
                if unread.len() == defs.len() {
                    entry.unread_by.push(label.clone());
                    entry.label = if option {
                        format!("{k} (sets {})", unread.join(", "))
                    } else {
                        k.to_string()
                    };
                }
            }
        }
    }
    // Keywords no pass declaring them reads, grouped by those passes.
    let mut groups: BTreeMap<Vec<String>, Vec<(String, Span)>> = BTreeMap::new();
    for ((span, _), unread) in found {
        for typo in unread.typos {
            problems.push(
                DeclarationError {
                    message: typo,
                    span,
                }
                .into(),
            );
        }
        if unread.unread_by.len() == unread.declared && !unread.label.is_empty() {
            groups
                .entry(unread.unread_by)
                .or_default()
                .push((unread.label, span));
        }
    }
    let mut warnings = Vec::new();
    for (passes, keywords) in groups {
        let list: Vec<&str> = keywords.iter().map(|(k, _)| k.as_str()).collect();
        let (of, composes) = match passes.as_slice() {
            [one] => (format!("`{one}`"), "it composes"),
            many => (
                many.iter()
                    .map(|p| format!("`{p}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                "they compose",
            ),
        };
        let mut warning = Diagnostic::new(format!(
            "{} declared keyword(s) of {of} appear in none of the modules {composes}: {}",
            list.len(),
            list.join(", ")
        ))
        .warning()
        .at(keywords[0].1, "never read");
        for (_, span) in &keywords[1..] {
            warning = warning.also(*span, "never read");
        }
        warnings.push(warning.note(
            "they change no variant: a typo, or a def of another tree? (the audit lists them as dead)",
        ));
    }
    warnings
}

/// What the passes declaring one keyword make of it.
#[derive(Default)]
struct Unread {
    /// How many passes declare it.
    declared: usize,
    /// The passes that read none of its defs.
    unread_by: Vec<String>,
    /// How the warning names it.
    label: String,
    /// Its defs that look like misspelt names the modules read.
    typos: Vec<String>,
}

/// Defs a pass sets to `false` (constants, valued keywords, options) that a module it
/// composes tests with `#ifdef`/`#ifndef`: naga_oil's `#ifdef` asks whether a def is set, not
/// its value, so the `false` def takes the branch meant for `true`. One warning per directive,
/// naming the passes.
pub(super) fn false_ifdefs(decl: &Declaration, tree: &Tree<'_>) -> Vec<Diagnostic> {
    // (file, directive's byte range, def) → passes
    let mut found: BTreeMap<(usize, usize, usize, String), Vec<String>> = BTreeMap::new();
    for shader in &decl.shaders {
        for pass in &shader.passes {
            let Some(entry) = pass.module else { continue };
            let mut falses: BTreeSet<&str> = pass
                .constants
                .iter()
                .filter(|c| c.value == DefValue::Bool(false))
                .map(|c| c.name.as_str())
                .collect();
            for (k, _) in declared(pass) {
                for (d, v) in defs_of(pass, k) {
                    if v == DefValue::Bool(false) {
                        falses.insert(d);
                    }
                }
            }
            if falses.is_empty() {
                continue;
            }
            for m in tree.reach(entry) {
                let file = tree.modules[m].file;
                for (range, def) in ifdefs(tree.files.text(file)) {
                    if falses.contains(def) {
                        found
                            .entry((file, range.start, range.end, def.to_string()))
                            .or_default()
                            .push(format!("{}/{}", shader.name, pass.name));
                    }
                }
            }
        }
    }
    found
        .into_iter()
        .map(|((file, start, end, def), passes)| {
            Diagnostic::new(format!(
                "`{def}` is `false` in {}, and `#ifdef` tests whether a def is set, not its value: the branch for a set `{def}` is taken",
                passes.join(", ")
            ))
            .warning()
            .at(Span::new(file, start..end), "true for a `false` def")
            .note(format!(
                "test the value (`#if {def} == true`), or leave `{def}` unset instead of `false`"
            ))
        })
        .collect()
}

/// Every `#ifdef NAME` / `#ifndef NAME` (also after `#else`) in `text`: the directive's byte
/// range and the name.
fn ifdefs(text: &str) -> Vec<(std::ops::Range<usize>, &str)> {
    let mut out = Vec::new();
    let mut at = 0;
    for line in text.split_inclusive('\n') {
        let start = at;
        at += line.len();
        let trimmed = line.trim();
        let directive = match trimmed.strip_prefix("#else") {
            Some(rest) => rest.trim_start(),
            None => trimmed.strip_prefix('#').unwrap_or_default(),
        };
        let Some(rest) = directive
            .strip_prefix("ifdef")
            .or_else(|| directive.strip_prefix("ifndef"))
        else {
            continue;
        };
        if !rest.starts_with([' ', '\t']) {
            continue;
        }
        let name = rest.split_whitespace().next().unwrap_or_default();
        let offset = line.len() - line.trim_start().len();
        out.push((start + offset..start + offset + trimmed.len(), name));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::ifdefs;

    #[test]
    fn ifdef_directives_are_found_with_their_names() {
        let text =
            "fn a() {}\n  #ifdef FOG\n#else ifndef SHADOWS // why\n#if FOG == true\n#ifdefX\n";
        let found = ifdefs(text);
        let names: Vec<&str> = found.iter().map(|f| f.1).collect();
        assert_eq!(names, ["FOG", "SHADOWS"]);
        assert_eq!(&text[found[0].0.clone()], "#ifdef FOG");
        assert_eq!(&text[found[1].0.clone()], "#else ifndef SHADOWS // why");
    }
}
