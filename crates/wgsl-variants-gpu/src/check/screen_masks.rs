//! The screen-space shadows the light rig carries (`SHADOWS_SCREEN`, docs/shading.md §11):
//! each directional light's map, rendered by `standard/ShadowCaster` through the light's
//! orthographic view, and the masks `screen_space_shadows/Collect` made of it over the
//! camera's depth buffer. The `Collect` check compares these masks; the lighting and forward
//! checks read them.

use super::camera::{LightingCamera, depth_camera_resources};
use super::scene::{TestScene, texture};
use super::shadows::{MAP_SIZE, SPOT_BIAS, refused, render_caster};
use crate::{
    BoundResource, CheckError, ColorTarget, GpuContext, GpuError, RenderJob, Resource,
    TargetFormat, render,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightType};
use wgsl_variants_shaders::reference::shadow::{ShadowMap2d, ShadowParams};

/// The directional shadows' strength.
pub const DIRECTIONAL_STRENGTH: f32 = 0.85;

/// The radius of the region the directional maps cover, around the test floor's centre.
pub const REGION_RADIUS: f32 = 2.0;

/// One directional light's shadow: its map and the masks `Collect` made of it.
#[derive(Clone, Debug)]
pub struct ScreenShadow {
    /// `DIRECTIONAL` or `DIRECTIONAL_COOKIE`.
    pub light: LightType,
    /// The map's parameters.
    pub params: ShadowParams,
    /// The map, read back.
    pub map: ShadowMap2d,
    /// The map as rendered (`Depth16Unorm`).
    pub map_texels: Vec<u16>,
    /// The mask of each `Collect` variant (in [`ScreenShadows::variants`] order), `Rgba8Unorm`
    /// bytes of the rig's camera view.
    pub masks: Vec<Vec<u8>>,
}

/// The screen-space shadows of the rig's two directional lights.
#[derive(Clone, Debug)]
pub struct ScreenShadows {
    /// The `Collect` variants' keywords, in the order of each light's masks.
    pub variants: Vec<Vec<String>>,
    /// One per directional light type.
    pub lights: Vec<ScreenShadow>,
    /// The masks' size in pixels.
    pub width: u32,
    /// The masks' height in pixels.
    pub height: u32,
}

impl ScreenShadows {
    /// Renders each of the `directional` lights' maps with the cut-out caster, then every
    /// `Collect` variant over `camera`'s depth buffer (what `ScreenShadows::render` does with
    /// the light rig's two directional lights and camera).
    ///
    /// # Errors
    /// A GPU failure, a variant that does not compile, or a map the reference refuses.
    pub(crate) fn render_lights(
        ctx: &GpuContext,
        lib: &Library,
        scene: &TestScene,
        directional: [(&Light, LightType); 2],
        camera: &LightingCamera<'_>,
    ) -> Result<ScreenShadows, GpuError> {
        let pass = lib
            .pass("screen_space_shadows", "Collect")
            .map_err(|e| CheckError::lookup("screen_space_shadows/Collect", e))?;
        let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
        let variants: Vec<Vec<String>> = choices
            .iter()
            .map(|c| c.keywords(pass).into_iter().map(str::to_owned).collect())
            .collect();
        let refused = refused("screen_space_shadows/Collect");
        let center = scene.centre.extend(0.5);
        let mut lights = Vec::new();
        for (light, kind) in directional {
            let params = ShadowParams::for_directional(
                light,
                DIRECTIONAL_STRENGTH,
                SPOT_BIAS,
                center,
                REGION_RADIUS,
            )
            .map_err(&refused)?;
            let image = render_caster(
                ctx,
                lib,
                &["_RENDERING_CUTOUT", "SHADOWS_DEPTH"],
                params.world_to_shadow,
                params.light_position.extend(params.inv_range),
                MAP_SIZE,
            )?;
            let map =
                ShadowMap2d::from_depth16(MAP_SIZE, MAP_SIZE, &image.depth).map_err(&refused)?;
            let mut masks = Vec::new();
            for choice in &choices {
                let variant = wgsl_variants::Variant {
                    pass,
                    choice: choice.clone(),
                };
                let mut job =
                    RenderJob::new(&variant.label(), &lib.wgsl(&variant), "vs_main", "fs_main");
                job.width = scene.width;
                job.height = scene.height;
                job.targets = vec![ColorTarget::new(TargetFormat::Rgba8Unorm)];
                job.resources = collect_resources(scene, camera, &params, &image.depth);
                masks.push(render(ctx, &job)?.remove(0));
            }
            lights.push(ScreenShadow {
                light: kind,
                params,
                map,
                map_texels: image.depth,
                masks,
            });
        }
        Ok(ScreenShadows {
            variants,
            lights,
            width: scene.width,
            height: scene.height,
        })
    }

    /// The light `t`'s shadow (directional types only).
    pub fn light(&self, t: LightType) -> Option<&ScreenShadow> {
        self.lights.iter().find(|l| l.light == t)
    }

    /// The mask the `Lighting` variants read for light `t`: the hard one (the lighting pass
    /// leaves `SHADOWS_SOFT` to `Collect`), as a texture resource.
    pub fn lighting_mask(&self, t: LightType) -> Option<Resource> {
        let hard = self.variants.iter().position(|v| v.is_empty())?;
        let light = self.light(t)?;
        Some(texture(
            TargetFormat::Rgba8Unorm,
            self.width,
            self.height,
            &light.masks[hard],
        ))
    }

    /// The factor the hard mask holds at pixel `i` for light `t` (1 for other lights).
    pub fn lighting_factor(&self, t: LightType, i: usize) -> f32 {
        let hard = self.variants.iter().position(|v| v.is_empty());
        match (hard, self.light(t)) {
            (Some(hard), Some(light)) => f32::from(light.masks[hard][i * 4]) / 255.0,
            _ => 1.0,
        }
    }
}

/// The bindings of a `Collect` draw: the depth (`R32Float`), the lighting pass's camera
/// uniform, the light's `Shadow` uniform, its map and the comparison sampler.
fn collect_resources(
    scene: &TestScene,
    camera: &LightingCamera<'_>,
    params: &ShadowParams,
    map: &[u16],
) -> Vec<BoundResource> {
    let mut out = depth_camera_resources((scene.width, scene.height), camera);
    out.extend(shadow_map_resources(params, map));
    out
}

/// Bindings 10-12 of a directional light's shadow (`lighting/shadow`): the `Shadow` uniform of
/// `params`, the `Depth16Unorm` map's texels and the LessEqual comparison sampler. Shared by
/// `Collect` and URP's main light (`stencil_deferred`, `_MAIN_LIGHT_SHADOWS`).
pub(crate) fn shadow_map_resources(params: &ShadowParams, map: &[u16]) -> Vec<BoundResource> {
    let shadow: Vec<u8> = params
        .uniform()
        .into_iter()
        .flat_map(f32::to_le_bytes)
        .collect();
    vec![
        BoundResource::new(0, 10, Resource::Uniform(shadow)),
        BoundResource::new(
            0,
            11,
            Resource::Texture2d {
                format: wgpu::TextureFormat::Depth16Unorm,
                width: MAP_SIZE,
                height: MAP_SIZE,
                data: map.iter().flat_map(|d| d.to_le_bytes()).collect(),
            },
        ),
        BoundResource::new(
            0,
            12,
            Resource::ComparisonSampler {
                compare: wgpu::CompareFunction::LessEqual,
                nearest: true,
            },
        ),
    ]
}
