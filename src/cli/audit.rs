//! `wgsl-variants audit`: variant counts per pass.

use std::process::ExitCode;

use serde::Serialize;
use serde_json::value::RawValue;

use wgsl_variants::variants::Space;

use super::output::{count, print_json};
use super::validate::build_reports;
use super::{BuildArgs, Context, Failed, load_materials};

#[derive(Serialize)]
struct AuditPass {
    shader: String,
    #[serde(rename = "pass")]
    pass_name: String,
    full_space: Box<RawValue>,
    after_filtering: Box<RawValue>,
    build_set: Box<RawValue>,
    distinct: u64,
    invalid: u64,
}

#[derive(Serialize)]
struct AuditOut {
    passes: Vec<AuditPass>,
}

pub fn run(ctx: &Context, build: &BuildArgs) -> Result<ExitCode, Failed> {
    let materials = load_materials(&build.materials)?;
    let reports = build_reports(ctx, false, build)?;
    let mut passes = Vec::new();
    for r in &reports {
        let pass = ctx.lib.pass(&r.shader, &r.pass)?;
        passes.push(AuditPass {
            shader: r.shader.clone(),
            pass_name: r.pass.clone(),
            full_space: count(&Space::full(pass).count()),
            after_filtering: count(&Space::after_skip(pass).count()),
            build_set: count(&ctx.lib.build_set(pass, materials.as_deref())?.count()),
            distinct: r.distinct,
            invalid: r.invalid,
        });
    }
    let failed = passes.iter().any(|p| p.invalid > 0);
    if ctx.json {
        print_json(&AuditOut { passes })?;
    } else {
        println!(
            "{:<32} {:>14} {:>16} {:>12} {:>10} {:>8}",
            "shader/pass", "full space", "after skip", "build set", "distinct", "invalid"
        );
        for p in &passes {
            println!(
                "{:<32} {:>14} {:>16} {:>12} {:>10} {:>8}",
                format!("{}/{}", p.shader, p.pass_name),
                p.full_space.get(),
                p.after_filtering.get(),
                p.build_set.get(),
                p.distinct,
                p.invalid
            );
        }
    }
    Ok(if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}
