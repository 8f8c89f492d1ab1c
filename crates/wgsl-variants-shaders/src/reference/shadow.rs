//! Shadows of the per-pixel lights (docs/shading.md §11), written from the formulas: the host
//! API that turns a light into the `Shadow` uniform of `wgsl/lighting/shadow.wgsl` (refusing
//! what has no shadow or makes the math undefined), the matrices the shadow maps are rendered
//! with, and the receiver's side — the depth comparison, the `SHADOWS_SOFT` filters and the
//! strength — against a shadow map given as data (in the GPU tests, the map the GPU rendered,
//! read back).
//!
//! - `SHADOWS_DEPTH` (spot): `c = shadow_coords(world_to_shadow, p)`; a tap at texel `(i, j)`
//!   is lit when `c.z − bias ≤ map[i, j]` (a `LessEqual` comparison sampler, nearest, clamp to
//!   edge). Hard: the texel under `c.xy`. Soft: the 3 × 3 texels around it with tent weights
//!   `(1 2 1) ⊗ (1 2 1) / 16`.
//! - `SHADOWS_CUBE` (point): the map stores `|p − light| / range`; a tap in direction `d` is
//!   lit when `stored(d) ≥ |d| / range · 0.97`. Soft: Unity's four taps at `d + o_k / 128`,
//!   `o_k` = (1,1,1), (−1,−1,1), (−1,1,−1), (1,−1,−1), weight ¼ each.
//! - The shadow factor multiplying the light: `mix(1 − strength, 1, visibility)`.
//!
//! A tap whose texel or comparison is within a hair of flipping ([`TEXEL_MARGIN`],
//! [`DEPTH_MARGIN`], [`DISTANCE_MARGIN`]) may go either way on a GPU; [`Visibility`] carries
//! the interval such taps allow, and is exact (`lo == hi`) everywhere else.
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::light::Light;
//! use wgsl_variants_shaders::reference::shadow::{ShadowError, ShadowMap2d, ShadowParams, shadow_mix};
//! let spot = Light::spot(Vec3::new(0.0, 0.0, 4.0), Vec3::NEG_Z, 60.0, 8.0, Vec3::ONE);
//! let params = ShadowParams::for_light(&spot, 0.75, 0.001).unwrap();
//! // A map whose caster is at depth 0.5 everywhere: the floor (deeper) is in shadow.
//! let map = ShadowMap2d::new(4, 4, vec![0.5; 16]).unwrap();
//! let v = map.visibility(params.coords(Vec3::new(0.3, 0.2, 0.0)), false);
//! assert_eq!((v.lo, v.hi), (0.0, 0.0));
//! assert_eq!(shadow_mix(params.strength, v.lo), 0.25);
//! // A directional light's map covers a region of the scene: `for_directional`.
//! let sun = Light::directional(Vec3::NEG_Z, Vec3::ONE);
//! assert!(matches!(ShadowParams::for_light(&sun, 1.0, 0.0), Err(ShadowError::NoShadowMap { .. })));
//! assert!(ShadowParams::for_directional(&sun, 1.0, 0.001, Vec3::ZERO, 2.0).is_ok());
//! ```

use glam::{Mat4, Vec3, Vec4};

use super::cube::face;
use super::light::{
    Light, LightError, LightShape, light_frame, look_at_rh, orthographic_rh, perspective_rh,
};

/// The near plane of a spot light's shadow projection, as a fraction of its range.
pub const SPOT_SHADOW_NEAR: f32 = 0.02;

/// The near plane of a point light's cube faces, as a fraction of its range.
pub const CUBE_SHADOW_NEAR: f32 = 0.01;

/// The receiver's distance factor of `SHADOWS_CUBE` (Unity's `mydist *= 0.97` in
/// `UnityShadowLibrary.cginc`): a surface compares 3 % nearer than it is, so it does not
/// shadow itself through the map's precision.
pub const CUBE_SHADOW_BIAS: f32 = 0.97;

/// The `SHADOWS_SOFT` cube taps' offset in world units (Unity's `1.0 / 128`).
pub const CUBE_SOFT_OFFSET: f32 = 1.0 / 128.0;

/// The `SHADOWS_SOFT` cube taps' diagonals (each scaled by [`CUBE_SOFT_OFFSET`]), weight ¼ each.
pub const CUBE_SOFT_DIAGONALS: [Vec3; 4] = [
    Vec3::new(1.0, 1.0, 1.0),
    Vec3::new(-1.0, -1.0, 1.0),
    Vec3::new(-1.0, 1.0, -1.0),
    Vec3::new(1.0, -1.0, -1.0),
];

/// The `SHADOWS_SOFT` 2D footprint: texel offsets and tent weights `(1 2 1) ⊗ (1 2 1) / 16`.
pub const PCF_TENT_3X3: [([i32; 2], f32); 9] = [
    ([-1, -1], 1.0 / 16.0),
    ([0, -1], 2.0 / 16.0),
    ([1, -1], 1.0 / 16.0),
    ([-1, 0], 2.0 / 16.0),
    ([0, 0], 4.0 / 16.0),
    ([1, 0], 2.0 / 16.0),
    ([-1, 1], 1.0 / 16.0),
    ([0, 1], 2.0 / 16.0),
    ([1, 1], 1.0 / 16.0),
];

/// A texel lookup this close (in texels) to a texel edge, or a cube lookup this close to a face
/// edge, may pick either neighbour on a GPU.
pub const TEXEL_MARGIN: f32 = 0.01;

