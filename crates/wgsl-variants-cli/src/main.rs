//! The `wgsl-variants` command line: argument parsing and dispatch. Each command lives in its
//! own file and turns its flags into the library's options.

// mimalloc: naga allocates per token and expression (Cargo.toml has the figure).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

mod audit;
mod audit_profiles;
mod bindings;
mod cache;
#[cfg(feature = "gpu")]
mod check_gpu;
mod context;
mod emit;
mod export;
mod list;
mod merge;
mod output;
mod reflect;
#[cfg(feature = "gpu")]
mod render;
mod table;
mod validate;
mod watch;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use wgsl_variants::{Library, LoadOptions};

use context::{BuildArgs, Context, Failed};

/// Unity-style shader variants for WGSL module trees, every variant validated by naga.
#[derive(Parser, Debug)]
#[command(name = "wgsl-variants", version, about, long_about = None)]
pub struct Cli {
    /// Library root (a folder of .wgsl modules; with a wgsl-variants.toml at its root, a
    /// naga_oil or WESL tree it declares). Default: the bundled library.
    #[arg(long, global = true, value_name = "DIR")]
    root: Option<PathBuf>,
    /// Print one JSON object on stdout instead of text.
    #[arg(long, global = true)]
    json: bool,
    /// Colours in diagnostics.
    #[arg(long, global = true, value_enum, default_value_t = Color::Auto)]
    color: Color,
    #[command(flatten)]
    limits: Limits,
    /// Worker threads (default: one per core). Output does not depend on it.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    /// The device variants are validated for: webgpu (the default), webgl2, desktop, or naga
    /// capability names joined by `,` (overrides the declaration file's `profile`). Repeat it
    /// to validate for several devices in one run (`validate`, `audit`, `watch`): one verdict
    /// per profile.
    #[arg(long, global = true, value_name = "NAME")]
    profile: Vec<wgsl_variants::validate::Profile>,
    #[command(subcommand)]
    command: Command,
}

/// Load limits: each has a clear error when passed.
#[derive(clap::Args, Debug, Clone)]
struct Limits {
    /// Deepest `#if` nesting in a module.
    #[arg(long, global = true, value_name = "N", default_value_t = LoadOptions::default().parse.if_depth)]
    max_if_depth: usize,
    /// Deepest expression nesting (parentheses and operators).
    #[arg(long, global = true, value_name = "N", default_value_t = LoadOptions::default().parse.expr_depth)]
    max_expr_depth: usize,
    /// Longest chain of imports.
    #[arg(long, global = true, value_name = "N", default_value_t = LoadOptions::default().max_import_depth)]
    max_import_depth: usize,
    /// Most module files in the library.
    #[arg(long, global = true, value_name = "N", default_value_t = LoadOptions::default().max_files)]
    max_files: usize,
    /// Most bytes of source in total.
    #[arg(long, global = true, value_name = "BYTES", default_value_t = LoadOptions::default().max_total_bytes)]
    max_source_bytes: usize,
}

