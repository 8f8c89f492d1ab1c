//! The bad-input corpus (`tests/bad/` at the repository root) through the command line: every
//! case exits with status 1 (a `warning` case with 0), never panics, and prints its
//! `file:line:col` and message.

use std::path::Path;

use std::process::Command;
use test_support::bad::Expect;

/// Runs the CLI on the case: it must fail with exit code 1 and print the location.
fn check_cli(dir: &Path, e: &Expect) -> Result<(), String> {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"));
    cmd.arg("--root")
        .arg(dir.join("lib"))
        .arg("--color")
        .arg("never");
    if e.stage == "lookup" {
        cmd.args([
            "emit",
            e.shader.as_deref().unwrap_or(""),
            e.pass.as_deref().unwrap_or(""),
            "--keywords",
            &e.keywords.join(","),
        ]);
    } else if let Some(t) = e.cover {
        cmd.args(["validate", "--cover", &t.to_string()]);
    } else {
        cmd.args(["validate", "--all"]);
    }
    let out = cmd.output().map_err(|x| x.to_string())?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    // A warning is printed and the command goes on: the tree itself is valid.
    let expected = if e.stage == "warning" { 0 } else { 1 };
    if e.stage == "warning" && !stderr.contains(&format!("warning: {}", e.message)) {
        return Err(format!("no warning `{}`:\n{stderr}", e.message));
    }
    if out.status.code() != Some(expected) {
        return Err(format!("exit status {:?}, stderr:\n{stderr}", out.status));
    }
    if stderr.contains("panicked") {
        return Err(format!("panic:\n{stderr}"));
    }
    if !stderr.contains(&format!("┌─ {}", e.location)) || !stderr.contains(&e.message) {
        return Err(format!(
            "stderr lacks `{}` / the message:\n{stderr}",
            e.location
        ));
    }
    Ok(())
}

#[test]
fn every_bad_input_is_diagnosed_at_its_location() {
    test_support::bad::check_all("the command line", check_cli);
}
