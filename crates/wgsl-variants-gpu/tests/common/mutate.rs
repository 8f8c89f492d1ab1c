//! The bundled library with one planted bug, for tests that show a check is not vacuous.

use wgsl_variants::Library;
use wgsl_variants_shaders::files;

/// The bundled library with `from` replaced by `to` in the module file `path` (asserting that
/// the text was there, so a renamed line cannot make the test pass vacuously).
pub fn bundled_with(path: &str, from: &str, to: &str) -> Library {
    let raw = files()
        .into_iter()
        .map(|mut f| {
            if f.path == path {
                let text = String::from_utf8(f.bytes).unwrap();
                let wrong = text.replace(from, to);
                assert_ne!(text, wrong, "the mutation applies");
                f.bytes = wrong.into_bytes();
            }
            f
        })
        .collect();
    Library::from_raw(raw, &Default::default()).unwrap()
}

/// The keyword sets of every variant with mismatches in the first pass of `report` (a check
/// of a library with a planted bug; all of them, not only the listed mismatches'), asserting
/// that the bug was caught at all.
pub fn caught_in(report: &wgsl_variants_gpu::check::CheckReport) -> Vec<String> {
    let p = &report.passes[0];
    assert!(p.mismatches > 0, "the planted bug is caught: {report}");
    assert_eq!(
        p.mismatches_by_variant.values().sum::<usize>(),
        p.mismatches,
        "every mismatch is tallied"
    );
    p.mismatches_by_variant.keys().cloned().collect()
}

/// Asserts that every caught variant (`caught`, from [`caught_in`]) names each of `tokens`:
/// the planted bug shows only where they are on.
pub fn assert_each_has(caught: &[String], tokens: &[&str]) {
    for k in caught {
        for token in tokens {
            assert!(k.contains(token), "caught in `{k}`, which lacks {token}");
        }
    }
}
