//! The command line on the bundled library: JSON shapes, exit codes, determinism.

use std::process::{Command, Output};

use serde_json::Value;

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

fn json(args: &[&str]) -> Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: stdout is not one JSON object: {e}"))
}

fn pass<'a>(report: &'a Value, shader: &str, pass: &str) -> &'a Value {
    report["passes"]
        .as_array()
        .expect("passes")
        .iter()
        .find(|p| p["shader"] == shader && p["pass"] == pass)
        .unwrap_or_else(|| panic!("no {shader}/{pass}"))
}

/// `validate --all --json` on one pass (standard/ForwardAdd, 18,432 variants): the report
/// covers its full space and nothing else. The whole library's full space is validated by the
/// README's main job (`validate --all`, a step of `.ci/run`, whose counts `scripts/figures.sh`
/// holds to the README), so this test does not repeat it.
#[test]
fn validate_all_json_covers_the_full_space_of_the_selected_pass() {
    let report = json(&[
        "validate",
        "--all",
        "--json",
        "--no-cache",
        "--shader",
        "standard",
        "--pass",
        "ForwardAdd",
    ]);
    let add = pass(&report, "standard", "ForwardAdd");
    for (key, value) in [
        ("full_space", 18_432),
        ("built", 18_432),
        ("distinct", 13_104),
        ("valid", 18_432),
        ("invalid", 0),
    ] {
        assert_eq!(add[key], value, "ForwardAdd {key}");
    }
    assert_eq!(report["passes"].as_array().map(Vec::len), Some(1));
    assert_eq!(report["ok"], true);
    assert_eq!(report["totals"]["invalid"], 0);
    assert_eq!(report["totals"]["built"], add["built"]);
}

/// `validate` on a twelfth of standard/Deferred's 110,592 variants (shard 1/12, 9,216 variants)
/// without the cache (every variant validated on each run, not read back); the full space's
/// order is checked by the manifest snapshot at one thread per core (tests/snapshots.rs).
#[test]
fn output_is_byte_identical_across_thread_counts() {
    for args in [
        [
            "validate",
            "--all",
            "--json",
            "--no-cache",
            "--pass",
            "Deferred",
            "--shard",
            "1/12",
        ]
        .as_slice(),
        ["list", "--json"].as_slice(),
        ["audit", "--json"].as_slice(),
    ] {
        let one = run(&[&["--threads", "1"], args].concat());
        let two = run(&[&["--threads", "2"], args].concat());
        let again = run(&[&["--threads", "2"], args].concat());
        assert!(one.status.success());
        assert_eq!(
            one.stdout, two.stdout,
            "{args:?} differs between 1 and 2 threads"
        );
        assert_eq!(two.stdout, again.stdout, "{args:?} differs between runs");
    }
}

#[test]
fn list_reports_tags_sets_and_counts() {
    let list = json(&["list", "--json"]);
    let standard = list["shaders"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "standard")
        .expect("standard");
    let deferred = standard["passes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "Deferred")
        .expect("Deferred");
    assert_eq!(deferred["full_space"], 110_592);
    assert_eq!(
        deferred["tags"][0],
        serde_json::json!(["LightMode", "Deferred"])
    );
    assert_eq!(deferred["exclude_renderers"], serde_json::json!(["nomrt"]));
    assert_eq!(deferred["keyword_sets"].as_array().unwrap().len(), 16);
}

#[test]
fn audit_json_has_the_stage_counts() {
    let audit = json(&["audit", "--json"]);
    let deferred = pass(&audit, "standard", "Deferred");
    for key in ["full_space", "after_filtering", "build_set", "distinct"] {
        assert_eq!(deferred[key], 110_592, "{key}");
    }
}

#[test]
fn emit_prints_the_variant_and_fails_clearly_on_bad_keywords() {
    let out = run(&[
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAP,UNITY_HDR_ON",
    ]);
    assert!(out.status.success());
    let wgsl = String::from_utf8(out.stdout).unwrap();
    assert!(wgsl.contains("normal_map") && !wgsl.contains("#if"));
    let bad = run(&[
        "--color",
        "never",
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_NORMAL_MAPP",
    ]);
    assert_eq!(bad.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&bad.stderr);
    assert!(
        stderr.contains("did you mean `_NORMAL_MAP`?") && stderr.contains("┌─ standard.wgsl:"),
        "{stderr}"
    );
    let conflict = run(&[
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "_SMOOTHNESS_ALBEDO,_SMOOTHNESS_METALLIC",
    ]);
    assert_eq!(conflict.status.code(), Some(1));
    let missing = run(&["emit", "standard", "NoSuchPass"]);
    assert_eq!(missing.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&missing.stderr)
            .contains("passes: ForwardBase, ForwardAdd, Deferred")
    );
}

