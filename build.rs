//! Records naga's exact version (the cache key of validated texts includes it).

use std::fs;
use std::path::{Path, PathBuf};

/// naga's exact version from the nearest Cargo.lock (the cache key of validated variants
/// includes it: another naga may judge a text differently), and the lock file it came from.
fn naga_version() -> (String, Option<PathBuf>) {
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
                return (v.trim_end_matches('"').to_string(), Some(lock));
            }
        }
    }
    ("30".to_string(), None)
}

fn main() {
    let (version, lock) = naga_version();
    println!("cargo:rustc-env=WGSL_VARIANTS_NAGA_VERSION={version}");
    // Without these lines cargo runs the script again (and rebuilds the crate) after an edit
    // of any file of the package, docs and tests included. Only an existing file is named: a
    // missing one would make cargo run the script on every build.
    println!("cargo:rerun-if-changed=build.rs");
    if let Some(lock) = lock {
        println!("cargo:rerun-if-changed={}", lock.display());
    }
}
