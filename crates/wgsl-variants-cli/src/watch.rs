//! `wgsl-variants watch`: validate a tree, then validate it again at each change, with the
//! library's [`Session`] (what changed first, then the rest in the background).
//!
//! Text output: each failure's diagnostic on stderr as it is found, then one status line per
//! verdict on stdout (a progress bar in between on a terminal). `--json`: one JSON object per
//! line on stdout, one per event (`started`, `failure`, `verdict`, `cancelled`, `error`).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use notify::Watcher;
use serde_json::json;
use wgsl_variants::LoadOptions;
use wgsl_variants::watch::{Event, Outcome, Session, Verdict, WatchError};

use super::context::BuildArgs;
use super::validate::CheckArgs;

/// `wgsl-variants watch` arguments.
#[derive(clap::Args, Debug, Clone)]
pub struct WatchArgs {
    /// Validate the full space, not only the build set.
    #[arg(long)]
    all: bool,
    #[command(flatten)]
    build: BuildArgs,
    #[command(flatten)]
    check: CheckArgs,
    /// Quiet time after a change before validating, in milliseconds (an editor's save can be
    /// several writes; a change during a run stops it and starts again anyway).
    #[arg(long, value_name = "MS", default_value_t = 20)]
    debounce: u64,
}

/// How to print, and when the change being validated was first seen.
struct Printer {
    json: bool,
    color: bool,
    bar: indicatif::ProgressBar,
    /// When the change this run validates was first seen.
    since: Instant,
    /// When its first failure was printed, after `since`.
    first: Mutex<Option<Duration>>,
}

impl Printer {
    fn json_line(&self, value: serde_json::Value) {
        let mut out = std::io::stdout().lock();
        // A closed stdout (the reader went away) is not worth a panic; the next change retries.
        let _ = writeln!(out, "{value}").and_then(|_| out.flush());
    }

    fn event(&self, event: Event<'_>) {
        match event {
            Event::Started {
                stale,
                kept,
                variants,
                ..
            } => {
                if self.json {
                    self.json_line(json!({
                        "event": "started", "stale": stale, "kept": kept, "variants": variants,
                    }));
                } else {
                    self.bar.set_length(variants);
                    self.bar.set_position(0);
                    self.bar.set_message(format!(
                        "validating {} pass(es) again, {kept} unchanged",
                        stale.len()
                    ));
                }
            }
            Event::Failure { library, error } => {
                let after = self.since.elapsed();
                self.first.lock().map(|mut f| *f.get_or_insert(after)).ok();
                let diagnostic = error.diagnostic();
                if self.json {
                    self.json_line(json!({
                        "event": "failure",
                        "variant": error.variant,
                        "stage": error.stage,
                        "message": error.message,
                        "location": error.location(library.files()).map(|l| l.to_string()),
                        "diagnostic": diagnostic.render(library.files(), false),
                        "after_ms": millis(after),
                    }));
                } else {
                    let text = diagnostic.render(library.files(), self.color);
                    self.bar.suspend(|| eprint!("{text}"));
                }
            }
            Event::Progress { done, .. } => self.bar.set_position(done),
            _ => {}
        }
    }

