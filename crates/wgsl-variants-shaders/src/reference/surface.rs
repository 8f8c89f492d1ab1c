//! The bundled shader's passes, pixel by pixel: surface inputs under each keyword
//! (docs/shading.md §4), the Deferred and ForwardBase passes, the deferred reflection passes and
//! the final LDR decode (§6, §7).
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::surface::*;
//! let kw = Keywords::from_names(&["_METALLIC_MAP", "UNITY_HDR_ON"]).unwrap();
//! let material = Material { tint: Vec4::new(0.8, 0.8, 0.8, 1.0), ..Material::default() };
//! let texels = Texels { metallic_map: Vec4::new(1.0, 0.0, 0.0, 1.0), ..Texels::default() };
//! let geometry = Geometry { world_position: Vec3::ZERO, normal: Vec3::Y, tangent: Vec4::new(1.0, 0.0, 0.0, 1.0) };
//! let scene = Scene::default();
//! let g = shade_deferred(&kw, &material, &texels, &geometry, &scene).unwrap();
//! // Fully metallic: no diffuse colour, the albedo is the specular colour.
//! assert_eq!(g.rt0, Vec4::new(0.0, 0.0, 0.0, 1.0));
//! assert!((g.rt1.truncate() - Vec3::splat(0.8)).abs().max_element() < 1e-6);
//! ```

use glam::{Vec3, Vec4};

use super::brdf::{
    Brdf, diffuse_and_specular_from_metallic, direct, indirect_specular, sh_ambient,
};
use super::cube::CubeFaces;
use super::gbuffer::{GBuffer, decode_normal};
use super::ldr::{ldr_accumulate, ldr_decode};
use super::light::{Cookies, LightParams, LightType, light_direct};
use super::lightmap::{LightmapDecode, LightmapKeywords, LightmapTexels, lightmap_diffuse};
use super::probe::{
    Probe, box_project, box_project_grown, composite_f16, draw_order, falloff, forward_blend,
    mip_from_smoothness, mix, sample_probe,
};

/// The rendering-mode keyword set of the forward pass
/// (`_ _RENDERING_CUTOUT _RENDERING_FADE _RENDERING_TRANSPARENT`). The Deferred pass only has
/// the two-way `_ _RENDERING_CUTOUT` set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RenderingMode {
    /// None of the set.
    #[default]
    Opaque,
    /// `_RENDERING_CUTOUT`: discard where alpha < cutoff.
    Cutout,
    /// `_RENDERING_FADE` (forward only): output alpha, blended by the pipeline.
    Fade,
    /// `_RENDERING_TRANSPARENT` (forward only): premultiplied diffuse, reflectivity-raised alpha.
    Transparent,
}

/// Where smoothness comes from (`_ _SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum SmoothnessSource {
    /// None of the set: the uniform smoothness alone.
    #[default]
    Uniform,
    /// `_SMOOTHNESS_ALBEDO`: times `main_tex.a` (which then no longer feeds alpha).
    Albedo,
    /// `_SMOOTHNESS_METALLIC`: times `metallic_map.a`, only together with `_METALLIC_MAP`.
    Metallic,
}

/// The keywords of one variant of the bundled shader. `Default` is every set at "none"
/// ([`Keywords::NONE`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Keywords {
    /// Rendering mode; the Deferred pass only knows `Opaque` and `Cutout` (it treats `Fade` and
    /// `Transparent`, which have no deferred variant, as `Opaque`).
    pub rendering: RenderingMode,
    /// `_METALLIC_MAP`: metallic from `metallic_map.r`.
    pub metallic_map: bool,
    /// `_SMOOTHNESS_ALBEDO` / `_SMOOTHNESS_METALLIC`.
    pub smoothness: SmoothnessSource,
    /// `_NORMAL_MAP`.
    pub normal_map: bool,
    /// `_OCCLUSION_MAP`.
    pub occlusion_map: bool,
    /// `_EMISSION_MAP`.
    pub emission_map: bool,
    /// `_DETAIL_MASK`.
    pub detail_mask: bool,
    /// `_DETAIL_ALBEDO_MAP`.
    pub detail_albedo: bool,
    /// `_DETAIL_NORMAL_MAP`.
    pub detail_normal: bool,
    /// `UNITY_HDR_ON`: RT3 is `Rgba16Float` holding `c` instead of 10-bit `exp2(−c)`.
    pub hdr: bool,
    /// `UNITY_ENABLE_REFLECTION_BUFFERS`: the Deferred pass leaves indirect specular out of RT3;
    /// the DeferredReflections passes add it per probe.
    pub reflection_buffers: bool,
    /// The Standard BRDF's tier: none (BRDF1), `UNITY_PBS_USE_BRDF2` or `UNITY_PBS_USE_BRDF3`.
    pub brdf: Brdf,
    /// `LIGHTMAP_ON`: the baked lightmap replaces the ambient SH (ForwardBase, Deferred).
    pub lightmap: bool,
    /// `DIRLIGHTMAP_COMBINED`: the lightmaps' directional maps.
    pub dirlightmap: bool,
    /// `DYNAMICLIGHTMAP_ON`: the realtime lightmap.
    pub dynamic_lightmap: bool,
}

/// A keyword set the reference cannot model.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum KeywordsError {
    /// A keyword the standard shader does not declare.
    #[error("unknown keyword `{0}`")]
    Unknown(String),
    /// Two keywords of one set.
    #[error("`{first}` and `{second}` belong to the same keyword set; only one can be on")]
    SameSet {
        /// The first one given.
        first: String,
        /// The second.
        second: String,
    },
}

