//! One light drawn over a read-back G-buffer by `deferred_shading/Lighting`, full screen:
//! the draw's bindings and its render onto RT3. The `Lighting` check, the light volumes and
//! the forward = deferred comparison all draw their lights this way.

use super::camera::{LightingCamera, depth_camera_resources};
use super::gbuffer::{GBufferImage, rt3_blend};
use super::rig::LightRig;
use super::scene::{TestScene, texture};
use crate::{BoundResource, ColorTarget, GpuContext, GpuError, RenderJob, TargetFormat, render};
use wgsl_variants_shaders::reference::light::LightParams;

/// Renders one `Lighting` variant (the light `light`) over `gbuffer`'s RT0–RT2 onto
/// `rt3` (the target's initial contents, `gbuffer`'s RT3 format), blended as the HDR mode says.
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_lighting(
    ctx: &GpuContext,
    scene: &TestScene,
    rig: &LightRig,
    gbuffer: &GBufferImage,
    label: &str,
    wgsl: &str,
    light: &LightParams,
    camera: &LightingCamera<'_>,
    rt3: Vec<u8>,
) -> Result<Vec<u8>, GpuError> {
    let target = ColorTarget::new(gbuffer.rt3_format())
        .with_blend(rt3_blend(gbuffer.hdr))
        .with_initial(rt3);
    let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
    job.width = scene.width;
    job.height = scene.height;
    job.targets = vec![target];
    job.resources = lighting_resources(scene, rig, gbuffer, light, camera);
    Ok(render(ctx, &job)?.remove(0))
}

/// The bindings of a `Lighting` draw: RT0–RT2 of `gbuffer`, the depth as `R32Float`, the
/// `DeferredCamera` uniform and the light's resources.
pub(crate) fn lighting_resources(
    scene: &TestScene,
    rig: &LightRig,
    gbuffer: &GBufferImage,
    light: &LightParams,
    camera: &LightingCamera<'_>,
) -> Vec<BoundResource> {
    let (w, h) = (scene.width, scene.height);
    let mut resources = vec![
        BoundResource::new(
            0,
            0,
            texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[0]),
        ),
        BoundResource::new(
            0,
            1,
            texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[1]),
        ),
        BoundResource::new(
            0,
            2,
            texture(TargetFormat::Rgb10a2Unorm, w, h, &gbuffer.targets[2]),
        ),
    ];
    if let Some(rt4) = gbuffer.targets.get(4) {
        // SHADOWS_SHADOWMASK: the baked occlusion.
        resources.push(BoundResource::new(
            0,
            5,
            texture(TargetFormat::Rgba8Unorm, w, h, rt4),
        ));
    }
    resources.extend(depth_camera_resources((scene.width, scene.height), camera));
    resources.extend(rig.resources_for(light));
    resources.push(super::scene::brdf_lut_resource());
    resources
}
