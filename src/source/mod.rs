//! Reading a library's module files: a folder on disk, or in-memory texts (e.g. a tree embedded
//! into a crate, as `wgsl-variants-shaders` embeds its library).
//!
//! Loading turns bytes into text once (UTF-8 required; a BOM is dropped, which moves no line
//! or column) and records every file in [`SourceFiles`]. Line breaks are kept as written: the
//! preprocessor and [`SourceFiles`] split lines at every WGSL line break (CR LF as one), so
//! byte offsets stay those of the file. Paths are library-relative with `/` separators and
//! are sorted, so loading is deterministic.

mod dir;

use crate::diagnostic::{Diagnostic, FileId, SourceFiles, Span};

pub use dir::{DirError, DirLimits, DirTree, read_dir_tree};

/// One raw file before decoding: library-relative path and bytes.
#[derive(Clone, Debug)]
pub struct RawFile {
    /// Library-relative path with `/` separators, e.g. `deferred/gbuffer.wgsl`.
    pub path: String,
    /// File contents.
    pub bytes: Vec<u8>,
}

/// Where a library's files come from.
#[derive(Clone, Debug)]
pub enum Origin {
    /// A folder on disk.
    Dir(std::path::PathBuf),
    /// Texts given through the API.
    Memory,
}

/// A file that could not be turned into text.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SourceError {
    /// The file is not UTF-8.
    #[error("`{path}` is not valid UTF-8")]
    NotUtf8 {
        /// Library-relative path.
        path: String,
        /// The first bad byte (the file's text is its lossy decoding, which keeps the valid
        /// prefix byte for byte).
        span: Span,
    },
}

impl SourceError {
    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        match self {
            SourceError::NotUtf8 { span, path } => Diagnostic::new(self.to_string())
                .at(*span, "invalid UTF-8 byte here")
                .note(if path.ends_with(".toml") {
                    "a declaration file must be UTF-8 (TOML is)"
                } else {
                    "WGSL sources must be UTF-8"
                }),
        }
    }
}

/// Decodes raw files into `files`. Returns the id of each decoded file in input order, and an
/// error for each file that is not UTF-8 (pointing at the first bad byte).
pub(crate) fn decode(
    raw: Vec<RawFile>,
    files: &mut SourceFiles,
) -> (Vec<FileId>, Vec<SourceError>) {
    let mut ids = Vec::with_capacity(raw.len());
    let mut errors = Vec::new();
    for file in raw {
        let bytes = file
            .bytes
            .strip_prefix(b"\xEF\xBB\xBF")
            .unwrap_or(&file.bytes);
        match std::str::from_utf8(bytes) {
            Ok(text) => ids.push(files.add(file.path, text.to_string())),
            Err(e) => {
                let good = e.valid_up_to();
                // Keep the valid prefix so the snippet shows the line up to the bad byte.
                let text = String::from_utf8_lossy(bytes).into_owned();
                // The lossy text keeps the valid prefix byte for byte.
                let at = good;
                let id = files.add(file.path.clone(), text);
                errors.push(SourceError::NotUtf8 {
                    path: file.path.clone(),
                    span: Span::new(id, at..at + 1),
                });
            }
        }
    }
    (ids, errors)
}