/// Every keyword name [`Keywords::from_names`] knows, in the order [`Keywords::names`] lists them.
pub const KEYWORD_NAMES: [&str; 19] = [
    "_RENDERING_CUTOUT",
    "_RENDERING_FADE",
    "_RENDERING_TRANSPARENT",
    "_METALLIC_MAP",
    "_SMOOTHNESS_ALBEDO",
    "_SMOOTHNESS_METALLIC",
    "_NORMAL_MAP",
    "_OCCLUSION_MAP",
    "_EMISSION_MAP",
    "_DETAIL_MASK",
    "_DETAIL_ALBEDO_MAP",
    "_DETAIL_NORMAL_MAP",
    "UNITY_HDR_ON",
    "UNITY_ENABLE_REFLECTION_BUFFERS",
    "UNITY_PBS_USE_BRDF2",
    "UNITY_PBS_USE_BRDF3",
    "LIGHTMAP_ON",
    "DIRLIGHTMAP_COMBINED",
    "DYNAMICLIGHTMAP_ON",
];

impl Default for Keywords {
    fn default() -> Keywords {
        Keywords::NONE
    }
}

impl Keywords {
    /// Every set at "none": what `Default` gives, usable in constants.
    pub const NONE: Keywords = Keywords {
        rendering: RenderingMode::Opaque,
        metallic_map: false,
        smoothness: SmoothnessSource::Uniform,
        normal_map: false,
        occlusion_map: false,
        emission_map: false,
        detail_mask: false,
        detail_albedo: false,
        detail_normal: false,
        hdr: false,
        reflection_buffers: false,
        brdf: Brdf::Brdf1,
        lightmap: false,
        dirlightmap: false,
        dynamic_lightmap: false,
    };

    /// Every texture map on, smoothness from the metallic map's alpha; opaque, LDR, no
    /// reflection buffers. The GPU checks and benches start from it; its names come from
    /// [`Keywords::names`], so the keyword list is written once ([`KEYWORD_NAMES`]).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::surface::Keywords;
    /// assert_eq!(
    ///     Keywords::EVERY_MAP.names().join(" "),
    ///     "_METALLIC_MAP _SMOOTHNESS_METALLIC _NORMAL_MAP _OCCLUSION_MAP _EMISSION_MAP \
    ///      _DETAIL_MASK _DETAIL_ALBEDO_MAP _DETAIL_NORMAL_MAP"
    /// );
    /// ```
    pub const EVERY_MAP: Keywords = Keywords {
        metallic_map: true,
        smoothness: SmoothnessSource::Metallic,
        normal_map: true,
        occlusion_map: true,
        emission_map: true,
        detail_mask: true,
        detail_albedo: true,
        detail_normal: true,
        ..Keywords::NONE
    };

