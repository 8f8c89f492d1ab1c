//! Reading a library folder from disk.

use std::fs;
use std::path::{Path, PathBuf};

use super::RawFile;

/// A problem reading a folder tree.
#[derive(Debug, thiserror::Error)]
pub enum DirError {
    /// The root or a file could not be read.
    #[error("cannot read `{path}`: {message}")]
    Io {
        /// The path that failed.
        path: PathBuf,
        /// The OS error.
        message: String,
    },
    /// The tree has more files than the configured limit.
    #[error("`{root}` holds more than {limit} .wgsl files (the module count limit)")]
    TooManyFiles {
        /// The library root.
        root: PathBuf,
        /// The limit.
        limit: usize,
    },
}

/// Every `.wgsl` file under `root`, sorted by relative path. Symbolic links that resolve
/// outside the root are not read; their relative paths are returned in the second list so an
/// import of one can be refused with a clear message.
pub fn read_dir_tree(
    root: &Path,
    max_files: usize,
) -> Result<(Vec<RawFile>, Vec<String>), DirError> {
    let io = |path: &Path, e: std::io::Error| DirError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let canonical_root = root.canonicalize().map_err(|e| io(root, e))?;
    let mut files = Vec::new();
    let mut escaping = Vec::new();
    let mut stack = vec![canonical_root.clone()];
    let mut rel_stack = vec![String::new()];
    while let (Some(dir), Some(rel)) = (stack.pop(), rel_stack.pop()) {
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
                escaping.push(rel_path);
                continue;
            }
            if resolved.is_dir() {
                stack.push(resolved);
                rel_stack.push(rel_path);
            } else if name.ends_with(".wgsl") || name.ends_with(".wesl") {
                let bytes = fs::read(&resolved).map_err(|e| io(&path, e))?;
                files.push(RawFile {
                    path: rel_path,
                    bytes,
                });
                if files.len() > max_files {
                    return Err(DirError::TooManyFiles {
                        root: root.to_path_buf(),
                        limit: max_files,
                    });
                }
            }
        }
    }
    files.sort_by(|a, b| a.path.cmp(&b.path));
    escaping.sort();
    Ok((files, escaping))
}