/// A 2D comparison whose two depths are this close may go either way on a GPU (the reference
/// depth may be rounded to the map's 16 bits before comparing: half a step is 7.6e-6).
pub const DEPTH_MARGIN: f32 = 2e-5;

/// A cube comparison whose two distances (over the range) are this close may go either way.
pub const DISTANCE_MARGIN: f32 = 1e-4;

/// URP's `BEYOND_SHADOW_FAR` (URP's `Shadows.hlsl`, `SampleShadowmap`): a receiver whose map
/// coordinate lies outside the light's depth range (`z ≤ 0` or `z ≥ 1`; wgpu's range, depth not
/// reversed) reads as lit, whatever the map holds. The factor `(lo, hi)` at map depth `z`:
/// `(1, 1)` beyond, unchanged inside, and both outcomes within [`DEPTH_MARGIN`] of either end.
///
/// ```
/// use wgsl_variants_shaders::reference::shadow::lit_beyond_shadow_far;
/// assert_eq!(lit_beyond_shadow_far(1.2, (0.1, 0.1)), (1.0, 1.0));
/// assert_eq!(lit_beyond_shadow_far(0.5, (0.1, 0.1)), (0.1, 0.1));
/// assert_eq!(lit_beyond_shadow_far(1.0 - 1e-6, (0.1, 0.1)), (0.1, 1.0));
/// ```
pub fn lit_beyond_shadow_far(z: f32, (lo, hi): (f32, f32)) -> (f32, f32) {
    let beyond = z <= 0.0 || z >= 1.0;
    let near_an_end = z.abs() < DEPTH_MARGIN || (z - 1.0).abs() < DEPTH_MARGIN;
    match (beyond, near_an_end) {
        (_, true) => (lo.min(1.0), 1.0),
        (true, false) => (1.0, 1.0),
        (false, false) => (lo, hi),
    }
}

/// Why a light's shadow cannot be set up, or a shadow map is unusable.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ShadowError {
    /// The light itself is invalid.
    #[error(transparent)]
    Light(#[from] LightError),
    /// A directional light given to [`ShadowParams::for_light`]: its map covers a region of the
    /// scene, which [`ShadowParams::for_directional`] takes.
    #[error(
        "a {light} light's shadow map covers a region of the scene: use ShadowParams::for_directional"
    )]
    NoShadowMap {
        /// The light's kind.
        light: &'static str,
    },
    /// A point or spot light given to [`ShadowParams::for_directional`].
    #[error(
        "only a directional light has a SHADOWS_SCREEN shadow (point and spot lights: ShadowParams::for_light)"
    )]
    NotDirectional,
    /// A directional shadow's region that is not finite or has no size.
    #[error(
        "the shadowed region (centre {center}, radius {radius}) must be finite with a radius > 0"
    )]
    Region {
        /// Its centre.
        center: Vec3,
        /// Its radius.
        radius: f32,
    },
    /// A strength outside [0, 1] (or NaN).
    #[error("shadow strength {0} must be in [0, 1]")]
    Strength(f32),
    /// A depth bias that is negative, not finite, or ≥ 1 (a whole depth range).
    #[error("shadow depth bias {0} must be finite and in [0, 1)")]
    Bias(f32),
    /// A map whose data does not fill its size, or of size 0.
    #[error("shadow map of {width} x {height} (x {faces} faces) needs {needed} texels, got {got}")]
    MapSize {
        /// Width in texels.
        width: u32,
        /// Height in texels.
        height: u32,
        /// 1 for a 2D map, 6 for a cube.
        faces: u32,
        /// Texels needed.
        needed: usize,
        /// Texels given.
        got: usize,
    },
    /// Cascade split depths that are not 2, 3 or 5 increasing view depths above 0 (1, 2 or 4
    /// cascades; [`crate::reference::cascades::Cascades::fit`]).
    #[error("cascade splits {0:?} must be 2, 3 or 5 increasing view depths above 0")]
    Cascades(Vec<f32>),
    /// Split spheres that are not 1 to 4 ([`crate::reference::cascades::Cascades::from_spheres`];
    /// each sphere is also checked as a directional region).
    #[error("{0} split spheres: URP's main light has 1 to 4 cascades")]
    SplitSpheres(usize),
    /// A shadow fade whose ramp is not finite or not increasing, or whose camera has no
    /// forward axis ([`crate::reference::shadow_fade::ShadowFade::new`]).
    #[error("shadow fade from {start} to {end} needs finite values, start < end and a camera axis")]
    Fade {
        /// Fade distance where the fade starts.
        start: f32,
        /// Fade distance where the realtime shadow is gone.
        end: f32,
    },
    /// URP's additional-light shadows with more lights or slices than the receivers' record
    /// holds, or a light whose slices are not all there
    /// ([`crate::reference::urp::additional_shadow::AdditionalShadows::new`]).
    #[error(
        "additional-light shadows of {lights} lights over {slices} slices: at most 8 lights and 48 slices, and every light's slices (six for a point light) among them"
    )]
    AdditionalSlices {
        /// Lights given.
        lights: usize,
        /// Slices given.
        slices: usize,
    },
    /// A map texel that is NaN or infinite.
    #[error("shadow map texel {index} is not finite: {value}")]
    NonFiniteTexel {
        /// Index of the texel (row-major, faces in wgpu layer order).
        index: usize,
        /// Its value.
        value: f32,
    },
}

