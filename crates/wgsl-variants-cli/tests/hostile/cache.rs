//! Case 1: a forged cache entry must not make an invalid variant valid.

use super::{assert_clean_exit, run_on, tree_with_bad_variant};

/// An entry written the way the cache wrote them before records were signed (check bytes =
/// the start of the hash's own unkeyed BLAKE3): what anyone with write access to a shared
/// cache folder can make.
#[test]
fn a_forged_cache_entry_does_not_make_an_invalid_variant_valid() {
    let tree = tempfile::tempdir().unwrap();
    tree_with_bad_variant(tree.path());
    let lib = wgsl_variants::Library::from_dir(tree.path()).unwrap();
    let bad = lib.variant("s", "P", &["BAD"]).unwrap();
    let text_hash = wgsl_variants::cache::hash(&lib.wgsl(&bad));

    let cache = tempfile::tempdir().unwrap();
    let key = wgsl_variants::cache::key();
    let folder = cache.path().join(&key);
    std::fs::create_dir_all(&folder).unwrap();
    let mut forged = b"WVCACHE2".to_vec();
    forged.extend_from_slice(&(key.len() as u16).to_le_bytes());
    forged.extend_from_slice(key.as_bytes());
    forged.extend_from_slice(&text_hash);
    forged.extend_from_slice(&blake3::hash(&text_hash).as_bytes()[..16]);
    std::fs::write(folder.join("forged.seg"), &forged).unwrap();
    // And in the format of the unsigned cache (8 check bytes): what fooled the tool before.
    let mut old = b"WVCACHE1".to_vec();
    old.extend_from_slice(&(key.len() as u16).to_le_bytes());
    old.extend_from_slice(key.as_bytes());
    old.extend_from_slice(&text_hash);
    old.extend_from_slice(&blake3::hash(&text_hash).as_bytes()[..8]);
    std::fs::write(folder.join("forged-unsigned.seg"), &old).unwrap();

    let dir = cache.path().to_str().unwrap();
    let out = run_on(tree.path(), &["validate", "--all", "--cache", dir]);
    assert_clean_exit(&out, 1);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("1 valid, 1 invalid"), "{stdout}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("untrusted"),
        "the forged record is reported: {stderr}"
    );

    let info = run_on(tree.path(), &["cache", "info", "--json", "--cache", dir]);
    assert_clean_exit(&info, 0);
    let info: serde_json::Value = serde_json::from_slice(&info.stdout).unwrap();
    assert_eq!(info["corrupt"], 2, "{info}");

    // The same entry signed with the secret the runs use is trusted: the cache is read.
    let secret = wgsl_variants::cache::Secret::from_hex(&"5".repeat(64)).unwrap();
    let signed = wgsl_variants::cache::ValidCache::open_with(cache.path(), secret);
    signed.insert(text_hash);
    signed.save().unwrap();
    let again = run_on(tree.path(), &["validate", "--all", "--cache", dir]);
    assert_clean_exit(&again, 0);
}
