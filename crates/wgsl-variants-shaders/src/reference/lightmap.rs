//! Unity's baked and realtime lightmaps as the built-in ForwardBase and Deferred passes read
//! them (docs/shading.md §14) [Unity's `UnityGlobalIllumination.cginc`: `UnityGI_Base`;
//! `UnityCG.cginc`: `DecodeLightmap`, `DecodeLightmapRGBM`, `DecodeRealtimeLightmap`,
//! `DecodeDirectionalLightmap`; Unity Manual, "Lightmaps: Technical information"]:
//!
//! ```text
//! baked     = rgb · (x · α^y), α = w · (a − 1) + 1        unity_Lightmap_HDR (x, y, _, w)
//! realtime  = pow((x · a) · rgb, y)                      unity_DynamicLightmap_HDR (x, y)
//! directional(c, dir, n) = c · (dot(n, dir.xyz − ½) + ½) / max(10⁻⁴, dir.w)
//! indirect diffuse = baked (LIGHTMAP_ON) + realtime (DYNAMICLIGHTMAP_ON), each through
//!                    `directional` with DIRLIGHTMAP_COMBINED; the ambient SH without either
//! ```
//!
//! The WGSL is `lighting/lightmap` (the decodes) and `standard/my_lighting`
//! (`my_lighting_ambient`).

use glam::{Vec3, Vec4};

use super::probe::rgbm_decode;

/// The texels a lightmapped pixel reads (each at its lightmap uv).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightmapTexels {
    /// `unity_Lightmap` (`LIGHTMAP_ON`), encoded as [`LightmapDecode::baked`] says.
    pub baked: Vec4,
    /// `unity_LightmapInd` (`LIGHTMAP_ON` with `DIRLIGHTMAP_COMBINED`): the dominant direction
    /// `xyz · ½ + ½` and the rebalancing coefficient `w`.
    pub baked_dir: Vec4,
    /// `unity_DynamicLightmap` (`DYNAMICLIGHTMAP_ON`).
    pub realtime: Vec4,
    /// `unity_DynamicDirectionality` (`DYNAMICLIGHTMAP_ON` with `DIRLIGHTMAP_COMBINED`).
    pub realtime_dir: Vec4,
}

impl Default for LightmapTexels {
    /// Black lightmaps, directional maps pointing nowhere with coefficient 1.
    fn default() -> LightmapTexels {
        let flat = Vec4::new(0.5, 0.5, 0.5, 1.0);
        LightmapTexels {
            baked: Vec4::new(0.0, 0.0, 0.0, 1.0),
            baked_dir: flat,
            realtime: Vec4::new(0.0, 0.0, 0.0, 1.0),
            realtime_dir: flat,
        }
    }
}

/// The lightmaps' decode instructions: Unity's `unity_Lightmap_HDR` and
/// `unity_DynamicLightmap_HDR`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightmapDecode {
    /// The baked lightmap's `(x, y, _, w)`: [`LightmapDecode::RGBM_LINEAR`],
    /// [`LightmapDecode::HDR`] or [`LightmapDecode::DLDR_LINEAR`].
    pub baked: Vec4,
    /// The realtime lightmap's `(x, y)` (zw unused).
    pub realtime: Vec4,
}

impl LightmapDecode {
    /// RGBM in linear colour space (desktop's Normal Quality): range `5^2.2 = 34.49`, the
    /// multiplier gamma-decoded (`α^2.2`).
    pub const RGBM_LINEAR: Vec4 = Vec4::new(34.493_24, 2.2, 0.0, 1.0);
    /// HDR lightmaps (High Quality: `Rgba16Float` or BC6H): the texel's rgb as is.
    pub const HDR: Vec4 = Vec4::new(1.0, 1.0, 0.0, 0.0);
    /// dLDR in linear colour space (mobile's Low Quality): `rgb · 2^2.2 = rgb · 4.59`.
    pub const DLDR_LINEAR: Vec4 = Vec4::new(4.594_794, 1.0, 0.0, 0.0);
}

