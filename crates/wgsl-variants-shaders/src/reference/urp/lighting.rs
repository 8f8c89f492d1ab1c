//! URP's deferred lighting (the `StencilDeferred` passes; docs/urp.md §9): one light at one
//! G-buffer texel — URP's attenuation, its "minimalist Cook-Torrance" BRDF rebuilt from the
//! G-buffer, and the material flags honoured. Facts from URP's shader library
//! (`RealtimeLights.hlsl` `DistanceAttenuation` / `AngleAttenuation`, `BRDF.hlsl`
//! `InitializeBRDFDataDirect` / `DirectBRDFSpecular`, `Lighting.hlsl`
//! `LightingPhysicallyBased`, `UnityGBuffer.hlsl` `BRDFDataFromGbuffer`, `Deferred.hlsl`,
//! `StencilDeferred.shader`), stated in docs/urp.md.
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::light::Light;
//! use wgsl_variants_shaders::reference::urp::lighting::{UrpLight, distance_attenuation};
//! // Half way to the range: 1/d² · (1 − (d²/r²)²)² = 1/4 · (1 − 1/16)² at d = 2, r = 4.
//! assert!((distance_attenuation(4.0, 1.0 / 16.0) - 0.25 * (15.0f32 / 16.0).powi(2)).abs() < 1e-7);
//! // Lights are checked before they are lit: a spot's inner angle cannot exceed its outer one.
//! let spot = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 60.0, 5.0, Vec3::ONE);
//! assert!(UrpLight::new(spot, 30.0, 1).params().is_ok());
//! assert!(UrpLight::new(spot, 70.0, 1).params().is_err());
//! ```

use glam::{Vec2, Vec3, Vec4};

use super::flags::{FlagsError, MaterialFlags, unpack_flags_byte};
use super::normal::{decode_normal_oct, decode_normal_snorm8, snorm8_to_f32};
use super::srgb::srgb8_to_linear_vec3;
use super::workflow::metallic_brdf_colors;
use crate::reference::light::{Light, LightError, LightShape};

/// HLSL's `HALF_MIN` (the smallest normal half float, 2^-14): URP's floor for `roughness²`
/// and for a light's squared distance.
pub const HALF_MIN: f32 = 6.103_515_6e-5;

/// HLSL's `HALF_MIN_SQRT` (2^-7): URP's floor for `roughness`.
pub const HALF_MIN_SQRT: f32 = 0.007_812_5;

/// The kind of a URP light, as the lighting passes split them (`_DIRECTIONAL`, `_POINT`,
/// `_SPOT`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UrpLightKind {
    /// Full-screen, no distance or angle attenuation.
    Directional,
    /// A sphere of influence.
    Point,
    /// A cone.
    Spot,
}

impl UrpLightKind {
    /// The lighting passes' keyword of this kind.
    pub fn keyword(self) -> &'static str {
        match self {
            UrpLightKind::Directional => "_DIRECTIONAL",
            UrpLightKind::Point => "_POINT",
            UrpLightKind::Spot => "_SPOT",
        }
    }
}

/// A light as a URP renderer describes it: the shape and colour of [`Light`], the spot's inner
/// angle (URP's `innerSpotAngle`, full angle in degrees; the falloff runs from it to the outer
/// angle) and the light's rendering-layer mask.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpLight {
    /// Shape (position, direction, range, outer spot angle) and colour.
    pub light: Light,
    /// Full inner cone angle in degrees (spot lights; ignored otherwise), `0 ≤ inner ≤ outer`.
    pub inner_spot_degrees: f32,
    /// The rendering layers this light lights (`_LIGHT_LAYERS`).
    pub layer_mask: u32,
}

/// What the URP lighting passes read of a light (the WGSL `UrpLight` record,
/// [`UrpLightParams::uniform`] lays it out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpLightParams {
    /// Which pass lights it.
    pub kind: UrpLightKind,
    /// World position (point and spot).
    pub position: Vec3,
    /// Colour times intensity.
    pub color: Vec3,
    /// URP's `_LightAttenuation`: x = `1 / range²` (0 for directional), y unused here (URP's
    /// mobile fade), z = `1 / max(cos(inner/2) − cos(outer/2), 0.001)`, w = `−cos(outer/2) · z`
    /// (spot); z = 0, w = 1 otherwise, so the angle term is 1.
    pub attenuation: Vec4,
    /// Unit direction: towards the light (directional) or the spot's axis reversed (URP's
    /// `_LightDirection`).
    pub direction: Vec3,
    /// Rendering-layer mask.
    pub layer_mask: u32,
}

