//! Reading the JSON and TOML files the tool takes (materials, budgets): one way to read them
//! and to report where they are wrong.

use std::path::Path;

use serde::de::DeserializeOwned;

/// A data file that could not be read or is not of the expected shape.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The file could not be read.
    #[error("cannot read {what} file `{path}`: {source}")]
    Io {
        /// What the file is, for messages: `materials`, `budget`.
        what: &'static str,
        /// The file.
        path: String,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// Not valid JSON/TOML of the expected shape.
    #[error("{path}:{line}:{column}: {message}")]
    Syntax {
        /// The file.
        path: String,
        /// 1-based line.
        line: usize,
        /// 1-based column.
        column: usize,
        /// The parser's message.
        message: String,
    },
}

/// The syntax of a data file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    /// JSON.
    Json,
    /// TOML.
    Toml,
}

/// The text of `path`; `what` names the file in messages.
pub(crate) fn read(path: &Path, what: &'static str) -> Result<String, FileError> {
    std::fs::read_to_string(path).map_err(|e| FileError::Io {
        what,
        path: path.display().to_string(),
        source: e,
    })
}

/// Parses a data file's text; `path` is used in messages.
pub(crate) fn parse<T: DeserializeOwned>(
    text: &str,
    format: Format,
    path: &str,
) -> Result<T, FileError> {
    let syntax = |line: usize, column: usize, message: String| FileError::Syntax {
        path: path.to_string(),
        line,
        column,
        message,
    };
    match format {
        Format::Toml => toml::from_str(text).map_err(|e| {
            let (line, column) = line_col(text, e.span().map_or(0, |s| s.start));
            syntax(line, column, e.message().to_string())
        }),
        Format::Json => {
            serde_json::from_str(text).map_err(|e| syntax(e.line(), e.column(), e.to_string()))
        }
    }
}

/// 1-based line and column (in characters) of byte `offset` of `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}