impl Default for LightmapDecode {
    /// RGBM baked lightmaps, realtime lightmaps with range 1 and exponent 1.
    fn default() -> LightmapDecode {
        LightmapDecode {
            baked: LightmapDecode::RGBM_LINEAR,
            realtime: Vec4::new(1.0, 1.0, 0.0, 0.0),
        }
    }
}

/// Which lightmaps a variant reads: `LIGHTMAP_ON`, `DIRLIGHTMAP_COMBINED`,
/// `DYNAMICLIGHTMAP_ON`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightmapKeywords {
    /// `LIGHTMAP_ON`: the baked lightmap.
    pub baked: bool,
    /// `DIRLIGHTMAP_COMBINED`: the directional maps.
    pub directional: bool,
    /// `DYNAMICLIGHTMAP_ON`: the realtime lightmap.
    pub realtime: bool,
}

impl LightmapKeywords {
    /// Whether some lightmap replaces the ambient SH.
    pub fn any(&self) -> bool {
        self.baked || self.realtime
    }
}

/// A baked lightmap texel decoded (Unity's `DecodeLightmap`): `rgb · (x · α^y)`, `α = w ·
/// (a − 1) + 1` — RGBM with `w = 1`, HDR and dLDR with `w = 0`.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::lightmap::{LightmapDecode, decode_baked};
/// let full = Vec4::new(1.0, 0.5, 0.25, 1.0);
/// let rgbm = decode_baked(full, LightmapDecode::RGBM_LINEAR);
/// assert!((rgbm - Vec3::new(34.493242, 17.246621, 8.6233105)).abs().max_element() < 1e-4);
/// assert_eq!(decode_baked(Vec4::new(2.0, 3.0, 0.5, 0.25), LightmapDecode::HDR), Vec3::new(2.0, 3.0, 0.5));
/// ```
pub fn decode_baked(texel: Vec4, decode: Vec4) -> Vec3 {
    rgbm_decode(texel, Vec3::new(decode.x, decode.y, decode.w))
}

/// A realtime lightmap texel decoded (Unity's `DecodeRealtimeLightmap`): `pow((x · a) · rgb,
/// y)` per channel.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::lightmap::decode_realtime;
/// let c = decode_realtime(Vec4::new(0.5, 0.25, 0.0, 0.5), Vec4::new(8.0, 2.0, 0.0, 0.0));
/// assert_eq!(c, Vec3::new(4.0, 1.0, 0.0));
/// ```
pub fn decode_realtime(texel: Vec4, decode: Vec4) -> Vec3 {
    ((decode.x * texel.w) * texel.truncate()).powf(decode.y)
}

/// Unity's `DecodeDirectionalLightmap`: `color · (dot(n, dir.xyz − ½) + ½) / max(10⁻⁴,
/// dir.w)` — a half-Lambert term around the baked dominant direction (not unit length on
/// purpose: its length is the directionality), over the rebalancing coefficient.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::lightmap::directional;
/// let dir = Vec4::new(0.5, 0.5, 1.0, 0.5); // pointing along +Z, fully directional
/// assert_eq!(directional(Vec3::ONE, dir, Vec3::Z), Vec3::splat(2.0));
/// assert_eq!(directional(Vec3::ONE, dir, -Vec3::Z), Vec3::ZERO);
/// ```
pub fn directional(color: Vec3, dir: Vec4, n: Vec3) -> Vec3 {
    let half_lambert = n.dot(dir.truncate() - Vec3::splat(0.5)) + 0.5;
    color * half_lambert / dir.w.max(1e-4)
}

