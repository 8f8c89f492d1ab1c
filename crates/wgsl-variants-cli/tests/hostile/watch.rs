//! Case 7: `watch` recovers when its root is deleted or renamed and made again: the tree that
//! does not load is reported, and the one that comes back is validated.

use std::io::{BufRead, BufReader};
use std::process::Stdio;
use std::sync::mpsc::channel;
use std::time::Duration;

const SHADER: &str = "#shader a\n#pass P\n#pragma multi_compile _ RED\n\
    @fragment fn fs() -> @location(0) vec4f {\n#ifdef RED\n    return vec4f(1.0);\n#endif\n    return vec4f(0.5);\n}\n#endpass\n";

#[test]
fn watch_recovers_when_its_root_comes_back() {
    let parent = tempfile::tempdir().unwrap();
    let root = parent.path().join("tree");
    std::fs::create_dir(&root).unwrap();
    std::fs::write(root.join("a.wgsl"), SHADER).unwrap();
    let mut child = super::bin()
        .arg("--root")
        .arg(&root)
        .args(["--json", "watch", "--no-cache", "--debounce", "10"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let stdout = child.stdout.take().unwrap();
    let (send, lines) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines() {
            let Ok(line) = line else { return };
            if send.send(line).is_err() {
                return;
            }
        }
    });
    let until = |what: &str| -> serde_json::Value {
        loop {
            let line = lines
                .recv_timeout(Duration::from_secs(60))
                .unwrap_or_else(|_| panic!("no `{what}` event within 60 s: watch did not recover"));
            let event: serde_json::Value = serde_json::from_str(&line).unwrap();
            if event["event"] == what {
                return event;
            }
        }
    };
    let first = until("verdict");
    assert_eq!(first["report"]["ok"], true, "{first}");

    // Renamed away: the tree no longer loads.
    std::fs::rename(&root, parent.path().join("old")).unwrap();
    until("error");
    // Made again, with an error in it: seen and validated.
    std::fs::create_dir(&root).unwrap();
    std::fs::write(
        root.join("a.wgsl"),
        SHADER.replace("vec4f(1.0)", "vec4f(1.0, ,)"),
    )
    .unwrap();
    let broken = until("verdict");
    assert_eq!(broken["report"]["ok"], false, "{broken}");
    // And edits inside the new folder are watched too.
    std::fs::write(root.join("a.wgsl"), SHADER).unwrap();
    let fixed = until("verdict");
    assert_eq!(fixed["report"]["ok"], true, "{fixed}");
    // Deleted outright, then made again.
    std::fs::remove_dir_all(&root).unwrap();
    until("error");
    std::fs::create_dir(&root).unwrap();
    std::fs::write(root.join("a.wgsl"), SHADER).unwrap();
    let back = until("verdict");
    assert_eq!(back["report"]["ok"], true, "{back}");
    let _ = child.kill();
    let _ = child.wait();
}
