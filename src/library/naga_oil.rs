//! Composing variants of a naga_oil tree with naga_oil itself (the `naga-oil` cargo feature):
//! the program Bevy would get for the same shader defs, so what we validate and emit is what
//! Bevy runs. naga_oil's errors are mapped to the file, line and column of the user's tree.
//!
//! Facts about naga_oil 0.23 this relies on (from its sources and README): a module is added
//! with `Composer::add_composable_module` after every module it imports; `make_naga_module`
//! composes an entry with a map of shader defs and validates the result; an error carries the
//! module's path and the *preprocessed* text it points into, which keeps every line of the
//! original (removed lines become blanks), so a line there is the same line in the file; spans
//! of the composed module hold the module's index above bit 21 and the byte offset below;
//! decorated names are `item` + `X_naga_oil_mod_X` + the module path in base32 + `X`.

use std::collections::HashMap;
use std::sync::Mutex;

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, ComposerError, ComposerErrorInner, ErrSource,
    NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
};

use crate::diagnostic::{SourceFiles, Span};
use crate::error::{Stage, VariantError};
use crate::preprocess::tree::ParsedModule;

use super::Variant;

/// naga_oil's span layout: the module's index above this bit, the byte offset below.
const SPAN_SHIFT: usize = 21;

/// One composer per worker thread, each holding every module of the tree (naga_oil caches
/// each module per def set, so a composer is reused, never shared).
pub(crate) struct NagaOilEngine {
    pool: Mutex<Vec<Composer>>,
    /// The ids of the modules the entries reach, each after those it imports.
    order: Vec<usize>,
}

impl std::fmt::Debug for NagaOilEngine {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NagaOilEngine").finish_non_exhaustive()
    }
}

impl NagaOilEngine {
    /// An engine for the modules of a loaded tree that `roots` (the passes' entry modules)
    /// reach; the import graph is already checked acyclic.
    pub(crate) fn new(
        modules: &[ParsedModule],
        resolved: &[Vec<usize>],
        roots: impl IntoIterator<Item = usize>,
    ) -> NagaOilEngine {
        let mut order = Vec::with_capacity(modules.len());
        let mut done = vec![false; modules.len()];
        fn visit(m: usize, resolved: &[Vec<usize>], done: &mut [bool], order: &mut Vec<usize>) {
            if done[m] {
                return;
            }
            done[m] = true;
            for &t in &resolved[m] {
                visit(t, resolved, done, order);
            }
            order.push(m);
        }
        for m in roots {
            visit(m, resolved, &mut done, &mut order);
        }
        NagaOilEngine {
            pool: Mutex::new(Vec::new()),
            order,
        }
    }

    /// A composer with every named module of the tree added.
    fn composer(
        &self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        capabilities: naga::valid::Capabilities,
    ) -> Result<Composer, Box<ComposerError>> {
        // Not validating: the program is validated here, and composed again by a validating
        // composer only when it fails, for naga_oil's located error (one validation per
        // variant on the path that passes, not two). naga_oil reads the capabilities as it
        // adds each module (as Bevy 0.19 builds its composer with the device's), so they are
        // set first.
        let mut composer = Composer::non_validating().with_capabilities(capabilities);
        for &m in &self.order {
            if modules[m].import_name.is_none() {
                continue;
            }
            let file = modules[m].file;
            composer
                .add_composable_module(ComposableModuleDescriptor {
                    source: files.text(file),
                    file_path: files.path(file),
                    language: ShaderLanguage::Wgsl,
                    ..Default::default()
                })
                .map_err(Box::new)?;
        }
        Ok(composer)
    }

