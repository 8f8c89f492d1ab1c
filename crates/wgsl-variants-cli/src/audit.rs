//! `wgsl-variants audit`: per pass, the stage counts, distinct variants, dead keywords, a
//! per-set multiplier table with suggestions, budgets (a CI gate) and an SVG chart.
//!
//! Nothing is validated here (that is `validate`), and nothing enumerates the space: counts
//! are exact for any number of keyword sets.

use std::path::PathBuf;
use std::process::ExitCode;

use num_bigint::BigUint;
use serde::Serialize;
use serde_json::value::RawValue;

use wgsl_variants::audit::budget::{Budgets, Verdict, verdict};
use wgsl_variants::audit::{self, AuditOptions, CodeGroup, Method, PassAudit, SetAudit};
use wgsl_variants::plan::select_passes;

use super::output::{count, print_json};
use super::{BuildArgs, Context, Failed, load_materials};

/// Most variants the audit composes when the groups of coupled sets cannot give an exact count.
const MAX_ENUMERATION: u64 = 1 << 22;

/// Options of `audit`.
#[derive(clap::Args, Debug, Clone)]
pub struct AuditArgs {
    #[command(flatten)]
    build: BuildArgs,
    /// Per-pass budgets (TOML: `default = N`, and `"shader/pass" = N` or `"shader" = N` under
    /// `[budgets]`). Exit status 1 when a pass's build set is over its budget.
    #[arg(long, value_name = "FILE")]
    budget: Option<PathBuf>,
    /// Also write a chart (SVG): variants per stage and the multiplier of each keyword set.
    #[arg(long, value_name = "FILE.svg")]
    chart: Option<PathBuf>,
}

#[derive(Serialize)]
struct BudgetOut {
    limit: u64,
    source: String,
    exceeded: bool,
}

#[derive(Serialize)]
struct GroupOut {
    variants: Box<RawValue>,
    distinct: u64,
}

#[derive(Serialize)]
struct SetOut {
    declaration: String,
    name: String,
    kind: wgsl_variants::preprocess::tree::SetKind,
    options: Vec<String>,
    factor: usize,
    after_filtering: usize,
    build_set: usize,
    distinct_factor: Option<u64>,
    coupled_with: Vec<String>,
    group: Option<GroupOut>,
    dead: bool,
    dead_keywords: Vec<String>,
    identical_options: Vec<Vec<String>>,
    used_by_materials: Option<Vec<String>>,
    suggestions: Vec<String>,
}

#[derive(Serialize)]
struct TogetherOut {
    keyword: String,
    with: Vec<Vec<String>>,
}

#[derive(Serialize)]
struct CodeGroupOut {
    keywords: Vec<String>,
    variants: Box<RawValue>,
    distinct: u64,
    shared: Vec<Vec<Vec<String>>>,
    shared_total: usize,
}

#[derive(Serialize)]
struct PassOut {
    shader: String,
    #[serde(rename = "pass")]
    pass_name: String,
    full_space: Box<RawValue>,
    after_filtering: Box<RawValue>,
    after_stripping: Box<RawValue>,
    build_set: Box<RawValue>,
    distinct: Box<RawValue>,
    distinct_exact: bool,
    distinct_method: Method,
    distinct_full_space: Box<RawValue>,
    distinct_after_filtering: Box<RawValue>,
    dead_keywords: Vec<String>,
    together: Vec<TogetherOut>,
    identical_code: Vec<CodeGroupOut>,
    sets: Vec<SetOut>,
    findings_exact: bool,
    budget: Option<BudgetOut>,
}

#[derive(Serialize)]
struct Totals {
    passes: usize,
    full_space: Box<RawValue>,
    build_set: Box<RawValue>,
    distinct: Box<RawValue>,
    distinct_exact: bool,
    over_budget: usize,
}

#[derive(Serialize)]
struct AuditOut {
    ok: bool,
    materials: bool,
    passes: Vec<PassOut>,
    totals: Totals,
}

fn set_out(s: &SetAudit) -> SetOut {
    SetOut {
        declaration: s.declaration.clone(),
        name: s.name.clone(),
        kind: s.kind,
        options: s.options.clone(),
        factor: s.factor,
        after_filtering: s.after_filtering,
        build_set: s.build_set,
        distinct_factor: s.distinct_factor,
        coupled_with: s.coupled_with.clone(),
        group: s.group.as_ref().map(|(n, d)| GroupOut {
            variants: count(n),
            distinct: *d,
        }),
        dead: s.dead,
        dead_keywords: s.dead_keywords.clone(),
        identical_options: s.identical_options.clone(),
        used_by_materials: s.used_by_materials.clone(),
        suggestions: s.suggestions.clone(),
    }
}

