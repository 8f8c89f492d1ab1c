//! Every naga back end for every variant of the bundled library, `emit --out` with its
//! manifest, and the build.rs API (`wgsl_variants::bake`). Needs every back end (the default
//! features).
#![cfg(all(
    feature = "spv-out",
    feature = "glsl-out",
    feature = "hlsl-out",
    feature = "msl-out"
))]

use rayon::prelude::*;
use std::path::Path;
use std::process::Command;
use std::time::Instant;
use wgsl_variants::bake::{Bake, BakeTarget};
use wgsl_variants::emit::backends::{
    Contents, Options, Target, parse_glsl_version, parse_msl_version, parse_shader_model, slots,
    translate,
};
use wgsl_variants::reflect::Stage;
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

use wgsl_variants::validate::{compile, validator};

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

/// Every target for every variant of `plan`: WGSL (read back and validated), SPIR-V (read back
/// by naga, and validated by `spirv-val` for Vulkan 1.0), GLSL 450, 310 es and 300 es, HLSL 5.1
/// and 6.0, and MSL 2.0 (with real Metal slots). Returns the number of variants.
fn every_target_for(lib: &Library, plan: &wgsl_variants::plan::Plan<'_>) -> usize {
    let spirv_val = tool("spirv-val");
    let scratch = tempfile::tempdir().unwrap();
    let started = Instant::now();
    let mut variants = 0;
    let mut outputs = 0;
    for (pass, choices) in plan {
        let results: Vec<Result<usize, String>> = choices
            .par_iter()
            .map(|choice| {
                let v = Variant {
                    pass,
                    choice: choice.clone(),
                };
                check_variant(lib, &v, spirv_val.as_deref(), scratch.path())
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
    variants
}

/// The acceptance test, as CI runs it: every target for the tests' selection of the bundled
/// library (`test_support::selection`: every variant of each pass of up to 8192 variants, a
/// t = 3 covering set of the larger ones: the three lit standard passes and URP's two).
#[test]
fn every_target_for_the_selection_of_the_bundled_library() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let plan = test_support::selection::plan_of(&lib);
    let expected: usize = plan.iter().map(|(_, c)| c.len()).sum();
    assert_eq!(every_target_for(&lib, &plan), expected);
    // Every pass is in it, and only the large ones are covered rather than built whole.
    for (pass, choices) in &plan {
        let space = Space::full(pass).enumerate(1_000_000).unwrap().len();
        if space as u64 <= test_support::selection::FULL_UP_TO {
            assert_eq!(choices.len(), space, "{}/{}", pass.shader, pass.name);
        } else {
            assert!(choices.len() < space / 50, "{}/{}", pass.shader, pass.name);
        }
    }
}

/// The acceptance test over the full space: every variant of the bundled library (1020582, which
/// is also the build set without materials) through every target. About 9 minutes on 2 cores
/// at 150,967 variants (2026-11-27), so about an hour now (by that rate):
/// `cargo test --release --test emit -- --ignored`.
#[test]
#[ignore = "the full space (1020582 variants x 8 targets): cargo test --release --test emit -- --ignored"]
fn every_target_for_every_variant_of_the_bundled_library() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let mut options = wgsl_variants::plan::PlanOptions::default();
    options.all = true;
    let plan = wgsl_variants::plan::plan(&lib, &options).unwrap();
    assert_eq!(every_target_for(&lib, &plan), 1_020_582);
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
    let lib = wgsl_variants_shaders::library().unwrap();
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
    let lib = wgsl_variants_shaders::library().unwrap();
    let v = lib
        .variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"])
        .unwrap();
    let once = |t: &Target| {
        let (m, i) = compile(&lib, &v).unwrap();
        translate(&m, &i, t, &Options::default()).unwrap()
    };
    // A digest of every target's outputs, checked against a committed snapshot: a hash-map
    // order or an address leaking into an output would differ between processes (std's
    // hashers are seeded per process) and fail here. Regenerate with `cargo insta review`
    // when naga changes its output.
    let digests: String = targets()
        .iter()
        .map(|t| {
            let mut hasher = blake3::Hasher::new();
            for output in once(t) {
                hasher.update(&output.contents.to_bytes());
            }
            format!("{t}: {}\n", hasher.finalize().to_hex())
        })
        .collect();
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        insta::assert_snapshot!("backend_digests", digests);
    });
    // The canonical WGSL is the snapshot text (snapshots/…), written by the same back end.
    let canonical = wgsl_variants::snapshot::canonical_wgsl(&lib, &v).unwrap();
    assert_eq!(
        once(&Target::Wgsl)[0].contents.as_text().unwrap(),
        canonical
    );
    // keep_coordinate_space drops the Y flip in GLSL.
    let (m, i) = compile(&lib, &v).unwrap();
    let glsl = Target::Glsl(Target::GLSL_DEFAULT);
    let kept = translate(&m, &i, &glsl, &{
        let mut o = Options::default();
        o.keep_coordinate_space = true;
        o
    })
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

// ---------------------------------------------------------------- bake
mod prelude_compiles {
    // The fixed part of the generated file, with an empty table: it must compile on its own.
    include!("../src/bake/prelude.rs");
    static VARIANTS: &[Variant] = &[];
    static PASSES: &[Pass] = &[];

