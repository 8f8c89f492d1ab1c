//! The URP frame's main-light shadow: every object drawn by `universal_lit/ShadowCaster`
//! (URP's caster bias and near-plane pancaking; the cutout object's alpha test) into one
//! `Depth16Unorm` map of an orthographic box around the scene (`_MAIN_LIGHT_SHADOWS`), or
//! into each cascade's tile of an atlas (`_MAIN_LIGHT_SHADOWS_CASCADE`: the cascades fitted to
//! slices of the camera's view, URP's split spheres), read back; both paths' receivers bind
//! what was rendered and the reference reads the same texels ([`main_light_map_factor`],
//! [`Cascades::factor`]). The additional lights' shadows: each casting point or spot light's
//! slices (six 90° views of a point light, one perspective view of a spot) drawn by the same
//! caster with `_CASTING_PUNCTUAL_LIGHT_SHADOW` into an atlas ([`AdditionalAtlas`]), read
//! back likewise. Whether the caster writes the right texels is the
//! `universal_lit/ShadowCaster` check's business (`check::urp_caster`).

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::super::scene::{push_mat4, push_vec4};
use super::super::screen_masks::{CascadeAtlas, map_resources};
use super::super::shadows::{DEPTH, refused};
use super::super::urp_additional_shadows::{AdditionalAtlas, Casting};
use super::UrpFrame;
use super::text;
use crate::{BoundResource, Draw, DrawPass, GpuContext, GpuError, Resource, render_pass};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cascades::{CascadeKeywords, Cascades, MAX_CASCADES};
use wgsl_variants_shaders::reference::light::Light;
use wgsl_variants_shaders::reference::shadow::{ShadowMap2d, ShadowParams};
use wgsl_variants_shaders::reference::tolerance::unorm_store_error;
use wgsl_variants_shaders::reference::urp::forward::{MainLightShadow, UrpShadowFade};
use wgsl_variants_shaders::reference::urp::shadow::main_light_map_factor;

/// Edge length of the main light's map in texels (of each cascade's tile with cascades).
pub const MAIN_SHADOW_MAP_SIZE: u32 = 512;

/// Edge length of one slice of the additional lights' atlas in texels.
pub const ADDITIONAL_SLICE_SIZE: u32 = 256;

/// How the URP frame's additional lights cast their shadows.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpAdditionalShadowSpec {
    /// Per additional light of the frame, in order: its strength and soft flag, or `None`
    /// for a light that casts no shadow.
    pub casting: Vec<Casting>,
    /// URP's `_ShadowBias` at the caster: (depth, normal), world units (negative: away from
    /// the light, into the surface).
    pub bias: Vec2,
    /// How the realtime shadows fade with the distance from the camera (URP's
    /// `_AdditionalShadowFadeParams`).
    pub fade: UrpShadowFade,
}

/// The frame's rendered shadows: the main light's and the additional lights' atlas (each
/// `None` where the frame has none).
#[derive(Clone, Debug, Default)]
pub struct UrpFrameShadows {
    /// The main light's map or cascades.
    pub main: Option<UrpFrameShadow>,
    /// The additional lights' atlas, with its reference (the lights in the frame's order).
    pub additional: Option<AdditionalAtlas>,
}

impl UrpFrameShadows {
    /// `_SHADOWS_SOFT`: one keyword for the main light's map or cascades and for each
    /// additional light whose own flag says soft — on when the main light's shadow is soft.
    pub fn soft(&self) -> bool {
        self.main.as_ref().is_some_and(|m| m.soft)
    }

