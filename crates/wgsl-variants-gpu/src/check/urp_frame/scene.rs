//! The URP frame's scene: the built-in frame's camera and opaque objects ([`FrameScene`]) with
//! URP Lit materials, URP's per-frame lighting, a main light and three additional lights on
//! rendering layers, their shadows and cookies (docs/urp.md §12).

use glam::{Vec2, Vec3, Vec4};

use super::super::frame::{FrameObject, FrameScene};
use super::super::scene::cube_resource;
use super::super::urp::{camera_uniform, lighting_uniform, material_uniform, object_uniform};
use super::super::urp_cookies::{
    DrawCookie, additional_light_cookies, atlas_resources, main_light_cookie, main_resources,
};
use super::super::urp_occlusion::ScreenOcclusion;
use super::shadow::{UrpAdditionalShadowSpec, UrpShadowSpec};
use crate::{BoundResource, CheckError, GpuError, Resource};
use wgsl_variants_shaders::reference::cube::CubeFaces;
use wgsl_variants_shaders::reference::light::{Light, LightError};
use wgsl_variants_shaders::reference::urp::ambient_occlusion::AmbientOcclusionFactor;
use wgsl_variants_shaders::reference::urp::cookie::{AdditionalLightCookies, MainLightCookie};
use wgsl_variants_shaders::reference::urp::forward::{
    CookieTints, UrpForwardLights, UrpShadowFade,
};
use wgsl_variants_shaders::reference::urp::gbuffer::{
    UrpKeywords, UrpLighting, UrpMaterial, UrpPixel, UrpTexels,
};
use wgsl_variants_shaders::reference::urp::lighting::{UrpLight, UrpLightParams};

/// URP's default rendering layer ("Light Layer default", bit 0): every object's but the
/// glowing sphere's, and the one layer of the warm point light's mask.
pub const DEFAULT_LAYER: u32 = 1;

/// The glowing sphere's rendering-layer mask: layer 1 only, which the masks of the main light,
/// the cool point light and the spot hold and the warm point light's does not.
pub const SHELTERED_LAYERS: u32 = 1 << 1;

/// The layer mask of every light but the warm point light: the default layer and the
/// sheltered one.
pub const EVERY_LAYER: u32 = DEFAULT_LAYER | SHELTERED_LAYERS;

/// One opaque object of the URP frame: the geometry of the built-in frame's object of the same
/// index, with a URP Lit material.
#[derive(Clone, Debug)]
pub struct UrpFrameObject {
    /// The material keywords (the passes' own keywords are added per pass).
    pub keywords: &'static [&'static str],
    /// URP Lit's properties.
    pub material: UrpMaterial,
    /// The mesh's rendering-layer mask (`_LIGHT_LAYERS`).
    pub rendering_layers: u32,
}

/// One additional (point or spot) light of the URP frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpFrameLight {
    /// A name for reports.
    pub name: &'static str,
    /// The light as a renderer describes it.
    pub light: Light,
    /// What the passes read (direction, attenuation, angles, layer mask).
    pub params: UrpLightParams,
}

/// The URP frame: geometry and camera from the built-in frame (its opaque objects, no sky and
/// no semi-transparent objects), URP Lit materials, the per-frame lighting, the main light
/// and the additional lights.
#[derive(Clone, Debug)]
pub struct UrpFrame {
    /// Camera, size and the opaque objects' meshes ([`FrameScene::cast`] finds what a pixel
    /// sees).
    pub geometry: FrameScene,
    /// One URP object per [`FrameScene::objects`] entry.
    pub objects: Vec<UrpFrameObject>,
    /// The per-frame lighting: ambient SH, the main light's direction and colour, the
    /// environment colour.
    pub lighting: UrpLighting,
    /// The main light as `StencilDeferred`'s `DirectionalLit` reads it.
    pub main_light: UrpLightParams,
    /// The additional lights (at most eight: URP's per-object limit in the forward path).
    pub lights: Vec<UrpFrameLight>,
    /// The main light's shadow (`_MAIN_LIGHT_SHADOWS`), or none.
    pub main_shadow: Option<UrpShadowSpec>,
    /// The additional lights' shadows (`_ADDITIONAL_LIGHT_SHADOWS`), or none.
    pub additional_shadows: Option<UrpAdditionalShadowSpec>,
    /// The lights' cookies (`_LIGHT_COOKIES`), or none.
    pub cookies: Option<UrpFrameCookies>,
    /// The screen-space occlusion both paths read (`_SCREEN_SPACE_OCCLUSION`; a stand-in
    /// pattern until URP's SSAO pass is built), or none.
    pub occlusion: Option<ScreenOcclusion>,
}

