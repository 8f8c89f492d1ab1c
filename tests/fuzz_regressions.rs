//! Replays the fuzz seeds and every input the fuzzers ever found (`fuzz/regressions/<target>/`)
//! through the same checks the fuzz targets run (`crates/fuzz-checks`).

use wgsl_variants_fuzz_checks as checks;

use std::path::Path;

fn inputs(kind: &str, target: &str) -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz")
        .join(kind)
        .join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(Result::ok).map(|e| e.path()).collect())
        .unwrap_or_default();
    files.sort();
    files
        .into_iter()
        .filter(|p| {
            p.is_file()
                && !p
                    .file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with("."))
        })
        .map(|p| std::fs::read(p).expect("read input"))
        .collect()
}

/// A fuzz target: its name and its check.
type Target = (&'static str, fn(&[u8]));

#[test]
fn fuzz_seeds_and_regressions_replay_cleanly() {
    let targets: [Target; 10] = [
        ("preprocess", checks::preprocess),
        ("expr", checks::expr),
        ("pragmas", checks::pragmas),
        ("loader", checks::loader),
        ("lean", checks::lean),
        ("naga_oil", checks::naga_oil),
        ("wesl", checks::wesl),
        ("declaration", checks::declaration),
        ("merge", checks::merge),
        ("cache", checks::cache),
    ];
    let mut total = 0;
    for (name, check) in targets {
        let mut seeds = inputs("initial", name);
        if name == "preprocess" || name == "lean" {
            // The bundled modules are seeds too, as scripts/fuzz.sh gives them to the fuzzer.
            let lib = wgsl_variants_shaders::library().expect("bundled library");
            let modules = (0..lib.module_paths().len())
                .filter(|&i| !lib.shaders().iter().any(|s| s.file == i));
            seeds.extend(modules.map(|i| lib.files().text(i).as_bytes().to_vec()));
        }
        assert!(!seeds.is_empty(), "no seeds for {name}");
        let regressions = inputs("regressions", name);
        for input in seeds.iter().chain(&regressions) {
            check(input);
        }
        println!(
            "fuzz {name}: {} seeds, {} regression inputs replayed",
            seeds.len(),
            regressions.len()
        );
        total += seeds.len() + regressions.len();
    }
    assert!(total > 0);
}
