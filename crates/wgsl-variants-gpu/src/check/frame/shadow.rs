//! The frame's shadow maps: every object drawn by its `standard/ShadowCaster` variant into a
//! spot light's `Depth16Unorm` map (`SHADOWS_DEPTH`), a point light's six faces of distances
//! (`SHADOWS_CUBE`) or a directional light's four cascades (`SHADOWS_SCREEN`), read back; the
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

use super::super::rig::fade_resource;
use super::super::scene::{push_mat4, push_vec4, texture};
use super::super::screen_masks::CascadeAtlas;
use super::super::shadows::{CUBE_FORMAT, DEPTH, red_f16, refused, shadow_bindings};
use super::{Drawer, FrameScene};
use crate::{
    BoundResource, ColorTarget, DepthTest, Draw, DrawPass, GpuContext, GpuError, Resource,
    TargetFormat, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades};
use wgsl_variants_shaders::reference::light::{Light, LightShape};
use wgsl_variants_shaders::reference::shadow::{
    ShadowCube, ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams, cube_face_view_proj,
    mix_realtime_and_baked, shadow_factor,
};
use wgsl_variants_shaders::reference::shadow_fade::ShadowFade;
use wgsl_variants_shaders::reference::surface::SmoothnessSource;
use wgsl_variants_shaders::reference::tolerance::unorm_store_error;

/// Edge length of a spot light's map in texels.
pub const SHADOW_MAP_SIZE: u32 = 128;

/// Edge length of each face of a point light's cube in texels.
pub const SHADOW_CUBE_SIZE: u32 = 32;

/// Edge length of each cascade's tile of a directional light's atlas in texels (four
/// cascades: a 512 × 512 atlas).
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
    /// A directional light's cascades are picked by the slices' bounding spheres
    /// (`SHADOWS_SPLIT_SPHERES`, Unity's Stable Fit) rather than by view depth; unused for
    /// other lights.
    pub split_spheres: bool,
}

/// One light's rendered shadow: what the receivers bind and the reference reads.
#[derive(Clone, Debug)]
pub struct FrameShadow {
    /// `SHADOWS_DEPTH` (spot), `SHADOWS_CUBE` (point) or `SHADOWS_SCREEN` (directional), with
    /// `SHADOWS_SOFT` as specified.
    pub keywords: ShadowKeywords,
    /// The `Shadow` uniform's values (a directional light's: its first cascade's).
    pub params: ShadowParams,
    /// A directional light's cascades over [`FrameScene::cascade_splits`] and the `Collect`
    /// keywords that read them.
    pub cascades: Option<(Cascades, CascadeKeywords)>,
    /// The spot's map, or the directional light's atlas of cascades.
    pub map: Option<ShadowMap2d>,
    /// The point's cube.
    pub cube: Option<ShadowCube>,
    /// The distance fade the receivers apply ([`FrameScene::shadow_fade`]).
    pub fade: ShadowFade,
    /// Bindings 10–14 (the map; for a directional light, what `Collect` binds) and the fade
    /// at 18, and after [`FrameShadows::with_masks`] a directional light's mask at 15.
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