#[test]
fn materials_restrict_the_build_set() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("materials.toml");
    std::fs::write(&path, "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAP\", \"_METALLIC_MAP\"]\n").unwrap();
    let report = json(&["validate", "--json", "--materials", path.to_str().unwrap()]);
    // One shader_feature combination × the 8 · 3 · 6 multi_compile combinations of Deferred
    // (HDR, reflection buffers, shadowmask; the BRDF tier; the lightmaps), × the 2 · 3 · 6
    // (SHADOWS_SCREEN, tier, lightmaps) of ForwardBase.
    assert_eq!(pass(&report, "standard", "Deferred")["built"], 144);
    assert_eq!(pass(&report, "standard", "ForwardBase")["built"], 36);
    std::fs::write(
        &path,
        "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAPP\"]\n",
    )
    .unwrap();
    let bad = run(&["validate", "--materials", path.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("did you mean `_NORMAL_MAP`?"));
}

#[test]
fn shards_partition_the_build_exactly() {
    use wgsl_variants::plan::{PlanOptions, variants_to_build};
    use wgsl_variants::variants::Shard;
    let lib = wgsl_variants_shaders::library().unwrap();
    let mut options = PlanOptions::default();
    options.all = true;
    let plans: Vec<_> = lib
        .passes()
        .map(|p| {
            (
                p.name.clone() + "@" + &p.shader,
                variants_to_build(&lib, p, &options).unwrap(),
            )
        })
        .collect();
    let whole: Vec<(String, _)> = plans
        .iter()
        .flat_map(|(p, cs)| cs.iter().map(move |c| (p.clone(), c.clone())))
        .collect();
    let mut union = Vec::new();
    for k in 1..=3 {
        let shard: Shard = format!("{k}/3").parse().unwrap();
        union.extend(
            shard
                .select(plans.clone())
                .into_iter()
                .flat_map(|(p, cs)| cs.into_iter().map(move |c| (p.clone(), c))),
        );
    }
    assert_eq!(union.len(), whole.len(), "shards overlap or miss variants");
    let mut sorted_union = union.clone();
    sorted_union.sort();
    sorted_union.dedup();
    let mut sorted_whole = whole.clone();
    sorted_whole.sort();
    assert_eq!(sorted_union, sorted_whole);
    // The command line selects the same shards: on the two ShadowCaster passes (standard's
    // and universal_lit's, 16 variants; validating every shard of the full space is one
    // whole run, which the README's main job does), each shard builds what the library's
    // selection holds, and they add up.
    let casters: Vec<_> = plans
        .iter()
        .filter(|(p, _)| p.starts_with("ShadowCaster@"))
        .cloned()
        .collect();
    assert_eq!(casters.len(), 2);
    let mut built = 0;
    for k in 1..=3 {
        let shard: Shard = format!("{k}/3").parse().unwrap();
        let expected: usize = shard
            .select(casters.clone())
            .iter()
            .map(|(_, cs)| cs.len())
            .sum();
        let report = json(&[
            "validate",
            "--all",
            "--json",
            "--no-cache",
            "--pass",
            "ShadowCaster",
            "--shard",
            &format!("{k}/3"),
        ]);
        assert_eq!(report["totals"]["built"], expected as u64, "shard {k}/3");
        built += expected;
    }
    assert_eq!(built, casters.iter().map(|(_, cs)| cs.len()).sum::<usize>());
    assert_eq!(run(&["validate", "--shard", "4/3"]).status.code(), Some(2));
}