/// The URP frame's light cookies (`_LIGHT_COOKIES`): the main light's, and the additional
/// lights' atlas with an entry for each light that has one.
#[derive(Clone, Debug)]
pub struct UrpFrameCookies {
    /// The main light's cookie (the forward pass reads it wherever `_LIGHT_COOKIES` is on).
    pub main: MainLightCookie,
    /// The atlas and each additional light's entry, in the order of [`UrpFrame::lights`].
    pub additional: AdditionalLightCookies,
}

/// Materials of the five objects: floor, metal sphere, glowing sphere, box, cutout box.
fn materials() -> Vec<UrpFrameObject> {
    let lit = |keywords, material, rendering_layers| UrpFrameObject {
        keywords,
        material,
        rendering_layers,
    };
    vec![
        lit(
            &[],
            UrpMaterial {
                base_color: Vec4::new(0.7, 0.7, 0.65, 1.0),
                smoothness: 0.35,
                ..UrpMaterial::default()
            },
            DEFAULT_LAYER,
        ),
        lit(
            &["_NORMALMAP", "_METALLICSPECGLOSSMAP"],
            UrpMaterial {
                smoothness: 0.9,
                bump_scale: 0.8,
                ..UrpMaterial::default()
            },
            DEFAULT_LAYER,
        ),
        lit(
            &["_EMISSION", "_OCCLUSIONMAP"],
            UrpMaterial {
                base_color: Vec4::new(0.9, 0.95, 1.0, 1.0),
                emission_color: Vec3::new(0.3, 0.2, 0.05),
                smoothness: 0.6,
                occlusion_strength: 0.7,
                ..UrpMaterial::default()
            },
            SHELTERED_LAYERS,
        ),
        lit(
            &["_SPECULAR_SETUP"],
            UrpMaterial {
                base_color: Vec4::new(0.8, 0.7, 0.9, 1.0),
                spec_color: Vec3::new(0.25, 0.2, 0.15),
                smoothness: 0.8,
                ..UrpMaterial::default()
            },
            DEFAULT_LAYER,
        ),
        lit(
            &["_ALPHATEST_ON", "_NORMALMAP"],
            UrpMaterial {
                base_color: Vec4::new(0.5, 0.8, 0.6, 1.0),
                smoothness: 0.5,
                ..UrpMaterial::default()
            },
            DEFAULT_LAYER,
        ),
    ]
}

impl UrpFrame {
    /// The frame the checks and pictures use, at the built-in frame's size.
    ///
    /// ```
    /// use wgsl_variants_gpu::check::urp_frame::UrpFrame;
    /// let frame = UrpFrame::new();
    /// assert_eq!(frame.objects.len(), frame.geometry.objects.len());
    /// assert_eq!(frame.lights.len(), 3);
    /// // The main light, the cool point light and the spot have cookies.
    /// let cookies = frame.cookies.as_ref().unwrap();
    /// assert_eq!(cookies.additional.lights.iter().flatten().count(), 2);
    /// assert!(frame.occlusion.is_some());
    /// ```
    pub fn new() -> UrpFrame {
        UrpFrame::sized(
            super::super::frame::FRAME_WIDTH,
            super::super::frame::FRAME_HEIGHT,
        )
    }

