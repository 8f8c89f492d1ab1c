//! The GPU proof of the bundled library: every variant of the standard shader's passes, the
//! deferred reflection and final passes, and compute kernels over the library's pure
//! functions, each compared with [`wgsl_variants_shaders::reference`] through [`wgsl_variants_shaders::reference::tolerance`].
//!
//! [`run`] is shared by the `check-gpu` command and the GPU tests:
//!
//! ```no_run
//! use wgsl_variants_gpu::check::{run, CheckOptions};
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let report = run(&lib, &CheckOptions::default()).unwrap();
//! assert!(report.passed(), "{report}");
//! ```
//!
//! `run` goes through a registry: each per-pass module declares its entry (the passes it
//! checks and what it needs set up: the light rig's shadow maps, its screen-space masks, a
//! device per worker), and the run sets up what the selected entries need, then runs them in
//! the order of their reports.
//!
//! The modules stand on three floors; none imports from a floor above its own, so no two
//! import each other, directly or around a loop.
//!
//! **Per-pass checks** (and what else is built on the shared parts):
//!
//! | part | what runs |
//! |---|---|
//! | passes | `standard/Deferred` (110592 variants; RT4 with `SHADOWS_SHADOWMASK`; the lightmaps), `standard/ForwardBase` (55296; `SHADOWS_SCREEN` over the directional light's mask; the lightmaps) and `standard/ForwardAdd` (18432, one light of each type from [`LightRig`], shadowed variants over its [`shadows::ShadowRig`] maps and the directional lights' masks) on [`scene::TestScene`] (one render job: [`standard_job`]); past 8192 variants each, so a t = 3 covering set plus one partner per keyword by default, every variant with [`CheckOptions::full`] |
//! | [`lights`] | `deferred_shading/Lighting` (all 384 variants: every BRDF tier) over LDR and HDR G-buffers (with RT4 for `SHADOWS_SHADOWMASK`), positions from depth; `SHADOWS_SCREEN` over the masks of [`screen_shadows`] |
//! | [`screen_shadows`] | `screen_space_shadows/Collect` (all 8 variants): the directional lights' 1, 2 and 4 cascades (`standard/ShadowCaster`, orthographic, one atlas tile each) turned into masks of the camera view, every pixel against the reference over the read-back atlas |
//! | [`caster`] | `standard/ShadowCaster` (all 8 variants): the occluder scene's spot map and six cube faces, every texel against the nearest kept occluder point |
//! | [`frame`] | a whole frame (five opaque objects, two of them lightmapped; two semi-transparent objects; a sky; a main light and four per-pixel lights with cookies and shadows) forward and deferred, HDR and LDR, every pixel against the reference and forward against deferred (the `gpu_frame` test; `render --frame`) |
//! | [`forward_deferred`] | the same surface lit by ForwardAdd and by G-buffer + Lighting (HDR), compared per pixel |
//! | deferred | `deferred_reflections/Reflections` (probe by probe), `deferred_reflections/Add` (both variants), `deferred_final/Final` |
//! | [`urp`] | `universal_lit/UniversalGBuffer` (49,152 variants: a t = 3 covering set plus one partner per keyword by default, every variant with [`CheckOptions::full`]) on [`urp::UrpScene`], every texel of every target against [`wgsl_variants_shaders::reference::urp::gbuffer`] |
//! | [`urp_forward`] | `universal_lit/UniversalForward` (786,432 variants: covered like `UniversalGBuffer`) on [`urp::UrpScene`] lit by the [`LightRig`]'s main light (its map, its cascades or a stand-in screen-space texture) and three additional lights (two casting shadows from [`urp_additional_shadows`]'s atlas), every texel of the `Rg11b10Ufloat` camera target against [`wgsl_variants_shaders::reference::urp::forward`] |
//! | [`urp_caster`] | `universal_lit/ShadowCaster` (all 8 variants): the URP quad into a directional and a spot map, every texel against the biased, pancaked, alpha-tested reference |
//! | `urp_depth_only` | `universal_lit/DepthOnly` (all 4 variants): the URP quad through the rig's camera and two light boxes (one clipping it), every texel of the `R32Float` target and the depth buffer against the alpha-tested reference |
//! | [`urp_lighting`] | `stencil_deferred/PunctualLit` and `DirectionalLit` (all 252 variants: 96 and 156) over `UniversalGBuffer` G-buffers, positions from depth, the main light's shadow over the map, the cascades or the screen-space texture of [`screen_shadows`], the screen-space occlusion; `stencil_deferred/SSAOOnly` (2) over their GBuffer3 (`urp_ssao_only`) |
//! | `urp_screen_shadows` | `universal_screen_space_shadows/ScreenSpaceShadows` (all 4 variants): the main light's map or cascades turned into URP's screen-space shadow over the rig's depth, every pixel against the reference |
//! | [`urp_frame`] | URP's frame (five objects, a main light with its shadow and three additional lights on rendering layers, shadows and cookies) through `UniversalForward` and through `UniversalGBuffer` + `stencil_deferred` (the punctual lights as their volumes after URP's stencil volume pass), every pixel against the reference and forward against deferred (the `gpu_urp_frame` test; `render --frame urp`) |
//! | [`skybox`] | `skybox/Cubemap` (its one variant) through a wide view over five faces, their edges and a corner, HDR and LDR |
//! | [`volumes`] | one light drawn as its volume after the `stencil_write/StencilWrite` pre-pass or full-screen ([`crate::light_volume`]), and the comparison of the two (the `gpu_volumes` test; not part of `check-gpu`) |
//! | [`kernels`] | compute shaders importing `deferred/gbuffer`, `deferred/ldr`, `deferred/probe` |
//! | [`pictures`] | the scene's targets as PNG images (the `render` command) |
//!
//! **Shared by the checks**, each standing only on the modules listed after it and the ground:
//!
//! | part | what it holds |
//! |---|---|
//! | `pass_check` | the registry's entry: the passes it checks, what it needs, the check; and the setup the run shares with every entry |
//! | `lighting` | one light drawn over a read-back G-buffer by `deferred_shading/Lighting` (the `Lighting` check, [`volumes`], [`forward_deferred`]) |
//! | `rig` | the light rig ([`LightRig`]): one light of each type, cookies, shadow maps and masks, the deferred camera and depth |
//! | `screen_masks` | the directional lights' maps and `Collect` masks the rig carries ([`screen_shadows::ScreenShadows`]) |
//! | `gbuffer` | `standard/Deferred` G-buffers read back ([`GBufferImage`], [`render_gbuffer`], [`CHAIN_INPUTS`]) and how light blends onto RT3 |
//! | `standard` | what a standard variant writes ([`StandardOutput`]) and the job that draws it ([`standard_job`]) |
//! | `camera` | what the full-screen deferred passes see of the camera, and its bindings |
//! | `volume_draw` | draws limited to a light's or probe's volume over the scene's depth |
//! | `quad_raster` | the URP quad rasterized at texel centres with the alpha test (the `ShadowCaster` and `DepthOnly` references) |
//! | `coverage` | keyword coverage, covering-set partners, the small passes run whole |
//! | `workers` | one device per GPU worker and the jobs spread over them |
//! | [`shadows`] | the spot map and point cube `standard/ShadowCaster` renders of an occluder scene, read back for the reference, and the analytic shadow of that scene (the `gpu_shadows` test) |
//!
//! **The ground**, importing nothing above it: [`scene`] (the test scene and its resources),
//! `compare` (texels against the reference), [`report`], [`merge`] and `options`
//! ([`CheckOptions`]).

