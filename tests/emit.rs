//! Every naga back end for every variant of the bundled library, `emit --out` with its
//! manifest, and the build.rs API (`wgsl_variants::bake`).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Output};
use std::time::Instant;

use rayon::prelude::*;
use serde_json::Value;

use wgsl_variants::bake::{Bake, BakeTarget};
use wgsl_variants::emit::backends::{
    Contents, Options, Target, compile, parse_glsl_version, parse_msl_version, parse_shader_model,
    slots, translate,
};
use wgsl_variants::emit::reflect::Stage;
use wgsl_variants::{Library, Space, Variant};

fn targets() -> Vec<Target> {
    vec![
        Target::Wgsl,
        Target::SpirV,
        Target::Glsl(parse_glsl_version("450").unwrap()),
        Target::Glsl(parse_glsl_version("310es").unwrap()),
        Target::Glsl(parse_glsl_version("300es").unwrap()),
        Target::Hlsl(parse_shader_model("5_1").unwrap()),
        Target::Hlsl(parse_shader_model("6_0").unwrap()),
        Target::Msl(2, 0),
    ]
}

fn validator() -> naga::valid::Validator {
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
}

/// An external validator on PATH (`spirv-val` from SPIRV-Tools, `glslangValidator` from
/// glslang; `scripts/test.sh` installs both). Without it the check is skipped loudly, unless
/// `CI=true` or `WGSL_VARIANTS_REQUIRE_TOOLS=1`.
fn tool(name: &str) -> Option<std::path::PathBuf> {
    let found = std::env::var_os("PATH").and_then(|paths| {
        std::env::split_paths(&paths)
            .map(|dir| dir.join(name))
            .find(|p| p.is_file())
    });
    if found.is_none() {
        let required = std::env::var("CI").is_ok_and(|v| v == "true")
            || std::env::var("WGSL_VARIANTS_REQUIRE_TOOLS").is_ok_and(|v| v == "1");
        assert!(
            !required,
            "`{name}` is required (CI / WGSL_VARIANTS_REQUIRE_TOOLS)"
        );
        eprintln!("SKIPPED: `{name}` is not installed; its check does not run");
    }
    found
}