    /// The frame at `width × height` pixels.
    pub fn sized(width: u32, height: u32) -> UrpFrame {
        let mut geometry = FrameScene::sized(width, height);
        geometry.transparent.clear();
        geometry.sky = None;
        let s = &geometry.scene;
        let lighting = UrpLighting {
            camera_position: s.camera_position,
            sh_r: s.sh_r,
            sh_g: s.sh_g,
            sh_b: s.sh_b,
            main_light_dir: s.light_dir,
            main_light_color: s.light_color,
            // The G-buffer pass reads these for mixed lighting only (none in this frame).
            shadow_attenuation: 1.0,
            shadow_strength: 1.0,
            subtractive_shadow_color: Vec3::ZERO,
            glossy_environment_color: Vec3::new(0.3, 0.25, 0.2),
            probes_occlusion: Vec4::ONE,
        };
        let params = |light: Light, inner: f32, mask: u32| {
            UrpLight::new(light, inner, mask)
                .params()
                .expect("the URP frame's lights are valid")
        };
        let sun = Light::directional(-s.light_dir, s.light_color);
        let main_light = params(sun, 0.0, EVERY_LAYER);
        // The built-in frame's point and spot lights (its cookie sun is a directional light,
        // which URP's additional lights in the forward path are not).
        let from = |name: &'static str, i: usize, inner: f32, mask: u32| {
            let light = geometry.lights[i].light;
            UrpFrameLight {
                name,
                light,
                params: params(light, inner, mask),
            }
        };
        let lights = vec![
            from("warm point (default layer only)", 0, 0.0, DEFAULT_LAYER),
            from("cool point", 2, 0.0, EVERY_LAYER),
            from("spot", 3, 36.0, EVERY_LAYER),
        ];
        // A soft shadow in four cascades of 512² over the built-in frame's splits (each
        // cascade holds part of the visible surfaces), URP's split spheres picking them; URP's
        // caster biases (about two texels of the widest cascade); faded out between 9 units
        // from the camera and the shadow distance, 12, where the last cascade ends.
        let main_shadow = Some(UrpShadowSpec {
            strength: 0.9,
            soft: true,
            bias: Vec2::new(-0.04, -0.06),
            center: Vec3::new(0.4, 0.5, -1.0),
            radius: 7.0,
            cascade_splits: Some(geometry.cascade_splits.clone()),
            screen: false,
            fade: UrpShadowFade::between(9.0, 12.0),
        });
        // The cool point light (hard, six cube-face slices: the glowing sphere's and the cutout
        // box's shadows, the box's with its holes) and the spot (soft) cast; the warm point
        // light casts none. 256² slices; URP's caster biases (a few texels where the slices
        // are widest); faded as the main light's.
        let additional_shadows = Some(UrpAdditionalShadowSpec {
            casting: vec![None, Some((0.9, false)), Some((0.85, true))],
            bias: Vec2::new(-0.05, -0.08),
            fade: UrpShadowFade::between(9.0, 12.0),
        });
        // Cookies: the main light's 4 × 4 pattern fitted around what the camera sees (every
        // fourth pixel's surface), so its edges cross the frame; the cool point light's and
        // the spot's rects of the lighting checks' atlas; the warm point light has none.
        let seen: Vec<Vec3> = geometry
            .pixels()
            .filter(|(x, y)| x % 4 == 0 && y % 4 == 0)
            .filter_map(|(x, y)| geometry.cast(f64::from(x) + 0.5, f64::from(y) + 0.5))
            .map(|hit| hit.geometry.world_position)
            .collect();
        let what = "the URP frame";
        let cookies = Some(UrpFrameCookies {
            main: main_light_cookie(&sun, &seen, what).expect("the URP frame's cookie fits"),
            additional: additional_light_cookies(
                &[None, Some(&lights[1].light), Some(&lights[2].light)],
                what,
            )
            .expect("the URP frame's lights take cookies"),
        });
        let occlusion = Some(ScreenOcclusion::new(width, height));
        UrpFrame {
            objects: materials(),
            geometry,
            lighting,
            main_light,
            lights,
            main_shadow,
            additional_shadows,
            cookies,
            occlusion,
        }
    }

    /// `_SCREEN_SPACE_OCCLUSION` where the frame has an SSAO texture.
    pub fn occlusion_keywords(&self) -> Vec<&'static str> {
        match self.occlusion {
            Some(_) => vec!["_SCREEN_SPACE_OCCLUSION"],
            None => Vec::new(),
        }
    }

    /// The SSAO texture's bindings (26-27), none without one.
    pub fn occlusion_resources(&self) -> Vec<BoundResource> {
        self.occlusion
            .as_ref()
            .map(ScreenOcclusion::resources)
            .unwrap_or_default()
    }

    /// The occlusion factors at pixel `(x, y)` (none without an SSAO texture).
    pub fn occlusion_at(&self, x: u32, y: u32) -> AmbientOcclusionFactor {
        self.occlusion
            .as_ref()
            .map_or(AmbientOcclusionFactor::NONE, |o| o.factor(x, y))
    }

    /// The passes' cookie keyword: `_LIGHT_COOKIES` where the frame's lights have cookies.
    pub fn cookie_keywords(&self) -> Vec<&'static str> {
        match self.cookies {
            Some(_) => vec!["_LIGHT_COOKIES"],
            None => Vec::new(),
        }
    }

    /// The forward pass's cookie bindings (`universal/light_cookie`'s 20-25): the main light's
    /// cookie and the additional lights' atlas; none without cookies.
    pub fn cookie_resources(&self) -> Vec<BoundResource> {
        let mut out = Vec::new();
        if let Some(c) = &self.cookies {
            out.extend(main_resources(&c.main));
            out.extend(atlas_resources(&c.additional));
        }
        out
    }

    /// Each light's cookie as its deferred draw binds it: the main light's first, then each
    /// additional light's (`None`: the light has no cookie, and its pass no `_LIGHT_COOKIES`).
    pub(crate) fn draw_cookies(&self) -> Vec<Option<DrawCookie<'_>>> {
        let mut out = vec![self.cookies.as_ref().map(|c| DrawCookie::Main(&c.main))];
        out.extend((0..self.lights.len()).map(|k| {
            self.cookies.as_ref().and_then(|c| {
                c.additional.lights.get(k).copied().flatten()?;
                Some(DrawCookie::Additional(&c.additional, k as u32))
            })
        }));
        out
    }

    /// The cookie tints the forward pass may apply at `p`: one per texel of the main light's
    /// cookie it may read there, each with the additional lights' cookies at the lower
    /// (`end` 0) or upper (1) end of their ranges; white alone without cookies.
    pub fn cookie_tints(&self, p: Vec3, end: usize) -> Vec<CookieTints> {
        match &self.cookies {
            Some(c) => CookieTints::candidates(&c.main, &c.additional, self.lights.len(), p, end),
            None => vec![CookieTints::WHITE],
        }
    }

    /// The additional lights as the forward pass reads them.
    ///
    /// # Errors
    /// [`GpuError::Check`] when the lights are more than URP's eight or one is directional.
    pub fn forward_lights(&self) -> Result<UrpForwardLights, GpuError> {
        let additional = self.lights.iter().map(|l| l.params).collect();
        UrpForwardLights::new(self.main_light.layer_mask, additional).map_err(|e: LightError| {
            GpuError::from(CheckError::UnknownToReference {
                variant: "the URP frame".to_owned(),
                message: e.to_string(),
            })
        })
    }

    /// The environment cube (the built-in frame's first probe cube; faces of one colour each).
    pub fn environment(&self) -> &CubeFaces {
        &self.geometry.scene.cubes[0]
    }

    /// Object `o`'s material keywords as the reference reads them.
    pub fn surface_keywords(&self, o: usize, pass_keywords: &[&str]) -> UrpKeywords {
        let mut names: Vec<&str> = self.objects[o].keywords.to_vec();
        names.extend(pass_keywords);
        UrpKeywords::from_names(&names).expect("the URP frame's keywords are URP Lit's")
    }

    /// Object `o`'s texels: the built-in object's one texel per map.
    pub fn texels(&self, o: usize) -> UrpTexels {
        let t = self.geometry.objects[o].reference_texels();
        UrpTexels {
            base_map: t.main_tex,
            bump_map: t.normal_map,
            metallic_gloss_map: t.metallic_map,
            occlusion_map: t.occlusion_map,
            emission_map: t.emission_map,
            ..UrpTexels::default()
        }
    }

    /// The per-pixel inputs of object `o` at `geometry`.
    pub fn pixel(
        &self,
        o: usize,
        geometry: wgsl_variants_shaders::reference::surface::Geometry,
    ) -> UrpPixel {
        UrpPixel {
            geometry,
            depth: 0.0,
            rendering_layers: self.objects[o].rendering_layers,
        }
    }

    /// Every binding of `wgsl/universal/bindings.wgsl` for object `o` (a variant binds those
    /// it uses), plus the forward pass's `forward_lights` (group 0, binding 4).
    ///
    /// # Errors
    /// As [`UrpFrame::forward_lights`].
    pub fn object_resources(&self, o: usize) -> Result<Vec<BoundResource>, GpuError> {
        let object: &FrameObject = &self.geometry.objects[o];
        let urp = &self.objects[o];
        let camera = camera_uniform(self.geometry.view_proj, &self.lighting);
        let lighting = lighting_uniform(&self.lighting);
        let material = material_uniform(&urp.material);
        // One lightmap texel: any scale and offset read it.
        let uniform = object_uniform(
            object.model,
            object.normal_matrix(),
            Vec4::new(1.0, 1.0, 0.0, 0.0),
            urp.rendering_layers,
        );
        let maps = object.maps();
        Ok(vec![
            BoundResource::new(0, 0, Resource::Uniform(camera)),
            BoundResource::new(0, 1, Resource::Uniform(lighting)),
            BoundResource::new(0, 2, cube_resource(self.environment())),
            BoundResource::new(0, 3, Resource::Sampler { nearest: true }),
            BoundResource::new(0, 4, Resource::Uniform(self.forward_lights()?.uniform())),
            BoundResource::new(1, 0, Resource::Uniform(material)),
            BoundResource::new(
                1,
                1,
                Resource::SamplerAddressed {
                    nearest: true,
                    address_mode: wgpu::AddressMode::Repeat,
                },
            ),
            BoundResource::new(1, 2, maps.main_tex.resource()),
            BoundResource::new(1, 3, maps.normal_map.resource()),
            BoundResource::new(1, 4, maps.metallic_map.resource()),
            BoundResource::new(1, 5, maps.occlusion_map.resource()),
            BoundResource::new(1, 6, maps.emission_map.resource()),
            BoundResource::new(2, 0, Resource::Uniform(uniform)),
        ])
    }
}

impl Default for UrpFrame {
    fn default() -> Self {
        UrpFrame::new()
    }
}
