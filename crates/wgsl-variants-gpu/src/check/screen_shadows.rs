//! `SHADOWS_SCREEN` for the GPU check (docs/shading.md §11): each directional light of the
//! [`LightRig`] gets cascaded shadow maps — 1, 2 and 4 cascades fitted to slices of the rig's
//! camera view, each the occluder scene of [`super::shadows`] rendered by
//! `standard/ShadowCaster` (`SHADOWS_DEPTH`) through the cascade's orthographic view into its
//! tile of an atlas ([`Cascades::fit`]) — and every `screen_space_shadows/Collect` variant
//! turns each atlas into a mask of the rig's camera view, over the same depth buffer the
//! `Lighting` check rebuilds its positions from. The atlases are read back: the reference
//! compares every mask texel with [`Cascades::factor`] over the read-back atlas at the rebuilt
//! position (an interval where a tap is within a hair of flipping, or the position within a
//! hair of a split, where both cascades count), and the `Lighting` variants with
//! `SHADOWS_SCREEN` read the rendered 4-cascade mask, as the reference does, so the lighting's
//! use of it is tested exactly.
//!
//! The maps and masks themselves ([`ScreenShadows`]) are rendered with the rig, which carries
//! them; this module checks the masks and keeps their public path.
//!
//! [`Cascades::fit`]: wgsl_variants_shaders::reference::cascades::Cascades::fit
//! [`Cascades::factor`]: wgsl_variants_shaders::reference::cascades::Cascades::factor

use std::time::Instant;

use super::compare::mask_code_within;
use super::coverage::keyword_coverage;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::rig::LightRig;
use super::scene::TestScene;
use super::shadows::MAP_SIZE;
use crate::{CheckError, GpuContext, GpuError};
use glam::Vec3;
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades};

pub use super::screen_masks::{
    CASCADE_COUNTS, CascadeAtlas, CascadeSet, DIRECTIONAL_STRENGTH, REGION_RADIUS, ScreenShadow,
    ScreenShadowTexture, ScreenShadows,
};

impl ScreenShadows {
    /// Renders each directional light's map of `rig` with the cut-out caster, then every
    /// `Collect` variant over the rig's depth buffer (what [`LightRig::render_screen_shadows`]
    /// keeps in the rig).
    ///
    /// # Errors
    /// A GPU failure, a variant that does not compile, or a map the reference refuses.
    pub fn render(
        ctx: &GpuContext,
        lib: &Library,
        scene: &TestScene,
        rig: &LightRig,
    ) -> Result<ScreenShadows, GpuError> {
        ScreenShadows::render_lights(
            ctx,
            lib,
            scene,
            rig.directional_lights(),
            &rig.camera(scene),
        )
    }
}

/// Checks every `Collect` variant's mask of each directional light and cascade count: every
/// pixel against [`Cascades::factor`] over the read-back atlas at the position rebuilt from
/// depth (1 LSB of `Rgba8Unorm`, within the interval of an uncertain tap or cascade), and each
/// keyword changing a pixel.
///
/// [`Cascades::factor`]: wgsl_variants_shaders::reference::cascades::Cascades::factor
pub fn check_collect(
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    shadows: &ScreenShadows,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let pass = lib
        .pass("screen_space_shadows", "Collect")
        .map_err(|e| CheckError::lookup("screen_space_shadows/Collect", e))?;
    let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    let mut report = PassReport::new("screen_space_shadows", "Collect");
    let mut uncertain = 0usize;
    let mut shadowed = 0usize;
    // Per view, pixels per cascade (then none, several) of the 4-cascade sets split by view
    // depth and by spheres.
    let mut picked = [[[0usize; 6]; 2]; 2];
    let (w, h) = (scene.width, scene.height);
    let rig_positions: Vec<Vec3> = scene
        .pixels()
        .map(|(x, y)| rig.deferred_position(scene, x, y))
        .collect();
    let deep_positions: Vec<Vec3> = scene
        .pixels()
        .map(|(x, y)| shadows.deep.position(x, y, w, h))
        .collect();
    for (v, names) in shadows.variants.iter().enumerate() {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let keywords = CascadeKeywords::of(&names);
        for light in &shadows.lights {
            let views = [
                ("camera", &light.sets, &rig_positions),
                ("deep", &light.deep_sets, &deep_positions),
            ];
            for (view, (name, sets, positions)) in views.into_iter().enumerate() {
                for (set, count) in sets.iter().zip(CASCADE_COUNTS) {
                    let mask = &set.masks[v];
                    for (i, (x, y)) in scene.pixels().enumerate() {
                        let p = positions[i];
                        let (lo, hi) = set.atlas.cascades.factor(keywords, &set.atlas.map, p);
                        if count == 4
                            && !keywords.single
                            && !keywords.soft
                            && let Some(w) = set.atlas.cascades.candidates(keywords, p)[0]
                        {
                            picked[view][usize::from(keywords.split_spheres)]
                                [Cascades::picked(w)] += 1;
                        }
                        uncertain += usize::from(lo != hi);
                        shadowed += usize::from(hi < 1.0);
                        let got = mask[i * 4];
                        let rest = [mask[i * 4 + 1], mask[i * 4 + 2], mask[i * 4 + 3]];
                        report.record(mask_code_within(got, lo, hi) && rest == [255; 3], || {
                            Mismatch {
                                shader: "screen_space_shadows".to_owned(),
                                pass: "Collect".to_owned(),
                                keywords: format!(
                                    "{{{}}} for {:?}, {count} cascade(s), {name} view",
                                    names.join(", "),
                                    light.light
                                ),
                                target: "mask Rgba8Unorm".to_owned(),
                                pixel: [x, y],
                                expected: vec![lo, hi],
                                got: vec![f32::from(got) / 255.0],
                                got_raw: mask[i * 4..i * 4 + 4]
                                    .iter()
                                    .map(|&b| u32::from(b))
                                    .collect(),
                            }
                        });
                    }
                    report.draws += 1;
                }
            }
        }
        report.variants_run += 1;
        report.distinct_shaders += 1;
    }
    report.keywords = keyword_coverage(pass, &choices, |a, b| {
        shadows
            .lights
            .iter()
            .flat_map(|l| l.sets.iter().chain(&l.deep_sets))
            .any(|s| s.masks[a] != s.masks[b])
    });
    report.judge_keywords();
    report.notes.push(format!(
        "the {}x{} masks of 2 directional lights with 1, 2 and 4 cascades, over the camera's view and a deep view along the floor (atlases of {MAP_SIZE}x{MAP_SIZE} Depth16Unorm tiles, one orthographic view per slice of the view); {shadowed} shadowed and {uncertain} uncertain pixel comparisons; pixels per cascade 0-3, none and several of the 4 cascades: camera view by view depth {:?}, by split spheres {:?}; deep view by view depth {:?}, by split spheres {:?}",
        scene.width, scene.height, picked[0][0], picked[0][1], picked[1][0], picked[1][1]
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `screen_space_shadows/Collect` in the check's registry.
pub(crate) struct Collect;

/// The entry of `screen_space_shadows/Collect`: the masks the rig rendered.
pub(crate) static COLLECT: Collect = Collect;

impl PassCheck for Collect {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("screen_space_shadows", "Collect")]
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
        let Some(screen) = &setup.rig.screen_shadows else {
            return Ok(Vec::new());
        };
        Ok(vec![check_collect(
            setup.lib,
            setup.scene,
            setup.rig,
            screen,
        )?])
    }
}