mod camera;
pub mod caster;
pub(crate) mod compare;
mod coverage;
pub(crate) mod deferred;
pub mod forward_deferred;
pub mod frame;
mod gbuffer;
pub mod kernels;
mod lighting;
pub mod lights;
pub mod merge;
mod options;
mod pass_check;
pub(crate) mod passes;
pub mod pictures;
mod quad_raster;
pub mod report;
mod rig;
pub mod scene;
mod screen_masks;
pub mod screen_shadows;
pub mod shadows;
pub mod skybox;
mod standard;
pub mod urp;
pub mod urp_additional_shadows;
pub mod urp_caster;
mod urp_cookies;
mod urp_depth_only;
pub mod urp_forward;
pub mod urp_frame;
pub mod urp_lighting;
pub mod urp_occlusion;
mod urp_screen_shadows;
mod urp_ssao_only;
mod volume_draw;
pub mod volumes;
mod workers;

use std::time::Instant;

pub use deferred::{ProbeDrawing, Reflections, reflection_buffer};
pub use gbuffer::{CHAIN_INPUTS, GBufferImage, render_gbuffer};
pub use options::{CheckOptions, DEFAULT_COVER_ABOVE, DEFAULT_COVER_T};
pub use report::{CheckReport, KernelReport, KeywordCoverage, Mismatch, PassReport};
pub use rig::LightRig;
pub use scene::TestScene;
pub use standard::{StandardOutput, standard_job};

