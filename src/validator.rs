//! naga's verdict on one composed text: the [`validator`] (every check, WebGPU's capabilities)
//! and [`validate_composed`], whose errors point into the original module files. The library
//! composes with it; [`crate::validate`] runs it over whole variant spaces.

use crate::diagnostic::Span;
use crate::error::{Stage, VariantError};
use crate::preprocess::Composed;

fn error_chain(e: &dyn std::error::Error) -> String {
    let mut message = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        message.push_str(": ");
        message.push_str(&s.to_string());
        source = s.source();
    }
    message
}

/// Parses and validates composed WGSL; `variant` names it in errors.
pub fn validate_composed(
    composed: &Composed,
    variant: &str,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    validate_with(composed, variant, &mut validator())
}

/// The validator every stage uses: every check on, and the capabilities WebGPU gives a shader
/// by default (what wgpu accepts without optional features).
pub fn validator() -> naga::valid::Validator {
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
}

fn map_spans<'a>(
    composed: &Composed,
    spans: impl Iterator<Item = (naga::Span, &'a str)>,
) -> Vec<(Span, String)> {
    spans
        .filter_map(|(span, label)| {
            let range = span.to_range()?;
            let original = composed
                .map
                .to_original(range.start, range.end, &composed.text)?;
            Some((original, label.to_string()))
        })
        .collect()
}

/// naga's parse error message. Its internal errors ("internal WGSL front end error") carry what
/// went wrong in a note and have no location: the note joins the message, so every report
/// (text, JSON, `watch`) says which limit tripped.
fn parse_message(e: &naga::front::wgsl::ParseError) -> String {
    let message = e.message();
    if e.labels().next().is_some() {
        return message.to_string();
    }
    let notes: Vec<&str> = e.notes().collect();
    if notes.is_empty() {
        return message.to_string();
    }
    let hint = if notes.iter().any(|n| n.contains("recursion limit")) {
        " (naga's WGSL parser nests expressions, blocks and types at most 200 levels deep: split the nesting with `let` bindings or functions)"
    } else {
        ""
    };
    format!("{message}: {}{hint}", notes.join("; "))
}

pub(crate) fn validate_with(
    composed: &Composed,
    variant: &str,
    validator: &mut naga::valid::Validator,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    if let Some(failure) = &composed.failure {
        return Err(VariantError {
            variant: variant.to_string(),
            ..(**failure).clone()
        });
    }
    let module = naga::front::wgsl::parse_str(&composed.text).map_err(|e| {
        VariantError {
            variant: variant.to_string(),
            stage: Stage::Parse,
            message: parse_message(&e),
            labels: map_spans(composed, e.labels()),
            notes: e.notes().map(str::to_string).collect(),
            source: None,
        }
        .with_source(e)
    })?;
    let info = validator.validate(&module).map_err(|e| {
        let mut labels = map_spans(composed, e.spans().map(|(s, l)| (*s, l.as_str())));
        // naga lists the enclosing function first; the narrowest span is where to look.
        labels.sort_by_key(|(span, _)| span.end - span.start);
        VariantError {
            variant: variant.to_string(),
            stage: Stage::Validate,
            message: error_chain(e.as_inner()),
            labels,
            notes: Vec::new(),
            source: None,
        }
        .with_source(e)
    })?;
    Ok((module, info))
}
