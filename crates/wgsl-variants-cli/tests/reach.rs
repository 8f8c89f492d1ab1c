//! Reachability on the command line: a helper no entry point calls is left out of the emitted
//! program, listed by the audit, and validated (and reported where it is written) with
//! `validate --strict`.

use std::path::Path;
use std::process::{Command, Output};

fn run(root: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("--root")
        .arg(root)
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

/// A tree whose module `m` has a helper that nothing calls, broken on line 4.
fn tree() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.wgsl"),
        "fn used() -> f32 { return 1.0; }\n\
         \n\
         fn broken() -> f32 {\n    return vec2f(1.0);\n}\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ A\n#import m\n\
         @fragment fn fs() -> @location(0) vec4f {\n\
         #ifdef A\n    return vec4f(used());\n#else\n    return vec4f(0.0);\n#endif\n}\n\
         #endpass\n",
    )
    .unwrap();
    dir
}

#[test]
fn an_unreached_broken_helper_is_left_out_listed_and_caught_by_strict() {
    let dir = tree();
    let root = dir.path();

    // Left out of both programs: they are valid.
    let out = run(root, &["validate", "--all", "--no-cache"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(
        stdout.contains("2 built (2 full space), 2 distinct, 2 valid"),
        "{stdout}"
    );
    let out = run(root, &["emit", "s", "P", "--keywords", "A"]);
    let emitted = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(
        emitted.contains("fn used()") && !emitted.contains("broken"),
        "{emitted}"
    );
    let out = run(root, &["emit", "s", "P"]);
    let emitted = String::from_utf8_lossy(&out.stdout);
    assert!(!emitted.contains("fn used()"), "{emitted}");

    // Listed by the audit, as text and as JSON.
    let out = run(root, &["audit"]);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("unreachable in every variant: m: broken"),
        "{table}"
    );
    let out = run(root, &["audit", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        json["passes"][0]["unreached"],
        serde_json::json!([{"module": "m", "names": ["broken"]}])
    );

    // --strict validates the composed texts too (two: A changes `fs`), each failing in m.wgsl,
    // and the exit is non-zero.
    let out = run(root, &["validate", "--all", "--no-cache", "--strict"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}{stderr}");
    assert!(stderr.contains("m.wgsl:4:12"), "{stderr}");
    assert!(
        stderr.contains("no entry point of this variant reaches"),
        "{stderr}"
    );
    assert!(stdout.contains("0 valid, 2 invalid"), "{stdout}");
    let out = run(
        root,
        &["validate", "--all", "--no-cache", "--strict", "--json"],
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let failures = json["passes"][0]["failures"].as_array().unwrap();
    assert_eq!(failures.len(), 2, "{json}");
    for (f, keywords) in failures
        .iter()
        .zip([serde_json::json!([[]]), serde_json::json!([["A"]])])
    {
        assert_eq!(f["location"], "m.wgsl:4:12");
        assert_eq!(f["keyword_sets"], keywords);
    }
}
