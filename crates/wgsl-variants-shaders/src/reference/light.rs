//! Per-pixel lights (docs/shading.md §10): the host API that turns a light's parameters into
//! the `Light` uniform of `wgsl/lighting/light.wgsl` (refusing parameters that make the math
//! undefined), and the reference of the light math: distance falloff, cookies, the spot cone,
//! the world position rebuilt from depth, and the light a pixel receives.
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::light::{Light, LightError, LightType, falloff};
//! let point = Light::point(Vec3::new(0.0, 0.0, 2.0), 4.0, Vec3::ONE).params().unwrap();
//! let (l, attenuation) = point.sample(LightType::Point, Vec3::ZERO, None);
//! assert_eq!(l, Vec3::Z);
//! assert_eq!(attenuation, falloff(0.25)); // |d|² / range² = 4 / 16
//! // Parameters that make the math undefined are refused, never turned into NaN.
//! assert!(matches!(Light::point(Vec3::ZERO, 0.0, Vec3::ONE).params(), Err(LightError::Range { .. })));
//! ```

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::brdf::{Brdf, direct};
use super::cube::CubeFaces;
use super::gbuffer::{GBuffer, decode_normal};
use super::texel::{self, Address};
use super::vector::view_and_reflection;

/// The light keywords of Unity's `multi_compile_lightpass` and `multi_compile_fwdadd`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightType {
    /// `DIRECTIONAL`.
    Directional,
    /// `DIRECTIONAL_COOKIE`: times a repeating 2D cookie's alpha at `(world_to_light · p).xy`.
    DirectionalCookie,
    /// `POINT`.
    Point,
    /// `POINT_COOKIE`: times a cube cookie's alpha in the direction `(world_to_light · p).xyz`.
    PointCookie,
    /// `SPOT`: the point falloff times the default spot cookie ([`spot_cookie`]).
    Spot,
}

impl LightType {
    /// Every light type, in the order of the `ForwardAdd` pass's keyword set.
    pub const ALL: [LightType; 5] = [
        LightType::Directional,
        LightType::DirectionalCookie,
        LightType::Point,
        LightType::PointCookie,
        LightType::Spot,
    ];

    /// The keyword (Unity spelling).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::light::LightType;
    /// assert_eq!(LightType::PointCookie.keyword(), "POINT_COOKIE");
    /// ```
    pub fn keyword(self) -> &'static str {
        match self {
            LightType::Directional => "DIRECTIONAL",
            LightType::DirectionalCookie => "DIRECTIONAL_COOKIE",
            LightType::Point => "POINT",
            LightType::PointCookie => "POINT_COOKIE",
            LightType::Spot => "SPOT",
        }
    }

    /// The light type a keyword names, if it names one.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::light::LightType;
    /// assert_eq!(LightType::from_keyword("SPOT"), Some(LightType::Spot));
    /// assert_eq!(LightType::from_keyword("UNITY_HDR_ON"), None);
    /// ```
    pub fn from_keyword(name: &str) -> Option<LightType> {
        LightType::ALL.into_iter().find(|t| t.keyword() == name)
    }

    /// Splits a variant's keyword names into its light type (the first light keyword, if any)
    /// and the other names.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::light::LightType;
    /// let (light, rest) = LightType::split(&["_NORMAL_MAP", "POINT", "UNITY_HDR_ON"]);
    /// assert_eq!((light, rest), (Some(LightType::Point), vec!["_NORMAL_MAP", "UNITY_HDR_ON"]));
    /// ```
    pub fn split<'a>(names: &[&'a str]) -> (Option<LightType>, Vec<&'a str>) {
        let light = names.iter().find_map(|n| LightType::from_keyword(n));
        let rest = names
            .iter()
            .copied()
            .filter(|n| LightType::from_keyword(n).is_none())
            .collect();
        (light, rest)
    }

    /// Whether the type is lit by a directional light (no position, no range).
    pub fn is_directional(self) -> bool {
        matches!(self, LightType::Directional | LightType::DirectionalCookie)
    }
}

/// The shape of a light, as a renderer describes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightShape {
    /// A directional light. `direction` is the way the light travels (Unity's light forward);
    /// its cookie repeats every `cookie_size` world units in the plane across `direction`,
    /// with its origin at `cookie_origin`.
    Directional {
        /// Direction the light travels (any length > 0).
        direction: Vec3,
        /// Edge length of one cookie tile in world units (> 0).
        cookie_size: f32,
        /// A world point where the cookie's uv is (0, 0).
        cookie_origin: Vec3,
    },
    /// A point light at `position` reaching `range`; its cube cookie is oriented by `forward`
    /// (the cookie's +Z axis).
    Point {
        /// World position.
        position: Vec3,
        /// Range (> 0): no light from `range` on.
        range: f32,
        /// The cube cookie's +Z axis in world space (any length > 0).
        forward: Vec3,
    },
    /// A spot light at `position` shining along `direction`, with a full cone angle of
    /// `angle_degrees` (0 < angle < 180) and range `range`.
    Spot {
        /// World position.
        position: Vec3,
        /// Axis of the cone, the way the light travels (any length > 0).
        direction: Vec3,
        /// Full opening angle of the cone, in degrees.
        angle_degrees: f32,
        /// Range (> 0).
        range: f32,
    },
}

