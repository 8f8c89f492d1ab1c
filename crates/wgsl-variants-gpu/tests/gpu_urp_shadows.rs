//! The GPU proof of URP Lit's ShadowCaster: every variant (8) renders the URP scene's quad into
//! a directional light's maps (a box around the scene and one tighter than the quad, whose near
//! plane pancakes it) or a spot light's map, every texel compared with the reference
//! (`wgsl_variants_shaders::reference::urp::shadow`); and planted bugs — no depth bias, the directional
//! formula for a punctual light, no pancaking — are caught where, and only where, they show.
//! Then URP's screen-space shadow pass (`universal_screen_space_shadows/ScreenSpaceShadows`,
//! 4 variants): the main light's map or cascades turned into a shadow per pixel of the rig's
//! view, every pixel against the reference, and a pass that reads no depth caught. And URP
//! Lit's depth prepass (`DepthOnly`, 4 variants): the quad's depth through the rig's camera
//! and two light boxes, every texel against the reference; a prepass without the object's
//! transform, and one without the alpha test, caught.
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport};

fn run(lib: &Library) -> Option<CheckReport> {
    run_pass(lib, "universal_lit", "ShadowCaster")
}

fn run_pass(lib: &Library, shader: &str, pass: &str) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some(shader.to_owned());
    options.pass = Some(pass.to_owned());
    options.adapter = common::gpu::adapter_filter();
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

#[test]
fn every_urp_shadow_caster_variant_matches_the_reference() {
    let Some(report) = run(&wgsl_variants_shaders::library().unwrap()) else {
        return;
    };
    let p = &report.passes[0];
    for note in &p.notes {
        eprintln!("  note: {note}");
    }
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    // 4 variants × 2 directional maps + 4 × the spot's, 64 × 64 texels less the edge ones.
    assert_eq!((p.variants_run, p.draws), (8, 12));
    assert!(p.pixels_compared > 12 * 4096 * 9 / 10, "{report}");
    assert!(p.untested_keywords.is_empty(), "{report}");
    let note = &p.notes[0];
    assert!(
        !note.contains(" 0 texels on a triangle with a vertex pancaked"),
        "{note}"
    );
    assert!(!note.contains("(0 discarded by the alpha test)"), "{note}");
}

/// The keyword sets of the variants with mismatches under one planted bug.
fn mismatching(path: &str, from: &str, to: &str) -> Option<Vec<String>> {
    let report = run(&common::mutate::bundled_with(path, from, to))?;
    Some(common::mutate::caught_in(&report))
}

#[test]
fn a_missing_depth_bias_is_caught() {
    mismatching(
        "universal/shadow_caster_pass.wgsl",
        "p + l * shadow_caster.bias.x + n * scale",
        "p + n * scale",
    );
}

#[test]
fn the_directional_bias_direction_for_a_punctual_light_is_caught_only_there() {
    let Some(bad) = mismatching(
        "universal/shadow_caster_pass.wgsl",
        "let l = normalize(shadow_caster.light_position.xyz - p);",
        "let l = normalize(shadow_caster.light_position.xyz);",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_CASTING_PUNCTUAL_LIGHT_SHADOW"), "{k}");
    }
}

#[test]
fn a_missing_pancake_is_caught_only_in_the_directional_maps() {
    let Some(bad) = mismatching(
        "universal/shadow_caster_pass.wgsl",
        "clip.z = max(clip.z, 0.0);",
        "clip.z = clip.z;",
    ) else {
        return;
    };
    for k in &bad {
        assert!(!k.contains("_CASTING_PUNCTUAL_LIGHT_SHADOW"), "{k}");
    }
}

const SCREEN: (&str, &str) = ("universal_screen_space_shadows", "ScreenSpaceShadows");

#[test]
fn every_urp_screen_space_shadow_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run_pass(&lib, SCREEN.0, SCREEN.1) else {
        return;
    };
    let p = &report.passes[0];
    println!("{report}");
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    assert_eq!((p.variants_run, p.pixels_compared), (4, 4 * 256));
    // _MAIN_LIGHT_SHADOWS_CASCADE (against the map) and _SHADOWS_SOFT.
    assert_eq!(p.keywords.len(), 2, "{report}");
    assert!(p.keywords.iter().all(|k| k.pairs_changed > 0), "{report}");
    assert!(
        !p.notes[0].contains(" 0 shadowed"),
        "some pixels must be shadowed: {report}"
    );
}

#[test]
fn a_screen_space_pass_that_reads_no_depth_is_caught() {
    // Every pixel rebuilt on the far plane (only this pass is run, so the shared depth
    // module's fault shows in it alone): the shadowed pixels come out lit. (The report lists
    // the first mismatches only, all of the map's variants, which come first.)
    let lib = common::mutate::bundled_with(
        "deferred/depth.wgsl",
        "let depth = textureLoad(depth_buffer, pixel, 0).r;",
        "let depth = 1.0;",
    );
    let Some(report) = run_pass(&lib, SCREEN.0, SCREEN.1) else {
        return;
    };
    let caught = common::mutate::caught_in(&report);
    assert!(
        caught.iter().all(|k| k.contains("_MAIN_LIGHT_SHADOWS")),
        "{caught:?}"
    );
}

const DEPTH_ONLY: (&str, &str) = ("universal_lit", "DepthOnly");

#[test]
fn every_urp_depth_only_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run_pass(&lib, DEPTH_ONLY.0, DEPTH_ONLY.1) else {
        return;
    };
    let p = &report.passes[0];
    println!("{report}");
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    // 4 variants × the camera's view and two 64 × 64 light boxes.
    assert_eq!((p.variants_run, p.draws), (4, 12));
    // _ALPHATEST_ON, and the smoothness keyword that changes the cutout with it.
    assert_eq!(p.keywords.len(), 2, "{report}");
    assert!(p.untested_keywords.is_empty(), "{report}");
    let note = &p.notes[0];
    assert!(!note.contains(" 0 depth"), "{note}");
    assert!(!note.contains("(0 discarded by the alpha test)"), "{note}");
}

#[test]
fn a_depth_prepass_without_the_object_transform_is_caught_everywhere() {
    let lib = common::mutate::bundled_with(
        "universal/depth_only_pass.wgsl",
        "camera.view_proj * (object.model * vec4f(in.position, 1.0))",
        "camera.view_proj * vec4f(in.position, 1.0)",
    );
    let Some(report) = run_pass(&lib, DEPTH_ONLY.0, DEPTH_ONLY.1) else {
        return;
    };
    let caught = common::mutate::caught_in(&report);
    assert!(
        caught.iter().any(|k| !k.contains("_ALPHATEST_ON")),
        "{caught:?}"
    );
}

#[test]
fn a_depth_prepass_without_the_alpha_test_is_caught_only_there() {
    let lib = common::mutate::bundled_with(
        "universal/depth_only_pass.wgsl",
        "urp_alpha(textureSample(base_map, material_sampler, in.uv).a);",
        "_ = textureSample(base_map, material_sampler, in.uv).a;",
    );
    let Some(report) = run_pass(&lib, DEPTH_ONLY.0, DEPTH_ONLY.1) else {
        return;
    };
    let caught = common::mutate::caught_in(&report);
    assert!(
        caught.iter().all(|k| k.contains("_ALPHATEST_ON")),
        "{caught:?}"
    );
}