    /// The variant's program as naga_oil composes it, written back as WGSL by naga.
    pub(crate) fn compose(
        &self,
        files: &SourceFiles,
        modules: &[ParsedModule],
        variant: &Variant<'_>,
        profile: crate::validator::Profile,
    ) -> Result<String, VariantError> {
        let capabilities = profile.capabilities();
        // A composer built for this profile's capabilities.
        let taken = self
            .pool
            .lock()
            .map(|mut p| {
                let at = p.iter().rposition(|c| c.capabilities == capabilities)?;
                Some(p.swap_remove(at))
            })
            .unwrap_or(None);
        let mut composer = match taken {
            Some(c) => c,
            None => self
                .composer(files, modules, capabilities)
                .map_err(|e| error(&e, &Composer::default(), files, variant))?,
        };
        let defs: HashMap<String, ShaderDefValue> = variant
            .pass
            .defs(variant.keywords())
            .into_iter()
            .map(|(name, value)| (name.to_string(), value.to_naga_oil()))
            .collect();
        let entry = modules[variant.pass.module].file;
        // naga_oil may panic on input it does not expect: that is one variant's failure, and
        // the composer it left behind is dropped rather than reused.
        let descriptor = || NagaModuleDescriptor {
            source: files.text(entry),
            file_path: files.path(entry),
            shader_defs: defs.clone(),
            ..Default::default()
        };
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let module = composer
                .make_naga_module(descriptor())
                .map_err(|e| error(&e, &composer, files, variant))?;
            match profile.validator().validate(&module) {
                Ok(info) => naga::back::wgsl::write_string(
                    &module,
                    &info,
                    naga::back::wgsl::WriterFlags::empty(),
                )
                .map_err(|e| {
                    super::unlocated(variant, Stage::Compose, format!("naga's WGSL writer: {e}"))
                }),
                Err(invalid) => {
                    composer.validate = true;
                    let located = composer.make_naga_module(descriptor());
                    composer.validate = false;
                    Err(match located {
                        Err(e) => error(&e, &composer, files, variant),
                        Ok(_) => super::unlocated(
                            variant,
                            Stage::Validate,
                            invalid.as_inner().to_string(),
                        ),
                    })
                }
            }
        }));
        match outcome {
            Ok(result) => {
                if let Ok(mut pool) = self.pool.lock() {
                    pool.push(composer);
                }
                result
            }
            Err(panic) => Err(super::composer_panicked(variant, "naga_oil", panic)),
        }
    }
}

/// A naga_oil error as a [`VariantError`] located in the original file.
fn error(
    e: &ComposerError,
    composer: &Composer,
    files: &SourceFiles,
    variant: &Variant<'_>,
) -> VariantError {
    let offset = e.source.offset();
    let local = |r: std::ops::Range<usize>| {
        let mask = (1 << SPAN_SHIFT) - 1;
        (r.start & mask).saturating_sub(offset)..(r.end & mask).saturating_sub(offset)
    };
    type Labels = Vec<(std::ops::Range<usize>, String)>;
    let (stage, raw, mut notes): (Stage, Labels, Vec<String>) = match &e.inner {
        ComposerErrorInner::WgslParseError(p) => (
            Stage::Parse,
            p.labels()
                .map(|(s, m)| (local(s.to_range().unwrap_or(0..0)), m.to_string()))
                .collect(),
            Vec::new(),
        ),
        ComposerErrorInner::ShaderValidationError(v)
        | ComposerErrorInner::HeaderValidationError(v) => (
            Stage::Validate,
            v.spans()
                .map(|(s, m)| (local(s.to_range().unwrap_or(0..0)), m.clone()))
                .collect(),
            chain(v.as_inner()),
        ),
        ComposerErrorInner::ImportNotFound(_, pos)
        | ComposerErrorInner::ImportParseError(_, pos)
        | ComposerErrorInner::NotEnoughEndIfs(pos)
        | ComposerErrorInner::TooManyEndIfs(pos)
        | ComposerErrorInner::ElseWithoutCondition(pos)
        | ComposerErrorInner::UnknownShaderDef { pos, .. }
        | ComposerErrorInner::UnknownShaderDefOperator { pos, .. }
        | ComposerErrorInner::InvalidShaderDefComparisonValue { pos, .. }
        | ComposerErrorInner::OverrideNotVirtual { pos, .. }
        | ComposerErrorInner::DefineInModule(pos)
        | ComposerErrorInner::InvalidShaderDefDefinitionValue { pos, .. } => (
            Stage::Compose,
            vec![(*pos..*pos, String::new())],
            Vec::new(),
        ),
        _ => (Stage::Compose, Vec::new(), Vec::new()),
    };
    // naga_oil finds a module's path and text in the composer (and panics if it is not there,
    // as when the composer itself could not be built).
    if let ErrSource::Module { name, .. } = &e.source
        && !composer.module_sets.contains_key(name)
    {
        return VariantError {
            variant: variant.label(),
            stage,
            message: format!(
                "naga_oil: {} (in module `{name}`)",
                undecorate(&e.inner.to_string())
            ),
            labels: Vec::new(),
            notes,
            source: None,
        };
    }
    let path = e.source.path(composer);
    let source = e.source.source(composer);
    let file = (0..files.len()).find(|&f| files.path(f) == path.as_str());
    let labels = match file {
        Some(file) => raw
            .into_iter()
            .map(|(r, m)| (original_span(files, file, &source, r), undecorate(&m)))
            .collect(),
        None => {
            notes.push(format!("in `{path}`"));
            Vec::new()
        }
    };
    VariantError {
        variant: variant.label(),
        stage,
        message: format!("naga_oil: {}", undecorate(&e.inner.to_string())),
        labels,
        notes: notes.iter().map(|n| undecorate(n)).collect(),
        source: None,
    }
}

