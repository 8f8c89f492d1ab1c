//! The frame's shadow maps: every object drawn by its `standard/ShadowCaster` variant into a
//! spot light's `Depth16Unorm` map (`SHADOWS_DEPTH`) or a point light's six faces of distances
//! (`SHADOWS_CUBE`), read back; the receivers bind what was rendered, and the reference reads
//! the same maps ([`wgsl_variants::reference::shadow`]). Whether a caster writes the right
//! texels is the ShadowCaster check's business (`check::caster`); the frame proves that both
//! paths receive the shadows alike.

use glam::{Mat4, Vec3, Vec4};

use super::super::scene::{push_mat4, push_vec4};
use super::super::shadows::{CUBE_FORMAT, DEPTH, red_f16, refused, shadow_bindings};
use super::{Drawer, FrameScene};
use crate::{
    BoundResource, ColorTarget, DepthTest, Draw, DrawPass, GpuContext, GpuError, Resource,
    TargetFormat, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants::reference::shadow::{
    ShadowCube, ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams, cube_face_view_proj,
    shadow_factor,
};
use wgsl_variants::reference::surface::SmoothnessSource;

/// Edge length of a spot light's map in texels.
pub const SHADOW_MAP_SIZE: u32 = 128;

/// Edge length of each face of a point light's cube in texels.
pub const SHADOW_CUBE_SIZE: u32 = 32;

/// How a light of the frame casts shadows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowSpec {
    /// Strength in [0, 1]: the shadowed light keeps `1 − strength`.
    pub strength: f32,
    /// A spot's depth bias (depth-buffer units); unused for point lights.
    pub bias: f32,
    /// `SHADOWS_SOFT`: the filtered footprint.
    pub soft: bool,
}

/// One light's rendered shadow: what the receivers bind and the reference reads.
#[derive(Clone, Debug)]
pub struct FrameShadow {
    /// `SHADOWS_DEPTH` (spot) or `SHADOWS_CUBE` (point), with `SHADOWS_SOFT` as specified.
    pub keywords: ShadowKeywords,
    /// The `Shadow` uniform's values.
    pub params: ShadowParams,
    /// The spot's map.
    pub map: Option<ShadowMap2d>,
    /// The point's cube.
    pub cube: Option<ShadowCube>,
    /// Bindings 10–14 of the receivers.
    pub resources: Vec<BoundResource>,
}

impl FrameShadow {
    /// The variant's shadow keywords.
    pub fn names(&self) -> Vec<&'static str> {
        let k = self.keywords;
        [
            (k.depth, "SHADOWS_DEPTH"),
            (k.cube, "SHADOWS_CUBE"),
            (k.soft, "SHADOWS_SOFT"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }

    /// The reference shadow factor interval at `p` (an uncertain tap may go either way).
    pub fn factor(&self, p: Vec3) -> (f32, f32) {
        shadow_factor(
            &self.params,
            self.keywords,
            ShadowMaps {
                map: self.map.as_ref(),
                cube: self.cube.as_ref(),
            },
            p,
        )
    }
}

/// The caster draws of every object with the camera binding set to the light's view
/// (`view_proj`; `position` = light position and `1 / range` in w).
fn caster_draws(
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

/// Renders the shadow of every light of `frame` that casts one (`None` for the others), in
/// `frame.lights` order.
///
/// # Errors
/// A GPU failure, or a shadow the reference refuses (a directional light, a strength outside
/// [0, 1]) as [`crate::CheckError::UnknownToReference`].
pub fn render_shadows(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
) -> Result<Vec<Option<FrameShadow>>, GpuError> {
    let refused = refused("standard/ShadowCaster");
    let mut drawer = Drawer::new(lib, frame, false);
    frame
        .lights
        .iter()
        .map(|light| {
            let Some(spec) = light.shadow else {
                return Ok(None);
            };
            let params = ShadowParams::for_light(&light.light, spec.strength, spec.bias)
                .map_err(&refused)?;
            let position = params.light_position.extend(params.inv_range);
            let cube = matches!(
                light.light.shape,
                wgsl_variants::reference::light::LightShape::Point { .. }
            );
            let keywords = ShadowKeywords {
                depth: !cube,
                cube,
                screen: false,
                soft: spec.soft,
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
                        &mut drawer,
                        "SHADOWS_CUBE",
                        cube_face_view_proj(params.light_position, face, range),
                        position,
                    )?;
                    *bytes = render_pass(ctx, &pass)?.targets.remove(0);
                }
                debug_assert_eq!(CUBE_FORMAT, TargetFormat::Rgba16Float.wgpu_format());
                let texels = faces.iter().flat_map(|f| red_f16(f)).collect();
                let cube = ShadowCube::new(size, texels).map_err(&refused)?;
                Ok(Some(FrameShadow {
                    keywords,
                    resources: shadow_bindings(&params, None, Some((&faces, size))),
                    params,
                    map: None,
                    cube: Some(cube),
                }))
            } else {
                let size = SHADOW_MAP_SIZE;
                let mut pass = DrawPass::new("frame: shadow map", size, size, Vec::new());
                pass.depth = true;
                pass.depth_format = DEPTH;
                pass.draws = caster_draws(
                    &mut drawer,
                    "SHADOWS_DEPTH",
                    params.world_to_shadow,
                    position,
                )?;
                let depth = render_pass(ctx, &pass)?.depth.unwrap_or_default();
                let codes: Vec<u16> = depth.iter().map(|d| (d * 65535.0).round() as u16).collect();
                let map = ShadowMap2d::from_depth16(size, size, &codes).map_err(&refused)?;
                Ok(Some(FrameShadow {
                    keywords,
                    resources: shadow_bindings(&params, Some((&codes, size)), None),
                    params,
                    map: Some(map),
                    cube: None,
                }))
            }
        })
        .collect()
}
