//! A WESL tree (`tests/fixtures/wesl`, written for this test, with a declaration file): it
//! loads in WESL's dialect, every variant is what the `wesl` crate compiles for the same
//! features, and the variants with a bug fail with the file, line and column of the user's
//! tree and their keyword sets.

use wgsl_variants::validate::{Stage, validate_pass};
use wgsl_variants::{Dialect, Library, Space};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/wesl");

fn fixture(path: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap()
}

#[test]
fn declaration_file_declares_the_passes() {
    let lib = Library::from_dir(ROOT).unwrap();
    assert_eq!(lib.dialect(), Dialect::Wesl);
    assert_eq!(
        lib.module_paths(),
        ["common/lighting", "common/skinning", "lit"]
    );
    let pass = lib.pass("lit", "Forward").unwrap();
    assert_eq!(Space::full(pass).count(), 12u32.into());
    assert_eq!(pass.tag("LightMode"), Some("Forward"));
    let keywords: Vec<&str> = pass.keywords().collect();
    assert_eq!(keywords, ["SKINNED", "FOG", "NORMAL_MAP", "VERTEX_COLORS"]);
}

/// The program the `wesl` crate itself compiles from the fixture's files for these features
/// (its own resolver over the files; the host's numbers in the `constants` package).
fn direct(on: &[&str]) -> String {
    let mut resolver = wesl::resolver::VirtualResolver::new();
    for (path, file) in [
        ("package::lit", "lit.wesl"),
        ("package::common::lighting", "common/lighting.wesl"),
        ("package::common::skinning", "common/skinning.wesl"),
    ] {
        resolver.add_module(path.parse().unwrap(), fixture(file).into());
    }
    resolver.add_module(
        "constants".parse().unwrap(),
        "public const MAX_LIGHTS = 4u;\n".into(),
    );
    let mut options = wesl::CompileOptions::default();
    for f in ["SKINNED", "FOG", "NORMAL_MAP", "VERTEX_COLORS"] {
        options.features.set(f, on.contains(&f));
    }
    wesl::compile(&"package::lit".parse().unwrap(), &options, &resolver)
        .unwrap()
        .to_string()
}

/// A program's top-level blocks (wesl writes a blank line between declarations), sorted.
fn blocks(text: &str) -> Vec<&str> {
    let mut b: Vec<&str> = text.split("\n\n").map(str::trim).collect();
    b.sort();
    b
}

#[test]
fn every_valid_variant_is_what_wesl_compiles() {
    let lib = Library::from_dir(ROOT).unwrap();
    let pass = lib.pass("lit", "Forward").unwrap();
    let mut compared = 0;
    for choice in Space::full(pass).iter() {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let keywords = variant.keywords();
        if keywords.contains(&"FOG") && !keywords.contains(&"VERTEX_COLORS") {
            continue;
        }
        let ours = lib.wgsl(&variant);
        // The same declarations (wesl 0.4 orders imported modules by hash-map iteration; ours
        // are in a fixed order), and the same bytes on every composition.
        assert_eq!(
            blocks(&ours),
            blocks(&direct(&keywords)),
            "{}",
            variant.label()
        );
        for _ in 0..8 {
            assert_eq!(lib.wgsl(&variant), ours, "{}", variant.label());
        }
        assert!(lib.naga_module(&variant).is_ok(), "{}", variant.label());
        compared += 1;
    }
    assert_eq!(compared, 8);
}

#[test]
fn the_failing_combination_is_located_in_the_tree() {
    let lib = Library::from_dir(ROOT).unwrap();
    let pass = lib.pass("lit", "Forward").unwrap();
    let choices: Vec<_> = Space::full(pass).iter().collect();
    let report = validate_pass(&lib, pass, &choices, &|_| {});
    assert_eq!((report.built, report.valid, report.invalid), (12, 8, 4));
    // One failure: the four variants fail alike.
    assert_eq!(report.failures.len(), 1, "{:#?}", report.failures);
    let failure = &report.failures[0];
    assert_eq!(failure.error.stage, Stage::Compose);
    assert_eq!(
        failure.location.as_ref().unwrap().to_string(),
        "lit.wesl:1:1"
    );
    assert!(
        failure
            .error
            .message
            .contains("has no declaration `fog_color`"),
        "{}",
        failure.error.message
    );
    assert_eq!(failure.keyword_sets.len(), 4);
    for set in &failure.keyword_sets {
        assert!(set.contains(&"FOG".to_string()) && !set.contains(&"VERTEX_COLORS".to_string()));
    }
    assert!(failure.diagnostic.contains("in variant lit/Forward {FOG}"));
}

