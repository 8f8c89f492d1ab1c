//! `wgsl-variants emit`: one variant to stdout, or (with `--out DIR`) a variant or a whole
//! build set written to a folder with `manifest.json`, through any of naga's back ends.

use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::ValueEnum;

use wgsl_variants::emit::backends::{
    Options, Target, TargetKind, TranslateError, parse_glsl_version, parse_msl_version,
    parse_shader_model, translate_to_text,
};
use wgsl_variants::emit::set::{self, SetError, WriteSummary};
use wgsl_variants::emit::variant_source;

use super::context::{BuildArgs, Context, Failed, load_materials};
use super::output::print_json;

/// A naga back end, on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TargetArg {
    /// WGSL (default).
    Wgsl,
    /// SPIR-V binary (needs --out).
    Spirv,
    /// GLSL, one file per entry point (--glsl-version).
    Glsl,
    /// HLSL (--shader-model).
    Hlsl,
    /// Metal Shading Language (--msl-version).
    Msl,
}

/// `emit` arguments.
#[derive(clap::Args, Debug)]
pub struct EmitArgs {
    /// Shader name. Without SHADER and PASS, --out writes the whole build set.
    #[arg(value_name = "SHADER")]
    shader_name: Option<String>,
    /// Pass name.
    #[arg(value_name = "PASS")]
    pass_name: Option<String>,
    /// Keywords that are on, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "A,B")]
    keywords: Vec<String>,
    /// If the exact variant is not built, use the closest one (Unity without strict matching).
    #[arg(long)]
    closest: bool,
    /// Print the composed WGSL even if naga rejects it (WGSL to stdout only).
    #[arg(long)]
    no_validate: bool,
    /// Back end(s), repeated or comma-separated: wgsl (default), spirv, glsl, hlsl, msl.
    #[arg(
        long = "target",
        value_enum,
        value_delimiter = ',',
        value_name = "TARGET"
    )]
    targets: Vec<TargetArg>,
    /// GLSL version: 450 (desktop core: 140 … 460) or 300es, 310es, 320es.
    #[arg(long, value_name = "VERSION", default_value = "450")]
    glsl_version: String,
    /// HLSL shader model: 5_0, 5_1, 6_0 … 6_9.
    #[arg(long, value_name = "MODEL", default_value = "5_1")]
    shader_model: String,
    /// Metal Shading Language version, e.g. 2.0.
    #[arg(long, value_name = "VERSION", default_value = "2.0")]
    msl_version: String,
    /// Keep WGSL's coordinate space in SPIR-V and GLSL (no Y flip / depth remap).
    #[arg(long)]
    keep_coordinate_space: bool,
    /// WGSL to stdout: naga's canonical WGSL (validated, compacted) instead of the composed text.
    #[arg(long)]
    canonical: bool,
    /// GLSL to stdout: only this entry point.
    #[arg(long, value_name = "NAME")]
    entry_point: Option<String>,
    /// Write files and manifest.json into DIR instead of printing.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// With --out and no SHADER/PASS: the full space of every pass, not the build set.
    #[arg(long)]
    all: bool,
    /// With --out: only shard K of N of the variants (numbered across passes; `K/N`).
    #[arg(long, value_name = "K/N")]
    shard: Option<wgsl_variants::variants::Shard>,
    #[command(flatten)]
    build: BuildArgs,
}

fn targets(args: &EmitArgs) -> Result<Vec<Target>, Failed> {
    let mut out: Vec<Target> = Vec::new();
    let kinds = if args.targets.is_empty() {
        vec![TargetArg::Wgsl]
    } else {
        args.targets.clone()
    };
    for kind in kinds {
        let target = match kind {
            TargetArg::Wgsl => Target::Wgsl,
            TargetArg::Spirv => Target::SpirV,
            TargetArg::Glsl => {
                Target::Glsl(parse_glsl_version(&args.glsl_version).map_err(Failed::from)?)
            }
            TargetArg::Hlsl => {
                Target::Hlsl(parse_shader_model(&args.shader_model).map_err(Failed::from)?)
            }
            TargetArg::Msl => {
                let (major, minor) = parse_msl_version(&args.msl_version).map_err(Failed::from)?;
                Target::Msl(major, minor)
            }
        };
        if !out.contains(&target) {
            out.push(target);
        }
    }
    Ok(out)
}

fn render_failure(ctx: &Context, e: &TranslateError) -> String {
    match e {
        TranslateError::Invalid(v) => ctx.render(&v.diagnostic()),
        other => format!("error: {other}\n"),
    }
}

