//! An on-disk cache of composed texts known to be valid, so an unchanged variant is not
//! validated again; one folder can be shared by many processes and machines at once (CI jobs
//! on a shared or network file system).
//!
//! The key is the BLAKE3 hash of a variant's composed WGSL, which already reflects every source
//! line and keyword that shapes it. Only successes are cached: a failing variant is validated
//! again, so its diagnostic is always fresh. The cache changes speed only, never output.
//!
//! Layout: `DIR/<key>/` (see [`key`]: this crate's and naga's versions, since another naga may
//! judge a text differently) holds segment files `<BLAKE3 of the contents>.seg`. Each save
//! writes a new segment with the hashes it adds, to a temporary file renamed into place, so
//! concurrent writers never overwrite each other's entries and a reader never sees half a
//! file. A segment starts with a header (magic and key), then 40-byte records: a hash and 8
//! check bytes (the start of the hash's own BLAKE3 hash). A record that fails its check, a
//! truncated record or a segment with a bad header is ignored and counted
//! ([`ValidCache::corrupt`]), never trusted. Past [`COMPACT_AFTER`] segments, a save writes one
//! segment with everything and removes the segments it read (segments written meanwhile by
//! others are kept, so no entry is lost). [`ValidCache::export`] writes the whole cache as one
//! segment file and [`import`] adds one, so a CI cache step can carry the cache between runs.
//!
//! ```
//! use wgsl_variants::cache::{ValidCache, hash};
//!
//! let dir = std::env::temp_dir().join(format!("wv-cache-doc-{}", std::process::id()));
//! let cache = ValidCache::open(&dir);
//! cache.insert(hash("fn f() {}"));
//! cache.save().unwrap();
//! assert!(ValidCache::open(&dir).contains(&hash("fn f() {}")));
//! # std::fs::remove_dir_all(&dir).unwrap();
//! ```

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

/// The first bytes of every segment file.
const MAGIC: &[u8; 8] = b"WVCACHE1";
/// A hash and its 8 check bytes.
const RECORD: usize = 40;
/// Segments in the folder past which a save compacts them into one.
pub const COMPACT_AFTER: usize = 32;

/// What a cache built by this crate is keyed by: `wgsl-variants-<version>-naga-<version>`,
/// the name of its folder in the cache directory.
pub fn key() -> String {
    format!(
        "wgsl-variants-{}-naga-{}",
        env!("CARGO_PKG_VERSION"),
        env!("WGSL_VARIANTS_NAGA_VERSION")
    )
}

/// Why a cache file could not be exported or imported.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CacheError {
    /// A file could not be read or written.
    #[error("`{path}`: {message}")]
    Io {
        /// The path.
        path: PathBuf,
        /// The OS error.
        message: String,
    },
    /// The file is not a cache export.
    #[error("`{path}` is not a wgsl-variants cache file")]
    NotACache {
        /// The path.
        path: PathBuf,
    },
    /// The file was made by another version (its entries would not be trusted).
    #[error("`{path}` is a cache of {found}, not of {expected}; it was not imported")]
    OtherVersion {
        /// The path.
        path: PathBuf,
        /// Its key.
        found: String,
        /// This build's [`key`].
        expected: String,
    },
}

fn io_error(path: &Path, e: std::io::Error) -> CacheError {
    CacheError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

fn check_bytes(hash: &Hash) -> [u8; 8] {
    let mut check = [0u8; 8];
    check.copy_from_slice(&blake3::hash(hash).as_bytes()[..8]);
    check
}

/// A segment's bytes: header, then sorted records.
fn encode(hashes: &[Hash]) -> Vec<u8> {
    let key = key();
    let mut bytes = Vec::with_capacity(10 + key.len() + hashes.len() * RECORD);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&(key.len() as u16).to_le_bytes());
    bytes.extend_from_slice(key.as_bytes());
    for h in hashes {
        bytes.extend_from_slice(h);
        bytes.extend_from_slice(&check_bytes(h));
    }
    bytes
}

