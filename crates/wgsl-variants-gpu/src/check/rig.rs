//! The per-pixel lights of the GPU check: one light of each type over the test scene
//! ([`LightRig`]), their cookies, shadow maps and screen-space masks, and the perspective
//! camera and depth buffer the full-screen deferred passes rebuild positions from.
//!
//! Cookie textures use nearest sampling: the rig moves the cookies until every lookup the check
//! makes (at the deferred pass's rebuilt positions and at the forward pass's pixel positions)
//! is at least [`MIN_COOKIE_MARGIN`] away from a texel or cube-face edge, so a lookup cannot
//! flip to a neighbouring texel through a few ULPs of position difference.

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::camera::LightingCamera;
use super::scene::{MapTexture, TestScene, cube_resource, push_vec4};
use super::screen_masks::ScreenShadows;
use super::shadows::ShadowRig;
use crate::{BoundResource, GpuContext, GpuError, Resource};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::cube::{CubeFaces, face_margin};
use wgsl_variants_shaders::reference::light::{
    Cookie2d, Light, LightParams, LightShape, LightType, look_at_rh, perspective_rh,
    world_from_depth,
};
use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
use wgsl_variants_shaders::reference::shadow::{ShadowKeywords, mix_realtime_and_baked};
use wgsl_variants_shaders::reference::shadow_fade::{FadeDistance, ShadowFade};

/// The smallest distance, in texels (2D cookie) or [`face_margin`] units (cube cookie), between
/// a cookie lookup of the check and an edge.
pub const MIN_COOKIE_MARGIN: f32 = 0.02;

/// Edge length of the 2D cookie in texels.
const COOKIE_SIZE: u32 = 4;

/// One light of each type over the test scene, their cookies, and the perspective camera and
/// depth buffer of the deferred lighting check.
///
/// Cookies are sampled nearest, so each lookup must stay clear of texel and cube-face edges:
/// - at the forward pass's pixel positions (a 0.25-unit grid on the plane `z = 0`), by
///   construction: the cookie light travels along −Z with 1-unit tiles of 4 texels whose
///   centres are the pixel centres, and the point light sits at `(0.5625, −0.5, 1)` with an
///   axis-aligned cookie, so `|dx|` (odd multiples of 1/16), `|dy|` (odd multiples of 1/8) and
///   `|dz| = 1` never come closer than 1/16;
/// - at the deferred pass's rebuilt positions, by the depth buffer: each pixel's depth puts its
///   point on the pixel's camera ray at the first height `z` in `0, ±0.03, ±0.06, …` (at most
///   ±0.48) where both lookups are [`MIN_COOKIE_MARGIN`] clear. So depth varies from pixel to
///   pixel and the reconstruction is checked on a non-planar surface.
#[derive(Clone, Debug)]
pub struct LightRig {
    /// The directional light (`DIRECTIONAL`), slanted.
    pub directional: LightParams,
    /// The directional light with the cookie (`DIRECTIONAL_COOKIE`), travelling along −Z.
    pub directional_cookie: LightParams,
    /// The point light (`POINT`, `POINT_COOKIE`).
    pub point: LightParams,
    /// The point light as a renderer describes it (for its volume).
    pub point_light: Light,
    /// The spot light as a renderer describes it (for its volume).
    pub spot_light: Light,
    /// The directional light as a renderer describes it (for its `SHADOWS_SCREEN` map).
    pub directional_light: Light,
    /// The directional light with the cookie, as a renderer describes it.
    pub directional_cookie_light: Light,
    /// The spot light (`SPOT`).
    pub spot: LightParams,
    /// The 2D cookie (`Rgba8Unorm`, alpha read).
    pub cookie: MapTexture,
    /// The cube cookie (one colour per face; alpha read).
    pub cube: CubeFaces,
    /// World-to-clip of the deferred check's perspective camera (at the scene's camera).
    pub view_proj: Mat4,
    /// The depth buffer of the deferred check: one `f32` per pixel, row by row.
    pub depth: Vec<f32>,
    /// The spot's and point's shadow maps, rendered by `standard/ShadowCaster`
    /// ([`ShadowRig::render`]); `None` until a GPU has rendered them (then the shadowed
    /// variants have no shadow bindings).
    pub shadows: Option<ShadowRig>,
    /// The directional lights' maps and screen-space masks (`SHADOWS_SCREEN`,
    /// [`ScreenShadows::render`]); `None` until a GPU has rendered them.
    pub screen_shadows: Option<ScreenShadows>,
    /// The shadow distance fade of the spot and point lights: by view depth (Unity's Close
    /// Fit), see [`LightRig::fade`].
    pub depth_fade: ShadowFade,
    /// The shadow distance fade of the directional lights (and ForwardBase's main light): by
    /// the distance to the camera (Unity's Stable Fit), see [`LightRig::fade`].
    pub sphere_fade: ShadowFade,
}

