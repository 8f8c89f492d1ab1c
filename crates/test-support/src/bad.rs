//! The bad-input corpus (`tests/bad/` at the repository root): one folder per case, a library
//! under `lib/` and the diagnostic it must produce in `expect.toml`. The library's tests check
//! each case through the API, the command line's tests through the binary.

use std::path::{Path, PathBuf};

use serde::Deserialize;

/// What a case must produce (`expect.toml`).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expect {
    /// The stage that reports it: `load`, `validate`, `budget`, `lookup`, `cover`, or `warning`
    /// (the library loads; a warning says it).
    pub stage: String,
    /// `file:line:col` of the primary label.
    pub location: String,
    /// A part of the message.
    pub message: String,
    /// For `load`: the kind of the first problem (`link::cycle`, `parse::unterminated`, …).
    pub kind: Option<String>,
    /// For `lookup`: the shader looked up.
    pub shader: Option<String>,
    /// For `lookup`: the pass looked up.
    pub pass: Option<String>,
    /// For `lookup`: the keywords asked for.
    #[serde(default)]
    pub keywords: Vec<String>,
    /// For `cover`: the covering strength asked for (`validate --cover T`).
    pub cover: Option<usize>,
}

/// One case: its folder, its name and what it must produce.
#[derive(Debug)]
pub struct Case {
    /// The case's folder (its library is `dir/lib`).
    pub dir: PathBuf,
    /// The folder's name.
    pub name: String,
    /// The expected diagnostic.
    pub expect: Expect,
}

/// Every case of the corpus, sorted by name. Panics on a malformed `expect.toml`.
pub fn cases() -> Vec<Case> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/bad");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&root)
        .unwrap_or_else(|e| panic!("{}: {e}", root.display()))
        .map(|e| e.expect("entry").path())
        .filter(|p| p.join("expect.toml").exists())
        .collect();
    dirs.sort();
    dirs.into_iter()
        .map(|dir| {
            let name = dir
                .file_name()
                .unwrap_or_default()
                .to_string_lossy()
                .into_owned();
            let text = std::fs::read_to_string(dir.join("expect.toml")).expect("expect.toml");
            let expect: Expect =
                toml::from_str(&text).unwrap_or_else(|err| panic!("{name}/expect.toml: {err}"));
            Case { dir, name, expect }
        })
        .collect()
}

/// Checks every case with `check` and fails, listing each failing case, if any did; `through`
/// names the path taken (API or CLI) in the summary line.
pub fn check_all(through: &str, check: impl Fn(&Path, &Expect) -> Result<(), String>) {
    let cases = cases();
    assert!(cases.len() >= 25, "the corpus has {} cases", cases.len());
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| {
            check(&case.dir, &case.expect).err().map(|why| {
                format!(
                    "{}: expected {} `{}`\n  {why}",
                    case.name, case.expect.location, case.expect.message
                )
            })
        })
        .collect();
    println!(
        "bad-input corpus: {} cases checked through {through}",
        cases.len()
    );
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
