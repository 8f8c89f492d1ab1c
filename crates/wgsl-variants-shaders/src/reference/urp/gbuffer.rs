//! What URP Lit's `UniversalGBuffer` fragment writes per texel (docs/urp.md §1–§4 and §8):
//! the surface inputs (URP's `InitializeStandardLitSurfaceData`), the BRDF data
//! (`InitializeBRDFData`), baked GI and the environment reflection (`GlobalIllumination`),
//! packed by `BRDFDataToGbuffer` into GBuffer0–3 and the optional targets.
//!
//! [`shade_gbuffer`] gives the values the shader writes (before the targets store them);
//! [`UrpGBufferOutput::texels`] lists them per target with how each target stores them
//! ([`UrpTexel`]), which [`crate::reference::tolerance::urp_texel_within`] compares with the
//! bytes read back.
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::cube::CubeFaces;
//! use wgsl_variants_shaders::reference::surface::Geometry;
//! use wgsl_variants_shaders::reference::urp::gbuffer::*;
//! let kw = UrpKeywords::from_names(&["_SPECULARHIGHLIGHTS_OFF", "_WRITE_RENDERING_LAYERS"]).unwrap();
//! let geo = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::new(1.0, 0.0, 0.0, 1.0) };
//! let pixel = UrpPixel { geometry: geo, depth: 0.5, rendering_layers: 0x8000_0001 };
//! let env = CubeFaces::uniform(Vec4::ZERO);
//! let out = shade_gbuffer(&kw, &UrpMaterial::default(), &UrpTexels::default(), &pixel,
//!     &UrpLighting::default(), &env).unwrap();
//! assert_eq!(out.gbuffer0.w, 2.0 / 255.0);              // flags: SpecularHighlightsOff
//! assert_eq!(out.gbuffer1.truncate(), Vec3::ZERO);      // no specular written
//! assert_eq!(out.rendering_layers, Some(0x8000_0001));
//! assert_eq!(out.texels(&kw).len(), 5);                 // GBuffer0–3 + rendering layers
//! ```

use glam::{Vec3, Vec4};

use super::flags::MaterialFlags;
use super::normal::encode_normal_oct;
use super::workflow::{DIELECTRIC_SPEC, ONE_MINUS_DIELECTRIC_SPEC};
use crate::reference::cube::CubeFaces;
use crate::reference::surface::{Geometry, KeywordsError, reflect};

/// The keywords of `universal_lit/UniversalGBuffer`, in declaration order.
pub const URP_KEYWORD_NAMES: [&str; 16] = [
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
    "_GBUFFER_NORMALS_OCT",
    "_RENDER_PASS_ENABLED",
    "_WRITE_RENDERING_LAYERS",
    "_MIXED_LIGHTING_SUBTRACTIVE",
    "SHADOWS_SHADOWMASK",
    "LIGHTMAP_ON",
];

/// The keyword set of one `UniversalGBuffer` variant, one flag per keyword of
/// [`URP_KEYWORD_NAMES`] (in that order).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct UrpKeywords(pub [bool; 16]);

/// Indices into [`UrpKeywords`].
pub mod kw {
    /// `_NORMALMAP`.
    pub const NORMALMAP: usize = 0;
    /// `_ALPHATEST_ON`.
    pub const ALPHATEST_ON: usize = 1;
    /// `_EMISSION`.
    pub const EMISSION: usize = 2;
    /// `_METALLICSPECGLOSSMAP`.
    pub const METALLICSPECGLOSSMAP: usize = 3;
    /// `_SPECULAR_SETUP`.
    pub const SPECULAR_SETUP: usize = 4;
    /// `_OCCLUSIONMAP`.
    pub const OCCLUSIONMAP: usize = 5;
    /// `_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A`.
    pub const SMOOTHNESS_ALBEDO_A: usize = 6;
    /// `_RECEIVE_SHADOWS_OFF`.
    pub const RECEIVE_SHADOWS_OFF: usize = 7;
    /// `_SPECULARHIGHLIGHTS_OFF`.
    pub const SPECULARHIGHLIGHTS_OFF: usize = 8;
    /// `_ENVIRONMENTREFLECTIONS_OFF`.
    pub const ENVIRONMENTREFLECTIONS_OFF: usize = 9;
    /// `_GBUFFER_NORMALS_OCT`.
    pub const GBUFFER_NORMALS_OCT: usize = 10;
    /// `_RENDER_PASS_ENABLED`.
    pub const RENDER_PASS_ENABLED: usize = 11;
    /// `_WRITE_RENDERING_LAYERS`.
    pub const WRITE_RENDERING_LAYERS: usize = 12;
    /// `_MIXED_LIGHTING_SUBTRACTIVE`.
    pub const MIXED_LIGHTING_SUBTRACTIVE: usize = 13;
    /// `SHADOWS_SHADOWMASK`.
    pub const SHADOWS_SHADOWMASK: usize = 14;
    /// `LIGHTMAP_ON`.
    pub const LIGHTMAP_ON: usize = 15;
}

