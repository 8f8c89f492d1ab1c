//! The variant-explosion audit: counts checked against hand-computed numbers (bundled library,
//! a fixture made to have dead and coupled keywords, synthetic 40- and 64-keyword shaders),
//! and the analytic distinct count cross-checked against enumeration on random libraries.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use test_support::shaders as synthetic;

// ---------------------------------------------------------------------------------------------
// The fixture: dead keywords, keywords that matter only together, identical code.
fn fixture() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tests/fixtures/audit")
}

// ---------------------------------------------------------------------------------------------
// The command line: JSON, table, budgets, chart.
fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

fn json_of(out: &Output) -> serde_json::Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| {
        panic!(
            "stdout is not JSON: {e}\n{}\n{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        )
    })
}

fn pass_json<'a>(v: &'a serde_json::Value, shader: &str, pass: &str) -> &'a serde_json::Value {
    v["passes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["shader"] == shader && p["pass"] == pass)
        .unwrap()
}

#[test]
fn cli_json_has_the_required_fields() {
    let out = run(&["audit", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v = json_of(&out);
    let d = pass_json(&v, "standard", "Deferred");
    for key in ["full_space", "after_filtering", "build_set", "distinct"] {
        assert_eq!(d[key], 110_592, "{key}");
    }
    assert_eq!(d["dead_keywords"], serde_json::json!([]));
    assert_eq!(d["distinct_exact"], true);
    assert_eq!(d["sets"].as_array().unwrap().len(), 16);
    // Every pass of the bundled library is audited.
    let passes = wgsl_variants_shaders::library().unwrap().passes().count();
    assert!(passes >= 11);
    assert_eq!(v["totals"]["passes"], passes);
    assert_eq!(v["ok"], true);
}

#[test]
fn cli_fixture_json_table_and_budget_gate() {
    let root = fixture().join("lib");
    let root = root.to_str().unwrap();
    let out = run(&["--root", root, "audit", "--json"]);
    assert!(out.status.success());
    let v = json_of(&out);
    let main = pass_json(&v, "fx", "Main");
    assert_eq!(main["full_space"], 288);
    assert_eq!(main["after_filtering"], 192);
    assert_eq!(main["build_set"], 192);
    assert_eq!(main["distinct"], 16);
    assert_eq!(main["distinct_full_space"], 24);
    assert_eq!(
        main["dead_keywords"],
        serde_json::json!(["UNUSED_DEBUG", "NOOP_FLAG", "QUALITY_MED"])
    );
    // The table for people.
    let out = run(&["--root", root, "audit"]);
    let table = String::from_utf8(out.stdout).unwrap();
    assert!(
        table.contains("fx/Main") && table.contains("x1 (dead)"),
        "{table}"
    );
    assert!(
        table.contains("RIM changes code only together with RIM_SOFT"),
        "{table}"
    );
    // The budget file: fx/Main's 192 variants are over its budget of 100.
    let budget = fixture().join("budget.toml");
    let budget = budget.to_str().unwrap();
    let out = run(&["--root", root, "audit", "--budget", budget]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("fx/Main: build set of 192 variants exceeds its budget of 100")
            && stderr.contains("\"fx/Main\""),
        "{stderr}"
    );
    assert!(!stderr.contains("fx/Outline"), "{stderr}");
    // With the materials the build set is 48: within budget.
    let materials = fixture().join("materials.toml");
    let out = run(&[
        "--root",
        root,
        "audit",
        "--json",
        "--budget",
        budget,
        "--materials",
        materials.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v = json_of(&out);
    let main = pass_json(&v, "fx", "Main");
    assert_eq!(
        (main["build_set"].clone(), main["distinct"].clone()),
        (48.into(), 12.into())
    );
    assert_eq!(main["budget"]["limit"], 100);
    assert_eq!(main["budget"]["exceeded"], false);
    // --max-variants is a budget too.
    let out = run(&[
        "--root",
        root,
        "audit",
        "--pass",
        "Outline",
        "--max-variants",
        "3",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("exceeds its budget of 3 (--max-variants)")
    );
}

#[test]
fn cli_budget_file_errors_are_clear() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("b.toml");
    std::fs::write(&bad, "[budgets]\n\"standard/Deferd\" = 10\n").unwrap();
    let out = run(&["audit", "--budget", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("did you mean `standard/Deferred`"),
        "{stderr}"
    );
    std::fs::write(&bad, "[budgets]\n\"standard\" = -1\n").unwrap();
    let out = run(&["audit", "--budget", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("b.toml:2:"));
}

#[test]
fn cli_audits_64_keywords_exactly_and_gates_them() {
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in synthetic::keyword_shader(64, true) {
        let p = dir.path().join(path);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    let out = run(&["--root", dir.path().to_str().unwrap(), "audit", "--json"]);
    // Over the default --max-variants: the report is printed, and the gate fails.
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("\"full_space\": 18446744073709551616"),
        "{text}"
    );
    assert!(text.contains("\"distinct\": 4294967296"), "{text}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "synth/P: build set of 18446744073709551616 variants exceeds its budget of 1000000"
        ),
        "{stderr}"
    );
}

#[test]
fn chart_is_deterministic_and_the_readme_copy_is_current() {
    let dir = tempfile::tempdir().unwrap();
    let one = dir.path().join("a.svg");
    let two = dir.path().join("b.svg");
    for (path, threads) in [(&one, "1"), (&two, "2")] {
        let out = run(&[
            "--threads",
            threads,
            "audit",
            "--shader",
            "standard",
            "--chart",
            path.to_str().unwrap(),
        ]);
        assert!(out.status.success());
    }
    let svg = std::fs::read_to_string(&one).unwrap();
    assert_eq!(svg, std::fs::read_to_string(&two).unwrap());
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("standard/Deferred") && svg.contains("UNITY_HDR_ON"));
    let committed = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("docs/audit.svg");
    assert_eq!(
        std::fs::read_to_string(committed).unwrap_or_default(),
        svg,
        "docs/audit.svg is stale: regenerate it with \
         `cargo run --release -- audit --shader standard --chart docs/audit.svg`"
    );
    let out = run(&[
        "audit",
        "--chart",
        dir.path().join("c.png").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
}