/// What the receivers read of a light's shadow: the fields of the WGSL `Shadow` record
/// ([`ShadowParams::uniform`] lays them out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowParams {
    /// A spot's view-projection (world to the map's clip space); identity for a point light.
    pub world_to_shadow: Mat4,
    /// Strength in [0, 1]: the shadowed light keeps `1 − strength`.
    pub strength: f32,
    /// Spot: the depth bias subtracted from the receiver; point: [`CUBE_SHADOW_BIAS`].
    pub bias: f32,
    /// `1 / range`.
    pub inv_range: f32,
    /// The light's world position.
    pub light_position: Vec3,
}

impl ShadowParams {
    /// The shadow of a spot (`SHADOWS_DEPTH`, `depth_bias` in depth-buffer units) or point light
    /// (`SHADOWS_CUBE`, `depth_bias` unused: [`CUBE_SHADOW_BIAS`]) at `strength`.
    ///
    /// # Errors
    /// [`ShadowError`]: an invalid light, a directional light, a strength outside [0, 1], a
    /// bias outside [0, 1).
    pub fn for_light(
        light: &Light,
        strength: f32,
        depth_bias: f32,
    ) -> Result<ShadowParams, ShadowError> {
        light.params()?;
        if !(0.0..=1.0).contains(&strength) {
            return Err(ShadowError::Strength(strength));
        }
        match light.shape {
            LightShape::Directional { .. } => Err(ShadowError::NoShadowMap {
                light: "directional",
            }),
            LightShape::Point {
                position, range, ..
            } => Ok(ShadowParams {
                world_to_shadow: Mat4::IDENTITY,
                strength,
                bias: CUBE_SHADOW_BIAS,
                inv_range: 1.0 / range,
                light_position: position,
            }),
            LightShape::Spot {
                position,
                direction,
                angle_degrees,
                range,
            } => {
                if !(depth_bias.is_finite() && (0.0..1.0).contains(&depth_bias)) {
                    return Err(ShadowError::Bias(depth_bias));
                }
                Ok(ShadowParams {
                    world_to_shadow: spot_shadow_view_proj(
                        position,
                        direction,
                        angle_degrees,
                        range,
                    ),
                    strength,
                    bias: depth_bias,
                    inv_range: 1.0 / range,
                    light_position: position,
                })
            }
        }
    }

    /// The shadow of a directional light (`SHADOWS_SCREEN`): one cascade, a 2D map through
    /// [`directional_shadow_view_proj`] covering the sphere (`center`, `radius`) of the scene,
    /// compared as a spot's map is (`depth_bias` in depth-buffer units). The screen-space pass
    /// (`internal/screen_space_shadows`) turns it into the mask the lighting pass reads.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::Light;
    /// use wgsl_variants_shaders::reference::shadow::ShadowParams;
    /// let sun = Light::directional(Vec3::NEG_Z, Vec3::ONE);
    /// let p = ShadowParams::for_directional(&sun, 0.5, 0.001, Vec3::ZERO, 2.0).unwrap();
    /// // The centre of the region: the middle of the map, half-way in depth.
    /// let c = p.coords(Vec3::ZERO);
    /// assert!((c - Vec3::new(0.5, 0.5, 0.5)).abs().max_element() < 1e-6);
    /// ```
    ///
    /// # Errors
    /// [`ShadowError`]: an invalid light or one that is not directional
    /// ([`ShadowError::NotDirectional`]), a strength outside [0, 1], a bias outside [0, 1), a
    /// region that is not finite or has no size.
    pub fn for_directional(
        light: &Light,
        strength: f32,
        depth_bias: f32,
        center: Vec3,
        radius: f32,
    ) -> Result<ShadowParams, ShadowError> {
        light.params()?;
        if !(0.0..=1.0).contains(&strength) {
            return Err(ShadowError::Strength(strength));
        }
        if !(depth_bias.is_finite() && (0.0..1.0).contains(&depth_bias)) {
            return Err(ShadowError::Bias(depth_bias));
        }
        if !(center.is_finite() && radius.is_finite() && radius > 0.0) {
            return Err(ShadowError::Region { center, radius });
        }
        let LightShape::Directional { direction, .. } = light.shape else {
            return Err(ShadowError::NotDirectional);
        };
        let forward = direction.normalize();
        Ok(ShadowParams {
            world_to_shadow: directional_shadow_view_proj(forward, center, radius),
            strength,
            bias: depth_bias,
            inv_range: 0.0,
            light_position: center - forward * (2.0 * radius),
        })
    }

    /// The map coordinates of `p` ([`shadow_coords`] through `world_to_shadow`).
    pub fn coords(&self, p: Vec3) -> Vec3 {
        shadow_coords(self.world_to_shadow, p)
    }

    /// The receiver's distance for `SHADOWS_CUBE`: `|p − light| / range · bias`.
    pub fn cube_distance(&self, p: Vec3) -> f32 {
        (p - self.light_position).length() * self.inv_range * self.bias
    }

    /// The WGSL `Shadow` record as 20 floats (an 80-byte uniform): `world_to_shadow`
    /// column-major, then `(strength, bias, 0, 1 / range)`.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::light::Light;
    /// use wgsl_variants_shaders::reference::shadow::ShadowParams;
    /// let point = Light::point(Vec3::ZERO, 4.0, Vec3::ONE);
    /// let u = ShadowParams::for_light(&point, 0.5, 0.0).unwrap().uniform();
    /// assert_eq!(&u[16..], &[0.5, 0.97, 0.0, 0.25]);
    /// ```
    pub fn uniform(&self) -> [f32; 20] {
        let mut out = [0.0; 20];
        out[..16].copy_from_slice(&self.world_to_shadow.to_cols_array());
        out[16..].copy_from_slice(&[self.strength, self.bias, 0.0, self.inv_range]);
        out
    }
}