impl UrpKeywords {
    /// The keyword set of these names (underscore-only names, the "off" option, are
    /// skipped); a name the pass does not declare is [`KeywordsError::Unknown`].
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::gbuffer::{kw, UrpKeywords};
    /// let k = UrpKeywords::from_names(&["_", "LIGHTMAP_ON"]).unwrap();
    /// assert!(k.on(kw::LIGHTMAP_ON) && !k.on(kw::NORMALMAP));
    /// assert!(UrpKeywords::from_names(&["_NORMAL_MAP"]).is_err());
    /// ```
    pub fn from_names(names: &[&str]) -> Result<UrpKeywords, KeywordsError> {
        let mut k = UrpKeywords::default();
        for &name in names {
            if !name.is_empty() && name.bytes().all(|b| b == b'_') {
                continue;
            }
            let i = URP_KEYWORD_NAMES
                .iter()
                .position(|&n| n == name)
                .ok_or_else(|| KeywordsError::Unknown(name.to_owned()))?;
            k.0[i] = true;
        }
        Ok(k)
    }

    /// Whether keyword `i` (an index of [`kw`]) is on.
    pub fn on(&self, i: usize) -> bool {
        self.0[i]
    }

    /// Whether the variant writes the shadowmask target (URP's `OUTPUT_SHADOWMASK`,
    /// docs/urp.md §1): under `SHADOWS_SHADOWMASK`, and under subtractive mixed lighting
    /// without a lightmap (a dynamic object then stores its probe occlusion).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::gbuffer::UrpKeywords;
    /// let k = |n: &[&str]| UrpKeywords::from_names(n).unwrap().writes_shadow_mask();
    /// assert!(k(&["SHADOWS_SHADOWMASK"]) && k(&["SHADOWS_SHADOWMASK", "LIGHTMAP_ON"]));
    /// assert!(k(&["_MIXED_LIGHTING_SUBTRACTIVE"]));
    /// assert!(!k(&["_MIXED_LIGHTING_SUBTRACTIVE", "LIGHTMAP_ON"]) && !k(&[]));
    /// ```
    pub fn writes_shadow_mask(&self) -> bool {
        self.on(kw::SHADOWS_SHADOWMASK)
            || (self.on(kw::MIXED_LIGHTING_SUBTRACTIVE) && !self.on(kw::LIGHTMAP_ON))
    }

    /// The material flags the variant writes (docs/urp.md §2).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::gbuffer::UrpKeywords;
    /// let k = UrpKeywords::from_names(&["_MIXED_LIGHTING_SUBTRACTIVE"]).unwrap();
    /// assert_eq!(k.flags().to_byte(), 0); // subtractive only with LIGHTMAP_ON
    /// ```
    pub fn flags(&self) -> MaterialFlags {
        MaterialFlags {
            receive_shadows_off: self.on(kw::RECEIVE_SHADOWS_OFF),
            specular_highlights_off: self.on(kw::SPECULARHIGHLIGHTS_OFF),
            subtractive_mixed_lighting: self.on(kw::LIGHTMAP_ON)
                && self.on(kw::MIXED_LIGHTING_SUBTRACTIVE),
            specular_setup: self.on(kw::SPECULAR_SETUP),
        }
    }
}

