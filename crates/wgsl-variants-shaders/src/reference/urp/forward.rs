//! What URP Lit's `UniversalForward` fragment writes (docs/urp.md §11): the surface of
//! [`super::gbuffer`] lit in one pass, as URP's `UniversalFragmentPBR` does — global
//! illumination (`GlobalIllumination`, the baked light after `MixRealtimeAndBakedGI`), the
//! main directional light with its realtime shadow, the additional point and spot lights per
//! pixel (`_ADDITIONAL_LIGHTS`) or per vertex (`_ADDITIONAL_LIGHTS_VERTEX`, URP's
//! `VertexLighting`), light layers, light cookies, the screen-space occlusion and the emission.
//! Facts from URP's `Lighting.hlsl`, `RealtimeLights.hlsl`, `GlobalIllumination.hlsl`,
//! `AmbientOcclusion.hlsl` and `LitForwardPass.hlsl`.
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::cube::CubeFaces;
//! use wgsl_variants_shaders::reference::surface::Geometry;
//! use wgsl_variants_shaders::reference::urp::forward::*;
//! use wgsl_variants_shaders::reference::urp::gbuffer::{UrpLighting, UrpMaterial, UrpPixel, UrpTexels};
//! let k = UrpForwardKeywords::from_names(&["_SPECULARHIGHLIGHTS_OFF", "_LIGHT_LAYERS"]).unwrap();
//! let geo = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::new(1.0, 0.0, 0.0, 1.0) };
//! let pixel = UrpPixel { geometry: geo, depth: 0.5, rendering_layers: 1 };
//! // A white light straight above a white dielectric (metallic 0): diffuse = 0.96.
//! let light = UrpLighting { main_light_dir: Vec3::Z, main_light_color: Vec3::ONE, ..UrpLighting::default() };
//! let env = CubeFaces::uniform(Vec4::ZERO);
//! let lights = UrpForwardLights::new(1, vec![]).unwrap();
//! let lit = shade_forward(&k, &UrpMaterial::default(), &UrpTexels::default(), &pixel, &light,
//!     &env, &lights, &ForwardInputs::NONE).unwrap();
//! assert!((lit - Vec3::splat(0.96)).abs().max_element() < 1e-6);
//! // The main light on another layer than the mesh's lights nothing.
//! let other = UrpForwardLights::new(2, vec![]).unwrap();
//! let unlit = shade_forward(&k, &UrpMaterial::default(), &UrpTexels::default(), &pixel, &light,
//!     &env, &other, &ForwardInputs::NONE).unwrap();
//! assert_eq!(unlit, Vec3::ZERO);
//! ```

use glam::Vec3;

use super::ambient_occlusion::AmbientOcclusionFactor;
use super::cookie::{AdditionalLightCookies, MainLightCookie};
use super::gbuffer::{
    UrpKeywords, UrpLighting, UrpMaterial, UrpPixel, UrpTexels, global_illumination, kw,
    urp_baked_gi, urp_brdf, urp_surface, urp_world_normal,
};
use super::lighting::{HALF_MIN_SQRT, UrpBrdfData, UrpLightKind, UrpLightParams};
use crate::reference::cube::CubeFaces;
use crate::reference::light::LightError;
use crate::reference::surface::KeywordsError;

/// The keywords of `universal_lit/UniversalForward`, in declaration order.
pub const URP_FORWARD_KEYWORD_NAMES: [&str; 20] = [
    "_NORMALMAP",
    "_ALPHATEST_ON",
    "_EMISSION",
    "_METALLICSPECGLOSSMAP",
    "_SPECULAR_SETUP",
    "_OCCLUSIONMAP",
    "_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A",
    "_RECEIVE_SHADOWS_OFF",
    "_SPECULARHIGHLIGHTS_OFF",
    "_ENVIRONMENTREFLECTIONS_OFF",
    "_MAIN_LIGHT_SHADOWS",
    "_MAIN_LIGHT_SHADOWS_CASCADE",
    "_MAIN_LIGHT_SHADOWS_SCREEN",
    "_SHADOWS_SOFT",
    "_ADDITIONAL_LIGHTS_VERTEX",
    "_ADDITIONAL_LIGHTS",
    "_ADDITIONAL_LIGHT_SHADOWS",
    "_LIGHT_LAYERS",
    "_MIXED_LIGHTING_SUBTRACTIVE",
    "LIGHTMAP_ON",
];

/// URP's limit of additional lights per object in the forward path (the WGSL array's length).
pub const MAX_ADDITIONAL_LIGHTS: usize = 8;

/// How the additional lights are evaluated (`_ _ADDITIONAL_LIGHTS_VERTEX _ADDITIONAL_LIGHTS`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AdditionalLights {
    /// Not at all.
    #[default]
    Off,
    /// Lambert at the vertices, interpolated, times the diffuse colour.
    PerVertex,
    /// URP's BRDF at every pixel.
    PerPixel,
}

/// Where the main light's realtime shadow comes from (`_ _MAIN_LIGHT_SHADOWS
/// _MAIN_LIGHT_SHADOWS_CASCADE _MAIN_LIGHT_SHADOWS_SCREEN`, in `UniversalForward` and
/// `stencil_deferred`'s `DirectionalLit`; URP's `Shadows.hlsl`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MainLightShadows {
    /// No shadow.
    #[default]
    Off,
    /// `_MAIN_LIGHT_SHADOWS`: one map (`_MainLightWorldToShadow[0]`).
    Map,
    /// `_MAIN_LIGHT_SHADOWS_CASCADE`: the cascade of the first split sphere that holds the
    /// point (`ComputeCascadeIndex`), lit in none.
    Cascades,
    /// `_MAIN_LIGHT_SHADOWS_SCREEN`: the texel at the pixel of the camera-sized target URP's
    /// `ScreenSpaceShadows` pass wrote (`SampleScreenSpaceShadowmap`): the realtime shadow with
    /// its strength and filtering applied there, from the map or the cascades.
    Screen,
}

