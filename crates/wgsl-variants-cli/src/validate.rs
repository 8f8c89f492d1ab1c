//! `wgsl-variants validate`.

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::analysis::region_aware;
use wgsl_variants::covering::{first_covered, shrink, tuple_label};
use wgsl_variants::plan::{Plan, PlanOptions};
use wgsl_variants::validate::ValidateReport;
use wgsl_variants::validate::validate_plan;
use wgsl_variants::variants::Shard;
use wgsl_variants::{Space, Variant};

use super::context::{BuildArgs, Context, Failed};
use super::output::{print_json, progress};

/// How `validate` runs: sharding, the cache of valid texts and strictness.
#[derive(clap::Args, Debug, Clone)]
pub struct RunArgs {
    /// Build only shard K of N (variants numbered across passes; `K/N`, 1 <= K <= N).
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    #[command(flatten)]
    check: CheckArgs,
}

/// How variants are checked (`validate` and `watch`): the cache of valid texts and
/// strictness.
#[derive(clap::Args, Debug, Clone)]
pub struct CheckArgs {
    /// Cache of validated texts, safe to share between processes and machines at once
    /// [default: target/wgsl-variants-cache when ./target or ./Cargo.toml exists].
    #[arg(long, value_name = "DIR")]
    cache: Option<PathBuf>,
    /// Validate everything again; neither read nor write the cache.
    #[arg(long, conflicts_with = "cache")]
    no_cache: bool,
    /// Also validate each variant's text as composed, before the items no entry point reaches
    /// are left out (once per distinct such text): a broken helper nobody calls is an error.
    #[arg(long)]
    pub strict: bool,
}

impl CheckArgs {
    /// The cache folder to use, if any.
    pub fn cache_dir(&self) -> Option<PathBuf> {
        if self.no_cache {
            return None;
        }
        super::cache::default_dir(self.cache.as_deref())
    }
}

pub fn run(ctx: &Context, all: bool, build: &BuildArgs, run: &RunArgs) -> Result<ExitCode, Failed> {
    let cache = run.check.cache_dir().map(|dir| super::cache::open(&dir));
    let mut options = super::context::plan_options(build, all, run.shard)?;
    options.strict = run.check.strict;
    let plan = ctx.plan(&options)?;
    let bar = progress(plan.iter().map(|p| p.1.len() as u64).sum(), "validating");
    let report = validate_plan(&ctx.lib, &plan, &options, cache.as_ref(), &|n| bar.inc(n));
    bar.finish_and_clear();
    if let Some(cache) = &cache
        && let Err(e) = cache.save()
    {
        eprintln!("warning: could not write the validation cache: {e}");
    }
    if ctx.json {
        print_json(&report)?;
    } else {
        for r in &report.passes {
            for f in &r.failures {
                eprint!("{}", ctx.render(&f.error.diagnostic()));
                let n = f.keyword_sets.len();
                if n > 1 {
                    eprintln!(
                        "  ({n} keyword sets fail alike (the same text, or the same composer error); first: {:?})\n",
                        f.keyword_sets.iter().take(3).collect::<Vec<_>>()
                    );
                }
            }
            println!(
                "{}/{}: {} built ({} full space), {} distinct, {} valid, {} invalid",
                r.shader, r.pass, r.built, r.full_space, r.distinct, r.valid, r.invalid
            );
        }
        if let Some(t) = options.cover {
            cover_report(ctx, &plan, &options, &report, t)?;
        }
        let t = &report.totals;
        println!(
            "total: {} passes, {} variants built, {} distinct, {} valid, {} invalid",
            t.passes, t.built, t.distinct, t.valid, t.invalid
        );
    }
    Ok(if report.ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// With `--cover T`: per pass, the space and the covering set's size; per failure, the
/// failing variant, the T-tuples it is the first of the covering set to contain, and the
/// smallest keyword subset that still fails (keywords turned off one at a time).
fn cover_report(
    ctx: &Context,
    plan: &Plan<'_>,
    options: &PlanOptions,
    report: &ValidateReport,
    t: usize,
) -> Result<(), Failed> {
    for ((pass, choices), r) in plan.iter().zip(&report.passes) {
        let space = if options.all {
            Space::full(pass)
        } else {
            ctx.lib.build_set(pass, options.materials.as_deref())?
        };
        if options
            .cover_above
            .is_some_and(|limit| space.count() <= limit.into())
        {
            println!(
                "{}/{}: built whole: its {}-variant space is at most --cover-above",
                pass.shader,
                pass.name,
                space.count()
            );
            continue;
        }
        // The region-aware size for comparison (dead sets fixed, coupled sets as one factor of
        // their distinct code); a pass with fewer sets than t is built whole either way.
        let regional = match region_aware(&ctx.lib, &space, t) {
            Ok(r) => r.len().to_string(),
            Err(_) => choices.len().to_string(),
        };
        println!(
            "{}/{}: covering t={t}: {} variants cover every {t}-way combination of keyword options of a {}-variant space (region-aware: {regional})",
            pass.shader,
            pass.name,
            choices.len(),
            space.count()
        );
        for f in &r.failures {
            let Some(index) = choices
                .iter()
                .position(|c| f.keyword_sets.iter().any(|k| *k == c.keywords(pass)))
            else {
                continue;
            };
            let failing = &choices[index];
            println!("  failing variant #{index}: {}", failing.label(pass));
            let fails = |c: &wgsl_variants::Choice| {
                let v = Variant {
                    pass,
                    choice: c.clone(),
                };
                ctx.lib.naga_module(&v).is_err()
                    || (options.strict
                        && wgsl_variants::validate::validate_composed(
                            &ctx.lib.compose_unpruned(&v, true),
                            &v.label(),
                        )
                        .is_err())
            };
            let small = shrink(&space, failing, fails);
            // The tuples the shrunk variant shares come first: they name the culprits.
            let mut tuples = first_covered(choices, index, t);
            tuples.sort_by_key(|u| {
                let shared = u.iter().all(|&(set, o)| small.0[set] == o);
                let on = u
                    .iter()
                    .filter(|&&(set, o)| pass.sets[set].options[o as usize].is_some())
                    .count();
                (!shared, std::cmp::Reverse(on))
            });
            let shown: Vec<String> = tuples
                .iter()
                .take(8)
                .map(|u| tuple_label(pass, u))
                .collect();
            println!(
                "    first to cover {} {t}-tuple(s): {}{}",
                tuples.len(),
                shown.join("; "),
                if tuples.len() > shown.len() {
                    "; …"
                } else {
                    ""
                }
            );
            println!("    smallest failing keyword subset: {}", small.label(pass));
        }
    }
    Ok(())
}
