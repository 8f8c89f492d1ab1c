//! URP's frame forward (`UniversalForward`) and deferred (`UniversalGBuffer`, then
//! `stencil_deferred`'s lights through the material-type stencil), every pixel against the CPU
//! reference and forward against deferred (docs/urp.md §12).
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::urp_frame::{
    UrpFrame, check_urp_frame, compare, render_urp_deferred, render_urp_forward, render_urp_shadows,
};
use wgsl_variants_shaders::reference::light::LightShape;
use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;

/// The adapter, or `None` after the SKIPPED banner (`tests/common/gpu.rs`).
fn context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context",
    )
}

#[test]
fn the_urp_frame_matches_the_reference_both_ways() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let frame = UrpFrame::new();
    let report = check_urp_frame(&ctx, &lib, &frame).expect("the URP frame renders");
    println!("{report}");
    assert!(report.passed(), "{report}");
    // Most of the frame is surface, not silhouette.
    assert!(report.compared > 2000, "{report}");
    assert!(report.edges < report.compared / 5, "{report}");
    // Forward: one draw per object. Deferred: one per object, then the main light, and the
    // three additional lights as their volumes, each after its stencil volume pass.
    assert_eq!(report.forward_draws, 5, "{report}");
    assert_eq!(report.volumes, 3, "{report}");
    assert_eq!(report.deferred_draws, 5 + 1 + 2 * 3, "{report}");
    // Every additional light shows, and the warm point light's layers keep it off the
    // glowing sphere where it would show.
    for (name, lit) in &report.lit_by {
        assert!(*lit > 50, "{name} lights {lit} pixels\n{report}");
    }
    assert!(report.layer_culled > 20, "{report}");
    // The main light's shadow falls on the surfaces in view, mostly clear of its edges.
    assert!(report.shadowed > 50, "{report}");
    assert!(report.uncertain < report.compared / 20, "{report}");
    // Four cascades, URP's split spheres picking one per pixel: each holds part of the frame
    // and the shadow falls in more than one; no pixel lies in two spheres URP's cascade index
    // cannot tell apart.
    let [all, shadowed] = report.cascades;
    assert!(all[..4].iter().all(|&n| n > 50), "{report}");
    assert!(
        shadowed[..4].iter().filter(|&&n| n > 0).count() >= 2,
        "{report}"
    );
    assert_eq!(all[5], 0, "{report}");
    // The cool point light (six cube-face slices) and the spot cast their own shadows on what
    // they light; the warm point light casts none.
    let own = &report.additional_shadowed;
    assert!(own[0] == 0 && own[1] > 50 && own[2] > 50, "{report}");
    // The main light's 4 × 4 cookie shows most of its texels across the frame, its edges
    // crossing it; the cool point light's and the spot's cookies have edges where they light.
    // The warm point light has no cookie.
    assert!(report.main_cookie_texels >= 10, "{report}");
    let edges = &report.cookie_edges;
    assert!(edges[0] > 20 && edges[0] < report.compared / 5, "{report}");
    assert!(edges[1] == 0 && edges[2] > 20 && edges[3] > 20, "{report}");
    // The screen-space occlusion reaches GBuffer3 through the main light in much of the frame.
    assert!(report.occluded > 500, "{report}");
}

