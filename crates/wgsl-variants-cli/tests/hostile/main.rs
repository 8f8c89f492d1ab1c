//! Hostile trees, forged caches and broken pipes: each case of the hostile-input review, by
//! name, run against the release binary under a time limit (and, where memory is the attack, a
//! memory limit). Every case failed before its fix: a lie, an overwrite, a hang, unbounded
//! memory or a crash.

mod cache;
mod emit;
mod entry;
mod json;
mod loading;
mod messages;
mod nesting;
mod pipe;
mod scale;
mod watch;

use std::io::Read;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// The binary under test.
pub fn bin() -> Command {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"));
    cmd.args(["--color", "never"]);
    // A fixed cache secret: the tests never read or make the user's own.
    cmd.env("WGSL_VARIANTS_CACHE_SECRET", "5".repeat(64));
    cmd
}

/// Runs `cmd` to completion within `limit`, or kills it and fails the test: a hang is a bug.
pub fn run_within(mut cmd: Command, limit: Duration) -> Output {
    cmd.stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("start wgsl-variants");
    // Read both pipes on threads, so a chatty child never blocks on a full pipe.
    let mut stdout = child.stdout.take().expect("stdout");
    let mut stderr = child.stderr.take().expect("stderr");
    let out = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = stdout.read_to_end(&mut v);
        v
    });
    let err = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = stderr.read_to_end(&mut v);
        v
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{cmd:?} did not finish within {limit:?}: a hang");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().expect("stdout reader"),
        stderr: err.join().expect("stderr reader"),
    }
}

/// Runs `args` on the tree at `root` within 60 seconds.
pub fn run_on(root: &Path, args: &[&str]) -> Output {
    run_on_within(root, args, Duration::from_secs(60))
}

/// Runs `args` on the tree at `root` within `limit`.
pub fn run_on_within(root: &Path, args: &[&str], limit: Duration) -> Output {
    let mut cmd = bin();
    cmd.arg("--root").arg(root).args(args);
    run_within(cmd, limit)
}

/// Asserts the run ended with `code` and without a panic or abort.
pub fn assert_clean_exit(out: &Output, code: i32) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "a panic: {stderr}");
    assert_eq!(out.status.code(), Some(code), "{stderr}");
}

/// A tree of our dialect with one pass of two variants, `BAD` invalid.
pub fn tree_with_bad_variant(dir: &Path) {
    std::fs::write(
        dir.join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ BAD\n\
         @fragment fn fs() -> @location(0) vec4f {\n\
         #ifdef BAD\n    let x: f32 = vec2f(1.0);\n#endif\n    return vec4f(1.0);\n}\n#endpass\n",
    )
    .unwrap();
}