impl UrpLight {
    /// A URP light over `light` with a spot's inner angle and a layer mask.
    pub fn new(light: Light, inner_spot_degrees: f32, layer_mask: u32) -> UrpLight {
        UrpLight {
            light,
            inner_spot_degrees,
            layer_mask,
        }
    }

    /// Checks the light (everything [`Light::params`] checks, and `0 ≤ inner ≤ outer` for a
    /// spot) and computes what the shaders read.
    ///
    /// # Errors
    /// [`LightError`]: a non-finite value, a negative colour channel, a zero direction, a range
    /// not > 0, a spot angle outside (0°, 180°), an inner angle outside `[0, outer]`.
    pub fn params(&self) -> Result<UrpLightParams, LightError> {
        let base = self.light.params()?;
        let color = base.color;
        let layer_mask = self.layer_mask;
        match self.light.shape {
            LightShape::Directional { .. } => Ok(UrpLightParams {
                kind: UrpLightKind::Directional,
                position: Vec3::ZERO,
                color,
                attenuation: Vec4::new(0.0, 0.0, 0.0, 1.0),
                direction: base.to_light,
                layer_mask,
            }),
            LightShape::Point { position, .. } => Ok(UrpLightParams {
                kind: UrpLightKind::Point,
                position,
                color,
                attenuation: Vec4::new(base.inv_range_sq, 0.0, 0.0, 1.0),
                direction: Vec3::ZERO,
                layer_mask,
            }),
            LightShape::Spot {
                position,
                angle_degrees,
                ..
            } => {
                let inner = self.inner_spot_degrees;
                if !(inner.is_finite() && (0.0..=angle_degrees).contains(&inner)) {
                    return Err(LightError::SpotInnerAngle {
                        inner_degrees: inner,
                        outer_degrees: angle_degrees,
                    });
                }
                let cos_outer = (angle_degrees.to_radians() * 0.5).cos();
                let cos_inner = (inner.to_radians() * 0.5).cos();
                let scale = 1.0 / (cos_inner - cos_outer).max(0.001);
                Ok(UrpLightParams {
                    kind: UrpLightKind::Spot,
                    position,
                    color,
                    attenuation: Vec4::new(base.inv_range_sq, 0.0, scale, -cos_outer * scale),
                    direction: base.to_light,
                    layer_mask,
                })
            }
        }
    }
}

impl UrpLightParams {
    /// The WGSL `UrpLight` record: `position`, `color`, `attenuation`, `direction` as four
    /// `vec4f` (w: 1, 0, –, 0) and `layer_mask` as a `vec4u` (x), little-endian.
    pub fn uniform(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(80);
        for v in [
            self.position.extend(1.0),
            self.color.extend(0.0),
            self.attenuation,
            self.direction.extend(0.0),
        ] {
            out.extend(v.to_array().iter().flat_map(|x| x.to_le_bytes()));
        }
        for word in [self.layer_mask, 0, 0, 0] {
            out.extend(word.to_le_bytes());
        }
        out
    }

    /// The unit direction to the light and its attenuation (distance × angle) at `p`, as
    /// URP's `UnityLightFromPunctualLightDataAndWorldSpacePosition` computes them; a
    /// directional light has attenuation 1.
    pub fn sample(&self, p: Vec3) -> (Vec3, f32) {
        if self.kind == UrpLightKind::Directional {
            return (self.direction, 1.0);
        }
        let to_light = self.position - p;
        let distance_sqr = to_light.dot(to_light).max(HALF_MIN);
        let l = to_light / distance_sqr.sqrt();
        let a = distance_attenuation(distance_sqr, self.attenuation.x)
            * angle_attenuation(
                self.direction,
                l,
                Vec2::new(self.attenuation.z, self.attenuation.w),
            );
        (l, a)
    }

    /// Whether the light lights a pixel of `rendering_layers` (`_LIGHT_LAYERS`: any common bit).
    pub fn lights_layers(&self, rendering_layers: u32) -> bool {
        self.layer_mask & rendering_layers != 0
    }
}

