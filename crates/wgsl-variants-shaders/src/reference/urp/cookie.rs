//! URP's light cookies: the main light's (URP's `LightCookie.hlsl`,
//! `ComputeLightCookieUVDirectional` and `SampleMainLightCookie`; `LightCookieInput.hlsl`'s
//! texture formats; `docs/urp.md` §9). A cookie is a texture projected along the light that
//! tints its colour: `StencilDeferred`'s `GetStencilLight` multiplies the main light's colour by
//! it under `_LIGHT_COOKIES`.
//!
//! The coordinate is `uv = (M · p).xy · 0.5 + 0.5` with `M` URP's `_MainLightWorldToLight` (the
//! light's world-to-local transform and an orthographic projection of the cookie's size and
//! offset, so light space x and y run over [−1, 1] across the cookie), not wrapped by the
//! shader: the sampler's address mode does (URP binds the cookie texture's own sampler). This
//! reference reads the texture as a nearest sampler with repeat addressing does (the GPU checks
//! bind that one): one texel per point, `floor(uv · size)` wrapped, `Rgba8Unorm` bytes over 255.
//! Where the coordinate lies within [`EDGE`] of a texel's edge, the texel a GPU picks is not
//! decided by the math, so [`MainLightCookie::color`] gives the range over both.
//!
//! The WGSL is `universal/light_cookie`; [`MainLightCookie::uniform`] is its `MainLightCookie`
//! record.

use glam::{Mat4, Vec2, Vec3, Vec4Swizzles};

use crate::reference::texel::nearest_repeat_within;

/// How close to a texel's edge, in texels, a coordinate leaves the nearest texel undecided:
/// the position rebuilt from a depth buffer and a GPU's fixed-point texel addressing (8
/// fractional bits on the samplers these checks run on) each move it by less.
pub const EDGE: f32 = 1.0 / 64.0;

/// URP's `_MainLightCookieTextureFormat`: which channels of the texture the cookie's colour
/// reads (`URP_LIGHT_COOKIE_FORMAT_*` of `LightCookieTypes.hlsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CookieFormat {
    /// rgb (URP's 0).
    Rgb,
    /// The alpha channel in all three (URP's 1, an `Alpha8` texture).
    Alpha,
    /// The red channel in all three (URP's 2).
    Red,
}

impl CookieFormat {
    /// URP's value of the format.
    pub fn value(self) -> f32 {
        match self {
            CookieFormat::Rgb => 0.0,
            CookieFormat::Alpha => 1.0,
            CookieFormat::Red => 2.0,
        }
    }

    /// The colour a texel (`Rgba8Unorm` bytes) gives under this format.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::urp::cookie::CookieFormat;
    /// let texel = [255, 0, 51, 102];
    /// assert_eq!(CookieFormat::Rgb.color(texel), Vec3::new(1.0, 0.0, 0.2));
    /// assert_eq!(CookieFormat::Alpha.color(texel), Vec3::splat(0.4));
    /// assert_eq!(CookieFormat::Red.color(texel), Vec3::ONE);
    /// ```
    pub fn color(self, texel: [u8; 4]) -> Vec3 {
        let unorm = |b: u8| f32::from(b) / 255.0;
        match self {
            CookieFormat::Rgb => Vec3::new(unorm(texel[0]), unorm(texel[1]), unorm(texel[2])),
            CookieFormat::Alpha => Vec3::splat(unorm(texel[3])),
            CookieFormat::Red => Vec3::splat(unorm(texel[0])),
        }
    }
}

/// The main light's cookie: URP's `_MainLightWorldToLight`, the texture and its format.
#[derive(Clone, Debug, PartialEq)]
pub struct MainLightCookie {
    /// URP's `_MainLightWorldToLight`.
    pub world_to_light: Mat4,
    /// The texture's `Rgba8Unorm` texels, rows from v = 0.
    pub texels: Vec<[u8; 4]>,
    /// Width and height in texels.
    pub size: (u32, u32),
    /// Which channels it reads.
    pub format: CookieFormat,
}

/// Why a cookie could not be made.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CookieError {
    /// The texels do not fill the size.
    #[error("{texels} texels for a {width}×{height} cookie")]
    Size {
        /// Texels given.
        texels: usize,
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
}

impl MainLightCookie {
    /// A cookie of `size` texels with `world_to_light` and `format`.
    pub fn new(
        world_to_light: Mat4,
        texels: Vec<[u8; 4]>,
        size: (u32, u32),
        format: CookieFormat,
    ) -> Result<MainLightCookie, CookieError> {
        if size.0 == 0 || size.1 == 0 || texels.len() != (size.0 * size.1) as usize {
            return Err(CookieError::Size {
                texels: texels.len(),
                width: size.0,
                height: size.1,
            });
        }
        Ok(MainLightCookie {
            world_to_light,
            texels,
            size,
            format,
        })
    }

    /// `ComputeLightCookieUVDirectional` with the whole texture and no wrapping: light space
    /// x and y from [−1, 1] to [0, 1].
    pub fn uv(&self, p: Vec3) -> Vec2 {
        (self.world_to_light * p.extend(1.0)).xy() * 0.5 + Vec2::splat(0.5)
    }

