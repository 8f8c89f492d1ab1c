//! `universal_lit/UniversalForward` on the URP scene: every selected variant rendered into an
//! `Rg11b10Ufloat` camera target (URP's default HDR colour format), read back and compared
//! texel by texel with [`wgsl_variants_shaders::reference::urp::forward::shade_forward`] through
//! [`wgsl_variants_shaders::reference::tolerance::urp_texel_within`]; then, per keyword, whether it
//! changed a texel (the loop of [`super::urp`], with the same covering set and partners).
//!
//! The scene is [`UrpScene`]'s quad, maps, lightmap and environment, lit by the [`LightRig`]:
//! its `DIRECTIONAL` light is the main light (with its shadow map from [`super::screen_shadows`]
//! for `_MAIN_LIGHT_SHADOWS`), and three additional lights: the rig's point and spot lights on
//! a layer the mesh has, and a second point light on a layer it does not (lit only without
//! `_LIGHT_LAYERS`). `_ADDITIONAL_LIGHTS_VERTEX` is checked against the reference evaluated at
//! the quad's four corners and interpolated across its two triangles as the rasterizer does
//! (the camera is orthographic, so screen-linear). `_ADDITIONAL_LIGHT_SHADOWS`: the point
//! light (hard, six slices) and the spot light (soft under `_SHADOWS_SOFT`, one slice) cast
//! the occluders' shadows from [`super::urp_additional_shadows`]'s atlas, the second point
//! light casts none; their fade ramps across the pixels they shadow. Where a shadow-map tap at
//! a pixel is within a hair of flipping (or a point light's receiver within a hair of another
//! cube face), the texel is compared within the interval of both outcomes. `_LIGHT_COOKIES`:
//! the main light's cookie fitted around the quad (`urp_cookies::main_light_cookie`)
//! and the atlas of the lighting check (`urp_cookies::additional_light_cookies`): the
//! point and the spot light read their rects, the second point light has none (an all-zero
//! rect: white); where a cookie coordinate is within 1/64 texel of an edge, the texel is
//! compared within the outcomes of the texels it may read. `_SCREEN_SPACE_OCCLUSION`: the SSAO
//! pattern of the lighting checks (`urp_occlusion::ScreenOcclusion`), read at each pixel.

use glam::{Vec3, Vec4};

use super::compare::format_name;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::PassReport;
use super::rig::LightRig;
use super::screen_masks::ScreenShadow;
use super::standard::CLEAR;
use super::urp::{
    DEFAULT_SEED, RENDERING_LAYERS, UrpColorPass, UrpScene, check_color_entry, fade_across,
    main_shadow_resources,
};
use super::urp_additional_shadows::{AdditionalAtlas, rig_casting};
use super::urp_cookies::{
    additional_light_cookies, atlas_resources, main_light_cookie, main_resources,
};
use super::urp_lighting::{
    MATCHING_LAYERS, OTHER_LAYERS, main_light_shadow, shadowed, spot_inner_degrees,
};
use super::urp_occlusion::ScreenOcclusion;
use crate::{
    BoundResource, CheckError, ColorTarget, GpuContext, GpuError, RenderJob, Resource, TargetFormat,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightError};
use wgsl_variants_shaders::reference::urp::additional_shadow::cube_map_face_id;
use wgsl_variants_shaders::reference::urp::cookie::{
    AdditionalLightCookies, MainLightCookie, range,
};
use wgsl_variants_shaders::reference::urp::forward::{
    CookieTints, ForwardInputs, MainLightShadow, MainLightShadows, UrpForwardKeywords,
    UrpForwardLights, UrpShadowFade, shade_forward, vertex_lighting,
};
use wgsl_variants_shaders::reference::urp::gbuffer::UrpTexel;
use wgsl_variants_shaders::reference::urp::lighting::UrpLight;

/// The second point light's position (lit only without `_LIGHT_LAYERS`).
const OTHER_POINT: Vec3 = Vec3::new(-0.6, -0.4, 0.9);

/// The URP scene lit for the forward pass.
#[derive(Clone, Debug)]
pub struct UrpForwardScene {
    /// The URP scene, its main light replaced by the rig's `DIRECTIONAL` light.
    pub urp: UrpScene,
    /// The main light's layer mask and the additional lights.
    pub lights: UrpForwardLights,
    /// The main light's shadow map.
    pub shadow: ScreenShadow,
    /// The main light's shadow fade (ramped across the pixels its map shadows).
    pub fade: UrpShadowFade,
    /// The additional lights' shadows (`_ADDITIONAL_LIGHT_SHADOWS`), their fade ramped across
    /// the pixels they shadow.
    pub additional_shadows: AdditionalAtlas,
    /// The main light's cookie (`_LIGHT_COOKIES`), fitted around the quad.
    pub main_cookie: MainLightCookie,
    /// The additional lights' cookies (`_LIGHT_COOKIES`): the point and the spot light's rects.
    pub cookies: AdditionalLightCookies,
    /// The SSAO texture (`_SCREEN_SPACE_OCCLUSION`).
    occlusion: ScreenOcclusion,
}

