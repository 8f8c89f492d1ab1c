//! `wgsl-variants audit`: per pass, the stage counts, distinct variants, dead keywords, a
//! per-set multiplier table with suggestions, budgets (a CI gate) and an SVG chart.
//!
//! Nothing is validated here (that is `validate`), and nothing enumerates the space: counts
//! are exact for any number of keyword sets; except with several `--profile`s, when the build
//! set is validated once per profile for the table of variants valid per profile
//! ([`super::audit_profiles`]).

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::audit::budget::Budgets;
use wgsl_variants::audit::{self, AuditOptions, AuditReport, AuditedPass, Method, PassAudit};
use wgsl_variants::plan::select_passes;

use super::context::{BuildArgs, Context, Failed, load_materials};
use super::output::print_json;

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
    let mut options = AuditOptions::default();
    options.materials = load_materials(&build.materials)?;
    // The whole-stage fallback composes at most this many variants (memory stays small).
    options.enumeration_limit = build.max_variants.min(MAX_ENUMERATION);
    let passes = select_passes(&ctx.lib, build.shader.as_deref(), build.pass.as_deref())?;
    let audits = audit::audit_passes(&ctx.lib, &passes, &options)?;
    if let Some(path) = &args.chart {
        std::fs::write(path, audit::chart::svg(&audits))
            .map_err(|e| Failed(format!("error: cannot write `{}`: {e}", path.display())))?;
    }
    let materials = options.materials.is_some();
    let report = AuditReport::new(
        audits,
        Some(build.max_variants),
        budgets.as_ref(),
        materials,
    );
    let per_profile = if ctx.lib.several_profiles() {
        Some(super::audit_profiles::validate(ctx, build)?)
    } else {
        None
    };
    if ctx.json {
        match &per_profile {
            None => print_json(&report)?,
            Some(rows) => print_json(&WithProfiles {
                report: &report,
                valid_per_profile: rows,
            })?,
        }
    } else {
        print!("{}", table(&report.passes));
        if let Some(rows) = &per_profile {
            let names = super::validate::profile_names(&ctx.lib);
            print!("\n{}", super::audit_profiles::table(rows, &names));
        }
        match ctx.lib.dialect() {
            wgsl_variants::Dialect::NagaOil => println!(
                "note: a naga_oil tree: \"distinct\" counts preprocessed texts, an upper bound on the programs naga_oil composes (it keeps only the imported items a program uses)"
            ),
            wgsl_variants::Dialect::Wesl => println!(
                "note: a WESL tree: \"distinct\" counts the texts left by the `@if` conditions, an upper bound on the programs the wesl crate composes (it keeps only the declarations the entry points reach)"
            ),
            _ => println!(
                "note: \"distinct\" counts composed texts; each variant keeps only the items its entry points reach, so `validate` counts programs (at most as many). Items \"unreachable in every variant\" are in no program: `validate --strict` validates them too"
            ),
        }
    }
    for v in report.over_budget() {
        eprintln!("error: {}", v.message);
    }
    Ok(if report.ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// `audit --json` with several profiles: the report, then `valid_per_profile`.
#[derive(serde::Serialize)]
struct WithProfiles<'a> {
    #[serde(flatten)]
    report: &'a AuditReport,
    valid_per_profile: &'a [super::audit_profiles::PassProfiles],
}

/// The distinct count as people read it: `≤ N` when it is a bound.
fn distinct_text(a: &PassAudit) -> String {
    if a.distinct.exact {
        a.distinct.count.to_string()
    } else {
        format!("<= {}", a.distinct.count)
    }
}

/// The report for people: a summary table, then per pass its multiplier table and findings.
fn table(passes: &[AuditedPass]) -> String {
    let mut rows = vec![vec![
        "shader/pass".to_string(),
        "full space".into(),
        "after filtering".into(),
        "build set".into(),
        "distinct".into(),
        "budget".into(),
    ]];
    for AuditedPass {
        audit: a,
        budget: v,
        ..
    } in passes
    {
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
    let mut out = super::table::columns(&rows, "", 1);
    for a in passes
        .iter()
        .map(|p| &p.audit)
        .filter(|a| !a.sets.is_empty() || !a.unreached.is_empty() || !a.unpushed_defs.is_empty())
    {
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
            _ if s.other_stages => "x1 (other stages)".to_string(),
            _ if s.dead => "x1 (dead)".to_string(),
            (Some(d), _) => format!("x{d}"),
            (None, Some((n, d))) => format!("coupled: {d} of {n}"),
            (None, None) => "?".into(),
        };
        let kind = match s.kind {
            wgsl_variants::keywords::SetKind::MultiCompile => "multi_compile",
            wgsl_variants::keywords::SetKind::ShaderFeature => "shader_feature",
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
    if !a.sets.is_empty() {
        out.push_str(&super::table::columns(&rows, "  ", 2));
    }
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
    if !a.constraints.is_empty() {
        notes.push(format!(
            "constraints (every count honours them): {}",
            a.constraints.join(", ")
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
    for u in &a.unpushed_defs {
        let to: Vec<&str> = u.pushed_to.iter().map(|s| s.name()).collect();
        let stage = a.stage.map_or("this", |s| s.name());
        let items: Vec<String> = u.changes.iter().map(|c| format!("`{c}`")).collect();
        notes.push(format!(
            "{} is pushed to the {} stage only, yet it changes code the {stage} stage runs ({} in variant {}): that code is never built",
            u.keyword,
            to.join(" and "),
            items.join(", "),
            u.variant
        ));
    }
    for u in &a.unreached {
        notes.push(format!(
            "unreachable in every variant: {}: {}",
            u.module,
            u.names.join(", ")
        ));
    }
    for n in notes {
        out.push_str("  - ");
        out.push_str(&n);
        out.push('\n');
    }
    out
}
