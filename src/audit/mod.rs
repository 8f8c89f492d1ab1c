//! The variant-explosion audit: per pass, the stage counts, the number of *distinct* variants
//! (keyword sets whose composed code is identical count once), dead keywords, keywords that
//! matter only together, and a per-set multiplier table with suggestions.
//!
//! Everything is exact and nothing enumerates the space: a static walk of the pass's
//! composition tree finds which keyword sets can change which part of the text, each small
//! group of coupled sets is enumerated on its own, and a check on the region outputs proves
//! that the distinct count is their product (see [`Method`]). Nothing here runs naga; only
//! the check of a split pass's stages ([`stages`]) composes, two programs per keyword it tries.
//!
//! ```
//! use wgsl_variants::{Library, audit};
//!
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let pass = lib.pass("standard", "Deferred").unwrap();
//! let report = audit::audit_pass(&lib, pass, &audit::AuditOptions::default()).unwrap();
//! assert_eq!(report.full_space, 110_592u32.into());
//! assert_eq!(report.distinct.count, 110_592u32.into());
//! assert!(report.distinct.exact && report.dead_keywords.is_empty());
//! ```

pub mod budget;
pub mod chart;
mod findings;
mod report;
pub mod stages;

use rayon::prelude::*;

use crate::library::Library;
use crate::materials::{self, Material, MaterialsError};
use crate::shader::Pass;
use crate::variants::Space;

use crate::analysis::compose::LineIds;
use crate::analysis::distinct::{self, Limits};

pub use crate::analysis::{Method, proves_all_distinct};

pub use report::{
    AuditReport, AuditTotals, AuditedPass, CodeGroup, Distinct, PassAudit, SetAudit, Together,
};

/// What to audit against, and the limits of the analysis.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct AuditOptions {
    /// Materials for the `shader_feature` stripping stage (the build set).
    pub materials: Option<Vec<Material>>,
    /// Most assignments enumerated for one group of coupled keyword sets.
    pub component_limit: u64,
    /// Most variants composed when the groups cannot give an exact count (the whole stage is
    /// then enumerated if it has at most this many variants; otherwise a bound is reported).
    pub enumeration_limit: u64,
}

impl Default for AuditOptions {
    fn default() -> Self {
        AuditOptions {
            materials: None,
            component_limit: crate::analysis::COMPONENT_LIMIT,
            enumeration_limit: 1_000_000,
        }
    }
}

/// Audits one pass.
pub fn audit_pass(
    lib: &Library,
    pass: &Pass,
    options: &AuditOptions,
) -> Result<PassAudit, MaterialsError> {
    let ids = LineIds::new(&lib.module_graph());
    audit_with(lib, &ids, pass, options)
}

/// Audits several passes (in parallel; the result is in the order given).
pub fn audit_passes(
    lib: &Library,
    passes: &[&Pass],
    options: &AuditOptions,
) -> Result<Vec<PassAudit>, MaterialsError> {
    if let Some(m) = &options.materials {
        materials::check(m, lib.shaders())?;
    }
    let ids = LineIds::new(&lib.module_graph());
    passes
        .par_iter()
        .map(|p| audit_with(lib, &ids, p, options))
        .collect()
}