impl MainLightShadows {
    /// The mode a variant's keyword `names` select.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::forward::MainLightShadows;
    /// let m = MainLightShadows::of(&["_SHADOWS_SOFT", "_MAIN_LIGHT_SHADOWS_CASCADE"]);
    /// assert_eq!(m, MainLightShadows::Cascades);
    /// assert_eq!(MainLightShadows::of(&["_SHADOWS_SOFT"]), MainLightShadows::Off);
    /// ```
    pub fn of(names: &[&str]) -> MainLightShadows {
        if names.contains(&"_MAIN_LIGHT_SHADOWS_SCREEN") {
            MainLightShadows::Screen
        } else if names.contains(&"_MAIN_LIGHT_SHADOWS_CASCADE") {
            MainLightShadows::Cascades
        } else if names.contains(&"_MAIN_LIGHT_SHADOWS") {
            MainLightShadows::Map
        } else {
            MainLightShadows::Off
        }
    }

    /// Its keyword (`None` for [`MainLightShadows::Off`]).
    pub fn keyword(self) -> Option<&'static str> {
        match self {
            MainLightShadows::Off => None,
            MainLightShadows::Map => Some("_MAIN_LIGHT_SHADOWS"),
            MainLightShadows::Cascades => Some("_MAIN_LIGHT_SHADOWS_CASCADE"),
            MainLightShadows::Screen => Some("_MAIN_LIGHT_SHADOWS_SCREEN"),
        }
    }
}

/// The keyword set of one `UniversalForward` variant.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UrpForwardKeywords {
    /// The surface keywords, shared with the G-buffer pass: the ten material keywords,
    /// `LIGHTMAP_ON` and `_MIXED_LIGHTING_SUBTRACTIVE` (at their [`kw`] indices).
    pub surface: UrpKeywords,
    /// The main light's shadow: none, one map, cascades or the screen-space pass's texel.
    pub main_light_shadows: MainLightShadows,
    /// `_SHADOWS_SOFT`: the 3 × 3 tent instead of one tap.
    pub shadows_soft: bool,
    /// The additional-lights keyword.
    pub additional_lights: AdditionalLights,
    /// `_ADDITIONAL_LIGHT_SHADOWS`: the per-pixel additional lights' realtime shadows.
    pub additional_light_shadows: bool,
    /// `_LIGHT_LAYERS`.
    pub light_layers: bool,
    /// `_LIGHT_COOKIES`: the main light's and the per-pixel additional lights' colours times
    /// their cookies ([`CookieTints`]).
    pub light_cookies: bool,
    /// `_SCREEN_SPACE_OCCLUSION`: the SSAO's direct part on the main and the per-pixel lights,
    /// its indirect part on the global illumination ([`ForwardInputs::occlusion`]).
    pub screen_space_occlusion: bool,
}

impl UrpForwardKeywords {
    /// The keyword set of these names (underscore-only names skipped); a name the pass does
    /// not declare is [`KeywordsError::Unknown`].
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::forward::{AdditionalLights, UrpForwardKeywords};
    /// let k = UrpForwardKeywords::from_names(&["_", "_ADDITIONAL_LIGHTS_VERTEX"]).unwrap();
    /// assert_eq!(k.additional_lights, AdditionalLights::PerVertex);
    /// assert!(UrpForwardKeywords::from_names(&["_GBUFFER_NORMALS_OCT"]).is_err());
    /// ```
    pub fn from_names(names: &[&str]) -> Result<UrpForwardKeywords, KeywordsError> {
        let mut k = UrpForwardKeywords::default();
        let mut surface = Vec::new();
        for &name in names {
            match name {
                "_MAIN_LIGHT_SHADOWS" => k.main_light_shadows = MainLightShadows::Map,
                "_MAIN_LIGHT_SHADOWS_CASCADE" => {
                    k.main_light_shadows = MainLightShadows::Cascades;
                }
                "_MAIN_LIGHT_SHADOWS_SCREEN" => k.main_light_shadows = MainLightShadows::Screen,
                "_SHADOWS_SOFT" => k.shadows_soft = true,
                "_ADDITIONAL_LIGHTS_VERTEX" => k.additional_lights = AdditionalLights::PerVertex,
                "_ADDITIONAL_LIGHTS" => k.additional_lights = AdditionalLights::PerPixel,
                "_ADDITIONAL_LIGHT_SHADOWS" => k.additional_light_shadows = true,
                "_LIGHT_LAYERS" => k.light_layers = true,
                "_LIGHT_COOKIES" => k.light_cookies = true,
                "_SCREEN_SPACE_OCCLUSION" => k.screen_space_occlusion = true,
                _ if URP_FORWARD_KEYWORD_NAMES.contains(&name)
                    || (!name.is_empty() && name.bytes().all(|b| b == b'_')) =>
                {
                    surface.push(name);
                }
                _ => return Err(KeywordsError::Unknown(name.to_owned())),
            }
        }
        k.surface = UrpKeywords::from_names(&surface)?;
        Ok(k)
    }