    /// The reference shadow factor interval at `p` (an uncertain tap or cascade may go
    /// either way). A directional light's is its cascades' ([`Cascades::factor`]).
    pub fn factor(&self, p: Vec3) -> (f32, f32) {
        if let (Some((cascades, keywords)), Some(atlas)) = (&self.cascades, &self.map) {
            return cascades.factor(*keywords, atlas, p);
        }
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

    /// What a receiver's light is scaled by at `p`: [`FrameShadow::factor`] (for a
    /// directional light widened by the 8-bit store of the `Rgba8Unorm` mask it reads) faded
    /// by distance (no baked occlusion in the frame).
    pub fn received(&self, p: Vec3) -> (f32, f32) {
        let (lo, hi) = self.factor(p);
        let (lo, hi) = if self.keywords.screen {
            let e = unorm_store_error(8);
            ((lo - e).max(0.0), (hi + e).min(1.0))
        } else {
            (lo, hi)
        };
        let fade = self.fade.fade(p);
        let mix = |f| mix_realtime_and_baked(self.keywords, f, 1.0, fade);
        (mix(lo), mix(hi))
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
            // The light's cascades (its resources bind their atlas and `CascadedShadow`).
            let mut names = Vec::new();
            if let Some((_, k)) = &shadow.cascades {
                names.extend(k.split_spheres.then_some("SHADOWS_SPLIT_SPHERES"));
                names.extend(k.soft.then_some("SHADOWS_SOFT"));
            }
            let (label, wgsl) = drawer.text("screen_space_shadows", "Collect", names)?;
            let resources = shadow.resources.clone();
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
/// atlas of cascades over the frame's [`FrameScene::cascade_splits`].
fn render_shadow(
    ctx: &GpuContext,
    drawer: &mut Drawer<'_>,
    light: &Light,
    spec: ShadowSpec,
) -> Result<FrameShadow, GpuError> {
    let refused = refused("standard/ShadowCaster");
    let frame = drawer.frame;
    if matches!(light.shape, LightShape::Directional { .. }) {
        return render_cascades(drawer, ctx, light, spec);
    }
    let params = ShadowParams::for_light(light, spec.strength, spec.bias).map_err(&refused)?;
    let size = SHADOW_MAP_SIZE;
    let position = params.light_position.extend(params.inv_range);
    let cube = matches!(light.shape, LightShape::Point { .. });
    let keywords = ShadowKeywords {
        depth: !cube,
        cube,
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
        let mut resources = shadow_bindings(&params, None, Some((&faces, size)));
        resources.push(fade_resource(&frame.shadow_fade));
        return Ok(FrameShadow {
            keywords,
            resources,
            params,
            cascades: None,
            map: None,
            cube: Some(cube),
            fade: frame.shadow_fade,
        });
    }
    let mut pass = DrawPass::new("frame: shadow map", size, size, Vec::new());
    pass.depth = true;
    pass.depth_format = DEPTH;
    pass.draws = caster_draws(drawer, "SHADOWS_DEPTH", params.world_to_shadow, position)?;
    let depth = render_pass(ctx, &pass)?.depth.unwrap_or_default();
    let codes: Vec<u16> = depth.iter().map(|d| (d * 65535.0).round() as u16).collect();
    let map = ShadowMap2d::from_depth16(size, size, &codes).map_err(&refused)?;
    let mut resources = shadow_bindings(&params, Some((&codes, size)), None);
    resources.push(fade_resource(&frame.shadow_fade));
    Ok(FrameShadow {
        keywords,
        resources,
        params,
        cascades: None,
        map: Some(map),
        cube: None,
        fade: frame.shadow_fade,
    })
}

/// A directional light's shadow: its cascades fitted to the frame's camera and
/// [`FrameScene::cascade_splits`], each rendered by the casters into its tile of the atlas
/// (`SHADOWS_SCREEN`: the receivers read the mask `Collect` makes of it).
fn render_cascades(
    drawer: &mut Drawer<'_>,
    ctx: &GpuContext,
    light: &Light,
    spec: ShadowSpec,
) -> Result<FrameShadow, GpuError> {
    let refused = refused("screen_space_shadows/Collect");
    let frame = drawer.frame;
    let cascades = Cascades::fit(
        light,
        spec.strength,
        spec.bias,
        &frame.cascade_camera(),
        &frame.cascade_splits,
    )
    .map_err(&refused)?;
    let size = DIRECTIONAL_MAP_SIZE;
    let atlas = CascadeAtlas::render(cascades, size, "screen_space_shadows/Collect", |c| {
        let mut pass = DrawPass::new("frame: shadow cascade", size, size, Vec::new());
        pass.depth = true;
        pass.depth_format = DEPTH;
        let position = c.params.light_position.extend(c.params.inv_range);
        pass.draws = caster_draws(drawer, "SHADOWS_DEPTH", c.view_proj, position)?;
        let depth = render_pass(ctx, &pass)?.depth.unwrap_or_default();
        Ok(depth.iter().map(|d| (d * 65535.0).round() as u16).collect())
    })?;
    let mut resources = atlas.resources();
    resources.push(fade_resource(&frame.shadow_fade));
    let collect = CascadeKeywords {
        single: false,
        split_spheres: spec.split_spheres,
        soft: spec.soft,
        lit_beyond_far: false,
    };
    Ok(FrameShadow {
        keywords: ShadowKeywords {
            screen: true,
            soft: spec.soft,
            ..ShadowKeywords::default()
        },
        params: atlas.cascades.cascades[0].params,
        cascades: Some((atlas.cascades, collect)),
        map: Some(atlas.map),
        cube: None,
        resources,
        fade: frame.shadow_fade,
    })
}
