//! The colour targets of URP's G-buffer (docs/urp.md §1), for pipelines of the bundled
//! `universal_lit` shader's `UniversalGBuffer` pass.

/// The colour-target formats a `UniversalGBuffer` variant with these keywords writes, in
/// location order: GBuffer0–3, then depth as colour (`_RENDER_PASS_ENABLED`), shadowmask
/// (`SHADOWS_SHADOWMASK`) and rendering layers (`_WRITE_RENDERING_LAYERS`).
///
/// ```
/// use wgsl_variants_gpu::urp_gbuffer_formats;
/// use wgpu::TextureFormat as F;
/// assert_eq!(
///     urp_gbuffer_formats(&["_GBUFFER_NORMALS_OCT", "_WRITE_RENDERING_LAYERS"]),
///     vec![F::Rgba8UnormSrgb, F::Rgba8Unorm, F::Rgba8Unorm, F::Rg11b10Ufloat, F::R32Uint],
/// );
/// assert_eq!(urp_gbuffer_formats(&[])[2], F::Rgba8Snorm);
/// ```
pub fn urp_gbuffer_formats(keywords: &[&str]) -> Vec<wgpu::TextureFormat> {
    use wgpu::TextureFormat as F;
    let on = |k: &str| keywords.contains(&k);
    let mut formats = vec![
        F::Rgba8UnormSrgb,
        F::Rgba8Unorm,
        if on("_GBUFFER_NORMALS_OCT") {
            F::Rgba8Unorm
        } else {
            F::Rgba8Snorm
        },
        F::Rg11b10Ufloat,
    ];
    if on("_RENDER_PASS_ENABLED") {
        formats.push(F::R32Float);
    }
    if on("SHADOWS_SHADOWMASK") {
        formats.push(F::Rgba8Unorm);
    }
    if on("_WRITE_RENDERING_LAYERS") {
        formats.push(F::R32Uint);
    }
    formats
}