/// A light as a renderer describes it: shape and colour (linear, intensity included).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light {
    /// Shape and placement.
    pub shape: LightShape,
    /// Colour times intensity (each channel finite and ≥ 0).
    pub color: Vec3,
}

/// Why a light's parameters cannot be lit: each would make the math undefined (a division by
/// zero, an infinite cone, a NaN) where the GPU would produce NaN or garbage.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum LightError {
    /// A parameter holds NaN or an infinity.
    #[error("light {what} is not finite: {value}")]
    NonFinite {
        /// The parameter.
        what: &'static str,
        /// Its value, printed.
        value: String,
    },
    /// A colour channel below 0.
    #[error("light colour {0} has a negative channel")]
    NegativeColor(Vec3),
    /// A direction of length 0 (or so small that normalizing it fails).
    #[error("light {what} has no direction (length 0)")]
    ZeroDirection {
        /// The parameter.
        what: &'static str,
    },
    /// A range that is not > 0 (the falloff divides by range²), or whose square is not a
    /// normal `f32`.
    #[error("light range {range} must be > 0 (and range² a normal f32)")]
    Range {
        /// The range given.
        range: f32,
    },
    /// A spot angle outside (0°, 180°): 0 has no cone, 180° and more an infinite one.
    #[error("spot angle {angle_degrees}° must be greater than 0° and less than 180°")]
    SpotAngle {
        /// The angle given.
        angle_degrees: f32,
    },
    /// A spot's inner angle (URP) outside `[0, outer]`, or not finite.
    #[error(
        "spot inner angle {inner_degrees}° must be between 0° and the outer angle {outer_degrees}°"
    )]
    SpotInnerAngle {
        /// The inner angle given.
        inner_degrees: f32,
        /// The outer angle.
        outer_degrees: f32,
    },
    /// More additional lights than a URP forward draw takes.
    #[error("{count} additional lights, but URP's forward pass takes at most {max} per object")]
    TooManyAdditional {
        /// The lights given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// A directional light among URP's additional lights (the forward pass's are point and
    /// spot lights; the directional one is the main light).
    #[error(
        "an additional light of URP's forward pass must be a point or spot light, not directional"
    )]
    AdditionalDirectional,
    /// A directional cookie size that is not > 0.
    #[error("directional cookie size {size} must be > 0")]
    CookieSize {
        /// The size given.
        size: f32,
    },
}

/// A light ready for the shaders: the fields of the WGSL `Light` record
/// ([`LightParams::uniform`] lays them out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightParams {
    /// Colour times intensity.
    pub color: Vec3,
    /// World position (point and spot; the cookie origin for a directional light).
    pub position: Vec3,
    /// `1 / range²` (point and spot; 0 for a directional light).
    pub inv_range_sq: f32,
    /// Unit direction from a surface TO the light (directional; the cone axis reversed for a spot).
    pub to_light: Vec3,
    /// Unity's `unity_WorldToLight`: cookie and spot coordinates of a world point.
    pub world_to_light: Mat4,
}

/// Scalars and vectors of a light's parameters, checked by one [`finite`].
trait Finite: Copy + std::fmt::Display {
    fn all_finite(self) -> bool;
}

impl Finite for f32 {
    fn all_finite(self) -> bool {
        self.is_finite()
    }
}

impl Finite for Vec3 {
    fn all_finite(self) -> bool {
        self.is_finite()
    }
}

fn finite<T: Finite>(what: &'static str, v: T) -> Result<T, LightError> {
    if v.all_finite() {
        Ok(v)
    } else {
        Err(LightError::NonFinite {
            what,
            value: format!("{v}"),
        })
    }
}

fn unit(what: &'static str, v: Vec3) -> Result<Vec3, LightError> {
    let v = finite(what, v)?;
    v.try_normalize().ok_or(LightError::ZeroDirection { what })
}

fn inv_range_sq(range: f32) -> Result<f32, LightError> {
    let range = finite("range", range)?;
    let sq = range * range;
    if range > 0.0 && sq.is_normal() && (1.0 / sq).is_normal() {
        Ok(1.0 / sq)
    } else {
        Err(LightError::Range { range })
    }
}

