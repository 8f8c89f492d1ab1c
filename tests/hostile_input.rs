//! Hostile and extreme input: each gives a clear diagnostic or works, never a panic, a hang or
//! unbounded memory. Large inputs are generated here rather than stored in the repository.

use wgsl_variants::{Library, LoadOptions};

fn load(sources: Vec<(String, String)>) -> Result<Library, wgsl_variants::LoadError> {
    Library::from_sources(sources)
}

fn shader(body: &str) -> (String, String) {
    (
        "main.wgsl".to_string(),
        format!("#shader s\n#pass P\n{body}\n#endpass\n"),
    )
}

#[test]
fn ten_thousand_deep_if_nesting_is_one_clear_error() {
    let text = "#if A\n".repeat(10_000) + &"#endif\n".repeat(10_000);
    let err = load(vec![("m.wgsl".into(), text)]).unwrap_err();
    assert_eq!(err.problems.len(), 1, "{err}");
    assert_eq!(err.locations(), ["m.wgsl:257:1"]);
    assert!(
        err.diagnostics()[0]
            .message
            .contains("`#if` nested deeper than the limit of 256")
    );
    // The limit is configurable.
    let mut options = LoadOptions::default();
    options.parse.if_depth = 20_000;
    let text = "#if A\n".repeat(10_000) + "fn f() {}\n" + &"#endif\n".repeat(10_000);
    let main = "#shader s\n#pass P\n#pragma multi_compile _ A\n#import m\n#endpass\n";
    let lib = Library::from_sources_with(
        [
            ("m.wgsl".to_string(), text),
            ("main.wgsl".to_string(), main.to_string()),
        ],
        &options,
    )
    .unwrap();
    // Composing walks 10,000 levels without recursion (this runs on a small test thread stack).
    let v = lib.variant("s", "P", &["A"]).unwrap();
    assert_eq!(lib.wgsl(&v), "fn f() {}\n");
}

#[test]
fn pathological_expressions_are_bounded() {
    for expr in [
        "(".repeat(5000) + "1" + &")".repeat(5000),
        "!".repeat(100_000) + "A",
        vec!["A"; 50_000].join(" || "),
        vec!["-"; 1000].join("") + "1",
    ] {
        let text = format!("#if {expr}\n#endif\n");
        let err = load(vec![("m.wgsl".into(), text)]).unwrap_err();
        assert!(
            err.diagnostics()[0]
                .message
                .contains("nested deeper than the limit"),
            "{}",
            err.diagnostics()[0].message
        );
        assert_eq!(err.locations()[0].split(':').nth(1), Some("1"));
    }
    let overflow = "#if 99999999999999999999\n#endif\n";
    let err = load(vec![("m.wgsl".into(), overflow.into())]).unwrap_err();
    assert_eq!(err.locations(), ["m.wgsl:1:5"]);
}

#[test]
fn long_lines_and_large_modules_work() {
    let long_line = format!(
        "const LONG: array<f32, 30000> = array<f32, 30000>({});",
        vec!["1.0"; 30_000].join(", ")
    );
    assert!(long_line.len() > 100_000);
    let big_module: String = (0..20_000)
        .map(|i| format!("fn big_{i}() -> f32 {{ return {i}.0; }} // padding padding\n"))
        .collect();
    assert!(big_module.len() > 1_000_000);
    let main =
        "#shader s\n#pass P\n#pragma multi_compile _ A\n#import long\n#import big\n#endpass\n";
    let lib = load(vec![
        ("long.wgsl".into(), long_line),
        ("big.wgsl".into(), big_module),
        ("main.wgsl".into(), main.into()),
    ])
    .unwrap();
    let v = lib.variant("s", "P", &["A"]).unwrap();
    if let Err(e) = lib.naga_module(&v) {
        panic!("{}", e.diagnostic().render(lib.files(), false));
    }
}

#[test]
fn ten_thousand_modules_load_and_a_long_import_chain_is_limited() {
    let mut sources: Vec<(String, String)> = (0..10_000)
        .map(|i| (format!("m/{i:05}.wgsl"), format!("fn f{i}() {{}}\n")))
        .collect();
    let imports: String = (0..10_000).map(|i| format!("#import m/{i:05}\n")).collect();
    sources.push(shader(&imports));
    let lib = load(sources).unwrap();
    let v = lib.variant("s", "P", &[] as &[&str]).unwrap();
    assert!(lib.naga_module(&v).is_ok());
    // A chain of 100 modules each importing the next passes the default depth limit of 64.
    let mut chain: Vec<(String, String)> = (0..100)
        .map(|i| (format!("c{i}.wgsl"), format!("#import c{}\n", i + 1)))
        .collect();
    chain.push(("c100.wgsl".into(), "fn end() {}\n".into()));
    let err = load(chain).unwrap_err();
    assert!(
        err.diagnostics()[0]
            .message
            .contains("import chain deeper than the limit of 64"),
        "{err}"
    );
}

#[test]
fn keyword_names_that_are_wgsl_identifiers_do_not_touch_the_code() {
    // Keywords never substitute text, so a keyword named like a WGSL type or builtin is safe.
    let body = "#pragma multi_compile _ vec4f\n#pragma shader_feature max\nfn f() -> vec4f {\n#if vec4f && max\n    return vec4f(max(1.0, 2.0));\n#else\n    return vec4f(0.0);\n#endif\n}";
    let lib = load(vec![shader(body)]).unwrap();
    for keywords in [vec![], vec!["vec4f"], vec!["vec4f", "max"]] {
        let v = lib.variant("s", "P", &keywords).unwrap();
        assert!(lib.naga_module(&v).is_ok(), "{keywords:?}");
    }
}

#[test]
fn hash_signs_inside_comments_are_not_directives() {
    let body = "// #import nowhere\n/* #if A\n  #else\n*/\nfn f() {} // trailing #endif";
    let lib = load(vec![shader(body)]).unwrap();
    let v = lib.variant("s", "P", &[] as &[&str]).unwrap();
    assert!(lib.compose(&v).text.contains("// #import nowhere"));
    // The lean text (for hashing, validation and `wgsl()`) drops comment-only lines.
    assert!(!lib.wgsl(&v).contains("// #import nowhere") && lib.wgsl(&v).contains("fn f() {}"));
}

#[test]
fn every_limit_is_configurable_with_a_clear_error() {
    let mut options = LoadOptions::default();
    options.max_total_bytes = 100;
    let err = Library::from_sources_with([("m.wgsl", "x".repeat(200))], &options).unwrap_err();
    assert!(err.to_string().contains("past the limit of 100"), "{err}");
    let dir = tempfile::tempdir().unwrap();
    for i in 0..5 {
        std::fs::write(dir.path().join(format!("{i}.wgsl")), "").unwrap();
    }
    let mut options = LoadOptions::default();
    options.max_files = 3;
    let err = Library::from_dir_with(dir.path(), &options).unwrap_err();
    assert!(err.to_string().contains("more than 3 .wgsl files"), "{err}");
    let mut options = LoadOptions::default();
    options.parse.expr_depth = 2;
    let err =
        Library::from_sources_with([("m.wgsl", "#if (((A)))\n#endif\n")], &options).unwrap_err();
    assert!(err.to_string().contains("limit of 2"), "{err}");
}