/// A spot light's shadow view-projection: a square perspective of the full cone angle from
/// the light's position along its axis (up from [`light_frame`]), near plane at
/// [`SPOT_SHADOW_NEAR`] · range, far plane at the range. Depth 0..1 as wgpu's.
pub fn spot_shadow_view_proj(
    position: Vec3,
    direction: Vec3,
    angle_degrees: f32,
    range: f32,
) -> Mat4 {
    let (_, up, forward) = light_frame(direction.normalize());
    perspective_rh(
        angle_degrees.to_radians(),
        1.0,
        range * SPOT_SHADOW_NEAR,
        range,
    ) * look_at_rh(position, position + forward, up)
}

/// A directional light's shadow view-projection (one cascade): an orthographic box around the
/// sphere (`center`, `radius`), looking along `forward` (the light's travel direction, unit
/// length; up from [`light_frame`]) from `center − 2 · radius · forward`, width and height
/// `2 · radius`, near plane at `radius` and far plane at `3 · radius` from the eye, so the
/// sphere lies inside and its centre at depth ½. Depth 0..1 as wgpu's.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::shadow::{directional_shadow_view_proj, shadow_coords};
/// let m = directional_shadow_view_proj(Vec3::NEG_Z, Vec3::ZERO, 2.0);
/// // Looking down −Z from z = 4: z = 2 is the near plane (depth 0), z = −2 the far (depth 1);
/// // x = 2 is the box's side, u = 1 (or 0: the light's frame picks the sides).
/// assert!(shadow_coords(m, Vec3::new(0.0, 0.0, 2.0)).z.abs() < 1e-6);
/// assert!((shadow_coords(m, Vec3::new(0.0, 0.0, -2.0)).z - 1.0).abs() < 1e-6);
/// let u = shadow_coords(m, Vec3::new(2.0, 0.0, 0.0));
/// assert!((u.x - 1.0).abs() < 1e-6 || u.x.abs() < 1e-6 || (u.y - 1.0).abs() < 1e-6 || u.y.abs() < 1e-6);
/// ```
pub fn directional_shadow_view_proj(forward: Vec3, center: Vec3, radius: f32) -> Mat4 {
    let (_, up, forward) = light_frame(forward);
    let eye = center - forward * (2.0 * radius);
    orthographic_rh(radius, radius, radius, 3.0 * radius) * look_at_rh(eye, center, up)
}

/// The view-projection of cube face `face` (wgpu layer order +X, −X, +Y, −Y, +Z, −Z) of a
/// point light at `position` with `range`: a 90° frustum whose pixel `(x, y)` of a
/// `size × size` target sees the directions the cube samples at that face's texel `(x, y)`
/// (the Vulkan cube-map face coordinates: `ndc.x = sc / |ma|`, `ndc.y = −tc / |ma|`), depth
/// from [`CUBE_SHADOW_NEAR`] · range to range. Mirrored on some faces: draw without culling.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::shadow::cube_face_view_proj;
/// // +Y (face 2): a point straight above the light lands at the face's centre.
/// let c = cube_face_view_proj(Vec3::ZERO, 2, 10.0) * Vec3::new(0.0, 3.0, 0.0).extend(1.0);
/// assert!((c.x / c.w).abs() < 1e-6 && (c.y / c.w).abs() < 1e-6);
/// assert!((0.0..1.0).contains(&(c.z / c.w)));
/// ```
pub fn cube_face_view_proj(position: Vec3, face: usize, range: f32) -> Mat4 {
    // (sc, tc, ma) axes of each face, as the cube-map lookup defines them.
    let (sc, tc, ma) = match face {
        0 => (Vec3::NEG_Z, Vec3::NEG_Y, Vec3::X),
        1 => (Vec3::Z, Vec3::NEG_Y, Vec3::NEG_X),
        2 => (Vec3::X, Vec3::Z, Vec3::Y),
        3 => (Vec3::X, Vec3::NEG_Z, Vec3::NEG_Y),
        4 => (Vec3::X, Vec3::NEG_Y, Vec3::Z),
        _ => (Vec3::NEG_X, Vec3::NEG_Y, Vec3::NEG_Z),
    };
    let (near, far) = (range * CUBE_SHADOW_NEAR, range);
    let a = far / (far - near);
    let b = -near * far / (far - near);
    // Rows on d = p − position: x = sc·d, y = −tc·d, z = a (ma·d) + b, w = ma·d.
    let row = |v: Vec3, k: f32| Vec4::new(v.x, v.y, v.z, k - v.dot(position));
    let (x, y, w) = (row(sc, 0.0), row(-tc, 0.0), row(ma, 0.0));
    let z = w * a + Vec4::new(0.0, 0.0, 0.0, b);
    Mat4::from_cols(x, y, z, w).transpose()
}

/// The clip-space transform that puts a whole map's view into tile `i` of an atlas of
/// `cols × rows` tiles (row-major): texture coordinates `(uv + tile) / grid`. Folded into a
/// view-projection (`atlas_tile(grid, i) * view_proj`), it gives the matrix a receiver reads
/// the atlas with (URP's cascades and additional-light slices).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::shadow::{atlas_tile, shadow_coords};
/// // The map's centre lands in the centre of tile 5 (second row, second column) of 4 × 2.
/// let c = shadow_coords(atlas_tile((4, 2), 5), Vec3::new(0.0, 0.0, 0.5));
/// assert_eq!((c.x, c.y, c.z), (0.375, 0.75, 0.5));
/// ```
pub fn atlas_tile((cols, rows): (u32, u32), i: usize) -> Mat4 {
    let (tx, ty) = ((i as u32 % cols) as f32, (i as u32 / cols) as f32);
    // u' = (u + tx) / cols with u = x/2 + 1/2; v' = (v + ty) / rows with v = 1/2 − y/2.
    let (sx, sy) = (1.0 / cols as f32, 1.0 / rows as f32);
    Mat4::from_cols(
        Vec4::new(sx, 0.0, 0.0, 0.0),
        Vec4::new(0.0, sy, 0.0, 0.0),
        Vec4::Z,
        Vec4::new(
            sx * (1.0 + 2.0 * tx) - 1.0,
            1.0 - sy * (1.0 + 2.0 * ty),
            0.0,
            1.0,
        ),
    )
}

