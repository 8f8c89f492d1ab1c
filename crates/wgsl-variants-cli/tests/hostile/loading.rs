//! Case 5: loading never hangs and never spends memory past its limits: directory loops,
//! FIFOs, devices and huge files named like modules.

use std::time::Duration;

use super::{assert_clean_exit, bin, run_on, run_within};

fn module(dir: &std::path::Path) {
    std::fs::write(
        dir.join("s.wgsl"),
        "#shader s\n#pass P\n@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }\n#endpass\n",
    )
    .unwrap();
}

#[cfg(unix)]
#[test]
fn a_link_to_its_own_folder_does_not_loop() {
    let tree = tempfile::tempdir().unwrap();
    module(tree.path());
    std::fs::create_dir(tree.path().join("sub")).unwrap();
    std::os::unix::fs::symlink("..", tree.path().join("sub/up")).unwrap();
    std::os::unix::fs::symlink(".", tree.path().join("loop")).unwrap();
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("`loop` is a link to a folder already read"),
        "{stderr}"
    );
    assert!(
        stderr.contains("`sub/up` is a link to a folder already read"),
        "{stderr}"
    );
}

#[cfg(unix)]
#[test]
fn a_link_loop_in_a_naga_oil_tree_does_not_grow_memory() {
    let tree = tempfile::tempdir().unwrap();
    std::fs::write(
        tree.path().join("wgsl-variants.toml"),
        "[[shader]]\nname = \"s\"\nentry = \"s.wgsl\"\n[[shader.pass]]\nname = \"P\"\n",
    )
    .unwrap();
    std::fs::write(
        tree.path().join("s.wgsl"),
        "@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }\n",
    )
    .unwrap();
    std::os::unix::fs::symlink(".", tree.path().join("loop")).unwrap();
    let out = run_limited(tree.path(), &["list"]);
    assert_clean_exit(&out, 0);
}

#[cfg(unix)]
#[test]
fn a_fifo_named_like_a_module_is_skipped_not_read() {
    let tree = tempfile::tempdir().unwrap();
    module(tree.path());
    let fifo = tree.path().join("x.wgsl");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(
        made.is_ok_and(|s| s.success()),
        "mkfifo (coreutils) makes the FIFO"
    );
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("`x.wgsl` is a FIFO"), "{stderr}");
}

/// A character device inside the tree needs `mknod`, which only root may run: as anyone
/// else this case says loudly that it did not run.
#[cfg(unix)]
#[test]
fn a_device_named_like_a_module_is_skipped_not_read() {
    let tree = tempfile::tempdir().unwrap();
    module(tree.path());
    let dev = tree.path().join("z.wgsl");
    // /dev/zero is character device 1,5 on Linux.
    let made = std::process::Command::new("mknod")
        .arg(&dev)
        .args(["c", "1", "5"])
        .stderr(std::process::Stdio::null())
        .status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("SKIPPED a_device_named_like_a_module_is_skipped_not_read: mknod needs root");
        return;
    }
    let out = run_limited(tree.path(), &["list"]);
    assert_clean_exit(&out, 0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("`z.wgsl` is a device"), "{stderr}");
}

/// A 2 GiB sparse file is refused from its size, before a byte is read: under a 1.5 GB
/// address-space limit, reading it first would fail.
#[cfg(unix)]
#[test]
fn a_huge_file_is_refused_before_it_is_read() {
    let tree = tempfile::tempdir().unwrap();
    module(tree.path());
    let big = std::fs::File::create(tree.path().join("big.wgsl")).unwrap();
    big.set_len(2 << 30).unwrap();
    let out = run_limited(tree.path(), &["list"]);
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("with `big.wgsl`, past the limit of 268435456"),
        "{stderr}"
    );
}

/// Runs the binary under `ulimit -v` (1.5 GB of address space) and 60 seconds.
#[cfg(unix)]
fn run_limited(root: &std::path::Path, args: &[&str]) -> std::process::Output {
    let cmd = bin();
    let mut sh = std::process::Command::new("sh");
    sh.arg("-c")
        .arg("ulimit -v 1500000 && exec \"$@\"")
        .arg("sh")
        .arg(cmd.get_program())
        .args(cmd.get_args())
        .arg("--root")
        .arg(root)
        .args(args);
    for (k, v) in cmd.get_envs() {
        if let Some(v) = v {
            sh.env(k, v);
        }
    }
    run_within(sh, Duration::from_secs(60))
}
