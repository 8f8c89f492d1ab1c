//! Directives, nesting and expressions, through the public API on in-memory libraries.

use wgsl_variants::Library;

/// Composes pass `P` of shader `s` (a pass body `body` plus `modules`) with `keywords` on.
fn compose(body: &str, modules: &[(&str, &str)], keywords: &[&str]) -> String {
    let main = format!(
        "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma multi_compile _ B\n#pragma shader_feature _ C1 C2\n{body}\n#endpass\n"
    );
    let mut sources = vec![("main.wgsl".to_string(), main)];
    sources.extend(modules.iter().map(|(p, t)| (p.to_string(), t.to_string())));
    let lib = Library::from_sources(sources).unwrap_or_else(|e| panic!("{e}"));
    let v = lib
        .variant("s", "P", keywords)
        .unwrap_or_else(|e| panic!("{e}"));
    lib.compose(&v).text
}

fn lines(text: &str) -> Vec<&str> {
    text.lines().collect()
}

#[test]
fn if_elif_else_choose_one_branch() {
    let body = "#if A\na\n#elif B\nb\n#else\nnone\n#endif";
    assert_eq!(lines(&compose(body, &[], &["A"])), ["a"]);
    assert_eq!(lines(&compose(body, &[], &["A", "B"])), ["a"]);
    assert_eq!(lines(&compose(body, &[], &["B"])), ["b"]);
    assert_eq!(lines(&compose(body, &[], &[])), ["none"]);
}

#[test]
fn ifdef_and_ifndef() {
    let body = "#ifdef A\nyes\n#endif\n#ifndef A\nno\n#endif";
    assert_eq!(lines(&compose(body, &[], &["A"])), ["yes"]);
    assert_eq!(lines(&compose(body, &[], &[])), ["no"]);
}

#[test]
fn nesting_is_respected() {
    let body = "#if A\n#if B\nab\n#else\na\n#endif\n#elif C1\n#ifdef B\nc1b\n#endif\nc1\n#endif";
    assert_eq!(lines(&compose(body, &[], &["A", "B"])), ["ab"]);
    assert_eq!(lines(&compose(body, &[], &["A"])), ["a"]);
    assert_eq!(lines(&compose(body, &[], &["B", "C1"])), ["c1b", "c1"]);
    assert_eq!(lines(&compose(body, &[], &["C2"])), Vec::<&str>::new());
}

#[test]
fn tutorial_expression_works_as_written() {
    // Catlike Coding Rendering 13's `#if defined(DEFERRED_PASS) && UNITY_ENABLE_REFLECTION_BUFFERS`.
    let body =
        "#define DEFERRED_PASS\n#if defined(DEFERRED_PASS) && A\nbuffers\n#else\nprobes\n#endif";
    assert_eq!(lines(&compose(body, &[], &["A"])), ["buffers"]);
    assert_eq!(lines(&compose(body, &[], &[])), ["probes"]);
}

#[test]
fn valued_defines_and_comparisons() {
    let body = "#define CASCADES 4\n#if CASCADES >= 2 && CASCADES != 3 && !(CASCADES > 4)\nok\n#endif\n#if UNDEFINED == 0 && !defined(UNDEFINED)\nundefined_is_zero\n#endif\n#if A == 1\nkeyword_is_one\n#endif";
    assert_eq!(
        lines(&compose(body, &[], &["A"])),
        ["ok", "undefined_is_zero", "keyword_is_one"]
    );
}

#[test]
fn define_and_undef_apply_in_text_order_across_imports() {
    let m = (
        "m.wgsl",
        "#ifdef FROM_PASS\nseen_in_module\n#endif\n#define FROM_MODULE 7",
    );
    let body = "#define FROM_PASS\n#import m\n#if FROM_MODULE == 7\nseen_in_pass\n#endif\n#undef FROM_MODULE\n#ifdef FROM_MODULE\nnot_here\n#endif";
    assert_eq!(
        lines(&compose(body, &[m], &[])),
        ["seen_in_module", "seen_in_pass"]
    );
}

#[test]
fn imports_come_in_once_and_diamonds_are_fine() {
    let base = ("lib/base.wgsl", "base");
    let left = ("lib/left.wgsl", "#import lib/base\nleft");
    let right = ("lib/right.wgsl", "#import lib/base\nright");
    let body = "#import lib/left\n#import lib/right\n#import lib/base\nmain";
    assert_eq!(
        lines(&compose(body, &[base, left, right], &[])),
        ["base", "left", "right", "main"]
    );
}