/// What `standard/ShadowCaster` writes into a `SHADOWS_CUBE` face for the surface point `p`:
/// the light-to-surface distance over the range, `|p − light| · inv_range` (Unity's
/// `UnityEncodeCubeShadowDepth` input; no bias on the caster's side). Under `SHADOWS_DEPTH`
/// the caster writes only the rasterizer's depth, [`shadow_coords`]`(view_proj, p).z`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::shadow::caster_distance;
/// // 3-4-5: |(3, 4, 0) − 0| = 5, over a range of 10.
/// assert_eq!(caster_distance(Vec3::new(3.0, 4.0, 0.0), Vec3::ZERO, 0.1), 0.5);
/// ```
pub fn caster_distance(p: Vec3, light: Vec3, inv_range: f32) -> f32 {
    (p - light).length() * inv_range
}

/// Clip → NDC → map space: `u = x/2 + ½`, `v = ½ − y/2` (rows run down), `z` the NDC depth.
pub fn shadow_coords(world_to_shadow: Mat4, p: Vec3) -> Vec3 {
    let q = world_to_shadow * p.extend(1.0);
    let ndc = q.truncate() / q.w;
    Vec3::new(ndc.x * 0.5 + 0.5, 0.5 - ndc.y * 0.5, ndc.z)
}

/// The shadow factor: `mix(1 − strength, 1, visibility)` (Unity's
/// `lerp(_LightShadowData.r, 1, visibility)`).
///
/// ```
/// use wgsl_variants_shaders::reference::shadow::shadow_mix;
/// assert_eq!(shadow_mix(1.0, 0.0), 0.0);
/// assert_eq!(shadow_mix(0.6, 0.5), 0.7);
/// assert_eq!(shadow_mix(0.3, 1.0), 1.0);
/// ```
pub fn shadow_mix(strength: f32, visibility: f32) -> f32 {
    (1.0 - strength) + (1.0 - (1.0 - strength)) * visibility
}

/// The fraction of a light that reaches a point, as an interval: `lo == hi` where every tap
/// is clear of [`TEXEL_MARGIN`] and the depth margins; otherwise the taps that could flip span
/// `[lo, hi]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Visibility {
    /// The visibility with every uncertain tap shadowed.
    pub lo: f32,
    /// The visibility with every uncertain tap lit.
    pub hi: f32,
}

impl Visibility {
    /// Whether no tap is uncertain.
    pub fn is_exact(&self) -> bool {
        self.lo == self.hi
    }

    fn add(&mut self, weight: f32, lit: bool, certain: bool) {
        if lit || !certain {
            self.hi += weight;
        }
        if lit && certain {
            self.lo += weight;
        }
    }
}

fn texel_margin(coord: f32) -> f32 {
    (coord - coord.round()).abs()
}

