//! Canonical WGSL and snapshot sets, for reviewing generated code with insta.
//!
//! Canonical text is what naga's WGSL back end writes after compaction (unused types,
//! constants and functions removed), as naga's own snapshot tests do: stable ordering and
//! formatting, so snapshots do not churn with comment or whitespace edits, and byte-identical
//! across runs and thread counts.
//!
//! Snapshot a whole library in your own tests with one call (insta must be a dev-dependency):
//!
//! ```no_run
//! let lib = wgsl_variants::Library::from_dir("shaders").unwrap();
//! wgsl_variants::assert_variant_snapshots!(&lib);
//! ```

use rayon::prelude::*;

use crate::emit::set::file_safe;
use crate::error::VariantError;
use crate::library::{Library, Variant};
use crate::shader::Pass;
use crate::variants::{Choice, Space};

/// A named text to snapshot.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Snapshot {
    /// Snapshot name (file-name safe): `shader.pass.keywords`.
    pub name: String,
    /// The canonical WGSL (or the manifest).
    pub text: String,
}

/// The canonical WGSL of a variant: validated, compacted, and written by naga's WGSL back end.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// let text = wgsl_variants::snapshot::canonical_wgsl(&lib, &v).unwrap();
/// assert!(text.contains("@fragment"));
/// ```
pub fn canonical_wgsl(lib: &Library, variant: &Variant<'_>) -> Result<String, VariantError> {
    let (module, info) = crate::validate::compile(lib, variant)?;
    let label = variant.label();
    naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty()).map_err(
        |e| {
            VariantError {
                variant: label,
                stage: crate::error::Stage::Validate,
                message: format!("naga's WGSL writer failed: {e}"),
                labels: Vec::new(),
                notes: Vec::new(),
                source: None,
            }
            .with_source(e)
        },
    )
}

/// A small covering set of a pass's variants, named: `all-off` (each set at its "none"
/// option, or its first), each keyword alone (named by the keyword), and `all-on` (each set at
/// its last option; under `#pragma exclude A B`, `B` is left off). Duplicates are removed;
/// order is stable. Under `#pragma require` a keyword comes with the keywords it requires; a
/// variant that still breaks a constraint is left out. For t-wise coverage see [`Space::covering`].
pub fn covering_set(pass: &Pass) -> Vec<(String, Choice)> {
    let base: Vec<u16> = pass
        .sets
        .iter()
        .map(|s| s.none_index().unwrap_or(0) as u16)
        .collect();
    let mut out = vec![(
        "all-off".to_string(),
        Choice(base.clone().into_boxed_slice()),
    )];
    for (set, s) in pass.sets.iter().enumerate() {
        for (option, name) in s.options.iter().enumerate() {
            if let Some(name) = name
                && option as u16 != base[set]
            {
                let mut c = base.clone();
                c[set] = option as u16;
                out.push((name.clone(), Choice(c.into_boxed_slice())));
            }
        }
    }
    let mut all_on: Vec<u16> = pass.sets.iter().map(|s| s.len() as u16 - 1).collect();
    for c in &pass.constraints {
        if c.kind == crate::keywords::ConstraintKind::Exclude && !c.holds(&all_on) {
            let set = c.at[1].0;
            all_on[set] = base[set];
        }
    }
    out.push(("all-on".to_string(), Choice(all_on.into_boxed_slice())));
    let full = Space::full(pass);
    for (_, choice) in out.iter_mut() {
        require(pass, choice);
    }
    let mut seen = std::collections::HashSet::new();
    out.retain(|(_, c)| full.contains(c) && seen.insert(c.clone()));
    out
}

/// Turns on what the keywords that are on require (transitively, bounded by the number of
/// constraints).
fn require(pass: &Pass, choice: &mut Choice) {
    for _ in 0..pass.constraints.len() {
        let mut changed = false;
        for c in &pass.constraints {
            if c.kind == crate::keywords::ConstraintKind::Require && !c.holds(&choice.0) {
                let (set, option) = c.at[1];
                choice.0[set] = option as u16;
                changed = true;
            }
        }
        if !changed {
            return;
        }
    }
}

