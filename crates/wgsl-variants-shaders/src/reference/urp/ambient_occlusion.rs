//! URP's screen-space ambient occlusion as the lighting reads it (docs/urp.md §14; URP's
//! `AmbientOcclusion.hlsl`: `GetScreenSpaceAmbientOcclusion`; `StencilDeferred.shader`:
//! `DeferredShading` under `_DEFERRED_FIRST_LIGHT`, `FragSSAOOnly`).
//!
//! The SSAO renderer feature leaves one occlusion value per pixel (1 open, 0 occluded). The
//! lighting splits it: the indirect occlusion is the value itself, the direct occlusion
//! `lerp(1, ssao, strength)` with the feature's Direct Lighting Strength
//! (`_AmbientOcclusionParam.w`). Every light is multiplied by the direct part; the indirect part
//! scales the global illumination (in the deferred path, GBuffer3 once, through
//! [`deferred_indirect_occlusion`]).

/// The two occlusion factors at a pixel (URP's `AmbientOcclusionFactor`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AmbientOcclusionFactor {
    /// What scales the indirect (global) illumination.
    pub indirect: f32,
    /// What scales every light's colour.
    pub direct: f32,
}

impl AmbientOcclusionFactor {
    /// No occlusion (without `_SCREEN_SPACE_OCCLUSION`).
    pub const NONE: AmbientOcclusionFactor = AmbientOcclusionFactor {
        indirect: 1.0,
        direct: 1.0,
    };

    /// `GetScreenSpaceAmbientOcclusion` for the SSAO texture's value `ssao` and the direct
    /// lighting strength `direct_strength` (`_AmbientOcclusionParam.w`).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::ambient_occlusion::AmbientOcclusionFactor;
    /// let f = AmbientOcclusionFactor::screen_space(0.4, 0.25);
    /// assert_eq!(f.indirect, 0.4);
    /// assert!((f.direct - 0.85).abs() < 1e-6); // 1 + 0.25 · (0.4 − 1)
    /// ```
    pub fn screen_space(ssao: f32, direct_strength: f32) -> AmbientOcclusionFactor {
        AmbientOcclusionFactor {
            indirect: ssao,
            direct: 1.0 + direct_strength * (ssao - 1.0),
        }
    }
}

/// What the deferred path multiplies GBuffer3 by (the alpha of the first directional light
/// under `_DEFERRED_FIRST_LIGHT`, and of the SSAOOnly pass, blended One SrcAlpha): the G-buffer
/// pass already multiplied the indirect light by the surface's occlusion `surface`, so where
/// the SSAO's `indirect` is lower the ratio makes the product the SSAO's; else 1 (the smaller
/// of the two stands, as the forward path's `min`).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::ambient_occlusion::deferred_indirect_occlusion;
/// assert_eq!(deferred_indirect_occlusion(0.3, 0.6), 0.5); // 0.6 · 0.5 = 0.3
/// assert_eq!(deferred_indirect_occlusion(0.8, 0.6), 1.0); // the surface's 0.6 stands
/// assert_eq!(deferred_indirect_occlusion(0.0, 0.0), 1.0); // no division by 0
/// ```
pub fn deferred_indirect_occlusion(indirect: f32, surface: f32) -> f32 {
    if indirect < surface {
        indirect / surface
    } else {
        1.0
    }
}
