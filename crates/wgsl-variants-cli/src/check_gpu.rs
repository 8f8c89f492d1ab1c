//! `wgsl-variants check-gpu`: the GPU proof of the bundled library (see
//! [`wgsl_variants_gpu::check`]): every variant of the standard passes, the deferred
//! reflection and final passes, URP's Lit passes (UniversalGBuffer and UniversalForward: a
//! covering set unless `--full`), URP's lighting passes, and
//! the compute kernels, compared with the CPU reference.

use std::process::ExitCode;

use wgsl_variants_gpu::GpuError;
use wgsl_variants_gpu::check::{self, CheckOptions};

use super::context::{Context, Failed};
use super::output::print_json;

/// `check-gpu` arguments.
#[derive(clap::Args, Debug)]
pub struct CheckGpuArgs {
    /// Only this shader (standard, deferred_shading, screen_space_shadows,
    /// deferred_reflections, deferred_final, universal_lit, stencil_deferred, skybox; kernels
    /// for the compute kernels).
    #[arg(long, value_name = "SHADER")]
    shader: Option<String>,
    /// Only passes (or kernels) with this name.
    #[arg(long, value_name = "PASS")]
    pass: Option<String>,
    /// Use the first adapter whose name contains NAME (case-insensitive).
    #[arg(long, value_name = "NAME")]
    adapter: Option<String>,
    /// GPU workers, each with its own device (default: one per core, at most 4).
    #[arg(long, value_name = "N", default_value_t = 0)]
    workers: usize,
    /// Check only every N-th variant of the standard passes (a quick look; keyword coverage
    /// is then not judged).
    #[arg(long, value_name = "N", default_value_t = 1)]
    sample: usize,
    /// Only shard K of N of each standard pass's variants (`K/N`), for a CI job matrix.
    #[arg(long, value_name = "K/N")]
    shard: Option<wgsl_variants::variants::Shard>,
    /// Check a T-wise covering set (T from 1 to 4) of each pass instead of every variant.
    /// Without it, passes past 8192 variants (the standard shader's ForwardBase, ForwardAdd and
    /// Deferred; URP's UniversalGBuffer and UniversalForward) get a 3-wise covering set.
    #[arg(long, value_name = "T", conflicts_with = "full")]
    cover: Option<usize>,
    /// Cover only passes whose space holds more than N variants (with --cover, as validate's;
    /// without it, the size past which the default 3-wise covering set applies).
    #[arg(long, value_name = "N", conflicts_with = "full")]
    cover_above: Option<u64>,
    /// Check every variant of every selected pass, URP's 49,152 and 55,296 included (no
    /// covering set).
    #[arg(long)]
    full: bool,
    /// Seconds each wait for the GPU may take before the check stops with an error (default
    /// 30). On a software adapter such as lavapipe a large variant compiles at its first draw;
    /// on a loaded machine, raise this rather than reading a slow compile as a hang.
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    timeout: Option<std::time::Duration>,
}

/// Parses a positive number of seconds (fractions allowed).
fn parse_seconds(text: &str) -> Result<std::time::Duration, String> {
    match text.parse::<f64>() {
        Ok(s) if s > 0.0 && s.is_finite() => Ok(std::time::Duration::from_secs_f64(s)),
        _ => Err(format!("`{text}` is not a positive number of seconds")),
    }
}

pub fn run(ctx: &Context, args: &CheckGpuArgs) -> Result<ExitCode, Failed> {
    let mut options = CheckOptions::default();
    options.shader = args.shader.clone();
    options.pass = args.pass.clone();
    options.adapter = args.adapter.clone();
    options.threads = args.workers;
    options.sample = args.sample;
    options.shard = args.shard;
    options.cover = args.cover;
    options.cover_above = args.cover_above;
    options.full = args.full;
    options.timeout = args.timeout;
    let report = check::run(&ctx.lib, &options).map_err(|e| match e {
        GpuError::Timeout { .. } => Failed(format!(
            "error: {e}\n  = help: a hang, or a slow first draw on a busy software adapter: \
             rerun that selection, and raise `--timeout` if it passes slowly; on lavapipe a \
             process keeps most of a megabyte per variant it compiled, so run a large \
             `--full` as `--shard K/N` processes and `wgsl-variants merge` their `--json` \
             reports (the repository's scripts/check-gpu-full.sh)"
        )),
        e => Failed(format!("error: {e}")),
    })?;
    if ctx.json {
        print_json(&report)?;
    } else {
        println!("{report}");
    }
    Ok(if report.passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
