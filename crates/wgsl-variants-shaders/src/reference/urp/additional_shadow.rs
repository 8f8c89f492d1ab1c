//! URP's additional-light realtime shadows (`_ADDITIONAL_LIGHT_SHADOWS`; URP's `Shadows.hlsl`:
//! `GetAdditionalLightShadowParams`, `AdditionalLightRealtimeShadow`, `SampleShadowmap`; the
//! SRP core's `CubeMapFaceID`): which slice of the additional lights' shadow atlas a receiver
//! reads, and the realtime shadow there; [`AdditionalShadows`] is everything the receivers read
//! (the WGSL `AdditionalShadows` record of `universal/additional_light_shadow` and the atlas).
//!
//! Each shadowed spot light has one slice (its perspective view), each shadowed point light
//! six, one per cube face in the order +X, −X, +Y, −Y, +Z, −Z; a point light's receiver picks
//! the face of the direction from the light to itself. The slice's matrix (URP's
//! `_AdditionalLightsWorldToShadow[slice]`, here the light's view-projection with the slice's
//! atlas tile folded in, as [`crate::reference::cascades`] folds a cascade's) takes the
//! receiver to clip space; the perspective divide gives its atlas coordinate; the tap (or the
//! 3 × 3 tent) compares it with the atlas — no receiver bias: URP biases the caster — and
//! URP's `LerpWhiteTo` mixes in the strength. A coordinate outside the depth range reads as lit
//! ([`lit_beyond_shadow_far`]). The distance fade (`GetAdditionalLightShadowFade`,
//! `_AdditionalShadowFadeParams.xy`) is the main light's formula with its own scale and bias:
//! [`super::forward::UrpShadowFade::at`].
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::urp::additional_shadow::{AdditionalShadowParams, cube_map_face_id};
//! // A point light whose six slices start at slice 2: a receiver below the light reads −Y.
//! let params = AdditionalShadowParams { strength: 1.0, soft: false, point: true, first_slice: Some(2) };
//! assert_eq!(cube_map_face_id(Vec3::new(0.2, -1.0, 0.3)), 3);
//! assert_eq!(params.slices(Vec3::new(-0.2, 1.0, -0.3)), vec![2 + 3]);
//! assert_eq!(params.uniform(), [1.0, 0.0, 1.0, 2.0]);
//! ```

use glam::{Mat4, Vec3};

use super::forward::{MainLightShadow, UrpShadowFade};
use crate::reference::shadow::{
    ShadowError, ShadowMap2d, lit_beyond_shadow_far, shadow_coords, shadow_mix,
};

/// The most additional lights the receivers' record describes (the forward pass's limit).
pub const MAX_SHADOWED_LIGHTS: usize = 8;

/// The most slices the receivers' record holds: six for each of [`MAX_SHADOWED_LIGHTS`].
pub const MAX_SHADOW_SLICES: usize = 6 * MAX_SHADOWED_LIGHTS;

/// How close (relative to the largest) two components of a direction may come before the cube
/// face picked for it counts as uncertain: the GPU computes the direction in `f32` from the
/// rebuilt or interpolated position, in another order than the reference.
pub const FACE_MARGIN: f32 = 1e-4;

/// URP's `_AdditionalShadowParams[light]` for one additional light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdditionalShadowParams {
    /// x: the shadow's strength in [0, 1] (the shadowed light keeps `1 − strength`).
    pub strength: f32,
    /// y > 0: soft (`_SHADOWS_SOFT`; the 3 × 3 tent here — URP 14's low, medium and high
    /// tiers are not built).
    pub soft: bool,
    /// z: a point light (six slices, one per cube face) rather than a spot light (one).
    pub point: bool,
    /// w: the light's first slice in the atlas; `None` (URP: −1) for a light that casts no
    /// shadow, which reads as lit.
    pub first_slice: Option<usize>,
}

impl AdditionalShadowParams {
    /// The record as URP packs it: `(strength, soft ? 1 : 0, point ? 1 : 0, first slice or
    /// −1)`.
    pub fn uniform(&self) -> [f32; 4] {
        [
            self.strength,
            if self.soft { 1.0 } else { 0.0 },
            if self.point { 1.0 } else { 0.0 },
            self.first_slice.map_or(-1.0, |s| s as f32),
        ]
    }

