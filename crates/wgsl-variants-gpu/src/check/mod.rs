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
//! | part | what runs |
//! |---|---|
//! | passes | `standard/Deferred` (6144 variants; RT4 with `SHADOWS_SHADOWMASK`), `standard/ForwardBase` (3072; `SHADOWS_SCREEN` over the directional light's mask) and `standard/ForwardAdd` (6144, one light of each type from [`LightRig`], shadowed variants over its [`shadows::ShadowRig`] maps and the directional lights' masks) on [`scene::TestScene`] (one render job: [`standard_job`]) |
//! | [`lights`] | `deferred_shading/Lighting` (all 128 variants) over LDR and HDR G-buffers (with RT4 for `SHADOWS_SHADOWMASK`), positions from depth; `SHADOWS_SCREEN` over the masks of [`screen_shadows`] |
//! | [`screen_shadows`] | `screen_space_shadows/Collect` (both variants): the directional lights' maps (`standard/ShadowCaster`, orthographic) turned into masks of the camera view, every pixel against the reference over the read-back map |
//! | [`caster`] | `standard/ShadowCaster` (all 8 variants): the occluder scene's spot map and six cube faces, every texel against the nearest kept occluder point |
//! | [`shadows`] | the spot map and point cube `standard/ShadowCaster` renders of an occluder scene, read back for the reference, and the analytic shadow of that scene (the `gpu_shadows` test) |
//! | [`frame`] | a whole frame (five objects, a main light and four per-pixel lights with cookies and shadows) forward and deferred, HDR and LDR, every pixel against the reference and forward against deferred (the `gpu_frame` test; `render --frame`) |
//! | [`forward_deferred`] | the same surface lit by ForwardAdd and by G-buffer + Lighting (HDR), compared per pixel |
//! | deferred | `deferred_reflections/Reflections` (probe by probe), `deferred_reflections/Add` (both variants), `deferred_final/Final` |
//! | [`urp`] | `universal_lit/UniversalGBuffer` (49,152 variants: a t = 3 covering set plus one partner per keyword by default, every variant with [`CheckOptions::full`]) on [`urp::UrpScene`], every texel of every target against [`wgsl_variants_shaders::reference::urp::gbuffer`] |
//! | [`urp_forward`] | `universal_lit/UniversalForward` (55,296 variants: covered like `UniversalGBuffer`) on [`urp::UrpScene`] lit by the [`LightRig`]'s main light (with its shadow map) and three additional lights, every texel of the `Rg11b10Ufloat` camera target against [`wgsl_variants_shaders::reference::urp::forward`] |
//! | [`urp_caster`] | `universal_lit/ShadowCaster` (all 8 variants): the URP quad into a directional and a spot map, every texel against the biased, pancaked, alpha-tested reference |
//! | [`urp_lighting`] | `stencil_deferred/PunctualLit` and `DirectionalLit` (all 24 variants) over `UniversalGBuffer` G-buffers, positions from depth, the main light's shadow over the map of [`screen_shadows`] |
//! | [`volumes`] | one light drawn as its volume after the `stencil_write/StencilWrite` pre-pass or full-screen ([`crate::light_volume`]), and the comparison of the two (the `gpu_volumes` test; not part of `check-gpu`) |
//! | [`kernels`] | compute shaders importing `deferred/gbuffer`, `deferred/ldr`, `deferred/probe` |
//! | [`pictures`] | the scene's targets as PNG images (the `render` command) |

pub mod caster;
pub(crate) mod compare;
pub(crate) mod deferred;
pub mod forward_deferred;
pub mod frame;
pub mod kernels;
pub mod lights;
pub mod merge;
pub(crate) mod passes;
pub mod pictures;
pub mod report;
pub mod scene;
pub mod screen_shadows;
pub mod shadows;
pub mod urp;
pub mod urp_caster;
pub mod urp_forward;
pub mod urp_lighting;
pub mod volumes;

use std::time::Instant;

pub use deferred::{
    CHAIN_INPUTS, GBufferImage, ProbeDrawing, Reflections, reflection_buffer, render_gbuffer,
};
pub use lights::LightRig;
use passes::Worker;
pub use passes::{StandardOutput, standard_job};
pub use report::{CheckReport, KernelReport, KeywordCoverage, Mismatch, PassReport};
pub use scene::TestScene;

use super::{CheckError, GpuContext, GpuError, GpuResources};
use wgsl_variants::Library;