/// Where the rig's fades start and end, as fractions of the range of fade distances over the
/// positions the checks light: the nearest keeps its whole realtime shadow, the farthest tenth
/// loses it, every other position fades part of it — so every shadowed light has shadowed
/// pixels inside the ramp (with a later start, one directional light's shadow fell where
/// the fade is 0 and the Shadowmask mode's `saturate(realtime + fade)` went unchecked there).
const FADE_RAMP: (f32, f32) = (0.0, 0.9);

impl LightRig {
    /// The rig over `scene`.
    ///
    /// # Panics
    /// If some pixel has no depth whose lookups are [`MIN_COOKIE_MARGIN`] clear of an edge
    /// (never for the default scene; a unit test checks it).
    pub fn new(scene: &TestScene) -> LightRig {
        let (w, h) = (scene.width, scene.height);
        let eye = scene.scene.camera_position;
        let target = scene.centre.extend(0.0);
        let view_proj =
            perspective_rh(0.6, w as f32 / h as f32, 0.5, 20.0) * look_at_rh(eye, target, Vec3::Y);
        let alpha = [
            255u8, 40, 170, 90, 0, 220, 130, 60, 200, 10, 255, 150, 100, 180, 30, 240,
        ];
        let cookie = MapTexture {
            width: COOKIE_SIZE,
            height: COOKIE_SIZE,
            texels: alpha.iter().map(|&a| [255, 255, 255, a]).collect(),
        };
        let face = |a: u8| Vec4::new(1.0, 1.0, 1.0, unorm_to_f32(u32::from(a), 8));
        let cube = CubeFaces([face(255), face(60), face(200), face(0), face(140), face(30)]);
        let params = |light: Light| {
            light
                .params()
                .expect("the test lights have valid parameters")
        };
        let point_light = Light::point(Vec3::new(0.5625, -0.5, 1.0), 2.6, Vec3::new(2.2, 1.8, 1.4));
        let spot_light = Light::spot(
            Vec3::new(-0.4, 0.6, 2.2),
            Vec3::new(0.8, -1.1, -2.2),
            70.0,
            5.0,
            Vec3::new(3.0, 2.5, 2.0),
        );
        let directional_light =
            Light::directional(Vec3::new(0.25, -0.35, -0.9), Vec3::new(0.9, 0.8, 0.7));
        let directional_cookie_light = Light {
            shape: LightShape::Directional {
                direction: Vec3::NEG_Z,
                cookie_size: 1.0,
                cookie_origin: Vec3::ZERO,
            },
            color: Vec3::new(0.8, 0.85, 0.9),
        };
        let mut rig = LightRig {
            directional: params(directional_light),
            directional_cookie: params(directional_cookie_light),
            directional_light,
            directional_cookie_light,
            point: params(point_light),
            spot: params(spot_light),
            point_light,
            spot_light,
            cookie,
            cube,
            view_proj,
            depth: Vec::new(),
            shadows: None,
            screen_shadows: None,
            depth_fade: ShadowFade::NONE,
            sphere_fade: ShadowFade::NONE,
        };
        rig.depth = scene
            .pixels()
            .map(|(x, y)| rig.clear_depth(scene, x, y))
            .collect();
        let positions = rig.lookup_positions(scene);
        rig.depth_fade = fade_over(scene, &positions, FadeDistance::ViewDepth);
        rig.sphere_fade = fade_over(scene, &positions, FadeDistance::Sphere(eye));
        rig
    }

    /// The shadow distance fade light `t`'s receivers bind (group 0, binding 18). Unity has
    /// one per camera; the rig gives the two kinds to different lights so that both are
    /// checked.
    pub fn fade(&self, t: LightType) -> &ShadowFade {
        if t.is_directional() {
            &self.sphere_fade
        } else {
            &self.depth_fade
        }
    }

