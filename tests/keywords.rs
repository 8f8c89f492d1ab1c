//! Unity's keyword semantics: sets, placeholders, build sets, skip_variants, lookup, counting.

use num_bigint::BigUint;
use wgsl_variants::lookup::{LookupError, lookup_closest, lookup_strict};
use wgsl_variants::materials::{self, Material};
use wgsl_variants::{Library, Space};

fn library(pragmas: &str) -> Library {
    let main = format!("#shader s\n#pass P\n{pragmas}\n#endpass\n");
    Library::from_sources([("main.wgsl", main)]).unwrap_or_else(|e| panic!("{e}"))
}

fn material(name: &str, keywords: &[&str]) -> Material {
    Material {
        name: name.into(),
        shader: "s".into(),
        keywords: keywords.iter().map(|k| k.to_string()).collect(),
    }
}

fn labels(lib: &Library, space: &Space<'_>) -> Vec<String> {
    let pass = lib.pass("s", "P").unwrap();
    space
        .enumerate(1000)
        .unwrap()
        .iter()
        .map(|c| c.label(pass))
        .collect()
}

#[test]
fn unity_manual_examples_count() {
    let lib = library("#pragma multi_compile A B C\n#pragma multi_compile D E");
    assert_eq!(
        Space::full(lib.pass("s", "P").unwrap()).count(),
        BigUint::from(6u32)
    );
    let ten: String = (0..10)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let lib = library(&ten);
    assert_eq!(
        Space::full(lib.pass("s", "P").unwrap()).count(),
        BigUint::from(1024u32)
    );
}

#[test]
fn placeholders_and_single_name_shader_feature() {
    let lib = library(
        "#pragma shader_feature _NORMAL_MAP\n#pragma shader_feature __ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC\n#pragma multi_compile ALWAYS",
    );
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(
        pass.sets.iter().map(|s| s.len()).collect::<Vec<_>>(),
        [2, 3, 1]
    );
    assert_eq!(
        labels(&lib, &Space::full(pass)),
        [
            "{ALWAYS}",
            "{_SMOOTHNESS_ALBEDO, ALWAYS}",
            "{_SMOOTHNESS_METALLIC, ALWAYS}",
            "{_NORMAL_MAP, ALWAYS}",
            "{_NORMAL_MAP, _SMOOTHNESS_ALBEDO, ALWAYS}",
            "{_NORMAL_MAP, _SMOOTHNESS_METALLIC, ALWAYS}"
        ]
    );
}

#[test]
fn local_forms_are_the_same_sets() {
    let lib = library("#pragma multi_compile_local _ A\n#pragma shader_feature_local B");
    let pass = lib.pass("s", "P").unwrap();
    assert!(pass.sets.iter().all(|s| s.local));
    assert_eq!(Space::full(pass).count(), BigUint::from(4u32));
}

#[test]
fn bundled_standard_shader_counts() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let deferred = lib.pass("standard", "Deferred").unwrap();
    assert_eq!(Space::full(deferred).count(), BigUint::from(110_592u32));
    assert_eq!(deferred.tag("LightMode"), Some("Deferred"));
    assert_eq!(deferred.exclude_renderers, ["nomrt"]);
    let forward = lib.pass("standard", "ForwardBase").unwrap();
    assert_eq!(Space::full(forward).count(), BigUint::from(55_296u32));
}

#[test]
fn build_set_is_multi_compile_times_material_combinations() {
    let lib = library(
        "#pragma multi_compile _ UNITY_HDR_ON\n#pragma shader_feature _NORMAL_MAP\n#pragma shader_feature _ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC",
    );
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(Space::full(pass).count(), BigUint::from(12u32));
    // Without materials the build set is the whole space.
    assert_eq!(
        lib.build_set(pass, None).unwrap().count(),
        BigUint::from(12u32)
    );
    // Two materials using two shader_feature combinations (and a duplicate of one).
    let mats = vec![
        material("bricks", &["_NORMAL_MAP"]),
        material("skin", &["_SMOOTHNESS_METALLIC"]),
        material("bricks2", &["_NORMAL_MAP"]),
    ];
    let build = lib.build_set(pass, Some(&mats)).unwrap();
    assert_eq!(build.count(), BigUint::from(4u32));
    assert_eq!(
        labels(&lib, &build),
        // Each material combination (sorted), then every multi_compile combination.
        [
            "{_SMOOTHNESS_METALLIC}",
            "{UNITY_HDR_ON, _SMOOTHNESS_METALLIC}",
            "{_NORMAL_MAP}",
            "{UNITY_HDR_ON, _NORMAL_MAP}"
        ]
    );
    // A multi_compile keyword in a material changes nothing: every mc option is built anyway.
    let with_mc = vec![material("m", &["UNITY_HDR_ON"])];
    assert_eq!(
        labels(&lib, &lib.build_set(pass, Some(&with_mc)).unwrap()),
        ["{}", "{UNITY_HDR_ON}"]
    );
}

