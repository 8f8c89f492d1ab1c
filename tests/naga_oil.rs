//! A naga_oil tree (`tests/fixtures/naga_oil`, written for this test, with a declaration file):
//! it loads in naga_oil's dialect, every variant composes through naga_oil exactly as a direct
//! naga_oil call with the same shader defs does, and the variants with a bug fail with the file,
//! line and column of the user's tree and their keyword sets.

use std::collections::HashMap;

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
};
use wgsl_variants::validate::{Stage, validate_pass};
use wgsl_variants::{Dialect, Library, Space};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/naga_oil");

fn fixture(path: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap()
}

#[test]
fn declaration_file_declares_the_passes() {
    let lib = Library::from_dir(ROOT).unwrap();
    assert_eq!(lib.dialect(), Dialect::NagaOil);
    let pass = lib.pass("lit", "Forward").unwrap();
    assert_eq!(Space::full(pass).count(), 12u32.into());
    assert_eq!(pass.tag("LightMode"), Some("Forward"));
    assert_eq!(pass.constants[0].name, "MAX_LIGHTS");
    let keywords: Vec<&str> = pass.keywords().collect();
    assert_eq!(keywords, ["SKINNED", "FOG", "NORMAL_MAP", "VERTEX_COLORS"]);
}

/// The program naga_oil itself makes of the fixture for these defs, written by naga.
fn direct(defs: &[(&str, ShaderDefValue)]) -> String {
    let mut composer = Composer::default();
    for module in ["common/skinning.wgsl", "common/lighting.wgsl"] {
        composer
            .add_composable_module(ComposableModuleDescriptor {
                source: &fixture(module),
                file_path: module,
                language: ShaderLanguage::Wgsl,
                ..Default::default()
            })
            .unwrap();
    }
    let module = composer
        .make_naga_module(NagaModuleDescriptor {
            source: &fixture("lit.wgsl"),
            file_path: "lit.wgsl",
            shader_defs: defs
                .iter()
                .map(|(k, v)| (k.to_string(), *v))
                .collect::<HashMap<_, _>>(),
            ..Default::default()
        })
        .unwrap();
    let info = wgsl_variants::validate::validator()
        .validate(&module)
        .unwrap();
    naga::back::wgsl::write_string(&module, &info, naga::back::wgsl::WriterFlags::empty()).unwrap()
}

#[test]
fn every_valid_variant_is_what_naga_oil_composes() {
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
        let mut defs = vec![("MAX_LIGHTS", ShaderDefValue::UInt(4))];
        defs.extend(keywords.iter().map(|k| (*k, ShaderDefValue::Bool(true))));
        let ours = lib.wgsl(&variant);
        assert_eq!(ours, direct(&defs), "{}", variant.label());
        // Composers are pooled and cache per def set: composing again gives the same bytes.
        assert_eq!(lib.wgsl(&variant), ours);
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
    assert_eq!(failure.error.stage, Stage::Parse);
    assert_eq!(
        failure.location.as_ref().unwrap().to_string(),
        "lit.wgsl:27:16"
    );
    assert!(
        failure.error.message.contains("demo::lighting::fog_color"),
        "{}",
        failure.error.message
    );
    assert_eq!(failure.keyword_sets.len(), 4);
    for set in &failure.keyword_sets {
        assert!(set.contains(&"FOG".to_string()) && !set.contains(&"VERTEX_COLORS".to_string()));
    }
    assert!(failure.diagnostic.contains("in variant lit/Forward {FOG}"));
}

