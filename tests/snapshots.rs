//! Snapshots of the bundled library's generated WGSL (insta, in `snapshots/` at the repo root):
//! the covering set of every pass as canonical WGSL, and a manifest with a content hash of every
//! variant of the full space. Stale snapshot files (no longer produced) fail the test, as
//! `cargo insta test --unreferenced=reject` would.
//!
//! CI checks the covering snapshots of every pass and the manifest's lines of the passes under
//! 20,000 variants (on one thread and on the default pool); the whole manifest, which compiles
//! every distinct text of the full space (327,248), is [`full_space_manifest`] (ignored:
//! minutes). The main job's figures (`scripts/figures.sh check`) hold the manifest's variant and
//! distinct counts of every pass to the main job's.

use std::collections::BTreeSet;
use std::path::Path;

use wgsl_variants::snapshot::{covering_snapshots, manifest_summary_of};
use wgsl_variants::{Library, Pass, Space};

/// The canonical WGSL of every pass's covering set, as `assert_variant_snapshots!` writes it.
#[test]
fn covering_snapshots_of_every_pass() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let snapshots = covering_snapshots(&lib).unwrap();
    assert!(
        snapshots.len() > lib.passes().count(),
        "{}",
        snapshots.len()
    );
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        for snapshot in snapshots {
            insta::assert_snapshot!(snapshot.name, snapshot.text);
        }
    });
}

/// `assert_variant_snapshots!` over the bundled library: the covering snapshots and the
/// manifest of all 1,020,582 variants. About 6 minutes on 2 cores for 627,366 of them (the
/// fresh-clone CI run of 2026-11-29, when this was CI's form); `universal_lit`'s 835,596 alone
/// took 10.4 minutes (`wgsl-variants manifest --summary --shader universal_lit`, 2026-11-29):
/// `cargo test --release --ignore-rust-version --test snapshots -- --ignored`.
#[test]
#[ignore = "the full space (1020582 variants): cargo test --release --test snapshots -- --ignored"]
fn full_space_manifest() {
    let lib = wgsl_variants_shaders::library().unwrap();
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        wgsl_variants::assert_variant_snapshots!(&lib);
    });
}

/// The macro itself, on a library of two keywords (`tests/fixtures/snapshot_macro/`): four
/// covering snapshots (all off, each keyword alone, all on) and the manifest.
#[test]
fn assert_variant_snapshots_writes_the_covering_set_and_the_manifest() {
    let lib = Library::from_sources([(
        "unlit.wgsl",
        "#shader unlit\n#pass Forward\n#pragma multi_compile _ RED\n#pragma multi_compile _ DETAIL\n\
         @fragment fn fs() -> @location(0) vec4f {\n#if RED\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n\
         #else\n    return vec4f(1.0);\n#endif\n}\n#endpass\n",
    )])
    .unwrap();
    insta::with_settings!({ snapshot_path => "fixtures/snapshot_macro", prepend_module_to_snapshot => false, omit_expression => true }, {
        wgsl_variants::assert_variant_snapshots!(&lib);
    });
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/snapshot_macro");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "manifest.snap",
            "unlit.Forward.DETAIL.snap",
            "unlit.Forward.RED.snap",
            "unlit.Forward.all-off.snap",
            "unlit.Forward.all-on.snap",
        ]
    );
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

/// The committed manifest has one line per pass with the pass's full-space size, so a pass
/// or keyword added without updating it fails here, not only in the full-space test.
#[test]
fn manifest_names_every_pass_with_its_size() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let snap = committed_manifest();
    let lines: Vec<&str> = snap
        .lines()
        .filter(|l| !l.starts_with('#') && l.contains(" variants, "))
        .collect();
    assert_eq!(lines.len(), lib.passes().count(), "{snap}");
    for pass in lib.passes() {
        let head = format!(
            "{}/{}: {} variants, ",
            pass.shader,
            pass.name,
            Space::full(pass).count()
        );
        assert!(
            lines.iter().any(|l| l.starts_with(&head)),
            "no `{head}` in snapshots/manifest.snap (review it: cargo test --release --test \
             snapshots -- --ignored, then cargo insta review)"
        );
    }
}

/// The canonical output on one thread and on the default pool (one thread per core) equals
/// the committed manifest snapshot, so the output does not depend on the thread count. On
/// every bundled pass under 20,000 variants (the largest, `standard/ForwardAdd`, 18,432): each
/// is split between threads the same way as a larger one, and the four larger passes (49,152
/// to 786,432 variants) compile 473,344 distinct texts, the full-space test's work.
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
    let pool = manifest_summary_of(&lib, &small, 1_000_000).unwrap();
    assert_eq!(one, pool, "one thread and the default pool differ");
    let snap = committed_manifest();
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
    assert_eq!((passes.len(), variants), (15, 19_110));
    assert!(one.contains("standard/ForwardAdd: 18432 variants"), "{one}");
}

/// `snapshots/manifest.snap` as committed.
fn committed_manifest() -> String {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("snapshots/manifest.snap");
    std::fs::read_to_string(&file).expect("snapshots/manifest.snap")
}
