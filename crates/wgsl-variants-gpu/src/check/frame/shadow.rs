//! The frame's shadow maps: every object drawn by its `standard/ShadowCaster` variant into a
//! spot light's `Depth16Unorm` map (`SHADOWS_DEPTH`), a point light's six faces of distances
//! (`SHADOWS_CUBE`) or a directional light's one cascade (`SHADOWS_SCREEN`), read back; the
//! receivers bind what was rendered, and the reference reads the same maps
//! ([`wgsl_variants_shaders::reference::shadow`]). A directional light's receivers read a screen-space
//! mask instead, which each path renders with `screen_space_shadows/Collect` over its own depth
//! buffer ([`FrameShadows::with_masks`]): the forward path's from a depth pre-pass of the
//! casters with the camera's view (as Unity renders its camera depth texture), the deferred
//! path's from the G-buffer's depth. Whether a caster writes the right texels is the
//! ShadowCaster check's business (`check::caster`), the mask's the Collect check's
//! (`check::screen_shadows`); the frame proves that both paths receive the shadows alike.

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};

use super::super::scene::{push_mat4, push_vec4, texture};
use super::super::shadows::{CUBE_FORMAT, DEPTH, red_f16, refused, shadow_bindings};
use super::{Drawer, FrameScene};
use crate::{
    BoundResource, ColorTarget, DepthTest, Draw, DrawPass, GpuContext, GpuError, Resource,
    TargetFormat, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cascades::Cascades;
use wgsl_variants_shaders::reference::light::{Light, LightShape};
use wgsl_variants_shaders::reference::shadow::{
    ShadowCube, ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams, cube_face_view_proj,
    shadow_factor,
};
use wgsl_variants_shaders::reference::surface::SmoothnessSource;
use wgsl_variants_shaders::reference::tolerance::unorm_store_error;

/// Edge length of a spot light's map in texels.
pub const SHADOW_MAP_SIZE: u32 = 128;

/// Edge length of each face of a point light's cube in texels.
pub const SHADOW_CUBE_SIZE: u32 = 32;

/// Edge length of a directional light's map (one cascade over [`FrameScene::shadow_region`])
/// in texels.
pub const DIRECTIONAL_MAP_SIZE: u32 = 256;

/// How a light of the frame casts shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowSpec {
    /// Strength in [0, 1]: the shadowed light keeps `1 − strength`.
    pub strength: f32,
    /// A spot's or directional light's depth bias (depth-buffer units); unused for point
    /// lights.
    pub bias: f32,
    /// `SHADOWS_SOFT`: the filtered footprint (a directional light's is its mask's: the
    /// `Collect` variant with `SHADOWS_SOFT`).
    pub soft: bool,
}

/// One light's rendered shadow: what the receivers bind and the reference reads.
#[derive(Clone, Debug)]
pub struct FrameShadow {
    /// `SHADOWS_DEPTH` (spot), `SHADOWS_CUBE` (point) or `SHADOWS_SCREEN` (directional), with
    /// `SHADOWS_SOFT` as specified.
    pub keywords: ShadowKeywords,
    /// The `Shadow` uniform's values.
    pub params: ShadowParams,
    /// The spot's or directional light's map.
    pub map: Option<ShadowMap2d>,
    /// The point's cube.
    pub cube: Option<ShadowCube>,
    /// Bindings 10–14 (the map; for a directional light, what `Collect` binds), and after
    /// [`FrameShadows::with_masks`] a directional light's mask at 15.
    pub resources: Vec<BoundResource>,
}

impl FrameShadow {
    /// The receiving variant's shadow keywords (a directional light's `SHADOWS_SOFT` belongs
    /// to its mask's `Collect` variant, not to the receiver).
    pub fn names(&self) -> Vec<&'static str> {
        let k = self.keywords;
        [
            (k.depth, "SHADOWS_DEPTH"),
            (k.cube, "SHADOWS_CUBE"),
            (k.screen, "SHADOWS_SCREEN"),
            (k.soft && !k.screen, "SHADOWS_SOFT"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }

    /// The reference shadow factor interval at `p` (an uncertain tap may go either way). A
    /// directional light's is its map's, compared as `Collect` compares it (as a spot's).
    pub fn factor(&self, p: Vec3) -> (f32, f32) {
        let maps = ShadowMaps {
            map: self.map.as_ref(),
            cube: self.cube.as_ref(),
        };
        let keywords = ShadowKeywords {
            depth: self.keywords.depth || self.keywords.screen,
            screen: false,
            ..self.keywords
        };
        shadow_factor(&self.params, keywords, maps, p)
    }

    /// What a receiver may read at `p`: [`FrameShadow::factor`], for a directional light
    /// widened by the 8-bit store of the `Rgba8Unorm` mask it reads.
    pub fn received(&self, p: Vec3) -> (f32, f32) {
        let (lo, hi) = self.factor(p);
        if self.keywords.screen {
            let e = unorm_store_error(8);
            ((lo - e).max(0.0), (hi + e).min(1.0))
        } else {
            (lo, hi)
        }
    }
}

/// Every shadow of a frame: the main light's and each per-pixel light's.
#[derive(Clone, Debug)]
pub struct FrameShadows {
    /// The main light's (`SHADOWS_SCREEN`), if [`FrameScene::main_shadow`] asks for one.
    pub main: Option<FrameShadow>,
    /// One per light of [`FrameScene::lights`], in order (`None`: no shadow).
    pub lights: Vec<Option<FrameShadow>>,
}

impl FrameShadows {
    /// Every shadow, the main light's first.
    pub fn iter(&self) -> impl Iterator<Item = &FrameShadow> {
        self.main.iter().chain(self.lights.iter().flatten())
    }

