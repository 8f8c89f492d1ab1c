//! URP's light cookies in the lighting checks (`_LIGHT_COOKIES`): the main light's cookie
//! ([`main_light_cookie`], `universal/light_cookie`'s bindings 20-22) and the additional lights'
//! atlas ([`additional_light_cookies`], bindings 23-25, and the drawn light's index at 9, URP's
//! `_CookieLightIndex`), bound with nearest samplers (the main light's repeating, the atlas
//! clamped to its edges) as the reference, [`wgsl_variants_shaders::reference::urp::cookie`],
//! reads them.

use glam::{Mat4, Vec2, Vec3, Vec4, Vec4Swizzles};

use crate::{BoundResource, CheckError, GpuError, Resource};
use wgsl_variants_shaders::reference::light::{Light, LightShape, look_at_rh};
use wgsl_variants_shaders::reference::urp::cookie::{
    AdditionalLightCookie, AdditionalLightCookies, CookieFormat, CookieProjection, CookieTexture,
    MainLightCookie,
};

/// The cookie a lighting draw binds.
#[derive(Clone, Copy, Debug)]
pub(crate) enum DrawCookie<'a> {
    /// The main light's (bindings 20-22).
    Main(&'a MainLightCookie),
    /// The additional lights' atlas (bindings 23-25) and the drawn light's index in it.
    Additional(&'a AdditionalLightCookies, u32),
}

impl DrawCookie<'_> {
    /// The bindings of `universal/light_cookie` (and the pass's `cookie_light_index`) for this
    /// cookie.
    pub(crate) fn resources(self) -> Vec<BoundResource> {
        match self {
            DrawCookie::Main(cookie) => main_resources(cookie),
            DrawCookie::Additional(cookies, index) => {
                let mut out = atlas_resources(cookies);
                let record = [index, 0, 0, 0].into_iter().flat_map(u32::to_le_bytes);
                out.push(BoundResource::new(
                    0,
                    9,
                    Resource::Uniform(record.collect()),
                ));
                out
            }
        }
    }

    /// The colour the cookie multiplies the light's by at `p`, as a range (the reference's).
    pub(crate) fn color(self, p: Vec3) -> (Vec3, Vec3) {
        match self {
            DrawCookie::Main(cookie) => cookie.color(p),
            DrawCookie::Additional(cookies, index) => cookies.color(index as usize, p),
        }
    }

    /// The colours of the texels the cookie may read at `p` (the reference's).
    pub(crate) fn candidates(self, p: Vec3) -> Vec<Vec3> {
        match self {
            DrawCookie::Main(cookie) => cookie.candidates(p),
            DrawCookie::Additional(cookies, index) => cookies.candidates(index as usize, p),
        }
    }
}

/// Bindings 20-22: the main light's `MainLightCookie` record, its texture and a nearest sampler
/// with repeat addressing.
pub(crate) fn main_resources(cookie: &MainLightCookie) -> Vec<BoundResource> {
    texture_resources(
        [20, 21, 22],
        cookie.uniform(),
        &cookie.texture,
        wgpu::AddressMode::Repeat,
    )
}

/// Bindings 23-25: the `AdditionalLightCookies` record, the atlas and a nearest sampler clamped
/// to the edges.
pub(crate) fn atlas_resources(cookies: &AdditionalLightCookies) -> Vec<BoundResource> {
    texture_resources(
        [23, 24, 25],
        cookies.uniform(),
        &cookies.atlas,
        wgpu::AddressMode::ClampToEdge,
    )
}

/// A record at `bindings[0]`, the texture (`Rgba8Unorm`) at `bindings[1]` and a nearest sampler
/// with `address_mode` at `bindings[2]`.
fn texture_resources(
    bindings: [u32; 3],
    record: Vec<u8>,
    texture: &CookieTexture,
    address_mode: wgpu::AddressMode,
) -> Vec<BoundResource> {
    vec![
        BoundResource::new(0, bindings[0], Resource::Uniform(record)),
        BoundResource::new(
            0,
            bindings[1],
            Resource::Texture2d {
                format: wgpu::TextureFormat::Rgba8Unorm,
                width: texture.size.0,
                height: texture.size.1,
                data: texture.bytes(),
            },
        ),
        BoundResource::new(
            0,
            bindings[2],
            Resource::SamplerAddressed {
                nearest: true,
                address_mode,
            },
        ),
    ]
}

fn refused(variant: &str, message: String) -> GpuError {
    GpuError::from(CheckError::UnknownToReference {
        variant: variant.to_owned(),
        message,
    })
}

