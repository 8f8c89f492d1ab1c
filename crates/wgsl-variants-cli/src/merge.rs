//! `wgsl-variants merge`: the outputs of N shards (`--shard K/N`) put back together into what
//! one run prints or writes (see [`wgsl_variants::merge`]).

use std::path::PathBuf;
use std::process::ExitCode;

use wgsl_variants::merge::{MergeError, manifest, validate};

use super::context::{Context, Failed};
use super::output::print_json;

/// `merge` arguments.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard outputs, all of one kind, in any order: `validate --json` reports,
    /// `check-gpu --json` reports, or `emit --out` folders.
    #[arg(required = true, value_name = "SHARD")]
    inputs: Vec<PathBuf>,
    /// With `emit --out` folders: the folder to write the merged set into.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

/// The kind of output a report file holds, by its fields.
enum Kind {
    Validate,
    #[cfg(feature = "gpu")]
    CheckGpu,
}

pub fn run(ctx: &Context, args: &MergeArgs) -> Result<ExitCode, Failed> {
    let dirs = args.inputs.iter().filter(|p| p.is_dir()).count();
    if dirs == args.inputs.len() {
        return merge_folders(ctx, args);
    }
    if dirs > 0 {
        return Err(Failed(
            "error: give shard outputs of one kind: report files or `emit --out` folders".into(),
        ));
    }
    if args.out.is_some() {
        return Err(Failed(
            "error: --out is for `emit --out` folders; merged reports are printed".into(),
        ));
    }
    let mut inputs = Vec::new();
    let mut kind = None;
    for path in &args.inputs {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| {
            Failed::from(MergeError::Read {
                shard: name.clone(),
                source: e,
            })
        })?;
        let this = kind_of(&name, &text)?;
        kind.get_or_insert(this);
        inputs.push((name, text));
    }
    let (text, ok) = match kind {
        Some(Kind::Validate) => validate::merge_reports(&inputs)?,
        #[cfg(feature = "gpu")]
        Some(Kind::CheckGpu) => wgsl_variants_gpu::check::merge::merge_reports(&inputs)?,
        None => return Err(Failed::from(MergeError::Empty)),
    };
    print!("{text}");
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn kind_of(name: &str, text: &str) -> Result<Kind, Failed> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        Failed::from(MergeError::NotJson {
            shard: name.to_string(),
            source: e,
        })
    })?;
    if value.get("selection").is_some() {
        return Ok(Kind::Validate);
    }
    #[cfg(feature = "gpu")]
    if value.get("adapter").is_some() {
        return Ok(Kind::CheckGpu);
    }
    Err(Failed(format!(
        "error: `{name}` is neither a `validate --json` nor a `check-gpu --json` report"
    )))
}

fn merge_folders(ctx: &Context, args: &MergeArgs) -> Result<ExitCode, Failed> {
    let Some(out) = &args.out else {
        return Err(Failed(
            "error: merging `emit --out` folders needs --out DIR for the merged set".into(),
        ));
    };
    let merged = manifest::merge_folders(&args.inputs, out)?;
    if ctx.json {
        print_json(&merged)?;
    } else {
        println!(
            "merged {} shards: {} files for {} variants and manifest.json to {}",
            args.inputs.len(),
            merged.files,
            merged.variants,
            out.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