impl UrpForwardScene {
    /// The forward scene over `urp` with `rig`'s lights; the rig must have its screen shadows
    /// rendered ([`LightRig::render_screen_shadows`]). Renders the additional lights' shadow
    /// atlas.
    pub fn new(
        ctx: &GpuContext,
        lib: &Library,
        urp: &UrpScene,
        rig: &LightRig,
    ) -> Result<UrpForwardScene, GpuError> {
        let refused = |e: LightError| {
            GpuError::from(CheckError::UnknownToReference {
                variant: "universal_lit/UniversalForward".to_owned(),
                message: e.to_string(),
            })
        };
        let params = |light: Light, inner: f32, mask: u32| {
            UrpLight::new(light, inner, mask).params().map_err(refused)
        };
        let main = params(rig.directional_light, 0.0, MATCHING_LAYERS)?;
        let other = Light::point(OTHER_POINT, 2.0, Vec3::new(1.5, 0.6, 0.9));
        let additional = vec![
            params(rig.point_light, 0.0, MATCHING_LAYERS)?,
            params(rig.spot_light, spot_inner_degrees(rig), MATCHING_LAYERS)?,
            params(other, 0.0, OTHER_LAYERS)?,
        ];
        let lights = UrpForwardLights::new(MATCHING_LAYERS, additional).map_err(refused)?;
        let mut urp = urp.clone();
        urp.lighting.main_light_dir = main.direction;
        urp.lighting.main_light_color = main.color;
        let positions: Vec<Vec3> = urp
            .scene
            .pixels()
            .map(|(x, y)| urp.scene.world_position(x, y))
            .collect();
        let shadow = main_light_shadow(rig, "universal_lit/UniversalForward")?.clone();
        let camera = urp.lighting.camera_position;
        let fade = fade_across(&shadowed(&shadow, &positions), camera);
        let [point, spot] = rig_casting(rig);
        let casting = [point, spot, (other, None)];
        let atlas = AdditionalAtlas::render(
            ctx,
            lib,
            "universal_lit/UniversalForward",
            &casting,
            UrpShadowFade::NONE,
        )?;
        let in_shadow: Vec<Vec3> = (0..2).flat_map(|i| atlas.shadowed(i, &positions)).collect();
        let additional_shadows = atlas.faded(fade_across(&in_shadow, camera));
        let what = "universal_lit/UniversalForward";
        let occlusion = ScreenOcclusion::new(urp.scene.width, urp.scene.height);
        Ok(UrpForwardScene {
            urp,
            lights,
            shadow,
            fade,
            additional_shadows,
            main_cookie: main_light_cookie(&rig.directional_light, &positions, what)?,
            cookies: additional_light_cookies(
                &[Some(&rig.point_light), Some(&rig.spot_light)],
                what,
            )?,
            occlusion,
        })
    }

    /// The per-vertex additional light interpolated at pixel `(x, y)`: the reference at the
    /// quad's corners (world position and normal as the vertex stage computes them), linear
    /// across the triangle (top-left, bottom-left, top-right) or (top-right, bottom-left,
    /// bottom-right) that holds the pixel centre.
    pub fn interpolated_vertex_lighting(&self, k: &UrpForwardKeywords, x: u32, y: u32) -> Vec3 {
        let s = &self.urp.scene;
        let normal = (s.normal_matrix * s.object_normal.extend(0.0))
            .truncate()
            .normalize();
        let corner = |ox: f32, oy: f32| {
            let p = (s.model * Vec4::new(ox, oy, 0.0, 1.0)).truncate();
            vertex_lighting(k, &self.lights, p, normal, RENDERING_LAYERS)
        };
        let (tl, tr, bl, br) = (
            corner(-1.0, 1.0),
            corner(1.0, 1.0),
            corner(-1.0, -1.0),
            corner(1.0, -1.0),
        );
        let u = (x as f32 + 0.5) / s.width as f32;
        let v = (y as f32 + 0.5) / s.height as f32;
        if u + v <= 1.0 {
            tl + (tr - tl) * u + (bl - tl) * v
        } else {
            br + (bl - br) * (1.0 - u) + (tr - br) * (1.0 - v)
        }
    }