    /// Whether the main light's shadow is read (the map, the cascades or the screen-space
    /// texel): a shadow keyword without `_RECEIVE_SHADOWS_OFF` (URP's `MainLightRealtimeShadow`
    /// returns 1 then).
    pub fn reads_main_light_shadow(&self) -> bool {
        self.main_light_shadows != MainLightShadows::Off
            && !self.surface.on(kw::RECEIVE_SHADOWS_OFF)
    }

    /// Whether the additional lights' shadows are read: `_ADDITIONAL_LIGHT_SHADOWS` with the
    /// per-pixel lights (the per-vertex ones have none) and without `_RECEIVE_SHADOWS_OFF`
    /// (URP's `AdditionalLightRealtimeShadow` returns 1 then).
    pub fn reads_additional_light_shadows(&self) -> bool {
        self.additional_light_shadows
            && self.additional_lights == AdditionalLights::PerPixel
            && !self.surface.on(kw::RECEIVE_SHADOWS_OFF)
    }
}

/// The main light's realtime shadow at a pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MainLightShadow {
    /// `1 − strength + strength · visibility`.
    pub attenuation: f32,
    /// The shadow's strength.
    pub strength: f32,
}

impl MainLightShadow {
    /// No shadow: attenuation 1, strength 0 (what the pass uses where it reads no map).
    pub const NONE: MainLightShadow = MainLightShadow {
        attenuation: 1.0,
        strength: 0.0,
    };

    /// URP's `MixRealtimeAndBakedShadows` with no baked shadow (1; none of the frame's
    /// variants read a shadowmask): the realtime attenuation lerped towards 1 by `fade`
    /// ([`UrpShadowFade::at`]), `a · (1 − fade) + fade` as the WGSL `mix` computes it.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::forward::MainLightShadow;
    /// let s = MainLightShadow { attenuation: 0.2, strength: 0.8 };
    /// assert_eq!(s.faded(0.0).attenuation, 0.2);
    /// assert_eq!(s.faded(1.0).attenuation, 1.0);
    /// assert!((s.faded(0.5).attenuation - 0.6).abs() < 1e-6);
    /// ```
    pub fn faded(self, fade: f32) -> MainLightShadow {
        MainLightShadow {
            attenuation: self.attenuation * (1.0 - fade) + fade,
            ..self
        }
    }
}

/// URP's shadow fade (`GetMainLightShadowFade` with `_MainLightShadowParams.zw`, and
/// `GetAdditionalLightShadowFade` with `_AdditionalShadowFadeParams.xy`: the same ramp): a
/// ramp in the squared distance from the camera, `saturate(|p − camera|² · scale + bias)`,
/// which URP's host sets to reach 1 at the shadow distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpShadowFade {
    /// `_MainLightShadowParams.z`.
    pub scale: f32,
    /// `_MainLightShadowParams.w`.
    pub bias: f32,
}

impl UrpShadowFade {
    /// No fade anywhere (scale and bias 0).
    pub const NONE: UrpShadowFade = UrpShadowFade {
        scale: 0.0,
        bias: 0.0,
    };

    /// The ramp from distance `start` (fade 0) to `end` (fade 1), linear in the squared
    /// distance as URP's is.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;
    /// let fade = UrpShadowFade::between(2.0, 4.0);
    /// assert_eq!(fade.at(Vec3::new(1.0, 0.0, 0.0), Vec3::ZERO), 0.0);
    /// assert!((fade.at(Vec3::new(0.0, 10f32.sqrt(), 0.0), Vec3::ZERO) - 0.5).abs() < 1e-6);
    /// assert_eq!(fade.at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO), 1.0);
    /// ```
    pub fn between(start: f32, end: f32) -> UrpShadowFade {
        let (a, b) = (start * start, end * end);
        let scale = 1.0 / (b - a);
        UrpShadowFade {
            scale,
            bias: -a * scale,
        }
    }

    /// How far the shadow has faded at `p` for a camera at `camera` (0 none, 1 gone).
    pub fn at(&self, p: Vec3, camera: Vec3) -> f32 {
        let d = p - camera;
        (d.dot(d) * self.scale + self.bias).clamp(0.0, 1.0)
    }

    /// The WGSL `main_light_shadow_params` uniform, URP's `_MainLightShadowParams` with this
    /// fade: `(strength, 0, scale, bias)`, little-endian (the receivers read the strength there
    /// with `_MAIN_LIGHT_SHADOWS_SCREEN` only; y, URP's soft flag, is the keyword's business).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;
    /// let bytes = UrpShadowFade { scale: 0.5, bias: -1.0 }.uniform(0.8);
    /// assert_eq!(bytes[..4], 0.8f32.to_le_bytes());
    /// assert_eq!(bytes[12..], (-1.0f32).to_le_bytes());
    /// ```
    pub fn uniform(&self, strength: f32) -> Vec<u8> {
        [strength, 0.0, self.scale, self.bias]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect()
    }
}

/// The lights of the forward pass besides the main light's direction and colour (which
/// [`UrpLighting`] holds): the main light's rendering-layer mask and up to
/// [`MAX_ADDITIONAL_LIGHTS`] point and spot lights.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpForwardLights {
    main_layer_mask: u32,
    additional: Vec<UrpLightParams>,
}

