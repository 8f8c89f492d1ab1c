//! The GPU proof of URP's `universal_lit/UniversalForward`: the default selection (a t = 3
//! covering set plus one partner per keyword) rendered on the URP scene lit by the main light
//! (with its shadow map, its four cascades, or a screen-space shadow texture) and three
//! additional lights (two casting shadows from the additional lights' atlas), every texel of
//! the `Rg11b10Ufloat` camera target compared with `reference::urp::forward`, every keyword
//! shown to change a texel; and libraries with planted bugs (the per-vertex light not
//! multiplied by the diffuse colour, light layers ignored by the per-pixel loop, the
//! subtractive mix's shadow strength wrong, the shadow fade dropped, the cascade selection
//! ignored, the screen-space shadow read at another pixel, a point light's shadow read from
//! the opposite cube face, a hard light filtered as soft, the additional lights' fade dropped,
//! the main light's cookie dropped, a light without a cookie reading the atlas) caught where,
//! and only where, the bug shows. The full space (786,432 variants) is the
//! ignored test `every_universal_forward_variant_matches_the_reference`
//! (`cargo test --release -p wgsl-variants-gpu --test gpu_urp_forward -- --ignored`).
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`): without an adapter the tests
//! print SKIPPED and pass, unless `CI=true` or `WGSL_VARIANTS_REQUIRE_GPU=1`.

mod common;

use wgsl_variants::Library;
use wgsl_variants::variants::Space;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport};

/// The covering strength of a planted bug's run (the check's own is 3): a pairwise covering
/// set with its keyword partners holds every pair of keywords a plant needs, at half the draws
/// of a mutated library that compiles anew.
const PLANT_COVER: usize = 2;

/// The forward pass's check: the default 3-wise covering set with partners, its `cover`-wise
/// one, or with `full` every variant.
fn run(lib: &Library, full: bool, cover: Option<usize>) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some("universal_lit".into());
    options.pass = Some("UniversalForward".into());
    options.adapter = common::gpu::adapter_filter();
    options.full = full;
    options.cover = cover;
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

fn assert_passes(report: &CheckReport, at_least: usize) {
    let p = &report.passes[0];
    println!("{report}");
    assert_eq!(
        (p.shader.as_str(), p.pass.as_str()),
        ("universal_lit", "UniversalForward")
    );
    assert!(p.variants_run >= at_least, "{} variants", p.variants_run);
    assert_eq!(p.mismatches, 0, "{report}");
    assert!(p.discarded_compared > 0, "the alpha test discarded nothing");
    // Every option but the first of each set: 10 material keywords, _MAIN_LIGHT_SHADOWS,
    // _MAIN_LIGHT_SHADOWS_CASCADE and _MAIN_LIGHT_SHADOWS_SCREEN, _SHADOWS_SOFT, the two
    // additional-light options, their shadows, _LIGHT_LAYERS, subtractive, lightmap, cookies,
    // the screen-space occlusion.
    assert_eq!(p.keywords.len(), 22);
    assert!(p.untested_keywords.is_empty(), "{:?}", p.untested_keywords);
    assert!(
        p.keywords.iter().all(|k| k.pairs_changed > 0),
        "{:?}",
        p.keywords
    );
    assert!(
        p.notes
            .iter()
            .any(|n| n.contains("hard shadow covers") && !n.contains("covers 0 of")),
        "some pixels must be in the main light's shadow: {report}"
    );
    assert!(
        p.notes
            .iter()
            .any(|n| n.contains("the point light's covers")
                && !n.contains("covers 0 pixels")
                && !n.contains("the spot light's 0")),
        "some pixels must be in the additional lights' shadows: {report}"
    );
    assert!(
        p.notes
            .iter()
            .any(|n| n.contains("cookies: the main light's reads")
                && !n.contains("reads 0 distinct")
                && !n.contains("reads 1 distinct")),
        "the main light's cookie must vary over the quad: {report}"
    );
    assert!(report.passed());
}

#[test]
fn covering_set_of_universal_forward_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, false, None) else {
        return;
    };
    let pass = lib.pass("universal_lit", "UniversalForward").unwrap();
    let cover = Space::full(pass).covering(3).unwrap().len();
    assert_passes(&report, cover);
    assert!(report.passes[0].variants_run <= cover + 22);
}

#[test]
#[ignore = "786,432 variants: run with --ignored (docs/urp.md gives the time)"]
fn every_universal_forward_variant_matches_the_reference() {
    let Some(report) = run(&wgsl_variants_shaders::library().unwrap(), true, None) else {
        return;
    };
    assert_passes(&report, 786_432);
}

#[test]
fn the_main_lights_cookie_dropped_is_caught_only_with_cookies() {
    // GetMainLight without SampleMainLightCookie.
    let Some(bad) = mismatching(
        "universal/lit_forward_pass.wgsl",
        "let cookie_color = lighting.main_light_color.rgb * urp_main_light_cookie(p);",
        "let cookie_color = lighting.main_light_color.rgb;",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_LIGHT_COOKIES"]);
}

#[test]
fn a_light_without_a_cookie_reading_the_atlas_is_caught_only_where_it_lights() {
    // SampleAdditionalLightCookie's all-zero test dropped: the second point light (no cookie,
    // a rect of zeros) reads the atlas's first texel. It lights the quad per pixel only
    // without _LIGHT_LAYERS (its layer is not the mesh's).
    let Some(bad) = mismatching(
        "universal/light_cookie.wgsl",
        "if all(additional_light_cookies.atlas_uv_rect[light] == vec4f(0.0)) {",
        "if additional_light_cookies.atlas_uv_rect[light].x < 0.0 {",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_LIGHT_COOKIES"), "{k}");
        let per_pixel = k
            .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .any(|t| t == "_ADDITIONAL_LIGHTS");
        assert!(per_pixel, "{k}");
        assert!(!k.contains("_LIGHT_LAYERS"), "{k}");
    }
}

#[test]
fn the_occlusion_ignored_by_the_global_illumination_is_caught_only_under_ssao() {
    // The global illumination with the surface's occlusion alone, the SSAO's indirect part
    // dropped.
    let Some(bad) = mismatching(
        "universal/lit_forward_pass.wgsl",
        "let occlusion = min(ssao, s.occlusion);",
        "let occlusion = s.occlusion;",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_SCREEN_SPACE_OCCLUSION"]);
}

#[test]
fn the_direct_occlusion_dropped_per_pixel_is_caught_only_with_per_pixel_lights_under_ssao() {
    // GetAdditionalLight without the SSAO's direct part. (The per-vertex lights, which URP
    // leaves unoccluded, reach this scene's quad at under 5e-4: a plant there would not show.)
    let Some(bad) = mismatching(
        "universal/lit_forward_pass.wgsl",
        "            let light_color = cookie_light * direct_occlusion;",
        "            let light_color = cookie_light;",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_SCREEN_SPACE_OCCLUSION", "_ADDITIONAL_LIGHTS"]);
}

/// Runs the forward pass's default selection over the bundled library with one planted bug
/// and returns the keyword sets of the variants with mismatches.
fn mismatching(path: &str, from: &str, to: &str) -> Option<Vec<String>> {
    let report = run(
        &common::mutate::bundled_with(path, from, to),
        false,
        Some(PLANT_COVER),
    )?;
    let covering = format!("{PLANT_COVER}-wise covering set of ");
    let notes = &report.passes[0].notes;
    assert!(notes.iter().any(|n| n.starts_with(&covering)), "{report}");
    Some(common::mutate::caught_in(&report))
}

#[test]
fn vertex_light_without_the_diffuse_colour_is_caught_only_per_vertex() {
    // URP: vertexLightingColor = vertexLighting · brdfData.diffuse.
    let Some(bad) = mismatching(
        "universal/lit_forward_pass.wgsl",
        "color += in.vertex_lighting * b.diffuse;",
        "color += in.vertex_lighting;",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_ADDITIONAL_LIGHTS_VERTEX"]);
}

#[test]
fn light_layers_ignored_per_pixel_are_caught_only_with_light_layers() {
    let Some(bad) = mismatching(
        "universal/lit_forward_pass.wgsl",
        "        if urp_lights_mesh(light.layer_mask.x) {\n            let a = ",
        "        if true {\n            let a = ",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_LIGHT_LAYERS"), "{k}");
        assert!(
            k.contains("_ADDITIONAL_LIGHTS") && !k.contains("_ADDITIONAL_LIGHTS_VERTEX"),
            "{k}"
        );
    }
}

#[test]
fn a_wrong_subtractive_shadow_strength_is_caught_only_under_subtractive_shadows() {
    // The subtractive mix takes the main light's shadow strength (URP's
    // SubtractDirectMainLightFromLightmap); full strength instead changes shadowed texels.
    let Some(bad) = mismatching(
        "universal/main_light_shadow.wgsl",
        "return vec2f(mix(realtime.x, 1.0, urp_shadow_fade(p, camera, main_light_shadow_params.zw)), realtime.y);",
        "return vec2f(mix(realtime.x, 1.0, urp_shadow_fade(p, camera, main_light_shadow_params.zw)), 1.0);",
    ) else {
        return;
    };
    for k in &bad {
        for needed in [
            "_MIXED_LIGHTING_SUBTRACTIVE",
            "LIGHTMAP_ON",
            "_MAIN_LIGHT_SHADOWS",
        ] {
            assert!(k.contains(needed), "{k}");
        }
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}

#[test]
fn an_ignored_shadow_fade_is_caught_only_where_the_main_light_is_shadowed() {
    // URP's MainLightShadow lerps the realtime shadow towards 1 with the distance from the
    // camera; the check's fade ramps across the shadowed texels.
    let Some(bad) = mismatching(
        "universal/main_light_shadow.wgsl",
        "return vec2f(mix(realtime.x, 1.0, urp_shadow_fade(p, camera, main_light_shadow_params.zw)), realtime.y);",
        "return realtime;",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_MAIN_LIGHT_SHADOWS"), "{k}");
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}

#[test]
fn an_ignored_cascade_selection_is_caught_only_with_cascades() {
    // URP's ComputeCascadeIndex picks the first split sphere holding the point; reading
    // cascade 0 everywhere puts the shadow of cascade 1's half (and of the points in no
    // cascade) in the wrong place.
    let Some(bad) = mismatching(
        "universal/main_light_shadow_map.wgsl",
        "let c = cascade_coords(main_light_cascades, p);",
        "let c = shadow_coords(main_light_cascades.world_to_shadow[0], p);",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_MAIN_LIGHT_SHADOWS_CASCADE"), "{k}");
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}

#[test]
fn the_screen_space_shadow_read_at_another_pixel_is_caught_only_with_screen_shadows() {
    // URP's SampleScreenSpaceShadowmap reads the texel at the fragment's own pixel; the check's
    // stand-in texture differs from pixel to pixel.
    let Some(bad) = mismatching(
        "universal/main_light_shadow.wgsl",
        "textureLoad(main_light_screen_shadow, pixel, 0)",
        "textureLoad(main_light_screen_shadow, pixel + vec2i(1, 0), 0)",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_MAIN_LIGHT_SHADOWS_SCREEN"), "{k}");
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}

#[test]
fn a_point_light_reading_the_opposite_cube_face_is_caught_only_with_additional_shadows() {
    // URP's AdditionalLightRealtimeShadow picks the slice of CubeMapFaceID(-lightDirection):
    // the face from the light to the receiver. The face towards the light sees no occluder.
    let Some(bad) = mismatching(
        "universal/additional_light_shadow.wgsl",
        "slice += urp_cube_map_face_id(-to_light);",
        "slice += urp_cube_map_face_id(to_light);",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_ADDITIONAL_LIGHT_SHADOWS"), "{k}");
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}

#[test]
fn soft_filtering_of_a_hard_light_is_caught_only_under_soft_additional_shadows() {
    // Under _SHADOWS_SOFT a light is filtered only if its own flag says soft (URP's
    // _AdditionalShadowParams.y); the check's point light is hard, its spot light soft.
    let Some(bad) = mismatching(
        "universal/additional_light_shadow.wgsl",
        "if params.y > 0.0 {",
        "if params.y >= 0.0 {",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_ADDITIONAL_LIGHT_SHADOWS", "_SHADOWS_SOFT"]);
}

#[test]
fn an_ignored_additional_shadow_fade_is_caught_only_with_additional_shadows() {
    // URP's AdditionalLightShadow lerps the realtime shadow towards 1 with the distance from
    // the camera (_AdditionalShadowFadeParams); the check's fade ramps across the texels the
    // additional lights shadow.
    let Some(bad) = mismatching(
        "universal/additional_light_shadow.wgsl",
        "return mix(urp_additional_light_realtime_shadow(light, p, to_light), 1.0, fade);",
        "return urp_additional_light_realtime_shadow(light, p, to_light);",
    ) else {
        return;
    };
    for k in &bad {
        assert!(k.contains("_ADDITIONAL_LIGHT_SHADOWS"), "{k}");
        assert!(!k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
    }
}
