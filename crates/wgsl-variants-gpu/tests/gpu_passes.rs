//! The GPU proof of the bundled passes: `standard/Deferred` (110592 variants) and
//! `standard/ForwardBase` (55296) rendered on the test scene and compared pixel by pixel with the
//! CPU reference — in CI a 3-wise covering set of each with a partner per keyword (every keyword
//! judged), every variant in the `--ignored` tests — then the deferred reflection, add and final
//! passes (`check::run`).
//!
//! They need a wgpu adapter (Mesa's lavapipe is enough: `apt-get install mesa-vulkan-drivers`).
//! Without one they print a loud SKIPPED line and pass, unless `CI=true` or
//! `WGSL_VARIANTS_REQUIRE_GPU=1`, in which case they fail. `WGSL_VARIANTS_ADAPTER=<substring>`
//! selects an adapter by name.
//!
//! The full spaces take minutes on lavapipe with a cold Mesa shader cache (compiling a pipeline
//! per variant dominates) and much less with a warm one; CI runs the covering sets, and
//! `cargo test --release -p wgsl-variants-gpu --test gpu_passes -- --ignored` (or
//! `wgsl-variants check-gpu --shader standard --full`) checks every variant. For a quick
//! local look, `WGSL_VARIANTS_GPU_SAMPLE=N` checks every N-th variant only (keyword coverage is
//! then not judged).

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport, TestScene, pictures};

/// Every n-th variant of the standard passes (`WGSL_VARIANTS_GPU_SAMPLE`, default 1: all).
fn sample() -> usize {
    std::env::var("WGSL_VARIANTS_GPU_SAMPLE")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(1usize)
        .max(1)
}

/// Runs the check; `None` (after a loud message) when there is no adapter and none is required.
fn run(
    lib: &Library,
    shader: Option<&str>,
    pass: Option<&str>,
    sample: usize,
) -> Option<CheckReport> {
    run_shard(lib, shader, pass, sample, None)
}

/// [`run`] for one shard of the variants.
fn run_shard(
    lib: &Library,
    shader: Option<&str>,
    pass: Option<&str>,
    sample: usize,
    shard: Option<wgsl_variants::variants::Shard>,
) -> Option<CheckReport> {
    run_options(lib, shader, pass, |options| {
        options.sample = sample;
        options.shard = shard;
    })
}

/// Runs the check of `shader`/`pass` with the options `set` chooses.
fn run_options(
    lib: &Library,
    shader: Option<&str>,
    pass: Option<&str>,
    set: impl FnOnce(&mut CheckOptions),
) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = shader.map(str::to_owned);
    options.pass = pass.map(str::to_owned);
    options.adapter = common::gpu::adapter_filter();
    options.threads = 0;
    set(&mut options);
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

/// Asserts a passing report with the expected variant count and prints what it compared.
fn assert_pass(report: &CheckReport, shader: &str, pass: &str, variants: usize) {
    let p = report
        .passes
        .iter()
        .find(|p| p.shader == shader && p.pass == pass)
        .unwrap_or_else(|| panic!("no report for {shader}/{pass}:\n{report}"));
    eprintln!(
        "{shader}/{pass} on {}: compared {} pixels over {} variants ({} draws, {} discarded pixels) in {:.1} s",
        report.adapter, p.pixels_compared, p.variants_run, p.draws, p.discarded_compared, p.seconds
    );
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    assert_eq!(p.variants_run, variants, "{report}");
    assert!(p.pixels_compared > 0 && p.draws > 0, "{report}");
}

/// Every variant of `standard/Deferred` (110592; CI runs
/// [`deferred_covering_set_matches_the_reference`] instead). In one process lavapipe keeps most
/// of a megabyte per compiled variant, far past a small machine's memory, so there the whole
/// space runs as shard processes (`scripts/check-gpu-full.sh`, docs/guide/gpu-proof.md) and
/// this test with a sample (`WGSL_VARIANTS_GPU_SAMPLE=64`: every 64th variant).
#[test]
#[ignore = "the full space: cargo test --release -p wgsl-variants-gpu --test gpu_passes -- --ignored"]
fn deferred_every_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let n = sample();
    let Some(report) = run_options(&lib, Some("standard"), Some("Deferred"), |o| {
        o.sample = n;
        o.full = true;
    }) else {
        return;
    };
    let variants = 110_592usize.div_ceil(n);
    assert_pass(&report, "standard", "Deferred", variants);
    let p = &report.passes[0];
    // 16 × 16 pixels × 4 targets per variant, 5 for the half with SHADOWS_SHADOWMASK (RT4);
    // cutout discards some pixels.
    if n == 1 {
        assert_eq!(p.pixels_compared, (110_592 * 4 + 55_296) * 256);
    }
    assert!(p.discarded_compared > 0);
    assert_eq!(p.keywords.len(), 18, "every keyword of the pass is covered");
    assert!(p.untested_keywords.is_empty(), "{report}");
}