    /// The shadows as one path's receivers bind them: each `SHADOWS_SCREEN` shadow gains its
    /// mask at binding 15, rendered by `screen_space_shadows/Collect` (`SHADOWS_SOFT` as the
    /// light asks) over `depth`, that path's depth buffer (one `f32` per pixel of the frame).
    /// Also returns the number of `Collect` draws.
    ///
    /// # Errors
    /// A GPU failure or a `Collect` variant that does not compile.
    pub fn with_masks(
        &self,
        ctx: &GpuContext,
        lib: &Library,
        frame: &FrameScene,
        depth: &[f32],
    ) -> Result<(FrameShadows, usize), GpuError> {
        let (w, h) = (frame.width, frame.height);
        let mut drawer = Drawer::new(lib, frame, false);
        let camera: Arc<[BoundResource]> = Arc::from(vec![
            BoundResource::new(
                0,
                3,
                Resource::Texture2d {
                    format: wgpu::TextureFormat::R32Float,
                    width: w,
                    height: h,
                    data: depth.iter().flat_map(|d| d.to_le_bytes()).collect(),
                },
            ),
            BoundResource::new(0, 4, Resource::Uniform(frame.deferred_camera())),
        ]);
        let mut draws = 0;
        let mut masked = |shadow: &Option<FrameShadow>| -> Result<Option<FrameShadow>, GpuError> {
            let Some(shadow) = shadow else {
                return Ok(None);
            };
            if !shadow.keywords.screen {
                return Ok(Some(shadow.clone()));
            }
            // The frame's directional light has one cascade (Unity's SHADOWS_SINGLE_CASCADE):
            // `Collect` binds its map as cascade 0 of a `CascadedShadow`.
            let mut names = vec!["SHADOWS_SINGLE_CASCADE"];
            if shadow.keywords.soft {
                names.push("SHADOWS_SOFT");
            }
            let (label, wgsl) = drawer.text("screen_space_shadows", "Collect", names)?;
            let cascade: Vec<u8> = Cascades::single(&shadow.params)
                .uniform()
                .into_iter()
                .flat_map(f32::to_le_bytes)
                .collect();
            let mut resources = shadow.resources.clone();
            for r in &mut resources {
                if (r.group, r.binding) == (0, 10) {
                    r.resource = Resource::Uniform(cascade.clone());
                }
            }
            let mut pass = DrawPass::new(
                "frame: screen-space shadow",
                w,
                h,
                vec![ColorTarget::new(TargetFormat::Rgba8Unorm)],
            );
            pass.draws.push(
                Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
                    .with_shared(&camera)
                    .with_resources(resources),
            );
            draws += 1;
            let mask = render_pass(ctx, &pass)?.targets.remove(0);
            let mut out = shadow.clone();
            out.resources.push(BoundResource::new(
                0,
                15,
                texture(TargetFormat::Rgba8Unorm, w, h, &mask),
            ));
            Ok(Some(out))
        };
        let main = masked(&self.main)?;
        let lights = self
            .lights
            .iter()
            .map(&mut masked)
            .collect::<Result<_, _>>()?;
        Ok((FrameShadows { main, lights }, draws))
    }