/// URP's distance attenuation: `1/d² · s²` with `s = saturate(1 − (d² · inv_range_sq)²)`, the
/// inverse square law faded smoothly to 0 at the range (the lightmapper's smoothing).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::lighting::distance_attenuation;
/// assert_eq!(distance_attenuation(1.0, 0.0), 1.0);      // no range: pure 1/d²
/// assert_eq!(distance_attenuation(16.0, 1.0 / 16.0), 0.0); // at the range
/// ```
pub fn distance_attenuation(distance_sqr: f32, inv_range_sq: f32) -> f32 {
    let factor = distance_sqr * inv_range_sq;
    let smooth = (1.0 - factor * factor).clamp(0.0, 1.0);
    (1.0 / distance_sqr) * smooth * smooth
}

/// URP's spot attenuation: `saturate(dot(spot_direction, l) · a.x + a.y)²` (1 for a point
/// light, whose `a` is `(0, 1)`).
///
/// ```
/// use glam::{Vec2, Vec3};
/// use wgsl_variants_shaders::reference::urp::lighting::angle_attenuation;
/// // Outer 90°, inner 0°: cos 45° = 0.7071 at the edge; half way in cosine is (½)² = ¼.
/// let c = (45f32).to_radians().cos();
/// let a = Vec2::new(1.0 / (1.0 - c), -c / (1.0 - c));
/// let l = Vec3::new(0.0, ((1.0 + c) / 2.0).acos().sin(), (1.0 + c) / 2.0);
/// assert!((angle_attenuation(Vec3::Z, l, a) - 0.25).abs() < 1e-5);
/// ```
pub fn angle_attenuation(spot_direction: Vec3, l: Vec3, a: Vec2) -> f32 {
    let t = (spot_direction.dot(l) * a.x + a.y).clamp(0.0, 1.0);
    t * t
}

/// One URP G-buffer texel as the lighting pass reads it (GBuffer0–2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpGBufferTexel {
    /// Base albedo, linear (GBuffer0.rgb through the sRGB target's decoding).
    pub albedo: Vec3,
    /// The material flags (GBuffer0.a).
    pub flags: MaterialFlags,
    /// GBuffer1.rgb: specular colour, or the reflectivity in r.
    pub specular: Vec3,
    /// Unit world normal (GBuffer2.rgb).
    pub normal: Vec3,
    /// Smoothness (GBuffer2.a).
    pub smoothness: f32,
}

impl UrpGBufferTexel {
    /// Decodes the bytes of GBuffer0 (`Rgba8UnormSrgb`), GBuffer1 (`Rgba8Unorm`) and GBuffer2
    /// (`Rgba8Unorm` octahedral with `oct`, else `Rgba8Snorm`).
    ///
    /// # Errors
    /// A flags byte with reserved bits set ([`FlagsError`]): reported, never masked.
    pub fn decode(
        gbuffer0: [u8; 4],
        gbuffer1: [u8; 4],
        gbuffer2: [u8; 4],
        oct: bool,
    ) -> Result<UrpGBufferTexel, FlagsError> {
        let unorm = |b: u8| f32::from(b) / 255.0;
        let flags = MaterialFlags::from_byte(unpack_flags_byte(unorm(gbuffer0[3])))?;
        let rgb = |t: [u8; 4]| [t[0], t[1], t[2]];
        let (normal, smoothness) = if oct {
            (decode_normal_oct(rgb(gbuffer2)), unorm(gbuffer2[3]))
        } else {
            let c = gbuffer2.map(|b| b as i8);
            (
                decode_normal_snorm8([c[0], c[1], c[2]]),
                snorm8_to_f32(c[3]),
            )
        };
        Ok(UrpGBufferTexel {
            albedo: srgb8_to_linear_vec3(rgb(gbuffer0)),
            flags,
            specular: Vec3::from_array(rgb(gbuffer1).map(unorm)),
            normal,
            smoothness,
        })
    }
}

/// URP's `BRDFData` as the lighting pass rebuilds it from the G-buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UrpBrdfData {
    /// Diffuse colour: `albedo · (1 − reflectivity)`.
    pub diffuse: Vec3,
    /// Specular colour (f0).
    pub specular: Vec3,
    /// `max(specular)` (specular setup) or GBuffer1.r (metallic).
    pub reflectivity: f32,
    /// `max((1 − smoothness)², HALF_MIN_SQRT)`.
    pub roughness: f32,
    /// `max(roughness², HALF_MIN)`.
    pub roughness2: f32,
    /// `roughness · 4 + 2`.
    pub normalization_term: f32,
    /// `roughness2 − 1`.
    pub roughness2_minus_one: f32,
}

