//! Light volumes = full-screen (docs/shading.md §10, "Light volumes"): each light of
//! `check::volumes::volume_cases` (point, point with cube cookie, spot, a point light around
//! the camera) drawn by `deferred_shading/Lighting` over LDR and HDR G-buffers, once the way
//! `light_volume::light_draw` says (icosphere / pyramid after the `stencil_write` pre-pass, or
//! the full-screen fallback) and once full-screen: RT3 must be bit-identical at every pixel,
//! since the light adds exactly nothing where its attenuation is 0. And a deliberately too
//! small volume is caught by the same comparison. Deferred reflection probes drawn as their
//! boxes equal full-screen probes the same way.
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use glam::Vec3;
use wgsl_variants::Library;
use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::volumes::{
    LightRender, VolumeCase, compare_draws, render_light, volume_cases,
};
use wgsl_variants_gpu::check::{
    CHAIN_INPUTS, GBufferImage, LightRig, ProbeDrawing, TestScene, reflection_buffer,
    render_gbuffer,
};
use wgsl_variants_gpu::light_volume::{
    FullScreenReason, LightDraw, LightVolume, light_draw, probe_draw,
};

struct Setup {
    ctx: GpuContext,
    lib: Library,
    scene: TestScene,
    rig: LightRig,
    gbuffers: Vec<GBufferImage>,
}

fn setup() -> Option<Setup> {
    let ctx = common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context",
    )?;
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let rig = LightRig::new(&scene);
    let gbuffers = [false, true]
        .into_iter()
        .map(|hdr| {
            let mut kw = CHAIN_INPUTS[0].names();
            if hdr {
                kw.push("UNITY_HDR_ON");
            }
            render_gbuffer(&ctx, &lib, &scene, &kw).unwrap()
        })
        .collect();
    Some(Setup {
        ctx,
        lib,
        scene,
        rig,
        gbuffers,
    })
}

fn draw(s: &Setup, g: &GBufferImage, case: &VolumeCase, how: &LightDraw) -> LightRender {
    render_light(&s.ctx, &s.lib, &s.scene, &s.rig, g, case, how)
        .unwrap_or_else(|e| panic!("{}: {e}", case.name))
}

#[test]
fn volume_and_full_screen_draws_are_bit_identical() {
    let Some(s) = setup() else {
        return;
    };
    let pixels = (s.scene.width * s.scene.height) as usize;
    let mut volumes = 0;
    let mut fallbacks = 0;
    for g in &s.gbuffers {
        let bpp = g.rt3_format().bytes_per_pixel();
        for case in volume_cases(&s.rig) {
            let how = light_draw(&case.light, s.rig.view_proj).unwrap();
            match &how {
                LightDraw::Volume(_) => volumes += 1,
                LightDraw::FullScreen(reason) => {
                    assert_eq!(*reason, FullScreenReason::CrossesNearPlane, "{}", case.name);
                    fallbacks += 1;
                }
            }
            let full = draw(
                &s,
                g,
                &case,
                &LightDraw::FullScreen(FullScreenReason::Directional),
            );
            let chosen = draw(&s, g, &case, &how);
            let c = compare_draws(&g.targets[3], &full.rt3, &chosen.rt3, bpp);
            eprintln!(
                "{} ({}): {} of {pixels} pixels lit, {:?} stencil-marked, {} differ",
                case.name,
                if g.hdr { "HDR" } else { "LDR" },
                c.lit,
                chosen.stencil_marked,
                c.differing.len()
            );
            assert!(c.identical(), "{} hdr={}: {:?}", case.name, g.hdr, c);
            // Some geometry lies outside the light's reach, except for the light around the
            // camera, whose range (6) holds the whole view: GGX's long tail (BRDF1) then lights
            // every pixel, metallic ones included (a Blinn-Phong lobe of exponent 256
            // underflowed to 0 away from its highlight). Some is lit, except by the light
            // behind the surface (which faces away from it: n · l < 0).
            let behind = case.name == "point behind the surface";
            let whole_view = case.name == "point around the camera";
            assert!(whole_view || c.lit < pixels, "{}: {} lit", case.name, c.lit);
            assert!(behind || c.lit > 0, "{}: nothing lit", case.name);
            let marked = chosen.stencil_marked;
            match (&how, case.name) {
                (LightDraw::FullScreen(_), _) => assert_eq!(marked, None),
                // The surface hides most of this volume: the pre-pass marks those pixels.
                _ if behind => assert!(marked > Some(0), "{marked:?}"),
                // Nothing lies in front of the others.
                _ => assert_eq!(marked, Some(0), "{}", case.name),
            }
        }
    }
    // Four lights as volumes; the light around the camera falls back, in LDR and HDR.
    assert_eq!((volumes, fallbacks), (8, 2));
}