/// A right-handed orthonormal frame `(right, up, forward)` around a unit `forward`: `up` is
/// world +Y made orthogonal to it (world +Z when `forward` is within about 8° of ±Y).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::light::light_frame;
/// let (right, up, forward) = light_frame(Vec3::NEG_Z);
/// assert!((right - Vec3::NEG_X).length() < 1e-6 && (up - Vec3::Y).length() < 1e-6);
/// assert!((right.cross(up) - forward).length() < 1e-6); // right-handed
/// assert_eq!(forward, Vec3::NEG_Z);
/// ```
pub fn light_frame(forward: Vec3) -> (Vec3, Vec3, Vec3) {
    let helper = if forward.y.abs() > 0.99 {
        Vec3::Z
    } else {
        Vec3::Y
    };
    let right = helper.cross(forward).normalize();
    let up = forward.cross(right);
    (right, up, forward)
}

/// The matrix whose rows are `right`, `up`, `forward` (scaled by `scale`) applied to
/// `p − origin`, with w = 1.
fn frame_matrix(origin: Vec3, (right, up, forward): (Vec3, Vec3, Vec3), scale: Vec3) -> Mat4 {
    let rows = [right * scale.x, up * scale.y, forward * scale.z];
    Mat4::from_cols(
        Vec4::new(rows[0].x, rows[1].x, rows[2].x, 0.0),
        Vec4::new(rows[0].y, rows[1].y, rows[2].y, 0.0),
        Vec4::new(rows[0].z, rows[1].z, rows[2].z, 0.0),
        Vec4::new(
            -rows[0].dot(origin),
            -rows[1].dot(origin),
            -rows[2].dot(origin),
            1.0,
        ),
    )
}

impl Light {
    /// A directional light travelling along `direction`, cookie tiles of 1 world unit at the
    /// origin.
    pub fn directional(direction: Vec3, color: Vec3) -> Light {
        Light {
            shape: LightShape::Directional {
                direction,
                cookie_size: 1.0,
                cookie_origin: Vec3::ZERO,
            },
            color,
        }
    }

    /// A point light at `position` with `range`, cube cookie facing world −Z.
    pub fn point(position: Vec3, range: f32, color: Vec3) -> Light {
        Light {
            shape: LightShape::Point {
                position,
                range,
                forward: Vec3::NEG_Z,
            },
            color,
        }
    }

    /// A spot light at `position` shining along `direction` with a full cone of
    /// `angle_degrees` and `range`.
    pub fn spot(
        position: Vec3,
        direction: Vec3,
        angle_degrees: f32,
        range: f32,
        color: Vec3,
    ) -> Light {
        Light {
            shape: LightShape::Spot {
                position,
                direction,
                angle_degrees,
                range,
            },
            color,
        }
    }

    /// Checks the parameters and computes what the shaders read.
    ///
    /// - Directional: `to_light = −normalize(direction)`; `world_to_light` maps `p` to
    ///   `(right·(p − origin), up·(p − origin), forward·(p − origin)) / cookie_size` in the
    ///   light's frame ([`light_frame`] of the travel direction), so the cookie's uv is `.xy`.
    /// - Point: `inv_range_sq = 1 / range²`; `world_to_light` is the frame of `forward` at the
    ///   light's position (the cube cookie's lookup direction).
    /// - Spot: `inv_range_sq = 1 / range²`, `to_light = −axis`; `world_to_light` is projective:
    ///   `q = (right·d / tan(a/2), up·d / tan(a/2), axis·d / range, axis·d)` with
    ///   `d = p − position`, so `q.xy / q.w` has length 1 on the cone's edge.
    ///
    /// # Errors
    /// [`LightError`]: a non-finite value, a negative colour channel, a zero direction, a range
    /// not > 0, a spot angle outside (0°, 180°), a cookie size not > 0.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::{Light, LightError};
    /// let spot = |angle| Light::spot(Vec3::ZERO, Vec3::NEG_Z, angle, 5.0, Vec3::ONE).params();
    /// assert!(spot(90.0).is_ok());
    /// assert!(matches!(spot(0.0), Err(LightError::SpotAngle { .. })));
    /// assert!(matches!(spot(180.0), Err(LightError::SpotAngle { .. })));
    /// assert!(matches!(spot(f32::NAN), Err(LightError::NonFinite { .. })));
    /// let dark = Light::directional(Vec3::ZERO, Vec3::ONE).params();
    /// assert!(matches!(dark, Err(LightError::ZeroDirection { .. })));
    /// ```
    pub fn params(&self) -> Result<LightParams, LightError> {
        let color = finite("colour", self.color)?;
        if color.min_element() < 0.0 {
            return Err(LightError::NegativeColor(color));
        }
        match self.shape {
            LightShape::Directional {
                direction,
                cookie_size,
                cookie_origin,
            } => {
                let forward = unit("direction", direction)?;
                let size = finite("cookie size", cookie_size)?;
                if size <= 0.0 || !(1.0 / size).is_finite() {
                    return Err(LightError::CookieSize { size });
                }
                let origin = finite("cookie origin", cookie_origin)?;
                Ok(LightParams {
                    color,
                    position: origin,
                    inv_range_sq: 0.0,
                    to_light: -forward,
                    world_to_light: frame_matrix(
                        origin,
                        light_frame(forward),
                        Vec3::splat(1.0 / size),
                    ),
                })
            }
            LightShape::Point {
                position,
                range,
                forward,
            } => {
                let position = finite("position", position)?;
                let inv_range_sq = inv_range_sq(range)?;
                let forward = unit("cookie forward", forward)?;
                Ok(LightParams {
                    color,
                    position,
                    inv_range_sq,
                    to_light: -forward,
                    world_to_light: frame_matrix(position, light_frame(forward), Vec3::ONE),
                })
            }
            LightShape::Spot {
                position,
                direction,
                angle_degrees,
                range,
            } => {
                let position = finite("position", position)?;
                let forward = unit("direction", direction)?;
                let angle = finite("spot angle", angle_degrees)?;
                if !(angle > 0.0 && angle < 180.0) {
                    return Err(LightError::SpotAngle {
                        angle_degrees: angle,
                    });
                }
                let inv_range_sq = inv_range_sq(range)?;
                let tan_half = (angle.to_radians() * 0.5).tan();
                if !(tan_half > 0.0 && (1.0 / tan_half).is_finite() && tan_half.is_finite()) {
                    return Err(LightError::SpotAngle {
                        angle_degrees: angle,
                    });
                }
                let (right, up, axis) = light_frame(forward);
                let frame = frame_matrix(
                    position,
                    (right, up, axis),
                    Vec3::new(1.0 / tan_half, 1.0 / tan_half, 1.0),
                );
                // Rows x, y from the scaled frame; z = axis·d / range; w = axis·d.
                let w_row = frame.row(2);
                let world_to_light = Mat4::from_cols(
                    frame.row(0),
                    frame.row(1),
                    w_row * inv_range_sq.sqrt(),
                    w_row,
                )
                .transpose();
                Ok(LightParams {
                    color,
                    position,
                    inv_range_sq,
                    to_light: -axis,
                    world_to_light,
                })
            }
        }
    }
}

