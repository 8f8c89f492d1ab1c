//! Source files, spans and rendered diagnostics.
//!
//! Every error of every stage carries a [`Span`] into an *original* module file (never into
//! composed output), so a report always names `file:line:col` of what the author wrote.
//! Reports are rendered with `codespan-reporting`, as naga renders its own. Lines are counted
//! at WGSL's line breaks (LF, VT, FF, CR, CR LF as one, NEL, LS, PS), as naga's lexer ends
//! them.

use std::fmt;
use std::ops::Range;

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::files::{Error as FilesError, Files, column_index};
use codespan_reporting::term::{self, termcolor};

/// Index of a file in [`SourceFiles`].
pub type FileId = usize;

/// A byte range in one original source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    /// The file the range is in.
    pub file: FileId,
    /// First byte.
    pub start: u32,
    /// One past the last byte.
    pub end: u32,
}

impl Span {
    /// A span over `range` of `file`.
    pub fn new(file: FileId, range: Range<usize>) -> Span {
        Span {
            file,
            start: range.start as u32,
            end: range.end as u32,
        }
    }

    /// The byte range.
    pub fn range(&self) -> Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// A resolved position: library-relative path, 1-based line and column (in characters).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize)]
pub struct Location {
    /// Path of the module relative to the library root, with `/` separators.
    pub path: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, counted in characters.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.path, self.line, self.column)
    }
}

/// The text of every file of a library, addressed by [`FileId`].
///
/// Texts are stored as loaded, after BOM removal only, so byte offsets are those of the file
/// on disk (less the BOM). Lines end at every WGSL line break (CR LF is one), so locations
/// match what naga and an editor that follows WGSL show.
#[derive(Default)]
pub struct SourceFiles {
    files: Vec<SourceFile>,
}

struct SourceFile {
    path: String,
    text: String,
    /// Byte offset of each line's start (see [`crate::preprocess::lines::line_starts`]).
    line_starts: Vec<usize>,
}

impl SourceFile {
    fn line_index(&self, byte: usize) -> usize {
        self.line_starts
            .partition_point(|&s| s <= byte)
            .saturating_sub(1)
    }

    /// The line's bytes with its break when that break is LF, CR or CR LF (which
    /// codespan trims when it prints the line, as its own files do), without it otherwise
    /// (so VT, FF, NEL, LS and PS are not printed into a terminal).
    fn line_range(&self, line: usize) -> Option<Range<usize>> {
        let start = *self.line_starts.get(line)?;
        let next = self
            .line_starts
            .get(line + 1)
            .copied()
            .unwrap_or(self.text.len());
        let end = match crate::preprocess::lines::next_break(&self.text, start) {
            Some(brk)
                if brk.end == next && !matches!(self.text.as_bytes()[brk.start], b'\n' | b'\r') =>
            {
                brk.start
            }
            _ => next,
        };
        Some(start..end)
    }
}

impl SourceFiles {
    /// An empty set.
    pub fn new() -> SourceFiles {
        SourceFiles::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, path: String, text: String) -> FileId {
        let line_starts = crate::preprocess::lines::line_starts(&text);
        self.files.push(SourceFile {
            path,
            text,
            line_starts,
        });
        self.files.len() - 1
    }

    /// Number of files.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// Whether there are no files.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Library-relative path of a file.
    pub fn path(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map_or("<unknown>", |f| f.path.as_str())
    }

    /// Text of a file.
    pub fn text(&self, file: FileId) -> &str {
        self.files.get(file).map_or("", |f| f.text.as_str())
    }

    /// Resolves the start of a span to `path:line:col` (lines counted at WGSL line breaks,
    /// columns in characters).
    pub fn location(&self, span: Span) -> Location {
        let (line, column) = match self.files.get(span.file) {
            Some(f) => {
                let line = f.line_index(span.start as usize);
                let range = f.line_range(line).unwrap_or(0..0);
                (line, column_index(&f.text, range, span.start as usize) + 1)
            }
            None => (0, 1),
        };
        Location {
            path: self.path(span.file).to_string(),
            line: line + 1,
            column,
        }
    }

    fn file(&self, id: FileId) -> Result<&SourceFile, FilesError> {
        self.files.get(id).ok_or(FilesError::FileMissing)
    }
}

/// What `codespan-reporting` renders from: the same files, with WGSL line starts.
impl<'a> Files<'a> for SourceFiles {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        Ok(self.file(id)?.path.as_str())
    }

    fn source(&'a self, id: FileId) -> Result<&'a str, FilesError> {
        Ok(self.file(id)?.text.as_str())
    }

    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, FilesError> {
        Ok(self.file(id)?.line_index(byte_index))
    }

    fn line_range(&'a self, id: FileId, line_index: usize) -> Result<Range<usize>, FilesError> {
        let file = self.file(id)?;
        file.line_range(line_index).ok_or(FilesError::LineTooLarge {
            given: line_index,
            max: file.line_starts.len() - 1,
        })
    }
}

