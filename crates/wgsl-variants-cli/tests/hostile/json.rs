//! Case 10: under `--json`, a failing command still prints one JSON object on stdout (what a
//! `validate --json > shard.json` keeps), with the error's kind, message and locations.

use serde_json::Value;

use super::{assert_clean_exit, run_on};

#[test]
fn a_load_error_under_json_is_a_json_error_object() {
    let tree = tempfile::tempdir().unwrap();
    std::fs::write(tree.path().join("a.wgsl"), "#import missing\n").unwrap();
    for command in [
        &["list"][..],
        &["validate", "--all"][..],
        &["audit"][..],
        &["manifest"][..],
        &["reflect", "s", "P"][..],
    ] {
        let mut args = vec!["--json"];
        args.extend_from_slice(command);
        let out = run_on(tree.path(), &args);
        assert_clean_exit(&out, 1);
        let value: Value = serde_json::from_slice(&out.stdout)
            .unwrap_or_else(|e| panic!("{command:?}: stdout is not JSON ({e}): {:?}", out.stdout));
        assert_eq!(value["ok"], false);
        assert_eq!(value["error"]["kind"], "load", "{value}");
        assert_eq!(
            value["error"]["problems"][0]["location"], "a.wgsl:1:9",
            "{value}"
        );
    }
}

#[test]
fn a_command_error_under_json_is_a_json_error_object() {
    let tree = tempfile::tempdir().unwrap();
    std::fs::write(
        tree.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile A B C D\n#pragma multi_compile E F G H\n\
         @fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }\n#endpass\n",
    )
    .unwrap();
    let out = run_on(
        tree.path(),
        &["--json", "validate", "--all", "--max-variants", "3"],
    );
    assert_clean_exit(&out, 1);
    let value: Value = serde_json::from_slice(&out.stdout).expect("stdout is JSON");
    assert_eq!(value["ok"], false);
    assert_eq!(value["error"]["kind"], "command");
    let message = value["error"]["message"].as_str().unwrap();
    assert!(message.contains('3'), "{message}");
}
