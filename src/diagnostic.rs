//! Source files, spans and rendered diagnostics.
//!
//! Every error of every stage carries a [`Span`] into an *original* module file (never into
//! composed output), so a report always names `file:line:col` of what the author wrote.
//! Reports are rendered with `codespan-reporting`, as naga renders its own.

use std::fmt;
use std::ops::Range;

use codespan_reporting::diagnostic::{Diagnostic as CsDiagnostic, Label};
use codespan_reporting::files::{Files, SimpleFiles};
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
/// Texts are stored as loaded after BOM removal and CRLF normalisation; neither changes a
/// line or a character column, so locations match what an editor shows.
#[derive(Default)]
pub struct SourceFiles {
    files: SimpleFiles<String, String>,
    count: usize,
}

impl SourceFiles {
    /// An empty set.
    pub fn new() -> SourceFiles {
        SourceFiles::default()
    }

    /// Adds a file and returns its id.
    pub fn add(&mut self, path: String, text: String) -> FileId {
        self.count += 1;
        self.files.add(path, text)
    }

    /// Number of files.
    pub fn len(&self) -> usize {
        self.count
    }

    /// Whether there are no files.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }

    /// Library-relative path of a file.
    pub fn path(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map(|f| f.name().as_str())
            .unwrap_or("<unknown>")
    }

    /// Text of a file.
    pub fn text(&self, file: FileId) -> &str {
        self.files
            .get(file)
            .map(|f| f.source().as_str())
            .unwrap_or("")
    }

    /// Resolves the start of a span to `path:line:col`.
    pub fn location(&self, span: Span) -> Location {
        let line = self
            .files
            .line_index(span.file, span.start as usize)
            .unwrap_or(0);
        let column = self
            .files
            .column_number(span.file, line, span.start as usize)
            .unwrap_or(1);
        Location {
            path: self.path(span.file).to_string(),
            line: line + 1,
            column,
        }
    }
}

/// A report ready to render: a message, where it happened, and what else is known.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
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
            message: message.into(),
            primary: None,
            secondary: Vec::new(),
            notes: Vec::new(),
        }
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
        let mut cs = CsDiagnostic::error().with_message(&self.message);
        let mut labels = Vec::new();
        if let Some((span, label)) = &self.primary {
            labels.push(Label::primary(span.file, span.range()).with_message(label));
        }
        for (span, label) in &self.secondary {
            labels.push(Label::secondary(span.file, span.range()).with_message(label));
        }
        cs = cs.with_labels(labels).with_notes(self.notes.clone());
        let config = term::Config::default();
        let mut buffer = if color {
            termcolor::Buffer::ansi()
        } else {
            termcolor::Buffer::no_color()
        };
        if term::emit_to_write_style(&mut buffer, &config, &files.files, &cs).is_err() {
            // codespan only fails on a span outside its file: fall back to the plain message.
            return format!("error: {}\n", self.message);
        }
        String::from_utf8_lossy(buffer.as_slice()).into_owned()
    }
}
