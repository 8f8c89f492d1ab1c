//! The GPU proof of the per-pixel lights: every variant of `deferred_shading/Lighting` (384) and
//! of `standard/ForwardAdd` (18432; in CI a 3-wise covering set with keyword partners, every
//! variant with `-- --ignored`), shadowed ones over maps `standard/ShadowCaster` rendered, rendered on lavapipe (or any GPU) and compared pixel by pixel
//! with the CPU reference (`wgsl_variants_shaders::reference::light`), each keyword proven to change at
//! least one pixel; and libraries with planted bugs (a wrong falloff, PCF weight, BRDF term,
//! shadowmask mix or fade distance) are caught where they show, each over the lighting pass's
//! pairwise covering set ([`PLANT_COVER`]: every plant needs at most two keywords on together
//! to show, and a mutated library compiles anew).
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`): without an adapter the tests
//! print SKIPPED and pass, unless `CI=true` or `WGSL_VARIANTS_REQUIRE_GPU=1`.
//! `WGSL_VARIANTS_GPU_SAMPLE=N` checks every N-th ForwardAdd variant only.

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport};

/// Every variant of `shader/pass` (every `sample`-th), whatever the pass's size.
fn run(lib: &Library, shader: &str, pass: &str, sample: usize) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.full = true;
    options.shader = Some(shader.to_owned());
    options.pass = Some(pass.to_owned());
    options.adapter = common::gpu::adapter_filter();
    options.sample = sample;
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

/// The covering strength a planted bug's run of `deferred_shading/Lighting` uses.
const PLANT_COVER: usize = 2;

fn sample() -> usize {
    std::env::var("WGSL_VARIANTS_GPU_SAMPLE")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(1usize)
        .max(1)
}

#[test]
fn deferred_shading_every_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, "deferred_shading", "Lighting", 1) else {
        return;
    };
    let p = &report.passes[0];
    eprintln!(
        "deferred_shading/Lighting on {}: {} pixels over {} variants ({} draws) in {:.1} s",
        report.adapter, p.pixels_compared, p.variants_run, p.draws, p.seconds
    );
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    assert_eq!(p.variants_run, 384);
    // Every variant over two G-buffers of its HDR mode (with RT4 for SHADOWS_SHADOWMASK),
    // 16 × 16 pixels each.
    assert_eq!((p.draws, p.pixels_compared), (768, 768 * 256));
    // Four light keywords against POINT (the set's first), SHADOWS_DEPTH, SHADOWS_CUBE,
    // SHADOWS_SCREEN, SHADOWS_SOFT, SHADOWS_SHADOWMASK, LIGHTMAP_SHADOW_MIXING, UNITY_HDR_ON
    // and the BRDF tiers UNITY_PBS_USE_BRDF2 and UNITY_PBS_USE_BRDF3.
    assert_eq!(p.keywords.len(), 13, "{report}");
    for k in &p.keywords {
        eprintln!(
            "  {}: {} of {} pairs changed",
            k.keyword, k.pairs_changed, k.pairs
        );
        if k.keyword == "SHADOWS_SOFT" {
            // Only with a shadow keyword: without one it changes nothing (those 24 variants
            // per BRDF tier are duplicates, as in Unity); with one, every pair changes.
            assert_eq!((k.pairs, k.pairs_changed), (144, 72), "{report}");
        } else if k.keyword == "LIGHTMAP_SHADOW_MIXING" {
            // Only with a realtime shadow: min(saturate(realtime + fade), baked) against
            // lerp(realtime, baked, fade), which differ wherever the shadow fades part way.
            assert_eq!((k.pairs, k.pairs_changed), (192, 96), "{report}");
        } else {
            assert!(k.pairs_changed == k.pairs && k.pairs > 0, "{report}");
        }
    }
    for note in &p.notes {
        eprintln!("  note: {note}");
    }
    assert!(p.untested_keywords.is_empty(), "{report}");
}

/// CI's form of the full-space test below: a 3-wise covering set of `standard/ForwardAdd`
/// plus a partner per keyword whose reference says it matters; every keyword is judged.
#[test]
fn forward_add_covering_set_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    // 4 light keywords (against DIRECTIONAL), 4 shadow keywords, 10 material keywords.
    let Some(p) = common::gpu::standard_covering_set_matches(&lib, "ForwardAdd", 20) else {
        return;
    };
    assert_eq!(p.pixels_compared, p.variants_run * 256);
}

/// Every variant of `standard/ForwardAdd` (18432, 13104 distinct texts; many minutes on
/// lavapipe with a cold shader cache, so CI runs the covering set above).
#[test]
#[ignore = "the full space: cargo test --release -p wgsl-variants-gpu --test gpu_lights -- --ignored"]
fn forward_add_every_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let n = sample();
    let Some(report) = run(&lib, "standard", "ForwardAdd", n) else {
        return;
    };
    let p = &report.passes[0];
    let variants = 18432usize.div_ceil(n);
    eprintln!(
        "standard/ForwardAdd on {}: {} pixels over {} variants ({} discarded) in {:.1} s",
        report.adapter, p.pixels_compared, p.variants_run, p.discarded_compared, p.seconds
    );
    assert_eq!(p.mismatches, 0, "{report}");
    assert_eq!(p.variants_run, variants, "{report}");
    assert_eq!(p.pixels_compared, variants * 256);
    if n == 1 {
        // 4 light keywords (against DIRECTIONAL), 4 shadow keywords, 10 material keywords,
        // 2 BRDF tiers.
        assert_eq!(p.keywords.len(), 20, "{report}");
        assert!(p.untested_keywords.is_empty(), "{report}");
        assert!(p.passed(), "{report}");
    }
}

/// Runs the lighting pass's check on a mutated `lib` and asserts that it fails, every listed
/// mismatch passing `expected`; returns how many mismatches there were (`None`: skipped).
fn lighting_check_fails(lib: &Library, expected: impl Fn(&str) -> bool) -> Option<usize> {
    let mut options = CheckOptions::default();
    options.shader = Some("deferred_shading".to_owned());
    options.pass = Some("Lighting".to_owned());
    options.adapter = common::gpu::adapter_filter();
    options.cover = Some(PLANT_COVER);
    let report = common::gpu::or_skip(check::run(lib, &options), "the GPU check")?;
    let p = &report.passes[0];
    let note = format!(
        "{PLANT_COVER}-wise covering set of {} of the",
        p.variants_run
    );
    assert!(p.notes.iter().any(|n| n.starts_with(&note)), "{report}");
    assert!(p.mismatches > 0 && !report.passed());
    let caught = common::mutate::caught_in(&report);
    assert!(caught.iter().all(|k| expected(k)), "{report}");
    Some(p.mismatches)
}

/// The check is not vacuous: a falloff of 1/(1 + 24t) instead of 1/(1 + 25t) fails it, in the
/// point and spot variants.
#[test]
fn a_wrong_falloff_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "lighting/light.wgsl",
        "/ (1.0 + 25.0 * t)",
        "/ (1.0 + 24.0 * t)",
    );
    let caught = lighting_check_fails(&lib, |k| k.contains("POINT") || k.contains("SPOT"));
    if let Some(n) = caught {
        eprintln!("a wrong falloff is caught: {n} mismatches");
    }
}

/// The shadow check is not vacuous: a PCF tent whose centre weighs 3/16 instead of 4/16 fails
/// it, in the soft spot variants only.
#[test]
fn a_wrong_pcf_weight_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "lighting/shadow.wgsl",
        "4.0 * textureSampleCompareLevel",
        "3.0 * textureSampleCompareLevel",
    );
    let caught = lighting_check_fails(&lib, |k| k.contains("SHADOWS_SOFT") && k.contains("SPOT"));
    if let Some(n) = caught {
        eprintln!("a wrong PCF weight is caught: {n} mismatches");
    }
}

/// The BRDF tiers are each checked: a planted fault in one tier's direct term fails the
/// lighting check in that tier's variants only — BRDF1's Smith-joint visibility with 0.45 for 0.5,
/// BRDF2's lobe with `a + 0.6` for `a + 0.5`, BRDF3's lookup table read with its axes swapped.
#[test]
fn a_wrong_brdf_term_fails_the_check_in_its_tier() {
    let tier_of = |k: &str| {
        if k.contains("UNITY_PBS_USE_BRDF2") {
            2
        } else if k.contains("UNITY_PBS_USE_BRDF3") {
            3
        } else {
            1
        }
    };
    let faults = [
        (
            1,
            "lighting/direct.wgsl",
            "let vis = 0.5 / (lambda_v",
            "let vis = 0.45 / (lambda_v",
        ),
        (2, "lighting/direct.wgsl", "(a + 0.5)", "(a + 0.6)"),
        (
            3,
            "lighting/brdf_lut.wgsl",
            "vec2f(x, pr) * vec2f(size)",
            "vec2f(pr, x) * vec2f(size)",
        ),
    ];
    for (tier, file, from, to) in faults {
        let lib = common::mutate::bundled_with(file, from, to);
        let caught = lighting_check_fails(&lib, |k| tier_of(k) == tier);
        if let Some(n) = caught {
            eprintln!("a wrong BRDF{tier} term is caught: {n} mismatches");
        }
    }
}

/// The shadowmask check is not vacuous: a Shadowmask mode that takes the lighter of the
/// realtime and baked shadows fails it, in the mixing variants with a realtime shadow only
/// (without SHADOWS_SHADOWMASK too: baked is 1 there, so `max` drops the realtime shadow).
#[test]
fn a_wrong_shadowmask_mix_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "lighting/shadow_fade.wgsl",
        "return min(saturate(realtime + fade), baked);",
        "return max(saturate(realtime + fade), baked);",
    );
    let caught = lighting_check_fails(&lib, |k| {
        k.contains("LIGHTMAP_SHADOW_MIXING")
            && ["SHADOWS_DEPTH", "SHADOWS_CUBE", "SHADOWS_SCREEN"]
                .iter()
                .any(|s| k.contains(s))
    });
    if let Some(n) = caught {
        eprintln!("a wrong shadowmask mix is caught: {n} mismatches");
    }
}

/// The shadow distance fade is checked: a fade whose `lerp(view depth, distance to the centre,
/// type)` has its ends swapped fails, in variants with a realtime shadow only (the rig's
/// directional lights fade by a sphere, its spot and point lights by view depth).
#[test]
fn a_swapped_fade_distance_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "lighting/shadow_fade.wgsl",
        "mix(z, sphere, shadow_fade.center_and_type.w)",
        "mix(sphere, z, shadow_fade.center_and_type.w)",
    );
    let caught = lighting_check_fails(&lib, |k| {
        ["SHADOWS_DEPTH", "SHADOWS_CUBE", "SHADOWS_SCREEN"]
            .iter()
            .any(|s| k.contains(s))
    });
    if let Some(n) = caught {
        eprintln!("a swapped fade distance is caught: {n} mismatches");
    }
}

