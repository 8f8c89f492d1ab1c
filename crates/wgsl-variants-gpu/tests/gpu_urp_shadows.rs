//! The GPU proof of URP Lit's ShadowCaster: every variant (8) renders the URP scene's quad into
//! a directional light's maps (a box around the scene and one tighter than the quad, whose near
//! plane pancakes it) or a spot light's map, every texel compared with the reference
//! (`wgsl_variants_shaders::reference::urp::shadow`); and planted bugs — no depth bias, the directional
//! formula for a punctual light, no pancaking — are caught where, and only where, they show.
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport};

fn run(lib: &Library) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some("universal_lit".to_owned());
    options.pass = Some("ShadowCaster".to_owned());
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
