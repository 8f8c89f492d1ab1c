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
//! file. A segment starts with a header (magic and key), then 48-byte records: a hash and 16
//! check bytes, a MAC of the hash (keyed BLAKE3 under a [`Secret`]). A record that fails its
//! check, a truncated record or a segment with a bad header is ignored and counted
//! ([`ValidCache::corrupt`]), never trusted.
//!
//! ## Trust
//!
//! An entry says "this exact text validated under this naga": the key is the text's full
//! BLAKE3 hash, and the folder is per version of this crate and of naga. Whoever can write to a
//! shared folder could still plant an entry for an invalid text, so each record carries a MAC
//! under a secret kept **outside** the folder ([`Secret::for_user`]: the
//! `WGSL_VARIANTS_CACHE_SECRET` environment variable, 64 hex digits, or else a random key made
//! once per user in `$XDG_CONFIG_HOME/wgsl-variants/cache-secret`, mode 0600). A record written
//! without the secret is not trusted: it counts as corrupt and its text is validated again.
//! Machines that share a cache folder (CI jobs) share the secret through their secret store;
//! without it they still share nothing wrong, only nothing at all. Past 32 segments, a save writes one
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
pub(crate) type Hash = [u8; 32];

/// Hashes a composed text.
pub fn hash(text: &str) -> Hash {
    *blake3::hash(text.as_bytes()).as_bytes()
}

/// The first bytes of every segment file.
const MAGIC: &[u8; 8] = b"WVCACHE2";
/// Check bytes of a record: the start of the record's MAC.
const CHECK: usize = 16;
/// A hash and its check bytes.
const RECORD: usize = 32 + CHECK;

/// The environment variable that holds a cache secret (64 hex digits).
pub const SECRET_VAR: &str = "WGSL_VARIANTS_CACHE_SECRET";

/// The key that signs a cache's records (see the [module docs](self)): only a process that
/// holds it can write an entry that another will trust.
#[derive(Clone, PartialEq, Eq)]
pub struct Secret([u8; 32]);

impl std::fmt::Debug for Secret {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Secret(..)")
    }
}

impl Secret {
    /// A secret from its 64 hex digits.
    ///
    /// ```
    /// use wgsl_variants::cache::Secret;
    /// assert!(Secret::from_hex(&"ab".repeat(32)).is_some());
    /// assert!(Secret::from_hex("abc").is_none());
    /// ```
    pub fn from_hex(hex: &str) -> Option<Secret> {
        let hex = hex.trim();
        if hex.len() != 64 || !hex.is_ascii() {
            return None;
        }
        let mut key = [0u8; 32];
        for (i, byte) in key.iter_mut().enumerate() {
            *byte = u8::from_str_radix(&hex[2 * i..2 * i + 2], 16).ok()?;
        }
        Some(Secret(key))
    }

    /// A new random secret (from the operating system).
    pub fn generate() -> Result<Secret, CacheError> {
        let mut key = [0u8; 32];
        getrandom::fill(&mut key).map_err(|e| CacheError::Secret {
            message: format!("no randomness from the operating system: {e}"),
        })?;
        Ok(Secret(key))
    }

    /// This user's secret: [`SECRET_VAR`] when it is set, else the key file in the user's
    /// configuration folder (`$XDG_CONFIG_HOME` or `~/.config`, `%APPDATA%` on Windows,
    /// then `wgsl-variants/cache-secret`), made with a random key on first use.
    pub fn for_user() -> Result<Secret, CacheError> {
        if let Some(value) = std::env::var_os(SECRET_VAR) {
            return value
                .to_str()
                .and_then(Secret::from_hex)
                .ok_or_else(|| CacheError::Secret {
                    message: format!("{SECRET_VAR} is set but is not 64 hex digits"),
                });
        }
        let dir = std::env::var_os("XDG_CONFIG_HOME")
            .filter(|d| !d.is_empty())
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("APPDATA").map(PathBuf::from))
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".config")))
            .ok_or_else(|| CacheError::Secret {
                message: format!(
                    "no configuration folder (HOME and XDG_CONFIG_HOME are unset): set {SECRET_VAR}"
                ),
            })?;
        Secret::from_file(&dir.join("wgsl-variants").join("cache-secret"))
    }

    /// The secret in `file`, made with a random key when the file does not exist (by one of
    /// several processes that start at once: the others read the winner's).
    pub fn from_file(file: &Path) -> Result<Secret, CacheError> {
        let read = |file: &Path| -> Result<Option<Secret>, CacheError> {
            match std::fs::read_to_string(file) {
                Ok(text) => Secret::from_hex(&text)
                    .map(Some)
                    .ok_or_else(|| CacheError::Secret {
                        message: format!("`{}` does not hold 64 hex digits", file.display()),
                    }),
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
                Err(e) => Err(io_error(file, e)),
            }
        };
        if let Some(secret) = read(file)? {
            return Ok(secret);
        }
        let secret = Secret::generate()?;
        let hex: String = secret.0.iter().map(|b| format!("{b:02x}")).collect();
        let dir = file.parent().unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
        let tmp = dir.join(format!(".cache-secret.{}.tmp", std::process::id()));
        let mut options = std::fs::OpenOptions::new();
        options.write(true).create(true).truncate(true);
        #[cfg(unix)]
        std::os::unix::fs::OpenOptionsExt::mode(&mut options, 0o600);
        let written = options
            .open(&tmp)
            .and_then(|mut f| f.write_all(format!("{hex}\n").as_bytes()))
            // A link never replaces a file: the first process to make one wins.
            .and_then(|()| match std::fs::hard_link(&tmp, file) {
                Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
                other => other,
            });
        let _ = std::fs::remove_file(&tmp);
        written.map_err(|e| io_error(file, e))?;
        read(file)?.ok_or_else(|| CacheError::Secret {
            message: format!("`{}` vanished as it was made", file.display()),
        })
    }

    /// The check bytes of a record for `hash`.
    fn check(&self, hash: &Hash) -> [u8; CHECK] {
        let mut check = [0u8; CHECK];
        check.copy_from_slice(&blake3::keyed_hash(&self.0, hash).as_bytes()[..CHECK]);
        check
    }
}
/// Segments in the folder past which a save compacts them into one.
pub(crate) const COMPACT_AFTER: usize = 32;

