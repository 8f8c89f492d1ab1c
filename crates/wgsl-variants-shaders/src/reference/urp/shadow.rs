//! URP Lit's ShadowCaster pass (docs/urp.md §10; URP's `ShadowCasterPass.hlsl`
//! `GetShadowPositionHClip` and `Shadows.hlsl` `ApplyShadowBias`): where a caster's vertex
//! lands in a light's depth map; and how a receiver reads the main light's one map
//! ([`main_light_map_factor`], docs/urp.md §9).
//!
//! ```
//! use glam::{Mat4, Vec2, Vec3};
//! use wgsl_variants_shaders::reference::urp::shadow::{CasterLight, caster_clip};
//! // A floor facing a light straight above: the depth bias pushes it 0.1 down (away from the
//! // light); the normal bias does nothing where n·l = 1.
//! let light = CasterLight::Directional { to_light: Vec3::Z };
//! let clip = caster_clip(Mat4::IDENTITY, Vec3::new(0.0, 0.0, 0.5), Vec3::Z, light, Vec2::new(-0.1, -0.2));
//! assert!((clip.z - 0.4).abs() < 1e-6);
//! ```

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::reference::shadow::{
    ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams, lit_beyond_shadow_far, shadow_factor,
};

/// The light a ShadowCaster variant renders for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CasterLight {
    /// A directional light (URP's `_LightDirection`, the unit direction to the light).
    Directional {
        /// Unit direction towards the light.
        to_light: Vec3,
    },
    /// A point or spot light at `position` (`_CASTING_PUNCTUAL_LIGHT_SHADOW`, URP's
    /// `_LightPosition`): the direction is taken per vertex.
    Punctual {
        /// World position.
        position: Vec3,
    },
}

impl CasterLight {
    /// The unit direction from `p` towards the light.
    pub fn direction(&self, p: Vec3) -> Vec3 {
        match *self {
            CasterLight::Directional { to_light } => to_light,
            CasterLight::Punctual { position } => (position - p).normalize(),
        }
    }
}

/// URP's `ApplyShadowBias`: `p + l · bias.x + n · (1 − saturate(l·n)) · bias.y`, with `bias`
/// = (depth bias, normal bias) in world units (negative: away from the light, into the surface).
///
/// ```
/// use glam::{Vec2, Vec3};
/// use wgsl_variants_shaders::reference::urp::shadow::apply_shadow_bias;
/// // Light at grazing 90°: n·l = 0, so the full normal bias applies: (0, 0, 0) − 0.2 · n.
/// let p = apply_shadow_bias(Vec3::ZERO, Vec3::Z, Vec3::X, Vec2::new(0.0, -0.2));
/// assert_eq!(p, Vec3::new(0.0, 0.0, -0.2));
/// ```
pub fn apply_shadow_bias(p: Vec3, n: Vec3, l: Vec3, bias: Vec2) -> Vec3 {
    let scale = (1.0 - l.dot(n).clamp(0.0, 1.0)) * bias.y;
    p + l * bias.x + n * scale
}

/// The clip position a caster vertex at world `p` with unit world normal `n` gets: the biased
/// position through `view_proj`, its z raised to 0 (wgpu's near plane) so a caster in front of
/// the near plane lies on it ("pancaking"; URP: `max(positionCS.z, UNITY_NEAR_CLIP_VALUE)`).
pub fn caster_clip(view_proj: Mat4, p: Vec3, n: Vec3, light: CasterLight, bias: Vec2) -> Vec4 {
    let l = light.direction(p);
    let mut clip = view_proj * apply_shadow_bias(p, n, l, bias).extend(1.0);
    clip.z = clip.z.max(0.0);
    clip
}

/// The main light's realtime shadow at `p` from its one map (`_MAIN_LIGHT_SHADOWS`; URP's
/// `MainLightRealtimeShadow` and `SampleShadowmap`): the tap (`soft`: the 3 × 3 tent) mixed by
/// the strength, as an interval where a tap is within a hair of flipping, and lit beyond the
/// light's depth range ([`lit_beyond_shadow_far`]). The cascades' counterpart is
/// [`crate::reference::cascades::Cascades::factor`] with
/// [`crate::reference::cascades::CascadeKeywords::urp`].
pub fn main_light_map_factor(
    params: &ShadowParams,
    map: &ShadowMap2d,
    soft: bool,
    p: Vec3,
) -> (f32, f32) {
    let keywords = ShadowKeywords {
        depth: true,
        soft,
        ..ShadowKeywords::default()
    };
    let maps = ShadowMaps {
        map: Some(map),
        cube: None,
    };
    lit_beyond_shadow_far(params.coords(p).z, shadow_factor(params, keywords, maps, p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bias_on_paper() {
        // l = (0, 0.6, 0.8), n = (0, 0, 1): l·n = 0.8, scale = 0.2 · bias.y = 0.2 · −0.5 = −0.1.
        // p' = (1, 2, 3) + l · (−0.25) + n · (−0.1) = (1, 2 − 0.15, 3 − 0.2 − 0.1) = (1, 1.85, 2.7).
        let p = apply_shadow_bias(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::Z,
            Vec3::new(0.0, 0.6, 0.8),
            Vec2::new(-0.25, -0.5),
        );
        assert!((p - Vec3::new(1.0, 1.85, 2.7)).length() < 1e-6, "{p}");
        // A back-facing light (l·n < 0) saturates to 0: the whole normal bias.
        let p = apply_shadow_bias(Vec3::ZERO, Vec3::Z, Vec3::NEG_Z, Vec2::new(0.0, -0.5));
        assert_eq!(p, Vec3::new(0.0, 0.0, -0.5));
    }

    #[test]
    fn punctual_direction_is_per_vertex_and_pancaking_clamps_z() {
        let light = CasterLight::Punctual {
            position: Vec3::new(0.0, 0.0, 4.0),
        };
        // From (3, 0, 0): (−3, 0, 4) / 5.
        assert!(
            (light.direction(Vec3::new(3.0, 0.0, 0.0)) - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6
        );
        // A vertex in front of the near plane (z < 0 after the transform) lands on it.
        let clip = caster_clip(
            Mat4::IDENTITY,
            Vec3::new(0.0, 0.0, -0.3),
            Vec3::Z,
            CasterLight::Directional { to_light: Vec3::Z },
            Vec2::ZERO,
        );
        assert_eq!(clip.z, 0.0);
    }
}
