//! The bad-input corpus (`tests/bad/` at the repository root) through the command line: every
//! case exits with status 1, never panics, and prints its `file:line:col` and message.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde::Deserialize;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Expect {
    stage: String,
    location: String,
    message: String,
    shader: Option<String>,
    pass: Option<String>,
    #[serde(default)]
    keywords: Vec<String>,
}

fn cases() -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/bad"
    )))
    .expect("tests/bad")
    .map(|e| e.expect("entry").path())
    .filter(|p| p.join("expect.toml").exists())
    .collect();
    dirs.sort();
    dirs
}

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
    } else {
        cmd.args(["validate", "--all"]);
    }
    let out = cmd.output().map_err(|x| x.to_string())?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    if out.status.code() != Some(1) {
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
    let cases = cases();
    assert!(cases.len() >= 25, "the corpus has {} cases", cases.len());
    let mut failures = Vec::new();
    for dir in &cases {
        let name = dir
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        let text = std::fs::read_to_string(dir.join("expect.toml")).expect("expect.toml");
        let expect: Expect =
            toml::from_str(&text).unwrap_or_else(|err| panic!("{name}/expect.toml: {err}"));
        if let Err(why) = check_cli(dir, &expect) {
            failures.push(format!(
                "{name}: expected {} `{}`\n  {why}",
                expect.location, expect.message
            ));
        }
    }
    println!(
        "bad-input corpus: {} cases checked through the command line",
        cases.len()
    );
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
