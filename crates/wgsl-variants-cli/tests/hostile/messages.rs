//! Case 11: messages say what is wrong with what the user wrote.

use super::{assert_clean_exit, run_on};

fn declared(dir: &std::path::Path, toml: &str) {
    std::fs::write(dir.join("wgsl-variants.toml"), toml).unwrap();
    std::fs::write(
        dir.join("lit.wgsl"),
        "@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0); }\n",
    )
    .unwrap();
}

#[test]
fn two_shader_entries_of_one_name_are_not_called_two_files() {
    let tree = tempfile::tempdir().unwrap();
    declared(
        tree.path(),
        "[[shader]]\nname = \"lit\"\nentry = \"lit.wgsl\"\n[[shader.pass]]\nname = \"P\"\n\
         [[shader]]\nname = \"lit\"\nentry = \"lit.wgsl\"\n[[shader.pass]]\nname = \"Q\"\n",
    );
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("shader `lit` is declared twice"),
        "{stderr}"
    );
    assert!(!stderr.contains("two files"), "{stderr}");
}

#[test]
fn a_declaration_file_that_is_not_utf8_is_not_called_a_wgsl_source() {
    let tree = tempfile::tempdir().unwrap();
    declared(tree.path(), "");
    std::fs::write(
        tree.path().join("wgsl-variants.toml"),
        b"[[shader]]\nname = \"l\xffit\"\n",
    )
    .unwrap();
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("a declaration file must be UTF-8"),
        "{stderr}"
    );
    assert!(!stderr.contains("WGSL sources"), "{stderr}");
}

#[test]
fn exclude_patterns_are_refused_and_unmatched_paths_warned() {
    for (pattern, why) in [
        ("*", "is a glob pattern"),
        ("common/**", "is a glob pattern"),
        ("", "is empty"),
        ("../x", "is not a plain relative path"),
    ] {
        let tree = tempfile::tempdir().unwrap();
        declared(
            tree.path(),
            &format!(
                "exclude = [\"{pattern}\"]\n[[shader]]\nname = \"lit\"\nentry = \"lit.wgsl\"\n[[shader.pass]]\nname = \"P\"\n"
            ),
        );
        let out = run_on(tree.path(), &["list"]);
        assert_clean_exit(&out, 1);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains(&format!("exclude entry `{pattern}` {why}")),
            "{pattern}: {stderr}"
        );
    }
    let tree = tempfile::tempdir().unwrap();
    declared(
        tree.path(),
        "exclude = [\"meshlet\"]\n[[shader]]\nname = \"lit\"\nentry = \"lit.wgsl\"\n[[shader.pass]]\nname = \"P\"\n",
    );
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("exclude entry `meshlet` matches no file or folder of the tree"),
        "{stderr}"
    );
}

#[test]
fn a_name_too_long_for_a_file_names_itself_not_the_folder() {
    let tree = tempfile::tempdir().unwrap();
    let name = "s".repeat(300);
    std::fs::write(
        tree.path().join("s.wgsl"),
        format!(
            "#shader {name}\n#pass P\n@fragment fn fs() -> @location(0) vec4f {{ return vec4f(1.0); }}\n#endpass\n"
        ),
    )
    .unwrap();
    let out_dir = tempfile::tempdir().unwrap();
    let out = run_on(
        tree.path(),
        &["emit", "--all", "--out", out_dir.path().to_str().unwrap()],
    );
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("(300 bytes) would be a file or folder name of")
            && stderr.contains("shorten the shader, pass or entry point name"),
        "{stderr}"
    );
}

/// naga's parser gives up past 200 levels of nesting with "internal WGSL front end error",
/// no location, and the reason in a note: the reason is part of the message.
#[test]
fn a_parser_recursion_limit_is_named_in_the_message() {
    let tree = tempfile::tempdir().unwrap();
    let deep = format!("{}1.0{}", "(".repeat(250), ")".repeat(250));
    std::fs::write(
        tree.path().join("s.wgsl"),
        format!(
            "#shader s\n#pass P\n@fragment fn fs() -> @location(0) vec4f {{ return vec4f({deep}); }}\n#endpass\n"
        ),
    )
    .unwrap();
    let out = run_on(tree.path(), &["--json", "validate", "--all"]);
    assert_clean_exit(&out, 1);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let message = report["passes"][0]["failures"][0]["message"]
        .as_str()
        .unwrap();
    assert!(
        message.starts_with("internal WGSL front end error: Parser recursion limit exceeded")
            && message.contains("at most 200 levels deep"),
        "{message}"
    );
}