/// What to check.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct CheckOptions {
    /// Only this shader (`standard`, `deferred_shading`, `deferred_reflections`, `deferred_final`, or `kernels`
    /// for the compute kernels alone).
    pub shader: Option<String>,
    /// Only passes (or kernels) with this name.
    pub pass: Option<String>,
    /// The first adapter whose name contains this (case-insensitive); default: the first one.
    pub adapter: Option<String>,
    /// GPU workers, each with its own device (0: one per available core, at most 4).
    pub threads: usize,
    /// Check every n-th variant of the standard passes only (0 or 1: all of them). Keyword
    /// coverage is judged on the full space only.
    pub sample: usize,
    /// Only this shard of each standard pass's variants (variant i of a pass is in shard
    /// `i % N`); with `sample`, both apply. Keyword coverage is judged on the full space only.
    pub shard: Option<wgsl_variants::variants::Shard>,
    /// Check a t-wise covering set of each standard pass instead of its full space
    /// ([`wgsl_variants::Space::covering`]); `sample` and `shard` then apply to it.
    pub cover: Option<usize>,
    /// With `cover`, cover only passes whose space holds more than this many variants (as
    /// `validate --cover-above`). Without `cover`, passes past this many variants (default
    /// [`DEFAULT_COVER_ABOVE`]) get a [`DEFAULT_COVER_T`]-wise covering set.
    pub cover_above: Option<u64>,
    /// Check every variant of every selected pass, whatever its size (no covering set).
    pub full: bool,
}

/// Passes with more variants than this are covered by default (URP's `UniversalGBuffer`).
pub const DEFAULT_COVER_ABOVE: u64 = 8192;

/// The covering strength of the default covering sets.
pub const DEFAULT_COVER_T: usize = 3;

/// The passes the check knows, as `(shader, pass)`.
pub const PASSES: [(&str, &str); 14] = [
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
    ("stencil_deferred", "PunctualLit"),
    ("stencil_deferred", "DirectionalLit"),
];

/// The pseudo-shader name that selects the compute kernels.
pub const KERNELS: &str = "kernels";

impl CheckOptions {
    fn wants(&self, shader: &str, pass: &str) -> bool {
        self.shader.as_deref().is_none_or(|s| s == shader)
            && self.pass.as_deref().is_none_or(|p| p == pass)
    }

    /// The covering strength for a pass of `count` variants, or `None` for its full space.
    ///
    /// ```
    /// use wgsl_variants_gpu::check::CheckOptions;
    /// let mut o = CheckOptions::default();
    /// assert_eq!((o.cover_for(3072), o.cover_for(65536)), (None, Some(3)));
    /// o.full = true;
    /// assert_eq!(o.cover_for(65536), None);
    /// o.full = false;
    /// o.cover = Some(2);
    /// assert_eq!((o.cover_for(3072), o.cover_for(65536)), (Some(2), Some(2)));
    /// o.cover_above = Some(8192);
    /// assert_eq!(o.cover_for(3072), None);
    /// ```
    pub fn cover_for(&self, count: u64) -> Option<usize> {
        if self.full {
            return None;
        }
        match self.cover {
            Some(t) => self.cover_above.is_none_or(|n| count > n).then_some(t),
            None => {
                (count > self.cover_above.unwrap_or(DEFAULT_COVER_ABOVE)).then_some(DEFAULT_COVER_T)
            }
        }
    }

    fn threads(&self) -> usize {
        if self.threads > 0 {
            self.threads
        } else {
            std::thread::available_parallelism()
                .map_or(1, |n| n.get())
                .min(4)
        }
    }
}