    /// The additional lights' shadow keywords in the receivers (`UniversalForward`,
    /// `PunctualLit`): `_ADDITIONAL_LIGHT_SHADOWS` and [`UrpFrameShadows::soft`]'s
    /// `_SHADOWS_SOFT`; none without the atlas.
    pub fn additional_keywords(&self) -> Vec<&'static str> {
        let mut out = Vec::new();
        if self.additional.is_some() {
            out.push("_ADDITIONAL_LIGHT_SHADOWS");
            if self.soft() {
                out.push("_SHADOWS_SOFT");
            }
        }
        out
    }

    /// The forward receivers' shadow keywords: the main light's
    /// ([`UrpFrameShadow::receiver_keywords`]) and [`UrpFrameShadows::additional_keywords`],
    /// each once.
    pub fn forward_keywords(&self) -> Vec<&'static str> {
        let mut out = self
            .main
            .as_ref()
            .map(UrpFrameShadow::receiver_keywords)
            .unwrap_or_default();
        for k in self.additional_keywords() {
            if !out.contains(&k) {
                out.push(k);
            }
        }
        out
    }

    /// Additional light `k`'s shadow at `p` (lit from the unit direction `to_light`) seen from
    /// `camera`: the two ends of its interval, 1 without the atlas.
    pub fn additional_at(&self, k: usize, p: Vec3, to_light: Vec3, camera: Vec3) -> [f32; 2] {
        self.additional.as_ref().map_or([1.0; 2], |a| {
            let (lo, hi) = a.shadows.attenuation(k, self.soft(), p, to_light, camera);
            [lo, hi]
        })
    }
}

/// How the URP frame's main light casts its shadow.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpShadowSpec {
    /// Strength in [0, 1]: the shadowed light keeps `1 − strength`.
    pub strength: f32,
    /// `_SHADOWS_SOFT`: the 3 × 3 tent instead of one tap.
    pub soft: bool,
    /// URP's `_ShadowBias` at the caster: (depth, normal), world units (negative: away from the
    /// light, into the surface).
    pub bias: Vec2,
    /// The centre of the map's orthographic box (one map).
    pub center: Vec3,
    /// Its half extent (the box reaches `radius` across the light and `2 · radius` along it on
    /// either side of `center`).
    pub radius: f32,
    /// `_MAIN_LIGHT_SHADOWS_CASCADE`: the view depths that cut the camera's view into the
    /// cascades (the near plane, the splits, the shadow distance: 2, 3 or 5 depths,
    /// [`Cascades::fit`]), instead of the one map over `center` and `radius`.
    pub cascade_splits: Option<Vec<f32>>,
    /// `_MAIN_LIGHT_SHADOWS_SCREEN`: URP's `ScreenSpaceShadows` pass turns the map or the
    /// cascades into a shadow per pixel over the camera's depth — the G-buffer pass's in the
    /// deferred path, the `DepthOnly` prepass's in the forward path — and the receivers
    /// (`DirectionalLit`, `UniversalForward`) read that texel.
    pub screen: bool,
    /// How the realtime shadow fades with the distance from the camera (URP's
    /// `_MainLightShadowParams.zw`).
    pub fade: UrpShadowFade,
}

/// Where the main light's shadow was rendered.
#[derive(Clone, Debug)]
pub enum UrpShadowMaps {
    /// `_MAIN_LIGHT_SHADOWS`: one [`MAIN_SHADOW_MAP_SIZE`]² map.
    Map {
        /// The map, read back.
        map: ShadowMap2d,
        /// Its `Depth16Unorm` codes, as rendered (for the receivers' bindings).
        codes: Vec<u16>,
    },
    /// `_MAIN_LIGHT_SHADOWS_CASCADE`: the cascades and their atlas of
    /// [`MAIN_SHADOW_MAP_SIZE`]² tiles.
    Cascades(CascadeAtlas),
}

/// The main light's rendered shadow: what the receivers bind and the reference reads.
#[derive(Clone, Debug)]
pub struct UrpFrameShadow {
    /// The map's parameters (the `Shadow` uniform; no receiver bias: URP biases the caster);
    /// with cascades, the first cascade's.
    pub params: ShadowParams,
    /// `_SHADOWS_SOFT`.
    pub soft: bool,
    /// The map or the cascades.
    pub maps: UrpShadowMaps,
    /// The receivers read the screen-space pass's texel ([`UrpShadowSpec::screen`]).
    pub screen: bool,
    /// The fade with the distance from the camera.
    pub fade: UrpShadowFade,
    /// The camera the fade measures from.
    pub camera: Vec3,
}

