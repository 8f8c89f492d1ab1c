// universal/ambient_occlusion: URP's screen-space ambient occlusion as the lighting reads it
// (docs/urp.md §14; URP's AmbientOcclusion.hlsl: SampleAmbientOcclusion,
// GetScreenSpaceAmbientOcclusion). The SSAO renderer feature writes one occlusion value per
// pixel (1: open, 0: occluded); the lighting splits it into the indirect part (the SSAO value)
// and the direct part (`lerp(1, ssao, _AmbientOcclusionParam.w)`, the feature's Direct Lighting
// Strength). Its binding exists with _SCREEN_SPACE_OCCLUSION:
//
//   group 0: 27 screen_space_occlusion (texture_2d<f32>, URP's _ScreenSpaceOcclusionTexture at
//              the camera's resolution, its r read at the pixel: URP samples it bilinearly at
//              the pixel's centre, which is this texel; a downsampled texture is not built)
//
// _AmbientOcclusionParam is the caller's: the forward pass reads it from its Lighting record
// (universal/bindings), the StencilDeferred passes at their binding 26. (One more uniform
// buffer in the forward pass's group 0, nine with every keyword, made Mesa 22.3's lavapipe
// crash at the draw: docs/urp.md §14.)
//
// Provides:
//   fn urp_screen_space_ambient_occlusion(pixel: vec2i) -> f32
//       the SSAO value at pixel, the indirect occlusion (1 without the keyword)
//   fn urp_direct_occlusion(ssao: f32, direct_strength: f32) -> f32
//       the direct occlusion: lerp(1, ssao, direct_strength)
//   fn urp_deferred_indirect_occlusion(indirect: f32, surface: f32) -> f32
//       what the deferred path multiplies GBuffer3 by (its alpha under Blend One SrcAlpha):
//       the G-buffer pass already applied the surface's occlusion, so the SSAO value replaces
//       it where it is lower (the ratio), else 1 (URP's StencilDeferred: the first directional
//       light under _DEFERRED_FIRST_LIGHT, and the SSAOOnly pass)

#if defined(_SCREEN_SPACE_OCCLUSION)
@group(0) @binding(27) var screen_space_occlusion: texture_2d<f32>;
#endif

fn urp_screen_space_ambient_occlusion(pixel: vec2i) -> f32 {
#if defined(_SCREEN_SPACE_OCCLUSION)
    return textureLoad(screen_space_occlusion, pixel, 0).r;
#else
    return 1.0;
#endif
}

fn urp_direct_occlusion(ssao: f32, direct_strength: f32) -> f32 {
    return mix(1.0, ssao, direct_strength);
}

fn urp_deferred_indirect_occlusion(indirect: f32, surface: f32) -> f32 {
    // The comparison also keeps a surface occlusion of 0 from dividing.
    if indirect < surface {
        return indirect / surface;
    }
    return 1.0;
}
