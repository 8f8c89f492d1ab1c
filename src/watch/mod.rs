//! Validating a tree again as it changes: the library side of `wgsl-variants watch`, and what
//! a renderer's hot reload calls when a shader file changes.
//!
//! A [`Session`] reloads its tree at each [`Session::run`] and validates what the change can
//! have broken, in the order most likely to show a diagnostic soon:
//!
//! 1. A pass whose inputs did not change keeps its last report, and nothing of it is composed.
//!    Its inputs are its module files (its module and every module it imports,
//!    [`Library::pass_files`]), its declaration and the plan options; a variant's text is
//!    made of nothing else.
//! 2. Of the other passes, the variants that failed most recently are validated first, then a
//!    pairwise covering set of each pass ([`Space::covering`](crate::Space::covering) with
//!    t = 2: every pair of keyword options in a few dozen variants), so an error that one or
//!    two keywords bring in shows within them.
//! 3. Then every variant of those passes, in enumeration order, exactly as `validate` does,
//!    with the cache of valid texts: a text validated in step 2 or in an earlier run is not
//!    validated again.
//!
//! Failures stream as they are found ([`Event::Failure`], each error — message and place —
//! once per run, however many variants it breaks).
//! The [`Verdict`]'s report is the one [`validate_plan`](crate::validate::validate_plan) gives
//! for the same tree and options. A run stops between batches once its `cancel` flag is set (a
//! newer change is waiting); the next run keeps what it finished and the texts it validated.
//!
//! ```
//! use std::sync::atomic::AtomicBool;
//! use wgsl_variants::plan::PlanOptions;
//! use wgsl_variants::watch::{Event, Outcome, Session};
//!
//! let dir = std::env::temp_dir().join(format!("wv-watch-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! let shader = "#shader s\n#pass P\n#pragma multi_compile _ RED\n\
//!     @fragment fn fs() -> @location(0) vec4f {\n#if RED\n    return vec4f(1.0);\n#else\n    return vec4f(0.5);\n#endif\n}\n#endpass\n";
//! std::fs::write(dir.join("s.wgsl"), shader).unwrap();
//! let mut session = Session::new(&dir, Default::default(), PlanOptions::default(), None);
//! let never = AtomicBool::new(false);
//! let Outcome::Verdict(v) = session.run(&never, &|_| {}).unwrap() else { unreachable!() };
//! assert!(v.report.ok && v.report.totals.built == 2);
//!
//! // A typo under `#if RED`: only the variant with RED fails, and it is reported as found.
//! std::fs::write(dir.join("s.wgsl"), shader.replace("vec4f(1.0)", "vec4(1.0")).unwrap();
//! let found = std::sync::Mutex::new(Vec::new());
//! let Outcome::Verdict(v) = session
//!     .run(&never, &|e| if let Event::Failure { error, .. } = e { found.lock().unwrap().push(error.variant.clone()) })
//!     .unwrap() else { unreachable!() };
//! assert_eq!(v.report.totals.invalid, 1);
//! assert_eq!(found.into_inner().unwrap(), ["s/P {RED}"]);
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

mod early;
mod inputs;

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

use crate::cache::{Hash, ValidCache};
use crate::diagnostic::Span;
use crate::error::VariantError;
use crate::library::{Library, LoadError, LoadOptions};
use crate::plan::{PlanError, PlanOptions};
use crate::validate::{Keyed, PassReport, ValidateReport, validate_keyed};

/// Why a run gave no verdict: the tree did not load or could not be planned. The session
/// stays usable: the next run (after the next change) tries again.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum WatchError {
    /// The tree did not load (render it with [`LoadError::render`]).
    #[error("{0}")]
    Load(#[from] LoadError),
    /// The plan could not be made (a budget, a covering set, the materials).
    #[error(transparent)]
    Plan(Box<PlanError>),
}

impl From<PlanError> for WatchError {
    fn from(e: PlanError) -> WatchError {
        WatchError::Plan(Box::new(e))
    }
}