    /// Whether some shadow needs a screen-space mask (and so the forward path a depth
    /// pre-pass).
    pub fn needs_masks(&self) -> bool {
        self.iter().any(|s| s.keywords.screen)
    }
}

/// The caster draws of every object with the camera binding set to the light's view
/// (`view_proj`; `position` = light position and `1 / range` in w).
pub(super) fn caster_draws(
    drawer: &mut Drawer<'_>,
    keyword: &'static str,
    view_proj: Mat4,
    position: Vec4,
) -> Result<Vec<Draw>, GpuError> {
    let frame = drawer.frame;
    let mut camera = Vec::new();
    push_mat4(&mut camera, view_proj);
    push_vec4(&mut camera, position);
    let mut draws = Vec::new();
    for object in &frame.objects {
        let mut names = Vec::new();
        if object.keywords.cutout() {
            names.push("_RENDERING_CUTOUT");
        }
        if object.keywords.smoothness == SmoothnessSource::Albedo {
            names.push("_SMOOTHNESS_ALBEDO");
        }
        names.push(keyword);
        let (label, wgsl) = drawer.text("standard", "ShadowCaster", names)?;
        let mut resources: Vec<BoundResource> = frame
            .object_resources(object)
            .into_iter()
            .filter(|r| (r.group, r.binding) != (0, 0))
            .collect();
        resources.push(BoundResource::new(0, 0, Resource::Uniform(camera.clone())));
        draws.push(
            Draw::fullscreen(
                &format!("{} {label}", object.name),
                &wgsl,
                "vs_main",
                "fs_main",
            )
            .with_mesh(object.mesh())
            .with_resources(resources)
            .with_depth(DepthTest::OPAQUE),
        );
    }
    Ok(draws)
}

/// Renders the shadow of every light of `frame` that casts one: the main light's
/// ([`FrameScene::main_shadow`]) and each per-pixel light's, in `frame.lights` order.
///
/// # Errors
/// A GPU failure, or a shadow the reference refuses (a strength outside [0, 1], a bias outside
/// [0, 1)) as [`crate::CheckError::UnknownToReference`].
pub fn render_shadows(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
) -> Result<FrameShadows, GpuError> {
    let mut drawer = Drawer::new(lib, frame, false);
    let main = frame
        .main_shadow
        .map(|spec| render_shadow(ctx, &mut drawer, &frame.main_light_source, spec))
        .transpose()?;
    let lights = frame
        .lights
        .iter()
        .map(|light| {
            light
                .shadow
                .map(|spec| render_shadow(ctx, &mut drawer, &light.light, spec))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    Ok(FrameShadows { main, lights })
}

/// Renders one light's shadow: a point light's cube, a spot's map, or a directional light's
/// map over the frame's [`FrameScene::shadow_region`].
fn render_shadow(
    ctx: &GpuContext,
    drawer: &mut Drawer<'_>,
    light: &Light,
    spec: ShadowSpec,
) -> Result<FrameShadow, GpuError> {
    let refused = refused("standard/ShadowCaster");
    let frame = drawer.frame;
    let (params, size) = match light.shape {
        LightShape::Directional { .. } => {
            let (center, radius) = frame.shadow_region;
            let params =
                ShadowParams::for_directional(light, spec.strength, spec.bias, center, radius)
                    .map_err(&refused)?;
            (params, DIRECTIONAL_MAP_SIZE)
        }
        _ => (
            ShadowParams::for_light(light, spec.strength, spec.bias).map_err(&refused)?,
            SHADOW_MAP_SIZE,
        ),
    };
    let position = params.light_position.extend(params.inv_range);
    let directional = matches!(light.shape, LightShape::Directional { .. });
    let cube = matches!(light.shape, LightShape::Point { .. });
    let keywords = ShadowKeywords {
        depth: !cube && !directional,
        cube,
        screen: directional,
        soft: spec.soft,
        ..ShadowKeywords::default()
    };
    if cube {
        let range = 1.0 / params.inv_range;
        let size = SHADOW_CUBE_SIZE;
        let mut faces: [Vec<u8>; 6] = Default::default();
        for (face, bytes) in faces.iter_mut().enumerate() {
            let mut pass = DrawPass::new(
                "frame: shadow cube face",
                size,
                size,
                vec![ColorTarget::new(TargetFormat::Rgba16Float).with_clear([1.0; 4])],
            );
            pass.depth = true;
            pass.draws = caster_draws(
                drawer,
                "SHADOWS_CUBE",
                cube_face_view_proj(params.light_position, face, range),
                position,
            )?;
            *bytes = render_pass(ctx, &pass)?.targets.remove(0);
        }
        debug_assert_eq!(CUBE_FORMAT, TargetFormat::Rgba16Float.wgpu_format());
        let texels = faces.iter().flat_map(|f| red_f16(f)).collect();
        let cube = ShadowCube::new(size, texels).map_err(&refused)?;
        return Ok(FrameShadow {
            keywords,
            resources: shadow_bindings(&params, None, Some((&faces, size))),
            params,
            map: None,
            cube: Some(cube),
        });
    }
    let mut pass = DrawPass::new("frame: shadow map", size, size, Vec::new());
    pass.depth = true;
    pass.depth_format = DEPTH;
    pass.draws = caster_draws(drawer, "SHADOWS_DEPTH", params.world_to_shadow, position)?;
    let depth = render_pass(ctx, &pass)?.depth.unwrap_or_default();
    let codes: Vec<u16> = depth.iter().map(|d| (d * 65535.0).round() as u16).collect();
    let map = ShadowMap2d::from_depth16(size, size, &codes).map_err(&refused)?;
    Ok(FrameShadow {
        keywords,
        resources: shadow_bindings(&params, Some((&codes, size)), None),
        params,
        map: Some(map),
        cube: None,
    })
}
