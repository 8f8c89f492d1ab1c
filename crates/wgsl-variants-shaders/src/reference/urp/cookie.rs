//! URP's light cookies (URP's `LightCookie.hlsl`: `ComputeLightCookieUVDirectional`,
//! `ComputeLightCookieUVSpot`, `ComputeLightCookieUVPoint`, `SampleMainLightCookie`;
//! `LightCookieInput.hlsl`'s records and texture formats; `docs/urp.md` §9). A cookie is a
//! texture projected from the light that tints its colour: `StencilDeferred`'s `GetStencilLight`
//! multiplies the main light's colour by its cookie, and a point or spot light's by its rect of
//! the additional lights' atlas, under `_LIGHT_COOKIES`.
//!
//! - The main light ([`MainLightCookie`]): `uv = (M · p).xy · 0.5 + 0.5` with `M` URP's
//!   `_MainLightWorldToLight` (the light's world-to-local transform and an orthographic
//!   projection of the cookie's size and offset, so light space x and y run over [−1, 1] across
//!   the cookie), not wrapped by the shader: the sampler's address mode does (URP binds the
//!   cookie texture's own sampler).
//! - The additional lights ([`AdditionalLightCookies`]): one atlas texture, each light a rect
//!   of it (`_AdditionalLightsCookieAtlasUVRects`: xy the rect's size, zw its offset, as the
//!   shader uses them: `atlas_uv = rect.xy · uv + rect.zw`). A spot light's `uv` is
//!   `saturate((q.xy / q.w) · 0.5 + 0.5)` with `q = M · p` and `M` its perspective
//!   (`_AdditionalLightsWorldToLights`); a point light's is `saturate(oct(normalize(q.xyz /
//!   q.w)) · 0.5 + 0.5)` with `M` its world-to-local transform and `oct` URP's octahedral
//!   quad encoding ([`super::normal::oct_encode`]).
//!
//! This reference reads a texture as a nearest sampler does (the GPU checks bind nearest ones:
//! the main light's cookie with repeat addressing, the atlas clamped to its edges): one texel
//! per point ([`crate::reference::texel`]), `Rgba8Unorm` bytes over 255. Where the coordinate
//! lies within [`EDGE`] of a texel's edge, the texel a GPU picks is not decided by the math, so
//! the colour is given as the range over both.
//!
//! The WGSL is `universal/light_cookie`; [`MainLightCookie::uniform`] and
//! [`AdditionalLightCookies::uniform`] are its records.

use glam::{Mat4, Vec2, Vec3, Vec4, Vec4Swizzles};

use super::normal::oct_encode;
use crate::reference::texel::{Address, nearest_within};

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

/// A cookie texture (the main light's, or the additional lights' atlas): `Rgba8Unorm` texels
/// and the format its colour is read in.
#[derive(Clone, Debug, PartialEq)]
pub struct CookieTexture {
    /// The texels, rows from v = 0.
    pub texels: Vec<[u8; 4]>,
    /// Width and height in texels.
    pub size: (u32, u32),
    /// Which channels it reads (URP's `_MainLightCookieTextureFormat` or
    /// `_AdditionalLightsCookieAtlasTextureFormat`).
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
    /// More additional lights than the record holds.
    #[error("{lights} additional lights with cookies; the record holds {ADDITIONAL_LIGHTS}")]
    TooManyLights {
        /// Lights given.
        lights: usize,
    },
}

impl CookieTexture {
    /// A texture of `size` texels read in `format`.
    ///
    /// # Errors
    /// [`CookieError::Size`] when the texels do not fill a non-empty `size`.
    pub fn new(
        texels: Vec<[u8; 4]>,
        size: (u32, u32),
        format: CookieFormat,
    ) -> Result<CookieTexture, CookieError> {
        if size.0 == 0 || size.1 == 0 || texels.len() != (size.0 * size.1) as usize {
            return Err(CookieError::Size {
                texels: texels.len(),
                width: size.0,
                height: size.1,
            });
        }
        Ok(CookieTexture {
            texels,
            size,
            format,
        })
    }