    /// The slices a receiver in the direction `to_light` from the light (the unit direction
    /// from the receiver to the light, URP's `lightDirection`) may read: the first slice of a
    /// spot light; for a point light the first plus the face of `−to_light`
    /// ([`cube_map_face_id`]), both faces where the direction lies within [`FACE_MARGIN`] of a
    /// face edge; none without a shadow.
    pub fn slices(&self, to_light: Vec3) -> Vec<usize> {
        let Some(first) = self.first_slice else {
            return Vec::new();
        };
        if !self.point {
            return vec![first];
        }
        let d = -to_light;
        let m = FACE_MARGIN * d.abs().max_element();
        let mut faces: Vec<usize> = Vec::new();
        // The face at `d`, and at `d` with each component nudged outward and inward.
        for axis in 0..3 {
            for s in [0.0, -m, m] {
                let mut n = d;
                n[axis] += s * d[axis].signum();
                let f = first + cube_map_face_id(n);
                if !faces.contains(&f) {
                    faces.push(f);
                }
            }
        }
        faces
    }
}

/// The SRP core's `CubeMapFaceID`: 0 +X, 1 −X, 2 +Y, 3 −Y, 4 +Z, 5 −Z, by the largest
/// component of `dir`; a tie goes to z, then to y.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::additional_shadow::cube_map_face_id;
/// assert_eq!(cube_map_face_id(Vec3::new(1.0, 0.5, -0.5)), 0);
/// assert_eq!(cube_map_face_id(Vec3::new(1.0, 1.0, 0.0)), 2);
/// assert_eq!(cube_map_face_id(Vec3::new(1.0, 1.0, -1.0)), 5);
/// ```
pub fn cube_map_face_id(dir: Vec3) -> usize {
    let a = dir.abs();
    if a.z >= a.x && a.z >= a.y {
        if dir.z < 0.0 { 5 } else { 4 }
    } else if a.y >= a.x {
        if dir.y < 0.0 { 3 } else { 2 }
    } else if dir.x < 0.0 {
        1
    } else {
        0
    }
}

/// URP's `AdditionalLightRealtimeShadow` at world position `p`, lit from the unit direction
/// `to_light`, as an interval (a tap within a hair of flipping, or a cube face within a hair of
/// its neighbour, gives both outcomes): 1 without a shadow; otherwise, for each slice the
/// receiver may read ([`AdditionalShadowParams::slices`]), the atlas coordinate through
/// `world_to_atlas[slice]` and the perspective divide ([`shadow_coords`]), the tap or the tent
/// over `atlas`, `1 − strength + strength · visibility`, lit beyond the depth range.
///
/// # Panics
/// If a slice the parameters name has no matrix in `world_to_atlas`.
pub fn additional_light_realtime_shadow(
    params: &AdditionalShadowParams,
    world_to_atlas: &[Mat4],
    atlas: &ShadowMap2d,
    p: Vec3,
    to_light: Vec3,
) -> (f32, f32) {
    let slices = params.slices(to_light);
    if slices.is_empty() {
        return (1.0, 1.0);
    }
    let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
    for slice in slices {
        let c = shadow_coords(world_to_atlas[slice], p);
        let v = atlas.visibility(c, params.soft);
        let f = lit_beyond_shadow_far(
            c.z,
            (
                shadow_mix(params.strength, v.lo),
                shadow_mix(params.strength, v.hi),
            ),
        );
        lo = lo.min(f.0);
        hi = hi.max(f.1);
    }
    (lo, hi)
}

/// Everything the receivers read of the additional lights' shadows: each light's parameters
/// (in the order of the pass's additional lights), each slice's matrix, the atlas and the
/// distance fade (URP's `_AdditionalShadowFadeParams.xy`; the main light's formula,
/// [`UrpShadowFade`]).
#[derive(Clone, Debug)]
pub struct AdditionalShadows {
    params: Vec<AdditionalShadowParams>,
    world_to_atlas: Vec<Mat4>,
    atlas: ShadowMap2d,
    fade: UrpShadowFade,
}

