//! A pass's `stages` table: the pass split into one pass per pipeline stage, each composing
//! its own entry module with the defs of its own keywords (see [`crate::stage`]).
//!
//! ```toml
//! [[shader.pass]]
//! name = "Forward"
//! use = ["mesh_pipeline"]
//! shader_feature = [["_", "NORMAL_MAP"]]
//! [shader.pass.stages.vertex]
//! entry = "render/mesh.wesl"
//! use = ["mesh_pipeline"]          # the defs of the block's keywords reach the vertex stage
//! [shader.pass.stages.fragment]
//! entry = "render/pbr.wesl"        # no `keywords` nor `use`: every keyword's defs
//! ```
//!
//! Every stage keeps the pass's whole keyword space (so a keyword set is judged by all its
//! stages alike); a keyword whose defs do not reach a stage is, in that stage, an option that
//! sets no def.

use std::collections::BTreeSet;

use toml::Spanned;

use super::DeclarationError;
use super::pass::{Shared, StageToml, StagesToml, at_file, declared_keywords, keyword_names};
use crate::diagnostic::Span;
use crate::preprocess::tree::PassDecl;
use crate::stage::PipelineStage;

/// `decl` split into one pass per stage of `stages`, in pipeline order; `decl` itself when
/// the pass has no `stages`. `uses` are the blocks the pass uses.
pub(super) fn split(
    decl: PassDecl,
    stages: StagesToml,
    uses: &[Spanned<String>],
    shared: &Shared<'_>,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
    errors: &mut Vec<DeclarationError>,
) -> Vec<PassDecl> {
    if stages.is_empty() {
        return vec![decl];
    }
    let declared = declared_keywords(&decl.pragmas);
    let mut split: Vec<(PipelineStage, PassDecl)> = Vec::new();
    for (name, stage) in stages {
        let Some(kind) = PipelineStage::from_name(name.get_ref()) else {
            let hint = crate::diagnostic::did_you_mean(
                name.get_ref(),
                PipelineStage::ALL.iter().map(|s| s.name()),
            );
            errors.push(DeclarationError {
                message: format!(
                    "pass `{}` has a stage `{}`: a pass's stages are `vertex` and `fragment`{hint}",
                    decl.name,
                    name.get_ref()
                ),
                span: at(name.span()),
            });
            continue;
        };
        let pass = PassParts {
            name: &decl.name,
            declared: &declared,
            uses,
            shared,
        };
        let reached = reached(&pass, kind, &stage, at, errors);
        let mut d = decl.clone();
        d.name = format!("{}/{}", decl.name, kind.name());
        d.span = at(name.span());
        if let Some(e) = &stage.entry {
            d.entry = Some((e.get_ref().clone(), at(e.span())));
        }
        for k in declared.iter().filter(|k| !reached.contains(k.as_str())) {
            d.options.insert(k.clone(), Vec::new());
        }
        d.stage = Some(kind);
        split.push((kind, d));
    }
    split.sort_by_key(|(kind, _)| *kind);
    split.into_iter().map(|(_, d)| d).collect()
}

/// What a stage's keywords are checked against: the pass's name, declared keywords and
/// blocks.
#[derive(Clone, Copy)]
struct PassParts<'d, 's> {
    name: &'s str,
    declared: &'d [String],
    uses: &'s [Spanned<String>],
    shared: &'s Shared<'s>,
}

/// The keywords of `declared` whose defs reach `stage` (of kind `kind`): those it names
/// (`keywords`, and the keywords of the blocks in its `use`); when it names none, every
/// keyword but those of blocks whose `stages` leave this one out.
fn reached<'d>(
    pass: &PassParts<'d, '_>,
    kind: PipelineStage,
    stage: &StageToml,
    at: impl Fn(std::ops::Range<usize>) -> Span + Copy,
    errors: &mut Vec<DeclarationError>,
) -> BTreeSet<&'d str> {
    let PassParts {
        name: pass_name,
        declared,
        uses,
        shared,
    } = *pass;
    if stage.keywords.is_none() && stage.uses.is_empty() {
        // Every keyword, but those of the blocks the pass uses that name other stages only.
        let elsewhere: BTreeSet<String> = shared
            .blocks
            .iter()
            .filter(|b| uses.iter().any(|u| u.get_ref() == b.name.get_ref()))
            .filter(|b| {
                b.block
                    .stages
                    .as_ref()
                    .is_some_and(|s| !s.get_ref().iter().any(|s| s.get_ref() == kind.name()))
            })
            .flat_map(|b| keyword_names(b.block, at_file(b.file)))
            .collect();
        return declared
            .iter()
            .map(String::as_str)
            .filter(|k| !elsewhere.contains(*k))
            .collect();
    }
    let mut named: Vec<(String, Span)> = Vec::new();
    for k in stage.keywords.iter().flatten() {
        named.push((k.get_ref().clone(), at(k.span())));
    }
    for b in &stage.uses {
        let block = shared
            .block(b.get_ref())
            .filter(|_| uses.iter().any(|u| u.get_ref() == b.get_ref()));
        match block {
            Some(block) => named.extend(
                keyword_names(block.block, at_file(block.file))
                    .into_iter()
                    .map(|k| (k, at(b.span()))),
            ),
            None => {
                let hint = crate::diagnostic::did_you_mean(
                    b.get_ref(),
                    uses.iter().map(|u| u.get_ref().as_str()),
                );
                errors.push(DeclarationError {
                    message: format!(
                        "a stage of pass `{}` uses block `{}`, which the pass does not use (its `use` list){hint}",
                        pass_name,
                        b.get_ref()
                    ),
                    span: at(b.span()),
                });
            }
        }
    }
    let mut out = BTreeSet::new();
    for (name, span) in named {
        // A valued set is named by its def: every `NAME=VALUE` keyword of it.
        let matching: Vec<&str> = declared
            .iter()
            .map(String::as_str)
            .filter(|k| *k == name || k.split_once('=').is_some_and(|(d, _)| d == name))
            .collect();
        if matching.is_empty() {
            let hint = crate::diagnostic::did_you_mean(
                &name,
                declared
                    .iter()
                    .map(|k| k.split_once('=').map_or(k.as_str(), |(d, _)| d)),
            );
            errors.push(DeclarationError {
                message: format!(
                    "a stage of pass `{pass_name}` names keyword `{name}`, which the pass does not declare{hint}"
                ),
                span,
            });
        }
        out.extend(matching);
    }
    out
}

/// Checks the `stages` list of every block: each a stage name.
pub(super) fn check_block_stages(shared: &Shared<'_>, errors: &mut Vec<DeclarationError>) {
    for b in &shared.blocks {
        let at = at_file(b.file);
        for s in b.block.stages.iter().flat_map(|s| s.get_ref()) {
            if PipelineStage::from_name(s.get_ref()).is_none() {
                let hint = crate::diagnostic::did_you_mean(
                    s.get_ref(),
                    PipelineStage::ALL.iter().map(|s| s.name()),
                );
                errors.push(DeclarationError {
                    message: format!(
                        "block `{}` names a stage `{}`: the stages are `vertex` and `fragment`{hint}",
                        b.name.get_ref(),
                        s.get_ref()
                    ),
                    span: at(s.span()),
                });
            }
        }
    }
}
