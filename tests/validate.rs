//! Validation counts: each distinct text validated once, duplicates and failures counted per
//! keyword set, the same report with and without the audit's all-distinct proof, on any
//! thread count.

use std::collections::HashSet;

use wgsl_variants::audit::proves_all_distinct;
use wgsl_variants::validate::{PassReport, validate_pass};
use wgsl_variants::{Library, Space, Variant};

fn lib(pass_body: &str) -> Library {
    Library::from_sources([(
        "s.wgsl",
        format!("#shader s\n#pass P\n{pass_body}\n#endpass\n"),
    )])
    .expect("library loads")
}

fn report(lib: &Library, threads: usize) -> PassReport {
    let pass = lib.pass("s", "P").expect("pass");
    let choices = Space::full(pass).enumerate(1 << 20).expect("enumerable");
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool")
        .install(|| validate_pass(lib, pass, &choices, &|_| {}))
}

/// Distinct texts counted by composing every variant and comparing the texts themselves.
fn distinct_by_text(lib: &Library) -> u64 {
    let pass = lib.pass("s", "P").expect("pass");
    let choices = Space::full(pass).enumerate(1 << 20).expect("enumerable");
    let texts: HashSet<String> = choices
        .into_iter()
        .map(|choice| lib.wgsl(&Variant { pass, choice }))
        .collect();
    texts.len() as u64
}

fn summary(r: &PassReport) -> String {
    let failures: Vec<String> = r
        .failures
        .iter()
        .map(|f| format!("{} {:?}", f.error, f.keyword_sets))
        .collect();
    format!(
        "built {} distinct {} valid {} invalid {} failures {failures:?}",
        r.built, r.distinct, r.valid, r.invalid
    )
}

const DEAD_AND_BROKEN: &str = "#pragma multi_compile _ A
#pragma multi_compile _ DEAD
#ifdef A
fn f() -> f32 { return missing; }
#endif
@fragment fn fs_main() -> @location(0) vec4f {
#ifdef A
    _ = f();
#endif
    return vec4f(1.0);
}";

#[test]
fn a_shared_failing_text_is_validated_once_and_counted_per_keyword_set() {
    let lib = lib(DEAD_AND_BROKEN);
    assert!(!proves_all_distinct(&lib, lib.pass("s", "P").unwrap()));
    let r = report(&lib, 1);
    assert_eq!((r.built, r.distinct, r.valid, r.invalid), (4, 2, 2, 2));
    assert_eq!(r.failures.len(), 1);
    let mut sets = r.failures[0].keyword_sets.clone();
    sets.sort();
    assert_eq!(sets, vec![vec!["A"], vec!["A", "DEAD"]]);
    assert!(r.failures[0].error.message.contains("missing"));
    assert_eq!(summary(&r), summary(&report(&lib, 2)));
}

#[test]
fn when_every_text_is_proved_distinct_the_counts_are_the_same() {
    let body = "#pragma multi_compile LOW MID HIGH
#pragma multi_compile _ A
#pragma multi_compile _ B
#if defined(LOW)
const T: f32 = 0.0;
#elif defined(MID)
const T: f32 = 1.0;
#else
const T: f32 = 2.0;
#endif
#if defined(HIGH) && defined(B)
@fragment fn f() -> @location(0) vec4f { return missing; }
#elif defined(MID)
@fragment fn f() -> @location(0) vec4f { return vec4f(1.0); }
#endif
#ifdef A
@fragment fn g() -> @location(0) vec4f { return vec4f(2.0); }
#endif
#ifdef B
@fragment fn h() -> @location(0) vec4f { return vec4f(3.0); }
#endif
@fragment fn fs_main() -> @location(0) vec4f { return vec4f(T); }";
    let lib = lib(body);
    assert!(proves_all_distinct(&lib, lib.pass("s", "P").unwrap()));
    let r = report(&lib, 1);
    assert_eq!((r.built, r.distinct, r.valid, r.invalid), (12, 12, 10, 2));
    assert_eq!(r.distinct, distinct_by_text(&lib));
    // Two different failing texts (HIGH B, HIGH A B): one failure each, in enumeration order.
    assert_eq!(r.failures.len(), 2);
    assert!(r.failures.iter().all(|f| f.keyword_sets.len() == 1));
    assert_eq!(summary(&r), summary(&report(&lib, 2)));
}