fn chain(e: &dyn std::error::Error) -> Vec<String> {
    let mut notes = Vec::new();
    let mut at = e.source();
    while let Some(s) = at {
        notes.push(s.to_string());
        at = s.source();
    }
    notes
}

/// Bytes `r` of naga_oil's preprocessed `source` of `file`, located in the file itself: the
/// same line (naga_oil keeps every line), the columns mapped back through the line's
/// substitutions ([`source_column`]).
fn original_span(
    files: &SourceFiles,
    file: crate::diagnostic::FileId,
    source: &str,
    r: std::ops::Range<usize>,
) -> Span {
    let start = r.start.min(source.len());
    let line = source[..start].matches('\n').count();
    let pre_start = source[..start].rfind('\n').map_or(0, |i| i + 1);
    let pre_end = source[pre_start..]
        .find('\n')
        .map_or(source.len(), |i| pre_start + i);
    let pre_line = &source[pre_start..pre_end];
    let text = files.text(file);
    let starts = crate::preprocess::lines::line_starts(text);
    let line_start = starts.get(line).copied().unwrap_or(text.len());
    let line_end = text[line_start..]
        .find('\n')
        .map_or(text.len(), |i| line_start + i);
    let original = &text[line_start..line_end];
    let col = start - pre_start;
    // A span running past its line keeps its length past the line's end (clipped below).
    let end_col = r.end.saturating_sub(pre_start).max(col + 1);
    let (begin, _) = source_column(original, pre_line, col);
    let (_, end) = if end_col <= pre_line.len() {
        source_column(original, pre_line, end_col - 1)
    } else {
        (0, original.len() + (end_col - pre_line.len()))
    };
    let begin = line_start + begin.min(original.len());
    let end = (line_start + end).max(begin + 1);
    Span::new(
        file,
        begin..end.min(line_end.max(begin + 1)).min(text.len().max(begin)),
    )
}