    /// The main light's shadow at `p`, seen at `pixel`, for a variant: the interval of its
    /// outcomes ([`ScreenShadow::urp_factor`]: the map, the cascades or the screen-space
    /// texel), `NONE` twice where the variant reads no shadow.
    fn main_light_shadow(
        &self,
        k: &UrpForwardKeywords,
        p: Vec3,
        pixel: (u32, u32),
    ) -> [MainLightShadow; 2] {
        if !k.reads_main_light_shadow() {
            return [MainLightShadow::NONE; 2];
        }
        let (lo, hi) = self
            .shadow
            .urp_factor(k.main_light_shadows, k.shadows_soft, p, pixel);
        let fade = self.fade.at(p, self.urp.lighting.camera_position);
        [lo, hi].map(|attenuation| {
            MainLightShadow {
                attenuation,
                strength: self.shadow.params.strength,
            }
            .faded(fade)
        })
    }

    /// Each additional light's shadow at `p` for a variant: the lower and the upper ends of
    /// their intervals (1 where the variant reads none).
    fn additional_light_shadows(&self, k: &UrpForwardKeywords, p: Vec3) -> [Vec<f32>; 2] {
        if !k.reads_additional_light_shadows() {
            return [Vec::new(), Vec::new()];
        }
        let camera = self.urp.lighting.camera_position;
        let (lo, hi) = self
            .lights
            .additional()
            .iter()
            .enumerate()
            .map(|(i, l)| {
                let (to_light, _) = l.sample(p);
                self.additional_shadows
                    .shadows
                    .attenuation(i, k.shadows_soft, p, to_light, camera)
            })
            .unzip();
        [lo, hi]
    }

    /// The cookie tints the pixel at `p` may take with the additional lights' cookies at the
    /// lower and the upper end of their ranges ([`CookieTints::candidates`]); white alone
    /// without `_LIGHT_COOKIES`.
    fn cookie_tints(&self, k: &UrpForwardKeywords, p: Vec3) -> [Vec<CookieTints>; 2] {
        if !k.light_cookies {
            return [vec![CookieTints::WHITE], vec![CookieTints::WHITE]];
        }
        let lights = self.lights.additional().len();
        [0, 1].map(|end| CookieTints::candidates(&self.main_cookie, &self.cookies, lights, p, end))
    }

    /// The reference texel at pixel `(x, y)`; `None` where the variant discards it. Shading
    /// grows with every shadow attenuation and every additional light's cookie, so their lower
    /// and upper ends bound those; the main light's cookie also lowers the subtractive
    /// lightmap, so each texel its cookie may read is shaded and the least and greatest kept.
    pub fn reference(&self, k: &UrpForwardKeywords, x: u32, y: u32) -> Option<UrpTexel> {
        let urp = &self.urp;
        let pixel = urp.pixel(x, y);
        let tex = urp.texels(x, y);
        let vl = self.interpolated_vertex_lighting(k, x, y);
        let p = pixel.geometry.world_position;
        let additional = self.additional_light_shadows(k, p);
        let shadows = self.main_light_shadow(k, p, (x, y));
        let tints_by_end = self.cookie_tints(k, p);
        let mut outcomes = Vec::with_capacity(2 * tints_by_end[0].len());
        for (end, candidates) in tints_by_end.into_iter().enumerate() {
            for tints in candidates {
                let inputs = ForwardInputs {
                    shadow: shadows[end],
                    vertex_lighting: vl,
                    additional_shadows: additional[end].clone(),
                    tints,
                    occlusion: self.occlusion.factor(x, y),
                };
                outcomes.push(shade_forward(
                    k,
                    &urp.material,
                    &tex,
                    &pixel,
                    &urp.lighting,
                    urp.environment(),
                    &self.lights,
                    &inputs,
                )?);
            }
        }
        match range(&outcomes) {
            (a, b) if a == b => Some(UrpTexel::Ufloat(a)),
            (a, b) => Some(UrpTexel::UfloatBetween(a, b)),
        }
    }

    /// The camera target, cleared to a value the scene never writes.
    fn target() -> ColorTarget {
        ColorTarget::new(TargetFormat::Rg11b10Ufloat).with_clear(CLEAR[3])
    }
}

impl UrpColorPass for UrpForwardScene {
    fn urp(&self) -> &UrpScene {
        &self.urp
    }

    /// The URP scene's resources, the lights (0/4), the main light's shadow (0/10-16), the
    /// additional lights' shadows (0/17-19), the cookies (0/20-25) and the SSAO texture
    /// (0/26-27).
    fn resources(&self) -> Vec<BoundResource> {
        let mut out = self.urp.resources();
        out.push(BoundResource::new(
            0,
            4,
            Resource::Uniform(self.lights.uniform()),
        ));
        out.extend(main_shadow_resources(&self.shadow, &self.fade));
        out.extend(self.additional_shadows.resources());
        out.extend(main_resources(&self.main_cookie));
        out.extend(atlas_resources(&self.cookies));
        out.extend(self.occlusion.resources());
        out
    }

