//! Embeds the bundled shader library (`wgsl/`) into the crate, so the tool works from any
//! directory. Generates `$OUT_DIR/bundled.rs`: a sorted list of (relative path, bytes).

use std::fs;
use std::path::{Path, PathBuf};

fn collect(root: &Path, dir: &Path, out: &mut Vec<(String, PathBuf)>) {
    let mut entries: Vec<_> = fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("reading {}: {e}", dir.display()))
        .filter_map(Result::ok)
        .map(|e| e.path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            collect(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            let rel = path.strip_prefix(root).expect("under root");
            let rel = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy())
                .collect::<Vec<_>>()
                .join("/");
            out.push((rel, path.canonicalize().expect("canonical path")));
        }
    }
}

/// naga's exact version from the nearest Cargo.lock (the cache key of validated variants
/// includes it: another naga may judge a text differently).
fn naga_version() -> String {
    let mut dir = PathBuf::from(std::env::var("OUT_DIR").unwrap_or_default());
    let mut candidates = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.lock")];
    while dir.pop() {
        candidates.push(dir.join("Cargo.lock"));
    }
    for lock in candidates {
        let Ok(text) = fs::read_to_string(&lock) else {
            continue;
        };
        let mut lines = text.lines();
        while let Some(line) = lines.next() {
            if line == "name = \"naga\""
                && let Some(v) = lines.next().and_then(|l| l.strip_prefix("version = \""))
            {
                return v.trim_end_matches('"').to_string();
            }
        }
    }
    "30".to_string()
}

fn main() {
    println!(
        "cargo:rustc-env=WGSL_VARIANTS_NAGA_VERSION={}",
        naga_version()
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("wgsl");
    println!("cargo:rerun-if-changed=wgsl");
    let mut files = Vec::new();
    collect(&root, &root, &mut files);
    let mut code = String::from(
        "/// The bundled library: (path relative to `wgsl/`, contents), sorted by path.\npub static BUNDLED: &[(&str, &[u8])] = &[\n",
    );
    for (rel, abs) in &files {
        println!("cargo:rerun-if-changed={}", abs.display());
        code.push_str(&format!(
            "    ({rel:?}, include_bytes!({:?})),\n",
            abs.display().to_string()
        ));
    }
    code.push_str("];\n");
    let out = PathBuf::from(std::env::var("OUT_DIR").expect("OUT_DIR")).join("bundled.rs");
    fs::write(out, code).expect("writing bundled.rs");
}