impl UrpFrameShadow {
    /// The keywords of the map or the cascades: `_MAIN_LIGHT_SHADOWS` or
    /// `_MAIN_LIGHT_SHADOWS_CASCADE`, and `_SHADOWS_SOFT` as specified (the receivers' that read
    /// them, and the screen-space pass's).
    pub fn map_keywords(&self) -> Vec<&'static str> {
        let mut out = vec![match self.maps {
            UrpShadowMaps::Cascades(_) => "_MAIN_LIGHT_SHADOWS_CASCADE",
            UrpShadowMaps::Map { .. } => "_MAIN_LIGHT_SHADOWS",
        }];
        if self.soft {
            out.push("_SHADOWS_SOFT");
        }
        out
    }

    /// The main light's keywords in both paths' receivers (`UniversalForward`,
    /// `DirectionalLit`): [`UrpFrameShadow::map_keywords`], or with [`UrpFrameShadow::screen`]
    /// `_MAIN_LIGHT_SHADOWS_SCREEN` alone (the screen-space pass, which takes the map's
    /// keywords, filters).
    pub fn receiver_keywords(&self) -> Vec<&'static str> {
        if self.screen {
            vec!["_MAIN_LIGHT_SHADOWS_SCREEN"]
        } else {
            self.map_keywords()
        }
    }

    /// A receiver's bindings (`universal/main_light_shadow`): the `Shadow` uniform and the
    /// map (10, 11) or the `CascadedShadow` uniform and the atlas (14, 15), the comparison
    /// sampler (12) and URP's `_MainLightShadowParams` (13: the strength and the fade). The
    /// screen-space pass binds the same (it declares no 13); a `_SCREEN` receiver adds the
    /// pass's target at 16.
    pub fn resources(&self) -> Vec<BoundResource> {
        let tile = MAIN_SHADOW_MAP_SIZE;
        let mut out = match &self.maps {
            UrpShadowMaps::Map { codes, .. } => map_resources(
                bytemuck::cast_slice(&self.params.uniform()),
                codes,
                (tile, tile),
                10,
            ),
            UrpShadowMaps::Cascades(atlas) => atlas.urp_resources(),
        };
        out.push(BoundResource::new(
            0,
            13,
            Resource::Uniform(self.fade.uniform(self.params.strength)),
        ));
        out
    }

    /// With cascades, the one URP's split spheres pick at `p` (0 to 3; [`MAX_CASCADES`] for
    /// none, one more for several: spheres URP's `ComputeCascadeIndex` cannot tell apart);
    /// `None` with one map.
    pub fn cascade_at(&self, p: Vec3) -> Option<usize> {
        let UrpShadowMaps::Cascades(atlas) = &self.maps else {
            return None;
        };
        let w = atlas.cascades.candidates(CascadeKeywords::urp(false), p)[0]
            .unwrap_or([0.0; MAX_CASCADES]);
        Some(Cascades::picked(w))
    }

    /// The main light's shadow a receiver at world position `p` reads, in a pixel whose depth
    /// (the G-buffer pass's or the depth prepass's) rebuilds `rebuilt`: [`UrpFrameShadow::at`]
    /// `p`, or with [`UrpFrameShadow::screen`] the screen-space pass's texel — the realtime
    /// shadow at `rebuilt` through the pass's 8-bit store (widened by one store's error) —
    /// faded at `p` (URP fades at the receiver's own position).
    pub fn received(&self, rebuilt: Vec3, p: Vec3) -> [MainLightShadow; 2] {
        if self.screen {
            self.faded(self.realtime(rebuilt), unorm_store_error(8), p)
        } else {
            self.at(p)
        }
    }

    /// The main light's shadow at world position `p`, faded with the distance: the interval
    /// of its attenuation (its two ends differ where a tap lies within a hair of flipping).
    pub fn at(&self, p: Vec3) -> [MainLightShadow; 2] {
        self.faded(self.realtime(p), 0.0, p)
    }

    /// `realtime`'s interval widened by `widen` on both sides (within [0, 1]), then faded with
    /// the distance of `p` from the camera.
    fn faded(&self, (lo, hi): (f32, f32), widen: f32, p: Vec3) -> [MainLightShadow; 2] {
        let (lo, hi) = ((lo - widen).max(0.0), (hi + widen).min(1.0));
        let fade = self.fade.at(p, self.camera);
        [lo, hi].map(|attenuation| {
            MainLightShadow {
                attenuation,
                strength: self.params.strength,
            }
            .faded(fade)
        })
    }

    /// The realtime shadow at `p` before the fade, as an interval.
    fn realtime(&self, p: Vec3) -> (f32, f32) {
        match &self.maps {
            UrpShadowMaps::Map { map, .. } => {
                main_light_map_factor(&self.params, map, self.soft, p)
            }
            UrpShadowMaps::Cascades(atlas) => {
                atlas
                    .cascades
                    .factor(CascadeKeywords::urp(self.soft), &atlas.map, p)
            }
        }
    }
}