#[test]
fn the_cache_changes_speed_not_output() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().to_str().unwrap();
    // standard/ForwardAdd: 18,432 variants, validated twice (the first run, the damaged
    // cache's), read back once.
    let args = [
        "validate",
        "--all",
        "--json",
        "--shader",
        "standard",
        "--pass",
        "ForwardAdd",
        "--cache",
        cache,
    ];
    let first = run(&args);
    let folder = dir.path().join(wgsl_variants::cache::key());
    let segments = || -> Vec<_> {
        std::fs::read_dir(&folder)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect()
    };
    let files = segments();
    assert_eq!(
        files.len(),
        1,
        "one segment per save, in one folder per version"
    );
    // One entry per distinct program (pruned text) of the 18,432 variants.
    assert_eq!(
        wgsl_variants::cache::ValidCache::open(dir.path()).len(),
        13104
    );
    let second = run(&args);
    assert_eq!(first.stdout, second.stdout);
    assert_eq!(segments(), files, "nothing new: nothing written");
    // A damaged cache is ignored record by record, never trusted blindly, and reported.
    std::fs::write(&files[0], b"garbage").unwrap();
    let damaged = run(&args);
    assert_eq!(damaged.stdout, first.stdout);
    let stderr = String::from_utf8_lossy(&damaged.stderr);
    assert!(stderr.contains("corrupt"), "{stderr}");
}

/// The cache is read: a cache entry for a text that does NOT validate makes `validate` report
/// it valid (only a read cache can do that), and `--no-cache` shows the same tree fails.
#[test]
fn a_cache_entry_is_a_hit() {
    let tree = tempfile::tempdir().unwrap();
    let shader = "#shader s\n#pass P\n#pragma multi_compile _ BAD\n\
                  #ifdef BAD\nfn f() -> f32 { return vec2f(1.0); }\n#endif\n\
                  @fragment fn fs() -> @location(0) vec4f {\n#ifdef BAD\n_ = f();\n#endif\n\
                  return vec4f(1.0);\n}\n#endpass\n";
    std::fs::write(tree.path().join("s.wgsl"), shader).unwrap();
    let lib = wgsl_variants::Library::from_dir(tree.path()).unwrap();
    let bad = lib.variant("s", "P", &["BAD"]).unwrap();
    let key = wgsl_variants::cache::hash(&lib.wgsl(&bad));

    let cache = tempfile::tempdir().unwrap();
    let root = tree.path().to_str().unwrap();
    let dir = cache.path().to_str().unwrap();
    let without = run(&["--root", root, "validate", "--all", "--no-cache"]);
    assert_eq!(without.status.code(), Some(1), "the BAD variant is invalid");

    let planted = wgsl_variants::cache::ValidCache::open(cache.path());
    planted.insert(key);
    planted.save().unwrap();
    let with = run(&["--root", root, "validate", "--all", "--cache", dir]);
    assert_eq!(
        with.status.code(),
        Some(0),
        "the planted entry was not read: {}",
        String::from_utf8_lossy(&with.stderr)
    );
}

