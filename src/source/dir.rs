//! Reading a library folder from disk.
//!
//! Only regular files are read: FIFOs, sockets and devices named like modules are skipped
//! with a note (reading one could block forever or never end). A file's size is checked
//! before it is read, and no more than the limit is read even if it grows meanwhile. Every
//! directory is entered once (by device and inode), so a symbolic link to a folder above it
//! cannot loop.

use std::collections::HashSet;
use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

use super::RawFile;

/// A problem reading a folder tree.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum DirError {
    /// The root or a file could not be read.
    #[error("cannot read `{}`: {source}", .path.display())]
    Io {
        /// The path that failed.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The tree has more files than the configured limit.
    #[error("`{}` holds more than {limit} .wgsl files (the module count limit)", .root.display())]
    TooManyFiles {
        /// The library root.
        root: PathBuf,
        /// The limit.
        limit: usize,
    },
    /// The tree's files hold more bytes than the configured limit (checked from their sizes
    /// before they are read).
    #[error("the library's sources under `{}` total at least {bytes} bytes with `{path}`, past the limit of {limit}", .root.display())]
    TooLarge {
        /// The library root.
        root: PathBuf,
        /// The file that passes the limit (relative to the root).
        path: String,
        /// Bytes counted up to and with that file.
        bytes: usize,
        /// The limit.
        limit: usize,
    },
}

/// Limits applied while reading a folder tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DirLimits {
    /// Most module files.
    pub max_files: usize,
    /// Most bytes of module source in total.
    pub max_total_bytes: usize,
}

/// What [`read_dir_tree`] found.
#[derive(Debug, Default)]
#[non_exhaustive]
pub struct DirTree {
    /// Every module file, sorted by relative path.
    pub files: Vec<RawFile>,
    /// Relative paths of symbolic links that resolve outside the root (not read; an import of
    /// one is refused with a clear message).
    pub escaping: Vec<String>,
    /// Entries named like modules that were not read, with the reason (a FIFO, a device, a
    /// folder entered twice through a link, …).
    pub skipped: Vec<(String, &'static str)>,
}

/// Identifies a directory across the different paths that reach it.
#[cfg(unix)]
fn dir_identity(meta: &fs::Metadata, _path: &Path) -> (u64, u64) {
    use std::os::unix::fs::MetadataExt;
    (meta.dev(), meta.ino())
}

#[cfg(not(unix))]
fn dir_identity(_meta: &fs::Metadata, path: &Path) -> PathBuf {
    path.to_path_buf()
}

/// Why a non-regular, non-folder entry is not read.
fn special_kind(file_type: fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if file_type.is_fifo() {
            return "a FIFO (named pipe), not a regular file: not read";
        }
        if file_type.is_socket() {
            return "a socket, not a regular file: not read";
        }
        if file_type.is_char_device() || file_type.is_block_device() {
            return "a device, not a regular file: not read";
        }
    }
    let _ = file_type;
    "not a regular file: not read"
}

/// Every `.wgsl` and `.wesl` file under `root`, sorted by relative path, within `limits`.
pub fn read_dir_tree(root: &Path, limits: DirLimits) -> Result<DirTree, DirError> {
    let io = |path: &Path, e: std::io::Error| DirError::Io {
        path: path.to_path_buf(),
        source: e,
    };
    let canonical_root = root.canonicalize().map_err(|e| io(root, e))?;
    let root_meta = fs::metadata(&canonical_root).map_err(|e| io(root, e))?;
    let mut seen = HashSet::new();
    seen.insert(dir_identity(&root_meta, &canonical_root));
    let mut tree = DirTree::default();
    let mut total = 0usize;
    let mut stack = vec![(canonical_root.clone(), String::new())];
    while let Some((dir, rel)) = stack.pop() {
        let mut entries: Vec<_> = fs::read_dir(&dir)
            .map_err(|e| io(&dir, e))?
            .filter_map(Result::ok)
            .collect();
        entries.sort_by_key(|e| e.file_name());
        for entry in entries {
            let name = entry.file_name().to_string_lossy().into_owned();
            let rel_path = if rel.is_empty() {
                name.clone()
            } else {
                format!("{rel}/{name}")
            };
            let path = entry.path();
            let resolved = match path.canonicalize() {
                Ok(p) => p,
                Err(_) => continue, // dangling link: nothing to read
            };
            if !resolved.starts_with(&canonical_root) {
                tree.escaping.push(rel_path);
                continue;
            }
            // Follows links: what the entry resolves to.
            let Ok(meta) = fs::metadata(&resolved) else {
                continue;
            };
            let module = name.ends_with(".wgsl") || name.ends_with(".wesl");
            if meta.is_dir() {
                if seen.insert(dir_identity(&meta, &resolved)) {
                    stack.push((resolved, rel_path));
                } else {
                    tree.skipped.push((
                        rel_path,
                        "a link to a folder already read (a loop or a second path): not read again",
                    ));
                }
            } else if !module {
                continue;
            } else if !meta.is_file() {
                tree.skipped
                    .push((rel_path, special_kind(meta.file_type())));
            } else {
                let size = usize::try_from(meta.len()).unwrap_or(usize::MAX);
                let over = |bytes: usize| DirError::TooLarge {
                    root: root.to_path_buf(),
                    path: rel_path.clone(),
                    bytes,
                    limit: limits.max_total_bytes,
                };
                if total.saturating_add(size) > limits.max_total_bytes {
                    return Err(over(total.saturating_add(size)));
                }
                // Reads at most one byte past what is left, in case the file grew meanwhile.
                let left = limits.max_total_bytes - total;
                let file = fs::File::open(&resolved).map_err(|e| io(&path, e))?;
                let mut bytes = Vec::with_capacity(size.min(left));
                file.take(left as u64 + 1)
                    .read_to_end(&mut bytes)
                    .map_err(|e| io(&path, e))?;
                if bytes.len() > left {
                    return Err(over(total + bytes.len()));
                }
                total += bytes.len();
                tree.files.push(RawFile {
                    path: rel_path,
                    bytes,
                });
                if tree.files.len() > limits.max_files {
                    return Err(DirError::TooManyFiles {
                        root: root.to_path_buf(),
                        limit: limits.max_files,
                    });
                }
            }
        }
    }
    tree.files.sort_by(|a, b| a.path.cmp(&b.path));
    tree.escaping.sort();
    tree.skipped.sort();
    Ok(tree)
}