    fn verdict(&self, verdict: &Verdict) {
        self.bar.finish_and_clear();
        let elapsed = self.since.elapsed();
        let first = self.first.lock().ok().and_then(|f| *f);
        let r = &verdict.report;
        if self.json {
            self.json_line(json!({
                "event": "verdict",
                "ok": r.ok,
                "validated": verdict.validated,
                "kept": verdict.kept,
                "first_diagnostic_ms": first.map(millis),
                "elapsed_ms": millis(elapsed),
                "report": r,
            }));
            return;
        }
        let t = &r.totals;
        let failing: usize = r.passes.iter().map(|p| p.failures.len()).sum();
        let names: Vec<&str> = t.profiles.iter().map(|p| p.profile.as_str()).collect();
        let head = if r.ok && names.is_empty() {
            format!("ok: {} variants valid", t.built)
        } else if r.ok {
            format!("ok: {} variants valid on {}", t.built, names.join(", "))
        } else {
            let counts: Vec<String> = t
                .profiles
                .iter()
                .map(|p| format!("{}: {} invalid", p.profile, p.invalid))
                .collect();
            format!(
                "FAILED: {failing} failing text(s) in {} of {} variants{}",
                t.invalid,
                t.built,
                if counts.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", counts.join(", "))
                }
            )
        };
        let first = first
            .map(|f| format!(", first diagnostic after {} ms", millis(f)))
            .unwrap_or_default();
        println!(
            "[{}] {head} ({} pass(es) validated again, {} kept; verdict after {:.2} s{first}); watching",
            clock(),
            verdict.validated.len(),
            verdict.kept,
            elapsed.as_secs_f64()
        );
    }

    fn error(&self, e: &WatchError) {
        let render = |color: bool| match e {
            WatchError::Load(load) => load.render(color),
            other => format!("error: {other}\n"),
        };
        let (locations, what) = match e {
            WatchError::Load(load) => (load.locations(), "the tree does not load"),
            _ => (Vec::new(), "no plan"),
        };
        self.problem(
            &e.to_string(),
            (&render(self.color), &render(false)),
            locations,
            what,
        );
    }

    /// A run that could not start: `message`, the diagnostic `(coloured, plain)`, its
    /// locations, and `what` for the status line.
    fn problem(
        &self,
        message: &str,
        (text, plain): (&str, &str),
        locations: Vec<String>,
        what: &str,
    ) {
        self.bar.finish_and_clear();
        if self.json {
            self.json_line(json!({
                "event": "error", "message": message, "locations": locations,
                "diagnostic": plain, "after_ms": millis(self.since.elapsed()),
            }));
        } else {
            eprint!("{text}");
            println!("[{}] {what}; watching", clock());
        }
    }
}

fn millis(d: Duration) -> u64 {
    d.as_millis().try_into().unwrap_or(u64::MAX)
}

/// `HH:MM:SS` (UTC) for status lines.
fn clock() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    format!(
        "{:02}:{:02}:{:02}",
        secs / 3600 % 24,
        secs / 60 % 60,
        secs % 60
    )
}

/// Whether a file event can change what the tree loads as: a module, a WESL file, a TOML
/// file (the declaration file, or one it includes) or the materials file created, changed, renamed or removed (not an
/// access, not the cache).
fn relevant(event: &notify::Event, cache: Option<&Path>, materials: Option<&Path>) -> bool {
    use notify::EventKind;
    if matches!(event.kind, EventKind::Access(_) | EventKind::Other) {
        return false;
    }
    event.paths.iter().any(|p| {
        let module = p
            .extension()
            .is_some_and(|e| e == "wgsl" || e == "wesl" || e == "toml");
        (module && cache.is_none_or(|c| !p.starts_with(c))) || materials.is_some_and(|m| p == m)
    })
}

/// Blocks until a relevant change, then until `quiet` passes without another; the time the
/// first one was seen. `None` when the watcher is gone.
fn next_change(changes: &Receiver<Instant>, quiet: Duration) -> Option<Instant> {
    let first = changes.recv().ok()?;
    loop {
        match changes.recv_timeout(quiet) {
            Ok(_) => {}
            Err(RecvTimeoutError::Timeout) => return Some(first),
            Err(RecvTimeoutError::Disconnected) => return None,
        }
    }
}

/// Runs `watch` until interrupted (or the watcher fails).
pub fn run(
    root: Option<&Path>,
    load: LoadOptions,
    profiles: &[wgsl_variants::validate::Profile],
    json: bool,
    color: bool,
    args: &WatchArgs,
) -> ExitCode {
    let Some(root) = root else {
        eprintln!(
            "error: watch needs --root DIR: the bundled library is built into the binary (watch a copy of it, e.g. --root wgsl in a checkout)"
        );
        return ExitCode::from(1);
    };
    match watch(root, load, profiles, json, color, args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(1)
        }
    }
}

