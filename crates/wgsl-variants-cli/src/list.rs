//! `wgsl-variants list`.

use std::path::PathBuf;
use std::process::ExitCode;

use super::context::{Context, Failed, load_materials};
use super::output::print_json;

pub fn run(ctx: &Context, materials: &Option<PathBuf>) -> Result<ExitCode, Failed> {
    let materials = load_materials(materials)?;
    let listing = ctx.lib.listing(materials.as_deref())?;
    if ctx.json {
        print_json(&listing)?;
        return Ok(ExitCode::SUCCESS);
    }
    for shader in &listing.shaders {
        println!("shader {} ({})", shader.name, shader.file);
        for p in &shader.passes {
            let pass = p.pass;
            let tags: Vec<String> = pass.tags.iter().map(|(k, v)| format!("{k}={v}")).collect();
            println!("  pass {} [{}]", pass.name, tags.join(" "));
            println!(
                "    variants: {} full space, {} after skip_variants, {} build set",
                p.full_space, p.after_skip, p.build_set
            );
            for set in &pass.sets {
                println!("    {:>3}x  {set}", set.len());
            }
            if let Some(stage) = pass.stage {
                let elsewhere: Vec<&str> = pass
                    .keywords()
                    .filter(|k| *k != "_" && pass.keyword_defs(k).is_empty())
                    .collect();
                if !elsewhere.is_empty() {
                    println!(
                        "    the {stage} stage gets no defs of: {}",
                        elsewhere.join(" ")
                    );
                }
            }
            if !pass.skip_variants.is_empty() {
                println!("    skip_variants {}", pass.skip_variants.join(" "));
            }
            for constraint in &pass.constraints {
                println!("    {constraint}");
            }
            if !pass.exclude_renderers.is_empty() {
                println!("    exclude_renderers {}", pass.exclude_renderers.join(" "));
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