    /// The colour at `uv` as a range: its least and greatest per channel over the texels a
    /// nearest sampler with `address` may read there (one texel, or two or four within
    /// [`EDGE`] of an edge). A non-finite `uv` gives the range over every texel.
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// use wgsl_variants_shaders::reference::texel::Address;
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, CookieTexture};
    /// let t = CookieTexture::new(vec![[0, 0, 0, 255], [255, 255, 255, 255]], (2, 1), CookieFormat::Rgb)
    ///     .unwrap();
    /// assert_eq!(t.color(Vec2::new(0.25, 0.5), Address::Repeat), (Vec3::ZERO, Vec3::ZERO));
    /// assert_eq!(t.color(Vec2::new(1.0, 0.5), Address::Repeat), (Vec3::ZERO, Vec3::ONE));
    /// assert_eq!(t.color(Vec2::new(1.0, 0.5), Address::ClampToEdge), (Vec3::ONE, Vec3::ONE));
    /// ```
    pub fn color(&self, uv: Vec2, address: Address) -> (Vec3, Vec3) {
        range(&self.candidates(uv, address))
    }

    /// The colours of the texels a nearest sampler with `address` may read at `uv`: one, or
    /// two or four within [`EDGE`] of an edge; every texel's for a non-finite `uv`.
    ///
    /// ```
    /// use glam::{Vec2, Vec3};
    /// use wgsl_variants_shaders::reference::texel::Address;
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, CookieTexture};
    /// let t = CookieTexture::new(vec![[0, 0, 0, 255], [255, 255, 255, 255]], (2, 1), CookieFormat::Rgb)
    ///     .unwrap();
    /// assert_eq!(t.candidates(Vec2::new(0.25, 0.5), Address::Repeat), vec![Vec3::ZERO]);
    /// assert_eq!(t.candidates(Vec2::new(0.5, 0.5), Address::Repeat), vec![Vec3::ZERO, Vec3::ONE]);
    /// ```
    pub fn candidates(&self, uv: Vec2, address: Address) -> Vec<Vec3> {
        if !uv.is_finite() {
            return self.texels.iter().map(|&t| self.format.color(t)).collect();
        }
        let (w, h) = self.size;
        let mut out = Vec::with_capacity(4);
        for y in nearest_within(uv.y, h, EDGE, address) {
            for x in nearest_within(uv.x, w, EDGE, address) {
                out.push(self.format.color(self.texels[(y * w + x) as usize]));
            }
        }
        out
    }

    /// The texture's bytes, rows from v = 0, as `Rgba8Unorm` uploads them.
    pub fn bytes(&self) -> Vec<u8> {
        self.texels.iter().flatten().copied().collect()
    }
}

/// The least and greatest of `colors` per channel (white for none).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::cookie::range;
/// let (lo, hi) = range(&[Vec3::new(0.2, 0.9, 0.5), Vec3::new(0.4, 0.1, 0.5)]);
/// assert_eq!((lo, hi), (Vec3::new(0.2, 0.1, 0.5), Vec3::new(0.4, 0.9, 0.5)));
/// assert_eq!(range(&[]), (Vec3::ONE, Vec3::ONE));
/// ```
pub fn range(colors: &[Vec3]) -> (Vec3, Vec3) {
    if colors.is_empty() {
        return (Vec3::ONE, Vec3::ONE);
    }
    colors.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), &c| (lo.min(c), hi.max(c)),
    )
}

/// The main light's cookie: URP's `_MainLightWorldToLight` and the texture.
#[derive(Clone, Debug, PartialEq)]
pub struct MainLightCookie {
    /// URP's `_MainLightWorldToLight`.
    pub world_to_light: Mat4,
    /// The cookie texture and its format.
    pub texture: CookieTexture,
}

impl MainLightCookie {
    /// `ComputeLightCookieUVDirectional` with the whole texture and no wrapping: light space
    /// x and y from [−1, 1] to [0, 1].
    pub fn uv(&self, p: Vec3) -> Vec2 {
        (self.world_to_light * p.extend(1.0)).xy() * 0.5 + Vec2::splat(0.5)
    }