/// Canonical WGSL of the covering set of every pass, named `shader.pass.which`.
pub fn covering_snapshots(lib: &Library) -> Result<Vec<Snapshot>, VariantError> {
    let variants: Vec<(String, Variant<'_>)> = lib
        .passes()
        .flat_map(|pass| {
            covering_set(pass).into_iter().map(move |(which, choice)| {
                let name = format!(
                    "{}.{}.{}",
                    file_safe(&pass.shader),
                    file_safe(&pass.name),
                    file_safe(&which)
                );
                (name, Variant { pass, choice })
            })
        })
        .collect();
    variants
        .par_iter()
        .map(|(name, v)| {
            Ok(Snapshot {
                name: name.clone(),
                text: canonical_wgsl(lib, v)?,
            })
        })
        .collect()
}

/// A manifest of every variant of every pass's full space: one line per variant with its
/// keyword set and a content hash of its canonical WGSL (BLAKE3, 16 hex digits), so a change to
/// any variant shows in review. `budget` bounds the variants per pass. `wgsl-variants manifest`
/// prints it; [`manifest_summary`] is the short form that snapshots hold.
pub fn manifest(lib: &Library, budget: u64) -> Result<String, ManifestError> {
    manifest_of(lib, &lib.passes().collect::<Vec<_>>(), budget)
}

/// [`manifest`] of the passes `passes` only (of `lib`), in that order.
pub fn manifest_of(lib: &Library, passes: &[&Pass], budget: u64) -> Result<String, ManifestError> {
    let mut out = String::new();
    for pass in manifest_passes(lib, passes, budget)? {
        out.push_str(&format!(
            "# {}/{}: {} variants\n",
            pass.shader,
            pass.pass,
            pass.lines.len()
        ));
        for line in &pass.lines {
            out.push_str(line);
            out.push('\n');
        }
    }
    Ok(out)
}

/// The reviewable form of [`manifest`]: per pass, the number of variants, of distinct canonical
/// texts, and a digest of the pass's manifest lines (BLAKE3 of the lines in enumeration order,
/// 16 hex digits). Any change to any variant's canonical WGSL changes the digest; `wgsl-variants
/// manifest` prints the full list to see which.
///
/// `DETAIL` reaches no code, so its two variants of each `RED` choice share one text:
///
/// ```
/// let lib = wgsl_variants::Library::from_sources([(
///     "unlit.wgsl",
///     "#shader unlit\n#pass Forward\n#pragma multi_compile _ RED\n#pragma multi_compile _ DETAIL\n\
///      @fragment fn fs() -> @location(0) vec4f {\n#if RED\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n\
///      #else\n    return vec4f(1.0);\n#endif\n}\n#endpass\n",
/// )])
/// .unwrap();
/// let summary = wgsl_variants::snapshot::manifest_summary(&lib, 100).unwrap();
/// assert!(summary.contains("unlit/Forward: 4 variants, 2 distinct, digest "));
/// ```
///
/// The bundled library's summary is the committed `snapshots/manifest.snap` (tests/snapshots.rs).
pub fn manifest_summary(lib: &Library, budget: u64) -> Result<String, ManifestError> {
    manifest_summary_of(lib, &lib.passes().collect::<Vec<_>>(), budget)
}

/// [`manifest_summary`] of the passes `passes` only (of `lib`), in that order: the same line
/// per pass as the whole library's summary.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let pass = lib.pass("deferred_final", "Final").unwrap();
/// let one = wgsl_variants::snapshot::manifest_summary_of(&lib, &[pass], 100).unwrap();
/// assert!(one.contains("deferred_final/Final: 1 variants, 1 distinct"));
/// assert!(!one.contains("standard/"));
/// ```
pub fn manifest_summary_of(
    lib: &Library,
    passes: &[&Pass],
    budget: u64,
) -> Result<String, ManifestError> {
    let mut out = String::from(
        "# shader/pass: variants, distinct canonical texts, digest of the full manifest lines\n\
         # (print the full list with `wgsl-variants manifest`)\n",
    );
    for pass in manifest_passes(lib, passes, budget)? {
        let mut hasher = blake3::Hasher::new();
        let mut distinct = std::collections::HashSet::new();
        for line in &pass.lines {
            hasher.update(line.as_bytes());
            hasher.update(b"\n");
            distinct.insert(line.split(' ').next().unwrap_or_default());
        }
        out.push_str(&format!(
            "{}/{}: {} variants, {} distinct, digest {}\n",
            pass.shader,
            pass.pass,
            pass.lines.len(),
            distinct.len(),
            &hasher.finalize().to_hex()[..16]
        ));
    }
    Ok(out)
}

/// One pass's manifest lines (`hash {KEYWORDS}`), in enumeration order.
struct PassManifest {
    shader: String,
    pass: String,
    lines: Vec<String>,
}

fn manifest_passes(
    lib: &Library,
    selected: &[&Pass],
    budget: u64,
) -> Result<Vec<PassManifest>, ManifestError> {
    let mut passes = Vec::new();
    for &pass in selected {
        let choices =
            Space::full(pass)
                .enumerate(budget)
                .map_err(|error| ManifestError::Budget {
                    shader: pass.shader.clone(),
                    pass: pass.name.clone(),
                    error,
                })?;
        // Identical composed texts have identical canonical texts: hash each distinct one once.
        let composed: Vec<String> = choices
            .par_iter()
            .map(|c| {
                lib.wgsl(&Variant {
                    pass,
                    choice: c.clone(),
                })
            })
            .collect();
        let mut first: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
        for (i, text) in composed.iter().enumerate() {
            first.entry(text.as_str()).or_insert(i);
        }
        let mut distinct: Vec<usize> = first.values().copied().collect();
        distinct.sort_unstable();
        let hashes: Vec<(usize, String)> = distinct
            .par_iter()
            .map(|&i| {
                let text = canonical_wgsl(
                    lib,
                    &Variant {
                        pass,
                        choice: choices[i].clone(),
                    },
                )?;
                Ok((i, blake3::hash(text.as_bytes()).to_hex()[..16].to_string()))
            })
            .collect::<Result<_, VariantError>>()?;
        let by_index: std::collections::HashMap<usize, &str> =
            hashes.iter().map(|(i, h)| (*i, h.as_str())).collect();
        let lines = choices
            .iter()
            .zip(&composed)
            .map(|(choice, text)| {
                let hash = by_index[&first[text.as_str()]];
                format!("{hash} {}", choice.label(pass))
            })
            .collect();
        passes.push(PassManifest {
            shader: pass.shader.clone(),
            pass: pass.name.clone(),
            lines,
        });
    }
    Ok(passes)
}

/// Why a manifest could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ManifestError {
    /// A pass's full space is past the budget.
    #[error("{shader}/{pass}: {error}")]
    Budget {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The budget error.
        error: crate::variants::BudgetError,
    },
    /// A variant is invalid.
    #[error(transparent)]
    Invalid(#[from] VariantError),
}

/// Asserts insta snapshots of a library: the canonical WGSL of every pass's covering set
/// ([`covering_set`]) and the summary of a manifest of every variant ([`manifest_summary`]). Needs `insta` as a
/// dev-dependency of the calling crate; snapshots land where insta puts them for that test.
#[macro_export]
macro_rules! assert_variant_snapshots {
    ($lib:expr) => {{
        let lib: &$crate::Library = $lib;
        for snapshot in $crate::snapshot::covering_snapshots(lib)
            .unwrap_or_else(|e| panic!("{}", e.diagnostic().render(lib.files(), false)))
        {
            ::insta::assert_snapshot!(snapshot.name, snapshot.text);
        }
        let manifest =
            $crate::snapshot::manifest_summary(lib, 1_000_000).unwrap_or_else(|e| panic!("{e}"));
        ::insta::assert_snapshot!("manifest", manifest);
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A keyword alone comes with what it requires; the all-on variant, which breaks an
    /// exclusion, is left out.
    #[test]
    fn covering_set_honours_constraints() {
        let lib = Library::from_sources([(
            "s.wgsl",
            "#shader s\n#pass P\n#pragma shader_feature _ N\n#pragma shader_feature _ D\n\
             #pragma multi_compile _ X\n#pragma require D N\n#pragma exclude X N\n#endpass",
        )])
        .unwrap();
        let pass = lib.pass("s", "P").unwrap();
        let names: Vec<(String, Vec<&str>)> = covering_set(pass)
            .into_iter()
            .map(|(n, c)| (n, c.keywords(pass)))
            .collect();
        let expected: Vec<(String, Vec<&str>)> = vec![
            ("all-off".into(), vec![]),
            ("N".into(), vec!["N"]),
            ("D".into(), vec!["N", "D"]),
            ("X".into(), vec!["X"]),
        ];
        assert_eq!(names, expected);
    }
}
