//! `wgsl-variants validate`.

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::validate::validate_plan;
use wgsl_variants::variants::Shard;

use super::output::{print_json, progress};
use super::{BuildArgs, Context, Failed};

/// How `validate` runs: sharding and the cache of valid texts.
#[derive(clap::Args, Debug, Clone)]
pub struct RunArgs {
    /// Build only shard K of N (variants numbered across passes; `K/N`, 1 <= K <= N).
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    /// Cache of validated texts, safe to share between processes and machines at once
    /// [default: target/wgsl-variants-cache when ./target or ./Cargo.toml exists].
    #[arg(long, value_name = "DIR")]
    cache: Option<PathBuf>,
    /// Validate everything again; neither read nor write the cache.
    #[arg(long, conflicts_with = "cache")]
    no_cache: bool,
}

impl RunArgs {
    fn cache_dir(&self) -> Option<PathBuf> {
        if self.no_cache {
            return None;
        }
        super::cache::default_dir(self.cache.as_deref())
    }
}

pub fn run(ctx: &Context, all: bool, build: &BuildArgs, run: &RunArgs) -> Result<ExitCode, Failed> {
    let cache = run.cache_dir().map(|dir| super::cache::open(&dir));
    let options = ctx.plan_options(build, all, run.shard)?;
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
                        "  (the same text is produced by {n} keyword sets; first: {:?})\n",
                        f.keyword_sets.iter().take(3).collect::<Vec<_>>()
                    );
                }
            }
            println!(
                "{}/{}: {} built ({} full space), {} distinct, {} valid, {} invalid",
                r.shader, r.pass, r.built, r.full_space, r.distinct, r.valid, r.invalid
            );
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