/// A naga_oil tree (found by its `wgsl-variants.toml`) goes through the same commands: the
/// covering set finds the failing combination, and its smallest failing keyword subset.
#[test]
fn a_naga_oil_tree_is_listed_covered_and_emitted() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/fixtures/naga_oil");
    let out = run(&["--root", root, "list"]);
    assert!(out.status.success());
    let listing = String::from_utf8_lossy(&out.stdout);
    assert!(listing.contains("12 full space"), "{listing}");

    let out = run(&[
        "--root",
        root,
        "--color",
        "never",
        "validate",
        "--cover",
        "2",
        "--no-cache",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stdout.contains("lit/Forward: 6 built (12 full space)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("smallest failing keyword subset: {FOG}"),
        "{stdout}"
    );
    assert!(stderr.contains("lit.wgsl:27:16"), "{stderr}");
    assert!(stderr.contains("`demo::lighting::fog_color`"), "{stderr}");

    let out = run(&[
        "--root",
        root,
        "emit",
        "lit",
        "Forward",
        "--keywords",
        "FOG,VERTEX_COLORS",
    ]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("@fragment"));
    let out = run(&["--root", root, "audit"]);
    assert!(out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stdout)
            .contains("an upper bound on the programs naga_oil composes")
    );

    // A variant naga_oil cannot compose has no text, validated or not.
    for extra in [&["--target", "spirv"][..], &["--no-validate"][..]] {
        let mut args = vec![
            "--root",
            root,
            "emit",
            "lit",
            "Forward",
            "--keywords",
            "FOG",
        ];
        args.extend_from_slice(extra);
        let out = run(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// A WESL tree: listed, covered (the failing combination shrunk and located in the tree),
/// emitted through a back end, audited; the same JSON report with 1 and 2 threads; and the
/// bundled library exported to WESL reads back as a tree whose variants all validate.
#[test]
fn a_wesl_tree_is_listed_covered_emitted_and_exported() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../tests/fixtures/wesl");
    let out = run(&["--root", root, "list"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("12 full space"));

    let validate = |threads: &str| {
        run(&[
            "--root",
            root,
            "--color",
            "never",
            "--threads",
            threads,
            "validate",
            "--cover",
            "2",
            "--no-cache",
        ])
    };
    let out = validate("2");
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stdout.contains("lit/Forward: 6 built (12 full space)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("smallest failing keyword subset: {FOG}"),
        "{stdout}"
    );
    assert!(stderr.contains("lit.wesl:1:1"), "{stderr}");
    assert_eq!(validate("1").stdout, out.stdout);

    let json = |threads: &str| {
        run(&[
            "--root",
            root,
            "--json",
            "--threads",
            threads,
            "validate",
            "--all",
            "--no-cache",
        ])
        .stdout
    };
    assert_eq!(json("1"), json("2"));

    let out = run(&[
        "--root",
        root,
        "emit",
        "lit",
        "Forward",
        "--keywords",
        "FOG,VERTEX_COLORS",
        "--target",
        "hlsl",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stdout).contains("VertexOut"));
    let out = run(&["--root", root, "audit"]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stdout).contains("the programs the wesl crate composes"));

    let dir = tempfile::tempdir().unwrap();
    let out_dir = dir.path().to_str().unwrap();
    let out = run(&["export", "--dialect", "wesl", "--all", "--out", out_dir]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = run(&[
        "--root",
        out_dir,
        "validate",
        "--all",
        "--cover",
        "2",
        "--no-cache",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("total: 19 passes"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
}

/// A tree of one pass whose variants need different devices: `ARRAY` a binding array (desktop
/// only), `CUBES` a cube array texture (not WebGL2), `STORAGE` a storage buffer (not WebGL2),
/// `WIDE` a 64-bit float (desktop only).
fn device_tree() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("main.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ ARRAY CUBES STORAGE WIDE\n#import lit\n#endpass\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("lit.wgsl"),
        "#ifdef ARRAY\nenable wgpu_binding_array;\n@group(0) @binding(0) var textures: binding_array<texture_2d<f32>, 4>;\n#endif\n\
         #ifdef CUBES\n@group(0) @binding(1) var cubes: texture_cube_array<f32>;\n#endif\n\
         #ifdef STORAGE\n@group(0) @binding(2) var<storage> values: array<vec4<f32>>;\n#endif\n\
         @group(0) @binding(3) var s: sampler;\n\
         @fragment\nfn fs_main() -> @location(0) vec4<f32> {\n    var c = vec4<f32>(0.0);\n\
         #ifdef ARRAY\n    c += textureSample(textures[1], s, vec2<f32>(0.5));\n#endif\n\
         #ifdef CUBES\n    c += textureSample(cubes, s, vec3<f32>(0.0, 0.0, 1.0), 0);\n#endif\n\
         #ifdef STORAGE\n    c += values[0];\n#endif\n\
         #ifdef WIDE\n    let w: f64 = 1.0lf;\n    c.x += f32(w);\n#endif\n    return c;\n}\n",
    )
    .unwrap();
    dir
}

fn in_tree(root: &std::path::Path, args: &[&str]) -> Output {
    let root = root.to_str().unwrap();
    run(&[&["--root", root, "--color", "never"], args].concat())
}

#[test]
fn several_profiles_give_one_verdict_each() {
    let tree = device_tree();
    let out = in_tree(
        tree.path(),
        &[
            "validate",
            "--no-cache",
            "--profile",
            "webgpu",
            "--profile",
            "webgl2",
            "--profile",
            "desktop",
        ],
    );
    assert_eq!(out.status.code(), Some(1), "a variant fails on a profile");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        stdout,
        "s/P: 5 built (5 full space), 5 distinct, 1 valid on every profile, 4 invalid on some\n\
         \x20 webgpu: 3 valid, 2 invalid\n\
         \x20 webgl2: 1 valid, 4 invalid\n\
         \x20 desktop: 5 valid, 0 invalid\n\
         \x20 {ARRAY}: fails on profiles webgpu, webgl2\n\
         \x20 {CUBES}: fails on profile webgl2\n\
         \x20 {STORAGE}: fails on profile webgl2\n\
         \x20 {WIDE}: fails on profiles webgpu, webgl2\n\
         total: 1 passes, 5 variants built, 5 distinct, 1 valid on every profile, 4 invalid on some\n\
         total webgpu: 3 valid, 2 invalid\n\
         total webgl2: 1 valid, 4 invalid\n\
         total desktop: 5 valid, 0 invalid\n"
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("= fails on profile webgl2")
            && stderr.contains("`values` is a storage buffer"),
        "{stderr}"
    );

    // Valid on every profile asked for: exit 0.
    let out = in_tree(
        tree.path(),
        &[
            "validate",
            "--no-cache",
            "--profile",
            "desktop",
            "--profile",
            "webgpu",
            "--pass",
            "P",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let out = in_tree(
        tree.path(),
        &["validate", "--no-cache", "--profile", "desktop"],
    );
    assert_eq!(out.status.code(), Some(0));
}

#[test]
fn several_profiles_in_json() {
    let tree = device_tree();
    let out = in_tree(
        tree.path(),
        &[
            "validate",
            "--json",
            "--no-cache",
            "--profile",
            "webgpu",
            "--profile",
            "desktop",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["ok"], false);
    let counts = serde_json::json!([
        {"profile": "webgpu", "valid": 3, "invalid": 2},
        {"profile": "desktop", "valid": 5, "invalid": 0},
    ]);
    assert_eq!(report["totals"]["profiles"], counts);
    let p = pass(&report, "s", "P");
    assert_eq!(p["profiles"], counts);
    assert_eq!(
        (p["valid"].as_u64(), p["invalid"].as_u64()),
        (Some(3), Some(2))
    );
    let failures: Vec<(Value, Value)> = p["failures"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| (f["keyword_sets"].clone(), f["profiles"].clone()))
        .collect();
    assert_eq!(
        failures,
        [
            (
                serde_json::json!([["ARRAY"]]),
                serde_json::json!(["webgpu"])
            ),
            (serde_json::json!([["WIDE"]]), serde_json::json!(["webgpu"])),
        ]
    );
    // The field order is fixed: `profiles` after `invalid`, and after `location`.
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.find("\"invalid\": 2,\n      \"profiles\"").is_some(),
        "{text}"
    );
    assert!(
        text.contains("\"location\": \"lit.wgsl:3:23\",\n          \"profiles\": ["),
        "{text}"
    );

    // One profile: no `profiles` anywhere, and the same bytes as without `--profile`.
    let one = in_tree(
        tree.path(),
        &["validate", "--json", "--no-cache", "--profile", "webgpu"],
    );
    let none = in_tree(tree.path(), &["validate", "--json", "--no-cache"]);
    assert_eq!(one.stdout, none.stdout);
    assert!(!String::from_utf8_lossy(&one.stdout).contains("\"profiles\""));
    // A profile given twice counts once.
    let twice = in_tree(
        tree.path(),
        &[
            "validate",
            "--json",
            "--no-cache",
            "--profile",
            "webgpu",
            "--profile",
            "webgpu",
        ],
    );
    assert_eq!(twice.stdout, none.stdout);
}

#[test]
fn several_profiles_are_deterministic_across_thread_counts() {
    let tree = device_tree();
    let root = tree.path().to_str().unwrap();
    for args in [
        ["validate", "--json", "--no-cache"].as_slice(),
        ["validate", "--no-cache"].as_slice(),
        ["audit", "--json"].as_slice(),
    ] {
        let with = |threads: &str| {
            run(&[
                &["--root", root, "--threads", threads],
                args,
                &[
                    "--profile",
                    "webgl2",
                    "--profile",
                    "webgpu",
                    "--profile",
                    "desktop",
                ],
            ]
            .concat())
        };
        let one = with("1");
        let four = with("4");
        assert_eq!(one.stdout, four.stdout, "{args:?}");
        assert_eq!(one.stderr, four.stderr, "{args:?}");
    }
}

#[test]
fn audit_tables_the_variants_valid_per_profile() {
    let tree = device_tree();
    let out = in_tree(
        tree.path(),
        &[
            "audit",
            "--profile",
            "webgpu",
            "--profile",
            "webgl2",
            "--profile",
            "desktop",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(
            "variants valid per profile (build set, validated):\n  shader/pass  built  webgpu  webgl2  desktop\n  s/P              5       3       1        5\n"
        ),
        "{stdout}"
    );
    let report = json(&[
        "--root",
        tree.path().to_str().unwrap(),
        "audit",
        "--json",
        "--profile",
        "webgpu",
        "--profile",
        "desktop",
    ]);
    assert_eq!(
        report["valid_per_profile"],
        serde_json::json!([{"shader": "s", "pass": "P", "built": 5, "profiles": [
            {"profile": "webgpu", "valid": 3, "invalid": 2},
            {"profile": "desktop", "valid": 5, "invalid": 0},
        ]}])
    );
    // One profile: the audit validates nothing and has no such table.
    let out = in_tree(tree.path(), &["audit", "--profile", "desktop"]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("valid per profile"));
}

#[test]
fn commands_that_build_one_program_refuse_several_profiles() {
    let tree = device_tree();
    for args in [
        ["emit", "s", "P"].as_slice(),
        ["reflect", "s", "P"].as_slice(),
        ["manifest"].as_slice(),
    ] {
        let out = in_tree(
            tree.path(),
            &[args, &["--profile", "webgpu", "--profile", "desktop"]].concat(),
        );
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains("`--profile` names 2 devices (webgpu, desktop)")
                && stderr.contains(&format!("`{}` builds for one", args[0])),
            "{args:?}: {stderr}"
        );
    }
    let out = in_tree(
        tree.path(),
        &[
            "validate",
            "--no-cache",
            "--shard",
            "1/2",
            "--profile",
            "webgpu",
            "--profile",
            "desktop",
        ],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--shard validates for one device"));
}