    /// The depth at pixel `(x, y)` whose rebuilt point lies on the camera ray at the first
    /// height `z = 0, ±0.03, …` where the cookie lookups are clear of edges.
    fn clear_depth(&self, scene: &TestScene, x: u32, y: u32) -> f32 {
        let (w, h) = (scene.width, scene.height);
        let inv = self.view_proj.inverse();
        let near = world_from_depth(inv, x, y, w, h, 0.0);
        let far = world_from_depth(inv, x, y, w, h, 1.0);
        for k in 0..33 {
            let step = ((k + 1) / 2) as f32 * 0.03;
            let z = if k % 2 == 1 { step } else { -step };
            let p = near + (far - near) * ((near.z - z) / (near.z - far.z));
            let clip = self.view_proj * p.extend(1.0);
            let depth = clip.z / clip.w;
            let rebuilt = world_from_depth(inv, x, y, w, h, depth);
            if self.cookie_margin(&[rebuilt]) >= MIN_COOKIE_MARGIN {
                return depth;
            }
        }
        panic!("pixel ({x}, {y}): no depth keeps the cookie lookups off texel edges");
    }

    /// The parameters the light keyword `t` uses.
    pub fn params(&self, t: LightType) -> &LightParams {
        match t {
            LightType::Directional => &self.directional,
            LightType::DirectionalCookie => &self.directional_cookie,
            LightType::Point | LightType::PointCookie => &self.point,
            LightType::Spot => &self.spot,
        }
    }

    /// The 2D cookie as the reference samples it.
    pub fn cookie_2d(&self) -> Cookie2d {
        Cookie2d {
            width: self.cookie.width,
            height: self.cookie.height,
            alpha: self
                .cookie
                .texels
                .iter()
                .map(|t| unorm_to_f32(u32::from(t[3]), 8))
                .collect(),
        }
    }

    /// The world position the deferred lighting pass rebuilds at pixel `(x, y)`.
    pub fn deferred_position(&self, scene: &TestScene, x: u32, y: u32) -> Vec3 {
        let d = self.depth[(y * scene.width + x) as usize];
        world_from_depth(self.view_proj.inverse(), x, y, scene.width, scene.height, d)
    }

    /// Every position a cookie is looked up at: the deferred check's and the forward pass's.
    pub fn lookup_positions(&self, scene: &TestScene) -> Vec<Vec3> {
        scene
            .pixels()
            .flat_map(|(x, y)| {
                [
                    self.deferred_position(scene, x, y),
                    scene.world_position(x, y),
                ]
            })
            .collect()
    }

    /// The smallest margin of the cookie lookups at `positions`: texels of the 2D cookie,
    /// [`face_margin`] of the cube cookie.
    pub fn cookie_margin(&self, positions: &[Vec3]) -> f32 {
        let cookie = self.cookie_2d();
        positions
            .iter()
            .map(|&p| {
                let q = self.directional_cookie.light_coords(p);
                let uv = cookie.edge_margin(Vec2::new(q.x, q.y));
                uv.min(face_margin(self.point.light_coords(p).truncate()))
            })
            .fold(f32::INFINITY, f32::min)
    }

    /// The light's bindings (group 0, 6–9 of `wgsl/lighting/light_bindings.wgsl`) for keyword `t`.
    pub fn resources(&self, t: LightType) -> Vec<BoundResource> {
        self.resources_for(self.params(t))
    }

    /// Renders the rig's shadow maps with `standard/ShadowCaster` (see [`ShadowRig`]).
    ///
    /// # Errors
    /// As [`ShadowRig::render`].
    pub fn render_shadows(&mut self, ctx: &GpuContext, lib: &Library) -> Result<(), GpuError> {
        self.shadows = Some(ShadowRig::render(
            ctx,
            lib,
            &self.spot_light,
            &self.point_light,
        )?);
        Ok(())
    }

    /// Renders the directional lights' maps and the `screen_space_shadows/Collect` masks of
    /// the rig's camera view (see [`ScreenShadows`]).
    ///
    /// # Errors
    /// As [`ScreenShadows::render`].
    pub fn render_screen_shadows(
        &mut self,
        ctx: &GpuContext,
        lib: &Library,
        scene: &TestScene,
    ) -> Result<(), GpuError> {
        let shadows = ScreenShadows::render_lights(
            ctx,
            lib,
            scene,
            self.directional_lights(),
            &self.camera(scene),
        )?;
        self.screen_shadows = Some(shadows);
        Ok(())
    }

    /// The two directional lights as a renderer describes them, with their keywords: the
    /// lights that get `SHADOWS_SCREEN` maps and masks.
    pub(crate) fn directional_lights(&self) -> [(&Light, LightType); 2] {
        [
            (&self.directional_light, LightType::Directional),
            (&self.directional_cookie_light, LightType::DirectionalCookie),
        ]
    }