/// Forward = deferred for one light: ForwardAdd and G-buffer + Lighting (HDR) agree on every
/// pixel within the bound derived from the G-buffer's quantization
/// (`reference::tolerance::gbuffer_light_bound`), for every light type and three keyword sets,
/// one per BRDF tier.
#[test]
fn forward_and_deferred_light_agree_per_pixel() {
    use wgsl_variants_gpu::check::forward_deferred::forward_vs_deferred;
    use wgsl_variants_gpu::check::{LightRig, TestScene};
    use wgsl_variants_shaders::reference::brdf::Brdf;
    use wgsl_variants_shaders::reference::light::LightType;
    use wgsl_variants_shaders::reference::surface::{Keywords, SmoothnessSource};

    let ctx = match wgsl_variants_gpu::GpuContext::new(common::gpu::adapter_filter().as_deref()) {
        Ok(ctx) => ctx,
        Err(e) => {
            common::gpu::or_skip::<()>(Err(e), "creating the GPU context");
            return;
        }
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let rig = LightRig::new(&scene);
    // One input per BRDF tier.
    let inputs = [
        Keywords::EVERY_MAP,
        Keywords {
            smoothness: SmoothnessSource::Albedo,
            normal_map: true,
            brdf: Brdf::Brdf2,
            ..Keywords::NONE
        },
        Keywords {
            brdf: Brdf::Brdf3,
            ..Keywords::EVERY_MAP
        },
    ];
    let (mut pixels, mut lit, mut worst, mut sum_light, mut sum_allowed) = (0, 0, 0.0f32, 0.0, 0.0);
    for kw in &inputs {
        for light in LightType::ALL {
            let pairs = forward_vs_deferred(&ctx, &lib, &scene, &rig, kw, light).unwrap();
            for p in &pairs {
                assert!(
                    p.agrees(),
                    "{light:?} {:?} pixel {:?}: forward {} deferred {} allowed {}",
                    kw.names(),
                    p.pixel,
                    p.forward,
                    p.deferred,
                    p.allowed
                );
                pixels += 1;
                if p.forward.max_element() > 0.0 {
                    lit += 1;
                    let diff = (p.forward - p.deferred).abs();
                    worst = worst.max((diff / p.allowed).max_element());
                    sum_light += p.forward.element_sum();
                    sum_allowed += p.allowed.element_sum();
                }
            }
        }
    }
    eprintln!(
        "forward = deferred: {pixels} pixels ({lit} lit), largest difference {:.0}% of its bound, bounds {:.2}% of the light on average",
        worst * 100.0,
        sum_allowed / sum_light * 100.0
    );
    assert!(lit > pixels / 2, "{lit} of {pixels} lit");
    // The bound is not vacuous: a few percent of the light, not a multiple of it.
    assert!(
        sum_allowed < 0.1 * sum_light,
        "{sum_allowed} vs {sum_light}"
    );
}