/// A 2D cookie texture (only its alpha matters), sampled with nearest filtering and repeat
/// addressing: `uv` reads texel `(floor(fract(u) · w), floor(fract(v) · h))`, row 0 at v = 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Cookie2d {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Alpha of each texel, row-major.
    pub alpha: Vec<f32>,
}

impl Cookie2d {
    /// The alpha at `uv` (nearest, repeat). A non-finite `uv` reads texel (0, 0).
    ///
    /// ```
    /// use glam::Vec2;
    /// use wgsl_variants_shaders::reference::light::Cookie2d;
    /// let c = Cookie2d { width: 2, height: 1, alpha: vec![0.25, 0.75] };
    /// assert_eq!(c.sample(Vec2::new(0.2, 0.5)), 0.25);
    /// assert_eq!(c.sample(Vec2::new(0.7, 0.5)), 0.75);
    /// assert_eq!(c.sample(Vec2::new(-0.2, 3.5)), 0.75); // repeat
    /// ```
    pub fn sample(&self, uv: Vec2) -> f32 {
        let x = texel::nearest(uv.x, self.width, Address::Repeat) as usize;
        let y = texel::nearest(uv.y, self.height, Address::Repeat) as usize;
        self.alpha[y * self.width as usize + x]
    }

    /// Distance, in texels, from `uv` to the nearest texel edge (how far a lookup is from
    /// reading another texel).
    ///
    /// ```
    /// use glam::Vec2;
    /// use wgsl_variants_shaders::reference::light::Cookie2d;
    /// let c = Cookie2d { width: 4, height: 4, alpha: vec![1.0; 16] };
    /// assert!((c.edge_margin(Vec2::new(0.125, 0.1)) - 0.4).abs() < 1e-6);
    /// ```
    pub fn edge_margin(&self, uv: Vec2) -> f32 {
        texel::edge_distance(uv.x, self.width).min(texel::edge_distance(uv.y, self.height))
    }
}

/// The cookie textures a light may read: the 2D one (`DIRECTIONAL_COOKIE`) and the cube
/// (`POINT_COOKIE`, its faces' alpha; see [`CubeFaces::sample`]).
#[derive(Clone, Copy, Debug)]
pub struct Cookies<'a> {
    /// The 2D cookie.
    pub texture: &'a Cookie2d,
    /// The cube cookie.
    pub cube: &'a CubeFaces,
}