    /// The colour the cookie multiplies the light's by at `p`, as a range over the texels a
    /// nearest sampler with repeat addressing may read there ([`CookieTexture::color`]).
    ///
    /// ```
    /// use glam::{Mat4, Vec3};
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, CookieTexture, MainLightCookie};
    /// // Two texels across x in [-1, 1]: black on the left, white on the right, repeated.
    /// let texture = CookieTexture::new(
    ///     vec![[0, 0, 0, 255], [255, 255, 255, 255]], (2, 1), CookieFormat::Rgb,
    /// ).unwrap();
    /// let cookie = MainLightCookie { world_to_light: Mat4::IDENTITY, texture };
    /// assert_eq!(cookie.color(Vec3::new(-0.5, 0.0, 0.0)), (Vec3::ZERO, Vec3::ZERO));
    /// assert_eq!(cookie.color(Vec3::new(0.5, 0.0, 0.0)), (Vec3::ONE, Vec3::ONE));
    /// assert_eq!(cookie.color(Vec3::new(2.5, 0.0, 0.0)), (Vec3::ONE, Vec3::ONE)); // repeated
    /// assert_eq!(cookie.color(Vec3::ZERO), (Vec3::ZERO, Vec3::ONE)); // on the edge
    /// ```
    pub fn color(&self, p: Vec3) -> (Vec3, Vec3) {
        self.texture.color(self.uv(p), Address::Repeat)
    }

    /// The colours of the texels the cookie may read at `p` ([`CookieTexture::candidates`]).
    pub fn candidates(&self, p: Vec3) -> Vec<Vec3> {
        self.texture.candidates(self.uv(p), Address::Repeat)
    }

    /// The WGSL `MainLightCookie` record: `world_to_light` (column-major) and `format`
    /// (x: URP's value), little-endian.
    ///
    /// ```
    /// use glam::Mat4;
    /// use wgsl_variants_shaders::reference::urp::cookie::{CookieFormat, CookieTexture, MainLightCookie};
    /// let texture = CookieTexture::new(vec![[255; 4]], (1, 1), CookieFormat::Alpha).unwrap();
    /// let cookie = MainLightCookie { world_to_light: Mat4::IDENTITY, texture };
    /// let bytes = cookie.uniform();
    /// assert_eq!(bytes.len(), 80);
    /// assert_eq!(bytes[64..68], 1.0f32.to_le_bytes());
    /// ```
    pub fn uniform(&self) -> Vec<u8> {
        self.world_to_light
            .to_cols_array()
            .into_iter()
            .chain([self.texture.format.value(), 0.0, 0.0, 0.0])
            .flat_map(f32::to_le_bytes)
            .collect()
    }
}

/// The lights the WGSL `AdditionalLightCookies` record holds (the forward pass's eight).
pub const ADDITIONAL_LIGHTS: usize = 8;

/// How an additional light projects its cookie (URP's `_AdditionalLightsLightTypes`;
/// StencilDeferred picks by its `_SPOT` / `_POINT` keyword instead).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CookieProjection {
    /// `ComputeLightCookieUVSpot`: the light's perspective (URP's light type 0).
    Spot,
    /// `ComputeLightCookieUVPoint`: the octahedral map of the direction (URP's light type 2).
    Point,
}

impl CookieProjection {
    /// URP's light type (`URP_LIGHT_TYPE_SPOT` 0, `URP_LIGHT_TYPE_POINT` 2).
    pub fn light_type(self) -> f32 {
        match self {
            CookieProjection::Spot => 0.0,
            CookieProjection::Point => 2.0,
        }
    }
}

/// One additional light's cookie: its entries of URP's `_AdditionalLightsWorldToLights`,
/// `_AdditionalLightsCookieAtlasUVRects` and `_AdditionalLightsLightTypes`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdditionalLightCookie {
    /// A spot light's perspective (x, y over w in [−1, 1] across the cookie's square) or a point
    /// light's world-to-local transform.
    pub world_to_light: Mat4,
    /// The light's rect of the atlas: xy its size, zw its offset, in atlas uv.
    pub uv_rect: Vec4,
    /// Spot or point.
    pub projection: CookieProjection,
}