/// What a run reports as it goes.
#[derive(Debug)]
#[non_exhaustive]
pub enum Event<'a> {
    /// The tree loaded: the passes validated again (their inputs changed) and how many kept
    /// their last report.
    Started {
        /// The tree as loaded for this run (to render diagnostics with).
        library: &'a Library,
        /// `shader/pass` of each pass validated again, in plan order.
        stale: Vec<String>,
        /// Passes whose last report stands.
        kept: usize,
        /// Variants of the stale passes.
        variants: u64,
    },
    /// An error, the first time this run finds it (an error is its message and first label;
    /// the same error in other variants is in the verdict's report only). Render with
    /// `error.diagnostic().render(library.files(), color)`.
    Failure {
        /// The tree as loaded for this run.
        library: &'a Library,
        /// The error, naming the first variant found with this text.
        error: &'a VariantError,
    },
    /// Variants of the stale passes done in the full sweep (step 3), of `total`.
    Progress {
        /// Done so far.
        done: u64,
        /// Variants of the stale passes.
        total: u64,
    },
}

/// How a run ended.
#[derive(Debug)]
#[non_exhaustive]
pub enum Outcome {
    /// Every variant of the plan has its verdict.
    Verdict(Verdict),
    /// `cancel` was set: the run stopped between batches.
    Cancelled,
}

/// The verdict of a run.
#[derive(Debug)]
#[non_exhaustive]
pub struct Verdict {
    /// The report of the whole plan (the same as `validate` makes of this tree).
    pub report: ValidateReport,
    /// `shader/pass` of the passes validated again in this run.
    pub validated: Vec<String>,
    /// Passes whose report was kept from an earlier run.
    pub kept: usize,
}

/// A pass's last report and the inputs it was made from.
#[derive(Debug)]
struct Done {
    inputs: Hash,
    report: PassReport,
}

/// A keyword set that failed, most recent first in [`Session`]'s list.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Recent {
    shader: String,
    pass: String,
    keywords: Vec<String>,
}

/// Failing keyword sets remembered to try first.
const RECENT: usize = 64;

/// A tree validated again and again: it keeps each pass's last report, the keyword sets that
/// failed most recently and a cache of valid texts (see the [module docs](self)).
#[derive(Debug)]
pub struct Session {
    root: PathBuf,
    load: LoadOptions,
    options: PlanOptions,
    cache: ValidCache,
    cache_dir: Option<PathBuf>,
    done: HashMap<(String, String), Done>,
    recent: Vec<Recent>,
    library: Option<Library>,
    profiles: Option<Vec<crate::validator::Profile>>,
}

impl Session {
    /// A session over the tree at `root` (loaded as [`Library::from_dir_with`] does), planned
    /// with `options` (a shard in them is left out: a session validates the whole plan).
    /// Valid texts are remembered in memory, and in the cache folder `cache_dir` when given
    /// (read now, written after each run, shared as [`ValidCache`] describes).
    pub fn new(
        root: impl AsRef<Path>,
        load: LoadOptions,
        mut options: PlanOptions,
        cache_dir: Option<&Path>,
    ) -> Session {
        options.shard = None;
        Session {
            root: root.as_ref().to_path_buf(),
            load,
            options,
            cache: cache_dir.map_or_else(ValidCache::in_memory, ValidCache::open),
            cache_dir: cache_dir.map(Path::to_path_buf),
            done: HashMap::new(),
            recent: Vec::new(),
            library: None,
            profiles: None,
        }
    }

    /// Validates for `profile` instead of the declaration file's (`--profile`).
    pub fn set_profile(&mut self, profile: crate::validator::Profile) {
        self.set_profiles(&[profile]);
    }

    /// Validates for every device of `profiles` instead of the declaration file's (repeated
    /// `--profile`; see [`Library::set_profiles`]): a variant is valid when it is valid on
    /// each, and the verdict's report counts each profile's.
    pub fn set_profiles(&mut self, profiles: &[crate::validator::Profile]) {
        self.profiles = Some(profiles.to_vec());
    }

    /// Plans the next runs with `options` (a shard in them is left out), e.g. after a
    /// materials file changed; a pass whose plan changes is validated again.
    pub fn set_options(&mut self, mut options: PlanOptions) {
        options.shard = None;
        self.options = options;
    }

    /// The tree's root.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The tree as loaded by the last run that gave a verdict (to render its report's
    /// diagnostics with).
    pub fn library(&self) -> Option<&Library> {
        self.library.as_ref()
    }