    /// The reference shadow factor of the lighting pass at pixel `i` (position `p`): the
    /// rendered mask's value with `SHADOWS_SCREEN` (exact: the mask is data here, checked on
    /// its own by the `Collect` check), else [`LightRig::shadow_factor`].
    pub fn lighting_shadow_factor(
        &self,
        t: LightType,
        keywords: ShadowKeywords,
        p: Vec3,
        i: usize,
    ) -> (f32, f32) {
        if keywords.screen {
            let f = self.screen_factor(t, i);
            (f, f)
        } else {
            self.shadow_factor(t, keywords, p)
        }
    }

    /// The reference light factor interval of light `t` at pixel `i` (position `p`): the
    /// realtime shadow ([`LightRig::lighting_shadow_factor`]) faded at `p` and mixed with the
    /// baked occlusion `baked` (1 without one), as Unity's `UnityMixRealtimeAndBakedShadows`
    /// (monotonic in the realtime factor, so the ends map to the ends).
    pub fn received_factor(
        &self,
        t: LightType,
        keywords: ShadowKeywords,
        (p, i): (Vec3, usize),
        baked: f32,
    ) -> (f32, f32) {
        let (lo, hi) = self.lighting_shadow_factor(t, keywords, p, i);
        let fade = self.fade(t).fade(p);
        let mix = |f| mix_realtime_and_baked(keywords, f, baked, fade);
        (mix(lo), mix(hi))
    }

    /// ForwardBase's main light factor at pixel `i` (position `p`): with `SHADOWS_SCREEN` the
    /// `Directional` light's mask, faded at `p` (no baked occlusion in the forward passes);
    /// else 1.
    pub fn main_light_factor(&self, keywords: ShadowKeywords, p: Vec3, i: usize) -> f32 {
        if keywords.screen {
            self.received_factor(LightType::Directional, keywords, (p, i), 1.0)
                .0
        } else {
            1.0
        }
    }

    /// The factor the hard screen-space mask of directional light `t` holds at pixel `i` (1
    /// for other lights, or before [`LightRig::render_screen_shadows`]). ForwardBase's main
    /// light reads the `Directional` one.
    pub fn screen_factor(&self, t: LightType, i: usize) -> f32 {
        self.screen_shadows
            .as_ref()
            .map_or(1.0, |s| s.lighting_factor(t, i))
    }

    /// ForwardBase's `SHADOWS_SCREEN` bindings: the `Directional` light's hard mask at group
    /// 0, binding 15, and its fade at 18 (none before [`LightRig::render_screen_shadows`]).
    pub fn main_light_shadow(&self) -> Vec<BoundResource> {
        let Some(mask) = self
            .screen_shadows
            .as_ref()
            .and_then(|s| s.lighting_mask(LightType::Directional))
        else {
            return Vec::new();
        };
        vec![
            BoundResource::new(0, 15, mask),
            fade_resource(self.fade(LightType::Directional)),
        ]
    }

    /// The reference shadow factor interval at `p` for light `t` under `keywords` (`(1, 1)`
    /// without shadow keywords or maps).
    pub fn shadow_factor(&self, t: LightType, keywords: ShadowKeywords, p: Vec3) -> (f32, f32) {
        self.shadows
            .as_ref()
            .map_or((1.0, 1.0), |s| s.factor(t, keywords, p))
    }

    /// The light's channel of RT4 (Unity's `unity_OcclusionMaskSelector`, one-hot): each of
    /// the rig's four lights its own, so every channel is read (`POINT_COOKIE` is the point
    /// light's).
    pub fn occlusion_mask(t: LightType) -> Vec4 {
        match t {
            LightType::Directional => Vec4::X,
            LightType::DirectionalCookie => Vec4::Y,
            LightType::Point | LightType::PointCookie => Vec4::Z,
            LightType::Spot => Vec4::W,
        }
    }

