//! `wgsl-variants list`.

use std::path::PathBuf;
use std::process::ExitCode;

use serde::Serialize;
use serde_json::value::RawValue;

use wgsl_variants::variants::Space;

use super::output::{count, print_json};
use super::{Context, Failed, load_materials};

#[derive(Serialize)]
struct SetOut {
    kind: wgsl_variants::preprocess::tree::SetKind,
    local: bool,
    options: Vec<Option<String>>,
}

#[derive(Serialize)]
struct PassOut {
    name: String,
    tags: Vec<(String, String)>,
    keyword_sets: Vec<SetOut>,
    skip_variants: Vec<String>,
    exclude_renderers: Vec<String>,
    full_space: Box<RawValue>,
    after_skip: Box<RawValue>,
    build_set: Box<RawValue>,
}

#[derive(Serialize)]
struct ShaderOut {
    name: String,
    file: String,
    passes: Vec<PassOut>,
}

#[derive(Serialize)]
struct ListOut {
    shaders: Vec<ShaderOut>,
}

pub fn run(ctx: &Context, materials: &Option<PathBuf>) -> Result<ExitCode, Failed> {
    let materials = load_materials(materials)?;
    let mut shaders = Vec::new();
    for shader in ctx.lib.shaders() {
        let mut passes = Vec::new();
        for pass in &shader.passes {
            let build = ctx.lib.build_set(pass, materials.as_deref())?;
            passes.push(PassOut {
                name: pass.name.clone(),
                tags: pass.tags.clone(),
                keyword_sets: pass
                    .sets
                    .iter()
                    .map(|s| SetOut {
                        kind: s.kind,
                        local: s.local,
                        options: s.options.clone(),
                    })
                    .collect(),
                skip_variants: pass.skip_variants.clone(),
                exclude_renderers: pass.exclude_renderers.clone(),
                full_space: count(&Space::full(pass).count()),
                after_skip: count(&Space::after_skip(pass).count()),
                build_set: count(&build.count()),
            });
        }
        shaders.push(ShaderOut {
            name: shader.name.clone(),
            file: ctx.lib.files().path(shader.file).to_string(),
            passes,
        });
    }
    if ctx.json {
        print_json(&ListOut { shaders })?;
        return Ok(ExitCode::SUCCESS);
    }
    for (shader, s) in shaders.iter().zip(ctx.lib.shaders()) {
        println!("shader {} ({})", shader.name, shader.file);
        for (p, pass) in shader.passes.iter().zip(&s.passes) {
            let tags: Vec<String> = p.tags.iter().map(|(k, v)| format!("{k}={v}")).collect();
            println!("  pass {} [{}]", p.name, tags.join(" "));
            println!(
                "    variants: {} full space, {} after skip_variants, {} build set",
                p.full_space, p.after_skip, p.build_set
            );
            for set in &pass.sets {
                println!("    {:>3}x  {set}", set.len());
            }
            if !p.skip_variants.is_empty() {
                println!("    skip_variants {}", p.skip_variants.join(" "));
            }
            if !p.exclude_renderers.is_empty() {
                println!("    exclude_renderers {}", p.exclude_renderers.join(" "));
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