fn checked(values: &[f32], needed: usize, size: (u32, u32, u32)) -> Result<(), ShadowError> {
    if needed == 0 || values.len() != needed {
        return Err(ShadowError::MapSize {
            width: size.0,
            height: size.1,
            faces: size.2,
            needed,
            got: values.len(),
        });
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(ShadowError::NonFiniteTexel {
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

/// A 2D shadow map (`SHADOWS_DEPTH`): one depth in [0, 1] per texel, row 0 at `v = 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowMap2d {
    width: u32,
    height: u32,
    depth: Vec<f32>,
}

impl ShadowMap2d {
    /// A `width × height` map from row-major depths.
    ///
    /// # Errors
    /// [`ShadowError::MapSize`] when `depth` does not hold exactly `width · height > 0` texels,
    /// [`ShadowError::NonFiniteTexel`] for NaN or ±∞.
    pub fn new(width: u32, height: u32, depth: Vec<f32>) -> Result<ShadowMap2d, ShadowError> {
        checked(&depth, width as usize * height as usize, (width, height, 1))?;
        Ok(ShadowMap2d {
            width,
            height,
            depth,
        })
    }

    /// A map read back from a `Depth16Unorm` texture: `depth = value / 65535`.
    ///
    /// # Errors
    /// As [`ShadowMap2d::new`].
    pub fn from_depth16(
        width: u32,
        height: u32,
        texels: &[u16],
    ) -> Result<ShadowMap2d, ShadowError> {
        Self::new(
            width,
            height,
            texels.iter().map(|&t| f32::from(t) / 65535.0).collect(),
        )
    }

    /// The stored depth at texel `(x, y)`, clamped to the edge.
    pub fn depth(&self, x: i64, y: i64) -> f32 {
        let x = x.clamp(0, i64::from(self.width) - 1) as usize;
        let y = y.clamp(0, i64::from(self.height) - 1) as usize;
        self.depth[y * self.width as usize + x]
    }

    /// The visibility at map coordinates `c` ([`shadow_coords`]; `c.z` already biased):
    /// one tap under `c.xy` (hard) or the [`PCF_TENT_3X3`] footprint around it (soft). A tap
    /// is uncertain when moving `c.xy` by [`TEXEL_MARGIN`] texels picks a texel with the other
    /// outcome, or its depths are within [`DEPTH_MARGIN`].
    pub fn visibility(&self, c: Vec3, soft: bool) -> Visibility {
        let (u, v) = (c.x * self.width as f32, c.y * self.height as f32);
        let m = TEXEL_MARGIN;
        let nudges = [(0.0, 0.0), (-m, 0.0), (m, 0.0), (0.0, -m), (0.0, m)];
        let mut out = Visibility { lo: 0.0, hi: 0.0 };
        let taps: &[([i32; 2], f32)] = if soft {
            &PCF_TENT_3X3
        } else {
            &[([0, 0], 1.0)]
        };
        for &([dx, dy], weight) in taps {
            let outcome = |(nu, nv): (f32, f32)| {
                let x = (u + nu).floor() as i64 + i64::from(dx);
                let y = (v + nv).floor() as i64 + i64::from(dy);
                let stored = self.depth(x, y);
                (c.z <= stored, (c.z - stored).abs() >= DEPTH_MARGIN)
            };
            let (lit, clear) = outcome(nudges[0]);
            let certain = clear && nudges[1..].iter().all(|&n| outcome(n) == (lit, true));
            out.add(weight, lit, certain);
        }
        out
    }
}

/// A cube shadow map (`SHADOWS_CUBE`): `|p − light| / range` per texel, six `size × size`
/// faces in wgpu layer order, rows running down each face.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadowCube {
    size: u32,
    faces: Vec<f32>,
}

impl ShadowCube {
    /// A cube from its six faces' texels, face after face, row-major.
    ///
    /// # Errors
    /// [`ShadowError::MapSize`] when `texels` does not hold exactly `6 · size² > 0` values,
    /// [`ShadowError::NonFiniteTexel`] for NaN or ±∞.
    pub fn new(size: u32, texels: Vec<f32>) -> Result<ShadowCube, ShadowError> {
        checked(&texels, 6 * size as usize * size as usize, (size, size, 6))?;
        Ok(ShadowCube {
            size,
            faces: texels,
        })
    }

    /// The texel direction `d` reads (nearest): `(face, x, y)` and how far the lookup is from
    /// a texel or face edge, in texels.
    pub fn texel(&self, d: Vec3) -> ((usize, usize, usize), f32) {
        let f = face(d);
        let (sc, tc, ma) = match f {
            0 => (-d.z, -d.y, d.x),
            1 => (d.z, -d.y, -d.x),
            2 => (d.x, d.z, d.y),
            3 => (d.x, -d.z, -d.y),
            4 => (d.x, -d.y, d.z),
            _ => (-d.x, -d.y, -d.z),
        };
        let n = self.size as f32;
        let s = (sc / ma * 0.5 + 0.5) * n;
        let t = (tc / ma * 0.5 + 0.5) * n;
        let clamp = |v: f32| (v.floor().max(0.0) as usize).min(self.size as usize - 1);
        // Interior texel edges, and the face's own edges (where a GPU may pick the neighbour
        // face): both are integers of s and t.
        let margin = texel_margin(s).min(texel_margin(t));
        ((f, clamp(s), clamp(t)), margin)
    }

    /// The stored value at `(face, x, y)`.
    pub fn value(&self, (f, x, y): (usize, usize, usize)) -> f32 {
        let n = self.size as usize;
        self.faces[(f * n + y) * n + x]
    }

    /// The visibility of a receiver at `d = p − light` with biased distance `mydist`
    /// ([`ShadowParams::cube_distance`]): one tap (hard) or Unity's four (soft). A tap is
    /// uncertain when moving its direction by [`TEXEL_MARGIN`] texels along any axis (which
    /// also crosses face edges) picks a texel with the other outcome, or its distances are
    /// within [`DISTANCE_MARGIN`].
    pub fn visibility(&self, d: Vec3, mydist: f32, soft: bool) -> Visibility {
        let mut out = Visibility { lo: 0.0, hi: 0.0 };
        let mut tap = |dir: Vec3, weight: f32| {
            let outcome = |dir: Vec3| {
                let stored = self.value(self.texel(dir).0);
                (stored >= mydist, (stored - mydist).abs() >= DISTANCE_MARGIN)
            };
            // One texel of a face spans 2 |major| / size in the minor axes.
            let step = TEXEL_MARGIN * 2.0 * dir.abs().max_element() / self.size as f32;
            let (lit, clear) = outcome(dir);
            let certain = clear
                && [Vec3::X, Vec3::Y, Vec3::Z]
                    .iter()
                    .flat_map(|&axis| [axis * step, -axis * step])
                    .all(|n| outcome(dir + n) == (lit, true));
            out.add(weight, lit, certain);
        };
        if soft {
            for o in CUBE_SOFT_DIAGONALS {
                tap(d + o * CUBE_SOFT_OFFSET, 0.25);
            }
        } else {
            tap(d, 1.0);
        }
        out
    }
}

/// The shadow keywords of a variant: `SHADOWS_DEPTH`, `SHADOWS_CUBE`, `SHADOWS_SCREEN`,
/// `SHADOWS_SOFT`, and the Shadowmask lighting modes' `SHADOWS_SHADOWMASK` and
/// `LIGHTMAP_SHADOW_MIXING`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadowKeywords {
    /// `SHADOWS_DEPTH`: a 2D map (spot).
    pub depth: bool,
    /// `SHADOWS_CUBE`: a cube of distances (point).
    pub cube: bool,
    /// `SHADOWS_SCREEN`: the screen-space mask of a directional light's map (the lighting
    /// pass reads the mask at its pixel; `internal/screen_space_shadows` made it).
    pub screen: bool,
    /// `SHADOWS_SOFT`: the filtered footprint.
    pub soft: bool,
    /// `SHADOWS_SHADOWMASK`: the G-buffer pass writes the baked occlusion to RT4 and the
    /// lighting pass reads the light's channel of it ([`baked_occlusion`]).
    pub shadowmask: bool,
    /// `LIGHTMAP_SHADOW_MIXING`: the Shadowmask mode's mix of realtime and baked shadows
    /// (without it, Distance Shadowmask's; [`mix_realtime_and_baked`]).
    pub mixing: bool,
}

impl ShadowKeywords {
    /// Splits the shadow keywords off `names`, returning them and the other names.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::shadow::ShadowKeywords;
    /// let (kw, rest) = ShadowKeywords::split(&["SPOT", "SHADOWS_DEPTH", "SHADOWS_SOFT"]);
    /// assert!(kw.depth && kw.soft && !kw.cube);
    /// assert_eq!(rest, ["SPOT"]);
    /// ```
    pub fn split<'a>(names: &[&'a str]) -> (ShadowKeywords, Vec<&'a str>) {
        let mut kw = ShadowKeywords::default();
        let mut rest = Vec::new();
        for &name in names {
            match name {
                "SHADOWS_DEPTH" => kw.depth = true,
                "SHADOWS_CUBE" => kw.cube = true,
                "SHADOWS_SCREEN" => kw.screen = true,
                "SHADOWS_SOFT" => kw.soft = true,
                "SHADOWS_SHADOWMASK" => kw.shadowmask = true,
                "LIGHTMAP_SHADOW_MIXING" => kw.mixing = true,
                _ => rest.push(name),
            }
        }
        (kw, rest)
    }

    /// Whether the variant reads a shadow map (or the screen-space mask) at all.
    pub fn any(&self) -> bool {
        self.depth || self.cube || self.screen
    }
}