    /// The keywords from the names of the active ones (Unity spelling).
    ///
    /// Names made only of underscores (`_`, `__`, …) mean "none of this set" and are ignored.
    /// A name given twice is the same as once. Errors: an unknown name, or two different names
    /// of the same set (rendering mode; smoothness source) — a variant has one name per set.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::surface::{Keywords, RenderingMode, SmoothnessSource};
    /// let k = Keywords::from_names(&["_RENDERING_CUTOUT", "_SMOOTHNESS_METALLIC", "_"]).unwrap();
    /// assert_eq!(k.rendering, RenderingMode::Cutout);
    /// assert_eq!(k.smoothness, SmoothnessSource::Metallic);
    /// assert!(!k.metallic_map);
    /// assert!(Keywords::from_names(&["_NORMALMAP"]).is_err());
    /// assert!(Keywords::from_names(&["_RENDERING_FADE", "_RENDERING_CUTOUT"]).is_err());
    /// assert_eq!(Keywords::from_names(&[]).unwrap(), Keywords::default());
    /// ```
    pub fn from_names(names: &[&str]) -> Result<Keywords, KeywordsError> {
        let mut k = Keywords::default();
        let mut rendering: Option<&str> = None;
        let mut smoothness: Option<&str> = None;
        let mut tier: Option<&str> = None;
        fn one_of_set<'a>(slot: &mut Option<&'a str>, name: &'a str) -> Result<(), KeywordsError> {
            match *slot {
                Some(previous) if previous != name => Err(KeywordsError::SameSet {
                    first: previous.to_string(),
                    second: name.to_string(),
                }),
                _ => {
                    *slot = Some(name);
                    Ok(())
                }
            }
        }
        for &name in names {
            match name {
                n if !n.is_empty() && n.bytes().all(|b| b == b'_') => {}
                "_RENDERING_CUTOUT" => {
                    one_of_set(&mut rendering, name)?;
                    k.rendering = RenderingMode::Cutout;
                }
                "_RENDERING_FADE" => {
                    one_of_set(&mut rendering, name)?;
                    k.rendering = RenderingMode::Fade;
                }
                "_RENDERING_TRANSPARENT" => {
                    one_of_set(&mut rendering, name)?;
                    k.rendering = RenderingMode::Transparent;
                }
                "_SMOOTHNESS_ALBEDO" => {
                    one_of_set(&mut smoothness, name)?;
                    k.smoothness = SmoothnessSource::Albedo;
                }
                "_SMOOTHNESS_METALLIC" => {
                    one_of_set(&mut smoothness, name)?;
                    k.smoothness = SmoothnessSource::Metallic;
                }
                "_METALLIC_MAP" => k.metallic_map = true,
                "_NORMAL_MAP" => k.normal_map = true,
                "_OCCLUSION_MAP" => k.occlusion_map = true,
                "_EMISSION_MAP" => k.emission_map = true,
                "_DETAIL_MASK" => k.detail_mask = true,
                "_DETAIL_ALBEDO_MAP" => k.detail_albedo = true,
                "_DETAIL_NORMAL_MAP" => k.detail_normal = true,
                "UNITY_HDR_ON" => k.hdr = true,
                "UNITY_ENABLE_REFLECTION_BUFFERS" => k.reflection_buffers = true,
                "UNITY_PBS_USE_BRDF2" => {
                    one_of_set(&mut tier, name)?;
                    k.brdf = Brdf::Brdf2;
                }
                "UNITY_PBS_USE_BRDF3" => {
                    one_of_set(&mut tier, name)?;
                    k.brdf = Brdf::Brdf3;
                }
                "LIGHTMAP_ON" => k.lightmap = true,
                "DIRLIGHTMAP_COMBINED" => k.dirlightmap = true,
                "DYNAMICLIGHTMAP_ON" => k.dynamic_lightmap = true,
                other => return Err(KeywordsError::Unknown(other.to_string())),
            }
        }
        Ok(k)
    }

    /// The names of the active keywords, in [`KEYWORD_NAMES`] order; `from_names` of the
    /// result gives `self` back.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::surface::Keywords;
    /// let k = Keywords { hdr: true, normal_map: true, ..Keywords::default() };
    /// assert_eq!(k.names(), vec!["_NORMAL_MAP", "UNITY_HDR_ON"]);
    /// assert_eq!(Keywords::from_names(&k.names()).unwrap(), k);
    /// ```
    pub fn names(&self) -> Vec<&'static str> {
        let on = [
            self.rendering == RenderingMode::Cutout,
            self.rendering == RenderingMode::Fade,
            self.rendering == RenderingMode::Transparent,
            self.metallic_map,
            self.smoothness == SmoothnessSource::Albedo,
            self.smoothness == SmoothnessSource::Metallic,
            self.normal_map,
            self.occlusion_map,
            self.emission_map,
            self.detail_mask,
            self.detail_albedo,
            self.detail_normal,
            self.hdr,
            self.reflection_buffers,
            self.brdf == Brdf::Brdf2,
            self.brdf == Brdf::Brdf3,
            self.lightmap,
            self.dirlightmap,
            self.dynamic_lightmap,
        ];
        KEYWORD_NAMES
            .iter()
            .zip(on)
            .filter_map(|(name, on)| on.then_some(*name))
            .collect()
    }

    /// The lightmap keywords.
    pub fn lightmaps(&self) -> LightmapKeywords {
        LightmapKeywords {
            baked: self.lightmap,
            directional: self.dirlightmap,
            realtime: self.dynamic_lightmap,
        }
    }

    /// Whether `_RENDERING_CUTOUT` is on (alpha test).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::surface::Keywords;
    /// assert!(Keywords::from_names(&["_RENDERING_CUTOUT"]).unwrap().cutout());
    /// assert!(!Keywords::default().cutout());
    /// ```
    pub fn cutout(&self) -> bool {
        self.rendering == RenderingMode::Cutout
    }
}

/// The material's uniform values (Unity's material properties). `Default` is the property
/// defaults of Unity's Standard shader: white tint, no emission, metallic 0, smoothness 0.5,
/// cutoff 0.5, occlusion strength 1, bump scales 1 (docs/shading.md §4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// `_Color`: albedo tint rgb and alpha.
    pub tint: Vec4,
    /// `_Emission` colour.
    pub emission: Vec3,
    /// `_Metallic` (used without `_METALLIC_MAP`).
    pub metallic: f32,
    /// `_Smoothness`.
    pub smoothness: f32,
    /// `_AlphaCutoff` (`_RENDERING_CUTOUT`).
    pub cutoff: f32,
    /// `_OcclusionStrength` (`_OCCLUSION_MAP`).
    pub occlusion_strength: f32,
    /// `_BumpScale` (`_NORMAL_MAP`).
    pub bump_scale: f32,
    /// `_DetailBumpScale` (`_DETAIL_NORMAL_MAP`).
    pub detail_bump_scale: f32,
}

impl Default for Material {
    fn default() -> Material {
        Material {
            tint: Vec4::ONE,
            emission: Vec3::ZERO,
            metallic: 0.0,
            smoothness: 0.5,
            cutoff: 0.5,
            occlusion_strength: 1.0,
            bump_scale: 1.0,
            detail_bump_scale: 1.0,
        }
    }
}

