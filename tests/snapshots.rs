//! Snapshots of the bundled library's generated WGSL (insta, in `snapshots/` at the repo root):
//! the covering set of every pass as canonical WGSL, and a manifest with a content hash of every
//! variant of the full space. Stale snapshot files (no longer produced) fail the test, as
//! `cargo insta test --unreferenced=reject` would.

use std::collections::BTreeSet;
use std::path::Path;

use wgsl_variants::snapshot::{covering_snapshots, manifest_summary_of};
use wgsl_variants::{Pass, Space};

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

/// The canonical output on one thread equals the committed manifest snapshot, which
/// `bundled_library_snapshots` checks on the default pool (one thread per core), so the output
/// does not depend on the thread count. On every bundled pass under 20,000 variants (the
/// largest, `standard/ForwardAdd`, 18,432): each is split between threads the same way as a
/// larger one, and the four larger passes (ForwardBase, Deferred and URP Lit's two lit passes,
/// 49,152 to 110,592 variants) would make the one-thread run the longest step of the test
/// suite.
#[test]
fn canonical_output_is_deterministic_across_thread_counts() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let small: Vec<&Pass> = lib
        .passes()
        .filter(|p| Space::full(p).count() < num_bigint::BigUint::from(20_000u32))
        .collect();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| manifest_summary_of(&lib, &small, 1_000_000).unwrap());
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("snapshots/manifest.snap");
    let snap = std::fs::read_to_string(&file).expect("snapshots/manifest.snap");
    let committed: BTreeSet<&str> = snap.lines().collect();
    let passes: Vec<&str> = one.lines().filter(|l| !l.starts_with('#')).collect();
    for line in &passes {
        assert!(
            committed.contains(line),
            "one thread gives `{line}`, not in snapshots/manifest.snap (if the shaders changed, \
             review the snapshot first: cargo insta test --review)"
        );
    }
    let variants: u64 = passes
        .iter()
        .map(|l| {
            let count = l.split(": ").nth(1).and_then(|r| r.split(' ').next());
            count.and_then(|c| c.parse::<u64>().ok()).expect("a count")
        })
        .sum();
    assert_eq!((passes.len(), variants), (14, 18_908));
    assert!(one.contains("standard/ForwardAdd: 18432 variants"), "{one}");
}
