//! Pass-through on WGSL nobody here wrote: every `.wgsl` file shipped in the crates.io packages
//! this crate depends on (naga, naga_oil, wgpu*), plus every `.wgsl` file under the folder named
//! by `WGSL_VARIANTS_WGSL_CORPUS` if set. A file without directive-looking lines, imported as a
//! module into a one-pass shader, must compose (full and lean) to a text naga treats exactly
//! as the file itself: the same module written back to WGSL, or the same error message; and
//! when naga accepts the file, it accepts the variant's pruned text (`src/reach`) too.

use wgsl_variants_fuzz_checks as checks;

use std::path::{Path, PathBuf};
use std::process::Command;

use wgsl_variants::Library;

const SHADER: &str = "#shader t\n#pass P\n#import m\n#endpass\n";

/// Source folders of the packages whose `.wgsl` files are compared, from `cargo metadata`.
fn dependency_dirs() -> Vec<(String, PathBuf)> {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
    let metadata = |offline: bool| {
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args(["metadata", "--format-version", "1", "--manifest-path"])
            .arg(&manifest);
        if offline {
            cmd.arg("--offline");
        }
        cmd.output().ok().filter(|o| o.status.success())
    };
    // Offline first: the sources are already there, since this test was built from them.
    let output = metadata(true)
        .or_else(|| metadata(false))
        .expect("cargo metadata runs");
    let json: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("cargo metadata prints JSON");
    let mut dirs: Vec<(String, PathBuf)> = json["packages"]
        .as_array()
        .expect("packages")
        .iter()
        .filter_map(|p| {
            let name = p["name"].as_str()?;
            let wanted = name == "naga" || name == "naga_oil" || name.starts_with("wgpu");
            let manifest = Path::new(p["manifest_path"].as_str()?);
            wanted.then(|| {
                let version = p["version"].as_str().unwrap_or("?");
                (
                    format!("{name}-{version}"),
                    manifest.parent().unwrap().to_path_buf(),
                )
            })
        })
        .collect();
    dirs.sort();
    dirs.dedup();
    dirs
}

fn wgsl_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.filter_map(Result::ok).map(|e| e.path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            wgsl_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(path);
        }
    }
}

/// A line whose first non-blank character is `#`: another preprocessor's dialect. WGSL's line
/// breaks and blankspace, not Rust's (the preprocessor's line splitting is internal).
fn has_directive_line(text: &str) -> bool {
    let line_break = |c| {
        matches!(
            c,
            '\u{000a}'..='\u{000d}' | '\u{0085}' | '\u{2028}' | '\u{2029}'
        )
    };
    let blank = |c| matches!(c, ' ' | '\t' | '\u{200e}' | '\u{200f}') || line_break(c);
    text.split(line_break)
        .any(|line| line.trim_start_matches(blank).starts_with('#'))
}

#[derive(Default)]
struct Figures {
    found: usize,
    compared: usize,
    identical: usize,
    /// Of the identical ones, those naga accepts (the rest are rejected with the same message).
    accepted: usize,
    differing: Vec<String>,
}

impl Figures {
    fn check(&mut self, path: &Path) {
        self.found += 1;
        let Ok(text) = std::fs::read_to_string(path) else {
            return;
        };
        if has_directive_line(&text) {
            return;
        }
        self.compared += 1;
        let own = checks::naga_outcome(&text);
        let lib = match Library::from_sources([("m.wgsl", text.as_str()), ("t.wgsl", SHADER)]) {
            Ok(lib) => lib,
            Err(e) => {
                let first = e.diagnostics().first().map(|d| d.render(&e.files, false));
                self.differing
                    .push(format!("{}: does not load: {first:?}", path.display()));
                return;
            }
        };
        let v = lib.variant("t", "P", &[] as &[&str]).expect("the pass");
        // The preprocessor's pass-through: the composed text before reachability.
        let full = checks::naga_outcome(&lib.compose_unpruned(&v, true).text);
        let lean = checks::naga_outcome(&lib.compose_unpruned(&v, false).text);
        // Reachability keeps every item an entry point uses: what naga accepts stays accepted.
        let pruned = checks::naga_outcome(&lib.wgsl(&v));
        if full == own && lean == own && (own.is_err() || pruned.is_ok()) {
            self.identical += 1;
            self.accepted += own.is_ok() as usize;
        } else {
            let show = |o: &Result<String, String>| match o {
                Ok(_) => "accepted".to_string(),
                Err(e) => format!("rejected: {e}"),
            };
            self.differing.push(format!(
                "{}: file {}, full {}, lean {}, pruned {}",
                path.display(),
                show(&own),
                show(&full),
                show(&lean),
                show(&pruned)
            ));
        }
    }

    fn report(&self, what: &str) {
        println!(
            "{what}: {} files found, {} compared, {} identical ({} accepted by naga), {} differing",
            self.found,
            self.compared,
            self.identical,
            self.accepted,
            self.differing.len()
        );
        for d in &self.differing {
            println!("  differs: {d}");
        }
    }
}

#[test]
fn foreign_wgsl_passes_through_unchanged() {
    let mut registry = Figures::default();
    for (package, dir) in dependency_dirs() {
        let mut files = Vec::new();
        wgsl_files(&dir, &mut files);
        println!("{package}: {} .wgsl files", files.len());
        for file in files {
            registry.check(&file);
        }
    }
    registry.report("packages");

    let mut corpus = Figures::default();
    if let Some(dir) = std::env::var_os("WGSL_VARIANTS_WGSL_CORPUS") {
        let mut files = Vec::new();
        wgsl_files(Path::new(&dir), &mut files);
        for file in files {
            corpus.check(&file);
        }
        corpus.report("WGSL_VARIANTS_WGSL_CORPUS");
        assert!(corpus.found > 0, "no .wgsl file under {dir:?}");
    }

    assert!(registry.found > 0, "no .wgsl file in the dependencies");
    assert!(registry.compared > 0, "every .wgsl file was skipped");
    assert!(
        registry.differing.is_empty() && corpus.differing.is_empty(),
        "composed text differs from the file for naga (see the list above)"
    );
}
