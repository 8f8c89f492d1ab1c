//! The whole built-in frame forward and deferred, HDR and LDR, every pixel against the CPU
//! reference and forward against deferred (docs/shading.md §12), in BRDF1 (Unity's desktop
//! tier) and, HDR, BRDF3 (the lookup table), LDR, BRDF2.
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::frame::{
    FrameScene, ResidentFrame, check_frame, compare, render_deferred, render_forward,
    render_shadows,
};
use wgsl_variants_shaders::reference::brdf::Brdf;

/// The adapter, or `None` after the SKIPPED banner (`tests/common/gpu.rs`).
fn context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context",
    )
}

fn frame_passes(hdr: bool, brdf: Brdf) {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let frame = FrameScene::new().with_brdf(brdf);
    let report = check_frame(&ctx, &lib, &frame, hdr).expect("the frame renders");
    println!("{brdf:?}: {report}");
    assert!(report.passed(), "{report}");
    // Most of the frame is surface, not silhouette.
    assert!(report.compared > 2000, "{report}");
    assert!(report.edges < report.compared / 5, "{report}");
    // The forward part both paths share: the sky, then two semi-transparent objects,
    // ForwardBase and a ForwardAdd draw per light, but the warm point light's culling mask
    // leaves out the glass sphere.
    let transparent = 1 + 2 * (1 + 4) - 1;
    // Forward: the depth pre-pass, the two directional lights' masks, ForwardBase, ForwardAdd
    // (the cookie sun and the cool point light leave out the glowing sphere).
    assert_eq!(report.forward_draws, 5 + 2 + 5 + 5 * 4 - 2 + transparent);
    // Deferred: the G-buffer, the masks, five lights (the three volumes each after its
    // stencil pre-pass), and the final pass in LDR.
    assert_eq!(
        report.deferred_draws,
        5 + 2 + 5 + 3 + usize::from(!hdr) + transparent
    );
    // The culling masks keep three lights (the main light one of them) off the glowing
    // sphere, where each would show.
    assert!(report.culled > 50, "{report}");
    // The semi-transparent objects cover opaque objects and the background.
    assert!(report.through_transparent > 100, "{report}");
    // Shadows fall on the surfaces in view, and most pixels are clear of a shadow edge.
    assert!(report.shadowed > 100, "{report}");
    assert!(report.uncertain < report.compared / 20, "{report}");
    // The point and spot lights are drawn as their volumes (none crosses a clip plane), the
    // directional ones full screen.
    assert_eq!(report.volumes, 3, "{report}");
}

#[test]
fn the_hdr_frame_is_the_same_forward_and_deferred() {
    frame_passes(true, Brdf::Brdf1);
    frame_passes(true, Brdf::Brdf3);
}

#[test]
fn the_ldr_frame_is_the_same_forward_and_deferred() {
    frame_passes(false, Brdf::Brdf1);
    frame_passes(false, Brdf::Brdf2);
}