/// Runs an external validator on `bytes` written to `dir/name`.
fn external(
    tool: &Path,
    args: &[&str],
    dir: &Path,
    name: &str,
    bytes: &[u8],
) -> Result<(), String> {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    let out = Command::new(tool).args(args).arg(&path).output().unwrap();
    if out.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{} {name}: {}{}",
            tool.display(),
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

/// Checks one variant's outputs for every target; returns the number of outputs checked.
fn check_variant(
    lib: &Library,
    variant: &Variant<'_>,
    spirv_val: Option<&Path>,
    scratch: &Path,
) -> Result<usize, String> {
    let label = variant.label();
    let (module, info) = compile(lib, variant).map_err(|e| e.to_string())?;
    let entry_names: Vec<&str> = module
        .entry_points
        .iter()
        .map(|e| e.name.as_str())
        .collect();
    let mut checked = 0;
    for target in targets() {
        let outputs = translate(&module, &info, &target, &Options::default())
            .map_err(|e| format!("{label}: {e}"))?;
        match target {
            Target::Wgsl => {
                // naga's WGSL re-parses and validates, with the same entry points.
                let text = outputs[0].contents.as_text().unwrap();
                let again = naga::front::wgsl::parse_str(text)
                    .map_err(|e| format!("{label}: WGSL output: {}", e.emit_to_string(text)))?;
                validator()
                    .validate(&again)
                    .map_err(|e| format!("{label}: WGSL output invalid: {e:?}"))?;
                let names: Vec<&str> = again.entry_points.iter().map(|e| e.name.as_str()).collect();
                if names != entry_names {
                    return Err(format!("{label}: WGSL entry points {names:?}"));
                }
            }
            Target::SpirV => {
                let Contents::SpirV(words) = &outputs[0].contents else {
                    return Err(format!("{label}: SPIR-V is not words"));
                };
                if words.first() != Some(&0x0723_0203) {
                    return Err(format!("{label}: no SPIR-V magic number"));
                }
                let bytes = outputs[0].contents.to_bytes();
                // naga's SPIR-V front end reads it back with the same entry points (its
                // validator is not run on the result: the front end turns vector OpLogicalAnd
                // into IR that naga's own validator rejects).
                let back =
                    naga::front::spv::parse_u8_slice(&bytes, &naga::front::spv::Options::default())
                        .map_err(|e| format!("{label}: SPIR-V does not parse back: {e}"))?;
                let mut names: Vec<&str> =
                    back.entry_points.iter().map(|e| e.name.as_str()).collect();
                let mut expected = entry_names.clone();
                names.sort_unstable();
                expected.sort_unstable();
                if names != expected {
                    return Err(format!("{label}: SPIR-V entry points {names:?}"));
                }
                // The authority: SPIRV-Tools' validator, for Vulkan 1.0.
                if let Some(tool) = spirv_val {
                    let name = format!("{}.spv", blake3::hash(&bytes).to_hex());
                    external(tool, &["--target-env", "vulkan1.0"], scratch, &name, &bytes)
                        .map_err(|e| format!("{label}: {e}"))?;
                }
            }
            Target::Glsl(version) => {
                // One output per entry point, for its stage.
                if outputs.len() != module.entry_points.len() {
                    return Err(format!("{label}: {} GLSL outputs", outputs.len()));
                }
                for (output, ep) in outputs.iter().zip(&module.entry_points) {
                    let text = output.contents.as_text().unwrap();
                    let reflected = output.entry_point.as_ref().unwrap();
                    if !text.starts_with(&format!("#version {version}"))
                        || !text.contains("void main()")
                        || reflected.name != ep.name
                    {
                        return Err(format!("{label}: GLSL {version} for {}", ep.name));
                    }
                }
            }
            Target::Hlsl(_) => {
                let text = outputs[0].contents.as_text().unwrap();
                for name in &entry_names {
                    if !text.contains(name) {
                        return Err(format!("{label}: HLSL lacks {name}"));
                    }
                }
            }
            Target::Msl(..) => {
                let text = outputs[0].contents.as_text().unwrap();
                if !text.contains("#include <metal_stdlib>") || text.contains("fake") {
                    return Err(format!("{label}: MSL without real bindings"));
                }
                for name in &entry_names {
                    if !text.contains(&format!(" {name}(")) {
                        return Err(format!("{label}: MSL lacks {name}"));
                    }
                }
                // Every slot the variant's bindings got is written out.
                for slot in slots(&module, &info, &target) {
                    let attr = format!("[[{}({})]]", slot.class, slot.slot.unwrap());
                    if !text.contains(&attr) {
                        return Err(format!("{label}: MSL lacks {attr}"));
                    }
                }
            }
        }
        checked += outputs.len();
    }
    Ok(checked)
}

/// The acceptance test: every variant of the bundled library (the full space, 4612, which is
/// also the build set without materials) through WGSL (read back and validated), SPIR-V
/// (read back by naga, and validated by `spirv-val` for Vulkan 1.0), GLSL 450, 310 es and
/// 300 es, HLSL 5.1 and 6.0, and MSL 2.0 (with real Metal slots).
#[test]
fn every_target_for_every_variant_of_the_bundled_library() {
    let lib = Library::bundled().unwrap();
    let spirv_val = tool("spirv-val");
    let scratch = tempfile::tempdir().unwrap();
    let started = Instant::now();
    let mut variants = 0;
    let mut outputs = 0;
    for pass in lib.passes() {
        let choices = Space::full(pass).enumerate(1_000_000).unwrap();
        let results: Vec<Result<usize, String>> = choices
            .par_iter()
            .map(|choice| {
                let v = Variant {
                    pass,
                    choice: choice.clone(),
                };
                check_variant(&lib, &v, spirv_val.as_deref(), scratch.path())
            })
            .collect();
        let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
        assert!(
            failures.is_empty(),
            "{} failures: {failures:?}",
            failures.len()
        );
        variants += choices.len();
        outputs += results.iter().map(|r| r.as_ref().unwrap()).sum::<usize>();
    }
    assert_eq!(variants, 4612);
    println!(
        "{variants} variants x {} targets: {outputs} outputs produced and checked{} in {:.1?}",
        targets().len(),
        if spirv_val.is_some() {
            " (SPIR-V by spirv-val)"
        } else {
            ""
        },
        started.elapsed()
    );
}

/// glslang compiles the GLSL of the covering set of every pass (each keyword alone, all
/// off, all on) for desktop 450 and ES 310. (ES 300 is produced, but naga writes integer
/// `mix()` for `select()` on integer vectors, which ES 3.00 lacks without
/// GL_EXT_shader_integer_mix; the LDR decode of the bundled library uses it.)
#[test]
fn glslang_compiles_the_glsl_of_every_covering_variant() {
    let Some(glslang) = tool("glslangValidator") else {
        return;
    };
    let lib = Library::bundled().unwrap();
    let scratch = tempfile::tempdir().unwrap();
    let jobs: Vec<Variant<'_>> = lib
        .passes()
        .flat_map(|pass| {
            wgsl_variants::snapshot::covering_set(pass)
                .into_iter()
                .map(move |(_, choice)| Variant { pass, choice })
        })
        .collect();
    let results: Vec<Result<usize, String>> = jobs
        .par_iter()
        .map(|v| {
            let (module, info) = compile(&lib, v).map_err(|e| e.to_string())?;
            let mut n = 0;
            for version in ["450", "310es"] {
                let target = Target::Glsl(parse_glsl_version(version).unwrap());
                for output in translate(&module, &info, &target, &Options::default())
                    .map_err(|e| e.to_string())?
                {
                    let ep = output.entry_point.unwrap();
                    let bytes = output.contents.to_bytes();
                    let name = format!(
                        "{}.{}",
                        blake3::hash(&bytes).to_hex(),
                        target.extension(Some(ep.stage))
                    );
                    external(&glslang, &[], scratch.path(), &name, &bytes)
                        .map_err(|e| format!("{} {version} {}: {e}", v.label(), ep.name))?;
                    n += 1;
                }
            }
            Ok(n)
        })
        .collect();
    let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
    assert!(failures.is_empty(), "{failures:?}");
    let compiled: usize = results.iter().map(|r| r.as_ref().unwrap()).sum();
    println!(
        "glslang compiled {compiled} GLSL outputs of {} variants",
        jobs.len()
    );
}

#[test]
fn version_flags_parse_and_reject() {
    assert!(parse_glsl_version("450").is_ok());
    assert!(parse_glsl_version("330").is_ok());
    assert!(parse_glsl_version("310es").unwrap().is_es());
    assert!(parse_glsl_version("451").is_err());
    assert!(parse_glsl_version("es").is_err());
    assert!(parse_shader_model("6_0").is_ok());
    assert!(parse_shader_model("6.6").is_ok());
    assert!(parse_shader_model("4_0").is_err());
    assert_eq!(parse_msl_version("2.1"), Ok((2, 1)));
    assert!(parse_msl_version("2").is_err());
    assert!(parse_msl_version("9.0").is_err());
}

#[test]
fn outputs_do_not_depend_on_the_build_or_run() {
    let lib = Library::bundled().unwrap();
    let v = lib
        .variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"])
        .unwrap();
    let once = |t: &Target| {
        let (m, i) = compile(&lib, &v).unwrap();
        translate(&m, &i, t, &Options::default()).unwrap()
    };
    for t in targets() {
        assert_eq!(once(&t), once(&t), "{t}");
    }
    // The canonical WGSL is the snapshot text (snapshots/…), written by the same back end.
    let canonical = wgsl_variants::snapshot::canonical_wgsl(&lib, &v).unwrap();
    assert_eq!(
        once(&Target::Wgsl)[0].contents.as_text().unwrap(),
        canonical
    );
    // keep_coordinate_space drops the Y flip in GLSL.
    let (m, i) = compile(&lib, &v).unwrap();
    let glsl = Target::Glsl(Target::GLSL_DEFAULT);
    let kept = translate(
        &m,
        &i,
        &glsl,
        &Options {
            keep_coordinate_space: true,
        },
    )
    .unwrap();
    let vertex = |o: &[wgsl_variants::emit::backends::Output]| {
        o.iter()
            .find(|o| o.entry_point.as_ref().unwrap().stage == Stage::Vertex)
            .unwrap()
            .contents
            .as_text()
            .unwrap()
            .to_string()
    };
    assert!(vertex(&once(&glsl)).contains("gl_Position.yz = vec2(-gl_Position.y"));
    assert!(!vertex(&kept).contains("gl_Position.yz = vec2(-gl_Position.y"));
}

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
    // 2 materials: ForwardBase 2 variants; Deferred 2 × 4 multi_compile combinations.
    assert_eq!(variants.len(), 2 + 8);
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
    let lib = Library::bundled().unwrap();
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

// ---------------------------------------------------------------- bake

mod prelude_compiles {
    // The fixed part of the generated file, with an empty table: it must compile on its own.
    include!("../src/emit/bake_prelude.rs");
    static VARIANTS: &[Variant] = &[];
    static PASSES: &[Pass] = &[];

    #[test]
    fn empty_table_lookups_fail_cleanly() {
        assert_eq!(
            variant("standard", "Deferred", &[]).unwrap_err(),
            LookupError::UnknownShader("standard".into())
        );
        assert!(variants().is_empty() && passes().is_empty());
        assert_eq!(spirv_words::<2>(&[1, 0, 0, 0, 2, 0, 0, 0]), [1, 2]);
    }
}

#[test]
fn bake_writes_a_strict_lookup_table_and_rerun_lines() {
    let out = tempfile::tempdir().unwrap();
    let materials = out.path().join("materials.toml");
    std::fs::write(
        &materials,
        "[[material]]\nname = \"Bricks\"\nshader = \"standard\"\nkeywords = [\"_NORMAL_MAP\"]\n\n[[material]]\nname = \"Final\"\nshader = \"deferred_final\"\n",
    )
    .unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("wgsl");
    let baked = Bake::new(&root)
        .materials(&materials)
        .target(BakeTarget::Wgsl)
        .target(BakeTarget::SpirV)
        .write_to(out.path())
        .unwrap();
    // standard: ForwardBase 1 + Deferred 1 × 4; deferred_final/Final 1; deferred_reflections
    // has no material, so it is not baked.
    assert_eq!(baked.variants, 6);
    assert_eq!(baked.outputs, 12);
    assert!(baked.rerun_if_changed.contains(&root));
    assert!(baked.rerun_if_changed.contains(&materials));
    assert!(
        baked
            .rerun_if_changed
            .contains(&root.join("deferred/gbuffer.wgsl"))
    );
    assert_eq!(baked.rerun_if_changed.len(), 2 + 11);
    let code = std::fs::read_to_string(&baked.file).unwrap();
    assert!(code.starts_with("// @generated by wgsl-variants"));
    assert!(code.contains("pub fn variant("));
    assert!(code.contains("keywords: &[\"_NORMAL_MAP\", \"UNITY_HDR_ON\"]"));
    assert!(code.contains("spirv_words::<"));
    assert_eq!(code.matches("    Variant {\n").count(), 6);
    // deferred_reflections is listed as a pass with nothing baked: lookups say "not baked".
    assert!(code.contains("shader: \"deferred_reflections\""));
    let blobs = std::fs::read_dir(out.path().join("wgsl_variants"))
        .unwrap()
        .count();
    assert_eq!(blobs, 12);

    // Rebaking with fewer outputs removes the stale ones, and an unchanged file keeps its time.
    let again = Bake::new(&root)
        .materials(&materials)
        .write_to(out.path())
        .unwrap();
    assert_eq!(again.outputs, 6);
    assert_eq!(
        std::fs::read_dir(out.path().join("wgsl_variants"))
            .unwrap()
            .count(),
        6
    );
    let modified = std::fs::metadata(&again.file).unwrap().modified().unwrap();
    Bake::new(&root)
        .materials(&materials)
        .write_to(out.path())
        .unwrap();
    assert_eq!(
        std::fs::metadata(&again.file).unwrap().modified().unwrap(),
        modified
    );
}

#[test]
fn bake_fails_with_rendered_diagnostics() {
    let root = tempfile::tempdir().unwrap();
    std::fs::write(
        root.path().join("s.wgsl"),
        "#shader s\n#pass P\n#pragma multi_compile _ A\n@fragment\nfn fs() -> @location(0) vec4f {\n#if A\n    return vec2f(1.0);\n#else\n    return vec4f(1.0);\n#endif\n}\n#endpass\n",
    )
    .unwrap();
    let out = tempfile::tempdir().unwrap();
    let e = Bake::new(root.path()).write_to(out.path()).unwrap_err();
    let text = e.to_string();
    assert!(text.contains("s.wgsl:7:"), "{text}");
    assert!(text.contains("in variant s/P {A}"), "{text}");
    assert!(
        text.contains("1 of 2 variants failed to build; nothing was baked"),
        "{text}"
    );
    assert!(!out.path().join("wgsl_variants.rs").exists());

    // A library that does not load, and a materials file that does not fit, fail the same way.
    std::fs::write(
        root.path().join("s.wgsl"),
        "#shader s\n#pass P\n#if\n#endpass\n",
    )
    .unwrap();
    let e = Bake::new(root.path()).write_to(out.path()).unwrap_err();
    assert!(e.to_string().contains("s.wgsl:3:"), "{e}");
    let materials = root.path().join("m.toml");
    std::fs::write(
        &materials,
        "[[material]]\nname = \"X\"\nshader = \"nope\"\n",
    )
    .unwrap();
    let e = Bake::bundled()
        .materials(&materials)
        .write_to(out.path())
        .unwrap_err();
    assert!(e.to_string().contains("nope"), "{e}");
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
