//! `wgsl-variants export`: one module (with its imports) on its own, as self-contained
//! prefixed WGSL, in naga_oil's dialect or in WESL's.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::ValueEnum;

use wgsl_variants::emit::export::{ExportError, export_prefixed_module};
use wgsl_variants::emit::naga_oil::{self, NagaOilModule};
use wgsl_variants::emit::wesl::{self, WeslModule};

use super::context::{Context, Failed};
use super::output::print_json;

/// The output dialect.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Dialect {
    /// Self-contained WGSL, every top-level name prefixed (needs --prefix).
    Wgsl,
    /// naga_oil modules (`#define_import_path`, `#import`, `#ifdef`), for Bevy.
    NagaOil,
    /// WESL modules (`import package::…`, `@if`), for WESL users (Bevy's main branch).
    Wesl,
}

/// `export` arguments.
#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// Module path, e.g. deferred/gbuffer (not a shader file).
    #[arg(value_name = "MODULE", required_unless_present = "all")]
    module: Option<String>,
    /// WGSL: the prefix of every top-level name. naga_oil: the root of the import paths.
    #[arg(long, value_name = "NAME")]
    prefix: Option<String>,
    /// WGSL: keywords defined (as 1) when composing, comma-separated.
    #[arg(long, value_delimiter = ',', value_name = "A,B")]
    keywords: Vec<String>,
    /// Output dialect.
    #[arg(long, value_enum, default_value_t = Dialect::Wgsl)]
    dialect: Dialect,
    /// naga_oil, WESL: every module of the library (WESL: and each pass's root).
    #[arg(long)]
    all: bool,
    /// Write into DIR (naga_oil: the module and every module it imports, one file each, at
    /// their library paths) instead of printing the module.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

fn fail(ctx: &Context, e: ExportError) -> Failed {
    Failed(ctx.render(&e.diagnostic()).trim_end().to_string())
}

fn write(dir: &Path, rel: &str, text: &str) -> Result<(), Failed> {
    let path = dir.join(rel);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)
            .map_err(|e| Failed(format!("error: cannot create `{}`: {e}", parent.display())))?;
    }
    std::fs::write(&path, text)
        .map_err(|e| Failed(format!("error: cannot write `{}`: {e}", path.display())))
}