/// The texel values the textures give at this pixel (already sampled; the detail maps at the
/// detail uv). A map whose keyword is off is not read. `Default` is Unity's default textures:
/// white everywhere, flat `(0.5, 0.5, 1, 1)` for the two normal maps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texels {
    /// `_MainTex`: albedo rgb, alpha (or smoothness with `_SMOOTHNESS_ALBEDO`) a.
    pub main_tex: Vec4,
    /// `_MetallicMap` (`_METALLIC_MAP`): metallic r, smoothness a.
    pub metallic_map: Vec4,
    /// `_NormalMap` (`_NORMAL_MAP`): tangent-space normal, rgb = n · 0.5 + 0.5.
    pub normal_map: Vec4,
    /// `_OcclusionMap` (`_OCCLUSION_MAP`): occlusion g.
    pub occlusion_map: Vec4,
    /// `_EmissionMap` (`_EMISSION_MAP`): rgb.
    pub emission_map: Vec4,
    /// `_DetailMask` (`_DETAIL_MASK`): mask a.
    pub detail_mask: Vec4,
    /// `_DetailTex` (`_DETAIL_ALBEDO_MAP`): rgb.
    pub detail_albedo: Vec4,
    /// `_DetailNormalMap` (`_DETAIL_NORMAL_MAP`).
    pub detail_normal: Vec4,
    /// The lightmaps at the pixel's lightmap uvs (`LIGHTMAP_ON`, `DYNAMICLIGHTMAP_ON`).
    pub lightmap: LightmapTexels,
}

impl Default for Texels {
    fn default() -> Texels {
        let flat = Vec4::new(0.5, 0.5, 1.0, 1.0);
        Texels {
            main_tex: Vec4::ONE,
            metallic_map: Vec4::ONE,
            normal_map: flat,
            occlusion_map: Vec4::ONE,
            emission_map: Vec4::ONE,
            detail_mask: Vec4::ONE,
            detail_albedo: Vec4::ONE,
            detail_normal: flat,
            lightmap: LightmapTexels::default(),
        }
    }
}

/// The interpolated vertex data at this pixel, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Geometry {
    /// World position `p`.
    pub world_position: Vec3,
    /// Vertex normal `N` (normalized by the shader).
    pub normal: Vec3,
    /// Vertex tangent: xyz = `T` (normalized by the shader), w = bitangent sign.
    pub tangent: Vec4,
}

/// The per-frame inputs: camera, ambient light, the directional light and the object's two
/// reflection probes with their cube maps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scene {
    /// World position of the camera.
    pub camera_position: Vec3,
    /// `unity_SHAr`.
    pub sh_r: Vec4,
    /// `unity_SHAg`.
    pub sh_g: Vec4,
    /// `unity_SHAb`.
    pub sh_b: Vec4,
    /// Unit direction from the surface TO the directional light (used as is, not normalized).
    pub light_dir: Vec3,
    /// The directional light's colour.
    pub light_color: Vec3,
    /// Probes 0 and 1 of the forward blend (probe 0's `forward_weight` is `t`).
    pub probes: [Probe; 2],
    /// The cube maps of probes 0 and 1.
    pub cubes: [CubeFaces; 2],
    /// The lightmaps' decode instructions.
    pub lightmap_decode: LightmapDecode,
}

impl Default for Scene {
    /// Camera at (0, 0, 5), no ambient, no direct light (light from +Y, colour 0), two
    /// unit-box probes without box projection over black cubes.
    fn default() -> Scene {
        let probe = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
        Scene {
            camera_position: Vec3::new(0.0, 0.0, 5.0),
            sh_r: Vec4::ZERO,
            sh_g: Vec4::ZERO,
            sh_b: Vec4::ZERO,
            light_dir: Vec3::Y,
            light_color: Vec3::ZERO,
            probes: [probe; 2],
            cubes: [CubeFaces::uniform(Vec4::new(0.0, 0.0, 0.0, 1.0)); 2],
            lightmap_decode: LightmapDecode::default(),
        }
    }
}

impl Scene {
    /// The scene with its directional light shadowed by `factor` (ForwardBase's
    /// `SHADOWS_SCREEN`: the screen-space mask's value at the pixel, `1 − strength` to 1;
    /// docs/shading.md §11): the light's colour times the factor, everything else unchanged.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::surface::Scene;
    /// let scene = Scene { light_color: Vec3::splat(2.0), ..Scene::default() };
    /// assert_eq!(scene.with_main_shadow(0.25).light_color, Vec3::splat(0.5));
    /// assert_eq!(scene.with_main_shadow(1.0), scene);
    /// ```
    pub fn with_main_shadow(&self, factor: f32) -> Scene {
        Scene {
            light_color: self.light_color * factor,
            ..*self
        }
    }
}

/// The surface values the keywords and inputs produce (docs/shading.md §4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Albedo (before the metallic split).
    pub albedo: Vec3,
    /// Alpha (`tint.a`, times `main_tex.a` unless `_SMOOTHNESS_ALBEDO`).
    pub alpha: f32,
    /// Metallic.
    pub metallic: f32,
    /// Smoothness.
    pub smoothness: f32,
    /// Occlusion.
    pub occlusion: f32,
    /// Emission.
    pub emission: Vec3,
    /// Unit world normal.
    pub normal: Vec3,
}

/// Unity's `UnpackScaleNormal`: `((r·2−1)·s, (g·2−1)·s, b·2−1)`, not normalized.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::surface::unpack_normal;
/// assert_eq!(unpack_normal(Vec4::new(1.0, 0.5, 0.75, 1.0), 2.0), Vec3::new(2.0, 0.0, 0.5));
/// ```
pub fn unpack_normal(texel: Vec4, scale: f32) -> Vec3 {
    let t = texel.truncate() * 2.0 - 1.0;
    Vec3::new(t.x * scale, t.y * scale, t.z)
}