/// A segment's contents.
#[derive(Debug, Default, PartialEq, Eq)]
struct Decoded {
    hashes: Vec<Hash>,
    corrupt: usize,
}

/// Decodes a segment; `Err(Some(key))` when it is of another key, `Err(None)` when it is no
/// segment at all.
fn decode(bytes: &[u8]) -> Result<Decoded, Option<String>> {
    let rest = bytes.strip_prefix(MAGIC).ok_or(None)?;
    let (len, rest) = rest.split_first_chunk::<2>().ok_or(None)?;
    let len = usize::from(u16::from_le_bytes(*len));
    let found = rest.get(..len).ok_or(None)?;
    if found != key().as_bytes() {
        return Err(Some(String::from_utf8_lossy(found).into_owned()));
    }
    let records = &rest[len..];
    let mut out = Decoded::default();
    for record in records.chunks(RECORD) {
        let hash: Option<Hash> = record.get(..32).and_then(|h| h.try_into().ok());
        match hash {
            Some(h) if record.len() == RECORD && record[32..] == check_bytes(&h) => {
                out.hashes.push(h)
            }
            _ => out.corrupt += 1,
        }
    }
    Ok(out)
}

/// Writes `bytes` to `path` through a temporary file in the same folder, renamed into place:
/// readers see the old file or the whole new one, never part of it.
fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_nanos());
    let name = path
        .file_name()
        .map_or("cache".into(), |n| n.to_string_lossy().into_owned());
    // Unique per process, thread-safe counter and moment, so concurrent writers (threads or
    // processes, here or on other machines) never share a temporary file.
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = dir.join(format!(".{name}.{}.{n}.{nanos}.tmp", std::process::id()));
    let written = (|| {
        let mut file = std::fs::File::create(&tmp)?;
        file.write_all(bytes)?;
        file.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if written.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    written
}

/// Writes `hashes` as a segment of `folder`, named by its contents (two writers of the same
/// entries write the same file). Returns its path.
fn write_segment(folder: &Path, hashes: &[Hash]) -> std::io::Result<PathBuf> {
    let bytes = encode(hashes);
    let name = blake3::hash(&bytes).to_hex();
    let path = folder.join(format!("{}.seg", &name[..32]));
    write_atomic(&path, &bytes)?;
    Ok(path)
}

/// Hashes of composed texts that validated, loaded from and saved to a cache folder.
#[derive(Debug)]
pub struct ValidCache {
    folder: PathBuf,
    known: HashSet<Hash>,
    added: Mutex<HashSet<Hash>>,
    /// Segments read at open (removed when a save compacts).
    segments: Vec<PathBuf>,
    corrupt: usize,
    problems: Vec<String>,
}

impl ValidCache {
    /// Opens (or starts) the cache in `dir`. A missing or unreadable folder is an empty cache;
    /// corrupt records and files are left out and counted.
    pub fn open(dir: &Path) -> ValidCache {
        let folder = dir.join(key());
        let mut cache = ValidCache {
            folder,
            ..ValidCache::in_memory()
        };
        let mut paths: Vec<PathBuf> = std::fs::read_dir(&cache.folder)
            .map(|entries| {
                entries
                    .filter_map(|e| e.ok().map(|e| e.path()))
                    .filter(|p| p.extension().is_some_and(|e| e == "seg"))
                    .collect()
            })
            .unwrap_or_default();
        paths.sort();
        for path in paths {
            // A segment removed by another process's compaction since the listing: its
            // entries are in that process's new segment.
            let Ok(bytes) = std::fs::read(&path) else {
                continue;
            };
            match decode(&bytes) {
                Ok(d) => {
                    if d.corrupt > 0 {
                        cache.problems.push(format!(
                            "{}: {} corrupt record(s) ignored",
                            path.display(),
                            d.corrupt
                        ));
                    }
                    cache.corrupt += d.corrupt;
                    cache.known.extend(d.hashes);
                }
                Err(_) => {
                    cache.corrupt += 1;
                    cache.problems.push(format!(
                        "{}: corrupt (not a segment of this cache), ignored",
                        path.display()
                    ));
                }
            }
            cache.segments.push(path);
        }
        cache
    }

    /// A cache in memory only, which [`save`](Self::save) never writes: what validating
    /// again and again in one process ([`crate::watch::Session`]) remembers without a folder.
    pub fn in_memory() -> ValidCache {
        ValidCache {
            folder: PathBuf::new(),
            known: HashSet::new(),
            added: Mutex::new(HashSet::new()),
            segments: Vec::new(),
            corrupt: 0,
            problems: Vec::new(),
        }
    }

    /// Whether a text with this hash is known to be valid (read at open or inserted since).
    pub fn contains(&self, hash: &Hash) -> bool {
        self.known.contains(hash) || self.added.lock().is_ok_and(|a| a.contains(hash))
    }

    /// Records a text that validated.
    pub fn insert(&self, hash: Hash) {
        if let Ok(mut added) = self.added.lock() {
            added.insert(hash);
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

    /// Segment files read when the cache was opened.
    pub fn segments(&self) -> usize {
        self.segments.len()
    }

    /// Corrupt records (and files that are no segment) ignored when the cache was opened.
    pub fn corrupt(&self) -> usize {
        self.corrupt
    }

    /// What was wrong with the files counted in [`corrupt`](Self::corrupt), one line each.
    pub fn problems(&self) -> &[String] {
        &self.problems
    }

    /// The folder of this cache's segments (`DIR/<key>`; empty for an
    /// [in-memory](Self::in_memory) cache).
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    fn all(&self) -> Vec<Hash> {
        let added: Vec<Hash> = self
            .added
            .lock()
            .map(|a| a.iter().copied().collect())
            .unwrap_or_default();
        let mut all: Vec<Hash> = self.known.iter().copied().chain(added).collect();
        all.sort_unstable();
        all.dedup();
        all
    }

    /// Writes the hashes added since opening as a new segment (nothing when none is new).
    /// Past [`COMPACT_AFTER`] segments, writes everything as one segment and removes the
    /// segments read at open. Safe with other processes saving into the same folder at once.
    /// An [in-memory](Self::in_memory) cache writes nothing.
    pub fn save(&self) -> std::io::Result<()> {
        if self.folder.as_os_str().is_empty() {
            return Ok(());
        }
        let mut new: Vec<Hash> = self
            .added
            .lock()
            .map(|a| {
                a.iter()
                    .filter(|h| !self.known.contains(*h))
                    .copied()
                    .collect()
            })
            .unwrap_or_default();
        new.sort_unstable();
        if self.segments.len() < COMPACT_AFTER {
            if !new.is_empty() {
                write_segment(&self.folder, &new)?;
            }
            return Ok(());
        }
        let whole = write_segment(&self.folder, &self.all())?;
        for path in &self.segments {
            if *path != whole {
                // Gone already: another process compacted it (into a segment of its own).
                let _ = std::fs::remove_file(path);
            }
        }
        Ok(())
    }

    /// Writes every known and added hash to one file (a segment, atomically), for a CI cache
    /// step to carry; [`import`] reads it back. Returns the number of entries.
    pub fn export(&self, file: &Path) -> Result<usize, CacheError> {
        let all = self.all();
        write_atomic(file, &encode(&all)).map_err(|e| io_error(file, e))?;
        Ok(all.len())
    }
}

/// What [`import`] added.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct Imported {
    /// Entries read from the file.
    pub entries: usize,
    /// Corrupt records in it, left out.
    pub corrupt: usize,
}

/// Adds the entries of `file` (written by [`ValidCache::export`] of this same version) to the
/// cache in `dir`, as a new segment. Corrupt records are left out and counted; a file of
/// another version is refused.
pub fn import(dir: &Path, file: &Path) -> Result<Imported, CacheError> {
    let bytes = std::fs::read(file).map_err(|e| io_error(file, e))?;
    let decoded = decode(&bytes).map_err(|found| match found {
        Some(found) => CacheError::OtherVersion {
            path: file.to_path_buf(),
            found,
            expected: key(),
        },
        None => CacheError::NotACache {
            path: file.to_path_buf(),
        },
    })?;
    let folder = dir.join(key());
    write_segment(&folder, &decoded.hashes).map_err(|e| io_error(&folder, e))?;
    Ok(Imported {
        entries: decoded.hashes.len(),
        corrupt: decoded.corrupt,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hashes(range: std::ops::Range<u32>) -> Vec<Hash> {
        range.map(|i| hash(&i.to_string())).collect()
    }

    #[test]
    fn concurrent_savers_lose_nothing() {
        let dir = tempfile::tempdir().unwrap();
        // Eight writers at once, each opening the folder as it stands and adding its own
        // entries, several times over (so compaction runs while others write).
        std::thread::scope(|s| {
            for t in 0..8u32 {
                let dir = dir.path();
                s.spawn(move || {
                    for round in 0..6u32 {
                        let cache = ValidCache::open(dir);
                        let start = (t * 6 + round) * 50;
                        for h in hashes(start..start + 50) {
                            cache.insert(h);
                        }
                        cache.save().unwrap();
                    }
                });
            }
        });
        let cache = ValidCache::open(dir.path());
        assert_eq!(cache.corrupt(), 0, "{:?}", cache.problems());
        assert_eq!(cache.len(), 8 * 6 * 50);
        assert!(hashes(0..2400).iter().all(|h| cache.contains(h)));
    }

    #[test]
    fn compaction_keeps_every_entry_in_one_segment() {
        let dir = tempfile::tempdir().unwrap();
        for i in 0..COMPACT_AFTER as u32 {
            let cache = ValidCache::open(dir.path());
            cache.insert(hash(&i.to_string()));
            cache.save().unwrap();
        }
        let cache = ValidCache::open(dir.path());
        assert_eq!(cache.segments(), COMPACT_AFTER);
        cache.save().unwrap();
        let cache = ValidCache::open(dir.path());
        assert_eq!((cache.segments(), cache.len()), (1, COMPACT_AFTER));
    }

    #[test]
    fn corrupt_records_are_ignored_and_counted() {
        let dir = tempfile::tempdir().unwrap();
        let cache = ValidCache::open(dir.path());
        for h in hashes(0..3) {
            cache.insert(h);
        }
        cache.save().unwrap();
        let segment = std::fs::read_dir(cache.folder())
            .unwrap()
            .next()
            .unwrap()
            .unwrap()
            .path();
        let mut bytes = std::fs::read(&segment).unwrap();
        // Flip a bit of the second record's hash, and cut the last record short.
        let second = bytes.len() - 2 * RECORD;
        bytes[second] ^= 1;
        bytes.truncate(bytes.len() - 1);
        std::fs::write(&segment, &bytes).unwrap();
        std::fs::write(cache.folder().join("junk.seg"), b"not a segment").unwrap();
        let cache = ValidCache::open(dir.path());
        assert_eq!(cache.len(), 1);
        assert_eq!(cache.corrupt(), 3, "{:?}", cache.problems());
        assert_eq!(cache.problems().len(), 2);
    }

    #[test]
    fn export_then_import_carries_every_entry() {
        let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        let cache = ValidCache::open(a.path());
        for h in hashes(0..100) {
            cache.insert(h);
        }
        let file = a.path().join("cache.bin");
        assert_eq!(cache.export(&file).unwrap(), 100);
        let imported = import(b.path(), &file).unwrap();
        assert_eq!((imported.entries, imported.corrupt), (100, 0));
        let back = ValidCache::open(b.path());
        assert!(back.len() == 100 && hashes(0..100).iter().all(|h| back.contains(h)));
        std::fs::write(&file, b"something else").unwrap();
        assert!(matches!(
            import(b.path(), &file),
            Err(CacheError::NotACache { .. })
        ));
        let mut other = MAGIC.to_vec();
        other.extend_from_slice(&3u16.to_le_bytes());
        other.extend_from_slice(b"old");
        std::fs::write(&file, other).unwrap();
        let err = import(b.path(), &file).unwrap_err();
        assert!(err.to_string().contains("is a cache of old"), "{err}");
    }
}
