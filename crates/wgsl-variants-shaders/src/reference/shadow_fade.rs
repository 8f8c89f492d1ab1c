//! The realtime shadows' distance fade (docs/shading.md §11, "Shadow distance fade"): past the
//! shadow distance Unity stops drawing realtime shadows, and to hide that edge every receiver
//! fades its realtime shadow out over a band before it [Unity's `UnityShadowLibrary.cginc`:
//! `UnityComputeShadowFadeDistance`, `UnityComputeShadowFade`; `AutoLight.cginc`
//! `UnityComputeForwardShadows`; `UnityDeferredLibrary.cginc` `UnityDeferredComputeShadow`]:
//!
//! ```text
//! fade distance = lerp(view depth, |p − centre|, type)     (unity_ShadowFadeCenterAndType)
//! fade          = saturate(fade distance · z + w)            (_LightShadowData.zw)
//! ```
//!
//! `type` is 0 for Unity's Close Fit shadow projection (the fade follows view depth) and 1 for
//! Stable Fit (a sphere around `centre`). The fade then enters
//! [`super::shadow::mix_realtime_and_baked`]: without baked shadows it lerps the realtime
//! factor to 1. Unity's engine sets `_LightShadowData.zw` from the quality settings' shadow
//! distance; the values are not in its published sources, so here they are the scale and
//! offset of a linear ramp from `start` to `end` that the host chooses
//! ([`ShadowFade::new`]).
//!
//! The WGSL is `lighting/shadow_fade`; [`ShadowFade::uniform`] is its `ShadowFade` record.

use glam::{Vec3, Vec4};

use super::shadow::ShadowError;

/// What the fade measures: Unity's `unity_ShadowFadeCenterAndType`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FadeDistance {
    /// Close Fit (`w = 0`): the receiver's view depth.
    ViewDepth,
    /// Stable Fit (`w = 1`): the receiver's distance to this centre.
    Sphere(Vec3),
}

/// A realtime shadow's distance fade, as the receivers read it.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::shadow_fade::{FadeDistance, ShadowFade};
/// // A camera at the origin looking down −Z; shadows fade out between depths 10 and 20.
/// let fade = ShadowFade::new(Vec3::ZERO, Vec3::NEG_Z, FadeDistance::ViewDepth, 10.0, 20.0)?;
/// assert_eq!(fade.fade(Vec3::new(3.0, 0.0, -5.0)), 0.0);
/// assert_eq!(fade.fade(Vec3::new(0.0, 0.0, -15.0)), 0.5);
/// assert_eq!(fade.fade(Vec3::new(0.0, 9.0, -25.0)), 1.0);
/// // Stable Fit: the distance to a centre instead.
/// let sphere = ShadowFade::new(Vec3::ZERO, Vec3::NEG_Z, FadeDistance::Sphere(Vec3::ZERO), 10.0, 20.0)?;
/// assert_eq!(sphere.fade(Vec3::new(15.0, 0.0, 0.0)), 0.5);
/// # Ok::<(), wgsl_variants_shaders::reference::shadow::ShadowError>(())
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowFade {
    /// What the fade distance is.
    pub distance: FadeDistance,
    /// The camera's forward axis and `dot(forward, position)`: view depth = `dot(p, xyz) − w`.
    pub view_axis: Vec4,
    /// `_LightShadowData.z`: the fade per unit of fade distance.
    pub scale: f32,
    /// `_LightShadowData.w`: the fade at fade distance 0.
    pub offset: f32,
}

impl ShadowFade {
    /// No fade anywhere (scale and offset 0): the realtime shadow everywhere, as if every
    /// receiver were well inside the shadow distance.
    pub const NONE: ShadowFade = ShadowFade {
        distance: FadeDistance::ViewDepth,
        view_axis: Vec4::ZERO,
        scale: 0.0,
        offset: 0.0,
    };

    /// The fade of a camera at `position` looking along `forward`: 0 up to fade distance
    /// `start`, 1 from `end` on, linear between.
    ///
    /// # Errors
    /// [`ShadowError::Fade`] where a value is not finite, `forward` has no length, or `start`
    /// is not below `end`.
    pub fn new(
        position: Vec3,
        forward: Vec3,
        distance: FadeDistance,
        start: f32,
        end: f32,
    ) -> Result<ShadowFade, ShadowError> {
        let centre_ok = match distance {
            FadeDistance::ViewDepth => true,
            FadeDistance::Sphere(c) => c.is_finite(),
        };
        let forward = forward.normalize_or_zero();
        let camera_ok = position.is_finite() && centre_ok && forward != Vec3::ZERO;
        let ramp_ok = start.is_finite() && end.is_finite() && start < end;
        if !(camera_ok && ramp_ok) {
            return Err(ShadowError::Fade { start, end });
        }
        let scale = 1.0 / (end - start);
        Ok(ShadowFade {
            distance,
            view_axis: forward.extend(forward.dot(position)),
            scale,
            offset: -start * scale,
        })
    }

