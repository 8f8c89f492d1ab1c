//! The audit's result types, assembled from the stage analyses.

use num_bigint::BigUint;
use serde::ser::SerializeStruct as _;
use serde::{Serialize as _, Serializer};

use crate::json::{ExactCount, exact_count};

use crate::keywords::SetKind;
use crate::shader::Pass;

use super::Method;
use super::budget::{Budgets, Verdict, verdict};
use super::distinct::{Analysis, Component};
use super::findings::{SetFindings, base_option, findings};

/// Most classes listed per group of identical code, and members listed per class.
const MAX_CLASSES: usize = 32;
const MAX_MEMBERS: usize = 16;

/// A distinct-variant count.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Distinct {
    /// Number of distinct composed texts (an upper bound when not `exact`).
    pub count: BigUint,
    /// Whether `count` is exact.
    pub exact: bool,
    /// How it was obtained.
    pub method: Method,
}

/// A keyword that changes code only when other keywords are on.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct Together {
    /// The keyword.
    pub keyword: String,
    /// The smallest sets of other keywords with which turning it on changes code (at most
    /// eight are listed).
    pub with: Vec<Vec<String>>,
}

/// Keyword sets whose choices, everything else equal, can generate identical code.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct CodeGroup {
    /// The keywords of the sets involved.
    pub keywords: Vec<String>,
    /// Number of assignments of those sets in the stage.
    #[serde(serialize_with = "exact_count")]
    pub variants: BigUint,
    /// Number of distinct codes among them.
    pub distinct: u64,
    /// The assignments that share code: each entry is one code, listing the keyword sets
    /// (keywords on among `keywords`) that generate it. Only codes shared by two or more
    /// assignments; at most 32 codes and 16 keyword sets each are listed.
    pub shared: Vec<Vec<Vec<String>>>,
    /// Number of codes shared by two or more assignments (listed or not).
    pub shared_total: usize,
}

/// One keyword set in the multiplier table.
///
/// Serialized without `together` (listed in the pass's [`PassAudit::together`]) and `known`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct SetAudit {
    /// The pragma as written, e.g. `shader_feature _ _NORMAL_MAP`.
    pub declaration: String,
    /// Its keywords, space-separated (the set's name in tables).
    pub name: String,
    /// `multi_compile` or `shader_feature`.
    pub kind: SetKind,
    /// Its options (`_` for "none").
    pub options: Vec<String>,
    /// How much it multiplies the full space (its number of options).
    pub factor: usize,
    /// Options left after `skip_variants`.
    pub after_filtering: usize,
    /// Options taken in the build set.
    pub build_set: usize,
    /// How much it multiplies the distinct variants of the full space, when that does not
    /// depend on other sets (1 for a dead set); `None` when coupled.
    pub distinct_factor: Option<u64>,
    /// Names of the sets it is coupled with (their code depends on each other).
    pub coupled_with: Vec<String>,
    /// For a coupled set: assignments of its whole group, and distinct codes among them
    /// (`{"variants": N, "distinct": D}` in JSON).
    #[serde(serialize_with = "group_json")]
    pub group: Option<(BigUint, u64)>,
    /// No option changes any generated code.
    pub dead: bool,
    /// Keywords of the set that generate the same code as its base option (`_`, or its first
    /// option) in every variant.
    pub dead_keywords: Vec<String>,
    /// Options that generate identical code in every variant (groups of two or more).
    pub identical_options: Vec<Vec<String>>,
    /// Keywords of the set that change code only together with others.
    #[serde(skip)]
    pub together: Vec<Together>,
    /// Keywords of the set that some material enables (`None` without materials).
    pub used_by_materials: Option<Vec<String>>,
    /// What could be done about it.
    pub suggestions: Vec<String>,
    /// In a stage of a pass split into stages: no keyword of the set has defs in this stage
    /// (they go to the others), so it changes nothing here by design — not a dead set.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub other_stages: bool,
    /// Whether the findings above are complete (false when its group was too large).
    #[serde(skip)]
    pub known: bool,
}