/// The main light's cookie of the checks: a 4 × 4 RGB pattern projected along the main light
/// (`light`, directional), its light-space square fitted around `positions` (the check's
/// receivers) with a margin of a twentieth each side, so every texel lights some and their
/// edges cross the picture. `what` names the pass in a refusal.
pub(crate) fn main_light_cookie(
    light: &Light,
    positions: &[Vec3],
    what: &str,
) -> Result<MainLightCookie, GpuError> {
    let main = light.params().map_err(|e| refused(what, e.to_string()))?;
    // The light's frame: looking along the light, z towards it.
    let up = if main.to_light.y.abs() < 0.9 {
        Vec3::Y
    } else {
        Vec3::X
    };
    let rotation = look_at_rh(Vec3::ZERO, -main.to_light, up);
    let (mut lo, mut hi) = (Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY));
    for p in positions {
        let p = (rotation * p.extend(1.0)).xy();
        lo = lo.min(p);
        hi = hi.max(p);
    }
    if (hi - lo).min_element() <= 0.0 {
        return Err(refused(
            what,
            format!("the positions span {lo} to {hi} across the light"),
        ));
    }
    let centre = (lo + hi) * 0.5;
    let scale = Vec2::splat(2.0) / ((hi - lo) * 1.1);
    let world_to_light = Mat4::from_scale(scale.extend(1.0))
        * Mat4::from_translation(-centre.extend(0.0))
        * rotation;
    let texels = (0..4u8)
        .flat_map(|ty| {
            (0..4u8).map(move |tx| [70 + 60 * tx, 70 + 60 * ty, 250 - 40 * ((tx + ty) % 4), 255])
        })
        .collect();
    let texture = CookieTexture::new(texels, (4, 4), CookieFormat::Rgb)
        .map_err(|e| refused(what, e.to_string()))?;
    Ok(MainLightCookie {
        world_to_light,
        texture,
    })
}

/// Width and height of the additional lights' atlas in texels: four 8 × 8 rects.
pub const ATLAS_SIZE: u32 = 16;

/// The rects of the additional lights' atlas (xy size, zw offset), given in turn to the lights
/// with a cookie: its lower-left quarter, the upper-right, the upper-left, the lower-right.
const ATLAS_RECTS: [Vec4; 4] = [
    Vec4::new(0.5, 0.5, 0.0, 0.0),
    Vec4::new(0.5, 0.5, 0.5, 0.5),
    Vec4::new(0.5, 0.5, 0.0, 0.5),
    Vec4::new(0.5, 0.5, 0.5, 0.0),
];

/// The additional lights' cookies of the checks: a 16 × 16 atlas read in its alpha channel (its
/// rgb differs, so reading the wrong channels shows). `lights` are the additional lights in
/// URP's order, `None` for a light without a cookie (an all-zero rect); the point and spot
/// lights with one get the atlas's quarters in turn ([`ATLAS_RECTS`]: the first the lower-left,
/// the second the upper-right; a quarter no light reads differs again, so a light reading
/// outside its rect shows). Each light's `world_to_light` is the built-in light's
/// (`LightParams::world_to_light`: the spot's perspective over its cone's square, the point
/// light's frame), as URP's. `what` names the pass in a refusal.
pub(crate) fn additional_light_cookies(
    lights: &[Option<&Light>],
    what: &str,
) -> Result<AdditionalLightCookies, GpuError> {
    let mut rects = ATLAS_RECTS.into_iter();
    let mut cookie = |light: &Light| {
        let projection = match light.shape {
            LightShape::Point { .. } => CookieProjection::Point,
            LightShape::Spot { .. } => CookieProjection::Spot,
            LightShape::Directional { .. } => {
                return Err(refused(
                    what,
                    "an additional directional light's cookie is not built".to_owned(),
                ));
            }
        };
        let uv_rect = rects
            .next()
            .ok_or_else(|| refused(what, "more than four cookies in the atlas".to_owned()))?;
        let world_to_light = light
            .params()
            .map_err(|e| refused(what, e.to_string()))?
            .world_to_light;
        Ok(AdditionalLightCookie {
            world_to_light,
            uv_rect,
            projection,
        })
    };
    let entries = lights
        .iter()
        .map(|l| l.map(&mut cookie).transpose())
        .collect::<Result<Vec<_>, _>>()?;
    let texels = (0..ATLAS_SIZE)
        .flat_map(|y| {
            (0..ATLAS_SIZE).map(move |x| {
                let alpha = 60 + ((x * 7 + y * 13) % 16) * 12;
                [
                    (255 - alpha) as u8,
                    (x * 16) as u8,
                    (y * 16) as u8,
                    alpha as u8,
                ]
            })
        })
        .collect();
    let atlas = CookieTexture::new(texels, (ATLAS_SIZE, ATLAS_SIZE), CookieFormat::Alpha)
        .map_err(|e| refused(what, e.to_string()))?;
    AdditionalLightCookies::new(atlas, entries).map_err(|e| refused(what, e.to_string()))
}
