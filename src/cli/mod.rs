//! Command-line front end: argument parsing and dispatch. Each command lives in its own file.

mod audit;
mod emit;
mod list;
mod output;
mod validate;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

use wgsl_variants::Library;
use wgsl_variants::materials::{self, Material};

/// Unity-style shader variants for WGSL module trees, every variant validated by naga.
#[derive(Parser, Debug)]
#[command(name = "wgsl-variants", version, about, long_about = None)]
pub struct Cli {
    /// Library root (a folder of .wgsl modules). Default: the bundled library.
    #[arg(long, global = true, value_name = "DIR")]
    root: Option<PathBuf>,
    /// Print one JSON object on stdout instead of text.
    #[arg(long, global = true)]
    json: bool,
    /// Colours in diagnostics.
    #[arg(long, global = true, value_enum, default_value_t = Color::Auto)]
    color: Color,
    /// Worker threads (default: one per core). Output does not depend on it.
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Color {
    Auto,
    Always,
    Never,
}

/// Options shared by commands that build variants.
#[derive(clap::Args, Debug, Clone)]
pub struct BuildArgs {
    /// Materials file (JSON or TOML) restricting shader_feature combinations.
    #[arg(long, value_name = "FILE")]
    materials: Option<PathBuf>,
    /// Most variants built per pass; past it the command fails (counting stays exact).
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    max_variants: u64,
    /// Only this shader.
    #[arg(long, value_name = "SHADER")]
    shader: Option<String>,
    /// Only passes with this name.
    #[arg(long, value_name = "PASS")]
    pass: Option<String>,
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
    /// Print the final WGSL of one variant (validated first).
    Emit {
        /// Shader name.
        shader: String,
        /// Pass name.
        pass: String,
        /// Keywords that are on, comma-separated.
        #[arg(long, value_delimiter = ',', value_name = "A,B")]
        keywords: Vec<String>,
        /// Materials file: the variant must be in their build set.
        #[arg(long, value_name = "FILE")]
        materials: Option<PathBuf>,
        /// If the exact variant is not built, use the closest one (Unity without strict matching).
        #[arg(long)]
        closest: bool,
        /// Print the WGSL even if naga rejects it.
        #[arg(long)]
        no_validate: bool,
    },
    /// Variant counts per pass: full space, after skip_variants, build set, distinct, failures.
    Audit {
        #[command(flatten)]
        build: BuildArgs,
    },
}

/// Everything a command needs: the library and how to print.
pub struct Context {
    lib: Library,
    json: bool,
    color: bool,
}

impl Context {
    fn render(&self, d: &wgsl_variants::Diagnostic) -> String {
        d.render(self.lib.files(), self.color)
    }

    /// A failure about a pass, rendered at the pass's declaration with its keyword sets.
    fn pass_failure(&self, pass: &wgsl_variants::Pass, message: String) -> Failed {
        let mut d = wgsl_variants::Diagnostic::new(message).at(pass.span, "pass declared here");
        for set in &pass.sets {
            d = d.note(format!("{set}"));
        }
        Failed(self.render(&d))
    }
}

/// A command's failure: printed to stderr, exit code 1.
pub struct Failed(pub String);

impl<E: std::fmt::Display> From<E> for Failed {
    fn from(e: E) -> Failed {
        Failed(format!("error: {e}"))
    }
}

/// Reads a materials file if one was given.
fn load_materials(path: &Option<PathBuf>) -> Result<Option<Vec<Material>>, Failed> {
    Ok(match path {
        Some(p) => Some(materials::load(p)?),
        None => None,
    })
}

/// Parses arguments, runs the command, and returns the process exit code.
pub fn main() -> ExitCode {
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
    let loaded = match &cli.root {
        Some(root) => Library::from_dir(root),
        None => Library::bundled(),
    };
    let lib = match loaded {
        Ok(lib) => lib,
        Err(e) => {
            eprint!("{}", e.render(color));
            eprintln!(
                "error: the library could not be loaded ({} problem{})",
                e.diagnostics.len(),
                if e.diagnostics.len() == 1 { "" } else { "s" }
            );
            return ExitCode::from(1);
        }
    };
    let ctx = Context {
        lib,
        json: cli.json,
        color,
    };
    let result = match cli.command {
        Command::List { materials } => list::run(&ctx, &materials),
        Command::Validate { all, build, run } => validate::run(&ctx, all, &build, &run),
        Command::Emit {
            shader,
            pass,
            keywords,
            materials,
            closest,
            no_validate,
        } => emit::run(
            &ctx,
            &shader,
            &pass,
            &keywords,
            &materials,
            closest,
            !no_validate,
        ),
        Command::Audit { build } => audit::run(&ctx, &build),
    };
    match result {
        Ok(code) => code,
        Err(Failed(message)) => {
            eprintln!("{message}");
            ExitCode::from(1)
        }
    }
}