#[test]
fn a_keyword_that_changes_only_unreached_code_makes_one_program() {
    let body = "#pragma multi_compile _ A
#ifdef A
fn unused() -> f32 { return missing; }
#endif
@fragment fn fs_main() -> @location(0) vec4f { return vec4f(1.0); }";
    let lib = lib(body);
    let pass = lib.pass("s", "P").unwrap();
    // The audit counts two composed texts; reachability leaves one program, valid.
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert_eq!(audit.distinct.count, 2u32.into());
    assert!(!proves_all_distinct(&lib, pass));
    let r = report(&lib, 2);
    assert_eq!((r.built, r.distinct, r.valid, r.invalid), (2, 1, 2, 0));
    assert_eq!(r.distinct, distinct_by_text(&lib));
    assert_eq!(
        wgsl_variants::analysis::unreached(&lib, pass),
        [wgsl_variants::analysis::Unreached {
            module: "s".into(),
            names: vec!["unused".into()],
        }]
    );
}

#[test]
fn distinct_counts_match_the_texts_themselves() {
    let bodies = [
        DEAD_AND_BROKEN,
        // Coupled keywords: B matters only with A.
        "#pragma multi_compile _ A\n#pragma multi_compile _ B\n#if defined(A) && defined(B)\nfn f() {}\n#endif",
        // A #define that hides a keyword's effect.
        "#pragma multi_compile _ A\n#pragma multi_compile _ B\n#ifdef A\n#define B_OFF 1\n#endif\n#if defined(B) && !defined(B_OFF)\nfn f() {}\n#endif",
        // Comments only differ: the same program.
        "#pragma multi_compile _ A\n#ifdef A\n// only a comment\n#endif\nfn f() {}",
        // Shader-feature and multi_compile mixed, every text distinct.
        "#pragma shader_feature _ X Y\n#pragma multi_compile _ A\n#ifdef X\nfn x() {}\n#endif\n#ifdef Y\nfn y() {}\n#endif\n#ifdef A\nfn a() {}\n#endif",
    ];
    for body in bodies {
        let lib = lib(body);
        let r = report(&lib, 2);
        assert_eq!(r.distinct, distinct_by_text(&lib), "{body}");
        let proved = proves_all_distinct(&lib, lib.pass("s", "P").unwrap());
        assert_eq!(proved, r.distinct == r.built, "{body}");
    }
}

/// naga's own error stays reachable as the source of a variant's error: the text is the
/// report's, the source is the typed error.
#[test]
fn variant_errors_keep_naga_errors_as_their_source() {
    use std::error::Error as _;
    let syntax = lib("@fragment fn fs() -> @location(0) vec4f { return vec4f(1.0) }");
    let pass = syntax.pass("s", "P").expect("pass");
    let v = Variant {
        pass,
        choice: Space::full(pass).iter().next().expect("a variant"),
    };
    let err = syntax.naga_module(&v).expect_err("a syntax error");
    let source = err.source().expect("naga's error kept");
    assert!(
        source
            .downcast_ref::<naga::front::wgsl::ParseError>()
            .is_some()
    );
    assert_eq!(err, err.clone(), "the source is shared, not compared");

    let typed = lib("@fragment fn fs() -> vec4f { return vec4f(1.0); }");
    let pass = typed.pass("s", "P").expect("pass");
    let v = Variant {
        pass,
        choice: Space::full(pass).iter().next().expect("a variant"),
    };
    let err = typed
        .naga_module(&v)
        .expect_err("an output without a location");
    let source = err.source().expect("naga's error kept");
    assert!(
        source
            .downcast_ref::<naga::WithSpan<naga::valid::ValidationError>>()
            .is_some(),
        "{source:?}"
    );
}

/// A merge input that cannot be read keeps the OS error.
#[test]
fn merge_read_errors_keep_the_io_error() {
    use std::error::Error as _;
    let missing = std::env::temp_dir().join("wgsl-variants-no-such-shard-folder");
    let err = wgsl_variants::merge::manifest::merge_folders(&[missing], &std::env::temp_dir())
        .expect_err("no such folder");
    let io = err
        .source()
        .and_then(|s| s.downcast_ref::<std::io::Error>());
    assert_eq!(
        io.map(std::io::Error::kind),
        Some(std::io::ErrorKind::NotFound),
        "{err}"
    );
}