    /// Loads the tree and validates what changed since the last verdict (every pass the first
    /// time), calling `on` with each [`Event`]. Stops between batches once `cancel` is set.
    pub fn run(
        &mut self,
        cancel: &AtomicBool,
        on: &(dyn Fn(Event<'_>) + Sync),
    ) -> Result<Outcome, WatchError> {
        let mut lib = Library::from_dir_with(&self.root, &self.load)?;
        if let Some(profiles) = &self.profiles {
            lib.set_profiles(profiles);
        }
        let plan = crate::plan::plan(&lib, &self.options)?;
        let options_text = self.options.fingerprint_text();
        let inputs: Vec<Hash> = plan
            .iter()
            .map(|(pass, _)| inputs::fingerprint(&lib, pass, &options_text))
            .collect();
        let stale: Vec<usize> = (0..plan.len())
            .filter(|&i| {
                self.done
                    .get(&name(plan[i].0))
                    .is_none_or(|d| d.inputs != inputs[i])
            })
            .collect();
        let total: u64 = stale.iter().map(|&i| plan[i].1.len() as u64).sum();
        on(Event::Started {
            library: &lib,
            stale: stale.iter().map(|&i| label(plan[i].0)).collect(),
            kept: plan.len() - stale.len(),
            variants: total,
        });
        // Each error is reported once per run, whichever step finds it first: an edit that
        // breaks every variant of a pass is one diagnostic, not one per text (the verdict's
        // report has every failing text).
        let mut reported: HashSet<(String, Option<Span>)> = HashSet::new();
        let mut found = |_: u128, error: &VariantError| {
            if reported.insert((error.message.clone(), error.labels.first().map(|l| l.0))) {
                on(Event::Failure {
                    library: &lib,
                    error,
                });
            }
        };
        let first = early::candidates(&lib, &plan, &stale, &self.recent, &self.options);
        if !early::validate(&lib, &first, &self.cache, cancel, &mut found) {
            return Ok(self.cancelled());
        }
        let done = AtomicU64::new(0);
        let progress = |n: u64| {
            on(Event::Progress {
                done: done.fetch_add(n, Ordering::Relaxed) + n,
                total,
            })
        };
        let how = Keyed {
            keep_seen: false,
            strict: self.options.strict,
            cancel: Some(cancel),
        };
        for &i in &stale {
            let (pass, choices) = &plan[i];
            let Some(report) = validate_keyed(
                &lib,
                pass,
                choices.iter().cloned(),
                Some(&self.cache),
                &progress,
                how,
                &mut found,
            ) else {
                return Ok(self.cancelled());
            };
            self.remember_failures(&report);
            self.done.insert(
                name(pass),
                Done {
                    inputs: inputs[i],
                    report,
                },
            );
        }
        let planned: HashSet<(String, String)> = plan.iter().map(|(p, _)| name(p)).collect();
        self.done.retain(|k, _| planned.contains(k));
        let passes = plan
            .iter()
            .map(|(pass, _)| self.done[&name(pass)].report.clone())
            .collect();
        let report = crate::validate::plan_report(&lib, passes, &self.options);
        let verdict = Verdict {
            report,
            validated: stale.iter().map(|&i| label(plan[i].0)).collect(),
            kept: plan.len() - stale.len(),
        };
        drop(plan);
        self.library = Some(lib);
        self.save_cache();
        Ok(Outcome::Verdict(verdict))
    }

    /// A run stopped: what it validated stays in the cache.
    fn cancelled(&mut self) -> Outcome {
        self.save_cache();
        Outcome::Cancelled
    }

    /// Puts the first keyword set of each of `report`'s failures at the front of the recent
    /// list.
    fn remember_failures(&mut self, report: &PassReport) {
        for f in report.failures.iter().rev() {
            let Some(keywords) = f.keyword_sets.first() else {
                continue;
            };
            let recent = Recent {
                shader: report.shader.clone(),
                pass: report.pass.clone(),
                keywords: keywords.clone(),
            };
            self.recent.retain(|r| *r != recent);
            self.recent.insert(0, recent);
        }
        self.recent.truncate(RECENT);
    }

    /// Writes the texts validated to the cache folder and reads it back, so that the next
    /// save writes only what is new by then.
    fn save_cache(&mut self) {
        let Some(dir) = &self.cache_dir else {
            return;
        };
        // A cache that cannot be written costs speed only; the next run validates again.
        if self.cache.save().is_ok() {
            self.cache = ValidCache::open(dir);
        }
    }
}

/// A pass's key in [`Session`]'s reports.
fn name(pass: &crate::Pass) -> (String, String) {
    (pass.shader.clone(), pass.name.clone())
}

/// `shader/pass`.
fn label(pass: &crate::Pass) -> String {
    format!("{}/{}", pass.shader, pass.name)
}
