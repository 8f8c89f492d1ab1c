//! `wgsl-variants validate`.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use serde::Serialize;
use serde_json::value::RawValue;

use wgsl_variants::validate::{PassReport, validate_pass_with};

use wgsl_variants::cache::ValidCache;
use wgsl_variants::variants::Shard;

use super::output::{count, print_json, progress};
use super::{BuildArgs, Context, Failed};

#[derive(Serialize)]
pub struct FailureOut {
    pub stage: wgsl_variants::validate::Stage,
    pub message: String,
    pub location: Option<String>,
    pub keyword_sets: Vec<Vec<String>>,
    pub diagnostic: String,
}

#[derive(Serialize)]
pub struct PassOut {
    pub shader: String,
    #[serde(rename = "pass")]
    pub pass_name: String,
    pub full_space: Box<RawValue>,
    pub built: u64,
    pub distinct: u64,
    pub valid: u64,
    pub invalid: u64,
    pub failures: Vec<FailureOut>,
}

#[derive(Serialize, Default)]
pub struct Totals {
    pub passes: usize,
    pub built: u64,
    pub distinct: u64,
    pub valid: u64,
    pub invalid: u64,
}

#[derive(Serialize)]
struct ValidateOut {
    ok: bool,
    selection: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    shard: Option<String>,
    passes: Vec<PassOut>,
    totals: Totals,
}

/// Builds and validates the selected passes (of one shard, with a cache of valid texts when
/// given), with a progress bar on stderr.
pub fn build_reports_with(
    ctx: &Context,
    all: bool,
    build: &BuildArgs,
    shard: Option<Shard>,
    cache: Option<&ValidCache>,
) -> Result<Vec<PassReport>, Failed> {
    let plans = ctx.plan(build, all, shard)?;
    let total: u64 = plans.iter().map(|p| p.1.len() as u64).sum();
    let bar = progress(total, "validating");
    let reports = plans
        .iter()
        .map(|(pass, choices)| {
            validate_pass_with(&ctx.lib, pass, choices.iter().cloned(), cache, &|n| {
                bar.inc(n)
            })
        })
        .collect();
    bar.finish_and_clear();
    Ok(reports)
}

/// JSON form of a pass report.
pub fn pass_out(ctx: &Context, r: &PassReport) -> PassOut {
    PassOut {
        shader: r.shader.clone(),
        pass_name: r.pass.clone(),
        full_space: count(&r.full_space),
        built: r.built,
        distinct: r.distinct,
        valid: r.valid,
        invalid: r.invalid,
        failures: r
            .failures
            .iter()
            .map(|f| FailureOut {
                stage: f.error.stage,
                message: f.error.message.clone(),
                location: f.error.location(ctx.lib.files()).map(|l| l.to_string()),
                keyword_sets: f.keyword_sets.clone(),
                diagnostic: f.error.diagnostic().render(ctx.lib.files(), false),
            })
            .collect(),
    }
}

/// How `validate` runs: sharding and the cache of valid texts.
#[derive(clap::Args, Debug, Clone)]
pub struct RunArgs {
    /// Build only shard K of N (variants numbered across passes; `K/N`, 1 <= K <= N).
    #[arg(long, value_name = "K/N")]
    shard: Option<Shard>,
    /// Cache of validated texts [default: target/wgsl-variants-cache when ./target or
    /// ./Cargo.toml exists].
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
        self.cache.clone().or_else(|| {
            (Path::new("target").is_dir() || Path::new("Cargo.toml").is_file())
                .then(|| PathBuf::from("target/wgsl-variants-cache"))
        })
    }
}

pub fn run(ctx: &Context, all: bool, build: &BuildArgs, run: &RunArgs) -> Result<ExitCode, Failed> {
    let cache = run.cache_dir().map(|dir| ValidCache::open(&dir));
    let reports = build_reports_with(ctx, all, build, run.shard, cache.as_ref())?;
    if let Some(cache) = &cache
        && let Err(e) = cache.save()
    {
        eprintln!("warning: could not write the validation cache: {e}");
    }
    let mut totals = Totals {
        passes: reports.len(),
        ..Totals::default()
    };
    for r in &reports {
        totals.built += r.built;
        totals.distinct += r.distinct;
        totals.valid += r.valid;
        totals.invalid += r.invalid;
    }
    let ok = totals.invalid == 0;
    if ctx.json {
        let passes = reports.iter().map(|r| pass_out(ctx, r)).collect();
        print_json(&ValidateOut {
            ok,
            selection: if all { "full_space" } else { "build_set" },
            shard: run.shard.map(|s| s.to_string()),
            passes,
            totals,
        })?;
    } else {
        for r in &reports {
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
        println!(
            "total: {} passes, {} variants built, {} distinct, {} valid, {} invalid",
            totals.passes, totals.built, totals.distinct, totals.valid, totals.invalid
        );
    }
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