impl AdditionalLightCookie {
    /// The light's cookie coordinate at `p` in [0, 1]² of its rect, before the rect
    /// (`ComputeLightCookieUVSpot` / `ComputeLightCookieUVPoint` without the last line).
    ///
    /// ```
    /// use glam::{Mat4, Vec2, Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::urp::cookie::{AdditionalLightCookie, CookieProjection};
    /// let point = AdditionalLightCookie {
    ///     world_to_light: Mat4::IDENTITY,
    ///     uv_rect: Vec4::new(1.0, 1.0, 0.0, 0.0),
    ///     projection: CookieProjection::Point,
    /// };
    /// assert_eq!(point.uv(Vec3::new(0.0, 0.0, 3.0)), Vec2::splat(0.5)); // +Z: the centre
    /// assert_eq!(point.uv(Vec3::new(2.0, 0.0, 0.0)), Vec2::new(1.0, 0.5)); // +X: the right edge
    /// ```
    pub fn uv(&self, p: Vec3) -> Vec2 {
        let q = self.world_to_light * p.extend(1.0);
        let code = match self.projection {
            CookieProjection::Spot => q.xy() / q.w,
            CookieProjection::Point => oct_encode((q.xyz() / q.w).normalize()),
        };
        // saturate, NaN kept (the texture range then covers every texel).
        let saturate = |c: f32| if c.is_nan() { c } else { c.clamp(0.0, 1.0) };
        let uv = code * 0.5 + Vec2::splat(0.5);
        Vec2::new(saturate(uv.x), saturate(uv.y))
    }

    /// The coordinate in the atlas: `rect.xy · uv + rect.zw`.
    pub fn atlas_uv(&self, p: Vec3) -> Vec2 {
        self.uv_rect.xy() * self.uv(p) + self.uv_rect.zw()
    }
}

/// The additional lights' cookies: the atlas (URP's `_AdditionalLightsCookieAtlasTexture` and
/// its format) and each light's entry, by URP's light index (`_CookieLightIndex`).
#[derive(Clone, Debug, PartialEq)]
pub struct AdditionalLightCookies {
    /// The atlas.
    pub atlas: CookieTexture,
    /// Each light's entry; `None`: the light has no cookie (its rect all zero).
    pub lights: Vec<Option<AdditionalLightCookie>>,
}

impl AdditionalLightCookies {
    /// The atlas and the lights' entries.
    ///
    /// # Errors
    /// [`CookieError::TooManyLights`] for more than [`ADDITIONAL_LIGHTS`] lights.
    pub fn new(
        atlas: CookieTexture,
        lights: Vec<Option<AdditionalLightCookie>>,
    ) -> Result<AdditionalLightCookies, CookieError> {
        if lights.len() > ADDITIONAL_LIGHTS {
            return Err(CookieError::TooManyLights {
                lights: lights.len(),
            });
        }
        Ok(AdditionalLightCookies { atlas, lights })
    }

    /// The colour light `index`'s cookie multiplies its colour by at `p`, as a range over the
    /// atlas texels a nearest sampler clamped to the edges may read there
    /// ([`CookieTexture::color`]); white for a light without a cookie (URP's forward pass
    /// tests the all-zero rect; StencilDeferred draws such a light without `_LIGHT_COOKIES`).
    ///
    /// ```
    /// use glam::{Mat4, Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::urp::cookie::{
    ///     AdditionalLightCookie, AdditionalLightCookies, CookieFormat, CookieProjection, CookieTexture,
    /// };
    /// // A 2 × 1 atlas: the point light's rect is its right half, a white texel.
    /// let atlas = CookieTexture::new(vec![[0; 4], [255; 4]], (2, 1), CookieFormat::Alpha).unwrap();
    /// let point = AdditionalLightCookie {
    ///     world_to_light: Mat4::IDENTITY,
    ///     uv_rect: Vec4::new(0.5, 1.0, 0.5, 0.0),
    ///     projection: CookieProjection::Point,
    /// };
    /// let cookies = AdditionalLightCookies::new(atlas, vec![None, Some(point)]).unwrap();
    /// assert_eq!(cookies.color(1, Vec3::new(0.0, 0.0, 1.0)), (Vec3::ONE, Vec3::ONE));
    /// assert_eq!(cookies.color(0, Vec3::ZERO), (Vec3::ONE, Vec3::ONE)); // no cookie
    /// ```
    pub fn color(&self, index: usize, p: Vec3) -> (Vec3, Vec3) {
        range(&self.candidates(index, p))
    }