fn group_out(g: &CodeGroup) -> CodeGroupOut {
    CodeGroupOut {
        keywords: g.keywords.clone(),
        variants: count(&g.variants),
        distinct: g.distinct,
        shared: g.shared.clone(),
        shared_total: g.shared_total,
    }
}

fn pass_out(a: &PassAudit, v: Option<&Verdict>) -> PassOut {
    PassOut {
        shader: a.shader.clone(),
        pass_name: a.pass.clone(),
        full_space: count(&a.full_space),
        after_filtering: count(&a.after_filtering),
        after_stripping: count(&a.after_stripping),
        build_set: count(&a.build_set),
        distinct: count(&a.distinct.count),
        distinct_exact: a.distinct.exact,
        distinct_method: a.distinct.method,
        distinct_full_space: count(&a.distinct_full_space.count),
        distinct_after_filtering: count(&a.distinct_after_filtering.count),
        dead_keywords: a.dead_keywords.clone(),
        together: a
            .together
            .iter()
            .map(|t| TogetherOut {
                keyword: t.keyword.clone(),
                with: t.with.clone(),
            })
            .collect(),
        identical_code: a.identical_code.iter().map(group_out).collect(),
        sets: a.sets.iter().map(set_out).collect(),
        findings_exact: a.findings_exact,
        budget: v.map(|v| BudgetOut {
            limit: v.limit.limit,
            source: v.limit.source.clone(),
            exceeded: v.exceeded,
        }),
    }
}