const DECLARATION: &str = "[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"HALF\"]]\n";

/// naga's errors on the compiled program (spans into wesl's output, names renamed) are traced
/// to the declaration's module and the text in it.
#[test]
fn a_type_error_is_located_in_the_module_that_has_it() {
    let sources = [
        (
            "main.wesl",
            "import package::lib::tint::tint;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(tint());\n}\n",
        ),
        (
            "lib/tint.wesl",
            "fn tint() -> f32 {\n    @if(HALF) {\n        return vec2<f32>(0.5);\n    }\n    return 1.0;\n}\n",
        ),
    ];
    let lib = Library::from_declared_sources(DECLARATION, sources).unwrap();
    assert_eq!(lib.dialect(), Dialect::Wesl);
    let off = lib.variant("s", "P", &[] as &[&str]).unwrap();
    assert!(lib.naga_module(&off).is_ok());
    let half = lib.variant("s", "P", &["HALF"]).unwrap();
    let err = lib.naga_module(&half).unwrap_err();
    assert_eq!(err.stage, Stage::Validate, "{err:?}");
    let files = lib.files();
    // The function (line 1) and the returned expression (line 3, `vec2<f32>(0.5)`).
    let lines: Vec<(String, usize, usize)> = err
        .labels
        .iter()
        .map(|(span, _)| {
            let at = files.location(*span);
            (files.path(span.file).to_string(), at.line, at.column)
        })
        .collect();
    assert_eq!(
        lines,
        [
            ("lib/tint.wesl".into(), 1, 4),
            ("lib/tint.wesl".into(), 3, 16)
        ],
        "{err:?}"
    );
    assert!(!err.message.contains("package_"), "{}", err.message);
}

/// `super::` imports, items used by their full path, a def no module reads (a warning) and
/// the audit's view of the `@if` tree.
#[test]
fn imports_warnings_and_the_audit_read_the_attribute_tree() {
    let declaration = "[[shader]]\nname = \"s\"\nentry = \"a/main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"HALF\"], [\"_\", \"UNREAD\"]]\n";
    let sources = [
        (
            "a/main.wesl",
            "import super::super::lib::tint;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(tint::tint() * package::lib::scale::scale());\n}\n",
        ),
        (
            "lib/tint.wesl",
            "fn tint() -> f32 {\n    @if(HALF) {\n        return 0.5;\n    }\n    return 1.0;\n}\n",
        ),
        ("lib/scale.wesl", "fn scale() -> f32 { return 2.0; }\n"),
    ];
    let lib = Library::from_declared_sources(declaration, sources).unwrap();
    assert_eq!(lib.warnings().len(), 1);
    assert!(lib.warnings()[0].message.contains("UNREAD"));
    let half = lib.variant("s", "P", &["HALF"]).unwrap();
    assert!(
        lib.naga_module(&half).is_ok(),
        "{:?}",
        lib.naga_module(&half).err()
    );
    assert!(lib.wgsl(&half).contains("0.5"), "{}", lib.wgsl(&half));
    let pass = lib.pass("s", "P").unwrap();
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert_eq!(audit.distinct_full_space.count, 2u32.into());
    assert_eq!(audit.dead_keywords, ["UNREAD"]);
}