/// The tangent-space normal under the normal keywords: `(0, 0, 1)`; with `_NORMAL_MAP` the
/// unpacked normal map; with `_DETAIL_NORMAL_MAP` blended with
/// `d = mix((0, 0, 1), unpack(detail_normal), m)` as `normalize((t.xy + d.xy, t.z · d.z))`.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::surface::{tangent_space_normal, Keywords, Material, Texels};
/// let k = Keywords { normal_map: true, ..Keywords::default() };
/// let t = Texels { normal_map: Vec4::new(0.75, 0.5, 1.0, 1.0), ..Texels::default() };
/// assert_eq!(tangent_space_normal(&k, &Material::default(), &t, 1.0), Vec3::new(0.5, 0.0, 1.0));
/// ```
pub fn tangent_space_normal(kw: &Keywords, mat: &Material, tex: &Texels, detail_mask: f32) -> Vec3 {
    let mut t = Vec3::Z;
    if kw.normal_map {
        t = unpack_normal(tex.normal_map, mat.bump_scale);
    }
    if kw.detail_normal {
        let d = mix(
            Vec3::Z,
            unpack_normal(tex.detail_normal, mat.detail_bump_scale),
            detail_mask,
        );
        t = Vec3::new(t.x + d.x, t.y + d.y, t.z * d.z).normalize();
    }
    t
}

/// The surface values at this pixel under the keywords (docs/shading.md §4).
///
/// The world normal is `normalize(t.x · T + t.y · B + t.z · N)` with `N` and `T` normalized and
/// `B = cross(N, T) · tangent.w`. Without `_NORMAL_MAP` and `_DETAIL_NORMAL_MAP`, `t = (0, 0, 1)`
/// and the result is just `normalize(N)` — computed that way, so the tangent is not used then
/// (a zero tangent does no harm).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::surface::*;
/// let k = Keywords::from_names(&["_SMOOTHNESS_ALBEDO"]).unwrap();
/// let m = Material { tint: Vec4::new(1.0, 0.5, 0.5, 0.8), smoothness: 0.5, ..Material::default() };
/// let t = Texels { main_tex: Vec4::new(0.5, 0.5, 1.0, 0.6), ..Texels::default() };
/// let g = Geometry { world_position: Vec3::ZERO, normal: Vec3::new(0.0, 2.0, 0.0), tangent: Vec4::ZERO };
/// let s = surface(&k, &m, &t, &g);
/// assert_eq!(s.albedo, Vec3::new(0.5, 0.25, 0.5));
/// assert_eq!(s.alpha, 0.8);           // main_tex.a feeds smoothness instead
/// assert_eq!(s.smoothness, 0.3);
/// assert_eq!(s.normal, Vec3::Y);
/// ```
pub fn surface(kw: &Keywords, mat: &Material, tex: &Texels, geo: &Geometry) -> Surface {
    let m = if kw.detail_mask {
        tex.detail_mask.w
    } else {
        1.0
    };

    let mut albedo = tex.main_tex.truncate() * mat.tint.truncate();
    if kw.detail_albedo {
        albedo = mix(albedo, albedo * tex.detail_albedo.truncate() * 2.0, m);
    }

    let mut alpha = mat.tint.w;
    if kw.smoothness != SmoothnessSource::Albedo {
        alpha *= tex.main_tex.w;
    }

    let metallic = if kw.metallic_map {
        tex.metallic_map.x
    } else {
        mat.metallic
    };

    let smoothness = mat.smoothness
        * match kw.smoothness {
            SmoothnessSource::Albedo => tex.main_tex.w,
            SmoothnessSource::Metallic if kw.metallic_map => tex.metallic_map.w,
            _ => 1.0,
        };

    // mix(1, g, strength) in WGSL's form: 1 · (1 − strength) + g · strength.
    let occlusion = if kw.occlusion_map {
        (1.0 - mat.occlusion_strength) + tex.occlusion_map.y * mat.occlusion_strength
    } else {
        1.0
    };

    let emission = if kw.emission_map {
        tex.emission_map.truncate() * mat.emission
    } else {
        mat.emission
    };

    let n_vertex = geo.normal.normalize();
    let normal = if kw.normal_map || kw.detail_normal {
        let t = tangent_space_normal(kw, mat, tex, m);
        let tangent = geo.tangent.truncate().normalize();
        let bitangent = n_vertex.cross(tangent) * geo.tangent.w;
        (t.x * tangent + t.y * bitangent + t.z * n_vertex).normalize()
    } else {
        n_vertex
    };

    Surface {
        albedo,
        alpha,
        metallic,
        smoothness,
        occlusion,
        emission,
        normal,
    }
}

pub use super::vector::{reflect, view_and_reflection};

/// The forward probe result (docs/shading.md §6), before occlusion: each probe's cube map
/// sampled in the box-projected (un-grown box) direction at `mip_from_smoothness`, RGBM-decoded
/// with its `hdr`, blended by probe 0's `forward_weight` (`forward_blend`).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::cube::CubeFaces;
/// use wgsl_variants_shaders::reference::surface::{forward_environment, Scene};
/// let mut scene = Scene::default();
/// scene.cubes = [CubeFaces::uniform(Vec4::ONE), CubeFaces::uniform(Vec4::new(3.0, 3.0, 3.0, 1.0))];
/// scene.probes[0].forward_weight = 0.75;
/// assert_eq!(forward_environment(&scene, Vec3::ZERO, Vec3::Y, 0.5), Vec3::splat(1.5));
/// ```
pub fn forward_environment(scene: &Scene, world_position: Vec3, r: Vec3, smoothness: f32) -> Vec3 {
    let mip = mip_from_smoothness(smoothness);
    let sample = |i: usize| {
        let probe = &scene.probes[i];
        let dir = box_project(r, world_position, probe);
        sample_probe(probe, &scene.cubes[i], dir, mip)
    };
    let t = scene.probes[0].forward_weight;
    let e0 = sample(0);
    if t >= 0.99999 {
        e0
    } else {
        forward_blend(e0, sample(1), t)
    }
}

