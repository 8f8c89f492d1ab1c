//! Case 6: a closed pipe (`| head -1`) ends the process quietly, as it ends `cat`: no panic,
//! no backtrace, exit 101 never.

use std::process::Stdio;

#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let tree = tempfile::tempdir().unwrap();
    std::fs::write(
        tree.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ A B C\n#pragma multi_compile _ D\n\
         @fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }\n#endpass\n",
    )
    .unwrap();
    for args in [
        &["list"][..],
        &["manifest"][..],
        &["audit", "--json"][..],
        &["export", "--all", "--dialect", "wesl"][..],
        &["validate", "--all", "--json"][..],
    ] {
        let mut cmd = super::bin();
        let mut child = cmd
            .arg("--root")
            .arg(tree.path())
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The reader goes away at once, as `head -c10` does after its bytes.
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert_ne!(out.status.code(), Some(101), "{args:?}: {stderr}");
        assert!(
            out.status.success() || out.status.signal() == Some(13),
            "{args:?} ends by SIGPIPE or success: {:?}",
            out.status
        );
    }
}
