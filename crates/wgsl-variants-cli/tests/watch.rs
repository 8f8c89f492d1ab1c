//! `wgsl-variants watch`: a test edits a file of a temporary tree and sees the diagnostic
//! appear (at its file:line:col, with the keyword set), then disappear after the fix — in JSON
//! lines and in text.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

/// Long enough for a loaded CI machine; a healthy run answers in well under a second.
const PATIENCE: Duration = Duration::from_secs(60);

const COLOR: &str = "fn tint() -> vec4f {\n#if defined(RED)\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n#else\n    return vec4f(0.5);\n#endif\n}\n";
const BROKEN: &str = "fn tint() -> vec4f {\n#if defined(RED)\n    return vec4f(1.0, ,0.0, 1.0);\n#else\n    return vec4f(0.5);\n#endif\n}\n";

fn tree() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("lib")).unwrap();
    save(&dir.path().join("lib/color.wgsl"), COLOR);
    std::fs::write(
        dir.path().join("a.wgsl"),
        "#shader a\n#pass P\n#pragma multi_compile _ RED\n#import lib/color\n\
         @fragment fn fs() -> @location(0) vec4f { return tint(); }\n#endpass\n",
    )
    .unwrap();
    dir
}

/// The watcher, killed when dropped, and its output lines as they come.
struct Watching {
    child: Child,
    lines: Receiver<String>,
}

impl Drop for Watching {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Watching {
    /// Starts `watch` on `root` with `args`: the watcher (reading stdout) and stderr's lines.
    fn start(root: &Path, args: &[&str]) -> (Watching, Receiver<String>) {
        let mut child = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .arg("--root")
            .arg(root)
            .args(["watch", "--no-cache", "--debounce", "10"])
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("start wgsl-variants watch");
        let lines = forward(child.stdout.take().unwrap());
        let errors = forward(child.stderr.take().unwrap());
        (Watching { child, lines }, errors)
    }

    /// Lines until one satisfies `done`; all of them, that one last.
    fn until(&self, done: impl Fn(&str) -> bool) -> Vec<String> {
        let mut seen = Vec::new();
        loop {
            match self.lines.recv_timeout(PATIENCE) {
                Ok(line) => {
                    let last = done(&line);
                    seen.push(line);
                    if last {
                        return seen;
                    }
                }
                Err(e) => panic!("no such line ({e}); got {seen:#?}"),
            }
        }
    }
}

/// A thread sending each line of `stream` down a channel.
fn forward(stream: impl Read + Send + 'static) -> Receiver<String> {
    let (send, lines) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stream).lines() {
            let Ok(line) = line else { return };
            if send.send(line).is_err() {
                return;
            }
        }
    });
    lines
}

/// Saves `text` as `path` the way many editors do: a temporary file renamed over it, so the
/// watcher never reads half a file.
fn save(path: &Path, text: &str) {
    let temporary = path.with_extension("wgsl.swp");
    std::fs::write(&temporary, text).unwrap();
    std::fs::rename(&temporary, path).unwrap();
}

fn event(line: &str) -> serde_json::Value {
    serde_json::from_str(line).unwrap_or_else(|e| panic!("not JSON ({e}): {line}"))
}

fn is_verdict(line: &str) -> bool {
    event(line)["event"] == "verdict"
}

#[test]
fn json_lines_show_the_error_of_an_edit_then_its_fix() {
    let dir = tree();
    let (watching, _errors) = Watching::start(dir.path(), &["--json"]);
    let first = watching.until(is_verdict);
    let verdict = event(first.last().unwrap());
    assert_eq!(verdict["ok"], true, "{first:#?}");
    assert_eq!(verdict["report"]["totals"]["built"], 2);

    save(&dir.path().join("lib/color.wgsl"), BROKEN);
    let broken: Vec<serde_json::Value> = watching
        .until(is_verdict)
        .iter()
        .map(|l| event(l))
        .collect();
    let failures: Vec<&serde_json::Value> =
        broken.iter().filter(|e| e["event"] == "failure").collect();
    assert_eq!(failures.len(), 1, "{broken:#?}");
    let failure = failures[0];
    assert!(
        failure["location"]
            .as_str()
            .unwrap()
            .starts_with("lib/color.wgsl:3:"),
        "{failure}"
    );
    assert_eq!(failure["variant"], "a/P {RED}");
    assert!(
        failure["diagnostic"]
            .as_str()
            .unwrap()
            .contains("in variant a/P {RED}")
    );
    assert!(failure["after_ms"].is_u64());
    let verdict = broken.last().unwrap();
    assert_eq!(verdict["ok"], false);
    assert_eq!(verdict["validated"], serde_json::json!(["a/P"]));
    assert_eq!(verdict["report"]["totals"]["invalid"], 1);
    assert!(verdict["first_diagnostic_ms"].is_u64());

    save(&dir.path().join("lib/color.wgsl"), COLOR);
    let fixed = watching.until(is_verdict);
    assert!(
        fixed.iter().all(|l| event(l)["event"] != "failure"),
        "{fixed:#?}"
    );
    let verdict = event(fixed.last().unwrap());
    assert_eq!(verdict["ok"], true);
    assert!(verdict["first_diagnostic_ms"].is_null());
}

