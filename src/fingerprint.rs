//! What an output was made from, as one hash: the library's sources, the stage and its
//! options, this crate's and naga's versions. Shards of one run share it; [`crate::merge`]
//! checks it, and every report and manifest records it.

use crate::library::Library;

/// A hex BLAKE3 fingerprint of what a stage's output is made from: this crate's and naga's
/// versions, every source file of `lib` (path and text), the stage's name and `options` (the
/// selection and options in any stable text form, the shard left out). Two outputs with the
/// same fingerprint come from the same inputs.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let a = wgsl_variants::fingerprint::fingerprint(&lib, "validate", "all");
/// assert_eq!(a, wgsl_variants::fingerprint::fingerprint(&lib, "validate", "all"));
/// assert_ne!(a, wgsl_variants::fingerprint::fingerprint(&lib, "validate", "build set"));
/// ```
pub fn fingerprint(lib: &Library, stage: &str, options: &str) -> String {
    let files = lib.files();
    // The devices, when they are not the default: outputs made for different devices never
    // merge.
    let profile = match lib.profiles() {
        [crate::validator::Profile::WebGpu] => None,
        [one] => Some(format!("profile {}", one.name())),
        several => Some(format!(
            "profiles {}",
            several
                .iter()
                .map(|p| p.name())
                .collect::<Vec<_>>()
                .join(" ")
        )),
    };
    let versions = [
        env!("CARGO_PKG_VERSION").as_bytes(),
        env!("WGSL_VARIANTS_NAGA_VERSION").as_bytes(),
        stage.as_bytes(),
        options.as_bytes(),
    ];
    let sources =
        (0..files.len()).flat_map(|id| [files.path(id).as_bytes(), files.text(id).as_bytes()]);
    hash_parts(
        versions
            .into_iter()
            .chain(profile.as_deref().map(str::as_bytes))
            .chain(sources),
    )
    .to_hex()
    .to_string()
}

/// The BLAKE3 hash of a list of byte strings, each length-prefixed so that no two lists hash
/// the same bytes.
pub(crate) fn hash_parts<'a>(parts: impl IntoIterator<Item = &'a [u8]>) -> blake3::Hash {
    let mut h = blake3::Hasher::new();
    for bytes in parts {
        h.update(&(bytes.len() as u64).to_le_bytes());
        h.update(bytes);
    }
    h.finalize()
}