impl AdditionalShadows {
    /// The shadows of `params.len()` lights over the slices `world_to_atlas` of `atlas`.
    ///
    /// ```
    /// use glam::Mat4;
    /// use wgsl_variants_shaders::reference::shadow::ShadowMap2d;
    /// use wgsl_variants_shaders::reference::urp::additional_shadow::{AdditionalShadowParams, AdditionalShadows};
    /// use wgsl_variants_shaders::reference::urp::forward::UrpShadowFade;
    /// let atlas = ShadowMap2d::new(1, 1, vec![1.0]).unwrap();
    /// let point = AdditionalShadowParams { strength: 1.0, soft: false, point: true, first_slice: Some(0) };
    /// let fade = UrpShadowFade::NONE;
    /// assert!(AdditionalShadows::new(vec![point], vec![Mat4::IDENTITY; 6], atlas.clone(), fade).is_ok());
    /// // A point light needs six slices.
    /// assert!(AdditionalShadows::new(vec![point], vec![Mat4::IDENTITY; 5], atlas, fade).is_err());
    /// ```
    ///
    /// # Errors
    /// [`ShadowError::AdditionalSlices`]: more than [`MAX_SHADOWED_LIGHTS`] lights or
    /// [`MAX_SHADOW_SLICES`] slices, or a light whose slices lie past `world_to_atlas`.
    pub fn new(
        params: Vec<AdditionalShadowParams>,
        world_to_atlas: Vec<Mat4>,
        atlas: ShadowMap2d,
        fade: UrpShadowFade,
    ) -> Result<AdditionalShadows, ShadowError> {
        let fits = |p: &AdditionalShadowParams| {
            p.first_slice
                .is_none_or(|s| s + if p.point { 6 } else { 1 } <= world_to_atlas.len())
        };
        if params.len() > MAX_SHADOWED_LIGHTS
            || world_to_atlas.len() > MAX_SHADOW_SLICES
            || !params.iter().all(fits)
        {
            return Err(ShadowError::AdditionalSlices {
                lights: params.len(),
                slices: world_to_atlas.len(),
            });
        }
        Ok(AdditionalShadows {
            params,
            world_to_atlas,
            atlas,
            fade,
        })
    }

    /// The same shadows with another distance fade.
    pub fn with_fade(&self, fade: UrpShadowFade) -> AdditionalShadows {
        AdditionalShadows {
            fade,
            ..self.clone()
        }
    }

    /// Each light's parameters.
    pub fn params(&self) -> &[AdditionalShadowParams] {
        &self.params
    }

    /// The atlas.
    pub fn atlas(&self) -> &ShadowMap2d {
        &self.atlas
    }

    /// URP's `AdditionalLightShadow` of light `light` at `p` (lit from the unit direction
    /// `to_light`) seen from `camera`, as an interval: the realtime shadow
    /// ([`additional_light_realtime_shadow`], with `_SHADOWS_SOFT` as `soft_keyword`: a light
    /// is soft only with the keyword and its own flag) lerped towards 1 by the fade, the baked
    /// shadow 1. A light past the record has no shadow (1).
    pub fn attenuation(
        &self,
        light: usize,
        soft_keyword: bool,
        p: Vec3,
        to_light: Vec3,
        camera: Vec3,
    ) -> (f32, f32) {
        let Some(params) = self.params.get(light) else {
            return (1.0, 1.0);
        };
        let params = AdditionalShadowParams {
            soft: params.soft && soft_keyword,
            ..*params
        };
        let (lo, hi) = additional_light_realtime_shadow(
            &params,
            &self.world_to_atlas,
            &self.atlas,
            p,
            to_light,
        );
        let fade = self.fade.at(p, camera);
        let faded = |a: f32| {
            MainLightShadow {
                attenuation: a,
                strength: params.strength,
            }
            .faded(fade)
            .attenuation
        };
        (faded(lo), faded(hi))
    }