/// `range` widened to character boundaries of `text` and clipped to it, so a label that a
/// byte-based mapping put inside a multi-byte line break still renders; empty when it starts
/// on a line break.
fn char_range(text: &str, range: Range<usize>) -> Range<usize> {
    let mut start = range.start.min(text.len());
    while !text.is_char_boundary(start) {
        start -= 1;
    }
    if crate::preprocess::lines::next_break(text, start).is_some_and(|b| b.start == start) {
        // A label on a line break marks the end of its line (one caret), not two lines.
        return start..start;
    }
    let mut end = range.end.clamp(start, text.len());
    while !text.is_char_boundary(end) {
        end += 1;
    }
    start..end
}

/// How serious a [`Diagnostic`] is.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Severity {
    /// The input cannot be used as it is.
    #[default]
    Error,
    /// The input works, but probably not as meant (e.g. a keyword no module reads).
    Warning,
}

/// A report ready to render: a message, where it happened, and what else is known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// Error or warning.
    pub severity: Severity,
    /// One-line summary.
    pub message: String,
    /// The primary location and its label.
    pub primary: Option<(Span, String)>,
    /// Related locations (e.g. the other end of an import cycle).
    pub secondary: Vec<(Span, String)>,
    /// Further lines, such as the keyword set of the variant.
    pub notes: Vec<String>,
}

impl Diagnostic {
    /// A diagnostic with a message only.
    pub fn new(message: impl Into<String>) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            message: message.into(),
            primary: None,
            secondary: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Makes it a warning.
    pub fn warning(mut self) -> Diagnostic {
        self.severity = Severity::Warning;
        self
    }

    /// Sets the primary location.
    pub fn at(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.primary = Some((span, label.into()));
        self
    }

    /// Adds a related location.
    pub fn also(mut self, span: Span, label: impl Into<String>) -> Diagnostic {
        self.secondary.push((span, label.into()));
        self
    }

    /// Adds a note line.
    pub fn note(mut self, note: impl Into<String>) -> Diagnostic {
        self.notes.push(note.into());
        self
    }

    /// `path:line:col` of the primary location, if any.
    pub fn location(&self, files: &SourceFiles) -> Option<Location> {
        self.primary.as_ref().map(|(span, _)| files.location(*span))
    }

    /// Renders like rustc/naga: `error: …`, the location, a snippet of the original source and
    /// the notes. `color` adds ANSI colours.
    pub fn render(&self, files: &SourceFiles, color: bool) -> String {
        let mut cs = match self.severity {
            Severity::Error => CsDiagnostic::error(),
            Severity::Warning => CsDiagnostic::warning(),
        }
        .with_message(&self.message);
        let mut labels = Vec::new();
        if let Some((span, label)) = &self.primary {
            let range = char_range(files.text(span.file), span.range());
            labels.push(Label::primary(span.file, range).with_message(label));
        }
        for (span, label) in &self.secondary {
            let range = char_range(files.text(span.file), span.range());
            labels.push(Label::secondary(span.file, range).with_message(label));
        }
        cs = cs.with_labels(labels).with_notes(self.notes.clone());
        let config = term::Config::default();
        let mut buffer = if color {
            termcolor::Buffer::ansi()
        } else {
            termcolor::Buffer::no_color()
        };
        if term::emit_to_write_style(&mut buffer, &config, files, &cs).is_err() {
            // codespan only fails on a span outside its file: fall back to the plain message.
            let what = match self.severity {
                Severity::Error => "error",
                Severity::Warning => "warning",
            };
            return format!("{what}: {}\n", self.message);
        }
        String::from_utf8_lossy(buffer.as_slice()).into_owned()
    }
}

/// `; did you mean `x`?`, the closest of `candidates` to `name` ([`suggest`]), or nothing: the
/// tail of a message about a name that is not there.
pub(crate) fn did_you_mean<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> String {
    hint(suggest(name, candidates).as_deref())
}

/// `; did you mean `x`?` for a suggestion, or nothing.
pub(crate) fn hint(suggestion: Option<&str>) -> String {
    suggestion
        .map(|s| format!("; did you mean `{s}`?"))
        .unwrap_or_default()
}

/// The closest of `candidates` to `name` by edit distance, if reasonably close.
pub(crate) fn suggest<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<String> {
    let limit = (name.len() / 3).max(2);
    candidates
        .into_iter()
        .map(|c| (strsim::levenshtein(name, c), c))
        .filter(|(d, _)| *d <= limit)
        .min()
        .map(|(_, c)| c.to_string())
}