impl UrpBrdfData {
    /// `BRDFDataFromGbuffer`: the specular setup (flag bit 3) takes `reflectivity =
    /// max(specular)` and `diffuse = albedo · (1 − reflectivity)`; the metallic workflow
    /// rebuilds metallic from GBuffer1.r ([`metallic_brdf_colors`]). Then
    /// `InitializeBRDFDataDirect`.
    pub fn from_gbuffer(t: &UrpGBufferTexel) -> UrpBrdfData {
        let (diffuse, specular, reflectivity) = if t.flags.specular_setup {
            let reflectivity = t.specular.max_element();
            (t.albedo * (1.0 - reflectivity), t.specular, reflectivity)
        } else {
            let (diffuse, specular) = metallic_brdf_colors(t.albedo, t.specular.x);
            (diffuse, specular, t.specular.x)
        };
        let perceptual_roughness = 1.0 - t.smoothness;
        let roughness = (perceptual_roughness * perceptual_roughness).max(HALF_MIN_SQRT);
        let roughness2 = (roughness * roughness).max(HALF_MIN);
        UrpBrdfData {
            diffuse,
            specular,
            reflectivity,
            roughness,
            roughness2,
            normalization_term: roughness * 4.0 + 2.0,
            roughness2_minus_one: roughness2 - 1.0,
        }
    }

    /// `DirectBRDFSpecular`: with `h = normalize(l + v)`, `d = (n·h)² · (r² − 1) + 1.00001`,
    /// the term `r² / (d² · max(0.1, (l·h)²) · (4r + 2))` (GGX times an approximation of
    /// visibility and Fresnel; multiplied by the specular colour by the caller).
    pub fn direct_specular(&self, n: Vec3, l: Vec3, v: Vec3) -> f32 {
        let h = safe_normalize(l + v);
        let n_dot_h = n.dot(h).clamp(0.0, 1.0);
        let l_dot_h = l.dot(h).clamp(0.0, 1.0);
        let d = n_dot_h * n_dot_h * self.roughness2_minus_one + 1.00001;
        self.roughness2 / ((d * d) * (l_dot_h * l_dot_h).max(0.1) * self.normalization_term)
    }
}

/// HLSL's `SafeNormalize`: `v · rsqrt(max(FLT_MIN, v·v))`.
pub fn safe_normalize(v: Vec3) -> Vec3 {
    v / v.dot(v).max(f32::MIN_POSITIVE).sqrt()
}

/// `LightingPhysicallyBased`: `(diffuse + specular · DirectBRDFSpecular) · color ·
/// (attenuation · saturate(n·l))`, the specular term dropped with `specular_highlights_off`.
pub fn lighting_physically_based(
    brdf: &UrpBrdfData,
    color: Vec3,
    attenuation: f32,
    l: Vec3,
    n: Vec3,
    v: Vec3,
    specular_highlights_off: bool,
) -> Vec3 {
    let n_dot_l = n.dot(l).clamp(0.0, 1.0);
    let radiance = color * (attenuation * n_dot_l);
    let mut brdf_color = brdf.diffuse;
    if !specular_highlights_off {
        brdf_color += brdf.specular * brdf.direct_specular(n, l, v);
    }
    brdf_color * radiance
}

