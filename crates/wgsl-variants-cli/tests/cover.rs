//! `--cover T` on the command line: a 64-keyword synthetic pass (2^64 variants) validated
//! through its pairwise covering set (this test is CI's `validate --cover 2` of it), the
//! failure report of a planted fault, and byte-identical output across thread counts.

use std::path::Path;
use std::process::{Command, Output};

use test_support::shaders;

fn run(root: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("--root")
        .arg(root)
        .args(["--color", "never"])
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

fn write(files: Vec<(String, String)>) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in files {
        let p = dir.path().join(path);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    dir
}

#[test]
fn validate_cover_2_of_64_keywords() {
    let dir = write(shaders::keyword_shader(64, true));
    let out = run(dir.path(), &["validate", "--cover", "2", "--no-cache"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains(
            "synth/P: covering t=2: 10 variants cover every 2-way combination of keyword options of a 18446744073709551616-variant space (region-aware: 8)"
        ),
        "{stdout}"
    );
    assert!(stdout.contains("10 variants built"), "{stdout}");
}

#[test]
fn a_planted_pair_is_reported_and_shrunk() {
    let dir = write(shaders::planted_fault_shader(64, &[(3, true), (17, true)]));
    let mut outputs = Vec::new();
    for threads in ["1", "2"] {
        let out = run(
            dir.path(),
            &[
                "--threads",
                threads,
                "validate",
                "--cover",
                "2",
                "--no-cache",
            ],
        );
        assert_eq!(out.status.code(), Some(1));
        outputs.push(out.stdout);
    }
    assert_eq!(
        outputs[0], outputs[1],
        "output differs across thread counts"
    );
    let stdout = String::from_utf8_lossy(&outputs[0]);
    assert!(stdout.contains("failing variant #"), "{stdout}");
    assert!(stdout.contains("first to cover"), "{stdout}");
    assert!(
        stdout.contains("smallest failing keyword subset: {K3, K17}"),
        "{stdout}"
    );
}

#[test]
fn bad_strength_is_an_error_naming_the_pass() {
    let dir = write(shaders::keyword_shader(8, false));
    let out = run(dir.path(), &["validate", "--cover", "0"]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("synth/P: covering strength t = 0"),
        "{stderr}"
    );
    let out = run(dir.path(), &["validate", "--cover", "5"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("past the supported 4"));
}

/// CI's `validate --cover 2` of URP's `UniversalGBuffer` (16 keyword sets, 49,152 variants),
/// and `--cover-above`: the built-in passes whole, only the huge pass covered.
#[test]
fn validate_cover_2_of_the_urp_pass_and_cover_above() {
    let bundled = |args: &[&str]| -> String {
        let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args(["--color", "never"])
            .args(args)
            .output()
            .expect("run wgsl-variants");
        let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "{args:?}: {stdout}\n{}",
            String::from_utf8_lossy(&out.stderr)
        );
        stdout
    };
    let urp = bundled(&[
        "validate",
        "--cover",
        "2",
        "--shader",
        "universal_lit",
        "--no-cache",
    ]);
    assert!(
        urp.contains("universal_lit/UniversalGBuffer: covering t=2: 10 variants cover every 2-way combination of keyword options of a 49152-variant space"),
        "{urp}"
    );
    assert!(urp.contains("10 valid, 0 invalid"), "{urp}");

    let mixed = bundled(&[
        "validate",
        "--cover",
        "2",
        "--cover-above",
        "8192",
        "--no-cache",
    ]);
    assert!(
        mixed.contains(
            "deferred_shading/Lighting: built whole: its 384-variant space is at most --cover-above"
        ),
        "{mixed}"
    );
    assert!(
        mixed.contains("deferred_shading/Lighting: 384 built (384 full space)"),
        "{mixed}"
    );
    assert!(
        mixed.contains("standard/Deferred: covering t=2:"),
        "{mixed}"
    );
    assert!(
        mixed.contains("universal_lit/UniversalGBuffer: 10 built (49152 full space)"),
        "{mixed}"
    );
    // --cover-above means nothing without --cover.
    let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["validate", "--cover-above", "10"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}