    #[test]
    fn empty_table_lookups_fail_cleanly() {
        assert_eq!(
            variant("standard", "Deferred", &[]).unwrap_err(),
            LookupError::UnknownShader("standard".into())
        );
        assert!(variants().is_empty() && passes().is_empty());
    }

    /// Two words, 1 and 2, little-endian.
    static TWO_WORDS: &[u32] = spirv_words!(
        2,
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/fixtures/bake/two_words.spv"
        )
    );

    #[test]
    fn spirv_files_are_read_as_words() {
        assert_eq!(TWO_WORDS, [1, 2]);
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
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/wgsl-variants-shaders/wgsl");
    let baked = Bake::new(&root)
        .materials(&materials)
        .target(BakeTarget::Wgsl)
        .target(BakeTarget::SpirV)
        .write_to(out.path())
        .unwrap();
    // standard: ForwardBase 1 × 2 (SHADOWS_SCREEN) × 3 (BRDF tier) × 6 (lightmaps) + ForwardAdd
    // 1 × 16 light and shadow combinations × 3 + Deferred 1 × 8 (HDR, reflection buffers,
    // shadowmask) × 3 × 6 + ShadowCaster 2; deferred_final/Final 1; deferred_reflections and
    // deferred_shading have no material, so they are not baked.
    assert_eq!(baked.variants, 231);
    // 174 distinct texts: SHADOWS_SOFT without a shadow keyword repeats 3 of ForwardAdd's per
    // tier (39 of 48), and with reflection buffers the tier changes nothing in Deferred (16 of
    // 24, times 6 lightmap combinations: 96); ForwardBase 36, ShadowCaster 2, Final 1. WGSL
    // and SPIR-V each.
    assert_eq!(baked.outputs, 348);
    assert!(baked.rerun_if_changed.contains(&root));
    assert!(baked.rerun_if_changed.contains(&materials));
    assert!(
        baked
            .rerun_if_changed
            .contains(&root.join("deferred/gbuffer.wgsl"))
    );
    // The library folder, the materials file and its 46 module files.
    assert_eq!(baked.rerun_if_changed.len(), 2 + 46);
    let code = std::fs::read_to_string(&baked.file).unwrap();
    assert!(code.starts_with("// @generated by wgsl-variants"));
    assert!(code.contains("pub fn variant("));
    assert!(code.contains("keywords: &[\"_NORMAL_MAP\", \"UNITY_HDR_ON\"]"));
    assert!(code.contains("spirv_words!("));
    assert_eq!(code.matches("    Variant {\n").count(), 231);
    // deferred_reflections is listed as a pass with nothing baked: lookups say "not baked".
    assert!(code.contains("shader: \"deferred_reflections\""));
    let blobs = std::fs::read_dir(out.path().join("wgsl_variants"))
        .unwrap()
        .count();
    assert_eq!(blobs, 348);

    // Rebaking with fewer outputs removes the stale ones, and an unchanged file keeps its time.
    let again = Bake::new(&root)
        .materials(&materials)
        .write_to(out.path())
        .unwrap();
    assert_eq!(again.outputs, 174);
    assert_eq!(
        std::fs::read_dir(out.path().join("wgsl_variants"))
            .unwrap()
            .count(),
        174
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
    let e = wgsl_variants_shaders::bake()
        .materials(&materials)
        .write_to(out.path())
        .unwrap_err();
    assert!(e.to_string().contains("nope"), "{e}");
}

/// `Bake::cover(2)` bakes each pass's pairwise covering set: 240 variants of the bundled
/// library (12 of Deferred's 110592, 13 of ForwardBase's 55296, 64 of ForwardAdd's 18432, 4 of
/// each ShadowCaster's 8, 10 of UniversalGBuffer's 49152, 16 of UniversalForward's 786432, 8 of
/// PunctualLit's 96, 39 of DirectionalLit's 156, 48 of Lighting's 384, 4 of Collect's 8, the
/// smallest passes whole, URP's ScreenSpaceShadows' 4, DepthOnly's 4 and SSAOOnly's 2 among
/// them); with `cover_above(1600)` the
/// ShadowCasters, URP's lighting passes, the built-in lighting pass and Collect are baked whole
/// and the larger passes are still covered.
#[test]
fn bake_cover_bakes_the_covering_sets() {
    let out = tempfile::tempdir().unwrap();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/wgsl-variants-shaders/wgsl");
    let baked = Bake::new(&root)
        .cover(2)
        .target(BakeTarget::Wgsl)
        .write_to(out.path())
        .unwrap();
    assert_eq!(baked.variants, 240);
    let code = std::fs::read_to_string(&baked.file).unwrap();
    assert_eq!(code.matches("    Variant {\n").count(), 240);
    let mixed = Bake::new(&root)
        .cover(2)
        .cover_above(1600)
        .target(BakeTarget::Wgsl)
        .write_to(tempfile::tempdir().unwrap().path())
        .unwrap();
    assert_eq!(
        mixed.variants,
        240 - 4 - 4 - 8 - 39 - 48 - 4 + 8 + 8 + 96 + 156 + 384 + 8
    );
}