/// The light one `StencilDeferred` Lit draw adds to GBuffer3 at a texel (before the One/One
/// blend): the light at `p` (rebuilt from depth), times `shadow` unless the texel's flags say
/// ReceiveShadowsOff, through URP's BRDF; 0 where `rendering_layers` (`_LIGHT_LAYERS`: the
/// texel's layers) shares no bit with the light's mask. `v = SafeNormalize(camera − p)`.
pub fn stencil_deferred_light(
    texel: &UrpGBufferTexel,
    p: Vec3,
    camera_position: Vec3,
    light: &UrpLightParams,
    shadow: f32,
    rendering_layers: Option<u32>,
) -> Vec3 {
    if rendering_layers.is_some_and(|layers| !light.lights_layers(layers)) {
        return Vec3::ZERO;
    }
    let (l, distance) = light.sample(p);
    let shadow = if texel.flags.receive_shadows_off {
        1.0
    } else {
        shadow
    };
    let brdf = UrpBrdfData::from_gbuffer(texel);
    let v = safe_normalize(camera_position - p);
    lighting_physically_based(
        &brdf,
        light.color,
        distance * shadow,
        l,
        texel.normal,
        v,
        texel.flags.specular_highlights_off,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texel(specular_setup: bool, specular: Vec3, smoothness: f32) -> UrpGBufferTexel {
        UrpGBufferTexel {
            albedo: Vec3::new(0.5, 0.25, 1.0),
            flags: MaterialFlags {
                specular_setup,
                ..Default::default()
            },
            specular,
            normal: Vec3::Z,
            smoothness,
        }
    }

    #[test]
    fn brdf_data_on_paper() {
        // Metallic: reflectivity 0.52 → metallic (0.52 − 0.04)/0.96 = 0.5;
        // diffuse = albedo · 0.48; specular = mix(0.04, albedo, 0.5) = 0.02 + albedo/2.
        // Smoothness 0.5: pr = 0.5, r = 0.25, r² = 0.0625, norm = 3, r² − 1 = −0.9375.
        let b = UrpBrdfData::from_gbuffer(&texel(false, Vec3::new(0.52, 0.0, 0.0), 0.5));
        assert!(
            (b.diffuse - Vec3::new(0.24, 0.12, 0.48))
                .abs()
                .max_element()
                < 1e-6
        );
        assert!(
            (b.specular - Vec3::new(0.27, 0.145, 0.52))
                .abs()
                .max_element()
                < 1e-6
        );
        assert_eq!(
            (b.roughness, b.roughness2, b.normalization_term),
            (0.25, 0.0625, 3.0)
        );
        assert_eq!(b.roughness2_minus_one, -0.9375);
        // Specular setup: reflectivity = max(0.2, 0.6, 0.4) = 0.6; diffuse = albedo · 0.4.
        let s = UrpBrdfData::from_gbuffer(&texel(true, Vec3::new(0.2, 0.6, 0.4), 1.0));
        assert!((s.diffuse - Vec3::new(0.2, 0.1, 0.4)).abs().max_element() < 1e-6);
        assert_eq!(s.reflectivity, 0.6);
        // Smoothness 1: the floors, r = 2^-7, r² = 2^-14.
        assert_eq!((s.roughness, s.roughness2), (HALF_MIN_SQRT, HALF_MIN));
    }

    #[test]
    fn specular_term_on_paper() {
        // n = l = v = +Z: h = +Z, n·h = l·h = 1. r² = 0.0625 (smoothness 0.5):
        // d = 1 · (−0.9375) + 1.00001 = 0.06251; term = 0.0625 / (0.06251² · 1 · 3)
        //   = 0.0625 / 0.011722500 = 5.33163…
        let b = UrpBrdfData::from_gbuffer(&texel(false, Vec3::splat(0.04), 0.5));
        let t = b.direct_specular(Vec3::Z, Vec3::Z, Vec3::Z);
        assert!((t - 5.331_627).abs() < 1e-3, "{t}");
        // Grazing light with l·h small: the 0.1 floor of (l·h)². l = +X, v = −X + tiny:
        // h ≈ +Y (normalised), l·h ≈ 0 → max(0.1, 0) = 0.1; n = +Y: n·h = 1.
        let v = Vec3::new(-1.0, 1e-3, 0.0).normalize();
        let t = b.direct_specular(Vec3::Y, Vec3::X, v);
        let d: f32 = 0.06251;
        assert!((t - 0.0625 / (d * d * 0.1 * 3.0)).abs() / t < 1e-3, "{t}");
    }

    #[test]
    fn attenuation_on_paper() {
        // d = 1, range 2: 1/1 · (1 − (1/4)²)² = (15/16)² = 0.87890625.
        assert_eq!(distance_attenuation(1.0, 0.25), 0.878_906_25);
        // Beyond the range: 0.
        assert_eq!(distance_attenuation(5.0, 0.25), 0.0);
        // Spot, outer 60°, inner 30°: cos 30° = 0.866025, cos 15° = 0.965926;
        // z = 1/0.099900 = 10.01, w = −0.866025 · z = −8.669. On the axis: saturate(1·z + w) = 1.
        let spot = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 60.0, 5.0, Vec3::ONE);
        let p = UrpLight::new(spot, 30.0, 1).params().unwrap();
        assert!(
            (p.attenuation.z - 10.0100).abs() < 1e-3,
            "{}",
            p.attenuation.z
        );
        assert!(
            (p.attenuation.w + 8.6690).abs() < 1e-3,
            "{}",
            p.attenuation.w
        );
        assert_eq!(p.direction, Vec3::Z);
        let (l, a) = p.sample(Vec3::new(0.0, 0.0, -2.0));
        // d² = 4, 1/r² = 1/25: 1/4 · (1 − (4/25)²)² = 0.25 · 0.9744² = 0.23736…
        assert_eq!(l, Vec3::Z);
        assert!((a - 0.25 * 0.9744f32.powi(2)).abs() < 1e-6, "{a}");
        // Outside the outer cone: 0.
        assert_eq!(p.sample(Vec3::new(2.0, 0.0, -1.0)).1, 0.0);
    }

    #[test]
    fn flags_are_honoured() {
        let light = UrpLight::new(
            Light::directional(Vec3::new(0.0, 0.0, -1.0), Vec3::ONE),
            0.0,
            0b10,
        )
        .params()
        .unwrap();
        let mut t = texel(false, Vec3::splat(0.04), 0.5);
        let lit = stencil_deferred_light(&t, Vec3::ZERO, Vec3::Z, &light, 0.25, None);
        // n = l = v = Z: (diffuse + 0.04 · 5.3316) · 0.25.
        let want = (t.albedo * 0.96 + Vec3::splat(0.04 * 5.331_627)) * 0.25;
        assert!((lit - want).abs().max_element() < 1e-4, "{lit} {want}");
        t.flags.receive_shadows_off = true;
        let unshadowed = stencil_deferred_light(&t, Vec3::ZERO, Vec3::Z, &light, 0.25, None);
        assert!((unshadowed - want * 4.0).abs().max_element() < 1e-4);
        t.flags.specular_highlights_off = true;
        let diffuse = stencil_deferred_light(&t, Vec3::ZERO, Vec3::Z, &light, 0.25, None);
        assert!((diffuse - t.albedo * 0.96).abs().max_element() < 1e-6);
        // Light layers: bit 1 lights layers 0b110, not 0b101.
        assert_ne!(
            stencil_deferred_light(&t, Vec3::ZERO, Vec3::Z, &light, 1.0, Some(0b110)),
            Vec3::ZERO
        );
        assert_eq!(
            stencil_deferred_light(&t, Vec3::ZERO, Vec3::Z, &light, 1.0, Some(0b101)),
            Vec3::ZERO
        );
    }

    #[test]
    fn bad_lights_are_refused() {
        let spot = |outer, inner| {
            UrpLight::new(
                Light::spot(Vec3::ZERO, Vec3::NEG_Z, outer, 5.0, Vec3::ONE),
                inner,
                1,
            )
            .params()
        };
        assert!(spot(60.0, 0.0).is_ok() && spot(60.0, 60.0).is_ok());
        assert!(matches!(
            spot(60.0, -1.0),
            Err(LightError::SpotInnerAngle { .. })
        ));
        assert!(matches!(
            spot(60.0, f32::NAN),
            Err(LightError::SpotInnerAngle { .. })
        ));
        assert!(matches!(
            spot(180.0, 10.0),
            Err(LightError::SpotAngle { .. })
        ));
        let point = UrpLight::new(Light::point(Vec3::ZERO, 0.0, Vec3::ONE), 0.0, 1);
        assert!(matches!(point.params(), Err(LightError::Range { .. })));
    }

    #[test]
    fn reserved_flag_bits_are_reported() {
        let e = UrpGBufferTexel::decode([0, 0, 0, 0x10], [0; 4], [128; 4], true);
        assert!(matches!(e, Err(FlagsError::ReservedBits { .. })));
        let t = UrpGBufferTexel::decode([255, 0, 0, 8], [51, 0, 0, 0], [0, 0, 127, 127], false)
            .unwrap();
        assert!(t.flags.specular_setup);
        assert_eq!((t.normal, t.smoothness, t.specular.x), (Vec3::Z, 1.0, 0.2));
        assert_eq!(t.albedo, Vec3::X);
    }
}
