//! The colour targets of URP's G-buffer (docs/urp.md §1), for pipelines of the bundled
//! `universal_lit` shader's `UniversalGBuffer` pass.

use wgsl_variants_shaders::reference::urp::gbuffer::{URP_KEYWORD_NAMES, UrpKeywords};

/// The colour-target formats a `UniversalGBuffer` variant with these keywords writes, in
/// location order: GBuffer0–3, then depth as colour (`_RENDER_PASS_ENABLED`), rendering layers
/// (`_WRITE_RENDERING_LAYERS`) and shadowmask
/// ([`UrpKeywords::writes_shadow_mask`](wgsl_variants_shaders::reference::urp::gbuffer::UrpKeywords::writes_shadow_mask)),
/// as URP's `UnityGBuffer.hlsl` assigns its optional slots. Names the pass does not declare
/// are ignored.
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
    if on("_WRITE_RENDERING_LAYERS") {
        formats.push(F::R32Uint);
    }
    if writes_shadow_mask(keywords) {
        formats.push(F::Rgba8Unorm);
    }
    formats
}

/// Whether a variant with these keywords writes the shadowmask target (the reference's rule).
pub(crate) fn writes_shadow_mask(keywords: &[&str]) -> bool {
    let known: Vec<&str> = keywords
        .iter()
        .copied()
        .filter(|k| URP_KEYWORD_NAMES.contains(k))
        .collect();
    UrpKeywords::from_names(&known).is_ok_and(|k| k.writes_shadow_mask())
}