/// `bake` (a build.rs) reads a WESL tree like any other; a failing variant stops it with the
/// variant's keyword set and location.
#[test]
fn a_wesl_tree_bakes() {
    let tree = tempfile::tempdir().unwrap();
    let write = |path: &str, text: &str| {
        let path = tree.path().join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap()
    };
    write("wgsl-variants.toml", DECLARATION);
    write(
        "main.wesl",
        "import package::tint::tint;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(tint());\n}\n",
    );
    write(
        "tint.wesl",
        "fn tint() -> f32 {\n    @if(HALF) {\n        return 0.5;\n    }\n    return 1.0;\n}\n",
    );
    let out = tempfile::tempdir().unwrap();
    let baked = wgsl_variants::bake::Bake::new(tree.path())
        .write_to(out.path())
        .unwrap();
    assert_eq!((baked.variants, baked.outputs), (2, 2));

    write(
        "tint.wesl",
        "fn tint() -> f32 {\n    @if(HALF) {\n        return undefined_name;\n    }\n    return 1.0;\n}\n",
    );
    let err = wgsl_variants::bake::Bake::new(tree.path())
        .write_to(out.path())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("tint.wesl:3:") && err.contains("{HALF}"),
        "{err}"
    );
}

/// A valued set gives a number one value per variant through the `constants` package (WESL
/// features are booleans), and the audit counts such a pass as a bound.
#[test]
fn valued_sets_reach_the_program_as_constants() {
    let declaration = "[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nvalues = { N = { uint = [1, 4] } }\n";
    let main = "import constants::N;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(f32(N));\n}\n";
    let lib = Library::from_declared_sources(declaration, [("main.wesl", main)]).unwrap();
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(pass.keywords().collect::<Vec<_>>(), ["N=1u", "N=4u"]);
    let four = lib.variant("s", "P", &["N=4u"]).unwrap();
    assert!(
        lib.naga_module(&four).is_ok(),
        "{:?}",
        lib.naga_module(&four).err()
    );
    assert!(lib.wgsl(&four).contains("4u"), "{}", lib.wgsl(&four));
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert!(!audit.distinct_full_space.exact);
    assert_eq!(audit.distinct_full_space.count, 2u32.into());
}

/// Two options of one variant that set the same def (as Bevy pushes `PREPASS_FRAGMENT` for each
/// prepass kind) give one `const` of the `constants` package, not a duplicate declaration.
#[test]
fn two_options_setting_one_def_compose() {
    let declaration = "dialect = \"wesl\"\n[constants]\nN = { uint = 1 }\n[options]\nA_ON = [\"A\", \"SHARED\"]\nB_ON = [\"B\", \"SHARED\"]\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"A_ON\"], [\"_\", \"B_ON\"]]\n";
    let main = "import constants::N;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    var c = f32(N);\n    @if(SHARED) { c = 0.5; }\n    @if(A) { c += 0.25; }\n    @if(B) { c += 0.125; }\n    return vec4<f32>(c);\n}\n";
    let lib = Library::from_declared_sources(declaration, [("main.wesl", main)]).unwrap();
    let both = lib.variant("s", "P", &["A_ON", "B_ON"]).unwrap();
    assert!(
        lib.naga_module(&both).is_ok(),
        "{:?}",
        lib.naga_module(&both).err()
    );
    let text = lib.wgsl(&both);
    assert!(text.contains("0.25") && text.contains("0.125"), "{text}");
}

/// `.wesl` files in a tree without a declaration file are not read as this crate's dialect:
/// they are left out, with a warning that says what a WESL tree needs.
#[test]
fn wesl_files_without_a_declaration_file_are_left_out_with_a_warning() {
    let lib = Library::from_sources([
        (
            "main.wgsl",
            "#shader s\n#pass P\n#pragma multi_compile _ A\n#endpass\n",
        ),
        ("lib.wesl", "@if(A) fn f() {}\n"),
    ])
    .unwrap();
    assert_eq!(lib.module_paths(), ["main"]);
    assert_eq!(lib.warnings().len(), 1);
    assert!(lib.warnings()[0].message.contains("dialect = \"wesl\""));
}