/// A light's baked occlusion from the G-buffer's RT4 (Unity's `UnityDeferredSampleShadowMask`):
/// `saturate(dot(rt4, selector))`, where `selector` is the light's channel, one-hot
/// (docs/shading.md §13).
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::shadow::baked_occlusion;
/// let rt4 = Vec4::new(0.2, 0.4, 0.6, 0.8);
/// assert_eq!(baked_occlusion(rt4, Vec4::new(0.0, 0.0, 1.0, 0.0)), 0.6);
/// ```
pub fn baked_occlusion(rt4: Vec4, selector: Vec4) -> f32 {
    rt4.dot(selector).clamp(0.0, 1.0)
}

/// Unity's `UnityMixRealtimeAndBakedShadows` (docs/shading.md §13): the factor a light's
/// colour is scaled by, from its realtime shadow factor, its baked occlusion (1 without
/// `SHADOWS_SHADOWMASK`) and the shadow distance fade at the receiver
/// ([`crate::reference::shadow_fade::ShadowFade::fade`]; 0 well inside the shadow distance).
///
/// - no realtime shadow keyword (`SHADOWS_DEPTH`, `SHADOWS_CUBE`, `SHADOWS_SCREEN`): `baked`;
/// - `LIGHTMAP_SHADOW_MIXING` (the Shadowmask mode): `min(saturate(realtime + fade), baked)`;
/// - else (Distance Shadowmask, or no shadowmask): `lerp(realtime, baked, fade)`.
///
/// ```
/// use wgsl_variants_shaders::reference::shadow::{ShadowKeywords, mix_realtime_and_baked};
/// let mut kw = ShadowKeywords { screen: true, shadowmask: true, ..Default::default() };
/// assert_eq!(mix_realtime_and_baked(kw, 0.75, 0.5, 0.0), 0.75);
/// assert_eq!(mix_realtime_and_baked(kw, 0.75, 0.5, 0.5), 0.625);
/// kw.mixing = true;
/// assert_eq!(mix_realtime_and_baked(kw, 0.75, 0.5, 0.0), 0.5);
/// assert_eq!(mix_realtime_and_baked(kw, 0.25, 1.0, 0.5), 0.75);
/// kw.screen = false;
/// assert_eq!(mix_realtime_and_baked(kw, 1.0, 0.25, 0.5), 0.25);
/// ```
pub fn mix_realtime_and_baked(
    keywords: ShadowKeywords,
    realtime: f32,
    baked: f32,
    fade: f32,
) -> f32 {
    if !keywords.any() {
        baked
    } else if keywords.mixing {
        (realtime + fade).clamp(0.0, 1.0).min(baked)
    } else {
        realtime + (baked - realtime) * fade
    }
}

/// The shadow maps a variant may read.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShadowMaps<'a> {
    /// The 2D map (`SHADOWS_DEPTH`).
    pub map: Option<&'a ShadowMap2d>,
    /// The cube (`SHADOWS_CUBE`).
    pub cube: Option<&'a ShadowCube>,
}