/// URP Lit's material properties (`wgsl/universal/bindings.wgsl`'s `Material`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpMaterial {
    /// `_BaseColor`.
    pub base_color: Vec4,
    /// `_SpecColor` (rgb).
    pub spec_color: Vec3,
    /// `_EmissionColor` (rgb).
    pub emission_color: Vec3,
    /// `_Metallic`.
    pub metallic: f32,
    /// `_Smoothness`.
    pub smoothness: f32,
    /// `_Cutoff`.
    pub cutoff: f32,
    /// `_BumpScale`.
    pub bump_scale: f32,
    /// `_OcclusionStrength`.
    pub occlusion_strength: f32,
}

impl Default for UrpMaterial {
    /// URP Lit's defaults: white, `_SpecColor` 0.2 grey, no emission, metallic 0,
    /// smoothness 0.5, cutoff 0.5, bump scale 1, occlusion strength 1.
    fn default() -> UrpMaterial {
        UrpMaterial {
            base_color: Vec4::ONE,
            spec_color: Vec3::splat(0.2),
            emission_color: Vec3::ZERO,
            metallic: 0.0,
            smoothness: 0.5,
            cutoff: 0.5,
            bump_scale: 1.0,
            occlusion_strength: 1.0,
        }
    }
}

/// The texels one pixel reads, as the shader sees them (after the texture format's decode).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpTexels {
    /// `_BaseMap`.
    pub base_map: Vec4,
    /// `_BumpMap` (`_NORMALMAP`).
    pub bump_map: Vec4,
    /// `_MetallicGlossMap` / `_SpecGlossMap` (`_METALLICSPECGLOSSMAP`).
    pub metallic_gloss_map: Vec4,
    /// `_OcclusionMap` (`_OCCLUSIONMAP`; g is read).
    pub occlusion_map: Vec4,
    /// `_EmissionMap` (`_EMISSION`).
    pub emission_map: Vec4,
    /// The lightmap texel (`LIGHTMAP_ON`), linear.
    pub lightmap: Vec3,
    /// The baked shadowmask texel (`SHADOWS_SHADOWMASK` with `LIGHTMAP_ON`).
    pub shadowmask: Vec4,
}

impl Default for UrpTexels {
    /// White maps, a flat normal, no light in the lightmap, an unshadowed mask.
    fn default() -> UrpTexels {
        UrpTexels {
            base_map: Vec4::ONE,
            bump_map: Vec4::new(0.5, 0.5, 1.0, 1.0),
            metallic_gloss_map: Vec4::ONE,
            occlusion_map: Vec4::ONE,
            emission_map: Vec4::ONE,
            lightmap: Vec3::ZERO,
            shadowmask: Vec4::ONE,
        }
    }
}

/// The per-frame inputs of the pass (`wgsl/universal/bindings.wgsl`'s `Lighting` and the
/// camera position).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpLighting {
    /// World position of the camera.
    pub camera_position: Vec3,
    /// `unity_SHAr`.
    pub sh_r: Vec4,
    /// `unity_SHAg`.
    pub sh_g: Vec4,
    /// `unity_SHAb`.
    pub sh_b: Vec4,
    /// Direction to the main light.
    pub main_light_dir: Vec3,
    /// The main light's colour.
    pub main_light_color: Vec3,
    /// The main light's realtime shadow attenuation at the object (a stand-in for a
    /// shadow-map sample).
    pub shadow_attenuation: f32,
    /// The main light's shadow strength.
    pub shadow_strength: f32,
    /// `_SubtractiveShadowColor`.
    pub subtractive_shadow_color: Vec3,
    /// `_GlossyEnvironmentColor`.
    pub glossy_environment_color: Vec3,
    /// `unity_ProbesOcclusion`.
    pub probes_occlusion: Vec4,
}

impl Default for UrpLighting {
    /// Camera at (0, 0, 5), no ambient or main light, unshadowed, black environment colour.
    fn default() -> UrpLighting {
        UrpLighting {
            camera_position: Vec3::new(0.0, 0.0, 5.0),
            sh_r: Vec4::ZERO,
            sh_g: Vec4::ZERO,
            sh_b: Vec4::ZERO,
            main_light_dir: Vec3::Y,
            main_light_color: Vec3::ZERO,
            shadow_attenuation: 1.0,
            shadow_strength: 1.0,
            subtractive_shadow_color: Vec3::ZERO,
            glossy_environment_color: Vec3::ZERO,
            probes_occlusion: Vec4::ONE,
        }
    }
}

