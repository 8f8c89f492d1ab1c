//! `wgsl-variants emit`: `--out` with its manifest, one variant to stdout or a folder, failures,
//! shards.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};

use serde_json::Value;

// ---------------------------------------------------------------- emit --out
fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
        .args(args)
        .output()
        .expect("run wgsl-variants")
}

fn ok(args: &[&str]) -> String {
    let out = cli(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn read_tree(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .replace('\\', "/");
                out.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

#[test]
fn emit_out_writes_a_build_set_with_a_deterministic_manifest() {
    let dirs = [tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap()];
    let materials = tempfile::NamedTempFile::with_suffix(".toml").unwrap();
    std::fs::write(
        materials.path(),
        "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAP\", \"_METALLIC_MAP\"]\n\n[[material]]\nname = \"Plain\"\nshader = \"standard\"\n",
    )
    .unwrap();
    for (dir, threads) in dirs.iter().zip(["1", "2"]) {
        ok(&[
            "--threads",
            threads,
            "emit",
            "--out",
            dir.path().to_str().unwrap(),
            "--target",
            "wgsl,spirv,glsl,hlsl,msl",
            "--glsl-version",
            "300es",
            "--materials",
            materials.path().to_str().unwrap(),
            "--shader",
            "standard",
        ]);
    }
    let (a, b) = (read_tree(dirs[0].path()), read_tree(dirs[1].path()));
    assert_eq!(a, b, "output depends on the thread count");

    let manifest: Value = serde_json::from_slice(&a["manifest.json"]).unwrap();
    let variants = manifest["variants"].as_array().unwrap();
    // 2 materials: ForwardBase 2 × 2 (SHADOWS_SCREEN) × 3 (BRDF tier) × 6 (lightmaps);
    // ForwardAdd 2 × 16 light and shadow combinations × 3; Deferred 2 × 8 multi_compile
    // combinations × 3 × 6; ShadowCaster 2 (SHADOWS_DEPTH, SHADOWS_CUBE: neither material has
    // a caster keyword, so both use the same two).
    assert_eq!(variants.len(), 72 + 96 + 288 + 2);
    let targets: Vec<&str> = manifest["targets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["target"].as_str().unwrap())
        .collect();
    assert_eq!(targets, ["wgsl", "spirv", "glsl", "hlsl", "msl"]);
    assert_eq!(manifest["targets"][2]["version"], "300es");
    let mut files = 0;
    for v in variants {
        assert_eq!(v["shader"], "standard");
        let eps: Vec<(&str, &str)> = v["entry_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| (e["name"].as_str().unwrap(), e["stage"].as_str().unwrap()))
            .collect();
        assert_eq!(eps, [("vs_main", "vertex"), ("fs_main", "fragment")]);
        // wgsl, spirv, 2 × glsl, hlsl, msl.
        assert_eq!(v["files"].as_array().unwrap().len(), 6);
        for f in v["files"].as_array().unwrap() {
            let bytes = &a[f["file"].as_str().unwrap()];
            assert_eq!(f["bytes"], bytes.len());
            assert_eq!(f["blake3"], blake3::hash(bytes).to_hex().as_str());
            files += 1;
        }
        let glsl: Vec<&Value> = v["files"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|f| f["target"] == "glsl")
            .collect();
        assert_eq!(glsl[0]["stage"], "vertex");
        assert!(glsl[0]["file"].as_str().unwrap().ends_with(".vs_main.vert"));
        assert!(glsl[1]["file"].as_str().unwrap().ends_with(".fs_main.frag"));
        assert!(!glsl[1]["slots"].as_array().unwrap().is_empty());
    }
    assert_eq!(a.len(), files + 1);
    assert!(a.contains_key("standard/Deferred/_METALLIC_MAP+_NORMAL_MAP+UNITY_HDR_ON.spv"));
    assert!(a.contains_key("standard/ForwardBase/none.wgsl"));
    let spv = &a["standard/ForwardBase/none.spv"];
    assert_eq!(spv[..4], 0x0723_0203u32.to_le_bytes());
    // The WGSL file is the canonical WGSL of the variant.
    let lib = wgsl_variants_shaders::library().unwrap();
    let v = lib
        .variant("standard", "ForwardBase", &[] as &[&str])
        .unwrap();
    assert_eq!(
        std::str::from_utf8(&a["standard/ForwardBase/none.wgsl"]).unwrap(),
        wgsl_variants::snapshot::canonical_wgsl(&lib, &v).unwrap()
    );
}

#[test]
fn emit_single_variant_to_stdout_and_folder() {
    // Default: the composed WGSL, as before.
    let composed = ok(&["emit", "standard", "Deferred", "--keywords", "_NORMAL_MAP"]);
    assert!(composed.contains("normal_map"));
    // Other text targets on stdout.
    let glsl = ok(&[
        "emit",
        "deferred_final",
        "Final",
        "--target",
        "glsl",
        "--entry-point",
        "fs_main",
    ]);
    assert!(glsl.starts_with("#version 450 core"), "{glsl}");
    assert!(!glsl.contains("// ====="));
    let both = ok(&[
        "emit",
        "deferred_final",
        "Final",
        "--target",
        "glsl",
        "--glsl-version",
        "300es",
    ]);
    assert!(both.contains("// ===== glsl 300es: vs_main (vertex) ====="));
    assert!(both.contains("#version 300 es"));
    let hlsl = ok(&[
        "emit",
        "standard",
        "Deferred",
        "--target",
        "hlsl",
        "--shader-model",
        "6_0",
    ]);
    assert!(hlsl.contains("fs_main"));
    let msl: Value = serde_json::from_str(&ok(&[
        "emit",
        "standard",
        "ForwardBase",
        "--target",
        "msl",
        "--msl-version",
        "2.1",
        "--json",
    ]))
    .unwrap();
    assert!(
        msl["outputs"][0]["text"]
            .as_str()
            .unwrap()
            .contains("metal2.1")
    );
    let canonical = ok(&["emit", "standard", "Deferred", "--canonical"]);
    assert!(!canonical.contains("//"), "canonical WGSL has no comments");

    // SPIR-V is binary: only into a folder.
    let out = cli(&["emit", "standard", "Deferred", "--target", "spirv"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--out DIR"));
    let dir = tempfile::tempdir().unwrap();
    ok(&[
        "emit",
        "standard",
        "Deferred",
        "--keywords",
        "UNITY_HDR_ON",
        "--target",
        "spirv",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    let spv = std::fs::read(dir.path().join("standard/Deferred/UNITY_HDR_ON.spv")).unwrap();
    assert_eq!(spv[..4], 0x0723_0203u32.to_le_bytes());
    let manifest: Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("manifest.json")).unwrap()).unwrap();
    assert_eq!(manifest["variants"].as_array().unwrap().len(), 1);

    for (args, message) in [
        (vec!["emit"], "--out DIR"),
        (vec!["emit", "standard"], "give SHADER and PASS"),
        (
            vec![
                "emit",
                "standard",
                "Deferred",
                "--target",
                "glsl",
                "--glsl-version",
                "451",
            ],
            "not supported",
        ),
        (
            vec![
                "emit",
                "standard",
                "Deferred",
                "--target",
                "hlsl",
                "--shader-model",
                "4_0",
            ],
            "not a shader model",
        ),
        (
            vec![
                "emit",
                "standard",
                "Deferred",
                "--target",
                "glsl",
                "--entry-point",
                "nope",
            ],
            "no entry point `nope`",
        ),
        (
            vec![
                "emit",
                "standard",
                "Deferred",
                "--target",
                "hlsl",
                "--no-validate",
            ],
            "--no-validate",
        ),
    ] {
        let out = cli(&args);
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}

#[test]
fn emit_out_reports_every_failing_variant_and_writes_nothing() {
    let root = tempfile::tempdir().unwrap();
    std::fs::write(
        root.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ A B\n@fragment\nfn fs() -> @location(0) vec4f {\n#if A\n    return vec3f(1.0);\n#else\n    return vec4f(1.0);\n#endif\n}\n#endpass\n",
    )
    .unwrap();
    let out_dir = tempfile::tempdir().unwrap();
    let target = out_dir.path().join("out");
    let out = cli(&[
        "--root",
        root.path().to_str().unwrap(),
        "--color",
        "never",
        "emit",
        "--out",
        target.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("s.wgsl:7:"), "{stderr}");
    assert!(stderr.contains("in variant s/P {A}"), "{stderr}");
    assert!(
        stderr.contains("1 variant(s) failed; nothing was written"),
        "{stderr}"
    );
    assert!(!target.exists());
}

#[test]
fn emit_out_shards_partition_the_build_set() {
    let dir = tempfile::tempdir().unwrap();
    let manifest = |name: &str, extra: &[&str]| -> Vec<serde_json::Value> {
        let out = dir.path().join(name);
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_wgsl-variants"))
            .args([
                "emit",
                "--out",
                out.to_str().unwrap(),
                "--shader",
                "deferred_reflections",
            ])
            .args(extra)
            .status()
            .unwrap();
        assert!(status.success());
        let text = std::fs::read_to_string(out.join("manifest.json")).unwrap();
        let json: serde_json::Value = serde_json::from_str(&text).unwrap();
        json["variants"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| serde_json::json!([v["pass"], v["keywords"]]))
            .collect()
    };
    let whole = manifest("all", &[]);
    let mut union = manifest("one", &["--shard", "1/2"]);
    union.extend(manifest("two", &["--shard", "2/2"]));
    assert_eq!(union.len(), whole.len(), "shards overlap or miss variants");
    for v in &whole {
        assert!(union.contains(v), "{v} missing from the shards");
    }
}
