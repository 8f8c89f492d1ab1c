//! The command line on the bundled library: JSON shapes, exit codes, determinism.

use std::process::{Command, Output};

use serde_json::Value;

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: stdout is not one JSON object: {e}"))
}

fn pass<'a>(report: &'a Value, shader: &str, pass: &str) -> &'a Value {
    report["passes"]
        .as_array()
        .expect("passes")
        .iter()
        .find(|p| p["shader"] == shader && p["pass"] == pass)
        .unwrap_or_else(|| panic!("no {shader}/{pass}"))
}

#[test]
fn validate_all_json_covers_the_full_space_of_both_standard_passes() {
    let report = json(&["validate", "--all", "--json"]);
    let deferred = pass(&report, "standard", "Deferred");
    for (key, value) in [
        ("full_space", 3072),
        ("built", 3072),
        ("valid", 3072),
        ("invalid", 0),
    ] {
        assert_eq!(deferred[key], value, "Deferred {key}");
    }
    let forward = pass(&report, "standard", "ForwardBase");
    for (key, value) in [
        ("full_space", 1536),
        ("built", 1536),
        ("valid", 1536),
        ("invalid", 0),
    ] {
        assert_eq!(forward[key], value, "ForwardBase {key}");
    }
    assert_eq!(report["ok"], true);
    assert_eq!(report["totals"]["invalid"], 0);
    let total_built: u64 = report["passes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["built"].as_u64().unwrap())
        .sum();
    assert_eq!(report["totals"]["built"], total_built);
}

#[test]
fn output_is_byte_identical_across_thread_counts() {
    for args in [
        ["validate", "--all", "--json"].as_slice(),
        ["list", "--json"].as_slice(),
        ["audit", "--json"].as_slice(),
    ] {
        let one = run(&[&["--threads", "1"], args].concat());
        let two = run(&[&["--threads", "2"], args].concat());
        let again = run(&[&["--threads", "2"], args].concat());
        assert!(one.status.success());
        assert_eq!(
            one.stdout, two.stdout,
            "{args:?} differs between 1 and 2 threads"
        );
        assert_eq!(two.stdout, again.stdout, "{args:?} differs between runs");
    }
}

#[test]
fn list_reports_tags_sets_and_counts() {
    let list = json(&["list", "--json"]);
    let standard = list["shaders"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "standard")
        .expect("standard");
    let deferred = standard["passes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "Deferred")
        .expect("Deferred");
    assert_eq!(deferred["full_space"], 3072);
    assert_eq!(
        deferred["tags"][0],
        serde_json::json!(["LightMode", "Deferred"])
    );
    assert_eq!(deferred["exclude_renderers"], serde_json::json!(["nomrt"]));
    assert_eq!(deferred["keyword_sets"].as_array().unwrap().len(), 11);
}

#[test]
fn audit_json_has_the_stage_counts() {
    let audit = json(&["audit", "--json"]);
    let deferred = pass(&audit, "standard", "Deferred");
    for key in ["full_space", "after_filtering", "build_set", "distinct"] {
        assert_eq!(deferred[key], 3072, "{key}");
    }
}

#[test]
fn emit_prints_the_variant_and_fails_clearly_on_bad_keywords() {
    let out = run(&[
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAP,UNITY_HDR_ON",
    ]);
    assert!(out.status.success());
    let wgsl = String::from_utf8(out.stdout).unwrap();
    assert!(wgsl.contains("normal_map") && !wgsl.contains("#if"));
    let bad = run(&[
        "--color",
        "never",
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAPP",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(
        stderr.contains("did you mean `_NORMAL_MAP`?") && stderr.contains("┌─ standard.wgsl:"),
        "{stderr}"
    );
    let conflict = run(&[
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_SMOOTHNESS_ALBEDO,_SMOOTHNESS_METALLIC",
    ]);
    assert_eq!(conflict.status.code(), Some(1));
    let missing = run(&["emit", "standard", "NoSuchPass"]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("passes: ForwardBase, Deferred"));
}

#[test]
fn materials_restrict_the_build_set() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("materials.toml");
    std::fs::write(&path, "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAP\", \"_METALLIC_MAP\"]\n").unwrap();
    let report = json(&["validate", "--json", "--materials", path.to_str().unwrap()]);
    // One shader_feature combination × the 4 multi_compile combinations of Deferred.
    assert_eq!(pass(&report, "standard", "Deferred")["built"], 4);
    assert_eq!(pass(&report, "standard", "ForwardBase")["built"], 1);
    std::fs::write(
        &path,
        "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAPP\"]\n",
    )
    .unwrap();
    let bad = run(&["validate", "--materials", path.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("did you mean `_NORMAL_MAP`?"));
}
