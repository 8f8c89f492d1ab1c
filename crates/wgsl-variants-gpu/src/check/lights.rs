//! The check of `deferred_shading/Lighting`: every variant drawn full-screen over G-buffers
//! rendered by `standard/Deferred` on the same GPU, with the world position rebuilt from a
//! depth buffer of a perspective camera, and compared with
//! [`wgsl_variants_shaders::reference::light::deferred_light`] blended as the pass's HDR mode says.
//!
//! The lights are the [`LightRig`]'s: one of each type, with cookies placed
//! [`MIN_COOKIE_MARGIN`] clear of texel and cube-face edges. The rig is one of the parts the
//! checks share, so it lives below them; this module still names it, as it always has.

use std::collections::HashMap;
use std::time::Instant;

use super::compare::{compare_texel, format_name, pixel};
use super::coverage::SmallPass;
use super::gbuffer::{CHAIN_INPUTS, GBufferImage, render_gbuffer};
use super::lighting::render_lighting;
use super::options::CheckOptions;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::PassReport;
use super::rig::shadowed;
use super::scene::TestScene;
use super::shadows::within;
use crate::{CheckError, GpuContext, GpuError};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::brdf::Brdf;
use wgsl_variants_shaders::reference::light::{Cookies, LightType, deferred_light};
use wgsl_variants_shaders::reference::shadow::{ShadowKeywords, baked_occlusion};
use wgsl_variants_shaders::reference::surface::{Keywords, reflections_add};

pub use super::rig::{LightRig, MIN_COOKIE_MARGIN};

/// The light type, shadow keywords and the rest (HDR mode, BRDF tier) of a
/// `deferred_shading/Lighting` keyword set.
fn lighting_keywords(names: &[&str]) -> Result<(LightType, ShadowKeywords, Keywords), String> {
    let (light, rest) = LightType::split(names);
    let light = light.ok_or_else(|| format!("no light keyword in {names:?}"))?;
    let (shadow, rest) = ShadowKeywords::split(&rest);
    let kw = Keywords::from_names(&rest).map_err(|e| e.to_string())?;
    Ok((light, shadow, kw))
}

/// Draws one `Lighting` variant over `gbuffer`, compares every pixel, returns RT3 decoded.
#[allow(clippy::too_many_arguments)]
fn run_lighting(
    ctx: &GpuContext,
    scene: &TestScene,
    rig: &LightRig,
    gbuffer: &GBufferImage,
    (label, keywords): (&str, &str),
    wgsl: &str,
    (light, shadow, brdf): (LightType, ShadowKeywords, Brdf),
    report: &mut PassReport,
) -> Result<Vec<[f32; 4]>, GpuError> {
    let (w, h) = (scene.width, scene.height);
    let format = gbuffer.rt3_format();
    let camera = rig.camera(scene);
    let out = render_lighting(
        ctx,
        scene,
        rig,
        gbuffer,
        label,
        wgsl,
        rig.params(light),
        &camera,
        gbuffer.targets[3].clone(),
    )?;
    report.draws += 1;

    let cookie = rig.cookie_2d();
    let cookies = Cookies {
        texture: &cookie,
        cube: &rig.cube,
    };
    let input = format!(
        "{keywords} over the G-buffer of standard/Deferred {{{}}}",
        gbuffer.keywords.join(", ")
    );
    let target = format!("RT3 {}", format_name(format));
    let mut uncertain = 0usize;
    for (i, (x, y)) in scene.pixels().enumerate() {
        let stored = gbuffer.texel(i);
        let rt3 = stored.rt3.to_vec4();
        let p = rig.deferred_position(scene, x, y);
        // The realtime shadow faded and mixed with the baked occlusion as stored in RT4 (1
        // without it).
        let baked = stored_baked(gbuffer, shadow, light, i);
        let (lo, hi) = rig.received_factor(light, shadow, (p, i), baked);
        let [want_lo, want_hi] = [lo, hi].map(|f| {
            let c = deferred_light(
                brdf,
                &stored.to_gbuffer(),
                p,
                scene.scene.camera_position,
                &shadowed(rig.params(light), f),
                light,
                Some(cookies),
            );
            reflections_add(rt3.truncate(), c, gbuffer.hdr).extend(rt3.w)
        });
        uncertain += usize::from(lo != hi);
        let want = within(pixel(format, &out, i).1, want_lo, want_hi);
        compare_texel(report, &input, &target, format, &out, i, w, want);
    }
    if uncertain > 0 {
        report.notes.push(format!(
            "{input}: {uncertain} pixels with a shadow tap within a hair of flipping, compared within the interval of its outcomes"
        ));
    }
    Ok((0..(w * h) as usize)
        .map(|i| pixel(format, &out, i).1)
        .collect())
}