impl UrpForwardLights {
    /// The lights; more than [`MAX_ADDITIONAL_LIGHTS`] additional lights, or a directional
    /// one among them (the pass's additional lights are punctual), is an error.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::Light;
    /// use wgsl_variants_shaders::reference::urp::forward::UrpForwardLights;
    /// use wgsl_variants_shaders::reference::urp::lighting::UrpLight;
    /// let point = UrpLight::new(Light::point(Vec3::Z, 4.0, Vec3::ONE), 0.0, 1).params().unwrap();
    /// assert!(UrpForwardLights::new(1, vec![point; 8]).is_ok());
    /// assert!(UrpForwardLights::new(1, vec![point; 9]).is_err());
    /// let sun = UrpLight::new(Light::directional(Vec3::NEG_Z, Vec3::ONE), 0.0, 1).params().unwrap();
    /// assert!(UrpForwardLights::new(1, vec![sun]).is_err());
    /// ```
    pub fn new(
        main_layer_mask: u32,
        additional: Vec<UrpLightParams>,
    ) -> Result<UrpForwardLights, LightError> {
        if additional.len() > MAX_ADDITIONAL_LIGHTS {
            return Err(LightError::TooManyAdditional {
                count: additional.len(),
                max: MAX_ADDITIONAL_LIGHTS,
            });
        }
        if additional
            .iter()
            .any(|l| l.kind == UrpLightKind::Directional)
        {
            return Err(LightError::AdditionalDirectional);
        }
        Ok(UrpForwardLights {
            main_layer_mask,
            additional,
        })
    }

    /// The main light's rendering-layer mask.
    pub fn main_layer_mask(&self) -> u32 {
        self.main_layer_mask
    }

    /// The additional lights.
    pub fn additional(&self) -> &[UrpLightParams] {
        &self.additional
    }

    /// The WGSL `ForwardLights` record: `params` (count, main light's mask, 0, 0) as a
    /// `vec4u`, then eight `UrpLight` records ([`UrpLightParams::uniform`]; zeros past the
    /// count), little-endian: 16 + 8 · 80 = 656 bytes.
    pub fn uniform(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(16 + 80 * MAX_ADDITIONAL_LIGHTS);
        let count = self.additional.len() as u32;
        for word in [count, self.main_layer_mask, 0, 0] {
            out.extend(word.to_le_bytes());
        }
        for light in &self.additional {
            out.extend(light.uniform());
        }
        out.resize(16 + 80 * MAX_ADDITIONAL_LIGHTS, 0);
        out
    }

    /// The additional lights that light a mesh of `rendering_layers` (every one without
    /// `_LIGHT_LAYERS`), with their indices.
    fn lighting(
        &self,
        layers: bool,
        rendering_layers: u32,
    ) -> impl Iterator<Item = (usize, &UrpLightParams)> {
        self.additional
            .iter()
            .enumerate()
            .filter(move |(_, l)| !layers || l.lights_layers(rendering_layers))
    }
}

/// URP's `VertexLighting` at one vertex: `Σ color · attenuation · saturate(n·l)` over the
/// additional lights that light the mesh (the vertex stage's `p` and unit normal `n`); 0
/// unless `_ADDITIONAL_LIGHTS_VERTEX`. The pass interpolates it across the triangle.
pub fn vertex_lighting(
    k: &UrpForwardKeywords,
    lights: &UrpForwardLights,
    p: Vec3,
    n: Vec3,
    rendering_layers: u32,
) -> Vec3 {
    if k.additional_lights != AdditionalLights::PerVertex {
        return Vec3::ZERO;
    }
    lights
        .lighting(k.light_layers, rendering_layers)
        .map(|(_, light)| {
            let (l, attenuation) = light.sample(p);
            light.color * attenuation * n.dot(l).clamp(0.0, 1.0)
        })
        .sum()
}

/// What the lights' cookies multiply their colours by at one pixel under `_LIGHT_COOKIES`
/// (URP's `GetMainLight` and the per-pixel `GetAdditionalLight`; the per-vertex lights take
/// none): the main light's, which the subtractive lightmap's estimate of the main light reads
/// too, and each additional light's in the order of [`UrpForwardLights::additional`] (missing
/// entries white). [`CookieTints::WHITE`] leaves every light as it is.
#[derive(Clone, Debug, PartialEq)]
pub struct CookieTints {
    /// The main light's cookie colour.
    pub main: Vec3,
    /// Each additional light's cookie colour.
    pub additional: Vec<Vec3>,
}

impl CookieTints {
    /// No tint.
    pub const WHITE: CookieTints = CookieTints {
        main: Vec3::ONE,
        additional: Vec::new(),
    };

