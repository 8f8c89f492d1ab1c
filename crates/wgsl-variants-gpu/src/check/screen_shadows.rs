//! `SHADOWS_SCREEN` for the GPU check (docs/shading.md §11): each directional light of the
//! [`LightRig`] gets a shadow map — the occluder scene of [`super::shadows`] rendered by
//! `standard/ShadowCaster` (`SHADOWS_DEPTH`) through the light's orthographic view
//! ([`ShadowParams::for_directional`]) — and `screen_space_shadows/Collect` turns that map into
//! a mask of the rig's camera view, over the same depth buffer the `Lighting` check rebuilds its
//! positions from. The maps are read back: the reference compares every mask texel with
//! [`shadow_factor`] over the read-back map at the rebuilt position (an interval where a tap is
//! within a hair of flipping), and the `Lighting` variants with `SHADOWS_SCREEN` read the
//! rendered mask, as the reference does, so the lighting's use of it is tested exactly.

use std::time::Instant;

use super::deferred::texture;
use super::lights::{LightRig, depth_camera_resources};
use super::passes::keyword_coverage;
use super::report::{Mismatch, PassReport};
use super::scene::TestScene;
use super::shadows::{MAP_SIZE, SPOT_BIAS, refused, render_caster};
use crate::{
    BoundResource, CheckError, ColorTarget, GpuContext, GpuError, RenderJob, Resource,
    TargetFormat, render,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::LightType;
use wgsl_variants_shaders::reference::shadow::{
    ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams, shadow_factor,
};
use wgsl_variants_shaders::reference::tolerance::unorm_within;

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
    /// Renders each directional light's map with the cut-out caster, then every `Collect`
    /// variant over the rig's depth buffer.
    ///
    /// # Errors
    /// A GPU failure, a variant that does not compile, or a map the reference refuses.
    pub fn render(
        ctx: &GpuContext,
        lib: &Library,
        scene: &TestScene,
        rig: &LightRig,
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
        for (light, kind) in [
            (&rig.directional_light, LightType::Directional),
            (&rig.directional_cookie_light, LightType::DirectionalCookie),
        ] {
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
                job.resources = collect_resources(scene, rig, &params, &image.depth);
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
    rig: &LightRig,
    params: &ShadowParams,
    map: &[u16],
) -> Vec<BoundResource> {
    let camera = rig.camera(scene);
    let mut out = depth_camera_resources((scene.width, scene.height), &camera);
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

/// Checks every `Collect` variant's mask of each directional light: every pixel against
/// [`shadow_factor`] over the read-back map at the position rebuilt from depth (1 LSB of
/// `Rgba8Unorm`, within the interval of an uncertain tap), and each keyword changing a pixel.
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
    for (v, names) in shadows.variants.iter().enumerate() {
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let (keywords, _) = ShadowKeywords::split(&names);
        let keywords = ShadowKeywords {
            depth: true,
            ..keywords
        };
        for light in &shadows.lights {
            let mask = &light.masks[v];
            for (i, (x, y)) in scene.pixels().enumerate() {
                let p = rig.deferred_position(scene, x, y);
                let (lo, hi) = shadow_factor(
                    &light.params,
                    keywords,
                    ShadowMaps {
                        map: Some(&light.map),
                        cube: None,
                    },
                    p,
                );
                uncertain += usize::from(lo != hi);
                shadowed += usize::from(hi < 1.0);
                let got = mask[i * 4];
                let want = (f32::from(got) / 255.0).clamp(lo.min(hi), lo.max(hi));
                let rest = [mask[i * 4 + 1], mask[i * 4 + 2], mask[i * 4 + 3]];
                report.record(
                    unorm_within(u32::from(got), want, 8) && rest == [255; 3],
                    || Mismatch {
                        shader: "screen_space_shadows".to_owned(),
                        pass: "Collect".to_owned(),
                        keywords: format!("{{{}}} for {:?}", names.join(", "), light.light),
                        target: "mask Rgba8Unorm".to_owned(),
                        pixel: [x, y],
                        expected: vec![lo, hi],
                        got: vec![f32::from(got) / 255.0],
                        got_raw: mask[i * 4..i * 4 + 4]
                            .iter()
                            .map(|&b| u32::from(b))
                            .collect(),
                    },
                );
            }
            report.draws += 1;
        }
        report.variants_run += 1;
        report.distinct_shaders += 1;
    }
    report.keywords = keyword_coverage(pass, &choices, |a, b| {
        shadows.lights.iter().any(|l| l.masks[a] != l.masks[b])
    });
    report.judge_keywords();
    report.notes.push(format!(
        "the {}x{} masks of 2 directional lights (one {MAP_SIZE}x{MAP_SIZE} Depth16Unorm map each, an orthographic box of radius {REGION_RADIUS}); {shadowed} shadowed and {uncertain} uncertain-tap pixel comparisons",
        scene.width, scene.height
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}
