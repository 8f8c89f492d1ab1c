//! `wgsl-variants check-gpu`: the GPU proof of the bundled library (see
//! [`wgsl_variants_gpu::check`]): every variant of the standard passes, the deferred
//! reflection and final passes, URP's Lit passes (UniversalGBuffer and UniversalForward: a
//! covering set unless `--full`), URP's lighting passes, and
//! the compute kernels, compared with the CPU reference.

use std::process::ExitCode;

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
    let report = check::run(&ctx.lib, &options).map_err(|e| Failed(format!("error: {e}")))?;
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