/// A tree holds more than the declared shaders: modules no entry reaches are not checked
/// (one here imports a path nothing defines), `exclude` leaves out one of two modules with the
/// same import path, and an item used by its full path without `#import` is an import.
#[test]
fn only_what_the_entries_reach_is_part_of_the_tree() {
    let declaration = "exclude = [\"alt\"]\n[[shader]]\nname = \"s\"\nentry = \"main.wgsl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"HALF\"]]\n";
    let sources = [
        (
            "main.wgsl",
            "@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(demo::tint::tint());\n}\n",
        ),
        (
            "tint.wgsl",
            "#define_import_path demo::tint\nfn tint() -> f32 {\n#ifdef HALF\n    return 0.5;\n#else\n    return 1.0;\n#endif\n}\n",
        ),
        (
            "alt/tint.wgsl",
            "#define_import_path demo::tint\nfn tint() -> f32 { return 2.0; }\n",
        ),
        ("unused.wgsl", "#import demo::nowhere\nfn f() {}\n"),
    ];
    let lib = Library::from_declared_sources(declaration, sources).unwrap();
    let pass = lib.pass("s", "P").unwrap();
    let half = lib.variant("s", "P", &["HALF"]).unwrap();
    assert!(lib.wgsl(&half).contains("0.5"), "{}", lib.wgsl(&half));
    // The audit sees HALF through the inline import: two distinct texts.
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert_eq!(audit.distinct_full_space.count, 2u32.into());
    assert!(audit.dead_keywords.is_empty());

    // Without `exclude`, the two `demo::tint` modules are ambiguous.
    let err = Library::from_declared_sources(declaration.split_once('\n').unwrap().1, sources)
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("two modules define import path `demo::tint`"),
        "{err}"
    );
}

/// A valued set gives a def one value per variant (`N=1u`, `N=4u`): naga_oil gets the typed
/// value, `#if` comparisons and the audit see it, and a substituted value makes the audit's
/// count a bound.
#[test]
fn valued_sets_give_a_def_one_value_per_variant() {
    let declaration = "[[shader]]\nname = \"s\"\nentry = \"main.wgsl\"\n[[shader.pass]]\nname = \"P\"\nvalues = { N = { uint = [1, 4] } }\n";
    let compare = "@fragment\nfn fs() -> @location(0) vec4<f32> {\n#if N > 2\n    return vec4<f32>(1.0);\n#else\n    return vec4<f32>(0.0);\n#endif\n}\n";
    let lib = Library::from_declared_sources(declaration, [("main.wgsl", compare)]).unwrap();
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(pass.keywords().collect::<Vec<_>>(), ["N=1u", "N=4u"]);
    let four = lib.variant("s", "P", &["N=4u"]).unwrap();
    assert!(lib.wgsl(&four).contains("vec4(1f)"), "{}", lib.wgsl(&four));
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert_eq!(audit.distinct_full_space.count, 2u32.into());
    assert!(audit.distinct_full_space.exact);

    let substitute = "const TAPS: u32 = #{N};\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(f32(TAPS));\n}\n";
    let lib = Library::from_declared_sources(declaration, [("main.wgsl", substitute)]).unwrap();
    let pass = lib.pass("s", "P").unwrap();
    let one = lib.variant("s", "P", &["N=1u"]).unwrap();
    assert!(lib.wgsl(&one).contains("1u"), "{}", lib.wgsl(&one));
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert!(!audit.distinct_full_space.exact);
    assert_eq!(audit.distinct_full_space.count, 2u32.into());
}

/// `bake` (a build.rs) reads a naga_oil tree like any other: its declaration file is found at
/// the root, every variant is validated, the outputs are written; a failing variant stops it
/// with the variant's keyword set and location.
#[test]
fn a_naga_oil_tree_bakes() {
    let tree = tempfile::tempdir().unwrap();
    let write = |path: &str, text: &str| std::fs::write(tree.path().join(path), text).unwrap();
    write(
        "wgsl-variants.toml",
        "[[shader]]\nname = \"s\"\nentry = \"main.wgsl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"HALF\"]]\n",
    );
    write(
        "tint.wgsl",
        "#define_import_path demo::tint\nfn tint() -> f32 {\n#ifdef HALF\n    return 0.5;\n#else\n    return 1.0;\n#endif\n}\n",
    );
    write(
        "main.wgsl",
        "#import demo::tint\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return vec4<f32>(tint::tint());\n}\n",
    );
    let out = tempfile::tempdir().unwrap();
    let baked = wgsl_variants::bake::Bake::new(tree.path())
        .write_to(out.path())
        .unwrap();
    assert_eq!((baked.variants, baked.outputs), (2, 2));
    assert!(
        std::fs::read_to_string(&baked.file)
            .unwrap()
            .contains("HALF")
    );

    write(
        "tint.wgsl",
        "#define_import_path demo::tint\nfn tint() -> f32 {\n#ifdef HALF\n    return vec2<f32>(0.5);\n#else\n    return 1.0;\n#endif\n}\n",
    );
    let err = wgsl_variants::bake::Bake::new(tree.path())
        .write_to(out.path())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("tint.wgsl:2:1") && err.contains("{HALF}"),
        "{err}"
    );
}