/// What the lighting shares between the passes: the view vector, the indirect diffuse light
/// (`sh(n) · occlusion`) and, when `with_reflections`, the forward probes' indirect specular in
/// tier `brdf` (else 0).
#[allow(clippy::too_many_arguments)]
fn indirect(
    s: &Surface,
    spec: Vec3,
    omr: f32,
    geo: &Geometry,
    scene: &Scene,
    with_reflections: bool,
    brdf: Brdf,
    (lightmaps, texels): (LightmapKeywords, &LightmapTexels),
) -> (Vec3, Vec3, Vec3) {
    let (v, r) = view_and_reflection(scene.camera_position, geo.world_position, s.normal);
    // Unity's UnityGI_Base: the lightmaps where the object has them, else the ambient SH.
    let ambient = if lightmaps.any() {
        lightmap_diffuse(lightmaps, texels, &scene.lightmap_decode, s.normal)
    } else {
        sh_ambient(scene.sh_r, scene.sh_g, scene.sh_b, s.normal)
    };
    let indirect_diffuse = ambient * s.occlusion;
    let specular = if with_reflections {
        let env = forward_environment(scene, geo.world_position, r, s.smoothness) * s.occlusion;
        indirect_specular(brdf, env, spec, s.smoothness, omr, s.normal, v)
    } else {
        Vec3::ZERO
    };
    (v, indirect_diffuse, specular)
}

/// The Deferred pass at one pixel (docs/shading.md §7): `None` when `_RENDERING_CUTOUT`
/// discards (`alpha < cutoff`), else the four target outputs:
/// RT0 = (diffuse, occlusion), RT1 = (spec_color, smoothness), RT2 = (encode_normal(n), 1),
/// RT3 = (`c` or `ldr_encode(c)`, 1) with
/// `c = emission + diffuse · sh(n) · occlusion + indirect_specular` (indirect specular 0 under
/// `UNITY_ENABLE_REFLECTION_BUFFERS`).
///
/// `Fade` and `Transparent` have no deferred variant and are treated as `Opaque`. The direct
/// light is not part of this pass.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::surface::*;
/// let kw = Keywords::from_names(&["_RENDERING_CUTOUT", "UNITY_HDR_ON"]).unwrap();
/// let mat = Material { tint: Vec4::new(1.0, 1.0, 1.0, 0.4), emission: Vec3::splat(2.0), ..Material::default() };
/// let geo = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::X };
/// assert!(shade_deferred(&kw, &mat, &Texels::default(), &geo, &Scene::default()).is_none());
/// let kept = Material { cutoff: 0.4, ..mat };
/// let g = shade_deferred(&kw, &kept, &Texels::default(), &geo, &Scene::default()).unwrap();
/// assert_eq!(g.rt3, Vec4::new(2.0, 2.0, 2.0, 1.0)); // emission only: no ambient, black probes
/// assert_eq!(g.rt2, Vec4::new(0.5, 0.5, 1.0, 1.0));
/// ```
pub fn shade_deferred(
    kw: &Keywords,
    mat: &Material,
    tex: &Texels,
    geo: &Geometry,
    scene: &Scene,
) -> Option<GBuffer> {
    let s = surface(kw, mat, tex, geo);
    if kw.cutout() && s.alpha < mat.cutoff {
        return None;
    }
    let (diffuse, spec, omr) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
    let (_, indirect_diffuse, indirect_specular) = indirect(
        &s,
        spec,
        omr,
        geo,
        scene,
        !kw.reflection_buffers,
        kw.brdf,
        (kw.lightmaps(), &tex.lightmap),
    );
    let c = s.emission + diffuse * indirect_diffuse + indirect_specular;
    Some(GBuffer::pack(
        diffuse,
        s.occlusion,
        spec,
        s.smoothness,
        s.normal,
        c,
        kw.hdr,
    ))
}