/// The distance falloff (project definition, docs/shading.md §10):
/// `1 / (1 + 25t) · saturate(5 · (1 − t))` for `t < 1`, else 0 (also for NaN), with
/// `t = |d|² / range²`.
///
/// ```
/// use wgsl_variants_shaders::reference::light::falloff;
/// assert_eq!(falloff(0.0), 1.0);
/// assert_eq!(falloff(0.5), 1.0 / 13.5);
/// assert_eq!(falloff(0.875), 0.625 / 22.875);
/// assert_eq!(falloff(1.0), 0.0);
/// assert_eq!(falloff(f32::NAN), 0.0);
/// ```
pub fn falloff(t: f32) -> f32 {
    if t < 1.0 {
        (5.0 * (1.0 - t)).clamp(0.0, 1.0) / (1.0 + 25.0 * t)
    } else {
        0.0
    }
}

/// The default spot cookie, a soft disk (project definition, docs/shading.md §10): 0 when
/// `q.w ≤ 0` (behind the light), else `saturate(5 · (1 − |q.xy / q.w|))`.
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::light::spot_cookie;
/// assert_eq!(spot_cookie(Vec4::new(0.0, 0.0, 0.0, 2.0)), 1.0);
/// assert_eq!(spot_cookie(Vec4::new(1.75, 0.0, 0.0, 2.0)), 0.625);
/// assert_eq!(spot_cookie(Vec4::new(2.0, 0.0, 0.0, 2.0)), 0.0);
/// assert_eq!(spot_cookie(Vec4::new(0.0, 0.0, 0.0, -1.0)), 0.0);
/// ```
pub fn spot_cookie(q: Vec4) -> f32 {
    if q.w <= 0.0 {
        return 0.0;
    }
    let uv = Vec2::new(q.x, q.y) / q.w;
    (5.0 * (1.0 - uv.length())).clamp(0.0, 1.0)
}

impl LightParams {
    /// `world_to_light · (p, 1)`: the cookie / spot coordinates of `p`.
    pub fn light_coords(&self, p: Vec3) -> Vec4 {
        self.world_to_light * p.extend(1.0)
    }

    /// What a point or spot light gives at `p`: `l = −d / |d|` (zero when `p` is the light's
    /// position) and `falloff(|d|² / range²)`, `d = p − position`.
    fn point(&self, p: Vec3) -> (Vec3, f32) {
        let d = p - self.position;
        let dist2 = d.dot(d);
        let l = if dist2 > 0.0 {
            -d / dist2.sqrt()
        } else {
            Vec3::ZERO
        };
        (l, falloff(dist2 * self.inv_range_sq))
    }

    /// The light at world position `p` as its keyword evaluates it: the unit direction to the
    /// light `l` and the attenuation (falloff × cookie, in [0, 1]).
    ///
    /// `cookies` is needed for `DIRECTIONAL_COOKIE` and `POINT_COOKIE`; without it those read
    /// a cookie of alpha 1.
    pub fn sample(
        &self,
        light_type: LightType,
        p: Vec3,
        cookies: Option<Cookies<'_>>,
    ) -> (Vec3, f32) {
        match light_type {
            LightType::Directional => (self.to_light, 1.0),
            LightType::DirectionalCookie => {
                let q = self.light_coords(p);
                let a = cookies.map_or(1.0, |c| c.texture.sample(Vec2::new(q.x, q.y)));
                (self.to_light, a)
            }
            LightType::Point => self.point(p),
            LightType::PointCookie => {
                let (l, f) = self.point(p);
                let dir = self.light_coords(p).truncate();
                let a = cookies.map_or(1.0, |c| c.cube.sample(dir).w);
                (l, f * a)
            }
            LightType::Spot => {
                let (l, f) = self.point(p);
                (l, f * spot_cookie(self.light_coords(p)))
            }
        }
    }

    /// The WGSL `Light` record as 28 floats (a 112-byte uniform): `color` (rgb, 0),
    /// `position` (xyz, 1/range²), `direction` (to_light, 0), then `world_to_light`
    /// column-major.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::Light;
    /// let u = Light::point(Vec3::new(1.0, 2.0, 3.0), 2.0, Vec3::ONE).params().unwrap().uniform();
    /// assert_eq!(&u[4..8], &[1.0, 2.0, 3.0, 0.25]);
    /// ```
    pub fn uniform(&self) -> [f32; 28] {
        let mut out = [0.0; 28];
        out[..4].copy_from_slice(&self.color.extend(0.0).to_array());
        out[4..8].copy_from_slice(&self.position.extend(self.inv_range_sq).to_array());
        out[8..12].copy_from_slice(&self.to_light.extend(0.0).to_array());
        out[12..].copy_from_slice(&self.world_to_light.to_cols_array());
        out
    }
}

