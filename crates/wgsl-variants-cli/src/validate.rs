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
    if run.shard.is_some() && ctx.lib.several_profiles() {
        return Err(Failed(format!(
            "error: --shard validates for one device, and this run validates for several ({}): `merge` puts together one profile's shards; run the shards of each `--profile` apart",
            profile_names(&ctx.lib).join(", ")
        )));
    }
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
                let mut diagnostic = f.error.diagnostic();
                if !f.profiles.is_empty() {
                    diagnostic = diagnostic.note(on_profiles(&f.profiles));
                }
                eprint!("{}", ctx.render(&diagnostic));
                let n = f.keyword_sets.len();
                if n > 1 {
                    eprintln!(
                        "  ({n} keyword sets fail alike (the same text, or the same composer error); first: {:?})\n",
                        f.keyword_sets.iter().take(3).collect::<Vec<_>>()
                    );
                }
            }
            if r.profiles.is_empty() {
                println!(
                    "{}/{}: {} built ({} full space), {} distinct, {} valid, {} invalid",
                    r.shader, r.pass, r.built, r.full_space, r.distinct, r.valid, r.invalid
                );
            } else {
                println!(
                    "{}/{}: {} built ({} full space), {} distinct, {} valid on every profile, {} invalid on some",
                    r.shader, r.pass, r.built, r.full_space, r.distinct, r.valid, r.invalid
                );
                print_profiles(&r.profiles, "  ");
                print_failing(r);
            }
        }
        if let Some(t) = options.cover {
            cover_report(ctx, &plan, &options, &report, t)?;
        }
        let t = &report.totals;
        if t.profiles.is_empty() {
            println!(
                "total: {} passes, {} variants built, {} distinct, {} valid, {} invalid",
                t.passes, t.built, t.distinct, t.valid, t.invalid
            );
        } else {
            println!(
                "total: {} passes, {} variants built, {} distinct, {} valid on every profile, {} invalid on some",
                t.passes, t.built, t.distinct, t.valid, t.invalid
            );
            print_profiles(&t.profiles, "total ");
        }
    }
    Ok(if report.ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// Most failing variants listed per pass in the text report (`--json` has every one).
const FAILING_LISTED: usize = 20;

/// The names of every profile the library's passes are validated for, in order of first
/// appearance.
pub(crate) fn profile_names(lib: &wgsl_variants::Library) -> Vec<String> {
    let mut names: Vec<String> = Vec::new();
    for pass in lib.passes() {
        for p in lib.pass_profiles(pass) {
            let name = p.name();
            if !names.contains(&name) {
                names.push(name);
            }
        }
    }
    names
}

/// `on profile webgpu` / `on profiles webgpu, webgl2`.
fn on_profiles(profiles: &[String]) -> String {
    format!(
        "fails on profile{} {}",
        if profiles.len() == 1 { "" } else { "s" },
        profiles.join(", ")
    )
}

/// One line per profile: `{prefix}webgpu: 3 valid, 1 invalid`.
fn print_profiles(profiles: &[wgsl_variants::validate::ProfileCounts], prefix: &str) {
    for p in profiles {
        println!(
            "{prefix}{}: {} valid, {} invalid",
            p.profile, p.valid, p.invalid
        );
    }
}

/// The pass's failing variants with the profiles each fails on, in enumeration order (the
/// first [`FAILING_LISTED`]).
fn print_failing(r: &wgsl_variants::validate::PassReport) {
    let failing = r.failing_variants();
    for v in failing.iter().take(FAILING_LISTED) {
        println!(
            "  {{{}}}: {}",
            v.keywords.join(", "),
            on_profiles(&v.profiles)
        );
    }
    if failing.len() > FAILING_LISTED {
        println!(
            "  … and {} more failing variants (`--json` lists every keyword set with its profiles)",
            failing.len() - FAILING_LISTED
        );
    }
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
            // On the profiles this failure happens on (the pass's first when one is validated).
            let profiles: Vec<wgsl_variants::validate::Profile> = ctx
                .lib
                .pass_profiles(pass)
                .iter()
                .copied()
                .filter(|p| f.profiles.is_empty() || f.profiles.contains(&p.name()))
                .take(if f.profiles.is_empty() { 1 } else { usize::MAX })
                .collect();
            let fails = |c: &wgsl_variants::Choice| {
                let v = Variant {
                    pass,
                    choice: c.clone(),
                };
                profiles.iter().any(|&p| {
                    ctx.lib.naga_module_for(&v, p).is_err()
                        || (options.strict
                            && wgsl_variants::validate::validate_for(
                                &ctx.lib.compose_unpruned(&v, true),
                                &v.label(),
                                p,
                            )
                            .is_err())
                })
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
