//! Case 4: deep nesting in a WESL module is refused at the limit, never a stack overflow
//! (which aborts the process, whatever the thread count).

use super::{assert_clean_exit, run_on};

fn wesl_tree(dir: &std::path::Path, depth: usize) {
    std::fs::write(
        dir.join("wgsl-variants.toml"),
        "dialect = \"wesl\"\n[[shader]]\nname = \"s\"\nentry = \"s.wesl\"\n\
         [[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"A\"]]\n",
    )
    .unwrap();
    let deep = format!("{}1.0{}", "(".repeat(depth), ")".repeat(depth));
    std::fs::write(
        dir.join("s.wesl"),
        format!(
            "fn unused() -> f32 {{ return {deep}; }}\n\
             @fragment fn fs() -> @location(0) vec4f {{\n    @if(A) {{ return vec4f(0.5); }}\n    return vec4f(1.0);\n}}\n"
        ),
    )
    .unwrap();
}

#[test]
fn deep_parentheses_in_a_wesl_module_are_refused_not_a_crash() {
    for depth in [5_000, 100_000] {
        let tree = tempfile::tempdir().unwrap();
        wesl_tree(tree.path(), depth);
        for args in [
            &["validate", "--all"][..],
            &["--threads", "1", "manifest"][..],
            &["list"][..],
            &["audit"][..],
        ] {
            let out = run_on(tree.path(), args);
            assert_clean_exit(&out, 1);
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(
                stderr.contains("nested deeper than the limit of 256")
                    && stderr.contains("s.wesl:1:"),
                "{args:?} at depth {depth}: {stderr}"
            );
        }
    }
}

#[test]
fn nesting_under_the_limit_still_loads() {
    let tree = tempfile::tempdir().unwrap();
    wesl_tree(tree.path(), 100);
    let out = run_on(tree.path(), &["validate", "--all"]);
    assert_clean_exit(&out, 0);
}