pub fn run(ctx: &Context, args: &EmitArgs) -> Result<ExitCode, Failed> {
    let targets = targets(args)?;
    let mut options = Options::default();
    options.keep_coordinate_space = args.keep_coordinate_space;
    let (shader, pass) = match (&args.shader_name, &args.pass_name) {
        (Some(s), Some(p)) => (s, p),
        (Some(_), None) => {
            return Err(Failed(
                "error: give SHADER and PASS (one variant), or neither with --out DIR (the build set)"
                    .into(),
            ));
        }
        (None, _) => return write_build_set(ctx, args, &targets, &options),
    };
    if args.build.shader.is_some() || args.build.pass.is_some() || args.all {
        return Err(Failed(
            "error: --shader, --pass and --all select passes of the build set; with SHADER PASS one variant is emitted"
                .into(),
        ));
    }
    let materials = load_materials(&args.build.materials)?;
    let pass = ctx.lib.pass(shader, pass)?;
    let variant = ctx.find_variant(pass, materials.as_deref(), &args.keywords, args.closest)?;

    if let Some(dir) = &args.out {
        let selection = vec![(pass, vec![variant.choice.clone()])];
        let origin = set::SetOrigin::default();
        return write_selection(ctx, &selection, &origin, &targets, &options, dir);
    }

    // The composed text, as written (the default).
    if targets == [Target::Wgsl] && !args.canonical {
        let source = match variant_source(&ctx.lib, &variant, !args.no_validate) {
            Ok(source) => source,
            Err(e) => {
                eprint!("{}", ctx.render(&e.diagnostic()));
                return Ok(ExitCode::from(1));
            }
        };
        if ctx.json {
            print_json(&source)?;
        } else {
            print!("{}", source.wgsl);
        }
        return Ok(ExitCode::SUCCESS);
    }
    if args.no_validate {
        return Err(Failed(
            "error: --no-validate applies to the composed WGSL only: the back ends need a valid module".into(),
        ));
    }
    if targets.contains(&Target::SpirV) {
        return Err(Failed(
            "error: SPIR-V is binary: write it into a folder with --out DIR".into(),
        ));
    }
    let mut translation = match translate_to_text(&ctx.lib, &variant, &targets, &options) {
        Ok(t) => t,
        Err(TranslateError::Invalid(e)) => {
            eprint!("{}", ctx.render(&e.diagnostic()));
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(Failed(render_failure(ctx, &e))),
    };
    if let Some(want) = &args.entry_point {
        translation
            .outputs
            .retain(|o| o.entry_point.as_ref().is_none_or(|ep| ep == want));
        if !translation
            .outputs
            .iter()
            .any(|o| o.entry_point.as_deref() == Some(want.as_str()))
            && targets.iter().any(|t| t.kind() == TargetKind::Glsl)
        {
            let names: Vec<&str> = translation
                .entry_points
                .iter()
                .map(|e| e.name.as_str())
                .collect();
            return Err(Failed(format!(
                "error: no entry point `{want}` in {} (entry points: {})",
                variant.label(),
                names.join(", ")
            )));
        }
    }
    let outputs = &translation.outputs;
    if ctx.json {
        print_json(&translation)?;
    } else {
        let single = outputs.len() == 1;
        let mut stdout = std::io::stdout().lock();
        for o in outputs {
            if !single {
                let what = match (&o.entry_point, o.stage) {
                    (Some(ep), Some(stage)) => format!("{}: {ep} ({stage})", o.target),
                    _ => o.target.clone(),
                };
                writeln!(stdout, "// ===== {what} =====")?;
            }
            write!(stdout, "{}", o.text)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn write_build_set(
    ctx: &Context,
    args: &EmitArgs,
    targets: &[Target],
    options: &Options,
) -> Result<ExitCode, Failed> {
    let Some(dir) = &args.out else {
        return Err(Failed(
            "error: give SHADER and PASS to print one variant, or --out DIR to write the whole build set".into(),
        ));
    };
    let plan_options = super::context::plan_options(&args.build, args.all, args.shard)?;
    let selection = ctx.plan(&plan_options)?;
    let origin = set::SetOrigin::new(&ctx.lib, &plan_options, targets, options);
    write_selection(ctx, &selection, &origin, targets, options, dir)
}

fn write_selection(
    ctx: &Context,
    selection: &wgsl_variants::plan::Plan<'_>,
    origin: &set::SetOrigin,
    targets: &[Target],
    options: &Options,
    dir: &std::path::Path,
) -> Result<ExitCode, Failed> {
    match set::write_set_from(&ctx.lib, selection, origin, targets, options, dir) {
        Ok(manifest) => {
            let summary = WriteSummary::new(dir, &manifest, targets);
            if ctx.json {
                print_json(&summary)?;
            } else {
                for (pass, choices) in selection {
                    println!("{}/{}: {} variants", pass.shader, pass.name, choices.len());
                }
                println!(
                    "wrote {} files for {} variants ({}) and manifest.json to {}",
                    summary.files,
                    summary.variants,
                    summary.targets.join(", "),
                    dir.display()
                );
            }
            Ok(ExitCode::SUCCESS)
        }
        Err(SetError::Failed(failures)) => {
            for f in &failures {
                eprint!("{}", render_failure(ctx, f));
            }
            eprintln!(
                "error: {} variant(s) failed; nothing was written",
                failures.len()
            );
            Ok(ExitCode::from(1))
        }
        Err(e) => Err(Failed::from(e)),
    }
}