/// The lightmaps' indirect diffuse light at normal `n` (before occlusion): the baked lightmap
/// with `LIGHTMAP_ON` plus the realtime one with `DYNAMICLIGHTMAP_ON`, each through
/// [`directional`] with `DIRLIGHTMAP_COMBINED`. Zero without either (the caller then takes the
/// ambient SH, as Unity's `LIGHTPROBE_SH` objects do).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::lightmap::*;
/// let kw = LightmapKeywords { baked: true, realtime: true, ..Default::default() };
/// let tex = LightmapTexels {
///     baked: Vec4::new(0.5, 0.5, 0.5, 0.0),
///     realtime: Vec4::new(0.25, 0.5, 1.0, 1.0),
///     ..Default::default()
/// };
/// let decode = LightmapDecode { baked: LightmapDecode::HDR, realtime: Vec4::new(2.0, 1.0, 0.0, 0.0) };
/// assert_eq!(lightmap_diffuse(kw, &tex, &decode, Vec3::Z), Vec3::new(1.0, 1.5, 2.5));
/// ```
pub fn lightmap_diffuse(
    kw: LightmapKeywords,
    tex: &LightmapTexels,
    decode: &LightmapDecode,
    n: Vec3,
) -> Vec3 {
    let with_dir = |c: Vec3, dir: Vec4| {
        if kw.directional {
            directional(c, dir, n)
        } else {
            c
        }
    };
    let mut d = Vec3::ZERO;
    if kw.baked {
        d += with_dir(decode_baked(tex.baked, decode.baked), tex.baked_dir);
    }
    if kw.realtime {
        d += with_dir(
            decode_realtime(tex.realtime, decode.realtime),
            tex.realtime_dir,
        );
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgbm_spans_its_documented_range_and_the_multiplier_is_gamma_decoded() {
        let top = decode_baked(Vec4::ONE, LightmapDecode::RGBM_LINEAR);
        // Unity Manual: RGBM lightmaps range from 0 to 34.49 (5^2.2) in linear space.
        assert!((top.x - 5f32.powf(2.2)).abs() < 1e-3, "{top}");
        let half = decode_baked(Vec4::new(1.0, 1.0, 1.0, 0.5), LightmapDecode::RGBM_LINEAR);
        assert!((half.x - 34.493_24 * 0.5f32.powf(2.2)).abs() < 1e-4);
        // dLDR: [0, 2] gamma-space maps to ×2^2.2 in linear space; alpha ignored.
        let dldr = decode_baked(Vec4::new(0.5, 0.5, 0.5, 0.0), LightmapDecode::DLDR_LINEAR);
        assert!((dldr.x - 0.5 * 2f32.powf(2.2)).abs() < 1e-4);
    }

    #[test]
    fn directional_is_half_lambert_over_the_coefficient() {
        let dir = Vec4::new(1.0, 0.5, 0.5, 0.8); // dominant direction +X, length ½
        let c = Vec3::new(0.8, 0.4, 0.2);
        // Facing the direction: ½ + ½ = 1; across it: ½; away: 0; over 0.8.
        assert!((directional(c, dir, Vec3::X) - c / 0.8).length() < 1e-6);
        assert!((directional(c, dir, Vec3::Y) - c * 0.5 / 0.8).length() < 1e-6);
        assert!(directional(c, dir, -Vec3::X).length() < 1e-6);
        // A zero coefficient is clamped, not a division by zero.
        assert!(directional(c, Vec4::new(1.0, 0.5, 0.5, 0.0), Vec3::X).is_finite());
    }

    #[test]
    fn keywords_pick_the_maps() {
        let tex = LightmapTexels {
            baked: Vec4::new(1.0, 0.0, 0.0, 1.0),
            baked_dir: Vec4::new(0.5, 0.5, 1.0, 1.0),
            realtime: Vec4::new(0.0, 1.0, 0.0, 1.0),
            realtime_dir: Vec4::new(0.5, 0.5, 0.0, 1.0),
        };
        let decode = LightmapDecode {
            baked: LightmapDecode::HDR,
            realtime: Vec4::new(1.0, 1.0, 0.0, 0.0),
        };
        let at = |baked, directional, realtime| {
            let kw = LightmapKeywords {
                baked,
                directional,
                realtime,
            };
            lightmap_diffuse(kw, &tex, &decode, Vec3::Z)
        };
        assert_eq!(at(false, false, false), Vec3::ZERO);
        assert_eq!(at(true, false, false), Vec3::X);
        assert_eq!(at(false, false, true), Vec3::Y);
        assert_eq!(at(true, false, true), Vec3::new(1.0, 1.0, 0.0));
        // Directional: the baked map faces the normal (×1), the realtime one faces away (×0).
        assert_eq!(at(true, true, true), Vec3::X);
    }
}