/// The comparison is sharp: a frame rendered with the main light 10 % too bright, the warm
/// point light 25 % too bright in HDR (50 % in LDR, whose 8-bit targets round each of the five
/// forward draws), without the spot light's draws, without the shadows, without one
/// directional light's screen-space shadow, with the floor's lightmap decoded with the wrong
/// range (RGBM's gamma-space 5 for its linear 34.49), with the glass sphere more opaque
/// (alpha 0.45 → 0.55), with the sky turned the wrong way, or with every light lighting every
/// layer (the culling masks ignored; or only the main light's) fails against the reference of the true frame, on both
/// paths.
#[test]
fn a_light_too_bright_or_missing_is_caught() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let truth = FrameScene::new();
    let mut main = truth.clone();
    main.scene.light_color *= 1.1;
    main.main_light.color *= 1.1;
    let brighter = |factor: f32| {
        let mut frame = truth.clone();
        frame.lights[0].params.color *= factor;
        frame
    };
    let (point_hdr, point_ldr) = (brighter(1.25), brighter(1.5));
    let mut missing = truth.clone();
    missing.lights.pop();
    let mut unshadowed = truth.clone();
    unshadowed.main_shadow = None;
    for light in &mut unshadowed.lights {
        light.shadow = None;
    }
    let mut main_unshadowed = truth.clone();
    main_unshadowed.main_shadow = None;
    let mut sun_unshadowed = truth.clone();
    sun_unshadowed.lights[1].shadow = None;
    let mut lightmap_range = truth.clone();
    lightmap_range.scene.lightmap_decode.baked.x = 5.0;
    let mut opaque_glass = truth.clone();
    opaque_glass.transparent[0].material.tint.w = 0.55;
    let mut sky_turned = truth.clone();
    if let Some(sky) = &mut sky_turned.sky {
        sky.skybox.rotation_degrees = -sky.skybox.rotation_degrees;
    }
    let mut unmasked = truth.clone();
    for light in &mut unmasked.lights {
        light.culling_mask = u32::MAX;
    }
    let mut main_unmasked = truth.clone();
    main_unmasked.main_culling_mask = u32::MAX;
    let truth_shadows = render_shadows(&ctx, &lib, &truth).expect("shadows");
    for (what, wrong, modes) in [
        ("main light 10 % brighter", &main, &[true, false][..]),
        ("warm point 25 % brighter", &point_hdr, &[true]),
        ("warm point 50 % brighter", &point_ldr, &[false]),
        ("no spot", &missing, &[true, false]),
        ("no shadows", &unshadowed, &[true, false]),
        ("no main-light shadow", &main_unshadowed, &[true, false]),
        ("no cookie-sun shadow", &sun_unshadowed, &[true]),
        ("lightmap range 5", &lightmap_range, &[true, false]),
        ("glass alpha 0.55", &opaque_glass, &[true, false]),
        ("sky turned the wrong way", &sky_turned, &[true, false]),
        ("culling masks ignored", &unmasked, &[true, false]),
        (
            "the main light's culling mask ignored",
            &main_unmasked,
            &[true, false],
        ),
    ] {
        for &hdr in modes {
            let shadows = render_shadows(&ctx, &lib, wrong).expect("shadows");
            let forward = render_forward(&ctx, &lib, wrong, &shadows, hdr).expect("forward");
            let deferred = render_deferred(&ctx, &lib, wrong, &shadows, hdr).expect("deferred");
            let report = compare(&truth, &truth_shadows, &forward, &deferred, hdr);
            assert!(
                report.failures[0] > 0 && report.failures[1] > 0,
                "{what}, hdr {hdr}: not caught\n{report}"
            );
        }
    }
}

/// The frame's scenes the GPU-resident frame can draw: the test frame without its
/// screen-space shadows (the point light's cube shadow, the spot's map, both cookies, the
/// spot's volume and the semi-transparent objects stay), and the bench's frame of 16 point
/// lights.
fn resident_scenes() -> Vec<(&'static str, FrameScene)> {
    let mut four = FrameScene::new();
    four.main_shadow = None;
    four.lights[1].shadow = None;
    vec![
        ("four lights", four),
        ("16 point lights", FrameScene::new().with_point_lights(16)),
    ]
}