#[test]
fn conditional_imports_follow_the_keyword() {
    let m = ("m.wgsl", "module");
    let body = "#if A\n#import m\n#endif\nmain";
    assert_eq!(lines(&compose(body, &[m], &["A"])), ["module", "main"]);
    assert_eq!(lines(&compose(body, &[m], &[])), ["main"]);
}

#[test]
fn directives_in_comments_are_text() {
    let body = "// #if A\n/* block\n#if A\n   /* nested */\n#endif\n*/\nkept";
    let out = compose(body, &[], &[]);
    assert_eq!(
        lines(&out),
        [
            "// #if A",
            "/* block",
            "#if A",
            "   /* nested */",
            "#endif",
            "*/",
            "kept"
        ]
    );
}

#[test]
fn trailing_comments_on_directives() {
    let body = "#if A // only with A\na\n#endif // A";
    assert_eq!(lines(&compose(body, &[], &["A"])), ["a"]);
}

#[test]
fn crlf_and_bom_are_accepted_and_locations_stay_right() {
    let main =
        "\u{feff}#shader s\r\n#pass P\r\n#pragma multi_compile _ A\r\n#import m\r\n#endpass\r\n";
    let m = "fn f() -> f32 {\r\n#if A\r\n    return vec2f(1.0);\r\n#else\r\n    return 1.0;\r\n#endif\r\n}\r\n";
    let lib = Library::from_sources([("main.wgsl", main), ("m.wgsl", m)]).unwrap();
    let ok = lib.variant("s", "P", &[] as &[&str]).unwrap();
    assert!(lib.naga_module(&ok).is_ok());
    assert!(!lib.wgsl(&ok).contains('\r'));
    let bad = lib.variant("s", "P", &["A"]).unwrap();
    let err = lib.naga_module(&bad).unwrap_err();
    assert_eq!(
        err.location(lib.files()).unwrap().to_string(),
        "m.wgsl:3:12"
    );
}

#[test]
fn errors_in_a_deep_import_point_at_the_original_line() {
    let inner = (
        "deep/inner.wgsl",
        "fn inner() -> f32 {\n    return undefined_name;\n}",
    );
    let outer = (
        "deep/outer.wgsl",
        "#import deep/inner\nfn outer() -> f32 { return inner(); }",
    );
    let main = "#shader s\n#pass P\n#pragma multi_compile _ A\n#import deep/outer\n#endpass\n";
    let lib = Library::from_sources([("main.wgsl", main), inner, outer]).unwrap();
    let v = lib.variant("s", "P", &["A"]).unwrap();
    let err = lib.naga_module(&v).unwrap_err();
    assert_eq!(
        err.location(lib.files()).unwrap().to_string(),
        "deep/inner.wgsl:2:12"
    );
    assert!(
        err.diagnostic()
            .notes
            .iter()
            .any(|n| n == "in variant s/P {A}"),
        "{:?}",
        err.diagnostic().notes
    );
}

#[test]
fn nesting_limit_gives_a_clear_error_not_a_crash() {
    let deep = "#if A\n".repeat(300) + &"#endif\n".repeat(300);
    let err = Library::from_sources([("m.wgsl", deep)]).unwrap_err();
    assert!(
        err.diagnostics()[0]
            .message
            .contains("nested deeper than the limit of 256"),
        "{}",
        err
    );
    assert_eq!(err.locations()[0], "m.wgsl:257:1");
}

/// A malformed `#pass` or `#shader` line is one error: the block is opened all the same, so its
/// pragmas, body and `#endpass` are not reported again.
#[test]
fn a_malformed_pass_or_shader_name_is_one_error() {
    for main in [
        "#shader s\n#pass Forward Base\n#pragma multi_compile _ A\nfn f() {}\n#endpass\n",
        "#shader ../x\n#pass P\n#pragma multi_compile _ A\nfn f() {}\n#endpass\n",
        "#shader s\n#pass a/../b\n#tag LightMode Deferred\nfn f() {}\n#endpass\n",
    ] {
        let err = Library::from_sources([("main.wgsl", main)]).unwrap_err();
        assert_eq!(err.problems.len(), 1, "{main:?}:\n{err}");
        assert!(err.to_string().contains("expected a name"), "{err}");
    }
    // Unity's own shader names have `/` and `-`: they follow the rule.
    let lib = Library::from_sources([(
        "main.wgsl",
        "#shader Hidden/Internal-DeferredShading\n#pass LIGHTING_PASS\n#endpass\n",
    )])
    .unwrap();
    assert_eq!(lib.shaders()[0].name, "Hidden/Internal-DeferredShading");
}