/// Runs the GPU check on the adapter `options.adapter` selects: every selected pass and kernel,
/// each compared with the CPU reference.
///
/// Mismatches are part of the report ([`CheckReport::passed`]); an `Err` means the check could
/// not run: no adapter, a variant that failed to compile or render (the error names it), a
/// shader or pass that does not exist, or a selection that matches nothing.
pub fn run(lib: &Library, options: &CheckOptions) -> Result<CheckReport, GpuError> {
    let start = Instant::now();
    let selected: Vec<(&str, &str)> = PASSES
        .iter()
        .copied()
        .filter(|(s, p)| options.wants(s, p))
        .collect();
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
    for (shader, pass) in &selected {
        lib.pass(shader, pass)
            .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))?;
    }

    let ctx = GpuContext::new(options.adapter.as_deref())?;
    let info = ctx.adapter_info();
    let mut report = CheckReport {
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
    };
    let scene = TestScene::default();
    let mut rig = LightRig::new(&scene);
    if selected
        .iter()
        .any(|&(s, p)| p == "ForwardAdd" || s == "deferred_shading")
    {
        rig.render_shadows(&ctx, lib)?;
    }
    let forward_selected = selected.contains(&("universal_lit", "UniversalForward"));
    // The masks: the lighting passes' SHADOWS_SCREEN, and the forward passes' (ForwardBase's
    // main light, ForwardAdd's directional lights).
    if forward_selected
        || selected.iter().any(|&(s, p)| {
            matches!(
                s,
                "deferred_shading" | "screen_space_shadows" | "stencil_deferred"
            ) || matches!(p, "ForwardBase" | "ForwardAdd")
        })
    {
        rig.render_screen_shadows(&ctx, lib, &scene)?;
    }
    let threads = options.threads();

    let standard: Vec<&str> = selected
        .iter()
        .filter(|(s, p)| *s == "standard" && *p != "ShadowCaster")
        .map(|(_, p)| *p)
        .collect();
    let urp_selected = selected.contains(&("universal_lit", "UniversalGBuffer"));
    // One device per worker, shared by the standard and URP passes.
    let mut contexts = Vec::new();
    if !standard.is_empty() || urp_selected || forward_selected {
        for _ in 1..threads {
            contexts.push(GpuContext::new(options.adapter.as_deref())?);
        }
    }
    if !standard.is_empty() {
        let mut resources = scene.standard_resources();
        // ForwardBase's SHADOWS_SCREEN: the main light's mask (the rig's directional light's).
        resources.extend(rig.main_light_mask());
        let workers = upload_workers(&ctx, &contexts, &resources, "test scene")?;
        for pass in standard {
            let pass = lib
                .pass("standard", pass)
                .map_err(|e| CheckError::lookup(format!("standard/{pass}"), e))?;
            report.passes.push(passes::check_standard_pass(
                &workers,
                lib,
                &scene,
                &rig,
                pass,
                options.sample,
                options.shard,
                options.cover_for(space_size(pass)),
            )?);
        }
    }
    let urp_scene = urp::UrpScene::new(&scene, urp::DEFAULT_SEED);
    for (name, on) in [
        ("UniversalGBuffer", urp_selected),
        ("UniversalForward", forward_selected),
    ] {
        if !on {
            continue;
        }
        let pass = lib
            .pass("universal_lit", name)
            .map_err(|e| CheckError::lookup(format!("universal_lit/{name}"), e))?;
        let forward;
        let spec: &dyn urp::UrpColorPass = if name == "UniversalForward" {
            forward = urp_forward::UrpForwardScene::new(&urp_scene, &rig)?;
            &forward
        } else {
            &urp_scene
        };
        let workers = upload_workers(&ctx, &contexts, &spec.resources(), name)?;
        report.passes.push(urp::check_urp_color_pass(
            &workers,
            lib,
            spec,
            pass,
            urp::Selection {
                cover: options.cover_for(space_size(pass)),
                sample: options.sample,
                shard: options.shard,
            },
        )?);
    }
    if selected.contains(&("standard", "ShadowCaster")) {
        report.passes.push(caster::check_shadow_caster(
            &ctx,
            lib,
            &rig.spot_light,
            &rig.point_light,
        )?);
    }
    if let (true, Some(screen)) = (
        selected.contains(&("screen_space_shadows", "Collect")),
        &rig.screen_shadows,
    ) {
        report
            .passes
            .push(screen_shadows::check_collect(lib, &scene, &rig, screen)?);
    }
    if selected.contains(&("deferred_shading", "Lighting")) {
        report
            .passes
            .push(lights::check_deferred_shading(&ctx, lib, &scene, &rig)?);
    }
    if selected.contains(&("universal_lit", "ShadowCaster")) {
        report.passes.push(urp_caster::check_urp_shadow_caster(
            &ctx, lib, &scene, &rig,
        )?);
    }
    for &(s, p) in &selected {
        if s == "stencil_deferred" {
            report.passes.push(urp_lighting::check_stencil_deferred(
                &ctx, lib, &scene, &rig, p,
            )?);
        }
    }
    let chain: Vec<(&str, &str)> = selected
        .iter()
        .copied()
        .filter(|(s, _)| {
            !matches!(
                *s,
                "standard"
                    | "deferred_shading"
                    | "screen_space_shadows"
                    | "universal_lit"
                    | "stencil_deferred"
            )
        })
        .collect();
    if !chain.is_empty() {
        report
            .passes
            .extend(deferred::check_deferred_chain(&ctx, lib, &scene, &chain)?);
    }
    if !kernel_selection.is_empty() {
        report.kernels = kernels::check_kernels(&ctx, lib, &kernel_selection)?;
    }
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// The number of variants in a pass's full space (saturated at `u64::MAX`).
fn space_size(pass: &wgsl_variants::shader::Pass) -> u64 {
    u64::try_from(wgsl_variants::Space::full(pass).count()).unwrap_or(u64::MAX)
}

/// One worker per context (`ctx` first), each with `resources` uploaded to its device.
fn upload_workers<'c>(
    ctx: &'c GpuContext,
    contexts: &'c [GpuContext],
    resources: &[crate::BoundResource],
    label: &str,
) -> Result<Vec<Worker<'c>>, GpuError> {
    std::iter::once(ctx)
        .chain(contexts)
        .map(|c| {
            Ok(Worker {
                ctx: c,
                resources: GpuResources::upload(c, label, resources)?,
            })
        })
        .collect()
}