impl Limits {
    fn options(&self) -> LoadOptions {
        let mut o = LoadOptions::default();
        o.parse.if_depth = self.max_if_depth;
        o.parse.expr_depth = self.max_expr_depth;
        o.max_import_depth = self.max_import_depth;
        o.max_files = self.max_files;
        o.max_total_bytes = self.max_source_bytes;
        o
    }
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Color {
    Auto,
    Always,
    Never,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Shaders, passes, tags, keyword sets and variant counts.
    List {
        /// Materials file for the build-set count.
        #[arg(long, value_name = "FILE")]
        materials: Option<PathBuf>,
    },
    /// Build and validate every variant of the build set (or, with --all, the full space).
    Validate {
        /// Validate the full space, not only the build set.
        #[arg(long)]
        all: bool,
        #[command(flatten)]
        build: BuildArgs,
        #[command(flatten)]
        run: validate::RunArgs,
    },
    /// Print one variant (validated first) as WGSL, GLSL, HLSL or MSL, or write a variant or
    /// the whole build set through any back end (SPIR-V too) into --out DIR with manifest.json.
    Emit(emit::EmitArgs),
    /// The bind groups and bindings a variant uses: kind, size, stage visibility.
    Reflect(reflect::ReflectArgs),
    /// Typed Rust for a pass: variant key, buffer structs with WGSL's padding (bytemuck),
    /// bindings, vertex inputs and colour targets of every variant.
    Bindings(bindings::BindingsArgs),
    /// One module with its imports on its own: prefixed self-contained WGSL, naga_oil's dialect or WESL's (--all --dialect wesl --out DIR: a WESL tree with its declaration file).
    Export(export::ExportArgs),
    /// Every variant of every pass's full space with a content hash of its canonical WGSL
    /// (the list that the `manifest` snapshot summarizes).
    Manifest {
        /// Only print the summary (variants, distinct texts, digest per pass).
        #[arg(long)]
        summary: bool,
        /// Only this shader.
        #[arg(long, value_name = "SHADER")]
        shader: Option<String>,
        /// Only passes with this name.
        #[arg(long, value_name = "PASS")]
        pass: Option<String>,
    },
    /// Put the outputs of N shards (`--shard K/N`: validate and check-gpu reports, emit
    /// folders) back together into what one run prints or writes; shards are checked to be
    /// 1..N of the same library, selection and version.
    Merge(merge::MergeArgs),
    /// The shared cache of valid texts: its state, and export to or import from one file.
    Cache(cache::CacheArgs),
    /// Variant counts per pass (full space, after skip_variants, build set, distinct), dead
    /// keywords, a multiplier table per keyword set, budgets (--budget) and a chart (--chart).
    Audit(audit::AuditArgs),
    /// Validate a tree (--root DIR), then validate it again at each change of its files: the
    /// passes the change touched first (recent failures, then a pairwise covering set, then
    /// the rest with the cache); diagnostics as found, one status line per verdict.
    Watch(watch::WatchArgs),
    /// Render every variant of the bundled passes on the GPU (lavapipe is enough) and compare
    /// every pixel, and compute kernels of the library's functions, with the CPU reference.
    #[cfg(feature = "gpu")]
    CheckGpu(check_gpu::CheckGpuArgs),
    /// Render the GPU check's test scene and write PNG pictures (G-buffer, light, final frame).
    #[cfg(feature = "gpu")]
    Render(render::RenderArgs),
}

/// `wgsl-variants manifest [--summary] [--shader S] [--pass P]`.
fn manifest(
    ctx: &Context,
    summary: bool,
    shader: Option<&str>,
    pass: Option<&str>,
) -> Result<ExitCode, Failed> {
    let passes = wgsl_variants::plan::select_passes(&ctx.lib, shader, pass)?;
    let make = if summary {
        wgsl_variants::snapshot::manifest_summary_of
    } else {
        wgsl_variants::snapshot::manifest_of
    };
    let text = make(&ctx.lib, &passes, 1_000_000).map_err(|e| Failed(format!("error: {e}")))?;
    print!("{text}");
    Ok(ExitCode::SUCCESS)
}

/// Commands that build one program per variant, or put together outputs made for one device,
/// refuse several `--profile`s rather than pick one: `validate`, `audit` and `watch` give one
/// verdict per profile, `list`, `cache` do not depend on the device. (A declaration file's
/// list of profiles gives these commands its first.)
fn one_profile(
    command: &Command,
    profiles: &[wgsl_variants::validate::Profile],
) -> Result<(), Failed> {
    let name = match command {
        Command::Emit(_) => "emit",
        Command::Reflect(_) => "reflect",
        Command::Export(_) => "export",
        Command::Manifest { .. } => "manifest",
        Command::Merge(_) => "merge",
        #[cfg(feature = "gpu")]
        Command::CheckGpu(_) => "check-gpu",
        #[cfg(feature = "gpu")]
        Command::Render(_) => "render",
        _ => return Ok(()),
    };
    if profiles.len() < 2 {
        return Ok(());
    }
    let names: Vec<String> = profiles.iter().map(|p| p.name()).collect();
    Err(Failed(format!(
        "error: `--profile` names {} devices ({}), but `{name}` builds for one: give one `--profile` (several are for `validate`, `audit` and `watch`)",
        names.len(),
        names.join(", ")
    )))
}

/// What a command run with `--json` prints on stdout when it fails, so a caller that reads
/// stdout (`validate --json > shard.json`) always gets JSON: `{"ok": false, "error": {…}}`.
#[derive(serde::Serialize)]
struct JsonFailure {
    ok: bool,
    error: JsonError,
}

#[derive(serde::Serialize)]
struct JsonError {
    /// `load` (the tree did not load) or `command` (the command failed).
    kind: &'static str,
    /// The one-line summary.
    message: String,
    /// Each problem, with its location where it has one.
    problems: Vec<JsonProblem>,
}

#[derive(serde::Serialize)]
struct JsonProblem {
    message: String,
    location: Option<String>,
}

/// Prints a [`JsonFailure`] on stdout.
fn print_json_failure(kind: &'static str, message: String, problems: Vec<JsonProblem>) {
    let failure = JsonFailure {
        ok: false,
        error: JsonError {
            kind,
            message,
            problems,
        },
    };
    if let Ok(text) = serde_json::to_string_pretty(&failure) {
        println!("{text}");
    }
}

/// The first line of a rendered failure, without its `error: ` prefix.
fn summary(rendered: &str) -> String {
    let line = rendered.lines().next().unwrap_or_default();
    line.strip_prefix("error: ").unwrap_or(line).to_string()
}

/// A closed pipe ends the process as it ends `cat` or `grep` (killed by SIGPIPE, status 141
/// in a shell), not with a panic: Rust ignores SIGPIPE by default, so `println!` into a closed
/// `| head` would panic.
fn restore_sigpipe() {
    #[cfg(unix)]
    // SAFETY: called first thing in `main`, before any other thread exists; setting a
    // signal's disposition to its default has no other effect.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Parses arguments, runs the command, and returns the process exit code.
fn main() -> ExitCode {
    restore_sigpipe();
    let cli = Cli::parse();
    if let Some(n) = cli.threads
        && let Err(e) = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()
    {
        eprintln!("error: cannot set up {n} threads: {e}");
        return ExitCode::from(1);
    }
    let color = match cli.color {
        Color::Auto => std::io::stderr().is_terminal(),
        Color::Always => true,
        Color::Never => false,
    };
    let options = cli.limits.options();
    // `watch` loads the tree itself, again at each change (a tree that does not load yet is
    // waited on, not the end).
    if let Command::Watch(args) = &cli.command {
        return watch::run(
            cli.root.as_deref(),
            options,
            &cli.profile,
            cli.json,
            color,
            args,
        );
    }
    let loaded = match &cli.root {
        Some(root) => Library::from_dir_with(root, &options),
        None => Library::from_raw(wgsl_variants_shaders::files(), &options),
    };
    let mut lib = match loaded {
        Ok(lib) => lib,
        Err(e) => {
            eprint!("{}", e.render(color));
            let message = format!(
                "the library could not be loaded ({} problem{})",
                e.problems.len(),
                if e.problems.len() == 1 { "" } else { "s" }
            );
            eprintln!("error: {message}");
            if cli.json {
                let problems = e
                    .diagnostics()
                    .iter()
                    .map(|d| JsonProblem {
                        message: d.message.clone(),
                        location: d.location(&e.files).map(|l| l.to_string()),
                    })
                    .collect();
                print_json_failure("load", message, problems);
            }
            return ExitCode::from(1);
        }
    };
    for warning in lib.warnings() {
        eprint!("{}", warning.render(lib.files(), color));
    }
    if !cli.profile.is_empty() {
        lib.set_profiles(&cli.profile);
    }
    let json = cli.json;
    let given = if cli.profile.is_empty() {
        &[][..]
    } else {
        lib.profiles()
    };
    if let Err(Failed(message)) = one_profile(&cli.command, given) {
        eprintln!("{message}");
        if json {
            print_json_failure("command", summary(&message), Vec::new());
        }
        return ExitCode::from(1);
    }
    let ctx = Context { lib, json, color };
    let result = match cli.command {
        Command::List { materials } => list::run(&ctx, &materials),
        Command::Validate { all, build, run } => validate::run(&ctx, all, &build, &run),
        Command::Emit(args) => emit::run(&ctx, &args),
        Command::Reflect(args) => reflect::run(&ctx, &args),
        Command::Bindings(args) => bindings::run(&ctx, &args),
        Command::Export(args) => export::run(&ctx, &args),
        Command::Audit(args) => audit::run(&ctx, &args),
        Command::Merge(args) => merge::run(&ctx, &args),
        Command::Cache(args) => cache::run(&ctx, &args),
        Command::Manifest {
            summary,
            shader,
            pass,
        } => manifest(&ctx, summary, shader.as_deref(), pass.as_deref()),
        Command::Watch(_) => unreachable!("watch is run before the library is loaded"),
        #[cfg(feature = "gpu")]
        Command::CheckGpu(args) => check_gpu::run(&ctx, &args),
        #[cfg(feature = "gpu")]
        Command::Render(args) => render::run(&ctx, &args),
    };
    match result {
        Ok(code) => code,
        Err(Failed(message)) => {
            eprintln!("{message}");
            if json {
                print_json_failure("command", summary(&message), Vec::new());
            }
            ExitCode::from(1)
        }
    }
}
