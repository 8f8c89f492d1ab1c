//! `wgsl-variants reflect`: the JSON is the library's reflection, the text names bindings, and
//! a mistyped keyword is a clear error.

use serde_json::Value;
use std::process::Command;

#[test]
fn reflect_command_line() {
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args(args)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8(out.stdout).unwrap()
    };
    let json: Value = serde_json::from_str(&run(&[
        "reflect",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAP,UNITY_HDR_ON",
        "--json",
    ]))
    .unwrap();
    let lib = wgsl_variants_shaders::library().unwrap();
    let v = lib
        .variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"])
        .unwrap();
    assert_eq!(
        json,
        serde_json::to_value(lib.reflect(&v).unwrap()).unwrap()
    );
    let text = run(&[
        "reflect",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAP",
    ]);
    assert!(
        text.starts_with(
            "standard/Deferred {_NORMAL_MAP}\nentry points: vs_main (vertex), fs_main (fragment)\n"
        ),
        "{text}"
    );
    assert!(text.contains("binding 4   normal_map"), "{text}");
    assert!(text.contains("texture 2d float"), "{text}");

    let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args([
            "reflect",
            "standard",
            "Deferred",
            "--keywords",
            "_NORMAL_MAPP",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("_NORMAL_MAP"));
}
