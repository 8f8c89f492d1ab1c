//! `wgsl-variants cache`: the state of the cache of valid texts, and its export to and import
//! from one file (for a CI cache step). See [`wgsl_variants::cache`].

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use wgsl_variants::cache::{ValidCache, import};

use super::context::{Context, Failed};
use super::output::print_json;

/// `cache` arguments.
#[derive(clap::Args, Debug)]
pub struct CacheArgs {
    /// The cache folder [default: as `validate`'s].
    #[arg(long, value_name = "DIR", global = true)]
    cache: Option<PathBuf>,
    #[command(subcommand)]
    action: Action,
}

#[derive(clap::Subcommand, Debug)]
enum Action {
    /// Entries, segment files and corrupt records of the cache.
    Info,
    /// Write every entry to one file.
    Export {
        /// The file to write.
        file: PathBuf,
    },
    /// Add the entries of a file written by `cache export` (of this same version).
    Import {
        /// The file to read.
        file: PathBuf,
    },
}

/// The cache folder: `dir`, or `target/wgsl-variants-cache` when `./target` or
/// `./Cargo.toml` exists.
pub fn default_dir(dir: Option<&Path>) -> Option<PathBuf> {
    dir.map(Path::to_path_buf).or_else(|| {
        (Path::new("target").is_dir() || Path::new("Cargo.toml").is_file())
            .then(|| PathBuf::from("target/wgsl-variants-cache"))
    })
}

/// Opens the cache in `dir`, with a warning for each corrupt file found.
pub fn open(dir: &Path) -> ValidCache {
    let cache = ValidCache::open(dir);
    for problem in cache.problems() {
        eprintln!("warning: cache: {problem}");
    }
    cache
}

/// `cache info --json`.
#[derive(serde::Serialize)]
struct Info {
    folder: String,
    entries: usize,
    segments: usize,
    corrupt: usize,
}

pub fn run(ctx: &Context, args: &CacheArgs) -> Result<ExitCode, Failed> {
    let dir = default_dir(args.cache.as_deref()).ok_or_else(|| {
        Failed("error: no cache folder: give --cache DIR (or run in a Cargo project)".into())
    })?;
    match &args.action {
        Action::Info => {
            let cache = open(&dir);
            let info = Info {
                folder: cache.folder().display().to_string(),
                entries: cache.len(),
                segments: cache.segments(),
                corrupt: cache.corrupt(),
            };
            if ctx.json {
                print_json(&info)?;
            } else {
                println!(
                    "{}: {} entries in {} segment(s), {} corrupt record(s) ignored",
                    info.folder, info.entries, info.segments, info.corrupt
                );
            }
        }
        Action::Export { file } => {
            let n = open(&dir).export(file)?;
            println!("exported {n} entries to {}", file.display());
        }
        Action::Import { file } => {
            let imported = import(&dir, file)?;
            if imported.corrupt > 0 {
                eprintln!(
                    "warning: {} corrupt record(s) in {} left out",
                    imported.corrupt,
                    file.display()
                );
            }
            println!(
                "imported {} entries from {} into {}",
                imported.entries,
                file.display(),
                dir.display()
            );
        }
    }
    Ok(ExitCode::SUCCESS)
}