    /// The colours of the atlas texels light `index`'s cookie may read at `p`
    /// ([`CookieTexture::candidates`], clamped); white alone for a light without a cookie.
    pub fn candidates(&self, index: usize, p: Vec3) -> Vec<Vec3> {
        match self.lights.get(index).copied().flatten() {
            Some(light) => self
                .atlas
                .candidates(light.atlas_uv(p), Address::ClampToEdge),
            None => vec![Vec3::ONE],
        }
    }

    /// The WGSL `AdditionalLightCookies` record: eight `world_to_light` (column-major), eight
    /// `atlas_uv_rect`, eight `light_type` (x) and `format` (x), little-endian; a light
    /// without a cookie, and the slots past the last light, all zero.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::cookie::{AdditionalLightCookies, CookieFormat, CookieTexture};
    /// let atlas = CookieTexture::new(vec![[255; 4]], (1, 1), CookieFormat::Red).unwrap();
    /// let bytes = AdditionalLightCookies::new(atlas, vec![]).unwrap().uniform();
    /// assert_eq!(bytes.len(), 784);
    /// assert_eq!(bytes[768..772], 2.0f32.to_le_bytes());
    /// ```
    pub fn uniform(&self) -> Vec<u8> {
        let slot = |i: usize| self.lights.get(i).copied().flatten();
        let mut floats = Vec::with_capacity(196);
        for i in 0..ADDITIONAL_LIGHTS {
            floats.extend(
                slot(i)
                    .map_or(Mat4::ZERO, |l| l.world_to_light)
                    .to_cols_array(),
            );
        }
        for i in 0..ADDITIONAL_LIGHTS {
            floats.extend(slot(i).map_or(Vec4::ZERO, |l| l.uv_rect).to_array());
        }
        for i in 0..ADDITIONAL_LIGHTS {
            floats.extend([
                slot(i).map_or(0.0, |l| l.projection.light_type()),
                0.0,
                0.0,
                0.0,
            ]);
        }
        floats.extend([self.atlas.format.value(), 0.0, 0.0, 0.0]);
        floats.into_iter().flat_map(f32::to_le_bytes).collect()
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
        MainLightCookie {
            world_to_light: Mat4::IDENTITY,
            texture: CookieTexture::new(texels, (2, 2), format).unwrap(),
        }
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

    /// A 4 × 4 atlas whose texel (x, y) has alpha 10 (4y + x) + 50.
    fn atlas() -> CookieTexture {
        let texels = (0..16u8).map(|i| [0, 0, 0, 10 * i + 50]).collect();
        CookieTexture::new(texels, (4, 4), CookieFormat::Alpha).unwrap()
    }

    fn alpha(i: u8) -> Vec3 {
        Vec3::splat(f32::from(10 * i + 50) / 255.0)
    }

    #[test]
    fn a_spot_reads_its_rect_through_its_perspective() {
        use crate::reference::light::Light;
        // A 90° spot at the origin along −Z: the cone's edge at |x| = |z|.
        let params = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 90.0, 10.0, Vec3::ONE)
            .params()
            .unwrap();
        // Its rect: the atlas's upper-right 2 × 2 texels.
        let spot = AdditionalLightCookie {
            world_to_light: params.world_to_light,
            uv_rect: Vec4::new(0.5, 0.5, 0.5, 0.5),
            projection: CookieProjection::Spot,
        };
        let on_axis = Vec3::new(0.0, 0.0, -4.0);
        assert!((spot.uv(on_axis) - Vec2::splat(0.5)).abs().max_element() < 1e-6);
        let cookies = AdditionalLightCookies::new(atlas(), vec![None, Some(spot)]).unwrap();
        // A quarter of the cone off the axis diagonally: each quadrant one texel of the rect,
        // (2..4, 2..4), the four different.
        let mut read: Vec<u8> = [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
            .into_iter()
            .map(|(x, y)| {
                let (lo, hi) = cookies.color(1, Vec3::new(x, y, -4.0));
                assert_eq!(lo, hi);
                (0..16u8).find(|&i| alpha(i) == lo).unwrap()
            })
            .collect();
        read.sort_unstable();
        assert_eq!(read, [10, 11, 14, 15]);
        // Far outside the cone the coordinate saturates onto the rect's edge, where a sampler
        // may read the rect's texel or its neighbour (URP's atlas bleeds there too; the spot's
        // cone has no light there).
        let uv = spot.uv(Vec3::new(40.0, 0.0, -4.0));
        assert!(uv.min_element() == 0.0 || uv.max_element() == 1.0, "{uv}");
        let (lo, hi) = cookies.color(1, Vec3::new(40.0, 0.0, -4.0));
        assert_ne!(lo, hi);
    }

    #[test]
    fn a_point_light_reads_the_octahedral_map_and_the_atlas_clamps() {
        let point = AdditionalLightCookie {
            world_to_light: Mat4::from_translation(Vec3::new(0.0, -1.0, 0.0)),
            uv_rect: Vec4::new(1.0, 1.0, 0.0, 0.0),
            projection: CookieProjection::Point,
        };
        let cookies = AdditionalLightCookies::new(atlas(), vec![Some(point)]).unwrap();
        // The light at y = 1: straight up is the code (0, 1), uv (0.5, 1): the top row's
        // edge, clamped to the last row, between texels 1 and 2 of it...
        let (lo, hi) = cookies.color(0, Vec3::new(0.0, 3.0, 0.0));
        assert_eq!(
            (lo, hi),
            (alpha(13).min(alpha(14)), alpha(13).max(alpha(14)))
        );
        // +Z from the light: the centre, between the four middle texels.
        let (lo, hi) = cookies.color(0, Vec3::new(0.0, 1.0, 5.0));
        assert_eq!((lo, hi), (alpha(5), alpha(10)));
        // Towards +X and a little +Z: code (≈1, 0): texel (3, 1 or 2), clear of the edges in x.
        let (lo, _) = cookies.color(0, Vec3::new(3.0, 1.2, 0.2));
        assert_eq!(lo, alpha(11));
    }

    #[test]
    fn too_many_lights_are_refused_and_the_record_zeroes_missing_ones() {
        let light = AdditionalLightCookie {
            world_to_light: Mat4::IDENTITY,
            uv_rect: Vec4::new(0.5, 0.5, 0.25, 0.0),
            projection: CookieProjection::Point,
        };
        assert_eq!(
            AdditionalLightCookies::new(atlas(), vec![Some(light); 9]),
            Err(CookieError::TooManyLights { lights: 9 })
        );
        let bytes = AdditionalLightCookies::new(atlas(), vec![None, Some(light)])
            .unwrap()
            .uniform();
        let f = |i: usize| f32::from_le_bytes(bytes[i * 4..i * 4 + 4].try_into().unwrap());
        assert!((0..16).all(|i| f(i) == 0.0), "light 0 has no cookie");
        assert_eq!(f(16), 1.0, "light 1's matrix");
        assert_eq!((f(128 + 4), f(128 + 6)), (0.5, 0.25), "light 1's rect");
        assert_eq!(f(160 + 4), 2.0, "light 1 is a point light");
        assert_eq!(f(192), 1.0, "the alpha format");
    }

    #[test]
    fn the_size_must_match_the_texels() {
        let err = CookieTexture::new(vec![[0; 4]; 3], (2, 2), CookieFormat::Rgb);
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
