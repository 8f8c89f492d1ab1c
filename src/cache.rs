//! An on-disk cache of composed texts known to be valid, so an unchanged variant is not
//! validated again.
//!
//! The key is the BLAKE3 hash of a variant's composed WGSL, which already reflects every source
//! line and keyword that shapes it, within a file named for this crate's and naga's versions
//! (another naga may judge a text differently). Only successes are cached: a failing variant
//! is validated again, so its diagnostic is always fresh. The cache changes speed only, never
//! output.

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// A content hash of a composed text.
pub type Hash = [u8; 32];

/// Hashes a composed text.
pub fn hash(text: &str) -> Hash {
    *blake3::hash(text.as_bytes()).as_bytes()
}

/// The file name of the cache for this build of the crate.
pub fn file_name() -> String {
    format!(
        "valid-wgsl-variants-{}-naga-{}.bin",
        env!("CARGO_PKG_VERSION"),
        env!("WGSL_VARIANTS_NAGA_VERSION")
    )
}

/// Hashes of composed texts that validated, loaded from and saved to one file.
#[derive(Debug)]
pub struct ValidCache {
    path: PathBuf,
    known: HashSet<Hash>,
    added: Mutex<Vec<Hash>>,
}

impl ValidCache {
    /// Opens (or starts) the cache in `dir`. A missing or unreadable file is an empty cache; a
    /// truncated one keeps its whole records.
    pub fn open(dir: &Path) -> ValidCache {
        let path = dir.join(file_name());
        let bytes = std::fs::read(&path).unwrap_or_default();
        let known = bytes
            .chunks_exact(32)
            .map(|c| c.try_into().unwrap_or([0; 32]))
            .collect();
        ValidCache {
            path,
            known,
            added: Mutex::new(Vec::new()),
        }
    }

    /// Whether a text with this hash is known to be valid.
    pub fn contains(&self, hash: &Hash) -> bool {
        self.known.contains(hash)
    }

    /// Records a text that validated.
    pub fn insert(&self, hash: Hash) {
        if let Ok(mut added) = self.added.lock() {
            added.push(hash);
        }
    }

    /// Number of hashes known when the cache was opened.
    pub fn len(&self) -> usize {
        self.known.len()
    }

    /// Whether the cache was empty when opened.
    pub fn is_empty(&self) -> bool {
        self.known.is_empty()
    }

    /// Writes the known and added hashes (sorted, deduplicated) atomically: a temporary file
    /// renamed over the old one, so a crash never leaves a corrupt cache.
    pub fn save(&self) -> std::io::Result<()> {
        let added = self.added.lock().map(|a| a.clone()).unwrap_or_default();
        if added.iter().all(|h| self.known.contains(h)) {
            return Ok(());
        }
        let mut all: Vec<Hash> = self.known.iter().copied().chain(added).collect();
        all.sort_unstable();
        all.dedup();
        if let Some(dir) = self.path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        let tmp = self
            .path
            .with_extension(format!("tmp{}", std::process::id()));
        let mut file = std::fs::File::create(&tmp)?;
        for h in &all {
            file.write_all(h)?;
        }
        file.sync_all()?;
        std::fs::rename(&tmp, &self.path)
    }
}