/// The frame kept on the GPU between passes (what the frame bench times) is the frame read
/// back between passes, bit for bit, forward and deferred, HDR and LDR; so it passes the
/// reference comparison too. Each timed pass's timestamps are in order (start ≤ end, passes
/// in submission order), where the adapter has timestamp queries; without them (forced) no
/// pass times come back. The Lighting pass's fragment count lies between one full-screen
/// light and every light full screen, and its bytes per fragment are the bound formats'.
#[test]
fn the_gpu_resident_frame_is_the_read_back_frame() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    if !ctx.has_timestamps() {
        eprintln!(
            "NOTE: {} has no timestamp queries: pass times not checked",
            ctx.adapter_name()
        );
    }
    for (name, frame) in resident_scenes() {
        let shadows = render_shadows(&ctx, &lib, &frame).expect("shadows");
        for hdr in [true, false] {
            let what = format!("{name}, hdr {hdr}");
            let forward = ResidentFrame::forward(&ctx, &lib, &frame, &shadows, hdr).expect(&what);
            let deferred = ResidentFrame::deferred(&ctx, &lib, &frame, &shadows, hdr).expect(&what);
            // The forward part, where the scene has a sky or semi-transparent objects.
            let part = frame.sky.is_some() || !frame.transparent.is_empty();
            let transparent = part.then_some("forward part");
            let mut names = vec!["forward base", "forward add"];
            names.extend(transparent);
            assert_eq!(forward.pass_names(), names);
            let mut names = vec!["G-buffer", "lighting"];
            if !hdr {
                names.push("final");
            }
            names.extend(transparent);
            assert_eq!(deferred.pass_names(), names);
            for path in [&forward, &deferred] {
                let time = path.run(&ctx).expect(&what);
                assert_eq!(time.passes.is_some(), ctx.has_timestamps(), "{what}");
                if let Some(spans) = &time.passes {
                    assert_eq!(spans.len(), path.pass_names().len(), "{what}");
                    for (i, s) in spans.iter().enumerate() {
                        assert!(s.start_ns <= s.end_ns, "{what}: pass {i} {spans:?}");
                        if i > 0 {
                            assert!(spans[i - 1].start_ns <= s.start_ns, "{what}: {spans:?}");
                        }
                    }
                }
            }
            let (f, d) = (
                forward.image(&ctx).expect(&what),
                deferred.image(&ctx).expect(&what),
            );
            let read_back_f = render_forward(&ctx, &lib, &frame, &shadows, hdr).expect(&what);
            let read_back_d = render_deferred(&ctx, &lib, &frame, &shadows, hdr).expect(&what);
            assert!(f.bytes == read_back_f.bytes, "{what}: forward differs");
            assert!(d.bytes == read_back_d.bytes, "{what}: deferred differs");
            assert_eq!(f.draws, read_back_f.draws, "{what}");
            // The read-back frame counts the depth fill as no draw; the resident frame has none.
            assert_eq!(d.draws, read_back_d.draws, "{what}");
            assert_eq!(d.volumes, read_back_d.volumes, "{what}");
            let report = compare(&frame, &shadows, &f, &d, hdr);
            assert_eq!(report.failures, [0; 3], "{what}\n{report}");

            let traffic = deferred.lighting_traffic(&ctx).expect(&what).expect(&what);
            let pixels = u64::from(frame.width * frame.height);
            let lights = frame.lights.len() as u64;
            assert!(
                traffic.fragments > pixels && traffic.fragments < pixels * (1 + lights),
                "{what}: {traffic:?}"
            );
            let expected = if hdr { (24, 8) } else { (20, 4) };
            assert_eq!(
                (
                    traffic.bytes_read_per_fragment,
                    traffic.bytes_written_per_fragment
                ),
                expected,
                "{what}"
            );
            assert!(forward.lighting_traffic(&ctx).expect(&what).is_none());
            let untimed = forward.without_timestamps();
            assert!(!untimed.timed());
            assert!(untimed.run(&ctx).expect(&what).passes.is_none(), "{what}");
        }
    }
}

/// A scene whose directional lights need screen-space masks (made from a depth read-back) is
/// refused by the GPU-resident frame with a message that says why.
#[test]
fn the_gpu_resident_frame_refuses_screen_space_masks() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let frame = FrameScene::new();
    let shadows = render_shadows(&ctx, &lib, &frame).expect("shadows");
    let err = ResidentFrame::deferred(&ctx, &lib, &frame, &shadows, true)
        .expect_err("screen-space masks need a read-back")
        .to_string();
    assert!(err.contains("screen-space shadow masks"), "{err}");
}