    /// Unity's `UnityComputeShadowFadeDistance` at `p`: its view depth, or its distance to the
    /// centre.
    pub fn fade_distance(&self, p: Vec3) -> f32 {
        match self.distance {
            FadeDistance::ViewDepth => p.dot(self.view_axis.truncate()) - self.view_axis.w,
            FadeDistance::Sphere(centre) => p.distance(centre),
        }
    }

    /// Unity's `UnityComputeShadowFade` at `p`: `saturate(fade distance · scale + offset)`.
    pub fn fade(&self, p: Vec3) -> f32 {
        (self.fade_distance(p) * self.scale + self.offset).clamp(0.0, 1.0)
    }

    /// The WGSL `ShadowFade` record: `center_and_type` (Unity's
    /// `unity_ShadowFadeCenterAndType`), `view_axis`, `params` (x scale, y offset, zw 0).
    pub fn uniform(&self) -> [f32; 12] {
        let center_and_type = match self.distance {
            FadeDistance::ViewDepth => Vec4::ZERO,
            FadeDistance::Sphere(c) => c.extend(1.0),
        };
        let mut out = [0.0; 12];
        out[..4].copy_from_slice(&center_and_type.to_array());
        out[4..8].copy_from_slice(&self.view_axis.to_array());
        out[8] = self.scale;
        out[9] = self.offset;
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn view_depth_follows_the_camera_axis_not_the_distance() {
        let eye = Vec3::new(1.0, 2.0, 3.0);
        let forward = Vec3::new(0.0, -1.0, -1.0);
        let fade = ShadowFade::new(eye, forward, FadeDistance::ViewDepth, 2.0, 6.0).unwrap();
        let axis = forward.normalize();
        // Points on a plane across the axis share a depth, whatever their distance.
        let side = Vec3::X * 7.0;
        for depth in [0.5f32, 2.0, 3.0, 4.0, 6.0, 9.0] {
            let p = eye + axis * depth + side;
            assert!((fade.fade_distance(p) - depth).abs() < 1e-5);
            let want = ((depth - 2.0) / 4.0).clamp(0.0, 1.0);
            assert!((fade.fade(p) - want).abs() < 1e-6, "depth {depth}");
        }
    }

    #[test]
    fn sphere_fade_is_radial_and_the_record_says_which() {
        let centre = Vec3::new(0.0, 0.0, -5.0);
        let fade = ShadowFade::new(
            Vec3::ZERO,
            Vec3::NEG_Z,
            FadeDistance::Sphere(centre),
            1.0,
            3.0,
        )
        .unwrap();
        for dir in [Vec3::X, Vec3::Y, Vec3::Z, Vec3::NEG_Z] {
            assert!((fade.fade(centre + dir * 2.0) - 0.5).abs() < 1e-6);
        }
        let u = fade.uniform();
        assert_eq!(&u[..4], &[0.0, 0.0, -5.0, 1.0]);
        assert_eq!(&u[4..8], &[0.0, 0.0, -1.0, 0.0]);
        assert_eq!(&u[8..], &[0.5, -0.5, 0.0, 0.0]);
        let depth = ShadowFade::new(Vec3::ZERO, Vec3::NEG_Z, FadeDistance::ViewDepth, 1.0, 3.0)
            .unwrap()
            .uniform();
        assert_eq!(&depth[..4], &[0.0; 4]);
    }

    #[test]
    fn none_never_fades_and_bad_ramps_are_refused() {
        assert_eq!(ShadowFade::NONE.fade(Vec3::splat(1e6)), 0.0);
        let bad = [
            (Vec3::ZERO, Vec3::ZERO, 1.0, 2.0),
            (Vec3::ZERO, Vec3::Z, 2.0, 2.0),
            (Vec3::ZERO, Vec3::Z, 3.0, 2.0),
            (Vec3::ZERO, Vec3::Z, f32::NAN, 2.0),
            (Vec3::splat(f32::INFINITY), Vec3::Z, 1.0, 2.0),
        ];
        for (eye, forward, start, end) in bad {
            let e = ShadowFade::new(eye, forward, FadeDistance::ViewDepth, start, end);
            assert!(
                matches!(e, Err(ShadowError::Fade { .. })),
                "{eye} {forward} {start} {end}"
            );
        }
        let centre = FadeDistance::Sphere(Vec3::splat(f32::NAN));
        assert!(ShadowFade::new(Vec3::ZERO, Vec3::Z, centre, 1.0, 2.0).is_err());
    }
}