pub fn run(ctx: &Context, args: &ExportArgs) -> Result<ExitCode, Failed> {
    if ctx.lib.dialect() != wgsl_variants::Dialect::WgslVariants {
        return Err(Failed(format!(
            "error: export turns modules of this crate's dialect into other dialects; this is a {} tree already",
            ctx.lib.dialect().name()
        )));
    }
    let keywords: Vec<&str> = args
        .keywords
        .iter()
        .map(|k| k.trim())
        .filter(|k| !k.is_empty())
        .collect();
    match args.dialect {
        Dialect::Wgsl => {
            let (Some(module), false) = (&args.module, args.all) else {
                return Err(Failed(
                    "error: --all exports naga_oil modules; the WGSL dialect exports one MODULE"
                        .into(),
                ));
            };
            let Some(prefix) = &args.prefix else {
                return Err(Failed("error: the WGSL dialect needs --prefix NAME (the prefix of every top-level name)".into()));
            };
            let exported = export_prefixed_module(&ctx.lib, module, prefix, &keywords)
                .map_err(|e| fail(ctx, e))?;
            if let Some(dir) = &args.out {
                let rel = format!("{}.wgsl", module.trim().trim_end_matches(".wgsl"));
                write(dir, &rel, &exported.source)?;
                println!("wrote {}", dir.join(rel).display());
            } else if ctx.json {
                print_json(&exported)?;
            } else {
                print!("{}", exported.source);
            }
        }
        Dialect::Wesl => {
            if !keywords.is_empty() || args.prefix.is_some() {
                return Err(Failed("error: WESL modules keep their conditions and live under `package::`: set keywords as WESL features when compiling, without --keywords or --prefix".into()));
            }
            let mut modules: Vec<WeslModule> = match (&args.module, args.all) {
                (_, true) => wesl::export_all(&ctx.lib),
                (Some(m), false) => wesl::export(&ctx.lib, m),
                (None, false) => unreachable!("clap requires MODULE without --all"),
            }
            .map_err(|e| fail(ctx, e))?;
            let mut roots = Vec::new();
            if args.all {
                // Each pass's program: its root module and the features its `#define`s set.
                for pass in ctx.lib.passes() {
                    let p = wesl::export_pass(&ctx.lib, pass).map_err(|e| fail(ctx, e))?;
                    let features = if p.features.is_empty() {
                        String::new()
                    } else {
                        format!(" + {}", p.features.join(", "))
                    };
                    roots.push(format!(
                        "{}/{}: compile {} with features: the variant's keywords{features}",
                        pass.shader, pass.name, p.root.module_path,
                    ));
                    if !modules.iter().any(|m| m.path == p.root.path) {
                        modules.push(p.root);
                    }
                }
            }
            if let Some(dir) = &args.out {
                // With --all, the keywords too: the folder is a WESL tree `--root` reads back.
                let files = if args.all {
                    wesl::export_tree(&ctx.lib).map_err(|e| fail(ctx, e))?
                } else {
                    modules
                        .iter()
                        .map(|m| (format!("{}.wesl", m.path), m.source.clone()))
                        .collect()
                };
                for (path, text) in &files {
                    write(dir, path, text)?;
                }
                println!(
                    "wrote {} WESL module(s) to {}",
                    modules.len(),
                    dir.display()
                );
                if args.all {
                    println!(
                        "wrote {} (check the export: wgsl-variants --root {} validate --all)",
                        wgsl_variants::declaration::FILE_NAME,
                        dir.display()
                    );
                }
                for r in &roots {
                    println!("{r}");
                }
            } else if ctx.json {
                let shown: Vec<&WeslModule> = if args.all {
                    modules.iter().collect()
                } else {
                    modules.last().into_iter().collect()
                };
                print_json(&shown)?;
            } else if args.all {
                for m in &modules {
                    print!("{}", m.source);
                }
            } else if let Some(m) = modules.last() {
                print!("{}", m.source);
                if modules.len() > 1 {
                    let deps: Vec<&str> = modules[..modules.len() - 1]
                        .iter()
                        .map(|m| m.path.as_str())
                        .collect();
                    eprintln!(
                        "note: it imports {} (use --out DIR to write them all)",
                        deps.join(", ")
                    );
                }
            }
        }
        Dialect::NagaOil => {
            if !keywords.is_empty() {
                return Err(Failed("error: naga_oil modules keep their conditions: pass keywords as shader defs when composing, not with --keywords".into()));
            }
            let root = args.prefix.as_deref();
            let modules: Vec<NagaOilModule> = match (&args.module, args.all) {
                (_, true) => naga_oil::export_all(&ctx.lib, root),
                (Some(m), false) => naga_oil::export(&ctx.lib, m, root),
                (None, false) => unreachable!("clap requires MODULE without --all"),
            }
            .map_err(|e| fail(ctx, e))?;
            if let Some(dir) = &args.out {
                for m in &modules {
                    write(dir, &format!("{}.wgsl", m.path), &m.source)?;
                }
                println!(
                    "wrote {} naga_oil module(s) to {}",
                    modules.len(),
                    dir.display()
                );
            } else {
                // Without --out: the module asked for (every module with --all).
                let shown: Vec<&NagaOilModule> = if args.all {
                    modules.iter().collect()
                } else {
                    modules.last().into_iter().collect()
                };
                if ctx.json {
                    print_json(&shown)?;
                } else {
                    for m in &shown {
                        print!("{}", m.source);
                    }
                    if !args.all && modules.len() > 1 {
                        let deps: Vec<&str> = modules[..modules.len() - 1]
                            .iter()
                            .map(|m| m.path.as_str())
                            .collect();
                        eprintln!(
                            "note: register its imports first: {} (use --out DIR to write them all)",
                            deps.join(", ")
                        );
                    }
                }
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
