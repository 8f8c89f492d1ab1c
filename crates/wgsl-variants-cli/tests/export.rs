//! `wgsl-variants export`: the command line over `emit::export` and `emit::naga_oil`.

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
