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

/// `check-gpu --cover 2` renders the pairwise covering sets of the standard passes (10 of
/// Deferred's 3072 variants, 12 of ForwardBase's 1536) and compares them with the reference.
#[test]
fn check_gpu_cover_renders_the_covering_sets() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(["check-gpu", "--cover", "2", "--shader", "standard"])
        .env("NODEVICE_SELECT", "1")
        .output()
        .expect("run check-gpu");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("ok   standard/Deferred: 10 variants"),
        "{stdout}"
    );
    assert!(
        stdout.contains("ok   standard/ForwardBase: 12 variants"),
        "{stdout}"
    );
    assert!(stdout.contains("2-wise covering set"), "{stdout}");
}
