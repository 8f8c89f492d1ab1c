//! The bundled library with one planted bug, for tests that show a check is not vacuous.

use wgsl_variants::Library;
use wgsl_variants::source::bundled_files;

/// The bundled library with `from` replaced by `to` in the module file `path` (asserting that
/// the text was there, so a renamed line cannot make the test pass vacuously).
pub fn bundled_with(path: &str, from: &str, to: &str) -> Library {
    let raw = bundled_files()
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