/// The shadow factor interval `[mix(lo), mix(hi)]` at world position `p` for a variant's
/// shadow keywords: `(1, 1)` without one, and without the map the keyword needs (a variant
/// must be given its map; the GPU tests always are).
pub fn shadow_factor(
    params: &ShadowParams,
    keywords: ShadowKeywords,
    maps: ShadowMaps<'_>,
    p: Vec3,
) -> (f32, f32) {
    let v = if keywords.depth {
        maps.map.map(|m| {
            let c = params.coords(p);
            m.visibility(Vec3::new(c.x, c.y, c.z - params.bias), keywords.soft)
        })
    } else if keywords.cube {
        maps.cube.map(|m| {
            m.visibility(
                p - params.light_position,
                params.cube_distance(p),
                keywords.soft,
            )
        })
    } else {
        None
    };
    v.map_or((1.0, 1.0), |v| {
        (
            shadow_mix(params.strength, v.lo),
            shadow_mix(params.strength, v.hi),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tent_weights_sum_to_one_and_are_symmetric() {
        let sum: f32 = PCF_TENT_3X3.iter().map(|t| t.1).sum();
        assert_eq!(sum, 1.0);
        for &([x, y], w) in &PCF_TENT_3X3 {
            let mirrored = PCF_TENT_3X3.iter().find(|t| t.0 == [-x, -y]).unwrap();
            assert_eq!(mirrored.1, w);
        }
    }

    #[test]
    fn soft_2d_filters_an_edge_with_the_tent() {
        // Left half (x < 2) a near caster, right half clear.
        let depth = (0..16).map(|i| if i % 4 < 2 { 0.2 } else { 1.0 }).collect();
        let map = ShadowMap2d::new(4, 4, depth).unwrap();
        // Texel (2, 1): the column to its left is shadowed -> 1 - (1 + 2 + 1) / 16.
        let v = map.visibility(Vec3::new(2.5 / 4.0, 1.5 / 4.0, 0.5), true);
        assert_eq!((v.lo, v.hi), (0.75, 0.75));
        let hard = map.visibility(Vec3::new(2.5 / 4.0, 1.5 / 4.0, 0.5), false);
        assert_eq!((hard.lo, hard.hi), (1.0, 1.0));
        // On a texel edge the tap is uncertain.
        let edge = map.visibility(Vec3::new(2.0 / 4.0, 1.5 / 4.0, 0.5), false);
        assert_eq!((edge.lo, edge.hi), (0.0, 1.0));
        // Equal depths are lit (LessEqual), but within the margin uncertain.
        let eq = map.visibility(Vec3::new(0.5 / 4.0, 0.5 / 4.0, 0.2), false);
        assert!(!eq.is_exact());
    }

    #[test]
    fn cube_faces_match_the_lookup() {
        // A direction through the centre of texel (x, y) of face f, rendered with
        // cube_face_view_proj, reads texel (x, y) of face f.
        let size = 8u32;
        let cube = ShadowCube::new(size, vec![0.0; 6 * 64]).unwrap();
        for f in 0..6 {
            let inv = cube_face_view_proj(Vec3::new(1.0, 2.0, 3.0), f, 10.0).inverse();
            for (x, y) in [(0u32, 0u32), (3, 5), (7, 7), (6, 1)] {
                let ndc = Vec3::new(
                    (x as f32 + 0.5) / size as f32 * 2.0 - 1.0,
                    1.0 - (y as f32 + 0.5) / size as f32 * 2.0,
                    0.5,
                );
                let h = inv * ndc.extend(1.0);
                let p = h.truncate() / h.w;
                let (texel, margin) = cube.texel(p - Vec3::new(1.0, 2.0, 3.0));
                assert_eq!(texel, (f, x as usize, y as usize), "face {f}");
                assert!(margin > 0.4);
            }
        }
    }

    #[test]
    fn cube_comparison_and_soft_taps() {
        // Every texel stores 0.5: nearer receivers are lit, farther ones shadowed.
        let cube = ShadowCube::new(2, vec![0.5; 24]).unwrap();
        let d = Vec3::new(0.3, 0.2, 1.0);
        assert_eq!(cube.visibility(d, 0.4, false).lo, 1.0);
        assert_eq!(cube.visibility(d, 0.6, true).hi, 0.0);
        assert!(!cube.visibility(d, 0.5, false).is_exact());
    }

    #[test]
    fn spot_matrix_puts_the_axis_at_the_centre_and_the_range_at_depth_one() {
        let m = spot_shadow_view_proj(Vec3::new(1.0, 1.0, 3.0), Vec3::NEG_Z, 60.0, 5.0);
        let c = shadow_coords(m, Vec3::new(1.0, 1.0, -2.0));
        assert!(
            (c - Vec3::new(0.5, 0.5, 1.0)).abs().max_element() < 1e-5,
            "{c}"
        );
    }

    #[test]
    fn bad_parameters_are_refused() {
        let spot = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 60.0, 5.0, Vec3::ONE);
        assert_eq!(
            ShadowParams::for_light(&spot, 1.5, 0.0),
            Err(ShadowError::Strength(1.5))
        );
        assert!(matches!(
            ShadowParams::for_light(&spot, f32::NAN, 0.0),
            Err(ShadowError::Strength(_))
        ));
        assert_eq!(
            ShadowParams::for_light(&spot, 1.0, -0.1),
            Err(ShadowError::Bias(-0.1))
        );
        let bad = Light::spot(Vec3::ZERO, Vec3::NEG_Z, 0.0, 5.0, Vec3::ONE);
        assert!(matches!(
            ShadowParams::for_light(&bad, 1.0, 0.0),
            Err(ShadowError::Light(_))
        ));
        assert!(matches!(
            ShadowMap2d::new(2, 2, vec![0.0; 3]),
            Err(ShadowError::MapSize { .. })
        ));
        assert!(matches!(
            ShadowMap2d::new(1, 1, vec![f32::NAN]),
            Err(ShadowError::NonFiniteTexel { index: 0, .. })
        ));
        assert!(matches!(
            ShadowCube::new(0, vec![]),
            Err(ShadowError::MapSize { .. })
        ));
    }
}