/// CI's form of the full-space test above: Deferred's covering set with keyword partners.
#[test]
fn deferred_covering_set_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(p) = common::gpu::standard_covering_set_matches(&lib, "Deferred", 18) else {
        return;
    };
    // 4 targets per variant, 5 with RT4; some of each; cutout discards some pixels.
    assert!(p.discarded_compared > 0);
    let v = p.variants_run * 256;
    assert!(p.pixels_compared > 4 * v && p.pixels_compared < 5 * v);
}

/// CI's form of the full-space test below: ForwardBase's covering set with keyword partners.
#[test]
fn forward_base_covering_set_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(p) = common::gpu::standard_covering_set_matches(&lib, "ForwardBase", 18) else {
        return;
    };
    assert!(p.discarded_compared > 0);
    assert_eq!(p.pixels_compared, p.variants_run * 256);
}

/// Every variant of `standard/ForwardBase` (55296; CI runs
/// [`forward_base_covering_set_matches_the_reference`] instead; on a small machine with lavapipe
/// the whole space runs as shard processes, as for Deferred above).
#[test]
#[ignore = "the full space: cargo test --release -p wgsl-variants-gpu --test gpu_passes -- --ignored"]
fn forward_base_every_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let n = sample();
    let Some(report) = run_options(&lib, Some("standard"), Some("ForwardBase"), |o| {
        o.sample = n;
        o.full = true;
    }) else {
        return;
    };
    let variants = 55_296usize.div_ceil(n);
    assert_pass(&report, "standard", "ForwardBase", variants);
    let p = &report.passes[0];
    assert_eq!(p.pixels_compared, variants * 256);
    assert_eq!(p.keywords.len(), 18, "every keyword of the pass is covered");
    assert!(p.untested_keywords.is_empty(), "{report}");
}

#[test]
fn deferred_reflections_add_and_final_match_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, Some("deferred_reflections"), None, 1) else {
        return;
    };
    // The reflections pass in each BRDF tier; each tier keyword changes the buffer.
    assert_pass(&report, "deferred_reflections", "Reflections", 3);
    assert_pass(&report, "deferred_reflections", "Add", 2);
    for p in &report.passes[..2] {
        assert!(!p.keywords.is_empty(), "{report}");
        assert!(p.keywords.iter().all(|k| k.pairs_changed > 0), "{report}");
    }
    let Some(report) = run(&lib, Some("deferred_final"), None, 1) else {
        return;
    };
    assert_pass(&report, "deferred_final", "Final", 1);
    // The 32 × 32 ramp of every 10-bit value plus the scene's RT3.
    assert!(report.passes[0].pixels_compared >= 1024 + 256);
}

/// `skybox/Cubemap` into HDR and LDR targets matches the reference over five faces, their
/// edges and a corner; the reference of a sky turned the wrong way, or decoded without its
/// RGBM alpha, fails against the same pictures.
#[test]
fn the_skybox_matches_the_reference_and_a_wrong_sky_fails() {
    use wgsl_variants_gpu::TargetFormat;
    use wgsl_variants_gpu::check::report::PassReport;
    use wgsl_variants_gpu::check::skybox::{Sky, check_sky};
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, Some("skybox"), None, 1) else {
        return;
    };
    assert_pass(&report, "skybox", "Cubemap", 1);
    assert_eq!(report.passes[0].pixels_compared, 2 * 64 * 48, "{report}");
    let ctx = wgsl_variants_gpu::GpuContext::new(common::gpu::adapter_filter().as_deref())
        .expect("the check ran on this adapter");
    let sky = Sky::check();
    let turned = wgsl_variants_shaders::reference::skybox::Skybox {
        rotation_degrees: -sky.skybox.rotation_degrees,
        ..sky.skybox
    };
    let mut no_alpha = sky.skybox;
    no_alpha.decode.w = 0.0;
    for (what, wrong) in [
        ("turned the wrong way", turned),
        ("RGBM alpha ignored", no_alpha),
    ] {
        for format in [TargetFormat::Rgba16Float, TargetFormat::Rgba8Unorm] {
            let mut r = PassReport::new("skybox", "Cubemap");
            check_sky(&ctx, &lib, &sky, &wrong, format, &mut r).expect("the sky renders");
            eprintln!(
                "a sky {what}, {format:?}: {} of {} pixels caught",
                r.mismatches, r.pixels_compared
            );
            assert!(
                r.mismatches > 100,
                "a sky {what} ({format:?}) was not caught: {r:?}"
            );
        }
    }
}

/// The check is not vacuous: a library whose BRDF is off by a little (dielectric specular 0.05
/// instead of 0.04) fails it, and the mismatch names the shader, pass, keyword set, target and
/// pixel.
#[test]
fn a_wrong_library_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "lighting/brdf.wgsl",
        "const BRDF_DIELECTRIC_SPEC: f32 = 0.04;",
        "const BRDF_DIELECTRIC_SPEC: f32 = 0.05;",
    );
    let Some(report) = run(&lib, Some("standard"), Some("ForwardBase"), 97) else {
        return;
    };
    assert!(!report.passed());
    let p = &report.passes[0];
    assert!(p.mismatches > 0);
    let m = &p.first_mismatches[0];
    assert_eq!(
        (m.shader.as_str(), m.pass.as_str()),
        ("standard", "ForwardBase")
    );
    assert!(
        m.keywords.starts_with('{') && m.target.contains("Rgba8Unorm"),
        "{m}"
    );
    let text = m.to_string();
    assert!(
        text.contains("pixel (") && text.contains("expected"),
        "{text}"
    );
    eprintln!(
        "a wrong library is caught: {} mismatches, e.g. {m}",
        p.mismatches
    );
}