#[test]
fn shader_with_no_material_builds_nothing_when_materials_are_given() {
    let lib = library("#pragma shader_feature A");
    let pass = lib.pass("s", "P").unwrap();
    let other = Material {
        name: "x".into(),
        shader: "s".into(),
        keywords: vec![],
    };
    assert_eq!(
        lib.build_set(pass, Some(&[other])).unwrap().count(),
        BigUint::from(1u32)
    );
    assert_eq!(
        lib.build_set(pass, Some(&[])).unwrap().count(),
        BigUint::from(0u32)
    );
}

#[test]
fn skip_variants_removes_every_variant_with_the_keyword_on() {
    let lib = library(
        "#pragma multi_compile _ A\n#pragma multi_compile B C D\n#pragma skip_variants A C",
    );
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(Space::full(pass).count(), BigUint::from(6u32));
    let after = Space::after_skip(pass);
    assert_eq!(after.count(), BigUint::from(2u32));
    assert_eq!(labels(&lib, &after), ["{B}", "{D}"]);
}

#[test]
fn strict_lookup_is_exact_or_names_the_nearest() {
    let lib = library(
        "#pragma multi_compile _ A\n#pragma multi_compile _ B\n#pragma shader_feature _ C\n#pragma skip_variants B",
    );
    let pass = lib.pass("s", "P").unwrap();
    let build = lib.build_set(pass, None).unwrap();
    assert_eq!(
        lookup_strict(&build, &["A", "C"], 100).unwrap().label(pass),
        "{A, C}"
    );
    match lookup_strict(&build, &["A", "B"], 100) {
        Err(LookupError::NotBuilt {
            nearest, reason, ..
        }) => {
            assert_eq!(reason, "`B` is in skip_variants");
            assert_eq!(nearest, ["{A}", "{}", "{A, C}"]);
        }
        other => panic!("{other:?}"),
    }
    // The fallback is only used when asked for.
    assert_eq!(
        lookup_closest(&build, &["A", "B"], 100)
            .unwrap()
            .label(pass),
        "{A}"
    );
}

#[test]
fn lookup_errors_are_specific() {
    let lib = library("#pragma multi_compile A B\n#pragma shader_feature _NORMAL_MAP");
    let pass = lib.pass("s", "P").unwrap();
    let err = pass.resolve(&["A", "B"]).unwrap_err().to_string();
    assert_eq!(
        err,
        "`A` and `B` are options of the same set (`multi_compile A B`): only one can be on"
    );
    let err = pass.resolve(&["_NORMAL_MAP"]).unwrap_err().to_string();
    assert_eq!(
        err,
        "no keyword of the set `multi_compile A B` is given, and the set has no \"none\" option"
    );
    let err = pass.resolve(&["A", "_NORMALMAP"]).unwrap_err().to_string();
    assert_eq!(
        err,
        "pass `s/P` declares no keyword `_NORMALMAP`; did you mean `_NORMAL_MAP`?"
    );
    assert!(matches!(
        lib.pass("s", "Q"),
        Err(LookupError::UnknownPass { .. })
    ));
    assert_eq!(
        lib.shader("standrd").unwrap_err().to_string(),
        "no shader named `standrd`"
    );
}