    /// What the full-screen deferred passes see of the rig's camera over `scene`.
    pub(crate) fn camera<'a>(&'a self, scene: &TestScene) -> LightingCamera<'a> {
        LightingCamera {
            view_proj: self.view_proj,
            position: scene.scene.camera_position,
            depth: &self.depth,
        }
    }

    /// The bindings of any light `params` with the rig's cookies, and the rig's shadow maps
    /// (the spot's shadow uniform for the rig's spot light, the point's otherwise).
    pub fn resources_for(&self, params: &LightParams) -> Vec<BoundResource> {
        let uniform: Vec<u8> = params
            .uniform()
            .into_iter()
            .flat_map(f32::to_le_bytes)
            .collect();
        let shadows = self.shadows.as_ref().map(|s| {
            s.resources(if *params == self.spot {
                &s.spot
            } else {
                &s.point
            })
        });
        let mut out = vec![
            BoundResource::new(0, 6, Resource::Uniform(uniform)),
            BoundResource::new(0, 7, self.cookie.resource()),
            BoundResource::new(0, 8, cube_resource(&self.cube)),
            BoundResource::new(
                0,
                9,
                Resource::SamplerAddressed {
                    nearest: true,
                    address_mode: wgpu::AddressMode::Repeat,
                },
            ),
        ];
        out.extend(shadows.into_iter().flatten());
        let light_type = [
            LightType::Directional,
            LightType::DirectionalCookie,
            LightType::Point,
            LightType::Spot,
        ]
        .into_iter()
        .find(|&t| self.params(t) == params);
        if let Some(mask) = light_type
            .filter(|t| t.is_directional())
            .zip(self.screen_shadows.as_ref())
            .and_then(|(t, s)| s.lighting_mask(t))
        {
            out.push(BoundResource::new(0, 15, mask));
        }
        if let Some(t) = light_type {
            let mut selector = Vec::new();
            push_vec4(&mut selector, LightRig::occlusion_mask(t));
            out.push(BoundResource::new(0, 16, Resource::Uniform(selector)));
            out.push(fade_resource(self.fade(t)));
        }
        out
    }
}

/// A shadow fade's `ShadowFade` uniform at group 0, binding 18 (`lighting/shadow_fade`).
pub(crate) fn fade_resource(fade: &ShadowFade) -> BoundResource {
    let bytes = fade
        .uniform()
        .into_iter()
        .flat_map(f32::to_le_bytes)
        .collect();
    BoundResource::new(0, 18, Resource::Uniform(bytes))
}

/// A fade of the kind `distance` for the scene's camera (looking at the scene's centre) whose
/// ramp spans [`FADE_RAMP`] of the fade distances of `positions`.
fn fade_over(scene: &TestScene, positions: &[Vec3], distance: FadeDistance) -> ShadowFade {
    let eye = scene.scene.camera_position;
    let forward = scene.centre.extend(0.0) - eye;
    let probe = ShadowFade::new(eye, forward, distance, 0.0, 1.0)
        .expect("the test camera has a forward axis");
    let (lo, hi) = positions
        .iter()
        .map(|&p| probe.fade_distance(p))
        .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    let at = |t: f32| lo + (hi - lo) * t;
    ShadowFade::new(eye, forward, distance, at(FADE_RAMP.0), at(FADE_RAMP.1))
        .expect("the test positions span a range of fade distances")
}

/// `params` with its colour scaled by a shadow factor (the light is linear in its colour).
pub(crate) fn shadowed(params: &LightParams, factor: f32) -> LightParams {
    LightParams {
        color: params.color * factor,
        ..*params
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wgsl_variants_shaders::reference::light::Cookies;

    #[test]
    fn cookie_lookups_are_off_edges_and_lights_reach_part_of_the_scene() {
        let scene = TestScene::default();
        let rig = &LightRig::new(&scene);
        assert!(rig.cookie_margin(&rig.lookup_positions(&scene)) >= MIN_COOKIE_MARGIN);
        let cookie = rig.cookie_2d();
        let cookies = Some(Cookies {
            texture: &cookie,
            cube: &rig.cube,
        });
        for t in LightType::ALL {
            let attenuations: Vec<f32> = scene
                .pixels()
                .map(|(x, y)| {
                    rig.params(t)
                        .sample(t, rig.deferred_position(&scene, x, y), cookies)
                        .1
                })
                .collect();
            let lit = attenuations.iter().filter(|&&a| a > 0.0).count();
            let distinct = {
                let mut v: Vec<u32> = attenuations.iter().map(|a| a.to_bits()).collect();
                v.sort_unstable();
                v.dedup();
                v.len()
            };
            assert!(lit > 20, "{t:?} lights {lit} pixels");
            if t != LightType::Directional {
                assert!(distinct > 3, "{t:?}: {distinct} distinct attenuations");
            }
            if !t.is_directional() {
                assert!(lit < 256, "{t:?}: some pixels must be out of reach");
            }
        }
    }

    #[test]
    fn depth_rebuilds_points_on_the_plane() {
        let scene = TestScene::default();
        let rig = &LightRig::new(&scene);
        for (x, y) in scene.pixels() {
            let p = rig.deferred_position(&scene, x, y);
            assert!(p.z.abs() < 0.5, "({x}, {y}): {p}");
            assert!((0.0..1.0).contains(&rig.depth[(y * scene.width + x) as usize]));
        }
    }
}