    /// The WGSL `AdditionalShadows` record, little-endian: `fade` (scale, bias, 0, 0), eight
    /// `params` ([`AdditionalShadowParams::uniform`]; `(0, 0, 0, −1)` past the lights), 48
    /// slice matrices column-major (identity past the slices): 16 + 8 · 16 + 48 · 64 = 3,216
    /// bytes.
    pub fn uniform(&self) -> Vec<u8> {
        let mut floats = vec![self.fade.scale, self.fade.bias, 0.0, 0.0];
        for i in 0..MAX_SHADOWED_LIGHTS {
            floats.extend(
                self.params
                    .get(i)
                    .map_or([0.0, 0.0, 0.0, -1.0], AdditionalShadowParams::uniform),
            );
        }
        for i in 0..MAX_SHADOW_SLICES {
            let m = self
                .world_to_atlas
                .get(i)
                .copied()
                .unwrap_or(Mat4::IDENTITY);
            floats.extend(m.to_cols_array());
        }
        floats.iter().flat_map(|v| v.to_le_bytes()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_axis_picks_its_face_and_ties_go_to_z_then_y() {
        let axes = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
        for (face, axis) in axes.iter().enumerate() {
            assert_eq!(cube_map_face_id(*axis * 2.0 + Vec3::splat(0.1)), face);
        }
        assert_eq!(cube_map_face_id(Vec3::new(-1.0, 0.0, 1.0)), 4);
        assert_eq!(cube_map_face_id(Vec3::new(-1.0, -1.0, 0.5)), 3);
    }

    #[test]
    fn a_spot_reads_its_one_slice_and_a_light_without_shadow_none() {
        let spot = AdditionalShadowParams {
            strength: 0.5,
            soft: true,
            point: false,
            first_slice: Some(7),
        };
        assert_eq!(spot.slices(Vec3::new(0.3, 0.9, 0.1)), vec![7]);
        assert_eq!(spot.uniform(), [0.5, 1.0, 0.0, 7.0]);
        let none = AdditionalShadowParams {
            first_slice: None,
            ..spot
        };
        assert!(none.slices(Vec3::Y).is_empty());
        assert_eq!(none.uniform()[3], -1.0);
    }

    #[test]
    fn a_direction_on_a_face_edge_may_read_either_face() {
        let point = AdditionalShadowParams {
            strength: 1.0,
            soft: false,
            point: true,
            first_slice: Some(0),
        };
        // From the light towards (1, 1, 0.2): the +X/+Y edge.
        let mut both = point.slices(-Vec3::new(1.0, 1.0, 0.2).normalize());
        both.sort_unstable();
        assert_eq!(both, vec![0, 2]);
        assert_eq!(point.slices(-Vec3::new(1.0, 0.5, 0.2).normalize()), vec![0]);
    }

    /// A 2 × 2 atlas whose left column holds a caster at depth 0.3 and whose right column is
    /// clear; the identity matrix maps world (x, y, z) to atlas uv ((x + 1) / 2, (1 − y) / 2)
    /// at depth z.
    fn atlas() -> ShadowMap2d {
        ShadowMap2d::new(2, 2, vec![0.3, 1.0, 0.3, 1.0]).unwrap()
    }

    #[test]
    fn the_realtime_shadow_mixes_the_strength_and_is_lit_beyond_the_depth_range() {
        let params = AdditionalShadowParams {
            strength: 0.8,
            soft: false,
            point: false,
            first_slice: Some(0),
        };
        let m = [Mat4::IDENTITY];
        let behind = Vec3::new(-0.5, 0.5, 0.6);
        let shadowed = 1.0 - 0.8;
        assert_eq!(
            additional_light_realtime_shadow(&params, &m, &atlas(), behind, Vec3::Z),
            (shadowed, shadowed)
        );
        let clear = Vec3::new(0.5, 0.5, 0.6);
        assert_eq!(
            additional_light_realtime_shadow(&params, &m, &atlas(), clear, Vec3::Z),
            (1.0, 1.0)
        );
        // Beyond the far plane the caster does not count: lit.
        let beyond = Vec3::new(-0.5, 0.5, 1.5);
        assert_eq!(
            additional_light_realtime_shadow(&params, &m, &atlas(), beyond, Vec3::Z),
            (1.0, 1.0)
        );
        let none = AdditionalShadowParams {
            first_slice: None,
            ..params
        };
        assert_eq!(
            additional_light_realtime_shadow(&none, &[], &atlas(), behind, Vec3::Z),
            (1.0, 1.0)
        );
    }

    #[test]
    fn a_point_light_reads_the_slice_of_its_face() {
        // Six slices: only the −Y face's (slice 3) sees the caster column.
        let params = AdditionalShadowParams {
            strength: 1.0,
            soft: false,
            point: true,
            first_slice: Some(0),
        };
        // The other faces' matrices move p onto the clear column.
        let mut m = [Mat4::from_translation(Vec3::X); 6];
        m[3] = Mat4::IDENTITY;
        let p = Vec3::new(-0.5, 0.5, 0.6);
        // The receiver lies below the light (to_light up): face −Y.
        assert_eq!(
            additional_light_realtime_shadow(&params, &m, &atlas(), p, Vec3::Y),
            (0.0, 0.0)
        );
        // Beside it (to_light along −X): face +X, whose matrix puts p on the clear column.
        assert_eq!(
            additional_light_realtime_shadow(&params, &m, &atlas(), p, -Vec3::X),
            (1.0, 1.0)
        );
    }
}