#[test]
fn a_too_small_volume_is_caught() {
    let Some(s) = setup() else {
        return;
    };
    let case = &volume_cases(&s.rig)[1];
    let LightDraw::Volume(volume) = light_draw(&case.light, s.rig.view_proj).unwrap() else {
        panic!("the rig's point light is drawn as a volume");
    };
    // The icosphere shrunk to half its size around the light: it no longer bounds the range.
    let centre = Vec3::new(0.5625, -0.5, 1.0);
    let small = LightVolume {
        positions: volume
            .positions
            .iter()
            .map(|&p| (centre + (Vec3::from(p) - centre) * 0.5).to_array())
            .collect(),
    };
    for g in &s.gbuffers {
        let bpp = g.rt3_format().bytes_per_pixel();
        let full = draw(
            &s,
            g,
            case,
            &LightDraw::FullScreen(FullScreenReason::Directional),
        );
        let culled = draw(&s, g, case, &LightDraw::Volume(small.clone()));
        let c = compare_draws(&g.targets[3], &full.rt3, &culled.rt3, bpp);
        assert!(
            !c.identical(),
            "hdr={}: a half-size volume culls nothing",
            g.hdr
        );
        assert!(
            c.differing.len() < c.lit,
            "the small volume still lights some pixels"
        );
    }
}

/// Deferred reflection probes drawn as their grown boxes (depth test GreaterEqual against the
/// scene's depth) leave the reflection buffer bit-identical to full-screen draws; the small
/// probe is drawn as a box, the probes around the camera full screen.
#[test]
fn probe_boxes_and_full_screen_probes_are_bit_identical() {
    let Some(s) = setup() else {
        return;
    };
    let probes: Vec<_> = s.scene.deferred_probes.iter().map(|(p, _)| *p).collect();
    let expected_boxes = probes
        .iter()
        .filter(|p| matches!(probe_draw(p, s.scene.view_proj), Ok(LightDraw::Volume(_))))
        .count();
    assert!(
        expected_boxes >= 1 && expected_boxes < probes.len(),
        "{expected_boxes} of {} probes as boxes",
        probes.len()
    );
    for g in &s.gbuffers {
        let boxes = reflection_buffer(&s.ctx, &s.lib, &s.scene, g, ProbeDrawing::Boxes).unwrap();
        let full =
            reflection_buffer(&s.ctx, &s.lib, &s.scene, g, ProbeDrawing::FullScreen).unwrap();
        assert_eq!(boxes.boxes, expected_boxes);
        assert_eq!(full.boxes, 0);
        assert!(
            boxes.last == full.last,
            "hdr={}: the box draws change the reflection buffer",
            g.hdr
        );
        assert!(boxes.last.iter().any(|&b| b != 0), "no reflections at all");
    }
}

/// A probe whose box has no volume, or with a NaN, is a typed error, not a NaN frame.
#[test]
fn a_probe_without_volume_is_refused() {
    use wgsl_variants_shaders::reference::probe::{Probe, ProbeError};
    let view_proj = glam::Mat4::IDENTITY;
    let flat = Probe::new(
        Vec3::ZERO,
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, 1.0),
    );
    assert!(matches!(
        probe_draw(&flat, view_proj),
        Err(ProbeError::EmptyBox { .. })
    ));
    let nan = Probe {
        blend_distance: f32::NAN,
        ..Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0))
    };
    assert!(matches!(
        probe_draw(&nan, view_proj),
        Err(ProbeError::NonFinite { .. })
    ));
}
