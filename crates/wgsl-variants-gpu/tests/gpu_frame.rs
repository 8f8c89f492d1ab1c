//! The whole built-in frame forward and deferred, HDR and LDR, every pixel against the CPU
//! reference and forward against deferred (docs/shading.md §12).
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::frame::{
    FrameScene, check_frame, compare, render_deferred, render_forward, render_shadows,
};

/// The adapter, or `None` after the SKIPPED banner (`tests/common/gpu.rs`).
fn context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context",
    )
}

fn frame_passes(hdr: bool) {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let frame = FrameScene::new();
    let report = check_frame(&ctx, &lib, &frame, hdr).expect("the frame renders");
    println!("{report}");
    assert!(report.passed(), "{report}");
    // Most of the frame is surface, not silhouette.
    assert!(report.compared > 2000, "{report}");
    assert!(report.edges < report.compared / 5, "{report}");
    // Forward: the depth pre-pass, the two directional lights' masks, ForwardBase, ForwardAdd.
    assert_eq!(report.forward_draws, 5 + 2 + 5 + 5 * 4);
    // Deferred: the G-buffer, the masks, five lights, and the final pass in LDR.
    assert_eq!(report.deferred_draws, 5 + 2 + 5 + usize::from(!hdr));
    // Shadows fall on the surfaces in view, and most pixels are clear of a shadow edge.
    assert!(report.shadowed > 100, "{report}");
    assert!(report.uncertain < report.compared / 20, "{report}");
    // The point and spot lights are drawn as their volumes (none crosses a clip plane), the
    // directional ones full screen.
    assert_eq!(report.volumes, 3, "{report}");
}

#[test]
fn the_hdr_frame_is_the_same_forward_and_deferred() {
    frame_passes(true);
}

#[test]
fn the_ldr_frame_is_the_same_forward_and_deferred() {
    frame_passes(false);
}

/// The comparison is sharp: a frame rendered with the main light 10 % too bright, the warm
/// point light 25 % too bright in HDR (50 % in LDR, whose 8-bit targets round each of the five
/// forward draws), without the spot light's draws, without the shadows, or without one
/// directional light's screen-space shadow fails against the reference of the true frame, on
/// both paths.
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
    let truth_shadows = render_shadows(&ctx, &lib, &truth).expect("shadows");
    for (what, wrong, modes) in [
        ("main light 10 % brighter", &main, &[true, false][..]),
        ("warm point 25 % brighter", &point_hdr, &[true]),
        ("warm point 50 % brighter", &point_ldr, &[false]),
        ("no spot", &missing, &[true, false]),
        ("no shadows", &unshadowed, &[true, false]),
        ("no main-light shadow", &main_unshadowed, &[true, false]),
        ("no cookie-sun shadow", &sun_unshadowed, &[true]),
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
