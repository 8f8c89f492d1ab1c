//! `wgsl-variants reflect`: the entry points and bindings of one variant.

use std::path::PathBuf;
use std::process::ExitCode;

use super::context::{Context, Failed, load_materials};
use super::output::print_json;

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

pub fn run(ctx: &Context, args: &ReflectArgs) -> Result<ExitCode, Failed> {
    let materials = load_materials(&args.materials)?;
    let pass = ctx.lib.pass(&args.shader, &args.pass)?;
    let variant = ctx.find_variant(pass, materials.as_deref(), &args.keywords, args.closest)?;
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