fn audit_with<'p>(
    lib: &Library,
    ids: &LineIds,
    pass: &'p Pass,
    options: &AuditOptions,
) -> Result<PassAudit, MaterialsError> {
    let graph = lib.module_graph();
    let limits = Limits {
        component: options.component_limit,
        whole: options.enumeration_limit,
    };
    let features = match &options.materials {
        None => None,
        Some(m) => {
            materials::check(m, lib.shaders())?;
            Some(materials::feature_combinations(pass, m)?)
        }
    };
    let analyse = |s: Space<'p>| distinct::analyze(&graph, ids, pass, s, limits);
    let full = analyse(Space::full(pass));
    let skip_space = Space::after_skip(pass);
    let after = if skip_space == full.space {
        full.clone()
    } else {
        analyse(skip_space)
    };
    let build_space = Space::build_set(pass, features);
    let build = if build_space == after.space {
        after.clone()
    } else {
        analyse(build_space)
    };
    let used = options.materials.as_ref().map(|m| used_keywords(pass, m));
    let (mut full, mut after, mut build) = (full, after, build);
    let substituted = substitutes_valued(lib, pass);
    if substituted {
        // The static walk tells texts apart by their lines, and a substituted value changes a
        // line's text, not which lines there are: count every variant as distinct (a bound).
        for a in [&mut full, &mut after, &mut build] {
            a.distinct = a.count.clone();
            a.exact = false;
            a.method = Method::Bound;
        }
    }
    let mut audit = report::assemble(pass, &full, &after, &build, used);
    if substituted {
        // Nor can it tell a valued keyword from its siblings: not dead, not identical.
        audit.dead_keywords.retain(|k| !valued(pass, k));
        for (set, row) in pass.sets.iter().zip(&mut audit.sets) {
            if set.keywords().any(|k| valued(pass, k)) {
                row.dead = false;
                row.dead_keywords.clear();
                row.identical_options.clear();
                row.suggestions.clear();
            }
        }
    }
    audit.unreached = crate::analysis::unreached(lib, pass);
    // A keyword whose defs go to other stages only changes nothing here by design: not dead.
    let pushed_here = |k: &str| k == "_" || !pass.keyword_defs(k).is_empty();
    audit.dead_keywords.retain(|k| pushed_here(k));
    for (set, row) in pass.sets.iter().zip(&mut audit.sets) {
        if pass.stage.is_some() && !set.keywords().any(pushed_here) {
            row.other_stages = true;
            row.suggestions.clear();
        }
    }
    audit.unpushed_defs = stages::unpushed_defs(lib, pass);
    Ok(audit)
}

/// Whether a def of one of `pass`'s valued sets (`NAME=VALUE` keywords) reaches code in a
/// module the pass composes: substituted by naga_oil (`#{NAME}` or `#NAME`), or, in a WESL
/// tree, read from the `constants` package (WESL conditions are boolean, so any mention of the
/// name is a use of its value).
fn substitutes_valued(lib: &Library, pass: &Pass) -> bool {
    let names: Vec<&str> = pass
        .keywords()
        .flat_map(|k| {
            // A valued keyword's def, or an option's def with a value other than "on".
            let whole = k.contains('=');
            pass.keyword_defs(k)
                .into_iter()
                .filter(move |(_, v)| whole || *v != crate::declaration::DefValue::Bool(true))
        })
        .map(|(name, _)| name)
        .collect();
    if names.is_empty() {
        return false;
    }
    let graph = lib.module_graph();
    let wesl = lib.dialect() == crate::Dialect::Wesl;
    graph.reach(pass.module).into_iter().any(|m| {
        let text = graph.files.text(graph.modules[m].file);
        names.iter().any(|name| {
            text.match_indices(name).any(|(at, _)| {
                let before = text[..at].trim_end_matches(['{', ' ', '\t']);
                let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
                let after = text[at + name.len()..].chars().next();
                let whole =
                    !after.is_some_and(ident) && !text[..at].chars().next_back().is_some_and(ident);
                whole && (wesl || before.ends_with('#'))
            })
        })
    })
}

/// Whether keyword `k` sets a def to a value other than "on": a valued keyword
/// (`NAME=VALUE`), or an option with such a def.
fn valued(pass: &Pass, k: &str) -> bool {
    k.contains('=')
        || pass
            .keyword_defs(k)
            .iter()
            .any(|(_, v)| *v != crate::declaration::DefValue::Bool(true))
}

/// Keywords of `pass` that some material of its shader enables.
fn used_keywords(pass: &Pass, materials: &[Material]) -> Vec<String> {
    let mut used: Vec<String> = materials
        .iter()
        .filter(|m| m.shader == pass.shader)
        .flat_map(|m| m.keywords.iter())
        .filter(|k| pass.keyword(k).is_some())
        .cloned()
        .collect();
    used.sort();
    used.dedup();
    used
}
