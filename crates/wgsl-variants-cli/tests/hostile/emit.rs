//! Case 2: `emit --out` never overwrites one output with another, and its manifest always
//! describes exactly the files beside it.

use super::{assert_clean_exit, run_on};

#[test]
fn colliding_output_paths_are_refused_and_nothing_is_written() {
    let tree = tempfile::tempdir().unwrap();
    for (file, name) in [("ab.wgsl", "a/b"), ("a_b.wgsl", "a-b")] {
        std::fs::write(
            tree.path().join(file),
            format!(
                "#shader {name}\n#pass P\n#pragma multi_compile _ X\n\
                 @fragment fn fs() -> @location(0) vec4f {{ return vec4f(1.0); }}\n#endpass\n"
            ),
        )
        .unwrap();
    }
    let out_dir = tempfile::tempdir().unwrap();
    let out = out_dir.path().join("out");
    let run = run_on(
        tree.path(),
        &["emit", "--all", "--out", out.to_str().unwrap()],
    );
    assert_clean_exit(&run, 1);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("would be written for both a-b/P {} and a/b/P {}")
            || stderr.contains("would be written for both a/b/P {} and a-b/P {}"),
        "{stderr}"
    );
    assert!(!out.join("manifest.json").exists(), "nothing written");
}

/// Every file in the folder (but the manifest) is listed with its hash, and every listed file
/// is there.
fn assert_manifest_describes_folder(dir: &std::path::Path) {
    let manifest: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("manifest.json")).unwrap()).unwrap();
    let mut listed = std::collections::BTreeMap::new();
    for v in manifest["variants"].as_array().unwrap() {
        for f in v["files"].as_array().unwrap() {
            listed.insert(
                f["file"].as_str().unwrap().to_string(),
                f["blake3"].as_str().unwrap().to_string(),
            );
        }
    }
    let mut found = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.file_name().unwrap() != "manifest.json" {
                let rel = p.strip_prefix(dir).unwrap().to_str().unwrap().to_string();
                let hash = blake3::hash(&std::fs::read(&p).unwrap())
                    .to_hex()
                    .to_string();
                found.insert(rel, hash);
            }
        }
    }
    assert_eq!(
        listed, found,
        "the manifest describes exactly the files beside it"
    );
}

#[test]
fn a_second_emit_into_a_used_folder_leaves_a_true_manifest() {
    let tree = tempfile::tempdir().unwrap();
    let shader = |sets: &str| {
        format!(
            "#shader s\n#pass P\n{sets}\
             @fragment fn fs() -> @location(0) vec4f {{\n#ifdef A\n    return vec4f(0.5);\n#endif\n    return vec4f(1.0);\n}}\n#endpass\n"
        )
    };
    std::fs::write(
        tree.path().join("s.wgsl"),
        shader("#pragma multi_compile _ A\n#pragma multi_compile _ B\n"),
    )
    .unwrap();
    let out_dir = tempfile::tempdir().unwrap();
    let out = out_dir.path().to_str().unwrap();
    let first = run_on(tree.path(), &["emit", "--all", "--out", out]);
    assert_clean_exit(&first, 0);
    assert_manifest_describes_folder(out_dir.path());

    // Fewer variants now: the files of the old ones must not linger, described by nothing.
    std::fs::write(
        tree.path().join("s.wgsl"),
        shader("#pragma multi_compile _ A\n"),
    )
    .unwrap();
    let second = run_on(tree.path(), &["emit", "--all", "--out", out]);
    assert_clean_exit(&second, 0);
    assert_manifest_describes_folder(out_dir.path());

    // A failing emit (an invalid variant) writes nothing: the manifest still matches.
    std::fs::write(
        tree.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ A\n\
         @fragment fn fs() -> @location(0) vec4f {\n#ifdef A\n    return 1.0;\n#endif\n    return vec4f(1.0);\n}\n#endpass\n",
    )
    .unwrap();
    let failed = run_on(tree.path(), &["emit", "--all", "--out", out]);
    assert_clean_exit(&failed, 1);
    assert_manifest_describes_folder(out_dir.path());
}
