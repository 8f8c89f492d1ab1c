//! Errors of loading and linking a library.

use std::fmt;

use crate::diagnostic::{Diagnostic, SourceFiles, Span};
use crate::keywords::KeywordError;
use crate::preprocess::ParseError;

/// A problem linking modules together (imports) or assembling shaders.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LinkError {
    /// `#import` of a module that does not exist.
    #[error("cannot import `{path}`: {reason}")]
    MissingImport {
        /// The path as written.
        path: String,
        /// Why (no such file, a directory, …).
        reason: String,
        /// Where.
        span: Span,
    },
    /// `#import` of a symlink that leads outside the library root.
    #[error("cannot import `{path}`: it is a symbolic link that leaves the library root")]
    LeavesRoot {
        /// The path as written.
        path: String,
        /// Where.
        span: Span,
    },
    /// Modules that import each other in a cycle.
    #[error("import cycle: {}", cycle.iter().map(|c| c.0.as_str()).collect::<Vec<_>>().join(" -> "))]
    Cycle {
        /// The modules of the cycle, each with the `#import` that continues it; the first module
        /// is repeated at the end.
        cycle: Vec<(String, Span)>,
    },
    /// An import chain deeper than the limit.
    #[error("import chain deeper than the limit of {limit}")]
    TooDeep {
        /// The limit.
        limit: usize,
        /// The import where the limit was passed.
        span: Span,
    },
    /// Two declarations (two files, or two `[[shader]]` entries of a declaration file) name
    /// the same shader.
    #[error("shader `{name}` is declared twice")]
    DuplicateShader {
        /// The name.
        name: String,
        /// The second declaration.
        span: Span,
        /// The first declaration.
        first: Span,
    },
    /// A shader with two passes of the same name.
    #[error("shader `{shader}` has two passes named `{name}`")]
    DuplicatePass {
        /// The shader.
        shader: String,
        /// The pass name.
        name: String,
        /// The second declaration.
        span: Span,
        /// The first.
        first: Span,
    },
    /// Two naga_oil modules with the same `#define_import_path`.
    #[error("two modules define import path `{name}`")]
    DuplicateImportPath {
        /// The import path.
        name: String,
        /// The second definition.
        span: Span,
        /// The first.
        first: Span,
    },
    /// A declaration file names an entry module the tree does not have.
    #[error("shader `{shader}`'s entry `{path}` is not a module of the tree{hint}")]
    UnknownEntry {
        /// The shader.
        shader: String,
        /// The path as written.
        path: String,
        /// A close match, as `; did you mean …?`, or empty.
        hint: String,
        /// Where it is written.
        span: Span,
    },
    /// The library is larger than the source-size limit.
    #[error("the library's sources total {bytes} bytes, past the limit of {limit}")]
    TooLarge {
        /// Total bytes.
        bytes: usize,
        /// The limit.
        limit: usize,
    },
}

impl LinkError {
    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        let d = Diagnostic::new(self.to_string());
        match self {
            LinkError::MissingImport {
                span, path, reason, ..
            } => d.at(*span, "imported here").note(
                if path.starts_with("package::") || reason.contains("package") {
                    "WESL imports name a module by its package and its path in the package (`package::a::b` is the file `a/b.wesl` of the importing module's package; `bevy_render::maths` is `maths.wesl` in the folder `[packages]` maps `bevy_render` to), then optionally its items"
                } else if path.contains("::") {
                    "naga_oil imports name a module's `#define_import_path`, then optionally its items"
                } else {
                    "paths are relative to the library root, `/`-separated, without `.wgsl`"
                },
            ),
            LinkError::LeavesRoot { span, .. } | LinkError::TooDeep { span, .. } => {
                d.at(*span, "imported here")
            }
            LinkError::UnknownEntry { span, .. } => d.at(*span, "named here"),
            LinkError::Cycle { cycle } => {
                let mut d = d;
                for (i, (module, span)) in
                    cycle.iter().enumerate().take(cycle.len().saturating_sub(1))
                {
                    let next = &cycle[i + 1].0;
                    d = if i == 0 {
                        d.at(*span, format!("`{module}` imports `{next}`"))
                    } else {
                        d.also(*span, format!("`{module}` imports `{next}`"))
                    };
                }
                d
            }
            LinkError::DuplicateShader { span, first, .. }
            | LinkError::DuplicatePass { span, first, .. }
            | LinkError::DuplicateImportPath { span, first, .. } => d
                .at(*span, "declared again here")
                .also(*first, "first declared here"),
            LinkError::TooLarge { .. } => d,
        }
    }
}

/// One problem found while loading a library, as the stage that found it reported it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadProblem {
    /// The library's folder could not be read.
    #[error(transparent)]
    Dir(#[from] crate::source::DirError),
    /// A file could not be decoded.
    #[error(transparent)]
    Source(#[from] crate::source::SourceError),
    /// A directive is malformed.
    #[error(transparent)]
    Parse(#[from] ParseError),
    /// Imports or shader declarations do not fit together.
    #[error(transparent)]
    Link(#[from] LinkError),
    /// A pass's keyword pragmas are inconsistent.
    #[error(transparent)]
    Keyword(#[from] KeywordError),
    /// The declaration file is malformed.
    #[error(transparent)]
    Declaration(#[from] crate::declaration::DeclarationError),
}

impl LoadProblem {
    /// A renderable report.
    pub fn diagnostic(&self) -> Diagnostic {
        match self {
            LoadProblem::Dir(e) => Diagnostic::new(e.to_string()),
            LoadProblem::Source(e) => e.diagnostic(),
            LoadProblem::Parse(e) => e.diagnostic(),
            LoadProblem::Link(e) => e.diagnostic(),
            LoadProblem::Keyword(e) => e.diagnostic(),
            LoadProblem::Declaration(e) => e.diagnostic(),
        }
    }
}

/// Loading a library failed. Holds every problem found, typed, and the sources, so each can
/// be matched on and rendered with a snippet of the original file.
///
/// ```
/// use wgsl_variants::library::{LinkError, LoadProblem};
///
/// let err = wgsl_variants::Library::from_sources([("a.wgsl", "#import b")]).unwrap_err();
/// assert!(matches!(err.problems[0], LoadProblem::Link(LinkError::MissingImport { .. })));
/// assert_eq!(err.locations(), ["a.wgsl:1:9"]);
/// ```
pub struct LoadError {
    /// The files that were read.
    pub files: SourceFiles,
    /// Every problem, in file order.
    pub problems: Vec<LoadProblem>,
}

impl LoadError {
    /// One report per problem, in file order.
    pub fn diagnostics(&self) -> Vec<Diagnostic> {
        self.problems.iter().map(LoadProblem::diagnostic).collect()
    }

    /// Renders every problem (ANSI colours when `color`).
    pub fn render(&self, color: bool) -> String {
        self.diagnostics()
            .iter()
            .map(|d| d.render(&self.files, color))
            .collect()
    }

    /// `path:line:col` of each problem that has a location.
    pub fn locations(&self) -> Vec<String> {
        self.diagnostics()
            .iter()
            .filter_map(|d| d.location(&self.files))
            .map(|l| l.to_string())
            .collect()
    }
}

impl fmt::Debug for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(false))
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(false))
    }
}

impl std::error::Error for LoadError {}
