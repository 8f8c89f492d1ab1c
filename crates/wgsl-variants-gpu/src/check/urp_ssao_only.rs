//! URP's `stencil_deferred/SSAOOnly` for the GPU check (docs/urp.md §14): both variants draw
//! full screen over GBuffer3 of `UniversalGBuffer` G-buffers (one per material input of the
//! lighting check), blended One SrcAlpha, reading the checks' SSAO texture
//! ([`ScreenOcclusion`]); every texel is compared with GBuffer3 as stored times
//! [`deferred_indirect_occlusion`] of the texel's SSAO and its surface occlusion (GBuffer1's
//! alpha) under `_SCREEN_SPACE_OCCLUSION`, and must be GBuffer3's bytes unchanged without it
//! (the pass draws nothing).

use std::time::Instant;

use super::compare::format_name;
use super::coverage::SmallPass;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::scene::texture;
use super::urp::{DEFAULT_SEED, UrpScene};
use super::urp_lighting::{GBUFFER_INPUTS, keep_blend, render_urp_gbuffer};
use super::urp_occlusion::ScreenOcclusion;
use crate::{BoundResource, ColorTarget, GpuError, RenderJob, TargetFormat, render};
use wgsl_variants_shaders::reference::tolerance::rg11b10_within;
use wgsl_variants_shaders::reference::urp::ambient_occlusion::deferred_indirect_occlusion;
use wgsl_variants_shaders::reference::urp::ufloat::unpack_rg11b10;

/// The shader and pass.
const PASS: (&str, &str) = ("stencil_deferred", "SSAOOnly");

/// Checks both variants of the SSAOOnly pass over the lighting check's G-buffers.
///
/// # Errors
/// A GPU failure or a variant that does not compile.
pub(crate) fn check_ssao_only(setup: &Setup<'_>) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let scene = setup.scene;
    let (w, h) = (scene.width, scene.height);
    let small = SmallPass::new(setup.lib, PASS.0, PASS.1, setup.options)?;
    let (pass, choices) = (small.pass, small.choices.as_slice());
    let occlusion = ScreenOcclusion::new(w, h);
    let urp = UrpScene::new(scene, DEFAULT_SEED);
    let gbuffers = GBUFFER_INPUTS
        .iter()
        .map(|material| render_urp_gbuffer(setup.ctx, setup.lib, &urp, material))
        .collect::<Result<Vec<_>, _>>()?;
    let mut report = PassReport::new(PASS.0, PASS.1);
    let (mut rescaled, mut whole, mut lit) = (0usize, 0usize, 0usize);
    let mut images = Vec::with_capacity(choices.len());
    for choice in choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let (label, names) = (variant.label(), variant.keywords());
        let on = names.contains(&"_SCREEN_SPACE_OCCLUSION");
        let wgsl = setup.lib.wgsl(&variant);
        let mut per_variant = Vec::with_capacity(gbuffers.len());
        for gbuffer in &gbuffers {
            let mut job = RenderJob::new(&label, &wgsl, "vs_main", "fs_main");
            job.width = w;
            job.height = h;
            job.targets = vec![
                ColorTarget::new(TargetFormat::Rg11b10Ufloat)
                    .with_blend(keep_blend())
                    .with_initial(gbuffer.targets[3].clone()),
            ];
            job.resources = vec![BoundResource::new(
                0,
                1,
                texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[1]),
            )];
            job.resources.extend(occlusion.resources());
            let out = render(setup.ctx, &job)?.remove(0);
            report.draws += 1;
            let input = format!(
                "{label} over the G-buffer of universal_lit/UniversalGBuffer {{{}}}",
                gbuffer.keywords.join(", ")
            );
            for (i, (x, y)) in scene.pixels().enumerate() {
                let word = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                let stored_bytes = &gbuffer.targets[3][i * 4..i * 4 + 4];
                let px = &out[i * 4..i * 4 + 4];
                let stored = unpack_rg11b10(word(stored_bytes));
                let keep = if on {
                    let surface = f32::from(gbuffer.targets[1][i * 4 + 3]) / 255.0;
                    deferred_indirect_occlusion(occlusion.factor(x, y).indirect, surface)
                } else {
                    1.0
                };
                rescaled += usize::from(keep < 1.0);
                whole += usize::from(on && keep == 1.0);
                lit += usize::from(stored.max_element() > 0.0);
                let want = stored * keep;
                // Without the keyword nothing is drawn: the bytes stay as they were.
                let ok = if on {
                    rg11b10_within(word(px), want)
                } else {
                    px == stored_bytes
                };
                report.record(ok, || Mismatch {
                    shader: PASS.0.to_owned(),
                    pass: PASS.1.to_owned(),
                    keywords: input.clone(),
                    target: format!("GBuffer3 {}", format_name(TargetFormat::Rg11b10Ufloat)),
                    pixel: [x, y],
                    expected: want.to_array().to_vec(),
                    got: unpack_rg11b10(word(px)).to_array().to_vec(),
                    got_raw: TargetFormat::Rg11b10Ufloat.decode_pixel(px).to_vec(),
                });
            }
            per_variant.push(out);
        }
        images.push(per_variant);
    }
    small.judge(&mut report, &images);
    report.notes.push(format!(
        "full-screen draws over GBuffer3 of {} UniversalGBuffer G-buffers ({lit} comparisons with a non-zero GBuffer3), blended One SrcAlpha; the SSAO texture an R8Unorm pattern of 16 levels; in {rescaled} comparisons the pass scales GBuffer3 by less than 1, in {whole} the surface's own occlusion is the lower and GBuffer3 is kept",
        gbuffers.len()
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `stencil_deferred/SSAOOnly` in the check's registry.
pub(crate) struct SsaoOnly;

/// The entry of URP's SSAOOnly pass.
pub(crate) static SSAO_ONLY: SsaoOnly = SsaoOnly;

impl PassCheck for SsaoOnly {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[PASS]
    }

    fn needs(&self) -> Needs {
        Needs::NOTHING
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_ssao_only(setup)?])
    }
}