/// Light `light`'s baked occlusion at pixel `i` as the lighting pass reads it from `gbuffer`'s
/// RT4 with `SHADOWS_SHADOWMASK` (1 without the keyword).
fn stored_baked(gbuffer: &GBufferImage, shadow: ShadowKeywords, light: LightType, i: usize) -> f32 {
    match gbuffer.shadowmask(i) {
        Some(rt4) if shadow.shadowmask => baked_occlusion(rt4, LightRig::occlusion_mask(light)),
        _ => 1.0,
    }
}

/// Checks every variant of `deferred_shading/Lighting` over the LDR and HDR G-buffers of each
/// `CHAIN_INPUTS` keyword set of the deferred chain check, and that each keyword changes the
/// result; or the covering set `options` ask for ([`CheckOptions::cover_for`]).
pub fn check_deferred_shading(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    options: &CheckOptions,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let small = SmallPass::new(lib, "deferred_shading", "Lighting", options)?;
    let (pass, choices) = (small.pass, small.choices.as_slice());
    let mut report = PassReport::new("deferred_shading", "Lighting");
    // The G-buffers, rendered once per input, HDR mode and shadowmask (RT4 or not).
    let mut gbuffers: HashMap<(usize, bool, bool), GBufferImage> = HashMap::new();
    for (n, keywords) in CHAIN_INPUTS.iter().enumerate() {
        for hdr in [false, true] {
            for shadowmask in [false, true] {
                let mut kw: Vec<&str> = keywords.names();
                if hdr {
                    kw.push("UNITY_HDR_ON");
                }
                if shadowmask {
                    kw.push("SHADOWS_SHADOWMASK");
                }
                let gbuffer = render_gbuffer(ctx, lib, scene, &kw)?;
                gbuffers.insert((n, hdr, shadowmask), gbuffer);
            }
        }
    }
    // outputs[v][n]: variant v over input n.
    let mut outputs: Vec<Vec<Vec<[f32; 4]>>> = Vec::new();
    for choice in choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let label = variant.label();
        let names = variant.keywords();
        let (light, shadow, kw) = lighting_keywords(&names).map_err(|message| {
            GpuError::from(CheckError::UnknownToReference {
                variant: label.clone(),
                message,
            })
        })?;
        let wgsl = lib.wgsl(&variant);
        let keywords = choice.label(pass);
        let mut per_input = Vec::new();
        for n in 0..CHAIN_INPUTS.len() {
            let gbuffer = &gbuffers[&(n, kw.hdr, shadow.shadowmask)];
            per_input.push(run_lighting(
                ctx,
                scene,
                rig,
                gbuffer,
                (&label, &keywords),
                &wgsl,
                (light, shadow, kw.brdf),
                &mut report,
            )?);
        }
        outputs.push(per_input);
    }
    small.judge(&mut report, &outputs);
    report.notes.push(format!(
        "full-screen draws over {} G-buffers (LDR and HDR, with RT4 for SHADOWS_SHADOWMASK and without); positions rebuilt from the depth of a perspective camera; HDR: One/One onto Rgba16Float RT3, LDR: DstColor/Zero onto the Rgb10a2Unorm exp2(-c) RT3",
        gbuffers.len()
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `deferred_shading/Lighting` in the check's registry.
pub(crate) struct Lighting;

/// The entry of `deferred_shading/Lighting`: shadowed variants read the rig's maps and masks.
pub(crate) static LIGHTING: Lighting = Lighting;

impl PassCheck for Lighting {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("deferred_shading", "Lighting")]
    }

    fn needs(&self) -> Needs {
        Needs {
            shadow_maps: true,
            screen_masks: true,
            ..Needs::NOTHING
        }
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_deferred_shading(
            setup.ctx,
            setup.lib,
            setup.scene,
            setup.rig,
            setup.options,
        )?])
    }
}