#[test]
fn text_shows_the_diagnostic_above_one_status_line_then_its_fix() {
    let dir = tree();
    let (watching, errors) = Watching::start(dir.path(), &["--color", "never"]);
    let is_status = |l: &str| l.contains("watching") && (l.contains("ok:") || l.contains("FAILED"));
    let first = watching.until(is_status);
    assert!(
        first.last().unwrap().contains("ok: 2 variants valid"),
        "{first:#?}"
    );

    save(&dir.path().join("lib/color.wgsl"), BROKEN);
    let broken = watching.until(is_status);
    let status = broken.last().unwrap();
    assert!(
        status.contains("FAILED: 1 failing text(s) in 1 of 2 variants"),
        "{broken:#?}"
    );
    assert!(status.contains("first diagnostic after"), "{status}");
    // The diagnostic went to stderr before the status line was printed (its reader thread
    // may lag behind stdout's).
    let mut diagnostic = String::new();
    while !diagnostic.contains("in variant") {
        match errors.recv_timeout(PATIENCE) {
            Ok(line) => diagnostic += &format!("{line}\n"),
            Err(e) => panic!("no diagnostic ({e}): {diagnostic}"),
        }
    }
    assert!(
        diagnostic.contains("lib/color.wgsl:3:") && diagnostic.contains("in variant a/P {RED}"),
        "{diagnostic}"
    );

    save(&dir.path().join("lib/color.wgsl"), COLOR);
    let fixed = watching.until(is_status);
    assert!(
        fixed.last().unwrap().contains("ok: 2 variants valid"),
        "{fixed:#?}"
    );
    let after: Vec<String> = errors.try_iter().collect();
    assert!(
        after.iter().all(|l| !l.contains("error")),
        "a diagnostic after the fix: {after:#?}"
    );
}

#[test]
fn watch_needs_a_folder() {
    let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("watch")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("watch needs --root DIR"), "{stderr}");

    let dir = tree();
    let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("--root")
        .arg(dir.path().join("no-such-folder"))
        .arg("watch")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("is not a folder"), "{stderr}");
}

/// `--materials FILE` outside the tree is watched and read again: the build set follows it,
/// and a file that does not load is an error until it is fixed.
#[test]
fn the_materials_file_is_watched_too() {
    let dir = tree();
    std::fs::write(
        dir.path().join("a.wgsl"),
        "#shader a\n#pass P\n#pragma shader_feature RED\n#pragma shader_feature GLOSS\n#import lib/color\n\
         @fragment fn fs() -> @location(0) vec4f { return tint(); }\n#endpass\n",
    )
    .unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let materials = elsewhere.path().join("materials.toml");
    let material = |keywords: &str| {
        format!("[[material]]\nname = \"M\"\nshader = \"a\"\nkeywords = [{keywords}]\n")
    };
    std::fs::write(&materials, material("")).unwrap();
    let (watching, _errors) = Watching::start(
        dir.path(),
        &["--json", "--materials", materials.to_str().unwrap()],
    );
    let built =
        |lines: &[String]| event(lines.last().unwrap())["report"]["totals"]["built"].clone();
    assert_eq!(built(&watching.until(is_verdict)), 1);

    // Another material: the pass is planned again (its build set is now {RED}).
    save(&materials, &material("\"RED\""));
    let red = watching.until(is_verdict);
    assert_eq!(built(&red), 1);
    assert_eq!(
        event(red.last().unwrap())["validated"],
        serde_json::json!(["a/P"])
    );

    let is_error = |l: &str| event(l)["event"] == "error";
    save(&materials, &material("\"NOT_A_KEYWORD\""));
    let error = event(
        watching
            .until(|l| is_verdict(l) || is_error(l))
            .last()
            .unwrap(),
    );
    assert_eq!(error["event"], "error", "{error}");
    assert!(
        error["message"].as_str().unwrap().contains("NOT_A_KEYWORD"),
        "{error}"
    );

    // Two materials: both shader_feature combinations are built.
    save(
        &materials,
        &(material("\"RED\"") + &material("\"RED\", \"GLOSS\"").replace("\"M\"", "\"N\"")),
    );
    assert_eq!(built(&watching.until(is_verdict)), 2);
}
