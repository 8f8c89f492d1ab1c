//! What every command shares: the loaded library and how to print ([`Context`]), the options
//! of commands that build variants ([`BuildArgs`]), and a command's failure ([`Failed`]).
//! Below the commands: each command module imports this one, never `main`.

use std::path::PathBuf;

use wgsl_variants::Library;
use wgsl_variants::covering::MAX_INTERACTIONS;
use wgsl_variants::materials::{self, Material};

/// Options shared by commands that build variants.
#[derive(clap::Args, Debug, Clone)]
pub struct BuildArgs {
    /// Materials file (JSON or TOML) restricting shader_feature combinations.
    #[arg(long, value_name = "FILE")]
    pub(crate) materials: Option<PathBuf>,
    /// Most variants built per pass; past it the command fails (counting stays exact).
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    pub(crate) max_variants: u64,
    /// Only this shader.
    #[arg(long, value_name = "SHADER")]
    pub(crate) shader: Option<String>,
    /// Only passes with this name.
    #[arg(long, value_name = "PASS")]
    pub(crate) pass: Option<String>,
    /// Build a t-wise covering set (T from 1 to 4) of each pass instead of every variant:
    /// every combination of options of every T keyword sets, in a few variants.
    #[arg(long, value_name = "T")]
    pub(crate) cover: Option<usize>,
    /// With --cover: cover only passes whose space holds more than N variants and build the
    /// others whole (every variant of the small passes, a covering set of the huge ones).
    #[arg(long, value_name = "N", requires = "cover")]
    pub(crate) cover_above: Option<u64>,
}

/// Everything a command needs: the library and how to print.
pub struct Context {
    pub(crate) lib: Library,
    pub(crate) json: bool,
    pub(crate) color: bool,
}

impl Context {
    pub(crate) fn render(&self, d: &wgsl_variants::Diagnostic) -> String {
        d.render(self.lib.files(), self.color)
    }

    /// The variant of `pass` with `keywords` on, in the build set of `materials`: strict, or
    /// the closest one with `closest` (with a note on stderr when it differs).
    pub(crate) fn find_variant<'l>(
        &'l self,
        pass: &'l wgsl_variants::Pass,
        materials: Option<&[Material]>,
        keywords: &[String],
        closest: bool,
    ) -> Result<wgsl_variants::Variant<'l>, Failed> {
        // Neighbour search for error messages and `--closest` looks at most this many variants.
        const NEIGHBOUR_BUDGET: u64 = 1_000_000;
        let space = self.lib.build_set(pass, materials)?;
        let keywords: Vec<&str> = keywords
            .iter()
            .map(|k| k.trim())
            .filter(|k| !k.is_empty())
            .collect();
        let found = if closest {
            wgsl_variants::lookup::lookup_closest(&space, &keywords, NEIGHBOUR_BUDGET)
        } else {
            wgsl_variants::lookup::lookup_strict(&space, &keywords, NEIGHBOUR_BUDGET)
        };
        let choice = found.map_err(|e| self.pass_failure(pass, format!("{e}")))?;
        let variant = wgsl_variants::Variant { pass, choice };
        if closest && variant.keywords() != keywords {
            eprintln!(
                "note: no exact variant; using the closest, {}",
                variant.label()
            );
        }
        Ok(variant)
    }

    /// The plan of `options`. A pass over its budget is reported at its declaration. A covering
    /// set that will take a while to generate is announced first, with its size.
    pub fn plan(
        &self,
        options: &wgsl_variants::plan::PlanOptions,
    ) -> Result<wgsl_variants::plan::Plan<'_>, Failed> {
        if let Some(t) = options.cover {
            self.announce_cover(options, t);
        }
        wgsl_variants::plan::plan(&self.lib, options).map_err(|e| match &e {
            wgsl_variants::plan::PlanError::Budget { shader, pass, .. } => {
                match self.lib.pass(shader, pass) {
                    Ok(p) => self.pass_failure(p, e.to_string()),
                    Err(_) => Failed::from(e),
                }
            }
            wgsl_variants::plan::PlanError::Cover(cover) => {
                let (shader, pass) = cover.pass();
                match self.lib.pass(shader, pass) {
                    Ok(p) => self.pass_failure(p, e.to_string()),
                    Err(_) => Failed::from(e),
                }
            }
            _ => Failed::from(e),
        })
    }

    /// A note on stderr for each pass whose t-wise covering set must cover more than ten
    /// million combinations of options (a generation of seconds to minutes), with the estimate
    /// measured on a 2-core machine (2026-11-27: 7.8 million combinations in about 2.7 s).
    fn announce_cover(&self, options: &wgsl_variants::plan::PlanOptions, t: usize) {
        let passes = wgsl_variants::plan::select_passes(
            &self.lib,
            options.shader.as_deref(),
            options.pass.as_deref(),
        )
        .unwrap_or_default();
        for pass in passes {
            let space = wgsl_variants::Space::full(pass);
            let covered = options
                .cover_above
                .is_none_or(|above| space.count() > above.into());
            let work = space.covering_work(t);
            if covered && t <= pass.sets.len() && work > 10_000_000 && work <= MAX_INTERACTIONS {
                let seconds = work as f64 / 7.8e6 * 2.7;
                eprintln!(
                    "note: {}/{}: a t = {t} covering set must cover {work} combinations of options; generating it takes about {seconds:.0} s on 2 cores",
                    pass.shader, pass.name
                );
            }
        }
    }

    /// A failure about a pass, rendered at the pass's declaration with its keyword sets.
    pub(crate) fn pass_failure(&self, pass: &wgsl_variants::Pass, message: String) -> Failed {
        let mut d = wgsl_variants::Diagnostic::new(message).at(pass.span, "pass declared here");
        for set in &pass.sets {
            d = d.note(format!("{set}"));
        }
        Failed(self.render(&d))
    }
}

/// The plan options of `build` (the full space with `all`, one shard with `shard`).
pub fn plan_options(
    build: &BuildArgs,
    all: bool,
    shard: Option<wgsl_variants::variants::Shard>,
) -> Result<wgsl_variants::plan::PlanOptions, Failed> {
    let mut options = wgsl_variants::plan::PlanOptions::default();
    options.all = all;
    options.materials = load_materials(&build.materials)?;
    options.budget = build.max_variants;
    options.shader = build.shader.clone();
    options.pass = build.pass.clone();
    options.shard = shard;
    options.cover = build.cover;
    options.cover_above = build.cover_above;
    Ok(options)
}

/// A command's failure: printed to stderr, exit code 1.
pub struct Failed(pub String);

impl<E: std::fmt::Display> From<E> for Failed {
    fn from(e: E) -> Failed {
        Failed(format!("error: {e}"))
    }
}

/// Reads a materials file if one was given.
pub(crate) fn load_materials(path: &Option<PathBuf>) -> Result<Option<Vec<Material>>, Failed> {
    Ok(match path {
        Some(p) => Some(materials::load(p)?),
        None => None,
    })
}