/// The per-pixel inputs: interpolated geometry, the fragment's depth and the mesh's
/// rendering-layer mask.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpPixel {
    /// World position, vertex normal and tangent.
    pub geometry: Geometry,
    /// The fragment's depth (`position.z`).
    pub depth: f32,
    /// The rendering-layer mask.
    pub rendering_layers: u32,
}

/// URP's surface data of one pixel (`SurfaceData`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpSurface {
    /// Base albedo (linear).
    pub albedo: Vec3,
    /// Alpha (the cutoff's operand).
    pub alpha: f32,
    /// Metallic (1 in the specular workflow).
    pub metallic: f32,
    /// Specular colour (specular workflow; else 0).
    pub specular: Vec3,
    /// Smoothness.
    pub smoothness: f32,
    /// Occlusion.
    pub occlusion: f32,
    /// Emission.
    pub emission: Vec3,
    /// Tangent-space normal (`UnpackNormalRGB` scaled, not normalized).
    pub normal_ts: Vec3,
}

/// `InitializeStandardLitSurfaceData` under the keywords; `None` where `_ALPHATEST_ON`
/// discards (`alpha < cutoff`).
pub fn urp_surface(k: &UrpKeywords, mat: &UrpMaterial, tex: &UrpTexels) -> Option<UrpSurface> {
    let albedo = tex.base_map.truncate() * mat.base_color.truncate();
    let alpha = if k.on(kw::SMOOTHNESS_ALBEDO_A) {
        mat.base_color.w
    } else {
        tex.base_map.w * mat.base_color.w
    };
    if k.on(kw::ALPHATEST_ON) && alpha < mat.cutoff {
        return None;
    }
    let gloss_source = if k.on(kw::SMOOTHNESS_ALBEDO_A) {
        tex.base_map.w
    } else if k.on(kw::METALLICSPECGLOSSMAP) {
        tex.metallic_gloss_map.w
    } else {
        1.0
    };
    let spec_gloss = if k.on(kw::METALLICSPECGLOSSMAP) {
        tex.metallic_gloss_map.truncate()
    } else if k.on(kw::SPECULAR_SETUP) {
        mat.spec_color
    } else {
        Vec3::splat(mat.metallic)
    };
    let (metallic, specular) = if k.on(kw::SPECULAR_SETUP) {
        (1.0, spec_gloss)
    } else {
        (spec_gloss.x, Vec3::ZERO)
    };
    let occlusion = if k.on(kw::OCCLUSIONMAP) {
        1.0 + (tex.occlusion_map.y - 1.0) * mat.occlusion_strength
    } else {
        1.0
    };
    let emission = if k.on(kw::EMISSION) {
        tex.emission_map.truncate() * mat.emission_color
    } else {
        Vec3::ZERO
    };
    let normal_ts = if k.on(kw::NORMALMAP) {
        let p = tex.bump_map.truncate() * 2.0 - 1.0;
        Vec3::new(p.x * mat.bump_scale, p.y * mat.bump_scale, p.z)
    } else {
        Vec3::Z
    };
    Some(UrpSurface {
        albedo,
        alpha,
        metallic,
        specular,
        smoothness: gloss_source * mat.smoothness,
        occlusion,
        emission,
        normal_ts,
    })
}

/// URP's BRDF data (`InitializeBRDFData`) of a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpBrdf {
    /// Diffuse colour.
    pub diffuse: Vec3,
    /// Specular colour.
    pub specular: Vec3,
    /// Reflectivity (GBuffer1.r in the metallic workflow).
    pub reflectivity: f32,
    /// `1 − smoothness`.
    pub perceptual_roughness: f32,
    /// `max(roughness², 2^-14)` with `roughness = max(pr², 2^-7)`.
    pub roughness2: f32,
    /// `saturate(smoothness + reflectivity)`.
    pub grazing: f32,
}

