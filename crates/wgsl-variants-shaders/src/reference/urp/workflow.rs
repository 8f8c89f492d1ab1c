//! GBuffer1 of a Lit material: the metallic workflow's reflectivity, or the specular colour
//! (URP's `BRDF.hlsl` `kDielectricSpec`, `OneMinusReflectivityMetallic`, and `UnityGBuffer.hlsl`
//! `BRDFDataToGbuffer` / `BRDFDataFromGbuffer`).
//!
//! Metallic workflow: `kDielectricSpec = (0.04, 0.04, 0.04, 1 − 0.04)`;
//! `oneMinusReflectivity = kDielectricSpec.a · (1 − metallic)`,
//! `reflectivity = 1 − oneMinusReflectivity`, stored in GBuffer1.r (g = b = 0). The lighting
//! pass rebuilds `metallic = (reflectivity − 0.04) / 0.96`, `diffuse = albedo · (1 − reflectivity)`
//! and `specular = lerp(kDielectricSpec.rgb, albedo, metallic)`. With `_SPECULARHIGHLIGHTS_OFF`
//! GBuffer1.rgb is written as 0.

use glam::Vec3;

/// `kDielectricSpec.rgb`: the specular colour of a non-metal.
pub const DIELECTRIC_SPEC: f32 = 0.04;
/// `kDielectricSpec.a = 1 − 0.04`.
pub const ONE_MINUS_DIELECTRIC_SPEC: f32 = 1.0 - DIELECTRIC_SPEC;

/// The reflectivity the metallic workflow stores: `1 − 0.96 · (1 − metallic)`.
///
/// ```
/// use wgsl_variants_shaders::reference::urp::workflow::metallic_reflectivity;
/// assert!((metallic_reflectivity(0.0) - 0.04).abs() < 1e-7);
/// assert_eq!(metallic_reflectivity(1.0), 1.0);
/// ```
pub fn metallic_reflectivity(metallic: f32) -> f32 {
    1.0 - ONE_MINUS_DIELECTRIC_SPEC * (1.0 - metallic)
}

/// The metallic value the lighting pass rebuilds: `(reflectivity − 0.04) / 0.96`
/// (URP's `MetallicFromReflectivity`).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::workflow::metallic_from_reflectivity;
/// assert_eq!(metallic_from_reflectivity(1.0), 1.0);
/// assert_eq!(metallic_from_reflectivity(0.04), 0.0);
/// ```
pub fn metallic_from_reflectivity(reflectivity: f32) -> f32 {
    (reflectivity - DIELECTRIC_SPEC) / ONE_MINUS_DIELECTRIC_SPEC
}

/// Diffuse and specular colour of a metallic-workflow texel, as URP's lighting pass rebuilds
/// them from the base albedo (GBuffer0) and the reflectivity (GBuffer1.r).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::workflow::metallic_brdf_colors;
/// let (diffuse, specular) = metallic_brdf_colors(Vec3::ONE, 1.0);
/// assert_eq!((diffuse, specular), (Vec3::ZERO, Vec3::ONE));
/// ```
pub fn metallic_brdf_colors(albedo: Vec3, reflectivity: f32) -> (Vec3, Vec3) {
    let metallic = metallic_from_reflectivity(reflectivity);
    let diffuse = albedo * (1.0 - reflectivity);
    let specular = Vec3::splat(DIELECTRIC_SPEC).lerp(albedo, metallic);
    (diffuse, specular)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_computed_on_paper() {
        // metallic 0.5: 1 − 0.96 · 0.5 = 0.52; back: (0.52 − 0.04)/0.96 = 0.5.
        assert!((metallic_reflectivity(0.5) - 0.52).abs() < 1e-7);
        assert!((metallic_from_reflectivity(0.52) - 0.5).abs() < 1e-7);
        // albedo (1, 0.5, 0), reflectivity 0.52: diffuse = albedo · 0.48 = (0.48, 0.24, 0);
        // specular = 0.04 + (albedo − 0.04) · 0.5 = (0.52, 0.27, 0.02).
        let (d, s) = metallic_brdf_colors(Vec3::new(1.0, 0.5, 0.0), 0.52);
        assert!(
            (d - Vec3::new(0.48, 0.24, 0.0)).abs().max_element() < 1e-6,
            "{d}"
        );
        assert!(
            (s - Vec3::new(0.52, 0.27, 0.02)).abs().max_element() < 1e-6,
            "{s}"
        );
        // Stored as 8-bit unorm: 0.52 · 255 = 132.6 → 133; read 133/255 = 0.521569
        // → metallic (0.521569 − 0.04)/0.96 = 0.501634: 8 bits keep metallic to ±0.002.
        let read = 133.0 / 255.0;
        assert!((metallic_from_reflectivity(read) - 0.501_634).abs() < 1e-6);
    }
}
