//! The bad-input corpus: every folder under `tests/bad/` is a library (`lib/`) and the
//! diagnostic it must produce (`expect.toml`: stage, `file:line:col`, message). Each case is
//! checked through the API here, and through the command line in the CLI crate's tests.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use wgsl_variants::lookup::lookup_strict;
use wgsl_variants::validate::{
    ValidateError, ValidateOptions, select_passes, validate_pass, variants_to_build,
};
use wgsl_variants::{Library, Space};

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
    let mut dirs: Vec<PathBuf> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad"))
            .expect("tests/bad")
            .map(|e| e.expect("entry").path())
            .filter(|p| p.join("expect.toml").exists())
            .collect();
    dirs.sort();
    dirs
}

/// Checks one case through the API; returns a description of what went wrong, if anything.
fn check_api(dir: &Path, e: &Expect) -> Result<(), String> {
    let loaded = Library::from_dir(dir.join("lib"));
    if e.stage == "load" {
        let err = match loaded {
            Ok(_) => return Err("library loaded, expected a load error".into()),
            Err(err) => err,
        };
        let first = err.diagnostics.first().ok_or("no diagnostic")?;
        let location = first
            .location(&err.files)
            .map(|l| l.to_string())
            .unwrap_or_default();
        if location != e.location || !first.message.contains(&e.message) {
            return Err(format!("got {location}: {}", first.message));
        }
        return Ok(());
    }
    let lib = loaded.map_err(|err| format!("unexpected load error:\n{err}"))?;
    match e.stage.as_str() {
        "validate" => {
            let options = ValidateOptions {
                all: true,
                ..ValidateOptions::default()
            };
            for pass in select_passes(&lib, None, None).map_err(|x| x.to_string())? {
                let choices = variants_to_build(&lib, pass, &options).map_err(|x| x.to_string())?;
                let report = validate_pass(&lib, pass, &choices, &|_| {});
                for f in &report.failures {
                    if f.keyword_sets.contains(&e.keywords) {
                        let location = f
                            .error
                            .location(lib.files())
                            .map(|l| l.to_string())
                            .unwrap_or_default();
                        if location != e.location || !f.error.message.contains(&e.message) {
                            return Err(format!("got {location}: {}", f.error.message));
                        }
                        if !f
                            .error
                            .diagnostic()
                            .notes
                            .iter()
                            .any(|n| n.contains(&format!("{{{}}}", e.keywords.join(", "))))
                        {
                            return Err("the diagnostic does not name the keyword set".into());
                        }
                        return Ok(());
                    }
                }
            }
            Err("no failure for the expected keyword set".into())
        }
        "lookup" => {
            let pass = lib
                .pass(
                    e.shader.as_deref().unwrap_or(""),
                    e.pass.as_deref().unwrap_or(""),
                )
                .map_err(|x| x.to_string())?;
            match lookup_strict(&Space::build_set(pass, None), &e.keywords, 1_000_000) {
                Ok(_) => Err("lookup succeeded".into()),
                Err(err) if err.to_string().contains(&e.message) => {
                    let location = lib.files().location(pass.span).to_string();
                    if location == e.location {
                        Ok(())
                    } else {
                        Err(format!("pass located at {location}"))
                    }
                }
                Err(err) => Err(format!("got {err}")),
            }
        }
        "budget" => {
            let pass = lib.passes().next().ok_or("no pass")?;
            match variants_to_build(&lib, pass, &ValidateOptions::default()) {
                Err(ValidateError::Budget { error, .. })
                    if error.to_string().contains(&e.message) =>
                {
                    Ok(())
                }
                Err(other) => Err(format!("got {other}")),
                Ok(v) => Err(format!("built {} variants", v.len())),
            }
        }
        other => Err(format!("unknown stage {other}")),
    }
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
        if let Err(why) = check_api(dir, &expect) {
            failures.push(format!(
                "{name}: expected {} `{}`\n  {why}",
                expect.location, expect.message
            ));
        }
    }
    println!(
        "bad-input corpus: {} cases checked through the API",
        cases.len()
    );
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