/// The audit of one pass.
///
/// Serialized (in `audit --json`) with exact counts, the build set's distinct count as
/// `distinct`, `distinct_exact` and `distinct_method`, only the counts of the other stages'
/// distinct variants, and without `materials`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct PassAudit {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// The pipeline stage, for a stage of a pass split into stages.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<crate::stage::PipelineStage>,
    /// The full space: the product of the sets' sizes.
    #[serde(serialize_with = "exact_count")]
    pub full_space: BigUint,
    /// After `skip_variants`.
    #[serde(serialize_with = "exact_count")]
    pub after_filtering: BigUint,
    /// After `shader_feature` stripping against the materials (equal to `after_filtering`
    /// without materials).
    #[serde(serialize_with = "exact_count")]
    pub after_stripping: BigUint,
    /// The variants `validate` builds (equal to `after_stripping`).
    #[serde(serialize_with = "exact_count")]
    pub build_set: BigUint,
    /// Distinct variants of the build set.
    #[serde(flatten, serialize_with = "distinct_fields")]
    pub distinct: Distinct,
    /// Distinct variants of the full space.
    #[serde(serialize_with = "distinct_count")]
    pub distinct_full_space: Distinct,
    /// Distinct variants after `skip_variants`.
    #[serde(serialize_with = "distinct_count")]
    pub distinct_after_filtering: Distinct,
    /// Keywords that change no generated code in any variant.
    pub dead_keywords: Vec<String>,
    /// The pass's `require`/`exclude` constraints as written (`require A B`); every count
    /// above honours them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub constraints: Vec<String>,
    /// Keywords that change code only together with others.
    pub together: Vec<Together>,
    /// Where build-set variants share code.
    pub identical_code: Vec<CodeGroup>,
    /// The multiplier table, one row per keyword set in declaration order.
    pub sets: Vec<SetAudit>,
    /// Whether dead keywords and the other findings are complete.
    pub findings_exact: bool,
    /// Per module, the top-level items no variant of the pass reaches
    /// ([`crate::analysis::unreached()`]): composed into the texts, left out of every program, so
    /// never validated without `validate --strict`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unreached: Vec<crate::analysis::Unreached>,
    /// For a stage of a pass split into stages: keywords pushed to other stages only whose
    /// defs would change the code this stage runs ([`super::stages::unpushed_defs`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub unpushed_defs: Vec<super::stages::UnpushedDefs>,
    /// Whether materials were given.
    #[serde(skip)]
    pub materials: bool,
}

/// `distinct`, `distinct_exact` and `distinct_method`.
fn distinct_fields<S: Serializer>(d: &Distinct, s: S) -> Result<S::Ok, S::Error> {
    let mut out = s.serialize_struct("Distinct", 3)?;
    out.serialize_field("distinct", &ExactCount(&d.count))?;
    out.serialize_field("distinct_exact", &d.exact)?;
    out.serialize_field("distinct_method", &d.method)?;
    out.end()
}

/// The count alone.
fn distinct_count<S: Serializer>(d: &Distinct, s: S) -> Result<S::Ok, S::Error> {
    exact_count(&d.count, s)
}

/// `{"variants": N, "distinct": D}`, or `null`.
fn group_json<S: Serializer>(group: &Option<(BigUint, u64)>, s: S) -> Result<S::Ok, S::Error> {
    #[derive(serde::Serialize)]
    struct Group<'a> {
        variants: ExactCount<'a>,
        distinct: u64,
    }
    group
        .as_ref()
        .map(|(n, d)| Group {
            variants: ExactCount(n),
            distinct: *d,
        })
        .serialize(s)
}

/// One pass of an [`AuditReport`]: its audit and the budget gate's verdict.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct AuditedPass {
    /// The audit.
    #[serde(flatten)]
    pub audit: PassAudit,
    /// The budget gate, when a budget applies.
    pub budget: Option<Verdict>,
}

/// Sums over the passes of an [`AuditReport`].
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct AuditTotals {
    /// Number of passes.
    pub passes: usize,
    /// Sum of the full spaces.
    #[serde(serialize_with = "exact_count")]
    pub full_space: BigUint,
    /// Sum of the build sets.
    #[serde(serialize_with = "exact_count")]
    pub build_set: BigUint,
    /// Sum of the build sets' distinct counts.
    #[serde(serialize_with = "exact_count")]
    pub distinct: BigUint,
    /// Whether every distinct count is exact.
    pub distinct_exact: bool,
    /// Number of passes over their budget.
    pub over_budget: usize,
}

/// The audit of several passes with their budget verdicts (what `audit --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct AuditReport {
    /// No pass is over its budget.
    pub ok: bool,
    /// Whether materials were given.
    pub materials: bool,
    /// The passes, in the order audited.
    pub passes: Vec<AuditedPass>,
    /// Sums over the passes.
    pub totals: AuditTotals,
}

