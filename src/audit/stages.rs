//! Defs a pipeline stage reads but is never given: a pass split into stages (a declaration
//! file's `stages`) composes each stage with the defs of its own keywords, as Bevy's render
//! pipelines push one def list to the vertex state and another to the fragment state. A def
//! pushed to the fragment stage only, but tested by code the vertex entry point runs, is a
//! branch that is never built: in Bevy 0.19 and 0.20 the 3D line gizmo's vertex `#ifdef
//! PERSPECTIVE` is one (`PERSPECTIVE` is pushed to the fragment state only).
//!
//! Found by composing, not by reading: for each keyword of a stage whose defs go to other
//! stages only, one variant with the keyword on (from the pass's 1-wise covering set) is
//! composed twice — as the stage gets it, and with the keyword's defs pushed to this stage
//! too — and the items the stage's entry points reach are compared ([`crate::reach`]). Only
//! keywords whose defs the stage's modules mention are tried, so the cost is two
//! compositions per such keyword.

use std::collections::BTreeMap;

use crate::library::{Library, Variant};
use crate::shader::Pass;
use crate::variants::Space;

/// A keyword whose defs change the code a stage runs, though the pass pushes them to other
/// stages only.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct UnpushedDefs {
    /// The keyword.
    pub keyword: String,
    /// The stages its defs are pushed to.
    pub pushed_to: Vec<crate::stage::PipelineStage>,
    /// The items of this stage's program (as composed) that its defs would change.
    pub changes: Vec<String>,
    /// The variant compared (its keywords).
    pub variant: String,
}

/// For a stage of a split pass, the keywords pushed to its other stages only whose defs would
/// change the code this stage's entry points run (empty for a pass that is not a stage).
pub fn unpushed_defs(lib: &Library, pass: &Pass) -> Vec<UnpushedDefs> {
    let Some(stage) = pass.stage else {
        return Vec::new();
    };
    let Some((declared, _)) = pass.name.rsplit_once('/') else {
        return Vec::new();
    };
    let siblings: Vec<&Pass> = lib
        .shader(&pass.shader)
        .map(|s| {
            s.passes
                .iter()
                .filter(|p| p.stage.is_some_and(|s| s != stage))
                .filter(|p| p.name.rsplit_once('/').is_some_and(|(d, _)| d == declared))
                .collect()
        })
        .unwrap_or_default();
    let graph = lib.module_graph();
    let reached = graph.reach(pass.module);
    let mut cover = None;
    let mut out = Vec::new();
    for keyword in pass.keywords() {
        if keyword == "_" || !pass.keyword_defs(keyword).is_empty() {
            continue;
        }
        // The defs another stage gets for it (every stage shares the pass's keywords).
        let mut pushed_to = Vec::new();
        let mut defs = Vec::new();
        for s in &siblings {
            let d = s.keyword_defs(keyword);
            if !d.is_empty() {
                pushed_to.extend(s.stage);
                defs = s.options.get(keyword).cloned().unwrap_or_else(|| {
                    let (name, value) = crate::declaration::def_of(keyword);
                    vec![crate::declaration::Constant {
                        name: name.to_string(),
                        value,
                    }]
                });
            }
        }
        if defs.is_empty() || !defs.iter().any(|d| graph.mentions(&reached, &d.name)) {
            continue;
        }
        let cover = cover.get_or_insert_with(|| Space::full(pass).covering(1).unwrap_or_default());
        let Some(choice) = cover.iter().find(|c| c.keywords(pass).contains(&keyword)) else {
            continue;
        };
        let mut given = pass.clone();
        given.options.insert(keyword.to_string(), defs);
        let as_is = lib.compose_text(&Variant {
            pass,
            choice: choice.clone(),
        });
        let pushed = lib.compose_text(&Variant {
            pass: &given,
            choice: choice.clone(),
        });
        if as_is.failure.is_some() || pushed.failure.is_some() {
            continue;
        }
        let (Some(a), Some(b)) = (
            crate::reach::stage_items(&as_is.text, stage),
            crate::reach::stage_items(&pushed.text, stage),
        ) else {
            continue;
        };
        let changes = changed_items(&a, &b);
        if !changes.is_empty() {
            out.push(UnpushedDefs {
                keyword: keyword.to_string(),
                pushed_to,
                changes,
                variant: choice.label(pass),
            });
        }
    }
    out
}

/// The names of the items that differ between two programs (added, removed or changed), in
/// the order of the first; a nameless item by its first line.
fn changed_items(a: &[(Option<String>, String)], b: &[(Option<String>, String)]) -> Vec<String> {
    let key = |(name, text): &(Option<String>, String)| {
        name.clone()
            .unwrap_or_else(|| text.lines().next().unwrap_or("").trim().to_string())
    };
    let index = |items: &[(Option<String>, String)]| -> BTreeMap<String, String> {
        items.iter().map(|i| (key(i), i.1.clone())).collect()
    };
    let (ia, ib) = (index(a), index(b));
    let mut out: Vec<String> = Vec::new();
    for item in a.iter().chain(b) {
        let k = key(item);
        if ia.get(&k) != ib.get(&k) && !out.contains(&k) {
            out.push(k);
        }
    }
    out
}