#[test]
fn counting_is_exact_for_huge_spaces() {
    let sets: String = (0..64)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let lib = library(&sets);
    let pass = lib.pass("s", "P").unwrap();
    assert_eq!(Space::full(pass).count(), BigUint::from(1u8) << 64);
    let err = Space::full(pass).enumerate(1_000_000).unwrap_err();
    assert_eq!(
        err.to_string(),
        "18446744073709551616 variants is past the build budget of 1000000 (raise it with --max-variants)"
    );
    let threes: String = (0..100)
        .map(|i| format!("#pragma multi_compile X{i} Y{i} Z{i}\n"))
        .collect();
    let lib = library(&threes);
    assert_eq!(
        Space::full(lib.pass("s", "P").unwrap()).count(),
        BigUint::from(3u8).pow(100)
    );
}

#[test]
fn materials_files_parse_and_are_checked() {
    let toml = "[[material]]\nname = \"Bricks\"\nshader = \"s\"\nkeywords = [\"A\"]\n";
    let json = r#"{"materials": [{"name": "Bricks", "shader": "s", "keywords": ["A"]}]}"#;
    let a = materials::parse(toml, true, "m.toml").unwrap();
    let b = materials::parse(json, false, "m.json").unwrap();
    assert_eq!(a, b);
    let err =
        materials::parse("{\"materials\": [\n  {\"name\": 1}]}", false, "m.json").unwrap_err();
    assert!(err.to_string().starts_with("m.json:2:"), "{err}");
    let lib = library("#pragma shader_feature _ A B");
    let pass = lib.pass("s", "P").unwrap();
    let typo = vec![material("m", &["AA"])];
    assert_eq!(
        lib.build_set(pass, Some(&typo)).unwrap_err().to_string(),
        "material `m` enables `AA`, which no pass of shader `s` declares; did you mean `A`?"
    );
    let both = vec![material("m", &["A", "B"])];
    assert!(
        lib.build_set(pass, Some(&both))
            .unwrap_err()
            .to_string()
            .contains("enables both `A` and `B`")
    );
}

/// A material whose keywords break a constraint between shader_feature sets is an error naming
/// the material, the pass and the constraint — never silently dropped from the build set. A
/// constraint that also involves a multi_compile set only removes the variants that break it.
#[test]
fn a_material_breaking_a_constraint_is_an_error() {
    let lib = library(
        "#pragma shader_feature _ DETAIL\n#pragma shader_feature _ NORMALS\n\
         #pragma multi_compile _ LOW HIGH\n#pragma require DETAIL NORMALS\n#pragma exclude NORMALS LOW",
    );
    let pass = lib.pass("s", "P").unwrap();
    let detail_only = vec![material("Moss", &["DETAIL"])];
    assert_eq!(
        lib.build_set(pass, Some(&detail_only))
            .unwrap_err()
            .to_string(),
        "material `Moss` breaks `#pragma require DETAIL NORMALS` of `s/P`: no variant of the pass has its keywords"
    );
    let fine = vec![material("Rock", &["DETAIL", "NORMALS"])];
    let space = lib.build_set(pass, Some(&fine)).unwrap();
    // Rock's one feature combination times the multi_compile options NORMALS allows (_, HIGH).
    assert_eq!(space.count(), BigUint::from(2u8));
}

#[test]
fn materials_that_no_variant_can_draw_are_refused_naming_material_and_pass() {
    let lib = library(
        "#pragma multi_compile _ FOG\n#pragma shader_feature _ A B\n#pragma shader_feature C\n#pragma skip_variants C",
    );
    let pass = lib.pass("s", "P").unwrap();
    // A keyword skip_variants strips from the pass.
    let e = lib
        .build_set(pass, Some(&[material("Glass", &["C"])]))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`Glass`") && e.contains("`C`") && e.contains("`s/P`"),
        "{e}"
    );
    assert!(e.contains("skip_variants"), "{e}");
    // Two options of one set.
    let e = lib
        .build_set(pass, Some(&[material("Both", &["A", "B"])]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("`Both`") && e.contains("`s/P`"), "{e}");
    // A multi_compile keyword is allowed (Unity: on when enabled globally or on the
    // material) and changes no build set.
    assert!(
        lib.build_set(pass, Some(&[material("Foggy", &["FOG", "A"])]))
            .is_ok()
    );
}