/// The ForwardBase pass at one pixel (docs/shading.md §7): `None` when `_RENDERING_CUTOUT`
/// discards, else the colour written to the `Rgba8Unorm` target (before the target clamps it):
/// `rgb = emission + diffuse · sh(n) · occlusion + indirect_specular + direct`,
/// `a = alpha` with `_RENDERING_FADE` / `_RENDERING_TRANSPARENT`, else 1.
///
/// With `_RENDERING_TRANSPARENT`, `diffuse = diffuse · alpha` and
/// `alpha = 1 − one_minus_reflectivity + alpha · one_minus_reflectivity` (before lighting).
/// The probes are always sampled (`UNITY_ENABLE_REFLECTION_BUFFERS` and `UNITY_HDR_ON` do not
/// affect this pass).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::surface::*;
/// let kw = Keywords::from_names(&["_RENDERING_FADE"]).unwrap();
/// let mat = Material { tint: Vec4::new(0.5, 0.5, 0.5, 0.25), ..Material::default() };
/// let geo = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::X };
/// let mut scene = Scene::default();
/// scene.light_dir = Vec3::Z;
/// scene.light_color = Vec3::ONE;
/// let c = shade_forward(&kw, &mat, &Texels::default(), &geo, &scene).unwrap();
/// assert_eq!(c.w, 0.25);
/// assert!(c.x > 0.48); // diffuse 0.5 · 0.96 plus a little specular
/// ```
pub fn shade_forward(
    kw: &Keywords,
    mat: &Material,
    tex: &Texels,
    geo: &Geometry,
    scene: &Scene,
) -> Option<Vec4> {
    let s = surface(kw, mat, tex, geo);
    if kw.cutout() && s.alpha < mat.cutoff {
        return None;
    }
    let (mut diffuse, spec, omr) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
    let mut alpha = s.alpha;
    if kw.rendering == RenderingMode::Transparent {
        diffuse *= alpha;
        alpha = 1.0 - omr + alpha * omr;
    }
    let (v, indirect_diffuse, indirect_specular) = indirect(
        &s,
        spec,
        omr,
        geo,
        scene,
        true,
        kw.brdf,
        (kw.lightmaps(), &tex.lightmap),
    );
    let d = direct(
        kw.brdf,
        diffuse,
        spec,
        s.smoothness,
        s.normal,
        v,
        scene.light_dir,
        scene.light_color,
    );
    let rgb = s.emission + diffuse * indirect_diffuse + indirect_specular + d;
    let a = match kw.rendering {
        RenderingMode::Fade | RenderingMode::Transparent => alpha,
        _ => 1.0,
    };
    Some(rgb.extend(a))
}

/// The ForwardAdd pass at one pixel (docs/shading.md §10): `None` when `_RENDERING_CUTOUT`
/// discards, else the colour written before the pipeline blends it (One/One; SrcAlpha/One with
/// fade and transparent): `rgb = light_direct(…)` of the one light, no ambient, reflections or
/// emission; `a` as in [`shade_forward`]. The diffuse colour is premultiplied by alpha with
/// `_RENDERING_TRANSPARENT`. The light's type comes from the variant's light keyword;
/// `Keywords::occlusion_map` and `emission_map` have no effect (the pass has no such keywords).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::light::{Light, LightType};
/// use wgsl_variants_shaders::reference::surface::*;
/// let mat = Material { emission: Vec3::ONE, ..Material::default() };
/// let geo = Geometry { world_position: Vec3::ZERO, normal: Vec3::Z, tangent: Vec4::X };
/// let light = Light::point(Vec3::new(0.0, 0.0, 10.0), 1.0, Vec3::ONE).params().unwrap();
/// // Out of range: black, whatever the emission.
/// let c = shade_forward_add(&Keywords::NONE, &mat, &Texels::default(), &geo, Vec3::Z * 5.0, &light, LightType::Point, None);
/// assert_eq!(c, Some(Vec4::new(0.0, 0.0, 0.0, 1.0)));
/// ```
#[allow(clippy::too_many_arguments)]
pub fn shade_forward_add(
    kw: &Keywords,
    mat: &Material,
    tex: &Texels,
    geo: &Geometry,
    camera_position: Vec3,
    light: &LightParams,
    light_type: LightType,
    cookies: Option<Cookies<'_>>,
) -> Option<Vec4> {
    let kw = Keywords {
        occlusion_map: false,
        emission_map: false,
        ..*kw
    };
    let s = surface(&kw, mat, tex, geo);
    if kw.cutout() && s.alpha < mat.cutoff {
        return None;
    }
    let (mut diffuse, spec, omr) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
    let mut alpha = s.alpha;
    if kw.rendering == RenderingMode::Transparent {
        diffuse *= alpha;
        alpha = 1.0 - omr + alpha * omr;
    }
    let rgb = light_direct(
        kw.brdf,
        diffuse,
        spec,
        s.smoothness,
        s.normal,
        geo.world_position,
        camera_position,
        light,
        light_type,
        cookies,
    );
    let a = match kw.rendering {
        RenderingMode::Fade | RenderingMode::Transparent => alpha,
        _ => 1.0,
    };
    Some(rgb.extend(a))
}

