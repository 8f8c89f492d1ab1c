//! `wgsl-variants export`: the command line over `emit::export`, `emit::naga_oil` and
//! `emit::wesl`.

use std::process::Command;

// ---------------------------------------------------------------- command line

fn cli(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

#[test]
fn export_command_line() {
    let out = cli(&[
        "export",
        "deferred/gbuffer",
        "--prefix",
        "wv_",
        "--keywords",
        "UNITY_HDR_ON",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.contains("fn wv_gbuffer_pack("));
    let module = naga::front::wgsl::parse_str(&text).expect("the export parses");
    wgsl_variants::validate::validator()
        .validate(&module)
        .expect("the export validates");

    let dir = tempfile::tempdir().unwrap();
    let out = cli(&[
        "export",
        "standard/my_lighting",
        "--dialect",
        "naga-oil",
        "--prefix",
        "wv",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for module in ["standard/my_lighting", "standard/surface", "deferred/ldr"] {
        let text = std::fs::read_to_string(dir.path().join(format!("{module}.wgsl"))).unwrap();
        assert!(text.contains(&format!(
            "#define_import_path wv::{}",
            module.replace('/', "::")
        )));
    }

    for (args, message) in [
        (vec!["export", "deferred/gbuffer"], "needs --prefix"),
        (
            vec!["export", "standard", "--prefix", "p_"],
            "is a shader file",
        ),
        (
            vec!["export", "deferred/ldr", "--prefix", "9"],
            "is not the start of a WGSL identifier",
        ),
        (
            vec![
                "export",
                "deferred/gbuffer",
                "--dialect",
                "naga-oil",
                "--keywords",
                "UNITY_HDR_ON",
            ],
            "shader defs",
        ),
    ] {
        let out = cli(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}

/// `--dialect wesl --all --out DIR`: every module as `PATH.wesl`, each pass's root (the pass
/// body as a module when it has code of its own), and a line per pass saying what to compile.
#[test]
fn export_wesl_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let out = cli(&[
        "export",
        "--dialect",
        "wesl",
        "--all",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains("standard/Deferred: compile package::standard::my_lighting with features: the variant's keywords + DEFERRED_PASS"),
        "{stdout}"
    );
    assert!(stdout.contains(
        "deferred_shading/Lighting: compile package::internal::deferred_shading::Lighting"
    ));
    let gbuffer = std::fs::read_to_string(dir.path().join("deferred/gbuffer.wesl")).unwrap();
    assert!(
        gbuffer.contains("import package::deferred::ldr::{ldr_encode};"),
        "{gbuffer}"
    );
    assert!(gbuffer.contains("@if(UNITY_HDR_ON)"), "{gbuffer}");
    let lighting =
        std::fs::read_to_string(dir.path().join("internal/deferred_shading/Lighting.wesl"))
            .unwrap();
    assert!(lighting.contains("fn fs_main"), "{lighting}");

    // One module on stdout; its imports are named on stderr.
    let out = cli(&["export", "deferred/gbuffer", "--dialect", "wesl"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("@if(UNITY_HDR_ON)"));
    assert!(String::from_utf8_lossy(&out.stderr).contains("it imports deferred/ldr"));

    let out = cli(&[
        "export",
        "deferred/gbuffer",
        "--dialect",
        "wesl",
        "--keywords",
        "UNITY_HDR_ON",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("WESL features"));
}
