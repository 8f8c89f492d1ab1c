//! `wgsl-variants bindings`: the typed Rust module of one pass.

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::bindings::{self, BindingsError};

use super::context::{Context, Failed};

/// `bindings` arguments.
#[derive(clap::Args, Debug)]
pub struct BindingsArgs {
    /// Shader name.
    shader: String,
    /// Pass name.
    pass: String,
    /// Write the module to this file instead of stdout (rewritten only when it changes).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also write the interfaces as wgpu's types (bind group layout entries, vertex buffer
    /// layout, colour target states); the module then needs `wgpu` 30.
    #[arg(long)]
    wgpu: bool,
    /// Most variants read; past it the command fails.
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    max_variants: u64,
}

pub fn run(ctx: &Context, args: &BindingsArgs) -> Result<ExitCode, Failed> {
    let pass = ctx.lib.pass(&args.shader, &args.pass)?;
    let options = bindings::Options::default().wgpu(args.wgpu);
    let generated = match bindings::generate_with(&ctx.lib, pass, args.max_variants, &options) {
        Ok(g) => g,
        Err(BindingsError::Variant(e)) => {
            eprint!("{}", ctx.render(&e.diagnostic()));
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(e.into()),
    };
    match &args.out {
        Some(path) => {
            if std::fs::read(path).ok().as_deref() != Some(generated.code.as_bytes()) {
                std::fs::write(path, &generated.code).map_err(|e| {
                    Failed(format!("error: cannot write `{}`: {e}", path.display()))
                })?;
            }
            eprintln!(
                "{}/{}: {} variants ({} distinct texts), {} structs, {} interfaces -> {}",
                pass.shader,
                pass.name,
                generated.variants,
                generated.distinct_texts,
                generated.structs,
                generated.interfaces,
                path.display()
            );
        }
        None => print!("{}", generated.code),
    }
    Ok(ExitCode::SUCCESS)
}