/// The world position of the centre of pixel `(x, y)` of a `width × height` target from its
/// depth-buffer value: `ndc = ((x + ½)/w · 2 − 1, 1 − (y + ½)/h · 2, depth)`,
/// `h = inv_view_proj · (ndc, 1)`, `p = h.xyz / h.w` (wgpu conventions: y up in NDC, depth in
/// [0, 1], row 0 at the top). `h.w = 0` (a point at infinity) gives non-finite components.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::light::{look_at_rh, perspective_rh, world_from_depth};
/// let view_proj = perspective_rh(1.0, 1.0, 0.5, 20.0)
///     * look_at_rh(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y);
/// // Pixel (1, 1) of a 2 × 2 target has its centre at ndc (0.5, −0.5).
/// let q = world_from_depth(view_proj.inverse(), 1, 1, 2, 2, 0.9);
/// let back = view_proj * q.extend(1.0);
/// assert!((back.truncate() / back.w - Vec3::new(0.5, -0.5, 0.9)).abs().max_element() < 1e-5);
/// ```
pub fn world_from_depth(
    inv_view_proj: Mat4,
    x: u32,
    y: u32,
    width: u32,
    height: u32,
    depth: f32,
) -> Vec3 {
    let u = (x as f32 + 0.5) / width as f32;
    let v = (y as f32 + 0.5) / height as f32;
    let h = inv_view_proj * Vec4::new(u * 2.0 - 1.0, 1.0 - v * 2.0, depth, 1.0);
    h.truncate() / h.w
}

/// A right-handed perspective projection with wgpu's depth range [0, 1] (camera looking down
/// −Z): vertical field of view `fov_y` in radians, `aspect` = width / height, planes
/// `0 < near < far`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::light::perspective_rh;
/// let p = perspective_rh(1.0, 1.0, 0.5, 20.0);
/// let near = p * Vec3::new(0.0, 0.0, -0.5).extend(1.0);
/// let far = p * Vec3::new(0.0, 0.0, -20.0).extend(1.0);
/// assert!((near.z / near.w).abs() < 1e-6 && (far.z / far.w - 1.0).abs() < 1e-6);
/// ```
pub fn perspective_rh(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let f = 1.0 / (0.5 * fov_y).tan();
    let r = far / (near - far);
    Mat4::from_cols(
        Vec4::new(f / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, f, 0.0, 0.0),
        Vec4::new(0.0, 0.0, r, -1.0),
        Vec4::new(0.0, 0.0, r * near, 0.0),
    )
}

/// A right-handed orthographic projection with wgpu's depth range [0, 1] (camera looking down
/// −Z): `x / half_width`, `y / half_height`, depth `(−z − near) / (far − near)`, `w = 1`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::light::orthographic_rh;
/// let p = orthographic_rh(2.0, 1.0, 1.0, 5.0);
/// // (2, −1, −3): the right edge, the bottom edge, half-way from near (z = −1) to far (z = −5).
/// assert_eq!(p * Vec3::new(2.0, -1.0, -3.0).extend(1.0), glam::Vec4::new(1.0, -1.0, 0.5, 1.0));
/// ```
pub fn orthographic_rh(half_width: f32, half_height: f32, near: f32, far: f32) -> Mat4 {
    let depth = 1.0 / (far - near);
    Mat4::from_cols(
        Vec4::new(1.0 / half_width, 0.0, 0.0, 0.0),
        Vec4::new(0.0, 1.0 / half_height, 0.0, 0.0),
        Vec4::new(0.0, 0.0, -depth, 0.0),
        Vec4::new(0.0, 0.0, -near * depth, 1.0),
    )
}