    /// The tints a pixel at `p` may take under `_LIGHT_COOKIES`: one per texel of the `main`
    /// light's cookie it may read there ([`MainLightCookie::candidates`]), each with the
    /// first `lights` of the `additional` lights' cookies at the lower (`end` 0) or the upper
    /// (`end` 1) end of their ranges ([`AdditionalLightCookies::color`]). Shading grows with
    /// every additional light's tint, so the two ends bound it; the main light's cookie also
    /// lowers the subtractive lightmap, so each of its texels is kept.
    ///
    /// ```
    /// use glam::{Mat4, Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::urp::cookie::{
    ///     AdditionalLightCookie, AdditionalLightCookies, CookieFormat, CookieProjection,
    ///     CookieTexture, MainLightCookie,
    /// };
    /// use wgsl_variants_shaders::reference::urp::forward::CookieTints;
    /// // The main light's cookie: black on the left, white on the right.
    /// let texture = CookieTexture::new(
    ///     vec![[0, 0, 0, 255], [255, 255, 255, 255]], (2, 1), CookieFormat::Rgb,
    /// ).unwrap();
    /// let main = MainLightCookie { world_to_light: Mat4::IDENTITY, texture };
    /// // One point light whose rect is a white texel; the second light has no cookie.
    /// let atlas = CookieTexture::new(vec![[0; 4], [255; 4]], (2, 1), CookieFormat::Alpha).unwrap();
    /// let point = AdditionalLightCookie {
    ///     world_to_light: Mat4::IDENTITY,
    ///     uv_rect: Vec4::new(0.5, 1.0, 0.5, 0.0),
    ///     projection: CookieProjection::Point,
    /// };
    /// let additional = AdditionalLightCookies::new(atlas, vec![Some(point), None]).unwrap();
    /// // On the main cookie's edge both of its texels may be read.
    /// let tints = CookieTints::candidates(&main, &additional, 2, Vec3::new(0.0, 0.0, 1.0), 0);
    /// assert_eq!(tints.len(), 2);
    /// assert_eq!((tints[0].main, tints[1].main), (Vec3::ZERO, Vec3::ONE));
    /// assert_eq!(tints[0].additional, vec![Vec3::ONE, Vec3::ONE]);
    /// ```
    pub fn candidates(
        main: &MainLightCookie,
        additional: &AdditionalLightCookies,
        lights: usize,
        p: Vec3,
        end: usize,
    ) -> Vec<CookieTints> {
        let additional: Vec<Vec3> = (0..lights)
            .map(|k| {
                let (lo, hi) = additional.color(k, p);
                [lo, hi][end]
            })
            .collect();
        main.candidates(p)
            .into_iter()
            .map(|main| CookieTints {
                main,
                additional: additional.clone(),
            })
            .collect()
    }
}

/// What the forward pass reads at a pixel besides its surface and the scene's lights: the
/// lights' shadows there, the interpolated per-vertex lighting, the cookies and the
/// screen-space occlusion. Each is read only under its keyword; [`ForwardInputs::NONE`] is
/// what a pixel without any of them reads.
#[derive(Clone, Debug, PartialEq)]
pub struct ForwardInputs {
    /// The main light's shadow at the pixel's position (read where
    /// [`UrpForwardKeywords::reads_main_light_shadow`]).
    pub shadow: MainLightShadow,
    /// The interpolated [`vertex_lighting`] (`_ADDITIONAL_LIGHTS_VERTEX`).
    pub vertex_lighting: Vec3,
    /// Each additional light's shadow attenuation at the pixel, in the order of
    /// [`UrpForwardLights::additional`] (URP's `AdditionalLightShadow`, read where
    /// [`UrpForwardKeywords::reads_additional_light_shadows`]; missing entries are 1).
    pub additional_shadows: Vec<f32>,
    /// The lights' cookie colours (`_LIGHT_COOKIES`).
    pub tints: CookieTints,
    /// The screen-space occlusion at the pixel (`_SCREEN_SPACE_OCCLUSION`).
    pub occlusion: AmbientOcclusionFactor,
}

impl ForwardInputs {
    /// No shadow, no per-vertex light, white cookies, no occlusion.
    pub const NONE: ForwardInputs = ForwardInputs {
        shadow: MainLightShadow::NONE,
        vertex_lighting: Vec3::ZERO,
        additional_shadows: Vec::new(),
        tints: CookieTints::WHITE,
        occlusion: AmbientOcclusionFactor::NONE,
    };
}

impl Default for ForwardInputs {
    fn default() -> Self {
        ForwardInputs::NONE
    }
}

/// The `UniversalForward` fragment at one pixel (rgb; the pass writes alpha 1): `None` where
/// `_ALPHATEST_ON` discards. `inputs` holds what the pixel reads besides its surface: the
/// lights' shadows, the per-vertex lighting, the cookies and the screen-space occlusion.
#[allow(clippy::too_many_arguments)]
pub fn shade_forward(
    k: &UrpForwardKeywords,
    mat: &UrpMaterial,
    tex: &UrpTexels,
    pixel: &UrpPixel,
    light: &UrpLighting,
    env: &CubeFaces,
    lights: &UrpForwardLights,
    inputs: &ForwardInputs,
) -> Option<Vec3> {
    let (shadow, tints) = (inputs.shadow, &inputs.tints);
    let sk = &k.surface;
    let s = urp_surface(sk, mat, tex)?;
    let b = urp_brdf(sk, &s);
    let roughness = (b.perceptual_roughness * b.perceptual_roughness).max(HALF_MIN_SQRT);
    let direct = UrpBrdfData {
        diffuse: b.diffuse,
        specular: b.specular,
        reflectivity: b.reflectivity,
        roughness,
        roughness2: b.roughness2,
        normalization_term: roughness * 4.0 + 2.0,
        roughness2_minus_one: b.roughness2 - 1.0,
    };
    let n = urp_world_normal(sk, s.normal_ts, &pixel.geometry);
    let p = pixel.geometry.world_position;
    let v = (light.camera_position - p).normalize();
    let specular_off = sk.on(kw::SPECULARHIGHLIGHTS_OFF);
    let shadow = if k.reads_main_light_shadow() {
        shadow
    } else {
        MainLightShadow::NONE
    };
    // CreateAmbientOcclusionFactor: the SSAO's indirect part, no larger than the surface's
    // occlusion, on the global illumination; its direct part on the main and the per-pixel
    // lights.
    let (occlusion, direct_occlusion) = if k.screen_space_occlusion {
        (
            inputs.occlusion.indirect.min(s.occlusion),
            inputs.occlusion.direct,
        )
    } else {
        (s.occlusion, 1.0)
    };
    // GetMainLight's colour times its cookie and the direct occlusion: the direct light and
    // the subtractive lightmap's estimate of it both read it.
    let light = &UrpLighting {
        main_light_color: light.main_light_color * tint(k, tints.main) * direct_occlusion,
        ..*light
    };
    let baked = urp_baked_gi(sk, tex, light, n, shadow.attenuation, shadow.strength);
    let mut color = global_illumination(sk, &b, baked, n, v, occlusion, light, env);
    let layers = pixel.rendering_layers;
    if !k.light_layers || lights.main_layer_mask & layers != 0 {
        color += super::lighting::lighting_physically_based(
            &direct,
            light.main_light_color,
            shadow.attenuation,
            light.main_light_dir,
            n,
            v,
            specular_off,
        );
    }
    match k.additional_lights {
        AdditionalLights::Off => {}
        AdditionalLights::PerPixel => {
            let reads_shadows = k.reads_additional_light_shadows();
            for (i, l) in lights.lighting(k.light_layers, layers) {
                let (dir, attenuation) = l.sample(p);
                let shadow = match inputs.additional_shadows.get(i) {
                    Some(&s) if reads_shadows => s,
                    _ => 1.0,
                };
                let cookie = tint(k, tints.additional.get(i).copied().unwrap_or(Vec3::ONE));
                color += super::lighting::lighting_physically_based(
                    &direct,
                    l.color * cookie * direct_occlusion,
                    attenuation * shadow,
                    dir,
                    n,
                    v,
                    specular_off,
                );
            }
        }
        AdditionalLights::PerVertex => color += inputs.vertex_lighting * b.diffuse,
    }
    Some(color + s.emission)
}

