//! `check-gpu` and `render` on the command line: a bad adapter filter is a clear error.

#[test]
fn check_gpu_with_an_adapter_that_is_not_there_is_a_clear_error() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args([
            "check-gpu",
            "--adapter",
            "no-such-adapter-anywhere",
            "--pass",
            "Final",
        ])
        .output()
        .expect("run check-gpu");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        !stderr.contains("panicked") && stderr.contains("no-such-adapter-anywhere"),
        "{stderr}"
    );
}