/// A right-handed view matrix at `eye` looking at `target` with `up` (not parallel to the
/// view direction).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::light::look_at_rh;
/// let v = look_at_rh(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y);
/// assert_eq!(v * Vec3::ZERO.extend(1.0), Vec3::new(0.0, 0.0, -5.0).extend(1.0));
/// ```
pub fn look_at_rh(eye: Vec3, target: Vec3, up: Vec3) -> Mat4 {
    let f = (target - eye).normalize();
    let s = f.cross(up).normalize();
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// The direct light of one light at one pixel: the Standard BRDF's direct term in tier `brdf`
/// ([`direct`]) with `light_color = color · attenuation` and `l` from [`LightParams::sample`].
/// `v = normalize(camera − p)`.
#[allow(clippy::too_many_arguments)]
pub fn light_direct(
    brdf: Brdf,
    diffuse: Vec3,
    spec_color: Vec3,
    smoothness: f32,
    n: Vec3,
    p: Vec3,
    camera_position: Vec3,
    light: &LightParams,
    light_type: LightType,
    cookies: Option<Cookies<'_>>,
) -> Vec3 {
    let (v, _) = view_and_reflection(camera_position, p, n);
    let (l, attenuation) = light.sample(light_type, p, cookies);
    direct(
        brdf,
        diffuse,
        spec_color,
        smoothness,
        n,
        v,
        l,
        light.color * attenuation,
    )
}

/// The deferred lighting pass (`deferred_shading/Lighting`) at one pixel: the light it adds,
/// before the blend. `gbuffer` holds the values read from RT0–RT2 (diffuse = RT0.rgb, spec
/// colour = RT1.rgb, smoothness = RT1.a, `n = decode_normal(RT2.rgb)`), `p` the position rebuilt
/// from depth ([`world_from_depth`]). Occlusion (RT0.a) does not dim direct light.
///
/// RT3 after the draw is [`super::surface::reflections_add`]`(rt3, light, hdr)`: `rt3 + light`
/// (HDR, One/One) or `rt3 · exp2(−light)` (LDR, DstColor/Zero).
pub fn deferred_light(
    brdf: Brdf,
    gbuffer: &GBuffer,
    p: Vec3,
    camera_position: Vec3,
    light: &LightParams,
    light_type: LightType,
    cookies: Option<Cookies<'_>>,
) -> Vec3 {
    let n = decode_normal(gbuffer.rt2.truncate());
    light_direct(
        brdf,
        gbuffer.rt0.truncate(),
        gbuffer.rt1.truncate(),
        gbuffer.rt1.w,
        n,
        p,
        camera_position,
        light,
        light_type,
        cookies,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).abs().max_element() < 1e-5
    }

    #[test]
    fn falloff_is_continuous_and_decreasing() {
        let mut last = falloff(0.0);
        let mut t = 0.0f32;
        while t < 1.2 {
            let f = falloff(t);
            assert!(f <= last && (0.0..=1.0).contains(&f), "t = {t}");
            assert!((last - f).abs() < 0.03, "jump at {t}");
            last = f;
            t += 0.001;
        }
        assert!((falloff(0.8) - 1.0 / 21.0).abs() < 1e-7);
        assert_eq!(falloff(0.81), 5.0 * 0.19f32 / (1.0 + 25.0 * 0.81));
        assert_eq!(falloff(f32::INFINITY), 0.0);
    }

    #[test]
    fn bad_parameters_are_typed_errors() {
        let ok = Vec3::ONE;
        let p = |range| Light::point(Vec3::ZERO, range, ok).params();
        for range in [0.0, -1.0, 1e-30, 1e30] {
            assert!(matches!(p(range), Err(LightError::Range { .. })), "{range}");
        }
        assert!(matches!(
            p(f32::INFINITY),
            Err(LightError::NonFinite { .. })
        ));
        assert!(matches!(p(f32::NAN), Err(LightError::NonFinite { .. })));
        let s = |angle| Light::spot(Vec3::ZERO, Vec3::X, angle, 1.0, ok).params();
        for angle in [0.0, -5.0, 180.0, 270.0] {
            assert!(
                matches!(s(angle), Err(LightError::SpotAngle { .. })),
                "{angle}"
            );
        }
        assert!(s(179.9).is_ok() && s(0.01).is_ok());
        let zero_axis = Light::spot(Vec3::ZERO, Vec3::ZERO, 30.0, 1.0, ok).params();
        assert!(matches!(zero_axis, Err(LightError::ZeroDirection { .. })));
        let nan_pos = Light::point(Vec3::new(f32::NAN, 0.0, 0.0), 1.0, ok).params();
        assert!(matches!(nan_pos, Err(LightError::NonFinite { .. })));
        let negative = Light::point(Vec3::ZERO, 1.0, Vec3::new(1.0, -0.1, 0.0)).params();
        assert!(matches!(negative, Err(LightError::NegativeColor(_))));
        let mut d = Light::directional(Vec3::NEG_Y, ok);
        d.shape = LightShape::Directional {
            direction: Vec3::NEG_Y,
            cookie_size: 0.0,
            cookie_origin: Vec3::ZERO,
        };
        assert!(matches!(d.params(), Err(LightError::CookieSize { .. })));
        // Every error prints a sentence naming the parameter.
        let e = s(180.0).unwrap_err().to_string();
        assert!(e.contains("180") && e.contains("spot angle"), "{e}");
    }

    #[test]
    fn valid_lights_never_give_nan() {
        let lights = [
            Light::directional(Vec3::new(0.3, -1.0, 0.2), Vec3::ONE),
            Light::point(Vec3::ZERO, 1e-3, Vec3::ONE),
            Light::spot(Vec3::ZERO, Vec3::Y, 179.0, 1e6, Vec3::ONE),
            Light::spot(Vec3::ZERO, Vec3::NEG_Y, 0.5, 2.0, Vec3::ONE),
        ];
        let points = [
            Vec3::ZERO,
            Vec3::new(0.0, 1e-6, 0.0),
            Vec3::splat(1e6),
            Vec3::NEG_Y,
        ];
        for light in lights {
            let params = light.params().unwrap();
            for t in LightType::ALL {
                for p in points {
                    let (l, a) = params.sample(t, p, None);
                    assert!(l.is_finite() && a.is_finite(), "{light:?} {t:?} {p}");
                    assert!((0.0..=1.0).contains(&a));
                }
            }
        }
    }

    #[test]
    fn spot_cone_edge_is_the_angle() {
        let spot = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 60.0, 10.0, Vec3::ONE)
            .params()
            .unwrap();
        assert!(close(spot.to_light, Vec3::Z));
        // On the axis: full cookie; at 30° off the axis: the edge (|uv| = 1, cookie 0); at
        // 27°: inside the soft rim.
        let at = |deg: f32| {
            let r = deg.to_radians();
            spot.light_coords(Vec3::new(r.sin(), 0.0, -r.cos()) * 2.0)
        };
        assert_eq!(spot_cookie(at(0.0)), 1.0);
        let q = at(30.0);
        assert!(((q.truncate().truncate() / q.w).length() - 1.0).abs() < 1e-5);
        assert!(spot_cookie(at(30.5)) == 0.0 && spot_cookie(at(27.0)) > 0.0);
        // Behind the light: nothing.
        assert_eq!(
            spot_cookie(spot.light_coords(Vec3::new(0.0, 0.0, 1.0))),
            0.0
        );
        // q.z is the distance along the axis over the range.
        assert!((at(0.0).z - 0.2).abs() < 1e-6);
    }

    #[test]
    fn directional_cookie_coordinates_tile_across_the_light() {
        let light = Light {
            shape: LightShape::Directional {
                direction: Vec3::NEG_Z,
                cookie_size: 2.0,
                cookie_origin: Vec3::new(1.0, 0.0, 0.0),
            },
            color: Vec3::ONE,
        }
        .params()
        .unwrap();
        let q = light.light_coords(Vec3::new(2.0, 1.0, 5.0));
        // The frame of −Z: right = −X, up = +Y.
        assert!((q.x + 0.5).abs() < 1e-6 && (q.y - 0.5).abs() < 1e-6);
        let cookie = Cookie2d {
            width: 2,
            height: 2,
            alpha: vec![0.0, 0.25, 0.5, 1.0],
        };
        let cookies = Cookies {
            texture: &cookie,
            cube: &CubeFaces::uniform(Vec4::ONE),
        };
        let (l, a) = light.sample(
            LightType::DirectionalCookie,
            Vec3::new(2.5, 1.5, 0.0),
            Some(cookies),
        );
        assert_eq!((l, a), (Vec3::Z, 0.5)); // uv (−0.75, 0.75): texel (0, 1)
        assert_eq!(
            light
                .sample(LightType::Directional, Vec3::ZERO, Some(cookies))
                .1,
            1.0
        );
    }

    #[test]
    fn depth_round_trip() {
        let view_proj = perspective_rh(0.8, 1.0, 0.5, 20.0)
            * look_at_rh(Vec3::new(0.75, -0.5, 6.0), Vec3::ZERO, Vec3::Y);
        let inv = view_proj.inverse();
        for (x, y) in [(0, 0), (7, 3), (15, 15)] {
            let p = world_from_depth(inv, x, y, 16, 16, 0.95);
            let clip = view_proj * p.extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let want_x = (2 * x + 1) as f32 / 16.0 - 1.0;
            let want_y = 1.0 - (2 * y + 1) as f32 / 16.0;
            assert!(close(ndc, Vec3::new(want_x, want_y, 0.95)), "{ndc}");
        }
    }

    #[test]
    fn deferred_light_hand_computed() {
        // A white directional light straight down onto an upward surface seen from above:
        // nl = 1, h = n, spec = (p + 8)/(8π).
        let light = Light::directional(Vec3::NEG_Y, Vec3::ONE).params().unwrap();
        let g = GBuffer::pack(
            Vec3::splat(0.5),
            1.0,
            Vec3::splat(0.04),
            0.0,
            Vec3::Y,
            Vec3::ZERO,
            true,
        );
        let c = deferred_light(
            Brdf::Brdf2,
            &g,
            Vec3::ZERO,
            Vec3::new(0.0, 3.0, 0.0),
            &light,
            LightType::Directional,
            None,
        );
        // BRDF2 with n = v = l, smoothness 0 (a = 1): ks = 1 / (1.5 · 1.00001² · 4).
        let spec = 0.04 / (1.5 * 1.00001f32 * 1.00001 * 4.0);
        assert!(close(c, Vec3::splat(0.5 + spec)), "{c}");
        // The same surface under a point light out of range: nothing.
        let far = Light::point(Vec3::new(0.0, 3.0, 0.0), 2.0, Vec3::ONE)
            .params()
            .unwrap();
        let none = deferred_light(
            Brdf::Brdf1,
            &g,
            Vec3::ZERO,
            Vec3::new(0.0, 3.0, 0.0),
            &far,
            LightType::Point,
            None,
        );
        assert_eq!(none, Vec3::ZERO);
    }
}
