//! URP's additional-light shadows in the pass checks (`_ADDITIONAL_LIGHT_SHADOWS`): an atlas of
//! [`TILE`]-texel slices — one perspective view for a spot light, six 90° views for a point
//! light (cube faces +X, −X, +Y, −Y, +Z, −Z) — rendered by the cut-out caster over the
//! occluders of [`super::shadows`], read back, and bound with URP's per-light parameters and
//! per-slice matrices (`universal/additional_light_shadow`'s bindings 17-19). The reference,
//! [`AdditionalShadows`], compares the same texels.

use glam::{Mat4, Vec3, Vec4};

use super::rig::LightRig;
use super::screen_masks::map_resources;
use super::shadows::{MAP_SIZE, POINT_STRENGTH, SPOT_STRENGTH, lay_tiles, refused, render_caster};
use crate::{BoundResource, GpuContext, GpuError, Resource};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightShape};
use wgsl_variants_shaders::reference::shadow::{
    ShadowMap2d, atlas_tile, cube_face_view_proj, spot_shadow_view_proj,
};
use wgsl_variants_shaders::reference::urp::additional_shadow::{
    AdditionalShadowParams, AdditionalShadows,
};
use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;

/// Edge length of one slice in texels.
pub const TILE: u32 = MAP_SIZE;

/// How one additional light casts: its strength and whether it is soft (URP's per-light soft
/// flag, honoured under `_SHADOWS_SOFT`); `None` for a light without shadow.
pub type Casting = Option<(f32, bool)>;

/// How the rig's point and spot lights cast in the URP checks, in this order (their indices in
/// the shadows' record): the point light hard at [`POINT_STRENGTH`], the spot light soft at
/// [`SPOT_STRENGTH`] (so that `_SHADOWS_SOFT` filters one and leaves the other).
pub(crate) fn rig_casting(rig: &LightRig) -> [(Light, Casting); 2] {
    [
        (rig.point_light, Some((POINT_STRENGTH, false))),
        (rig.spot_light, Some((SPOT_STRENGTH, true))),
    ]
}

/// The additional lights' atlas as rendered, with the reference over it.
#[derive(Clone, Debug)]
pub struct AdditionalAtlas {
    /// What the receivers read, for the reference.
    pub shadows: AdditionalShadows,
    /// The atlas as rendered (`Depth16Unorm`).
    pub texels: Vec<u16>,
    /// Its width and height in texels.
    pub size: (u32, u32),
    /// Each light's position (the origin for a directional light, which casts none here).
    pub positions: Vec<Vec3>,
}

impl AdditionalAtlas {
    /// Renders the slices of `lights` (each with how it casts; directional lights cast none
    /// here) with the cut-out caster over the built-in shadow check's occluders into an atlas
    /// of [`TILE`]-texel tiles ([`AdditionalAtlas::render_with`]); `pass` names the reader in
    /// an error.
    ///
    /// # Errors
    /// A GPU failure, or lights the reference refuses (more than it describes).
    pub(crate) fn render(
        ctx: &GpuContext,
        lib: &Library,
        pass: &str,
        lights: &[(Light, Casting)],
        fade: UrpShadowFade,
    ) -> Result<AdditionalAtlas, GpuError> {
        AdditionalAtlas::render_with(pass, lights, fade, TILE, |view_proj, position| {
            Ok(render_caster(
                ctx,
                lib,
                &["_RENDERING_CUTOUT", "SHADOWS_DEPTH"],
                view_proj,
                position,
                TILE,
            )?
            .depth)
        })
    }