/// The lightmaps are checked: a baked lightmap decoded with RGBM's gamma-space range (5) where
/// its linear-space range (5^2.2 = 34.49) belongs fails the Deferred covering set, in the
/// `LIGHTMAP_ON` variants only.
#[test]
fn a_lightmap_decoded_with_the_wrong_range_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "standard/my_lighting.wgsl",
        "lightmap_sampler, luv), lightmap.decode)",
        "lightmap_sampler, luv), lightmap.decode * vec4f(5.0 / 34.493242, 1.0, 1.0, 1.0))",
    );
    let Some(report) = run_options(&lib, Some("standard"), Some("Deferred"), |o| {
        o.cover = Some(3);
    }) else {
        return;
    };
    assert!(!report.passed());
    let p = &report.passes[0];
    assert!(p.mismatches > 0);
    assert!(
        common::mutate::caught_in(&report)
            .iter()
            .all(|k| k.contains("LIGHTMAP_ON")),
        "{report}"
    );
    eprintln!(
        "a lightmap with the wrong range is caught: {} mismatches",
        p.mismatches
    );
}

#[test]
fn pictures_are_written() {
    let ctx = match wgsl_variants_gpu::GpuContext::new(
        std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref(),
    ) {
        Ok(ctx) => ctx,
        Err(e) => {
            let required = std::env::var("CI").is_ok_and(|v| v == "true")
                || std::env::var("WGSL_VARIANTS_REQUIRE_GPU").is_ok_and(|v| v == "1");
            assert!(!required, "a GPU adapter is required: {e}");
            eprintln!("SKIPPED: no GPU adapter: {e}");
            return;
        }
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let dir = tempfile::tempdir().unwrap();
    let pics = pictures::render_pictures(
        &ctx,
        &lib,
        &scene,
        "standard",
        "Deferred",
        &pictures::DEFAULT_KEYWORDS.names(),
    )
    .unwrap();
    let names: Vec<&str> = pics.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "albedo",
            "occlusion",
            "specular",
            "smoothness",
            "normal",
            "emission",
            "reflections",
            "final"
        ]
    );
    for p in &pics {
        let path = p.write_png(dir.path(), 4).unwrap();
        let image = image::open(&path).unwrap();
        assert_eq!(
            (image.width(), image.height()),
            (scene.width * 4, scene.height * 4)
        );
    }
    let forward = pictures::render_pictures(
        &ctx,
        &lib,
        &scene,
        "standard",
        "ForwardBase",
        &["_NORMAL_MAP"],
    )
    .unwrap();
    assert_eq!(forward.len(), 2);
    assert!(pictures::render_pictures(&ctx, &lib, &scene, "deferred_final", "Final", &[]).is_err());
}

/// The tiers' indirect specular is checked: BRDF2's surface reduction with 0.09 for 0.08 fails
/// the reflections pass in its BRDF2 variant only.
#[test]
fn a_wrong_indirect_specular_fails_the_reflections_check() {
    let lib = common::mutate::bundled_with(
        "lighting/brdf.wgsl",
        "(0.6 - 0.08 * pr)",
        "(0.6 - 0.09 * pr)",
    );
    let Some(report) = run(&lib, Some("deferred_reflections"), Some("Reflections"), 1) else {
        return;
    };
    let p = &report.passes[0];
    assert!(p.mismatches > 0 && !report.passed(), "{report}");
    for k in common::mutate::caught_in(&report) {
        assert!(k.contains("UNITY_PBS_USE_BRDF2"), "{k}");
    }
    eprintln!(
        "a wrong BRDF2 surface reduction is caught: {} mismatches",
        p.mismatches
    );
}

#[test]
fn shards_of_the_gpu_check_add_up_to_the_whole() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let variants = |shard: Option<&str>| -> Option<u64> {
        let report = run_shard(
            &lib,
            Some("standard"),
            Some("ForwardBase"),
            2,
            shard.map(|s| s.parse().unwrap()),
        )?;
        let p = report.passes.iter().find(|p| p.pass == "ForwardBase")?;
        assert_eq!(p.mismatches, 0);
        Some(p.variants_run as u64)
    };
    let Some(whole) = variants(None) else { return };
    let parts: u64 = ["1/3", "2/3", "3/3"]
        .iter()
        .map(|s| variants(Some(s)).unwrap_or(0))
        .sum();
    // Every other variant of ForwardBase's covering set (the pass is past the default
    // covering threshold).
    assert!(whole >= 20, "{whole}");
    assert_eq!(parts, whole);
}
