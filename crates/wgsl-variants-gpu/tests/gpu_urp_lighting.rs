//! The GPU proof of URP's lighting passes: every variant of `stencil_deferred/PunctualLit` (96),
//! `stencil_deferred/DirectionalLit` (156) and `stencil_deferred/SSAOOnly` (2), drawn over G-buffers `universal_lit`'s
//! UniversalGBuffer pass rendered on the same GPU, compared texel by texel with the CPU
//! reference (`wgsl_variants_shaders::reference::urp::lighting`), each keyword proven to change at
//! least one texel; and libraries with planted bugs (a wrong specular constant, a flag ignored,
//! the older URP's diffuse formula, the shadow fade dropped, the cascade selection ignored,
//! the screen-space shadow read at another pixel, the main light's cookie flipped, a spot's
//! cookie flipped, a point light reading the spot's rect of the cookie atlas, the SSAO's direct
//! part ignored, the first light's or the SSAOOnly pass's scale of GBuffer3 wrong)
//! are caught where, and only where, the bug shows. A planted bug runs the pass's pairwise
//! covering set ([`PLANT_COVER`]) rather than its whole space: each plant needs at most two
//! keywords on together to show, and the whole space of the mutated library would compile
//! anew on every run (lavapipe compiles at the first draw).
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`): without an adapter the tests
//! print SKIPPED and pass, unless `CI=true` or `WGSL_VARIANTS_REQUIRE_GPU=1`.

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport};

/// The covering strength a planted bug's run uses.
const PLANT_COVER: usize = 2;

/// The check of `stencil_deferred/pass`: every variant, or a `cover`-wise covering set.
fn run(lib: &Library, pass: &str, cover: Option<usize>) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some("stencil_deferred".to_owned());
    options.pass = Some(pass.to_owned());
    options.cover = cover;
    options.adapter = common::gpu::adapter_filter();
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

#[test]
fn every_lighting_variant_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    // (pass, variants, keywords judged: every set's options but the first)
    for (pass, variants, keywords) in [("PunctualLit", 96, 7), ("DirectionalLit", 156, 10)] {
        let Some(report) = run(&lib, pass, None) else {
            return;
        };
        let p = &report.passes[0];
        eprintln!(
            "stencil_deferred/{pass} on {}: {} texels over {} variants ({} draws) in {:.1} s",
            report.adapter, p.pixels_compared, p.variants_run, p.draws, p.seconds
        );
        for k in &p.keywords {
            eprintln!(
                "  {}: {} of {} pairs changed",
                k.keyword, k.pairs_changed, k.pairs
            );
        }
        for note in &p.notes {
            eprintln!("  note: {note}");
        }
        assert!(p.passed(), "{report}");
        assert_eq!(p.mismatches, 0, "{report}");
        assert_eq!(p.variants_run, variants);
        // Each variant over the 3 G-buffers of its normal encoding, with 2 layer masks.
        assert_eq!(
            (p.draws, p.pixels_compared),
            (variants * 6, variants * 6 * 256)
        );
        assert_eq!(p.keywords.len(), keywords, "{report}");
        assert!(p.untested_keywords.is_empty(), "{report}");
        for k in &p.keywords {
            assert!(k.pairs_changed > 0, "{report}");
        }
        let shadowed = if pass == "DirectionalLit" {
            "in the main light's shadow"
        } else {
            "in a point or spot light's own shadow"
        };
        assert!(
            p.notes.iter().any(|n| n.contains(shadowed)),
            "some pixels must be shadowed: {report}"
        );
        assert_eq!(
            p.notes
                .iter()
                .any(|n| n.contains("under the main light's cookie")),
            pass == "DirectionalLit",
            "the main light's cookie tints DirectionalLit's pixels only: {report}"
        );
        assert_eq!(
            p.notes
                .iter()
                .any(|n| n.contains("under a point or spot light's cookie")),
            pass == "PunctualLit",
            "the atlas tints PunctualLit's pixels only: {report}"
        );
        // The first directional light scales GBuffer3 somewhere (DirectionalLit only).
        let rescaled = p
            .notes
            .iter()
            .find(|n| n.contains("under the screen-space occlusion"))
            .unwrap_or_else(|| panic!("no occlusion note: {report}"));
        assert_eq!(
            rescaled.contains("the first directional light scales GBuffer3"),
            pass == "DirectionalLit",
            "{report}"
        );
    }
}

/// URP's SSAOOnly pass: both variants over GBuffer3, the occlusion where it is lower than the
/// surface's own and GBuffer3 kept where it is not, the keyword changing texels; nothing drawn
/// without it.
#[test]
fn the_ssao_only_pass_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, "SSAOOnly", None) else {
        return;
    };
    let p = &report.passes[0];
    for note in &p.notes {
        eprintln!("  note: {note}");
    }
    assert!(p.passed() && p.mismatches == 0, "{report}");
    assert_eq!((p.variants_run, p.draws), (2, 6), "{report}");
    assert!(p.keywords.iter().all(|k| k.pairs_changed > 0), "{report}");
    let note = &p.notes[0];
    let count = |after: &str| -> usize {
        let tail = &note[note.find(after).expect(after) + after.len()..];
        tail.split_whitespace().next().unwrap().parse().unwrap()
    };
    assert!(count("; in ") > 100, "{note}");
    assert!(count("less than 1, in ") > 20, "{note}");
}

#[test]
fn an_ignored_direct_occlusion_is_caught_only_under_ssao() {
    // The light not dimmed by the SSAO's direct part.
    let Some(bad) = mismatching(
        "universal/stencil_deferred_pass.wgsl",
        "let color = cookie_color * urp_direct_occlusion(ssao, ambient_occlusion_params.w);",
        "let color = cookie_color;",
        "PunctualLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_SCREEN_SPACE_OCCLUSION"]);
}

#[test]
fn the_first_lights_occlusion_without_the_surfaces_is_caught_only_in_the_first_light() {
    // GBuffer3 scaled by the SSAO itself, as if the G-buffer pass had not applied the
    // surface's occlusion already (the ratio dropped).
    let Some(bad) = mismatching(
        "universal/stencil_deferred_pass.wgsl",
        "let alpha = urp_deferred_indirect_occlusion(ssao, g1.a);",
        "let alpha = ssao;",
        "DirectionalLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_DEFERRED_FIRST_LIGHT"]);
}

#[test]
fn an_ssao_only_pass_that_always_divides_is_caught() {
    // The ratio taken even where the surface's own occlusion is the lower (GBuffer3 brightened).
    let Some(bad) = mismatching(
        "universal/ambient_occlusion.wgsl",
        "if indirect < surface {",
        "if surface > 0.0 {",
        "SSAOOnly",
    ) else {
        return;
    };
    // Only the G-buffer with an occlusion map has texels whose own occlusion is the lower.
    assert!(!bad.is_empty());
    common::mutate::assert_each_has(
        &bad,
        &["SSAOOnly {_SCREEN_SPACE_OCCLUSION}", "_OCCLUSIONMAP"],
    );
}

#[test]
fn a_flipped_cookie_is_caught_only_under_the_main_lights_cookie() {
    // The cookie read upside down: v from the other edge of the texture.
    let Some(bad) = mismatching(
        "universal/light_cookie.wgsl",
        "let uv = (main_light_cookie.world_to_light * vec4f(p, 1.0)).xy * 0.5 + 0.5;",
        "let uv = (main_light_cookie.world_to_light * vec4f(p, 1.0)).xy * vec2f(0.5, -0.5) + 0.5;",
        "DirectionalLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_LIGHT_COOKIES", "_DEFERRED_MAIN_LIGHT"]);
}

#[test]
fn a_flipped_spot_cookie_is_caught_only_under_the_spots_cookie() {
    // The spot's cookie read upside down within its rect.
    let Some(bad) = mismatching(
        "universal/light_cookie.wgsl",
        "saturate(q.xy / q.w * 0.5 + 0.5)",
        "saturate(q.xy / q.w * vec2f(0.5, -0.5) + 0.5)",
        "PunctualLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_LIGHT_COOKIES", "_SPOT"]);
}

#[test]
fn a_point_light_reading_the_spots_cookie_is_caught_only_for_the_point_light() {
    // URP's _CookieLightIndex names the drawn light's entry; entry 1 is the spot's.
    let Some(bad) = mismatching(
        "universal/stencil_deferred_pass.wgsl",
        "urp_point_light_cookie(cookie_light_index.x, p)",
        "urp_point_light_cookie(1u, p)",
        "PunctualLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_LIGHT_COOKIES", "_POINT"]);
}

/// Runs `pass` over the bundled library with one planted bug and returns the keyword sets of
/// the variants with mismatches.
fn mismatching(path: &str, from: &str, to: &str, pass: &str) -> Option<Vec<String>> {
    let lib = common::mutate::bundled_with(path, from, to);
    let report = run(&lib, pass, Some(PLANT_COVER))?;
    // A pass of no more keyword sets than the strength (SSAOOnly's one) runs whole.
    let p = &report.passes[0];
    let note = format!(
        "{PLANT_COVER}-wise covering set of {} of the",
        p.variants_run
    );
    let sets = lib.pass("stencil_deferred", pass).unwrap().sets.len();
    let covered = p.notes.iter().any(|n| n.starts_with(&note));
    assert_eq!(covered, sets > PLANT_COVER, "{report}");
    Some(common::mutate::caught_in(&report))
}

#[test]
fn a_wrong_specular_constant_is_caught() {
    // URP's d = (n·h)² (r² − 1) + 1.00001; 1.01 flattens the highlight.
    let Some(bad) = mismatching(
        "universal/lighting.wgsl",
        "+ 1.00001;",
        "+ 1.01;",
        "PunctualLit",
    ) else {
        return;
    };
    eprintln!("caught, e.g. in {}", bad[0]);
}

#[test]
fn an_ignored_receive_shadows_off_flag_is_caught_only_where_it_matters() {
    // Both passes: the main light's shadow and a punctual light's own.
    for (pass, shadow) in [
        ("DirectionalLit", "_MAIN_LIGHT_SHADOWS"),
        ("PunctualLit", "_ADDITIONAL_LIGHT_SHADOWS"),
    ] {
        let Some(bad) = mismatching(
            "universal/stencil_deferred_pass.wgsl",
            "if (flags & URP_FLAG_RECEIVE_SHADOWS_OFF) != 0u {",
            "if flags != flags {",
            pass,
        ) else {
            return;
        };
        for k in &bad {
            // Only the shadowed variants over the G-buffer whose flags say ReceiveShadowsOff.
            assert!(k.contains(shadow), "{k}");
            assert!(k.contains("_RECEIVE_SHADOWS_OFF"), "{k}");
        }
    }
}

#[test]
fn a_punctual_light_reading_another_lights_shadow_is_caught_only_for_the_spot() {
    // URP's _ShadowLightIndex names the drawn light's record; record 0 is the point light's
    // (six cube-face slices), so the point light's variants read their own either way.
    let Some(bad) = mismatching(
        "universal/stencil_deferred_pass.wgsl",
        "urp_additional_light_shadow(shadow_light_index.x,",
        "urp_additional_light_shadow(0u,",
        "PunctualLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_SPOT", "_ADDITIONAL_LIGHT_SHADOWS"]);
}

#[test]
fn an_ignored_shadow_fade_is_caught_only_in_the_main_lights_shadowed_variants() {
    // URP's MainLightShadow lerps the realtime shadow towards 1 with the distance; the check's
    // fade ramps across the pixels, so dropping it shows where the shadow falls.
    let Some(bad) = mismatching(
        "universal/main_light_shadow.wgsl",
        "return vec2f(mix(realtime.x, 1.0, urp_shadow_fade(p, camera, main_light_shadow_params.zw)), realtime.y);",
        "return realtime;",
        "DirectionalLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_MAIN_LIGHT_SHADOWS"]);
}

#[test]
fn an_ignored_cascade_selection_is_caught_only_in_the_cascaded_variants() {
    // Cascade 0 for every point instead of URP's ComputeCascadeIndex.
    let Some(bad) = mismatching(
        "universal/main_light_shadow_map.wgsl",
        "let c = cascade_coords(main_light_cascades, p);",
        "let c = shadow_coords(main_light_cascades.world_to_shadow[0], p);",
        "DirectionalLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_MAIN_LIGHT_SHADOWS_CASCADE"]);
}

#[test]
fn the_screen_space_shadow_read_at_another_pixel_is_caught_only_with_screen_shadows() {
    let Some(bad) = mismatching(
        "universal/main_light_shadow.wgsl",
        "textureLoad(main_light_screen_shadow, pixel, 0)",
        "textureLoad(main_light_screen_shadow, pixel + vec2i(1, 0), 0)",
        "DirectionalLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_MAIN_LIGHT_SHADOWS_SCREEN"]);
}

#[test]
fn the_older_specular_setup_diffuse_is_caught_only_in_the_specular_setup() {
    // URP's BRDFDataFromGbuffer: diffuse = albedo · (1 − max(specular)); older URPs used
    // albedo · (1 − specular) per channel.
    let Some(bad) = mismatching(
        "universal/lighting.wgsl",
        "    b.diffuse = albedo * (1.0 - reflectivity);",
        "    b.diffuse = albedo * select(vec3f(1.0 - reflectivity), 1.0 - specular, specular_setup);",
        "PunctualLit",
    ) else {
        return;
    };
    common::mutate::assert_each_has(&bad, &["_SPECULAR_SETUP"]);
}

#[test]
fn the_urp_pictures_show_the_gbuffer_and_the_light() {
    use wgsl_variants_gpu::check::{TestScene, pictures};
    let Some(ctx) = common::gpu::or_skip(
        wgsl_variants_gpu::GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "the URP pictures",
    ) else {
        return;
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let pics = pictures::render_pictures(
        &ctx,
        &lib,
        &scene,
        "universal_lit",
        "UniversalGBuffer",
        &[
            "_RECEIVE_SHADOWS_OFF",
            "_SPECULAR_SETUP",
            "_GBUFFER_NORMALS_OCT",
        ],
    )
    .unwrap();
    let names: Vec<&str> = pics.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "albedo",
            "flags",
            "specular",
            "occlusion",
            "normal",
            "smoothness",
            "gi",
            "lighting"
        ]
    );
    let by_name = |n: &str| pics.iter().find(|p| p.name == n).unwrap();
    // ReceiveShadowsOff in red, SpecularSetup in blue, at every pixel.
    for px in by_name("flags").rgba.chunks(4) {
        assert_eq!(px, [255, 0, 255, 255]);
    }
    // The lights add to GBuffer3: brighter somewhere, never darker.
    let (gi, lit) = (&by_name("gi").rgba, &by_name("lighting").rgba);
    assert!(gi.iter().zip(lit.iter()).all(|(g, l)| l >= g));
    assert!(gi.iter().zip(lit.iter()).any(|(g, l)| l > g));
}

#[test]
fn urp_light_volumes_with_the_stencil_equal_full_screen_on_lit_texels_only() {
    use wgsl_variants_gpu::check::urp_lighting::compare_urp_volume;
    use wgsl_variants_gpu::check::{LightRig, TestScene};
    use wgsl_variants_shaders::reference::urp::lighting::UrpLightKind;
    let Some(ctx) = common::gpu::or_skip(
        wgsl_variants_gpu::GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "URP's light volumes",
    ) else {
        return;
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let mut rig = LightRig::new(&scene);
    rig.render_screen_shadows(&ctx, &lib, &scene).unwrap();
    for kind in [UrpLightKind::Point, UrpLightKind::Spot] {
        let c = compare_urp_volume(&ctx, &lib, &scene, &rig, kind).unwrap();
        eprintln!(
            "{kind:?}: {} Lit texels lit by the volume, {} Unlit texels the full-screen draw reached, {} differing",
            c.lit,
            c.unlit_reached,
            c.differing.len()
        );
        // The volume draw gives the full-screen result, bit for bit, where the G-buffer pass
        // stamped Lit, and leaves the Unlit half as it was; the light pass zeroed StencilLight.
        assert!(c.differing.is_empty(), "{kind:?}: {:?}", c.differing);
        assert_eq!(c.stencil_light_left, 0, "{kind:?}");
        // Neither comparison is vacuous: the light reaches both halves.
        assert!(c.lit > 10 && c.unlit_reached > 10, "{kind:?}: {c:?}");
    }
}
