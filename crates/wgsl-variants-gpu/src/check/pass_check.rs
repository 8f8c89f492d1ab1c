//! What one entry of the GPU check's registry is: the passes it proves, what the run must set
//! up for it, and the check itself. Each per-pass module declares its entries; `check::run`
//! goes through the list of them in the order of their reports.

use std::cell::OnceCell;

use super::options::CheckOptions;
use super::report::PassReport;
use super::rig::LightRig;
use super::scene::TestScene;
use super::workers::{Worker, upload_workers};
use crate::{BoundResource, CheckError, GpuContext, GpuError};
use wgsl_variants::Library;
use wgsl_variants::shader::Pass;

/// What an entry needs before it runs; the run sets up the union of what the selected entries
/// need, once, and shares it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Needs {
    /// The light rig's spot and point shadow maps ([`LightRig::render_shadows`]).
    pub(crate) shadow_maps: bool,
    /// The rig's directional maps and screen-space masks ([`LightRig::render_screen_shadows`]).
    pub(crate) screen_masks: bool,
    /// A device per GPU worker (as many as [`CheckOptions`] asks for), for the passes with
    /// thousands of variants.
    pub(crate) workers: bool,
}

impl Needs {
    /// Nothing beyond the context, the library, the scene and the rig's lights.
    pub(crate) const NOTHING: Needs = Needs {
        shadow_maps: false,
        screen_masks: false,
        workers: false,
    };

    /// What `self` or `other` needs.
    pub(crate) fn and(self, other: Needs) -> Needs {
        Needs {
            shadow_maps: self.shadow_maps || other.shadow_maps,
            screen_masks: self.screen_masks || other.screen_masks,
            workers: self.workers || other.workers,
        }
    }
}

/// One entry of the registry: the way the GPU test harnesses declare each test with its
/// requirements, so that the run needs no knowledge of any pass.
pub(crate) trait PassCheck: Sync {
    /// The passes it checks, `(shader, pass)`, in the order of their reports. Most entries
    /// check one; the deferred chain checks its three together, since the earlier passes are
    /// the later ones' inputs.
    fn passes(&self) -> &'static [(&'static str, &'static str)];

    /// What the run sets up for it.
    fn needs(&self) -> Needs {
        Needs::NOTHING
    }

    /// Renders the `selected` passes (those of [`PassCheck::passes`] the options select, never
    /// none), compares them with the reference and judges their keyword coverage: one report
    /// per pass, in order.
    fn check(
        &self,
        setup: &Setup<'_>,
        selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError>;
}

/// What the run set up, shared by every entry it runs.
pub(crate) struct Setup<'a> {
    /// The context the entries render on (the first worker's too).
    pub(crate) ctx: &'a GpuContext,
    /// The library the variants come from.
    pub(crate) lib: &'a Library,
    /// The options of the run.
    pub(crate) options: &'a CheckOptions,
    /// The test scene.
    pub(crate) scene: &'a TestScene,
    /// The light rig, with what the entries' [`Needs`] asked for rendered.
    pub(crate) rig: &'a LightRig,
    /// The other workers' contexts (with [`Needs::workers`]).
    contexts: &'a [GpuContext],
    /// The standard passes' workers: one upload of the test scene's resources for all of them.
    standard: OnceCell<Vec<Worker<'a>>>,
}

impl<'a> Setup<'a> {
    /// The setup over what the run made.
    pub(crate) fn new(
        ctx: &'a GpuContext,
        contexts: &'a [GpuContext],
        lib: &'a Library,
        options: &'a CheckOptions,
        scene: &'a TestScene,
        rig: &'a LightRig,
    ) -> Setup<'a> {
        Setup {
            ctx,
            lib,
            options,
            scene,
            rig,
            contexts,
            standard: OnceCell::new(),
        }
    }

    /// `shader/pass` of the library.
    pub(crate) fn pass(&self, shader: &str, pass: &str) -> Result<&'a Pass, GpuError> {
        self.lib
            .pass(shader, pass)
            .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))
    }

    /// One worker per context, each with `resources` uploaded to its device.
    pub(crate) fn workers(
        &self,
        resources: &[BoundResource],
        label: &str,
    ) -> Result<Vec<Worker<'a>>, GpuError> {
        upload_workers(self.ctx, self.contexts, resources, label)
    }

    /// The workers of the standard passes, made by the first that asks: the test scene's
    /// resources and ForwardBase's `SHADOWS_SCREEN` mask (the rig's directional light's),
    /// uploaded once for every standard pass of the run.
    pub(crate) fn standard_workers(&self) -> Result<&[Worker<'a>], GpuError> {
        if let Some(workers) = self.standard.get() {
            return Ok(workers);
        }
        let mut resources = self.scene.standard_resources();
        resources.extend(self.rig.main_light_shadow());
        let workers = self.workers(&resources, "test scene")?;
        Ok(self.standard.get_or_init(|| workers))
    }
}
