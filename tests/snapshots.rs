//! Snapshots of the bundled library's generated WGSL (insta, in `snapshots/` at the repo root):
//! the covering set of every pass as canonical WGSL, and a manifest with a content hash of every
//! variant of the full space. Stale snapshot files (no longer produced) fail the test, as
//! `cargo insta test --unreferenced=reject` would.

use std::collections::BTreeSet;
use std::path::Path;

use wgsl_variants::snapshot::{covering_snapshots, manifest};

#[test]
fn bundled_library_snapshots() {
    let lib = wgsl_variants_shaders::library().unwrap();
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        wgsl_variants::assert_variant_snapshots!(&lib);
    });
}

#[test]
fn no_unreferenced_snapshots() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let mut expected: BTreeSet<String> = covering_snapshots(&lib)
        .unwrap()
        .into_iter()
        .map(|s| format!("{}.snap", s.name))
        .collect();
    expected.insert("manifest.snap".into());
    // Digests of every back end's output of one variant (tests/emit.rs).
    expected.insert("backend_digests.snap".into());
    // Reflection JSON (tests/reflect.rs, SNAPSHOTS).
    for name in [
        "reflect.standard.Deferred.all-off",
        "reflect.standard.Deferred.maps-hdr-reflection-buffers",
        "reflect.standard.ForwardBase.emission-occlusion",
        "reflect.deferred_reflections.Reflections",
        "reflect.deferred_final.Final",
        // Typed Rust of a pass (tests/bindings.rs).
        "bindings.standard.Deferred",
    ] {
        expected.insert(format!("{name}.snap"));
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("snapshots");
    let mut stale = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("snapshots/") {
        let name = entry
            .expect("entry")
            .file_name()
            .to_string_lossy()
            .into_owned();
        if !expected.contains(&name) {
            stale.push(name);
        }
    }
    assert!(
        stale.is_empty(),
        "unreferenced or pending snapshots in snapshots/ (delete or review them): {stale:?}"
    );
}

#[test]
fn canonical_output_is_deterministic_across_thread_counts() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| manifest(&lib, 1_000_000).unwrap());
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
        .install(|| manifest(&lib, 1_000_000).unwrap());
    assert_eq!(one, two);
    assert_eq!(one.lines().filter(|l| !l.starts_with('#')).count(), 119983);
}
