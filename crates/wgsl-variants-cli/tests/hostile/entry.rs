//! Case 3: the entry a declaration names is the file validated, never another with the same
//! stem.

use super::{assert_clean_exit, run_on};

fn naga_oil_tree(dir: &std::path::Path, entry: &str) {
    std::fs::write(
        dir.join("wgsl-variants.toml"),
        format!(
            "dialect = \"naga-oil\"\n[[shader]]\nname = \"lit\"\nentry = \"{entry}\"\n\
             [[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"A\"]]\n"
        ),
    )
    .unwrap();
    std::fs::write(dir.join("lit.wesl"), "this is not WGSL at all {{{").unwrap();
}

#[test]
fn a_wesl_entry_in_a_naga_oil_tree_is_not_replaced_by_the_wgsl_file() {
    let tree = tempfile::tempdir().unwrap();
    naga_oil_tree(tree.path(), "lit.wesl");
    std::fs::write(
        tree.path().join("lit.wgsl"),
        "@fragment fn fs() -> @location(0) vec4f {\n#ifdef A\n    return vec4f(0.5);\n#endif\n    return vec4f(1.0);\n}\n",
    )
    .unwrap();
    let out = run_on(tree.path(), &["validate", "--all"]);
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("entry `lit.wesl` is not a module of the tree")
            && stderr.contains("is `lit.wgsl`"),
        "{stderr}"
    );
}

#[test]
fn a_wesl_entry_alone_in_a_naga_oil_tree_says_why_it_is_not_read() {
    let tree = tempfile::tempdir().unwrap();
    naga_oil_tree(tree.path(), "lit.wesl");
    let out = run_on(tree.path(), &["list"]);
    assert_clean_exit(&out, 1);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("`.wesl` files are modules of WESL trees only"),
        "{stderr}"
    );
}