fn watch(
    root: &Path,
    load: LoadOptions,
    profiles: &[wgsl_variants::validate::Profile],
    json: bool,
    color: bool,
    args: &WatchArgs,
) -> Result<(), String> {
    if !root.is_dir() {
        return Err(format!("`{}` is not a folder", root.display()));
    }
    // Event paths start with the path watched: watch absolute paths, compare absolute paths.
    let root = std::fs::canonicalize(root).map_err(|e| format!("`{}`: {e}", root.display()))?;
    let options = |args: &WatchArgs| {
        super::context::plan_options(&args.build, args.all, None).map(|mut o| {
            o.strict = args.check.strict;
            o
        })
    };
    let planned = options(args).map_err(|e| e.0)?;
    let cache_dir = args.check.cache_dir();
    let cache_abs: Option<PathBuf> = cache_dir
        .as_ref()
        .and_then(|d| std::fs::canonicalize(d).ok());
    let materials: Option<PathBuf> = args
        .build
        .materials
        .as_ref()
        .and_then(|m| std::fs::canonicalize(m).ok());
    let cancel = Arc::new(AtomicBool::new(false));
    // Set when the root itself was removed, renamed or made again: its recursive watch is then
    // gone (the OS drops it with the folder) and is set up anew.
    let rearm = Arc::new(AtomicBool::new(false));
    let (send, changes) = std::sync::mpsc::channel::<Instant>();
    let stop = Arc::clone(&cancel);
    let root_moved = Arc::clone(&rearm);
    let watched_materials = materials.clone();
    let watched_root = root.clone();
    let mut watcher = notify::recommended_watcher(move |event: notify::Result<notify::Event>| {
        let Ok(event) = event else { return };
        let of_root = !matches!(event.kind, notify::EventKind::Access(_))
            && event.paths.contains(&watched_root);
        if of_root {
            root_moved.store(true, Ordering::Relaxed);
        }
        if of_root || relevant(&event, cache_abs.as_deref(), watched_materials.as_deref()) {
            // Stop the run in progress at once: it validates a tree that is no longer there.
            stop.store(true, Ordering::Relaxed);
            let _ = send.send(Instant::now());
        }
    })
    .map_err(|e| format!("cannot watch files: {e}"))?;
    watcher
        .watch(&root, notify::RecursiveMode::Recursive)
        .map_err(|e| format!("cannot watch `{}`: {e}", root.display()))?;
    // The root's folder too, not recursively: a root deleted or renamed and made again is seen
    // there, and watched again.
    if let Some(parent) = root.parent() {
        watcher
            .watch(parent, notify::RecursiveMode::NonRecursive)
            .map_err(|e| format!("cannot watch `{}`: {e}", parent.display()))?;
    }
    // A materials file outside the tree: its folder too (an editor's save replaces the file).
    if let Some(folder) = materials
        .as_deref()
        .filter(|m| !m.starts_with(&root))
        .and_then(Path::parent)
    {
        watcher
            .watch(folder, notify::RecursiveMode::NonRecursive)
            .map_err(|e| format!("cannot watch `{}`: {e}", folder.display()))?;
    }
    let mut session = Session::new(&root, load, planned, cache_dir.as_deref());
    if !profiles.is_empty() {
        session.set_profiles(profiles);
    }
    let quiet = Duration::from_millis(args.debounce);
    let mut since = Instant::now();
    if !json {
        println!("[{}] watching {} (Ctrl-C to stop)", clock(), root.display());
    }
    loop {
        cancel.store(false, Ordering::Relaxed);
        let printer = Printer {
            json,
            color,
            bar: if json {
                indicatif::ProgressBar::hidden()
            } else {
                super::output::progress(0, "loading")
            },
            since,
            first: Mutex::new(None),
        };
        // The materials file is read again at each change (it may be what changed).
        match materials.as_ref().map(|_| options(args)) {
            Some(Err(super::context::Failed(message))) => printer.problem(
                &message,
                (&format!("{message}\n"), &format!("{message}\n")),
                Vec::new(),
                "the materials file does not load",
            ),
            reread => {
                if let Some(Ok(o)) = reread {
                    session.set_options(o);
                }
                match session.run(&cancel, &|e| printer.event(e)) {
                    Ok(Outcome::Verdict(verdict)) => printer.verdict(&verdict),
                    Ok(_) => {
                        printer.bar.finish_and_clear();
                        if json {
                            printer.json_line(json!({"event": "cancelled"}));
                        }
                    }
                    Err(e) => printer.error(&e),
                }
            }
        }
        match next_change(&changes, quiet) {
            Some(first) => since = first,
            None => return Err("the file watcher stopped".into()),
        }
        if rearm.swap(false, Ordering::Relaxed) {
            // Gone with the old folder (or never set up, if it was already gone); a root that
            // is not back yet is watched from its parent until it is.
            let _ = watcher.unwatch(&root);
            if root.is_dir() {
                let _ = watcher.watch(&root, notify::RecursiveMode::Recursive);
            }
        }
    }
}