/// The DeferredReflections pass for one probe at one pixel: what it writes to the reflection
/// buffer, `(indirect_specular, falloff)`.
///
/// `gbuffer` holds the values the pass reads from RT0–RT2 (for GPU-stored targets use
/// `GBufferTexel::to_gbuffer`; RT3 is not read): occlusion = RT0.a, spec colour = RT1.rgb,
/// smoothness = RT1.a, `n = decode_normal(RT2.rgb)`. Then `v = normalize(camera − p)`,
/// `r = reflect(−v, n)`, the probe's cube is sampled in `box_project_grown(r, p, probe)` and
/// RGBM-decoded, `env = sample · occlusion`, and
/// `rgb = indirect_specular(brdf, env, spec, smoothness, 1 − max(spec.r, spec.g, spec.b), n, v)`;
/// `a = falloff(p, probe)`.
///
/// `one_minus_reflectivity` is not stored in the G-buffer; like Unity's
/// `Internal-DeferredReflections` (`1 − SpecularStrength(specColor)`), it is recovered from the
/// specular colour's largest channel. For a metallic-workflow surface this equals the
/// forward value `0.96 · (1 − metallic)` when the albedo's largest channel is 1.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::cube::CubeFaces;
/// use wgsl_variants_shaders::reference::gbuffer::GBuffer;
/// use wgsl_variants_shaders::reference::probe::Probe;
/// use wgsl_variants_shaders::reference::brdf::Brdf;
/// use wgsl_variants_shaders::reference::surface::reflection_probe_pixel;
/// // A mirror (smoothness 1) with spec colour 1, seen head-on: rgb = the probe colour.
/// let g = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ONE, 1.0, Vec3::Z, Vec3::ZERO, true);
/// let probe = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// let cube = CubeFaces::uniform(Vec4::new(0.25, 0.5, 0.75, 1.0));
/// let out = reflection_probe_pixel(Brdf::Brdf1, &g, Vec3::new(1.5, 0.0, 0.0), Vec3::new(1.5, 0.0, 5.0), &probe, &cube);
/// // BRDF1 floors the roughness at 0.002: the surface reduction is 1 / (1 + 0.002²).
/// assert!((out - Vec4::new(0.25, 0.5, 0.75, 0.5)).abs().max_element() < 1e-5);
/// ```
pub fn reflection_probe_pixel(
    brdf: Brdf,
    gbuffer: &GBuffer,
    world_position: Vec3,
    camera_position: Vec3,
    probe: &Probe,
    cube: &CubeFaces,
) -> Vec4 {
    let occlusion = gbuffer.rt0.w;
    let spec = gbuffer.rt1.truncate();
    let smoothness = gbuffer.rt1.w;
    let n = decode_normal(gbuffer.rt2.truncate());
    let omr = 1.0 - spec.max_element();
    let (v, r) = view_and_reflection(camera_position, world_position, n);
    let dir = box_project_grown(r, world_position, probe);
    let env = sample_probe(probe, cube, dir, mip_from_smoothness(smoothness)) * occlusion;
    let rgb = indirect_specular(brdf, env, spec, smoothness, omr, n, v);
    rgb.extend(falloff(world_position, probe))
}

/// The reflection buffer at one pixel after the DeferredReflections passes (tier `brdf`): the buffer starts
/// at 0, `probes` (each with its cube map) are drawn in [`draw_order`], and each blends its
/// [`reflection_probe_pixel`] over the buffer with its falloff, the `Rgba16Float` buffer
/// rounding to half float after each draw ([`composite_f16`]).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::cube::CubeFaces;
/// use wgsl_variants_shaders::reference::gbuffer::GBuffer;
/// use wgsl_variants_shaders::reference::probe::Probe;
/// use wgsl_variants_shaders::reference::brdf::Brdf;
/// use wgsl_variants_shaders::reference::surface::reflection_buffer;
/// let g = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ONE, 1.0, Vec3::Z, Vec3::ZERO, true);
/// let big = Probe::new(Vec3::ZERO, Vec3::splat(-4.0), Vec3::splat(4.0));
/// let small = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// let cubes = [CubeFaces::uniform(Vec4::new(1.0, 0.0, 0.0, 1.0)), CubeFaces::uniform(Vec4::new(0.0, 1.0, 0.0, 1.0))];
/// // The small probe (drawn second) covers half: half of each.
/// let p = Vec3::new(1.5, 0.0, 0.0);
/// let refl = reflection_buffer(Brdf::Brdf1, &g, p, p + Vec3::Z, &[(small, cubes[1]), (big, cubes[0])]);
/// assert_eq!(refl, Vec3::new(0.5, 0.5, 0.0));
/// ```
pub fn reflection_buffer(
    brdf: Brdf,
    gbuffer: &GBuffer,
    world_position: Vec3,
    camera_position: Vec3,
    probes: &[(Probe, CubeFaces)],
) -> Vec3 {
    let only_probes: Vec<Probe> = probes.iter().map(|(p, _)| *p).collect();
    let samples: Vec<(Vec3, f32)> = draw_order(&only_probes)
        .into_iter()
        .map(|i| {
            let (probe, cube) = &probes[i];
            let out =
                reflection_probe_pixel(brdf, gbuffer, world_position, camera_position, probe, cube);
            (out.truncate(), out.w)
        })
        .collect();
    composite_f16(Vec3::ZERO, &samples)
}

/// The DeferredReflectionsAdd pass: RT3 after adding the reflection buffer `refl`.
/// HDR (One/One): `rt3 + refl`; LDR (DstColor/Zero with `src = exp2(−max(refl, 0))`):
/// `ldr_accumulate(rt3, refl)`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::surface::reflections_add;
/// assert_eq!(reflections_add(Vec3::splat(1.0), Vec3::splat(0.5), true), Vec3::splat(1.5));
/// assert_eq!(reflections_add(Vec3::splat(0.5), Vec3::splat(1.0), false), Vec3::splat(0.25));
/// ```
pub fn reflections_add(rt3: Vec3, refl: Vec3, hdr: bool) -> Vec3 {
    if hdr {
        rt3 + refl
    } else {
        ldr_accumulate(rt3, refl)
    }
}

/// The DeferredFinal pass (LDR only): the colour `ldr_decode(rt3)` written to the output
/// target, before the target clamps it (channels where RT3 holds 0 decode to +∞).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::surface::final_ldr;
/// assert_eq!(final_ldr(Vec3::new(1.0, 0.5, 0.0)), Vec3::new(0.0, 1.0, f32::INFINITY));
/// ```
pub fn final_ldr(rt3: Vec3) -> Vec3 {
    ldr_decode(rt3)
}

#[cfg(test)]
mod tests;