/// `InitializeBRDFData`: metallic `reflectivity = 1 − 0.96 · (1 − metallic)`, diffuse
/// `albedo · 0.96 · (1 − metallic)`, specular `mix(0.04, albedo, metallic)`; specular setup
/// `reflectivity = max(specular)`, diffuse `albedo · (1 − reflectivity)` (current URP's
/// `BRDF.hlsl`; older releases used `albedo · (1 − specular)` per channel).
pub fn urp_brdf(k: &UrpKeywords, s: &UrpSurface) -> UrpBrdf {
    let (diffuse, specular, reflectivity) = if k.on(kw::SPECULAR_SETUP) {
        let reflectivity = s.specular.max_element();
        (s.albedo * (1.0 - reflectivity), s.specular, reflectivity)
    } else {
        let one_minus = ONE_MINUS_DIELECTRIC_SPEC * (1.0 - s.metallic);
        (
            s.albedo * one_minus,
            Vec3::splat(DIELECTRIC_SPEC).lerp(s.albedo, s.metallic),
            1.0 - one_minus,
        )
    };
    let perceptual_roughness = 1.0 - s.smoothness;
    let roughness = (perceptual_roughness * perceptual_roughness).max(2f32.powi(-7));
    UrpBrdf {
        diffuse,
        specular,
        reflectivity,
        perceptual_roughness,
        roughness2: (roughness * roughness).max(2f32.powi(-14)),
        grazing: (s.smoothness + reflectivity).clamp(0.0, 1.0),
    }
}

/// The world normal: `normalize(T·t.x + B·t.y + N·t.z)` with `B = cross(N, T) · w` under
/// `_NORMALMAP`, else `normalize(N)` (N and T normalized as the vertex stage does).
pub fn urp_world_normal(k: &UrpKeywords, normal_ts: Vec3, geo: &Geometry) -> Vec3 {
    let n = geo.normal.normalize();
    if !k.on(kw::NORMALMAP) {
        return n;
    }
    let t = geo.tangent.truncate().normalize();
    let b = n.cross(t) * geo.tangent.w;
    (t * normal_ts.x + b * normal_ts.y + n * normal_ts.z).normalize()
}

/// Baked GI: the lightmap texel with `LIGHTMAP_ON` (minus the main light's estimated
/// contribution where shadowed, with `_MIXED_LIGHTING_SUBTRACTIVE`: URP's
/// `SubtractDirectMainLightFromLightmap`), else `max(0, L0 + L1)` spherical harmonics.
/// `shadow` is the main light's realtime shadow attenuation at the pixel and `strength` the
/// shadow's strength (the subtraction's `mix(gi, max(subtracted, shadow colour), strength)`).
pub fn urp_baked_gi(
    k: &UrpKeywords,
    tex: &UrpTexels,
    light: &UrpLighting,
    n: Vec3,
    shadow: f32,
    strength: f32,
) -> Vec3 {
    if !k.on(kw::LIGHTMAP_ON) {
        let n1 = n.extend(1.0);
        return Vec3::new(light.sh_r.dot(n1), light.sh_g.dot(n1), light.sh_b.dot(n1))
            .max(Vec3::ZERO);
    }
    let gi = tex.lightmap;
    if !k.on(kw::MIXED_LIGHTING_SUBTRACTIVE) {
        return gi;
    }
    let lambert = light.main_light_color * light.main_light_dir.dot(n).clamp(0.0, 1.0);
    let subtracted = gi - lambert * (1.0 - shadow);
    let realtime = gi.lerp(subtracted.max(light.subtractive_shadow_color), strength);
    gi.min(realtime)
}

/// The G-buffer pass's main-light shadow attenuation: 1 with `_RECEIVE_SHADOWS_OFF` (URP's
/// `MainLightRealtimeShadow`), else the scene's stand-in [`UrpLighting::shadow_attenuation`].
pub fn gbuffer_main_light_shadow(k: &UrpKeywords, light: &UrpLighting) -> f32 {
    if k.on(kw::RECEIVE_SHADOWS_OFF) {
        1.0
    } else {
        light.shadow_attenuation
    }
}

