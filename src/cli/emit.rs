//! `wgsl-variants emit`.

use std::path::PathBuf;
use std::process::ExitCode;

use serde::Serialize;

use wgsl_variants::Variant;
use wgsl_variants::lookup::{lookup_closest, lookup_strict};
use wgsl_variants::validate::validate_composed;

use super::output::print_json;
use super::{Context, Failed, load_materials};

#[derive(Serialize)]
struct EmitOut<'a> {
    shader: &'a str,
    #[serde(rename = "pass")]
    pass_name: &'a str,
    keywords: Vec<&'a str>,
    wgsl: &'a str,
}

/// Neighbour search for error messages and `--closest` looks at most this many variants.
const NEIGHBOUR_BUDGET: u64 = 1_000_000;

pub fn run(
    ctx: &Context,
    shader: &str,
    pass: &str,
    keywords: &[String],
    materials: &Option<PathBuf>,
    closest: bool,
    validate: bool,
) -> Result<ExitCode, Failed> {
    let materials = load_materials(materials)?;
    let pass = ctx.lib.pass(shader, pass)?;
    let space = ctx.lib.build_set(pass, materials.as_deref())?;
    let keywords: Vec<&str> = keywords
        .iter()
        .map(|k| k.trim())
        .filter(|k| !k.is_empty())
        .collect();
    let found = if closest {
        lookup_closest(&space, &keywords, NEIGHBOUR_BUDGET)
    } else {
        lookup_strict(&space, &keywords, NEIGHBOUR_BUDGET)
    };
    let choice = found.map_err(|e| ctx.pass_failure(pass, format!("{e}")))?;
    let variant = Variant { pass, choice };
    let composed = ctx.lib.compose(&variant);
    if validate && let Err(e) = validate_composed(&composed, &variant.label()) {
        eprint!("{}", ctx.render(&e.diagnostic()));
        return Ok(ExitCode::from(1));
    }
    if closest && variant.keywords() != keywords {
        eprintln!(
            "note: no exact variant; using the closest, {}",
            variant.label()
        );
    }
    if ctx.json {
        print_json(&EmitOut {
            shader: &pass.shader,
            pass_name: &pass.name,
            keywords: variant.keywords(),
            wgsl: &composed.text,
        })?;
    } else {
        print!("{}", composed.text);
    }
    Ok(ExitCode::SUCCESS)
}