use super::{CheckError, GpuContext, GpuError};
use pass_check::{Needs, PassCheck, Setup};
use wgsl_variants::Library;

/// The passes the check knows, as `(shader, pass)`.
pub const PASSES: [(&str, &str); 18] = [
    ("standard", "Deferred"),
    ("standard", "ForwardBase"),
    ("standard", "ForwardAdd"),
    ("standard", "ShadowCaster"),
    ("deferred_shading", "Lighting"),
    ("screen_space_shadows", "Collect"),
    ("deferred_reflections", "Reflections"),
    ("deferred_reflections", "Add"),
    ("deferred_final", "Final"),
    ("universal_lit", "UniversalGBuffer"),
    ("universal_lit", "UniversalForward"),
    ("universal_lit", "ShadowCaster"),
    ("universal_lit", "DepthOnly"),
    ("stencil_deferred", "PunctualLit"),
    ("stencil_deferred", "DirectionalLit"),
    ("stencil_deferred", "SSAOOnly"),
    ("universal_screen_space_shadows", "ScreenSpaceShadows"),
    ("skybox", "Cubemap"),
];

/// The pseudo-shader name that selects the compute kernels.
pub const KERNELS: &str = kernels::PSEUDO_SHADER;

/// Every check of [`PASSES`], in the order of its reports: the standard passes first (they
/// share one upload of the test scene), the URP colour passes, then the smaller passes, and
/// the deferred chain last.
static CHECKS: &[&dyn PassCheck] = &[
    &passes::DEFERRED,
    &passes::FORWARD_BASE,
    &passes::FORWARD_ADD,
    &urp::UNIVERSAL_GBUFFER,
    &urp_forward::UNIVERSAL_FORWARD,
    &caster::SHADOW_CASTER,
    &screen_shadows::COLLECT,
    &lights::LIGHTING,
    &urp_caster::URP_SHADOW_CASTER,
    &urp_depth_only::URP_DEPTH_ONLY,
    &urp_lighting::PUNCTUAL_LIT,
    &urp_lighting::DIRECTIONAL_LIT,
    &urp_ssao_only::SSAO_ONLY,
    &urp_screen_shadows::URP_SCREEN_SHADOWS,
    &skybox::CUBEMAP,
    &deferred::CHAIN,
];