/// `cookie` under `_LIGHT_COOKIES`, white without.
fn tint(k: &UrpForwardKeywords, cookie: Vec3) -> Vec3 {
    if k.light_cookies { cookie } else { Vec3::ONE }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::light::Light;
    use crate::reference::surface::Geometry;
    use crate::reference::urp::lighting::UrpLight;
    use glam::Vec4;

    /// A white point light of range 4 2 above the pixel, on rendering layers `layers`.
    fn point_above(layers: u32) -> UrpLightParams {
        UrpLight::new(
            Light::point(Vec3::new(0.0, 0.0, 2.0), 4.0, Vec3::ONE),
            0.0,
            layers,
        )
        .params()
        .unwrap()
    }

    fn pixel(layers: u32) -> UrpPixel {
        UrpPixel {
            geometry: Geometry {
                world_position: Vec3::ZERO,
                normal: Vec3::Z,
                tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
            },
            depth: 0.5,
            rendering_layers: layers,
        }
    }

    /// The pixel at the origin facing +Z (layer 1) of the default material and texels `tex`,
    /// shaded under `light`, `lights` and `inputs` with a black environment.
    fn on_paper(
        k: &UrpForwardKeywords,
        tex: &UrpTexels,
        light: &UrpLighting,
        lights: &UrpForwardLights,
        inputs: &ForwardInputs,
    ) -> Vec3 {
        let env = CubeFaces::uniform(Vec4::ZERO);
        shade_forward(
            k,
            &UrpMaterial::default(),
            tex,
            &pixel(1),
            light,
            &env,
            lights,
            inputs,
        )
        .unwrap()
    }

    fn shade(names: &[&str], lights: &UrpForwardLights, shadow: MainLightShadow, vl: Vec3) -> Vec3 {
        let k = UrpForwardKeywords::from_names(names).unwrap();
        let light = UrpLighting {
            main_light_dir: Vec3::Z,
            ..UrpLighting::default()
        };
        on_paper(
            &k,
            &UrpTexels::default(),
            &light,
            lights,
            &ForwardInputs {
                shadow,
                vertex_lighting: vl,
                ..ForwardInputs::NONE
            },
        )
    }

    #[test]
    fn the_additional_lights_shadow_scales_only_the_per_pixel_light_it_belongs_to() {
        // Two point lights 2 above the pixel (0.2109375 each, as on paper below); the first
        // shadowed to 0.25 of its light. The shadow counts only with _ADDITIONAL_LIGHT_SHADOWS
        // and the per-pixel lights, and not with _RECEIVE_SHADOWS_OFF.
        let point = point_above(1);
        let lights = UrpForwardLights::new(0, vec![point, point]).unwrap();
        let run = |names: &[&str]| {
            let k = UrpForwardKeywords::from_names(names).unwrap();
            on_paper(
                &k,
                &UrpTexels::default(),
                &UrpLighting::default(),
                &lights,
                &ForwardInputs {
                    additional_shadows: vec![0.25],
                    ..ForwardInputs::NONE
                },
            )
        };
        let one = 0.210_937_5;
        let lit = run(&["_SPECULARHIGHLIGHTS_OFF", "_ADDITIONAL_LIGHTS"]);
        assert!((lit - Vec3::splat(2.0 * one)).abs().max_element() < 1e-6);
        let shadowed = run(&[
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS",
            "_ADDITIONAL_LIGHT_SHADOWS",
        ]);
        assert!((shadowed - Vec3::splat(1.25 * one)).abs().max_element() < 1e-6);
        let unreceived = run(&[
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS",
            "_ADDITIONAL_LIGHT_SHADOWS",
            "_RECEIVE_SHADOWS_OFF",
        ]);
        assert_eq!(unreceived, lit);
    }

    #[test]
    fn additional_point_light_on_paper() {
        // A point light 2 above the pixel, range 4: 1/d² · (1 − (d²/r²)²)² = 1/4 · (1 − 1/16)²
        // = 0.2197265625; n·l = 1; a white dielectric's diffuse 0.96 (no specular):
        // 0.2109375 per pixel. Black main light, no GI.
        let point = point_above(1);
        let lights = UrpForwardLights::new(0, vec![point]).unwrap();
        let off = ["_SPECULARHIGHLIGHTS_OFF"];
        assert_eq!(
            shade(&off, &lights, MainLightShadow::NONE, Vec3::ZERO),
            Vec3::ZERO
        );
        let per_pixel = shade(
            &["_SPECULARHIGHLIGHTS_OFF", "_ADDITIONAL_LIGHTS"],
            &lights,
            MainLightShadow::NONE,
            Vec3::ZERO,
        );
        assert!((per_pixel - Vec3::splat(0.210_937_5)).abs().max_element() < 1e-6);
        // Per vertex: the same Lambert at a vertex there, times the diffuse colour.
        let k = UrpForwardKeywords::from_names(&["_ADDITIONAL_LIGHTS_VERTEX"]).unwrap();
        let at_vertex = vertex_lighting(&k, &lights, Vec3::ZERO, Vec3::Z, 1);
        assert!((at_vertex - Vec3::splat(0.219_726_56)).abs().max_element() < 1e-7);
        let per_vertex = shade(
            &["_SPECULARHIGHLIGHTS_OFF", "_ADDITIONAL_LIGHTS_VERTEX"],
            &lights,
            MainLightShadow::NONE,
            at_vertex,
        );
        assert!((per_vertex - per_pixel).abs().max_element() < 1e-6);
        // Light layers: the light's layer 0 is the mesh's.
        let elsewhere = point_above(2);
        let lights = UrpForwardLights::new(0, vec![elsewhere]).unwrap();
        let layered = [
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS",
            "_LIGHT_LAYERS",
        ];
        assert_eq!(
            shade(&layered, &lights, MainLightShadow::NONE, Vec3::ZERO),
            Vec3::ZERO
        );
    }

    #[test]
    fn cookies_tint_the_main_and_the_per_pixel_lights_only_under_their_keyword() {
        // A white main light from +Z and a point light 2 above the white dielectric, specular
        // off; the main light's cookie 0.5, the point light's 0.25.
        let point = point_above(1);
        let one = UrpForwardLights::new(1, vec![point]).unwrap();
        let none = UrpForwardLights::new(1, vec![]).unwrap();
        let light = UrpLighting {
            main_light_dir: Vec3::Z,
            main_light_color: Vec3::ONE,
            ..UrpLighting::default()
        };
        let tints = CookieTints {
            main: Vec3::splat(0.5),
            additional: vec![Vec3::splat(0.25)],
        };
        let run = |names: &[&str], lights: &UrpForwardLights, tints: &CookieTints| {
            let k = UrpForwardKeywords::from_names(names).unwrap();
            on_paper(
                &k,
                &UrpTexels::default(),
                &light,
                lights,
                &ForwardInputs {
                    vertex_lighting: Vec3::splat(0.1),
                    tints: tints.clone(),
                    ..ForwardInputs::NONE
                },
            )
        };
        let pixel_lights = [
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS",
            "_LIGHT_COOKIES",
        ];
        let main = run(&pixel_lights, &none, &CookieTints::WHITE);
        let both = run(&pixel_lights, &one, &CookieTints::WHITE);
        let tinted = run(&pixel_lights, &one, &tints);
        let want = main * 0.5 + (both - main) * 0.25;
        assert!(
            (tinted - want).abs().max_element() < 1e-6,
            "{tinted} {want}"
        );
        // Without the keyword the tints are not read.
        let plain = ["_SPECULARHIGHLIGHTS_OFF", "_ADDITIONAL_LIGHTS"];
        assert_eq!(run(&plain, &one, &tints), both);
        // The per-vertex lights take no cookie (URP's two-argument GetAdditionalLight).
        let vertex = [
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS_VERTEX",
            "_LIGHT_COOKIES",
        ];
        let only_additional = CookieTints {
            main: Vec3::ONE,
            additional: vec![Vec3::splat(0.25)],
        };
        assert_eq!(
            run(&vertex, &one, &only_additional),
            run(&vertex, &one, &CookieTints::WHITE)
        );
    }

    #[test]
    fn main_light_shadow_on_paper() {
        // White main light from +Z onto the white dielectric, specular off: 0.96 unshadowed.
        // Strength 0.8, visibility 0.25: attenuation 1 − 0.8 + 0.8 · 0.25 = 0.4 → 0.384.
        let lights = UrpForwardLights::new(1, vec![]).unwrap();
        let k = UrpForwardKeywords::from_names(&["_MAIN_LIGHT_SHADOWS", "_SPECULARHIGHLIGHTS_OFF"])
            .unwrap();
        let light = UrpLighting {
            main_light_dir: Vec3::Z,
            main_light_color: Vec3::ONE,
            ..UrpLighting::default()
        };
        let shadow = MainLightShadow {
            attenuation: 0.4,
            strength: 0.8,
        };
        let run = |k: &UrpForwardKeywords| {
            on_paper(
                k,
                &UrpTexels::default(),
                &light,
                &lights,
                &ForwardInputs {
                    shadow,
                    ..ForwardInputs::NONE
                },
            )
        };
        assert!((run(&k) - Vec3::splat(0.384)).abs().max_element() < 1e-6);
        // Receiving no shadows ignores the map.
        let mut off = k;
        off.surface.0[kw::RECEIVE_SHADOWS_OFF] = true;
        assert!((run(&off) - Vec3::splat(0.96)).abs().max_element() < 1e-6);
        // Subtractive: lightmap 1, lambert 1 · (1 − 0.4) = 0.6 subtracted → 0.4; mixed by
        // strength 0.8 from 1: 1 − 0.8 · 0.6 = 0.52; GI = 0.52 · 0.96 = 0.4992; + 0.384.
        let sub = UrpForwardKeywords::from_names(&[
            "_MAIN_LIGHT_SHADOWS",
            "_SPECULARHIGHLIGHTS_OFF",
            "LIGHTMAP_ON",
            "_MIXED_LIGHTING_SUBTRACTIVE",
        ])
        .unwrap();
        let tex = UrpTexels {
            lightmap: Vec3::ONE,
            ..UrpTexels::default()
        };
        let subtractive = |k: &UrpForwardKeywords, tints: &CookieTints| {
            on_paper(
                k,
                &tex,
                &light,
                &lights,
                &ForwardInputs {
                    shadow,
                    tints: tints.clone(),
                    ..ForwardInputs::NONE
                },
            )
        };
        let got = subtractive(&sub, &CookieTints::WHITE);
        assert!(
            (got - Vec3::splat(0.4992 + 0.384)).abs().max_element() < 1e-6,
            "{got}"
        );
        // With the main light's cookie 0.5 the subtractive estimate reads the tinted colour:
        // lambert 0.5 · 0.6 = 0.3 subtracted → 0.7; 1 − 0.8 · 0.3 = 0.76; GI 0.76 · 0.96 =
        // 0.7296; direct 0.384 · 0.5 = 0.192.
        let mut cookies = sub;
        cookies.light_cookies = true;
        let half = CookieTints {
            main: Vec3::splat(0.5),
            additional: Vec::new(),
        };
        let got = subtractive(&cookies, &half);
        assert!(
            (got - Vec3::splat(0.7296 + 0.192)).abs().max_element() < 1e-6,
            "{got}"
        );
    }

    #[test]
    fn the_screen_space_occlusion_on_paper() {
        // The white dielectric (specular off, occlusion 1) under a white main light from +Z
        // (0.96), a point light 2 above (0.2109375) and a uniform white environment (SH
        // ambient 1 · diffuse 0.96, no reflection with a black cube): SSAO 0.5 with direct
        // strength 0.25 gives indirect 0.5 and direct 0.875.
        let point = point_above(1);
        let lights = UrpForwardLights::new(1, vec![point]).unwrap();
        let light = UrpLighting {
            main_light_dir: Vec3::Z,
            main_light_color: Vec3::ONE,
            sh_r: Vec4::new(0.0, 0.0, 0.0, 1.0),
            sh_g: Vec4::new(0.0, 0.0, 0.0, 1.0),
            sh_b: Vec4::new(0.0, 0.0, 0.0, 1.0),
            ..UrpLighting::default()
        };
        let inputs = ForwardInputs {
            occlusion: AmbientOcclusionFactor::screen_space(0.5, 0.25),
            ..ForwardInputs::NONE
        };
        let run = |names: &[&str], inputs: &ForwardInputs| {
            let k = UrpForwardKeywords::from_names(names).unwrap();
            on_paper(&k, &UrpTexels::default(), &light, &lights, inputs)
        };
        let names = ["_SPECULARHIGHLIGHTS_OFF", "_ADDITIONAL_LIGHTS"];
        let open = run(&names, &ForwardInputs::NONE);
        let ambient = open - Vec3::splat(0.96 + 0.210_937_5);
        let with = [
            "_SPECULARHIGHLIGHTS_OFF",
            "_ADDITIONAL_LIGHTS",
            "_SCREEN_SPACE_OCCLUSION",
        ];
        let occluded = run(&with, &inputs);
        let want = ambient * 0.5 + Vec3::splat((0.96 + 0.210_937_5) * 0.875);
        assert!(ambient.min_element() > 0.1, "{ambient}");
        assert!(
            (occluded - want).abs().max_element() < 1e-5,
            "{occluded} {want}"
        );
        // Without the keyword the occlusion is not read.
        assert_eq!(run(&names, &inputs), open);
        // The smaller of the SSAO and the surface's occlusion darkens the ambient light: an
        // SSAO of 1 (direct part 1) leaves the surface's own.
        let clear = ForwardInputs {
            occlusion: AmbientOcclusionFactor::screen_space(1.0, 0.25),
            ..ForwardInputs::NONE
        };
        assert_eq!(run(&with, &clear), open);
    }

    #[test]
    fn uniform_layout() {
        let point = UrpLight::new(Light::point(Vec3::Z, 4.0, Vec3::ONE), 0.0, 5)
            .params()
            .unwrap();
        let bytes = UrpForwardLights::new(9, vec![point, point])
            .unwrap()
            .uniform();
        assert_eq!(bytes.len(), 656);
        assert_eq!(&bytes[..8], &[2, 0, 0, 0, 9, 0, 0, 0]);
        assert_eq!(&bytes[16..96], &point.uniform()[..]);
        assert!(bytes[176..].iter().all(|&b| b == 0));
    }
}