    fn targets(&self, _keywords: &[&str]) -> Vec<(String, ColorTarget)> {
        vec![(
            format!("camera {}", format_name(TargetFormat::Rg11b10Ufloat)),
            Self::target(),
        )]
    }

    fn job(&self, label: &str, wgsl: &str, keywords: &[&str]) -> RenderJob {
        let mut job = self.urp.job(label, wgsl, keywords);
        job.targets = vec![Self::target()];
        job
    }

    fn reference_image(&self, keywords: &[&str]) -> Result<Vec<Option<Vec<UrpTexel>>>, String> {
        let k = UrpForwardKeywords::from_names(keywords).map_err(|e| e.to_string())?;
        Ok(self
            .urp
            .scene
            .pixels()
            .map(|(x, y)| self.reference(&k, x, y).map(|t| vec![t]))
            .collect())
    }

    fn note(&self) -> String {
        let s = &self.urp.scene;
        let shadowed = s
            .pixels()
            .filter(|&(x, y)| {
                let k = UrpForwardKeywords {
                    main_light_shadows: MainLightShadows::Map,
                    ..UrpForwardKeywords::default()
                };
                let p = self.urp.pixel(x, y).geometry.world_position;
                let [lo, _] = self.main_light_shadow(&k, p, (x, y));
                lo.attenuation < 1.0
            })
            .count();
        let positions: Vec<Vec3> = s.pixels().map(|(x, y)| s.world_position(x, y)).collect();
        let lights = self.lights.additional();
        let in_shadow = |i: usize| self.additional_shadows.shadowed(i, &positions);
        let point = in_shadow(0);
        let mut faces = [0usize; 6];
        for &p in &point {
            faces[cube_map_face_id(p - lights[0].position)] += 1;
        }
        // Cookies: the texels each light's cookie reads over the quad, and the pixels whose
        // coordinate is within 1/64 texel of an edge (compared within the outcomes).
        let main_reads: Vec<Vec<Vec3>> = positions
            .iter()
            .map(|&p| self.main_cookie.candidates(p))
            .collect();
        let spot_reads: Vec<Vec<Vec3>> = positions
            .iter()
            .map(|&p| self.cookies.candidates(1, p))
            .collect();
        let distinct = |reads: &[Vec<Vec3>]| {
            let mut seen: Vec<[u32; 3]> = reads
                .iter()
                .filter(|r| r.len() == 1)
                .map(|r| r[0].to_array().map(f32::to_bits))
                .collect();
            seen.sort_unstable();
            seen.dedup();
            seen.len()
        };
        let on_edge = |reads: &[Vec<Vec3>]| reads.iter().filter(|r| r.len() > 1).count();
        format!(
            "{}x{} pixels into an Rg11b10Ufloat camera target; the main light's hard shadow covers {shadowed} of them; URP's {}; {} additional lights (one on a layer the mesh lacks); per-vertex lights interpolated from the quad's corners; additional-light shadows: the point light's covers {} pixels (by cube face +X, -X, +Y, -Y, +Z, -Z: {faces:?}), the spot light's {}; cookies: the main light's reads {} distinct texels over the quad ({} pixels within 1/64 texel of an edge), the spot's {} ({})",
            s.width,
            s.height,
            self.shadow.urp_cascade_census(&positions),
            lights.len(),
            point.len(),
            in_shadow(1).len(),
            distinct(&main_reads),
            on_edge(&main_reads),
            distinct(&spot_reads),
            on_edge(&spot_reads),
        )
    }
}

/// `universal_lit/UniversalForward` in the check's registry.
pub(crate) struct UniversalForward;

/// The entry of `universal_lit/UniversalForward`: its main light's map is the rig's
/// `DIRECTIONAL` light's.
pub(crate) static UNIVERSAL_FORWARD: UniversalForward = UniversalForward;

impl PassCheck for UniversalForward {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("universal_lit", "UniversalForward")]
    }

    fn needs(&self) -> Needs {
        Needs {
            workers: true,
            screen_masks: true,
            ..Needs::NOTHING
        }
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        let urp = UrpScene::new(setup.scene, DEFAULT_SEED);
        let forward = UrpForwardScene::new(setup.ctx, setup.lib, &urp, setup.rig)?;
        check_color_entry(setup, "UniversalForward", &forward)
    }
}