    /// The colour the cookie multiplies the light's by at `p`, as a range: its least and
    /// greatest per channel over the texels a nearest sampler with repeat addressing may read
    /// there (one texel, or two or four within [`EDGE`] of an edge).
    ///
    /// ```
    /// use glam::{Mat4, Vec3};
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, MainLightCookie};
    /// // Two texels across x in [-1, 1]: black on the left, white on the right, repeated.
    /// let cookie = MainLightCookie::new(
    ///     Mat4::IDENTITY, vec![[0, 0, 0, 255], [255, 255, 255, 255]], (2, 1), CookieFormat::Rgb,
    /// ).unwrap();
    /// assert_eq!(cookie.color(Vec3::new(-0.5, 0.0, 0.0)), (Vec3::ZERO, Vec3::ZERO));
    /// assert_eq!(cookie.color(Vec3::new(0.5, 0.0, 0.0)), (Vec3::ONE, Vec3::ONE));
    /// assert_eq!(cookie.color(Vec3::new(2.5, 0.0, 0.0)), (Vec3::ONE, Vec3::ONE)); // repeated
    /// assert_eq!(cookie.color(Vec3::ZERO), (Vec3::ZERO, Vec3::ONE)); // on the edge
    /// ```
    pub fn color(&self, p: Vec3) -> (Vec3, Vec3) {
        let uv = self.uv(p);
        let (w, h) = self.size;
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        for y in nearest_repeat_within(uv.y, h, EDGE) {
            for x in nearest_repeat_within(uv.x, w, EDGE) {
                let c = self.format.color(self.texels[(y * w + x) as usize]);
                lo = lo.min(c);
                hi = hi.max(c);
            }
        }
        (lo, hi)
    }

    /// The WGSL `MainLightCookie` record: `world_to_light` (column-major) and `format`
    /// (x: URP's value), little-endian.
    ///
    /// ```
    /// use glam::Mat4;
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, MainLightCookie};
    /// let cookie = MainLightCookie::new(Mat4::IDENTITY, vec![[255; 4]], (1, 1), CookieFormat::Alpha)
    ///     .unwrap();
    /// let bytes = cookie.uniform();
    /// assert_eq!(bytes.len(), 80);
    /// assert_eq!(bytes[64..68], 1.0f32.to_le_bytes());
    /// ```
    pub fn uniform(&self) -> Vec<u8> {
        self.world_to_light
            .to_cols_array()
            .into_iter()
            .chain([self.format.value(), 0.0, 0.0, 0.0])
            .flat_map(f32::to_le_bytes)
            .collect()
    }

    /// The texture's bytes, rows from v = 0, as `Rgba8Unorm` uploads them.
    pub fn bytes(&self) -> Vec<u8> {
        self.texels.iter().flatten().copied().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cookie(format: CookieFormat) -> MainLightCookie {
        // 2 × 2: the texel at (x, y) has red 100 x + 50, green 100 y + 50, alpha 200.
        let texels = (0..2u8)
            .flat_map(|y| (0..2u8).map(move |x| [100 * x + 50, 100 * y + 50, 7, 200]))
            .collect();
        MainLightCookie::new(Mat4::IDENTITY, texels, (2, 2), format).unwrap()
    }

    #[test]
    fn each_quadrant_reads_its_texel_and_the_formats_pick_channels() {
        let c = cookie(CookieFormat::Rgb);
        let (lo, hi) = c.color(Vec3::new(0.5, -0.5, 3.0));
        assert_eq!(lo, hi);
        assert_eq!(lo, Vec3::new(150.0, 50.0, 7.0) / 255.0);
        let a = cookie(CookieFormat::Alpha)
            .color(Vec3::new(0.5, 0.5, 0.0))
            .0;
        assert_eq!(a, Vec3::splat(200.0 / 255.0));
        let r = cookie(CookieFormat::Red).color(Vec3::new(-0.5, 0.5, 0.0)).0;
        assert_eq!(r, Vec3::splat(50.0 / 255.0));
    }

    #[test]
    fn a_corner_is_the_range_of_its_four_texels_and_repeat_wraps() {
        let c = cookie(CookieFormat::Rgb);
        let (lo, hi) = c.color(Vec3::ZERO);
        assert_eq!(lo, Vec3::new(50.0, 50.0, 7.0) / 255.0);
        assert_eq!(hi, Vec3::new(150.0, 150.0, 7.0) / 255.0);
        // x = 1 (uv 1) is the wrap's edge between the last texel and the first.
        let (lo, hi) = c.color(Vec3::new(1.0, -0.5, 0.0));
        assert_eq!((lo.x, hi.x), (50.0 / 255.0, 150.0 / 255.0));
    }

    #[test]
    fn the_size_must_match_the_texels() {
        let err = MainLightCookie::new(Mat4::IDENTITY, vec![[0; 4]; 3], (2, 2), CookieFormat::Rgb);
        assert_eq!(
            err,
            Err(CookieError::Size {
                texels: 3,
                width: 2,
                height: 2
            })
        );
    }
}
