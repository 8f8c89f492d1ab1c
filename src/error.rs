//! The errors of a variant, at the bottom of the stages: composing (our preprocessor, naga_oil
//! or wesl), naga's front end and naga's validator all report a [`VariantError`], which every
//! stage above them (library, validate, emit, bake, watch) passes on.

use std::sync::Arc;

use crate::diagnostic::{Diagnostic, Location, SourceFiles, Span};

/// Which naga stage rejected a variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stage {
    /// The tree's composer (naga_oil for a naga_oil tree: its preprocessor and imports).
    Compose,
    /// The WGSL front end (syntax, name resolution, types).
    Parse,
    /// naga's IR validator.
    Validate,
}

/// naga rejected a variant. Spans point into the original module files.
#[derive(Clone, Debug)]
pub struct VariantError {
    /// `shader/pass {KEYWORDS}`.
    pub variant: String,
    /// The failing stage.
    pub stage: Stage,
    /// naga's message, with its chain of causes.
    pub message: String,
    /// naga's labels, mapped back to original files.
    pub labels: Vec<(Span, String)>,
    /// naga's notes.
    pub notes: Vec<String>,
    /// naga's error that this reports, for [`std::error::Error::source`]; `None` where the
    /// failure is not naga's own (our checks; naga_oil's and wesl's errors are read here, not
    /// owned). Shared, so that reports stay `Clone`.
    pub(crate) source: Option<Arc<dyn std::error::Error + Send + Sync>>,
}

/// Equal when they report the same thing: the source is not compared (naga's errors are not
/// `PartialEq`, and `message`, `labels` and `notes` already carry what it says).
impl PartialEq for VariantError {
    fn eq(&self, other: &Self) -> bool {
        (
            &self.variant,
            self.stage,
            &self.message,
            &self.labels,
            &self.notes,
        ) == (
            &other.variant,
            other.stage,
            &other.message,
            &other.labels,
            &other.notes,
        )
    }
}

impl Eq for VariantError {}

impl std::fmt::Display for VariantError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} (in variant {})", self.message, self.variant)
    }
}

impl std::error::Error for VariantError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.source.as_deref().map(|e| e as _)
    }
}

impl VariantError {
    /// Keeps `source` as the error this one reports.
    pub(crate) fn with_source(
        mut self,
        source: impl std::error::Error + Send + Sync + 'static,
    ) -> VariantError {
        self.source = Some(Arc::new(source));
        self
    }

    /// A renderable report naming the variant's keyword set.
    pub fn diagnostic(&self) -> Diagnostic {
        let mut d = Diagnostic::new(self.message.clone());
        for (i, (span, label)) in self.labels.iter().enumerate() {
            d = if i == 0 {
                d.at(*span, label.clone())
            } else {
                d.also(*span, label.clone())
            };
        }
        for note in &self.notes {
            d = d.note(note.clone());
        }
        d.note(format!("in variant {}", self.variant))
    }

    /// `path:line:col` of the first label.
    pub fn location(&self, files: &SourceFiles) -> Option<Location> {
        self.labels.first().map(|(s, _)| files.location(*s))
    }
}