impl AuditReport {
    /// Judges each audit against the tightest of `max_variants` and its budget in `budgets`
    /// (see [`budget::Verdict`](crate::audit::budget::Verdict)), and sums the counts.
    pub fn new(
        audits: Vec<PassAudit>,
        max_variants: Option<u64>,
        budgets: Option<&Budgets>,
        materials: bool,
    ) -> AuditReport {
        let sum = |f: &dyn Fn(&PassAudit) -> &BigUint| {
            audits.iter().map(f).fold(BigUint::default(), |a, b| a + b)
        };
        let totals = AuditTotals {
            passes: audits.len(),
            full_space: sum(&|a| &a.full_space),
            build_set: sum(&|a| &a.build_set),
            distinct: sum(&|a| &a.distinct.count),
            distinct_exact: audits.iter().all(|a| a.distinct.exact),
            over_budget: 0,
        };
        let passes: Vec<AuditedPass> = audits
            .into_iter()
            .map(|audit| AuditedPass {
                budget: verdict(&audit, max_variants, budgets),
                audit,
            })
            .collect();
        let over_budget = passes
            .iter()
            .filter(|p| p.budget.as_ref().is_some_and(|v| v.exceeded))
            .count();
        AuditReport {
            ok: over_budget == 0,
            materials,
            passes,
            totals: AuditTotals {
                over_budget,
                ..totals
            },
        }
    }

    /// The verdicts of the passes over their budget.
    pub fn over_budget(&self) -> impl Iterator<Item = &Verdict> {
        self.passes
            .iter()
            .filter_map(|p| p.budget.as_ref())
            .filter(|v| v.exceeded)
    }
}

fn stage(a: &Analysis) -> Distinct {
    Distinct {
        count: a.distinct.clone(),
        exact: a.exact,
        method: a.method,
    }
}

fn label(option: &Option<String>) -> String {
    option.clone().unwrap_or_else(|| "_".to_string())
}

/// A set's name: its keywords, space-separated.
pub(crate) fn set_name(pass: &Pass, set: usize) -> String {
    let names: Vec<&str> = pass.sets[set].keywords().collect();
    if names.is_empty() {
        "_".to_string()
    } else {
        names.join(" ")
    }
}

/// Builds the report from the analyses of the three stages.
pub(crate) fn assemble(
    pass: &Pass,
    full: &Analysis,
    after: &Analysis,
    build: &Analysis,
    used: Option<Vec<String>>,
) -> PassAudit {
    let found = findings(pass, full);
    let sets: Vec<SetAudit> = (0..pass.sets.len())
        .map(|s| set_row(pass, s, full, after, build, &found[s], used.as_deref()))
        .collect();
    let dead_keywords = sets.iter().flat_map(|r| r.dead_keywords.clone()).collect();
    let together = sets.iter().flat_map(|r| r.together.clone()).collect();
    let findings_exact = full.exact && found.iter().all(|f| f.known);
    PassAudit {
        shader: pass.shader.clone(),
        pass: pass.name.clone(),
        stage: pass.stage,
        full_space: full.count.clone(),
        after_filtering: after.count.clone(),
        after_stripping: build.count.clone(),
        build_set: build.count.clone(),
        distinct: stage(build),
        distinct_full_space: stage(full),
        distinct_after_filtering: stage(after),
        sets,
        dead_keywords,
        constraints: pass.constraints.iter().map(|c| c.to_string()).collect(),
        together,
        identical_code: groups(pass, build),
        findings_exact,
        unreached: Vec::new(),
        unpushed_defs: Vec::new(),
        materials: used.is_some(),
    }
}