/// URP's `GlobalIllumination`: `(baked · diffuse + env · surfaceReduction ·
/// mix(specular, grazing, (1 − N·V)^4)) · occlusion` with `surfaceReduction = 1 / (r² + 1)`;
/// `env` is the environment cube's colour in the reflected direction (uniform faces, so the
/// mip level does not matter), or `_GlossyEnvironmentColor` with
/// `_ENVIRONMENTREFLECTIONS_OFF`.
#[allow(clippy::too_many_arguments)]
pub fn global_illumination(
    k: &UrpKeywords,
    b: &UrpBrdf,
    baked: Vec3,
    n: Vec3,
    v: Vec3,
    occlusion: f32,
    light: &UrpLighting,
    env: &CubeFaces,
) -> Vec3 {
    let fresnel = (1.0 - n.dot(v).clamp(0.0, 1.0)).powi(4);
    let environment = if k.on(kw::ENVIRONMENTREFLECTIONS_OFF) {
        light.glossy_environment_color
    } else {
        env.sample(reflect(-v, n)).truncate()
    };
    let surface_reduction = 1.0 / (b.roughness2 + 1.0);
    (baked * b.diffuse
        + environment * surface_reduction * b.specular.lerp(Vec3::splat(b.grazing), fresnel))
        * occlusion
}

/// What the fragment writes, before the targets store it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpGBufferOutput {
    /// GBuffer0: linear albedo, flags / 255.
    pub gbuffer0: Vec4,
    /// GBuffer1: specular colour or `(reflectivity, 0, 0)` (0 with
    /// `_SPECULARHIGHLIGHTS_OFF`), occlusion.
    pub gbuffer1: Vec4,
    /// The unit world normal GBuffer2 encodes.
    pub normal: Vec3,
    /// GBuffer2.a: smoothness.
    pub smoothness: f32,
    /// GBuffer3: emission + GI · occlusion.
    pub gbuffer3: Vec3,
    /// Depth as colour (`_RENDER_PASS_ENABLED`).
    pub depth_as_color: Option<f32>,
    /// Shadowmask ([`UrpKeywords::writes_shadow_mask`]): the baked texel with `LIGHTMAP_ON`
    /// (and `SHADOWS_SHADOWMASK`), else `unity_ProbesOcclusion`.
    pub shadow_mask: Option<Vec4>,
    /// Rendering layers (`_WRITE_RENDERING_LAYERS`).
    pub rendering_layers: Option<u32>,
}

/// The `UniversalGBuffer` fragment at one pixel; `None` where `_ALPHATEST_ON` discards.
/// `env` is the environment cube (uniform faces, so the mip level does not matter).
pub fn shade_gbuffer(
    k: &UrpKeywords,
    mat: &UrpMaterial,
    tex: &UrpTexels,
    pixel: &UrpPixel,
    light: &UrpLighting,
    env: &CubeFaces,
) -> Option<UrpGBufferOutput> {
    let s = urp_surface(k, mat, tex)?;
    let b = urp_brdf(k, &s);
    let n = urp_world_normal(k, s.normal_ts, &pixel.geometry);
    let v = (light.camera_position - pixel.geometry.world_position).normalize();
    let shadow = gbuffer_main_light_shadow(k, light);
    let baked = urp_baked_gi(k, tex, light, n, shadow, light.shadow_strength);
    let gi = global_illumination(k, &b, baked, n, v, s.occlusion, light, env);
    let packed_specular = if k.on(kw::SPECULARHIGHLIGHTS_OFF) {
        Vec3::ZERO
    } else if k.on(kw::SPECULAR_SETUP) {
        b.specular
    } else {
        Vec3::new(b.reflectivity, 0.0, 0.0)
    };
    Some(UrpGBufferOutput {
        gbuffer0: s.albedo.extend(k.flags().pack()),
        gbuffer1: packed_specular.extend(s.occlusion),
        normal: n,
        smoothness: s.smoothness,
        gbuffer3: s.emission + gi,
        depth_as_color: k.on(kw::RENDER_PASS_ENABLED).then_some(pixel.depth),
        shadow_mask: k.writes_shadow_mask().then(|| {
            if k.on(kw::LIGHTMAP_ON) {
                tex.shadowmask
            } else {
                light.probes_occlusion
            }
        }),
        rendering_layers: k
            .on(kw::WRITE_RENDERING_LAYERS)
            .then_some(pixel.rendering_layers),
    })
}