/// The engine parses each module once per loaded tree and compiles every variant from that
/// parse: a module edited between two `watch` runs is read anew (each run loads the tree
/// again), never compiled from its earlier parse, and compiling one parse again and again
/// (every variant, twice, in any order) gives the same programs.
#[test]
fn an_edited_module_is_parsed_anew_between_watch_runs() {
    use std::sync::Mutex;
    use std::sync::atomic::AtomicBool;
    use wgsl_variants::watch::{Event, Outcome, Session};

    let tree = tempfile::tempdir().unwrap();
    let write = |path: &str, text: &str| std::fs::write(tree.path().join(path), text).unwrap();
    let tint = |half: &str| {
        format!(
            "fn tint() -> f32 {{\n    @if(HALF) {{\n        return {half};\n    }}\n    return 1.0;\n}}\n"
        )
    };
    write("wgsl-variants.toml", DECLARATION);
    write(
        "main.wesl",
        "import package::tint::tint;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(tint());\n}\n",
    );
    write("tint.wesl", &tint("0.5"));
    let mut session = Session::new(tree.path(), Default::default(), Default::default(), None);
    let run = |session: &mut Session| {
        let errors = Mutex::new(Vec::new());
        let outcome = session
            .run(&AtomicBool::new(false), &|e| {
                if let Event::Failure { library, error } = e {
                    let at = error.location(library.files()).map(|l| l.to_string());
                    errors.lock().unwrap().push(format!(
                        "{} @ {} in {}",
                        error.message,
                        at.unwrap_or_default(),
                        error.variant
                    ));
                }
            })
            .unwrap();
        let Outcome::Verdict(verdict) = outcome else {
            panic!("not cancelled, yet {outcome:?}");
        };
        (verdict.report.totals.invalid, errors.into_inner().unwrap())
    };
    let half = |session: &Session| {
        let lib = session.library().unwrap();
        lib.wgsl(&lib.variant("s", "P", &["HALF"]).unwrap())
    };
    assert_eq!(run(&mut session), (0, Vec::new()));
    assert!(half(&session).contains("0.5"), "{}", half(&session));

    write("tint.wesl", &tint("undefined_name"));
    let (invalid, errors) = run(&mut session);
    assert_eq!(invalid, 1);
    assert!(
        errors.len() == 1 && errors[0].contains("@ tint.wesl:3:") && errors[0].contains("{HALF}"),
        "{errors:?}"
    );

    write("tint.wesl", &tint("0.25"));
    assert_eq!(run(&mut session), (0, Vec::new()));
    assert!(half(&session).contains("0.25"), "{}", half(&session));

    // One parse, compiled again and again in any order: the same programs.
    let lib = session.library().unwrap();
    let none: &[&str] = &[];
    let variants = [
        lib.variant("s", "P", none).unwrap(),
        lib.variant("s", "P", &["HALF"]).unwrap(),
    ];
    let first: Vec<String> = variants.iter().map(|v| lib.wgsl(v)).collect();
    assert_ne!(first[0], first[1]);
    for i in [1, 0, 1, 0] {
        assert_eq!(lib.wgsl(&variants[i]), first[i]);
    }
}

/// naga's span names the identifier it cannot find; in the source it is that identifier as a
/// whole word (not the end of a longer name), at the same occurrence.
#[test]
fn an_unknown_identifier_is_located_at_its_use_not_inside_a_longer_name() {
    let lib = Library::from_declared_sources(
        "dialect = \"wesl\"\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"A\"]]\n",
        [(
            "main.wesl",
            "struct In { @location(0) ddx_uv: f32, @location(1) @if(A) uv: f32, }\n\
             @fragment fn fs(v: In) -> @location(0) vec4f {\n    let ddx_uv = v.ddx_uv;\n    return vec4f(ddx_uv + uv + v.uv);\n}\n",
        )],
    )
    .unwrap();
    let composed = lib.compose(&lib.variant("s", "P", &["A"]).unwrap());
    let e = composed.failure.expect("`uv` is not declared");
    let at = e.location(lib.files()).expect("located").to_string();
    assert_eq!(at, "main.wesl:4:27", "{e:?}");
}