pub fn run(ctx: &Context, args: &AuditArgs) -> Result<ExitCode, Failed> {
    let build = &args.build;
    if let Some(chart) = &args.chart
        && chart.extension().is_none_or(|e| e != "svg")
    {
        return Err(Failed(format!(
            "error: --chart writes SVG; give it a `.svg` file name (got `{}`)",
            chart.display()
        )));
    }
    let budgets = match &args.budget {
        Some(path) => {
            let b = Budgets::load(path)?;
            b.check(&ctx.lib)?;
            Some(b)
        }
        None => None,
    };
    let options = AuditOptions {
        materials: load_materials(&build.materials)?,
        // The whole-stage fallback composes at most this many variants (memory stays small).
        enumeration_limit: build.max_variants.min(MAX_ENUMERATION),
        ..AuditOptions::default()
    };
    let passes = select_passes(&ctx.lib, build.shader.as_deref(), build.pass.as_deref())?;
    let audits = audit::audit_passes(&ctx.lib, &passes, &options)?;
    let verdicts: Vec<Option<Verdict>> = audits
        .iter()
        .map(|a| verdict(a, Some(build.max_variants), budgets.as_ref()))
        .collect();
    if let Some(path) = &args.chart {
        std::fs::write(path, audit::chart::svg(&audits))
            .map_err(|e| Failed(format!("error: cannot write `{}`: {e}", path.display())))?;
    }
    let over: Vec<&Verdict> = verdicts.iter().flatten().filter(|v| v.exceeded).collect();
    if ctx.json {
        let sum = |f: &dyn Fn(&PassAudit) -> &BigUint| {
            audits.iter().map(f).fold(BigUint::default(), |a, b| a + b)
        };
        print_json(&AuditOut {
            ok: over.is_empty(),
            materials: options.materials.is_some(),
            passes: audits
                .iter()
                .zip(&verdicts)
                .map(|(a, v)| pass_out(a, v.as_ref()))
                .collect(),
            totals: Totals {
                passes: audits.len(),
                full_space: count(&sum(&|a| &a.full_space)),
                build_set: count(&sum(&|a| &a.build_set)),
                distinct: count(&sum(&|a| &a.distinct.count)),
                distinct_exact: audits.iter().all(|a| a.distinct.exact),
                over_budget: over.len(),
            },
        })?;
    } else {
        print!("{}", table(&audits, &verdicts));
    }
    for v in &over {
        eprintln!("error: {}", v.message);
    }
    Ok(if over.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// The distinct count as people read it: `≤ N` when it is a bound.
fn distinct_text(a: &PassAudit) -> String {
    if a.distinct.exact {
        a.distinct.count.to_string()
    } else {
        format!("<= {}", a.distinct.count)
    }
}

/// Formats rows: the first `left` columns left-aligned, the others right-aligned.
fn columns(rows: &[Vec<String>], indent: &str, left: usize) -> String {
    let n = rows.iter().map(Vec::len).max().unwrap_or(0);
    let widths: Vec<usize> = (0..n)
        .map(|i| {
            rows.iter()
                .filter_map(|r| r.get(i))
                .map(|c| c.chars().count())
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    for r in rows {
        let mut line = indent.to_string();
        for (i, c) in r.iter().enumerate() {
            let pad = widths[i] - c.chars().count();
            if i > 0 {
                line.push_str("  ");
            }
            if i < left {
                line.push_str(c);
                line.push_str(&" ".repeat(pad));
            } else {
                line.push_str(&" ".repeat(pad));
                line.push_str(c);
            }
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// The report for people: a summary table, then per pass its multiplier table and findings.
fn table(audits: &[PassAudit], verdicts: &[Option<Verdict>]) -> String {
    let mut rows = vec![vec![
        "shader/pass".to_string(),
        "full space".into(),
        "after filtering".into(),
        "build set".into(),
        "distinct".into(),
        "budget".into(),
    ]];
    for (a, v) in audits.iter().zip(verdicts) {
        rows.push(vec![
            format!("{}/{}", a.shader, a.pass),
            a.full_space.to_string(),
            a.after_filtering.to_string(),
            a.build_set.to_string(),
            distinct_text(a),
            match v {
                Some(v) if v.exceeded => format!("OVER {}", v.limit.limit),
                Some(v) => v.limit.limit.to_string(),
                None => "-".into(),
            },
        ]);
    }
    let mut out = columns(&rows, "", 1);
    for a in audits.iter().filter(|a| !a.sets.is_empty()) {
        out.push('\n');
        out.push_str(&pass_details(a));
    }
    out
}

fn pass_details(a: &PassAudit) -> String {
    let mut out = format!(
        "{}/{}: {} keyword set{}, distinct {} of {} (full space: {} of {}{})\n",
        a.shader,
        a.pass,
        a.sets.len(),
        if a.sets.len() == 1 { "" } else { "s" },
        distinct_text(a),
        a.build_set,
        a.distinct_full_space.count,
        a.full_space,
        match a.distinct.method {
            Method::Components => "",
            Method::Enumeration => "; by enumeration",
            Method::Bound => "; an upper bound",
        }
    );
    let mut rows = vec![vec![
        "keyword set".to_string(),
        "kind".into(),
        "space".into(),
        "filtered".into(),
        "build".into(),
        "distinct".into(),
    ]];
    for s in &a.sets {
        let distinct = match (s.distinct_factor, &s.group) {
            _ if s.dead => "x1 (dead)".to_string(),
            (Some(d), _) => format!("x{d}"),
            (None, Some((n, d))) => format!("coupled: {d} of {n}"),
            (None, None) => "?".into(),
        };
        let kind = match s.kind {
            wgsl_variants::preprocess::tree::SetKind::MultiCompile => "multi_compile",
            wgsl_variants::preprocess::tree::SetKind::ShaderFeature => "shader_feature",
        };
        rows.push(vec![
            s.name.clone(),
            kind.into(),
            format!("x{}", s.factor),
            format!("x{}", s.after_filtering),
            format!("x{}", s.build_set),
            distinct,
        ]);
    }
    out.push_str(&columns(&rows, "  ", 2));
    let mut notes = Vec::new();
    let mut groups: Vec<Vec<String>> = Vec::new();
    for s in a.sets.iter().filter(|s| !s.coupled_with.is_empty()) {
        let mut g = s.coupled_with.clone();
        g.push(s.name.clone());
        g.sort();
        if !groups.contains(&g) {
            groups.push(g);
        }
    }
    for g in groups {
        notes.push(format!(
            "coupled (their code depends on each other): {}",
            g.join(" & ")
        ));
    }
    if !a.dead_keywords.is_empty() {
        notes.push(format!(
            "dead keywords (no code depends on them): {}",
            a.dead_keywords.join(", ")
        ));
    }
    for t in &a.together {
        let with: Vec<String> = t.with.iter().map(|w| w.join(" + ")).collect();
        notes.push(format!(
            "{} changes code only together with {}",
            t.keyword,
            with.join(" or ")
        ));
    }
    for g in &a.identical_code {
        for shared in &g.shared {
            let sets: Vec<String> = shared
                .iter()
                .map(|k| format!("{{{}}}", k.join(", ")))
                .collect();
            notes.push(format!("identical code: {}", sets.join(" = ")));
        }
        if g.shared_total > g.shared.len() {
            notes.push(format!(
                "identical code: … {} more among {}",
                g.shared_total - g.shared.len(),
                g.keywords.join(", ")
            ));
        }
    }
    for s in &a.sets {
        for sug in &s.suggestions {
            notes.push(format!("suggestion for {}: {sug}", s.name));
        }
    }
    if !a.findings_exact {
        notes.push("findings are incomplete: a group of coupled sets was too large".into());
    }
    for n in notes {
        out.push_str("  - ");
        out.push_str(&n);
        out.push('\n');
    }
    out
}