/// Runs the GPU check on the adapter `options.adapter` selects: every selected pass and kernel,
/// each compared with the CPU reference.
///
/// Mismatches are part of the report ([`CheckReport::passed`]); an `Err` means the check could
/// not run: no adapter, a variant that failed to compile or render (the error names it), a
/// shader or pass that does not exist, or a selection that matches nothing.
pub fn run(lib: &Library, options: &CheckOptions) -> Result<CheckReport, GpuError> {
    let start = Instant::now();
    let selected = select(options);
    let kernel_selection = kernels::KERNELS
        .iter()
        .filter(|k| options.wants(KERNELS, k.name))
        .collect::<Vec<_>>();
    if selected.is_empty() && kernel_selection.is_empty() {
        let known: Vec<String> = PASSES
            .iter()
            .map(|(s, p)| format!("{s}/{p}"))
            .chain(
                kernels::KERNELS
                    .iter()
                    .map(|k| format!("{KERNELS}/{}", k.name)),
            )
            .collect();
        return Err(GpuError::from(CheckError::NoMatch {
            shader: options.shader.clone(),
            pass: options.pass.clone(),
            known,
        }));
    }
    // In the order of PASSES, so the first missing pass is the one named.
    for (shader, pass) in PASSES.iter().filter(|(s, p)| options.wants(s, p)) {
        lib.pass(shader, pass)
            .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))?;
    }

    let ctx = options.context()?;
    let mut report = empty_report(&ctx, lib, options);
    let scene = TestScene::default();
    let mut rig = LightRig::new(&scene);
    let needs = selected
        .iter()
        .fold(Needs::NOTHING, |n, (check, _)| n.and(check.needs()));
    if needs.shadow_maps {
        rig.render_shadows(&ctx, lib)?;
    }
    if needs.screen_masks {
        rig.render_screen_shadows(&ctx, lib, &scene)?;
    }
    // One device per worker, shared by the passes large enough to spread.
    let mut contexts = Vec::new();
    if needs.workers {
        for _ in 1..options.threads() {
            contexts.push(options.context()?);
        }
    }
    let setup = Setup::new(&ctx, &contexts, lib, options, &scene, &rig);
    for (check, passes) in &selected {
        report.passes.extend(check.check(&setup, passes)?);
    }
    if !kernel_selection.is_empty() {
        report.kernels = kernels::check_kernels(&ctx, lib, &kernel_selection)?;
    }
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// A selected entry of the registry, with the passes of it the options select.
type Selected = (&'static dyn PassCheck, Vec<(&'static str, &'static str)>);

/// The registry's entries with a pass the options select, each with those passes.
fn select(options: &CheckOptions) -> Vec<Selected> {
    CHECKS
        .iter()
        .filter_map(|&check| {
            let passes: Vec<_> = check
                .passes()
                .iter()
                .copied()
                .filter(|(s, p)| options.wants(s, p))
                .collect();
            (!passes.is_empty()).then_some((check, passes))
        })
        .collect()
}

/// The report of a run on `ctx` before any pass: the adapter, its driver, and the fingerprint
/// of the library and the options that change what is checked.
fn empty_report(ctx: &GpuContext, lib: &Library, options: &CheckOptions) -> CheckReport {
    let info = ctx.adapter_info();
    CheckReport {
        adapter: ctx.adapter_name().to_owned(),
        driver: format!("{:?}, {} {}", info.backend, info.driver, info.driver_info),
        fingerprint: wgsl_variants::merge::fingerprint(
            lib,
            "check-gpu",
            &format!(
                "{:?} {:?} {}{}",
                options.shader,
                options.pass,
                options.sample.max(1),
                // Only when set, so the fingerprints of runs without them stay as they were.
                if options.cover.is_some() || options.cover_above.is_some() || options.full {
                    format!(
                        " cover {:?} above {:?} full {}",
                        options.cover, options.cover_above, options.full
                    )
                } else {
                    String::new()
                }
            ),
        ),
        shard: options.shard,
        passes: Vec::new(),
        kernels: Vec::new(),
        seconds: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_checks_every_pass_once() {
        let mut registered: Vec<(&str, &str)> = CHECKS
            .iter()
            .flat_map(|c| c.passes().iter().copied())
            .collect();
        let mut known = PASSES.to_vec();
        registered.sort_unstable();
        known.sort_unstable();
        assert_eq!(registered, known);
    }
}
