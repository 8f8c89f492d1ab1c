//! The edit loop: `wgsl-variants watch --json` on a copy of the bundled library, with one-line
//! edits of `standard/surface.wgsl` (`var alpha = material.tint.a;`, which every standard
//! variant reaches).
//!
//! `cargo bench -p wgsl-variants-cli --bench watch` starts the watcher with an empty cache
//! (its first verdict fills it), then, each round (`BENCH_ROUNDS`, default 5), times from just
//! before the file is written:
//!
//! - a breaking edit (`.a` → `.q`): until the first `failure` line (edit to first diagnostic)
//!   and until the `verdict` line;
//! - its fix: until the verdict (every text is known valid again: cache hits);
//! - a valid edit that no earlier round made (`* 1.125`, `* 1.25`, …): until the verdict (every
//!   text of the passes that read the line is new and validated);
//! - and, in the same round, the baseline: `wgsl-variants validate` of the same tree with the
//!   same cache, a process of its own (what one would run by hand after the edit).
//!
//! Prints medians over rounds and writes them under `watch` in `target/bench-summary.json`,
//! with the ratio of the fix's verdict to the baseline (paired per round; lower is faster).

use test_support::timing;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

const LINE: &str = "    var alpha = material.tint.a;";

fn copy_tree(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).expect("read the library") {
        let path = entry.expect("entry").path();
        let target = to.join(path.file_name().expect("name"));
        if path.is_dir() {
            std::fs::create_dir_all(&target).expect("mkdir");
            copy_tree(&path, &target);
        } else {
            std::fs::copy(&path, &target).expect("copy");
        }
    }
}

fn binary() -> &'static str {
    env!("CARGO_BIN_EXE_wgsl-variants")
}

struct Watcher {
    child: Child,
    lines: Receiver<Value>,
}

impl Drop for Watcher {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Watcher {
    fn start(root: &Path, cache: &Path) -> Watcher {
        let mut child = Command::new(binary())
            .arg("--root")
            .arg(root)
            .args(["--json", "watch", "--cache"])
            .arg(cache)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("start the watcher");
        let stdout = child.stdout.take().expect("stdout");
        let (send, lines) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stdout).lines().map_while(Result::ok) {
                let value: Value = serde_json::from_str(&line).expect("a JSON line");
                if send.send(value).is_err() {
                    return;
                }
            }
        });
        Watcher { child, lines }
    }

    /// The next event named `name` (earlier ones dropped), and when it came.
    fn next(&self, name: &str) -> (Value, Instant) {
        loop {
            let event = self
                .lines
                .recv_timeout(Duration::from_secs(600))
                .unwrap_or_else(|e| panic!("no `{name}` event: {e}"));
            if event["event"] == name {
                return (event, Instant::now());
            }
        }
    }
}

/// Writes the surface module with `line` in place of [`LINE`]; the time just before.
fn edit(surface: &Path, original: &str, line: &str) -> Instant {
    let text = original.replacen(LINE, line, 1);
    let at = Instant::now();
    std::fs::write(surface, text).expect("write the module");
    at
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let workspace = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = tempfile::tempdir().expect("temp dir");
    let (root, cache) = (dir.path().join("wgsl"), dir.path().join("cache"));
    std::fs::create_dir_all(&root).expect("mkdir");
    copy_tree(&workspace.join("crates/wgsl-variants-shaders/wgsl"), &root);
    let surface = root.join("standard/surface.wgsl");
    let original = std::fs::read_to_string(&surface).expect("surface module");
    assert!(original.contains(LINE), "the edited line moved: {LINE}");

    let started = Instant::now();
    let watcher = Watcher::start(&root, &cache);
    let (first, _) = watcher.next("verdict");
    assert_eq!(first["ok"], true, "the bundled library validates");
    println!(
        "first verdict (empty cache): {:.1} s for {} variants",
        started.elapsed().as_secs_f64(),
        first["report"]["totals"]["built"]
    );

    let rounds = timing::rounds();
    let (mut to_first, mut broken, mut fixed, mut valid, mut baseline) =
        (vec![], vec![], vec![], vec![], vec![]);
    let mut server_first = vec![];
    for round in 0..rounds {
        let at = edit(&surface, &original, &LINE.replace(".a;", ".q;"));
        let (failure, seen) = watcher.next("failure");
        assert!(
            failure["location"]
                .as_str()
                .is_some_and(|l| l.starts_with("standard/surface.wgsl:46:")),
            "{failure}"
        );
        to_first.push(seen - at);
        let (verdict, done) = watcher.next("verdict");
        assert_eq!(verdict["ok"], false);
        broken.push(done - at);
        server_first.push(verdict["first_diagnostic_ms"].as_f64().unwrap_or(f64::NAN));

        let at = edit(&surface, &original, LINE);
        let (verdict, done) = watcher.next("verdict");
        assert_eq!(verdict["ok"], true);
        fixed.push(done - at);

        let t = Instant::now();
        let status = Command::new(binary())
            .arg("--root")
            .arg(&root)
            .args(["validate", "--cache"])
            .arg(&cache)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .expect("validate");
        assert!(status.success());
        baseline.push(t.elapsed());

        let factor = 1.0 + (round + 1) as f64 / 8.0;
        let at = edit(
            &surface,
            &original,
            &LINE.replace(".a;", &format!(".a * {factor:?};")),
        );
        let (verdict, done) = watcher.next("verdict");
        assert_eq!(verdict["ok"], true);
        valid.push(done - at);
    }
    std::fs::write(&surface, &original).expect("restore");

    let median = |t: &[Duration]| ms(timing::median_of(t));
    let ratio = timing::median_ratio(&fixed, &baseline);
    let mut server_first_sorted = server_first.clone();
    server_first_sorted.sort_by(f64::total_cmp);
    println!(
        "edit to first diagnostic: {:.0} ms (watcher's own clock, from the file event: {:.0} ms)",
        median(&to_first),
        server_first_sorted[server_first_sorted.len() / 2]
    );
    println!(
        "verdict after the breaking edit: {:.2} s; after its fix: {:.2} s; after a new valid edit: {:.2} s",
        median(&broken) / 1e3,
        median(&fixed) / 1e3,
        median(&valid) / 1e3
    );
    println!(
        "`validate` of the same tree, same cache: {:.2} s; fix verdict / validate: {ratio:.2}",
        median(&baseline) / 1e3
    );
    timing::write_summary(json!({
        "watch": {
            "machine": timing::machine(),
            "rounds": rounds,
            "edit_to_first_diagnostic_ms": median(&to_first),
            "verdict_after_breaking_edit_ms": median(&broken),
            "verdict_after_fix_ms": median(&fixed),
            "verdict_after_new_valid_edit_ms": median(&valid),
            "validate_same_tree_ms": median(&baseline),
            "ratio_fix_verdict_vs_validate": ratio,
        }
    }));
}
