//! URP's `universal_screen_space_shadows/ScreenSpaceShadows` for the GPU check (docs/urp.md
//! §9): every variant — the main light's map or its cascades, hard or soft — draws the main
//! light's realtime shadow over the rig's depth buffer into an `Rgba8Unorm` target (URP's
//! `R8_UNorm`, or its 8-bit BGRA fallback: the same codes), and every pixel is compared with
//! [`ScreenShadow::urp_factor`] at the position rebuilt from depth, the same maps the receivers'
//! checks bind (1 LSB of an 8-bit store, within the interval of a tap or split within a hair of
//! flipping), all four channels alike; then each keyword is shown to change a pixel.
//!
//! The receivers' `_MAIN_LIGHT_SHADOWS_SCREEN` variants are checked against a stand-in texture
//! ([`super::screen_masks::ScreenShadowTexture`]); this check proves what the real one holds.

use std::time::Instant;

use super::camera::depth_camera_resources;
use super::compare::mask_code_within;
use super::coverage::judge_every_variant;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::screen_masks::{ScreenShadow, render_mask};
use super::urp_lighting::main_light_shadow;
use crate::GpuError;
use wgsl_variants_shaders::reference::urp::forward::MainLightShadows;

/// The shader and pass.
const PASS: (&str, &str) = ("universal_screen_space_shadows", "ScreenSpaceShadows");

/// Checks every variant of URP's screen-space shadow pass over the rig's camera view (the
/// rig's screen shadows must be rendered: the main light's map and cascades are the
/// `DIRECTIONAL` light's).
///
/// # Errors
/// A GPU failure, a variant that does not compile, or no main-light shadow in the rig.
pub(crate) fn check_urp_screen_shadows(setup: &Setup<'_>) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let (scene, rig) = (setup.scene, setup.rig);
    let label = format!("{}/{}", PASS.0, PASS.1);
    let pass = setup.pass(PASS.0, PASS.1)?;
    let shadow: &ScreenShadow = main_light_shadow(rig, &label)?;
    let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    let mut report = PassReport::new(PASS.0, PASS.1);
    let size = (scene.width, scene.height);
    let positions: Vec<_> = scene
        .pixels()
        .map(|(x, y)| rig.deferred_position(scene, x, y))
        .collect();
    let mut resources = depth_camera_resources(size, &rig.camera(scene));
    resources.extend(shadow.urp_resources());
    let (mut shadowed, mut uncertain) = (0usize, 0usize);
    let mut images = Vec::with_capacity(choices.len());
    for choice in &choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let names = variant.keywords();
        let mode = MainLightShadows::of(&names);
        let soft = names.contains(&"_SHADOWS_SOFT");
        let image = render_mask(
            setup.ctx,
            &variant.label(),
            &setup.lib.wgsl(&variant),
            size,
            resources.clone(),
        )?;
        for (i, (x, y)) in scene.pixels().enumerate() {
            let (lo, hi) = shadow.urp_factor(mode, soft, positions[i], (x, y));
            shadowed += usize::from(hi < 1.0);
            uncertain += usize::from(lo != hi);
            let px = &image[i * 4..i * 4 + 4];
            let got = f32::from(px[0]) / 255.0;
            report.record(
                mask_code_within(px[0], lo, hi) && px.iter().all(|&c| c == px[0]),
                || Mismatch {
                    shader: PASS.0.to_owned(),
                    pass: PASS.1.to_owned(),
                    keywords: format!("{{{}}}", names.join(", ")),
                    target: "screen-space shadow Rgba8Unorm".to_owned(),
                    pixel: [x, y],
                    expected: vec![lo, hi],
                    got: vec![got],
                    got_raw: px.iter().map(|&b| u32::from(b)).collect(),
                },
            );
        }
        images.push(image);
        report.draws += 1;
    }
    judge_every_variant(&mut report, pass, &choices, &images);
    report.notes.push(format!(
        "full-screen draws over the {}x{} depth of the rig's perspective camera, the main light's map and URP's four cascades (its {}); {shadowed} shadowed and {uncertain} uncertain pixel comparisons",
        scene.width,
        scene.height,
        shadow.urp_cascade_census(&positions),
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `universal_screen_space_shadows/ScreenSpaceShadows` in the check's registry.
pub(crate) struct UrpScreenShadows;

/// The entry of URP's screen-space shadow pass: the rig's main-light shadow over its depth.
pub(crate) static URP_SCREEN_SHADOWS: UrpScreenShadows = UrpScreenShadows;

impl PassCheck for UrpScreenShadows {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[PASS]
    }

    fn needs(&self) -> Needs {
        Needs {
            screen_masks: true,
            ..Needs::NOTHING
        }
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_urp_screen_shadows(setup)?])
    }
}