/// Renders the shadows of `frame`: the main light's map or cascades
/// ([`UrpFrame::main_shadow`]) and the additional lights' atlas
/// ([`UrpFrame::additional_shadows`]).
///
/// # Errors
/// A variant lookup or GPU error; [`GpuError::Check`] when the shadows' parameters are
/// refused.
pub fn render_urp_shadows(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<UrpFrameShadows, GpuError> {
    Ok(UrpFrameShadows {
        main: render_main_shadow(ctx, lib, frame)?,
        additional: render_additional_shadows(ctx, lib, frame)?,
    })
}

/// The additional lights' atlas of `frame` (`None` without
/// [`UrpFrame::additional_shadows`]): each casting light's slices drawn by
/// `universal_lit/ShadowCaster` with `_CASTING_PUNCTUAL_LIGHT_SHADOW`.
fn render_additional_shadows(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<Option<AdditionalAtlas>, GpuError> {
    let Some(spec) = &frame.additional_shadows else {
        return Ok(None);
    };
    let lights: Vec<(Light, Casting)> = frame
        .lights
        .iter()
        .zip(spec.casting.iter().chain(std::iter::repeat(&None)))
        .map(|(l, c)| (l.light, *c))
        .collect();
    let atlas = AdditionalAtlas::render_with(
        "universal_lit/ShadowCaster",
        &lights,
        spec.fade,
        ADDITIONAL_SLICE_SIZE,
        |view_proj, position| {
            let view = CasterView {
                view_proj,
                light_direction: Vec3::ZERO,
                light_position: Some(position.truncate()),
                bias: spec.bias,
            };
            render_casters(ctx, lib, frame, &view, ADDITIONAL_SLICE_SIZE)
        },
    )?;
    Ok(Some(atlas))
}

/// The main light's map or cascades of `frame` (`None` without [`UrpFrame::main_shadow`]).
fn render_main_shadow(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<Option<UrpFrameShadow>, GpuError> {
    let Some(spec) = &frame.main_shadow else {
        return Ok(None);
    };
    let view = |view_proj| CasterView {
        view_proj,
        light_direction: frame.lighting.main_light_dir,
        light_position: None,
        bias: spec.bias,
    };
    let refused = refused("universal_lit/ShadowCaster");
    let light = Light::directional(
        -frame.lighting.main_light_dir,
        frame.lighting.main_light_color,
    );
    let tile = MAIN_SHADOW_MAP_SIZE;
    let (params, maps) = match &spec.cascade_splits {
        None => {
            let params =
                ShadowParams::for_directional(&light, spec.strength, 0.0, spec.center, spec.radius)
                    .map_err(&refused)?;
            let codes = render_casters(ctx, lib, frame, &view(params.world_to_shadow), tile)?;
            let map = ShadowMap2d::from_depth16(tile, tile, &codes).map_err(&refused)?;
            (params, UrpShadowMaps::Map { map, codes })
        }
        Some(splits) => {
            let camera = frame.geometry.cascade_camera();
            let cascades =
                Cascades::fit(&light, spec.strength, 0.0, &camera, splits).map_err(&refused)?;
            let atlas = CascadeAtlas::render(cascades, tile, "universal_lit/ShadowCaster", |c| {
                render_casters(ctx, lib, frame, &view(c.view_proj), tile)
            })?;
            (
                atlas.cascades.cascades[0].params,
                UrpShadowMaps::Cascades(atlas),
            )
        }
    };
    Ok(Some(UrpFrameShadow {
        params,
        soft: spec.soft,
        maps,
        screen: spec.screen,
        fade: spec.fade,
        camera: frame.lighting.camera_position,
    }))
}

/// One light's view for the casters: its view-projection (of the map, a cascade or a slice),
/// the unit direction to a directional light or a point or spot light's position
/// (`_CASTING_PUNCTUAL_LIGHT_SHADOW`), and URP's `_ShadowBias`.
struct CasterView {
    view_proj: Mat4,
    light_direction: Vec3,
    light_position: Option<Vec3>,
    bias: Vec2,
}

/// Every object of `frame` drawn by `universal_lit/ShadowCaster` through `view` into a
/// `size`² depth map: its `Depth16Unorm` codes, row by row.
fn render_casters(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
    view: &CasterView,
    size: u32,
) -> Result<Vec<u16>, GpuError> {
    let g = &frame.geometry;
    let mut pass = DrawPass::new("URP frame: shadow caster", size, size, Vec::new());
    pass.depth = true;
    pass.depth_format = DEPTH;
    let mut camera = Vec::new();
    push_mat4(&mut camera, view.view_proj);
    push_vec4(&mut camera, Vec4::ZERO);
    let mut caster = Vec::new();
    push_vec4(&mut caster, view.light_direction.extend(0.0));
    push_vec4(
        &mut caster,
        view.light_position.unwrap_or(Vec3::ZERO).extend(1.0),
    );
    push_vec4(&mut caster, view.bias.extend(0.0).extend(0.0));
    for (o, object) in g.objects.iter().enumerate() {
        let mut names: Vec<&str> = frame.objects[o]
            .keywords
            .iter()
            .copied()
            .filter(|k| *k == "_ALPHATEST_ON")
            .collect();
        if view.light_position.is_some() {
            names.push("_CASTING_PUNCTUAL_LIGHT_SHADOW");
        }
        let (label, wgsl) = text(lib, "universal_lit", "ShadowCaster", &names)?;
        let mut resources: Vec<BoundResource> = frame
            .object_resources(o)?
            .into_iter()
            .filter(|r| !matches!((r.group, r.binding), (0, 0) | (0, 4)))
            .collect();
        resources.push(BoundResource::new(0, 0, Resource::Uniform(camera.clone())));
        resources.push(BoundResource::new(0, 4, Resource::Uniform(caster.clone())));
        pass.draws.push(
            Draw::fullscreen(
                &format!("{} {label}", object.name),
                &wgsl,
                "vs_main",
                "fs_main",
            )
            .depth_only()
            .with_mesh(object.mesh())
            .with_resources(resources)
            .with_depth(crate::DepthTest::OPAQUE),
        );
    }
    let depth = render_pass(ctx, &pass)?.depth.unwrap_or_default();
    Ok(depth.iter().map(|d| (d * 65535.0).round() as u16).collect())
}