/// One target's expected texel and how the target stores it (what
/// [`crate::reference::tolerance::urp_texel_within`] compares the read-back bytes with).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UrpTexel {
    /// `Rgba8UnormSrgb`: linear rgb (sRGB-encoded by the target), linear alpha.
    Srgb8(Vec4),
    /// `Rgba8Unorm`.
    Unorm8(Vec4),
    /// `Rgba8Unorm` holding an octahedral normal's three bytes ([`encode_normal_oct`]) and
    /// the smoothness in alpha.
    OctNormal {
        /// The three bytes of the reference normal.
        bytes: [u8; 3],
        /// Alpha.
        smoothness: f32,
    },
    /// `Rgba8Snorm`.
    Snorm8(Vec4),
    /// `Rg11b10Ufloat`.
    Ufloat(Vec3),
    /// `Rg11b10Ufloat` where the reference allows any value between two (per channel, either
    /// order): a shadow-map tap within a hair of flipping (the forward pass's main light).
    UfloatBetween(Vec3, Vec3),
    /// `R32Float`.
    F32(f32),
    /// `R32Uint`.
    U32(u32),
}

impl UrpTexel {
    /// The expected value as floats, for reports: the linear values the shader wrote
    /// (octahedral bytes as `byte / 255`, snorm normals as written).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::gbuffer::UrpTexel;
    /// assert_eq!(UrpTexel::U32(7).to_vec(), vec![7.0]);
    /// ```
    pub fn to_vec(&self) -> Vec<f32> {
        match *self {
            UrpTexel::Srgb8(v) | UrpTexel::Unorm8(v) | UrpTexel::Snorm8(v) => v.to_array().to_vec(),
            UrpTexel::OctNormal { bytes, smoothness } => {
                let mut out: Vec<f32> = bytes.iter().map(|&b| f32::from(b) / 255.0).collect();
                out.push(smoothness);
                out
            }
            UrpTexel::Ufloat(v) => v.to_array().to_vec(),
            UrpTexel::UfloatBetween(a, b) => a.to_array().into_iter().chain(b.to_array()).collect(),
            UrpTexel::F32(x) => vec![x],
            UrpTexel::U32(x) => vec![x as f32],
        }
    }
}

