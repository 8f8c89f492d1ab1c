//! `wgsl-variants reflect`: the entry points and bindings of one variant.

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::Variant;
use wgsl_variants::lookup::{lookup_closest, lookup_strict};

use super::output::print_json;
use super::{Context, Failed, load_materials};

/// `reflect` arguments.
#[derive(clap::Args, Debug)]
pub struct ReflectArgs {
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
    /// If the exact variant is not built, use the closest one.
    #[arg(long)]
    closest: bool,
}

/// Neighbour search for error messages and `--closest` looks at most this many variants.
const NEIGHBOUR_BUDGET: u64 = 1_000_000;

pub fn run(ctx: &Context, args: &ReflectArgs) -> Result<ExitCode, Failed> {
    let materials = load_materials(&args.materials)?;
    let pass = ctx.lib.pass(&args.shader, &args.pass)?;
    let space = ctx.lib.build_set(pass, materials.as_deref())?;
    let keywords: Vec<&str> = args
        .keywords
        .iter()
        .map(|k| k.trim())
        .filter(|k| !k.is_empty())
        .collect();
    let found = if args.closest {
        lookup_closest(&space, &keywords, NEIGHBOUR_BUDGET)
    } else {
        lookup_strict(&space, &keywords, NEIGHBOUR_BUDGET)
    };
    let choice = found.map_err(|e| ctx.pass_failure(pass, format!("{e}")))?;
    let variant = Variant { pass, choice };
    if args.closest && variant.keywords() != keywords {
        eprintln!(
            "note: no exact variant; using the closest, {}",
            variant.label()
        );
    }
    let reflection = match ctx.lib.reflect(&variant) {
        Ok(r) => r,
        Err(e) => {
            eprint!("{}", ctx.render(&e.diagnostic()));
            return Ok(ExitCode::from(1));
        }
    };
    if ctx.json {
        print_json(&reflection)?;
    } else {
        print!("{}", reflection.to_text());
    }
    Ok(ExitCode::SUCCESS)
}