/// Where byte `col` of a preprocessed line lies in its `original` line, as the range of
/// original bytes it comes from: itself where the text is the same, the whole substitution
/// (`#{NAME}`, `#NAME`) where naga_oil put a def's value. The literal text between
/// substitutions is found again in the preprocessed line, in order.
fn source_column(original: &str, preprocessed: &str, col: usize) -> (usize, usize) {
    let mut o = 0; // in `original`
    let mut p = 0; // in `preprocessed`
    while o < original.len() {
        // The literal text up to the next substitution.
        let next = original[o..].find('#').map_or(original.len(), |i| o + i);
        let literal = &original[o..next];
        if preprocessed[p..].starts_with(literal) {
            if col < p + literal.len() {
                let at = o + (col - p);
                return (at, at + 1);
            }
            p += literal.len();
        } else {
            // Not the same text (a directive line, a change we do not model): same column.
            let at = col.min(original.len());
            return (at, at + 1);
        }
        if next == original.len() {
            break;
        }
        // The substitution's source: `#{NAME}` or `#NAME`.
        let rest = &original[next + 1..];
        let len = if let Some(inner) = rest.strip_prefix('{') {
            inner.find('}').map_or(rest.len(), |i| i + 2)
        } else {
            rest.find(|c: char| !(c.is_alphanumeric() || c == '_'))
                .unwrap_or(rest.len())
        };
        let token = next..next + 1 + len;
        o = token.end;
        // Its value runs to where the next literal text starts again.
        let following = original[o..].find('#').map_or(original.len(), |i| o + i);
        let literal = &original[o..following];
        let value_end = if literal.is_empty() {
            if following == original.len() {
                preprocessed.len()
            } else {
                p
            }
        } else {
            preprocessed[p..]
                .find(literal)
                .map_or(preprocessed.len(), |i| p + i)
        };
        if col < value_end {
            return (token.start, token.end);
        }
        p = value_end;
    }
    let at = original.len() + col.saturating_sub(p);
    (at, at + 1)
}

/// naga_oil's decorated names (`itemX_naga_oil_mod_X<base32 module>X`) written as
/// `module::item`, as the user wrote them.
fn undecorate(text: &str) -> String {
    const PRE: &str = "X_naga_oil_mod_X";
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(PRE) {
        let (before, after) = rest.split_at(at);
        let after = &after[PRE.len()..];
        // The base32 run ends with the closing `X` (base32 itself has `X` too: the last one
        // closes).
        let run = after
            .find(|c: char| !(c.is_ascii_uppercase() || c.is_ascii_digit()))
            .unwrap_or(after.len());
        let end = after[..run].rfind('X').unwrap_or(run);
        let module = data_encoding::BASE32_NOPAD
            .decode(&after.as_bytes()[..end])
            .ok()
            .and_then(|b| String::from_utf8(b).ok());
        match (module, after[end..].strip_prefix('X')) {
            (Some(module), Some(tail)) => {
                let item_start = before
                    .rfind(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .map_or(0, |i| i + 1);
                out.push_str(&before[..item_start]);
                out.push_str(&module);
                out.push_str("::");
                out.push_str(&before[item_start..]);
                rest = tail;
            }
            _ => {
                out.push_str(before);
                out.push_str(PRE);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

impl super::engine::Engine for NagaOilEngine {
    fn compose(
        &self,
        tree: &crate::preprocess::compose::ModuleGraph<'_>,
        variant: &Variant<'_>,
        how: super::engine::How,
    ) -> crate::preprocess::Composed {
        super::engine::composed(self.compose(tree.files, tree.modules, variant, how.profile))
    }

    /// naga_oil validates each imported module's header with the composer's capabilities,
    /// so a composition can succeed on one device and fail on another: one per profile.
    fn composes_alike(&self) -> bool {
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_map_back_through_substitutions() {
        let original = "const N: f32 = #{COUNT}; let b = #SCALE * x;";
        let pre = "const N: f32 = 10u; let b = 2.5 * x;";
        let find = |s: &str, t: &str| s.find(t).unwrap();
        // Before any substitution: the same byte.
        assert_eq!(source_column(original, pre, 6), (6, 7));
        // Inside a value: the whole substitution it came from.
        let value = find(pre, "10u");
        let token = find(original, "#{COUNT}");
        assert_eq!(source_column(original, pre, value + 1), (token, token + 8));
        let value = find(pre, "2.5");
        let token = find(original, "#SCALE");
        assert_eq!(source_column(original, pre, value), (token, token + 6));
        // After them: shifted by what the values changed.
        assert_eq!(
            source_column(original, pre, find(pre, "x;")),
            (find(original, "x;"), find(original, "x;") + 1)
        );
    }

    #[test]
    fn decorated_names_read_as_paths() {
        let decorated = Composer::decorated_name(Some("my_lib::light"), "shade");
        assert_eq!(
            undecorate(&format!("call to {decorated} fails")),
            "call to my_lib::light::shade fails"
        );
        assert_eq!(undecorate("plain"), "plain");
    }
}