/// What a cache built by this crate is keyed by:
/// `wgsl-variants-<version>-naga-<version>-signed`, the name of its folder in the cache
/// directory. `-signed` is the record format (MACs under a [`Secret`]): caches written before
/// it live in another folder and are simply not read, rather than reported corrupt at every run.
pub fn key() -> String {
    format!(
        "wgsl-variants-{}-naga-{}-signed",
        env!("CARGO_PKG_VERSION"),
        env!("WGSL_VARIANTS_NAGA_VERSION")
    )
}

/// Why a cache file could not be exported or imported.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CacheError {
    /// A file could not be read or written.
    #[error("`{}`: {source}", .path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The file is not a cache export.
    #[error("`{path}` is not a wgsl-variants cache file")]
    NotACache {
        /// The path.
        path: PathBuf,
    },
    /// No cache secret could be had (see [`Secret::for_user`]).
    #[error("cache secret: {message}")]
    Secret {
        /// What went wrong.
        message: String,
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
        source: e,
    }
}

/// A segment's bytes: header, then sorted records.
fn encode(hashes: &[Hash], secret: &Secret) -> Vec<u8> {
    let key = key();
    let mut bytes = Vec::with_capacity(10 + key.len() + hashes.len() * RECORD);
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&(key.len() as u16).to_le_bytes());
    bytes.extend_from_slice(key.as_bytes());
    for h in hashes {
        bytes.extend_from_slice(h);
        bytes.extend_from_slice(&secret.check(h));
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
fn decode(bytes: &[u8], secret: &Secret) -> Result<Decoded, Option<String>> {
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
            Some(h) if record.len() == RECORD && record[32..] == secret.check(&h) => {
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
fn write_segment(folder: &Path, hashes: &[Hash], secret: &Secret) -> std::io::Result<PathBuf> {
    let bytes = encode(hashes, secret);
    let name = blake3::hash(&bytes).to_hex();
    let path = folder.join(format!("{}.seg", &name[..32]));
    write_atomic(&path, &bytes)?;
    Ok(path)
}

/// Hashes of composed texts that validated, loaded from and saved to a cache folder.
#[derive(Debug)]
pub struct ValidCache {
    folder: PathBuf,
    secret: Secret,
    known: HashSet<Hash>,
    added: Mutex<HashSet<Hash>>,
    /// Segments read at open (removed when a save compacts).
    segments: Vec<PathBuf>,
    corrupt: usize,
    problems: Vec<String>,
}

impl ValidCache {
    /// Opens (or starts) the cache in `dir` with this user's [`Secret::for_user`]. A missing
    /// or unreadable folder is an empty cache; corrupt and untrusted records and files are
    /// left out and counted. Without a secret, the cache is read as empty and written under a
    /// random one (so nothing is trusted that should not be), and [`problems`](Self::problems)
    /// says why.
    pub fn open(dir: &Path) -> ValidCache {
        match Secret::for_user() {
            Ok(secret) => ValidCache::open_with(dir, secret),
            Err(e) => {
                let mut cache = ValidCache::in_memory();
                cache.folder = dir.join(key());
                cache
                    .problems
                    .push(format!("{e}; the cache is not read this run"));
                cache
            }
        }
    }

    /// Opens (or starts) the cache in `dir`, trusting only records signed with `secret`.
    pub fn open_with(dir: &Path, secret: Secret) -> ValidCache {
        let folder = dir.join(key());
        let mut cache = ValidCache {
            folder,
            secret,
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
            match decode(&bytes, &cache.secret) {
                Ok(d) => {
                    if d.corrupt > 0 {
                        cache.problems.push(format!(
                            "{}: {} corrupt or untrusted record(s) ignored (not signed with this cache secret)",
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
            // Never written or read: any key will do, and a fixed one needs no randomness.
            secret: Secret([0; 32]),
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
    /// Past 32 segments (`COMPACT_AFTER`), writes everything as one segment and removes the
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
                write_segment(&self.folder, &new, &self.secret)?;
            }
            return Ok(());
        }
        let whole = write_segment(&self.folder, &self.all(), &self.secret)?;
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
        write_atomic(file, &encode(&all, &self.secret)).map_err(|e| io_error(file, e))?;
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

/// Adds the entries of `file` (written by [`ValidCache::export`] of this same version, under
/// the same [`Secret::for_user`]) to the cache in `dir`, as a new segment. Corrupt and
/// untrusted records are left out and counted; a file of another version is refused.
pub fn import(dir: &Path, file: &Path) -> Result<Imported, CacheError> {
    import_with(dir, file, &Secret::for_user()?)
}

/// [`import`] with an explicit secret.
pub fn import_with(dir: &Path, file: &Path, secret: &Secret) -> Result<Imported, CacheError> {
    let bytes = std::fs::read(file).map_err(|e| io_error(file, e))?;
    let decoded = decode(&bytes, secret).map_err(|found| match found {
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
    write_segment(&folder, &decoded.hashes, secret).map_err(|e| io_error(&folder, e))?;
    Ok(Imported {
        entries: decoded.hashes.len(),
        corrupt: decoded.corrupt,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn secret() -> Secret {
        Secret([7; 32])
    }

    fn open(dir: &Path) -> ValidCache {
        ValidCache::open_with(dir, secret())
    }

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
                        let cache = open(dir);
                        let start = (t * 6 + round) * 50;
                        for h in hashes(start..start + 50) {
                            cache.insert(h);
                        }
                        cache.save().unwrap();
                    }
                });
            }
        });
        let cache = open(dir.path());
        assert_eq!(cache.corrupt(), 0, "{:?}", cache.problems());
        assert_eq!(cache.len(), 8 * 6 * 50);
        assert!(hashes(0..2400).iter().all(|h| cache.contains(h)));
    }

    #[test]
    fn compaction_keeps_every_entry_in_one_segment() {
        let dir = tempfile::tempdir().unwrap();
        for i in 0..COMPACT_AFTER as u32 {
            let cache = open(dir.path());
            cache.insert(hash(&i.to_string()));
            cache.save().unwrap();
        }
        let cache = open(dir.path());
        assert_eq!(cache.segments(), COMPACT_AFTER);
        cache.save().unwrap();
        let cache = open(dir.path());
        assert_eq!((cache.segments(), cache.len()), (1, COMPACT_AFTER));
    }

    #[test]
    fn corrupt_records_are_ignored_and_counted() {
        let dir = tempfile::tempdir().unwrap();
        let cache = open(dir.path());
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
        let cache = open(dir.path());
        assert_eq!(cache.len(), 1);
        assert_eq!(cache.corrupt(), 3, "{:?}", cache.problems());
        assert_eq!(cache.problems().len(), 2);
    }

    #[test]
    fn export_then_import_carries_every_entry() {
        let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        let cache = open(a.path());
        for h in hashes(0..100) {
            cache.insert(h);
        }
        let file = a.path().join("cache.bin");
        assert_eq!(cache.export(&file).unwrap(), 100);
        let imported = import_with(b.path(), &file, &secret()).unwrap();
        assert_eq!((imported.entries, imported.corrupt), (100, 0));
        let back = open(b.path());
        assert!(back.len() == 100 && hashes(0..100).iter().all(|h| back.contains(h)));
        std::fs::write(&file, b"something else").unwrap();
        assert!(matches!(
            import_with(b.path(), &file, &secret()),
            Err(CacheError::NotACache { .. })
        ));
        let mut other = MAGIC.to_vec();
        other.extend_from_slice(&3u16.to_le_bytes());
        other.extend_from_slice(b"old");
        std::fs::write(&file, other).unwrap();
        let err = import_with(b.path(), &file, &secret()).unwrap_err();
        assert!(err.to_string().contains("is a cache of old"), "{err}");
    }

    /// An entry written without the secret (a forged or foreign one) is not trusted: the
    /// text it names is validated again.
    #[test]
    fn records_of_another_secret_are_not_trusted() {
        let dir = tempfile::tempdir().unwrap();
        let forger = ValidCache::open_with(dir.path(), Secret([9; 32]));
        forger.insert(hash("fn invalid() -> f32 { return vec2f(); }"));
        forger.save().unwrap();
        let cache = open(dir.path());
        assert!(!cache.contains(&hash("fn invalid() -> f32 { return vec2f(); }")));
        assert_eq!((cache.len(), cache.corrupt()), (0, 1));
        assert!(
            cache.problems()[0].contains("untrusted"),
            "{:?}",
            cache.problems()
        );
    }

    #[test]
    fn a_secret_file_is_made_once_and_read_back() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("config/cache-secret");
        let first = Secret::from_file(&file).unwrap();
        assert_eq!(Secret::from_file(&file).unwrap(), first);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&file).unwrap().permissions().mode();
            assert_eq!(mode & 0o777, 0o600);
        }
        std::fs::write(&file, "short").unwrap();
        assert!(matches!(
            Secret::from_file(&file),
            Err(CacheError::Secret { .. })
        ));
    }
}