    /// Renders the slices of `lights` (each with how it casts; directional lights cast none)
    /// into an atlas of `tile`-texel tiles four tiles wide, in the order of the lights, and
    /// fades them with `fade`. `render` draws one slice: given the slice's view-projection and
    /// the light's position (w: 1 / range), its `Depth16Unorm` codes row by row.
    ///
    /// # Errors
    /// What `render` returns, or lights the reference refuses (more than it describes).
    pub(crate) fn render_with(
        pass: &str,
        lights: &[(Light, Casting)],
        fade: UrpShadowFade,
        tile: u32,
        mut render: impl FnMut(Mat4, Vec4) -> Result<Vec<u16>, GpuError>,
    ) -> Result<AdditionalAtlas, GpuError> {
        let mut params = Vec::new();
        let mut positions = Vec::new();
        // Each slice's view: its view-projection and the caster's light position (w: 1/range).
        let mut views: Vec<(Mat4, Vec4)> = Vec::new();
        for (light, casting) in lights {
            let first_slice = views.len();
            positions.push(match light.shape {
                LightShape::Point { position, .. } | LightShape::Spot { position, .. } => position,
                LightShape::Directional { .. } => Vec3::ZERO,
            });
            let (point, slices) = match (light.shape, casting) {
                (
                    LightShape::Point {
                        position, range, ..
                    },
                    Some(_),
                ) => {
                    let faces = (0..6).map(|f| {
                        (
                            cube_face_view_proj(position, f, range),
                            position.extend(1.0 / range),
                        )
                    });
                    (true, faces.collect())
                }
                (
                    LightShape::Spot {
                        position,
                        direction,
                        angle_degrees,
                        range,
                    },
                    Some(_),
                ) => (
                    false,
                    vec![(
                        spot_shadow_view_proj(position, direction, angle_degrees, range),
                        position.extend(1.0 / range),
                    )],
                ),
                _ => (false, Vec::new()),
            };
            let (strength, soft) = casting.unwrap_or((0.0, false));
            params.push(AdditionalShadowParams {
                strength,
                soft,
                point,
                first_slice: (!slices.is_empty()).then_some(first_slice),
            });
            views.extend(slices);
        }
        let grid = (4, views.len().div_ceil(4).max(1) as u32);
        let (texels, size) = lay_tiles(
            grid,
            tile,
            views
                .iter()
                .map(|&(view_proj, position)| render(view_proj, position)),
        )?;
        let atlas = ShadowMap2d::from_depth16(size.0, size.1, &texels).map_err(refused(pass))?;
        let world_to_atlas = views
            .iter()
            .enumerate()
            .map(|(i, (view_proj, _))| atlas_tile(grid, i) * *view_proj)
            .collect();
        let shadows =
            AdditionalShadows::new(params, world_to_atlas, atlas, fade).map_err(refused(pass))?;
        Ok(AdditionalAtlas {
            shadows,
            texels,
            size,
            positions,
        })
    }

    /// The same atlas with another fade.
    pub(crate) fn faded(&self, fade: UrpShadowFade) -> AdditionalAtlas {
        AdditionalAtlas {
            shadows: self.shadows.with_fade(fade),
            ..self.clone()
        }
    }

    /// Bindings 17-19 of `universal/additional_light_shadow`: the `AdditionalShadows` record,
    /// the atlas and the comparison sampler.
    pub(crate) fn resources(&self) -> Vec<BoundResource> {
        map_resources(&self.shadows.uniform(), &self.texels, self.size, 17)
    }

    /// Binding 8 of `stencil_deferred`'s `PunctualLit` with `_ADDITIONAL_LIGHT_SHADOWS`: URP's
    /// `_ShadowLightIndex`, the drawn light's record among the atlas's parameters (a `vec4u`,
    /// x the index).
    pub(crate) fn shadow_light_index(index: u32) -> BoundResource {
        let bytes = [index, 0, 0, 0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        BoundResource::new(0, 8, Resource::Uniform(bytes))
    }

    /// Where light `light` is shadowed among `positions`: those its realtime shadow darkens
    /// (before the fade), for fitting the fade and for reports.
    pub(crate) fn shadowed(&self, light: usize, positions: &[Vec3]) -> Vec<Vec3> {
        let light_position = self.positions[light];
        let unfaded = self.shadows.with_fade(UrpShadowFade::NONE);
        positions
            .iter()
            .copied()
            .filter(|&p| {
                let to_light = (light_position - p).normalize();
                unfaded.attenuation(light, false, p, to_light, p).0 < 1.0
            })
            .collect()
    }
}
