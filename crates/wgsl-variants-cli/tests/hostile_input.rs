//! Hostile and extreme input: each gives a clear diagnostic or works, never a panic, a hang or
//! unbounded memory. Large inputs are generated here rather than stored in the repository.

use std::process::Command;

#[test]
fn the_cli_never_panics_on_hostile_trees() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("deep.wgsl"), "#if A\n".repeat(10_000)).unwrap();
    std::fs::write(dir.path().join("cycle.wgsl"), "#import cycle\n").unwrap();
    std::fs::write(dir.path().join("bin.wgsl"), [0xff, 0xfe, 0x00, 0x41]).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .arg("--root")
        .arg(dir.path())
        .args(["--color", "never", "validate"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"));
    assert!(
        stderr.contains("the library could not be loaded (3 problems)"),
        "{stderr}"
    );
}

#[test]
fn limits_are_configurable_from_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("m.wgsl"),
        "#if A\n".repeat(10) + &"#endif\n".repeat(10),
    )
    .unwrap();
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .arg("--root")
            .arg(dir.path())
            .args(extra)
            .args(["--color", "never", "list"])
            .output()
            .unwrap()
    };
    assert!(run(&[]).status.success());
    let out = run(&["--max-if-depth", "5"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("`#if` nested deeper than the limit of 5")
    );
    let out = run(&["--max-source-bytes", "10"]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("past the limit of 10"));
}