impl UrpGBufferOutput {
    /// The expected texel of every target the variant writes, in location order (docs/urp.md
    /// §1): GBuffer0–3, depth as colour, rendering layers, shadowmask.
    pub fn texels(&self, k: &UrpKeywords) -> Vec<UrpTexel> {
        let gbuffer2 = if k.on(kw::GBUFFER_NORMALS_OCT) {
            UrpTexel::OctNormal {
                bytes: encode_normal_oct(self.normal),
                smoothness: self.smoothness,
            }
        } else {
            UrpTexel::Snorm8(self.normal.extend(self.smoothness))
        };
        let mut out = vec![
            UrpTexel::Srgb8(self.gbuffer0),
            UrpTexel::Unorm8(self.gbuffer1),
            gbuffer2,
            UrpTexel::Ufloat(self.gbuffer3),
        ];
        out.extend(self.depth_as_color.map(UrpTexel::F32));
        out.extend(self.rendering_layers.map(UrpTexel::U32));
        out.extend(self.shadow_mask.map(UrpTexel::Unorm8));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pixel() -> UrpPixel {
        UrpPixel {
            geometry: Geometry {
                world_position: Vec3::ZERO,
                normal: Vec3::Z,
                tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
            },
            depth: 0.5,
            rendering_layers: 5,
        }
    }

    #[test]
    fn metallic_workflow_on_paper() {
        // metallic 0.25: reflectivity = 1 − 0.96 · 0.75 = 0.28; GBuffer1 = (0.28, 0, 0, 1).
        let mat = UrpMaterial {
            metallic: 0.25,
            ..UrpMaterial::default()
        };
        let out = shade_gbuffer(
            &UrpKeywords::default(),
            &mat,
            &UrpTexels::default(),
            &pixel(),
            &UrpLighting::default(),
            &CubeFaces::uniform(Vec4::ZERO),
        )
        .unwrap();
        assert!((out.gbuffer1.x - 0.28).abs() < 1e-6);
        assert_eq!(out.gbuffer1.w, 1.0);
        assert_eq!(out.gbuffer0, Vec4::new(1.0, 1.0, 1.0, 0.0));
        assert_eq!(out.normal, Vec3::Z);
    }

    #[test]
    fn ambient_and_environment_on_paper() {
        // Normal +Z seen head on: N·V = 1, fresnel 0. SH: L0 = 0.5 on every channel and
        // L1 z = 0.25 -> gi = 0.75. Metallic 0, albedo 1: diffuse 0.96, specular 0.04.
        // Smoothness 0.5: pr = 0.5, roughness = 0.25, roughness² = 0.0625, reduction
        // 1 / 1.0625. Environment 1: 0.75 · 0.96 + 0.04 / 1.0625 = 0.72 + 0.0376471 = 0.7576471.
        let light = UrpLighting {
            sh_r: Vec4::new(0.0, 0.0, 0.25, 0.5),
            sh_g: Vec4::new(0.0, 0.0, 0.25, 0.5),
            sh_b: Vec4::new(0.0, 0.0, 0.25, 0.5),
            ..UrpLighting::default()
        };
        let out = shade_gbuffer(
            &UrpKeywords::default(),
            &UrpMaterial::default(),
            &UrpTexels::default(),
            &pixel(),
            &light,
            &CubeFaces::uniform(Vec4::ONE),
        )
        .unwrap();
        assert!(
            (out.gbuffer3 - Vec3::splat(0.757_647_1))
                .abs()
                .max_element()
                < 1e-6
        );
    }

    #[test]
    fn subtractive_lightmap_on_paper() {
        // Lightmap 1, light colour 1 head on (N·L = 1), shadow attenuation 0.25:
        // subtracted = 1 − 1 · 0.75 = 0.25, max with the shadow colour 0.1 -> 0.25;
        // strength 0.5: mix(1, 0.25, 0.5) = 0.625; min(1, 0.625) = 0.625.
        let k = UrpKeywords::from_names(&["LIGHTMAP_ON", "_MIXED_LIGHTING_SUBTRACTIVE"]).unwrap();
        let light = UrpLighting {
            main_light_dir: Vec3::Z,
            main_light_color: Vec3::ONE,
            shadow_attenuation: 0.25,
            shadow_strength: 0.5,
            subtractive_shadow_color: Vec3::splat(0.1),
            ..UrpLighting::default()
        };
        let tex = UrpTexels {
            lightmap: Vec3::ONE,
            ..UrpTexels::default()
        };
        let shadow = gbuffer_main_light_shadow(&k, &light);
        assert_eq!(
            urp_baked_gi(&k, &tex, &light, Vec3::Z, shadow, 0.5),
            Vec3::splat(0.625)
        );
        assert_eq!(k.flags().to_byte(), 4);
        // Receiving no shadows: nothing is subtracted.
        let k = UrpKeywords::from_names(&[
            "LIGHTMAP_ON",
            "_MIXED_LIGHTING_SUBTRACTIVE",
            "_RECEIVE_SHADOWS_OFF",
        ])
        .unwrap();
        let shadow = gbuffer_main_light_shadow(&k, &light);
        assert_eq!(
            urp_baked_gi(&k, &tex, &light, Vec3::Z, shadow, 0.5),
            Vec3::ONE
        );
    }

    #[test]
    fn alpha_test_and_targets() {
        let k = UrpKeywords::from_names(&["_ALPHATEST_ON"]).unwrap();
        let tex = UrpTexels {
            base_map: Vec4::new(1.0, 1.0, 1.0, 0.25),
            ..UrpTexels::default()
        };
        let run = |k: &UrpKeywords| {
            shade_gbuffer(
                k,
                &UrpMaterial::default(),
                &tex,
                &pixel(),
                &UrpLighting::default(),
                &CubeFaces::uniform(Vec4::ZERO),
            )
        };
        assert!(run(&k).is_none());
        // With the smoothness in the base map's alpha, alpha is _BaseColor.a (1): kept.
        let k = UrpKeywords::from_names(&["_ALPHATEST_ON", "_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A"])
            .unwrap();
        let out = run(&k).unwrap();
        assert_eq!(out.smoothness, 0.125); // 0.25 · 0.5
        let all = UrpKeywords([true; 16]);
        let texels = run(&all).unwrap().texels(&all);
        assert_eq!(texels.len(), 7);
        assert!(matches!(texels[2], UrpTexel::OctNormal { .. }));
        // Depth as colour, then rendering layers, then the shadowmask (URP's slot order).
        assert!(matches!(texels[4], UrpTexel::F32(_)));
        assert_eq!(texels[5], UrpTexel::U32(5));
        assert!(matches!(texels[6], UrpTexel::Unorm8(_)));
    }
}
