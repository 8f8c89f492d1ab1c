//! Records naga's exact version (the cache key of validated texts includes it).

use std::fs;
use std::path::{Path, PathBuf};

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
}