/// The main light through URP's screen-space shadow pass in both paths
/// (`_MAIN_LIGHT_SHADOWS_SCREEN`: the cascades turned into a shadow per pixel over the G-buffer
/// pass's depth, and over the forward path's `DepthOnly` prepass): every pixel against the
/// reference (through the pass's 8-bit store) and forward against deferred. A screen-space
/// pass that reads another pixel's depth fails both paths.
#[test]
fn the_urp_frame_with_screen_space_shadows_matches_the_reference() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let mut frame = UrpFrame::new();
    if let Some(spec) = &mut frame.main_shadow {
        spec.screen = true;
    }
    let report = check_urp_frame(&ctx, &lib, &frame).expect("the URP frame renders");
    println!("{report}");
    assert!(report.passed(), "{report}");
    assert!(report.compared > 2000 && report.shadowed > 50, "{report}");
    // The screen-space pass is one more draw of the deferred path; the prepass and the
    // screen-space pass come before the forward path's five.
    assert_eq!(report.deferred_draws, 5 + 1 + 1 + 2 * 3, "{report}");
    assert_eq!(report.forward_draws, 5 + 1 + 5, "{report}");

    let shadow = render_urp_shadows(&ctx, &lib, &frame).expect("shadow");
    let blind = common::mutate::bundled_with(
        "internal/universal_screen_space_shadows.wgsl",
        "depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel)",
        "depth_world_position(depth_tex, deferred_camera.inv_view_proj, pixel / 2)",
    );
    let forward = render_urp_forward(&ctx, &blind, &frame, &shadow).expect("forward");
    let deferred = render_urp_deferred(&ctx, &blind, &frame, &shadow).expect("deferred");
    let report = compare(&frame, &shadow, &forward, &deferred).expect("compare");
    assert!(
        report.failures[0] > 0 && report.failures[2] > 0,
        "a screen-space pass that reads another pixel's depth: not caught\n{report}"
    );
}

/// The frame rendered with a fault, compared with the reference of the true frame: a light
/// 25 % too bright, the main light missing, the rendering layers ignored (the warm point light
/// on every layer), the main light's shadow missing, not fading with the distance or drawn
/// from one map where the frame has cascades, the additional lights' shadows missing or the
/// spot's hard where it is soft, the main light's or the spot's cookie flipped, the cookies
/// dropped, the screen-space occlusion ignored — each fails on both paths; a light volume too
/// small fails deferred only.
#[test]
fn a_wrong_light_is_caught_both_ways() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let truth = UrpFrame::new();
    let truth_shadow = render_urp_shadows(&ctx, &lib, &truth).expect("shadow");
    // The warm point light, which has no cookie: the spot dimmed by its cookie (0.24 to 0.94)
    // and 25 % brighter failed 59 forward pixels but 1 deferred one (four stores' steps).
    let mut brighter = truth.clone();
    brighter.lights[0].params.color *= 1.25;
    let mut no_main = truth.clone();
    no_main.main_light.color = glam::Vec3::ZERO;
    no_main.lighting.main_light_color = glam::Vec3::ZERO;
    let mut unlayered = truth.clone();
    unlayered.lights[0].params.layer_mask = u32::MAX;
    let mut unshadowed = truth.clone();
    unshadowed.main_shadow = None;
    let mut unfaded = truth.clone();
    if let Some(spec) = &mut unfaded.main_shadow {
        spec.fade = UrpShadowFade::NONE;
    }
    let mut one_map = truth.clone();
    if let Some(spec) = &mut one_map.main_shadow {
        spec.cascade_splits = None;
    }
    let mut no_additional = truth.clone();
    no_additional.additional_shadows = None;
    let mut hard_spot = truth.clone();
    if let Some(spec) = &mut hard_spot.additional_shadows {
        spec.casting[2] = spec.casting[2].map(|(strength, _)| (strength, false));
    }
    // A cookie mirrored across its x axis: light space x negated before the projection.
    let mirror = glam::Mat4::from_scale(glam::Vec3::new(-1.0, 1.0, 1.0));
    let mut flipped_main = truth.clone();
    if let Some(c) = &mut flipped_main.cookies {
        c.main.world_to_light = mirror * c.main.world_to_light;
    }
    let mut flipped_spot = truth.clone();
    if let Some(spot) = flipped_spot
        .cookies
        .as_mut()
        .and_then(|c| c.additional.lights[2].as_mut())
    {
        spot.world_to_light = mirror * spot.world_to_light;
    }
    let mut uncookied = truth.clone();
    uncookied.cookies = None;
    let mut unoccluded = truth.clone();
    unoccluded.occlusion = None;
    for (what, wrong) in [
        ("the warm point light 25 % brighter", &brighter),
        ("no main light", &no_main),
        ("rendering layers ignored", &unlayered),
        ("no main-light shadow", &unshadowed),
        ("the shadow's fade ignored", &unfaded),
        ("one map instead of the cascades", &one_map),
        ("no additional-light shadows", &no_additional),
        ("the spot's shadow hard", &hard_spot),
        ("the main light's cookie flipped", &flipped_main),
        ("the spot's cookie flipped", &flipped_spot),
        ("no cookies", &uncookied),
        ("the screen-space occlusion ignored", &unoccluded),
    ] {
        let shadow = render_urp_shadows(&ctx, &lib, wrong).expect("shadow");
        let forward = render_urp_forward(&ctx, &lib, wrong, &shadow).expect("forward");
        let deferred = render_urp_deferred(&ctx, &lib, wrong, &shadow).expect("deferred");
        let report = compare(&truth, &truth_shadow, &forward, &deferred).expect("compare");
        println!("{what}: failures {:?}", report.failures);
        assert!(
            report.failures[0] > 0 && report.failures[2] > 0,
            "{what}: not caught\n{report}"
        );
    }
    // The warm point light's volume built for half its range: the deferred path's light stops
    // at the volume, the forward path is right.
    let mut small = truth.clone();
    if let LightShape::Point { range, .. } = &mut small.lights[0].light.shape {
        *range *= 0.5;
    }
    let forward = render_urp_forward(&ctx, &lib, &small, &truth_shadow).expect("forward");
    let deferred = render_urp_deferred(&ctx, &lib, &small, &truth_shadow).expect("deferred");
    let report = compare(&truth, &truth_shadow, &forward, &deferred).expect("compare");
    assert!(
        report.failures[0] == 0 && report.failures[2] > 0 && report.failures[3] > 0,
        "a light volume half its size: not caught\n{report}"
    );
}