fn set_row(
    pass: &Pass,
    s: usize,
    full: &Analysis,
    after: &Analysis,
    build: &Analysis,
    f: &SetFindings,
    used: Option<&[String]>,
) -> SetAudit {
    let set = &pass.sets[s];
    let opt = |o: usize| label(&set.options[o]);
    let component = full.components.iter().find(|c| c.sets.contains(&s));
    let (distinct_factor, coupled_with, group) = match component {
        None => (Some(1), Vec::new(), None),
        Some(c) if c.sets.len() == 1 => {
            (c.table.as_ref().map(|t| t.classes as u64), Vec::new(), None)
        }
        Some(c) => (
            None,
            c.sets
                .iter()
                .filter(|&&t| t != s)
                .map(|&t| set_name(pass, t))
                .collect(),
            c.table.as_ref().map(|t| (c.size.clone(), t.classes as u64)),
        ),
    };
    let dead_keywords: Vec<String> = f
        .dead_options
        .iter()
        .filter_map(|&o| set.options[o].clone())
        .collect();
    let together: Vec<Together> = f
        .together
        .iter()
        .filter_map(|(o, with)| {
            Some(Together {
                keyword: set.options[*o].clone()?,
                with: with.clone(),
            })
        })
        .collect();
    let used_by_materials = used.map(|u| {
        set.keywords()
            .filter(|k| u.iter().any(|x| x == k))
            .map(str::to_string)
            .collect::<Vec<_>>()
    });
    let mut suggestions = Vec::new();
    let n = set.len();
    if f.dead {
        suggestions.push(format!(
            "strip it: no generated code depends on it (it multiplies the space by {n} and distinct variants by 1)"
        ));
    } else {
        for &o in &f.dead_options {
            suggestions.push(format!(
                "drop `{}`: it generates the same code as `{}` in every variant",
                opt(o),
                opt(base_option(pass, s))
            ));
        }
        let base = base_option(pass, s);
        for g in &f.equivalent {
            if !g.contains(&base) {
                let names: Vec<String> = g.iter().map(|&o| format!("`{}`", opt(o))).collect();
                suggestions.push(format!(
                    "merge {}: they generate identical code in every variant",
                    names.join(" and ")
                ));
            }
        }
    }
    if let Some(u) = &used_by_materials
        && u.is_empty()
        && n > 1
        && !f.dead
    {
        match set.kind {
            SetKind::MultiCompile => suggestions.push(format!(
                "no material enables {}: if it is only set per material, declare it shader_feature (x{n} -> x1 with these materials)",
                set.keywords().map(|k| format!("`{k}`")).collect::<Vec<_>>().join(", ")
            )),
            SetKind::ShaderFeature => suggestions.push(
                "no material enables it: the build set keeps only its base option".to_string(),
            ),
        }
    }
    SetAudit {
        declaration: set.to_string(),
        name: set_name(pass, s),
        kind: set.kind,
        options: set.options.iter().map(label).collect(),
        factor: n,
        after_filtering: after.space.options(s).len(),
        build_set: build.space.options(s).len(),
        distinct_factor,
        coupled_with,
        group,
        dead: f.dead,
        dead_keywords,
        identical_options: f
            .equivalent
            .iter()
            .map(|g| g.iter().map(|&o| opt(o)).collect())
            .collect(),
        together,
        used_by_materials,
        suggestions,
        other_stages: false,
        known: f.known,
    }
}

/// Where the build set's variants share code.
fn groups(pass: &Pass, a: &Analysis) -> Vec<CodeGroup> {
    let mut out = Vec::new();
    for c in &a.components {
        if let Some(g) = component_group(pass, a, c) {
            out.push(g);
        }
    }
    // Factors no code depends on: all their choices share code.
    for (f, factor) in a.factors.iter().enumerate() {
        let sets = factor.sets();
        if factor.len() < 2 || sets.is_empty() || !sets.iter().all(|s| a.dead.contains(s)) {
            continue;
        }
        let members: Vec<Vec<String>> = (0..factor.len())
            .take(MAX_MEMBERS)
            .map(|i| keywords_of(pass, a, &[f], &[i], &sets))
            .collect();
        out.push(CodeGroup {
            keywords: sets
                .iter()
                .flat_map(|&s| pass.sets[s].keywords().map(str::to_string))
                .collect(),
            variants: BigUint::from(factor.len()),
            distinct: 1,
            shared: vec![members],
            shared_total: 1,
        });
    }
    out.sort_by_key(|g| {
        g.keywords
            .first()
            .and_then(|k| pass.keyword(k))
            .map(|k| k.0)
    });
    out
}

fn component_group(pass: &Pass, a: &Analysis, c: &Component) -> Option<CodeGroup> {
    let t = c.table.as_ref()?;
    if t.classes as usize == t.class.len() {
        return None;
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); t.classes as usize];
    for (row, &class) in t.class.iter().enumerate() {
        members[class as usize].push(row);
    }
    let shared: Vec<&Vec<usize>> = members.iter().filter(|m| m.len() > 1).collect();
    Some(CodeGroup {
        keywords: c
            .sets
            .iter()
            .flat_map(|&s| pass.sets[s].keywords().map(str::to_string))
            .collect(),
        variants: c.size.clone(),
        distinct: t.classes as u64,
        shared_total: shared.len(),
        shared: shared
            .iter()
            .take(MAX_CLASSES)
            .map(|rows| {
                rows.iter()
                    .take(MAX_MEMBERS)
                    .map(|&row| keywords_of(pass, a, &c.factors, &t.digits(row), &c.sets))
                    .collect()
            })
            .collect(),
    })
}

/// The keywords on among `sets` when `factors` take `digits`.
fn keywords_of(
    pass: &Pass,
    a: &Analysis,
    factors: &[usize],
    digits: &[usize],
    sets: &[usize],
) -> Vec<String> {
    let mut choice = vec![0u16; pass.sets.len()];
    for (&f, &d) in factors.iter().zip(digits) {
        a.factors[f].apply(d, &mut choice);
    }
    sets.iter()
        .filter_map(|&s| pass.sets[s].options[choice[s] as usize].clone())
        .collect()
}