/// URP's `BEYOND_SHADOW_FAR`: with one map whose box (radius 3: 6 units along the light on
/// either side of its centre) ends short of the far floor, the receivers beyond its far plane
/// read as lit, both ways and in the reference; a receiver that compares them with the map
/// anyway (the rule dropped) darkens them and fails both paths.
#[test]
fn receivers_beyond_the_shadow_maps_far_plane_are_lit() {
    let Some(ctx) = context() else {
        return;
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let mut frame = UrpFrame::new();
    if let Some(spec) = &mut frame.main_shadow {
        spec.cascade_splits = None;
        spec.radius = 3.0;
    }
    let shadow = render_urp_shadows(&ctx, &lib, &frame).expect("shadow");
    let params = &shadow
        .main
        .as_ref()
        .expect("the frame's main light casts")
        .params;
    let g = &frame.geometry;
    let beyond = g
        .pixels()
        .filter_map(|(x, y)| g.cast(f64::from(x) + 0.5, f64::from(y) + 0.5))
        .filter(|hit| params.coords(hit.geometry.world_position).z >= 1.0)
        .count();
    println!("{beyond} pixels see a surface beyond the map's far plane");
    assert!(beyond > 100, "{beyond}");
    let report = check_urp_frame(&ctx, &lib, &frame).expect("the URP frame renders");
    println!("{report}");
    assert!(report.passed(), "{report}");

    let unruled = common::mutate::bundled_with(
        "universal/main_light_shadow_map.wgsl",
        "if c.z <= 0.0 || c.z >= 1.0 {",
        "if false {",
    );
    let forward = render_urp_forward(&ctx, &unruled, &frame, &shadow).expect("forward");
    let deferred = render_urp_deferred(&ctx, &unruled, &frame, &shadow).expect("deferred");
    let report = compare(&frame, &shadow, &forward, &deferred).expect("compare");
    println!("with the rule dropped: {:?}", report.failures);
    assert!(
        report.failures[0] > 0 && report.failures[2] > 0,
        "BEYOND_SHADOW_FAR dropped: not caught\n{report}"
    );
}
