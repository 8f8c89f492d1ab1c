//! The metallic workflow and the BRDF terms (docs/shading.md §5).
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::brdf::diffuse_and_specular_from_metallic;
//! let (diffuse, spec, omr) = diffuse_and_specular_from_metallic(Vec3::new(1.0, 0.5, 0.0), 0.0);
//! assert_eq!(spec, Vec3::splat(0.04));
//! assert_eq!(omr, 0.96);
//! assert_eq!(diffuse, Vec3::new(0.96, 0.48, 0.0));
//! ```

use glam::{Vec3, Vec4};

/// Splits an albedo into diffuse and specular colour by metalness:
/// `spec_color = mix((0.04, 0.04, 0.04), albedo, metallic)`,
/// `one_minus_reflectivity = 0.96 · (1 − metallic)`, `diffuse = albedo · one_minus_reflectivity`.
/// Returns `(diffuse, spec_color, one_minus_reflectivity)`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::diffuse_and_specular_from_metallic;
/// let albedo = Vec3::new(0.9, 0.6, 0.3);
/// let (diffuse, spec, omr) = diffuse_and_specular_from_metallic(albedo, 1.0);
/// assert_eq!((diffuse, spec, omr), (Vec3::ZERO, albedo, 0.0));
/// ```
pub fn diffuse_and_specular_from_metallic(albedo: Vec3, metallic: f32) -> (Vec3, Vec3, f32) {
    let spec_color = Vec3::splat(0.04) * (1.0 - metallic) + albedo * metallic;
    let one_minus_reflectivity = 0.96 * (1.0 - metallic);
    (
        albedo * one_minus_reflectivity,
        spec_color,
        one_minus_reflectivity,
    )
}

/// The ambient (L0 + L1 spherical harmonics) light for normal `n`:
/// `max((dot(sh_r, (n, 1)), dot(sh_g, (n, 1)), dot(sh_b, (n, 1))), 0)` — Unity's
/// `unity_SHAr/g/b` form (xyz: the L1 coefficients, w: L0). The indirect diffuse light is this
/// times occlusion.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::brdf::sh_ambient;
/// let sh_r = Vec4::new(0.0, 0.5, 0.0, 0.5); // brighter from above
/// let sh_g = Vec4::new(0.0, 0.0, 0.0, 0.25);
/// let sh_b = Vec4::new(0.0, 0.0, 0.0, -1.0); // negative: clamped to 0
/// assert_eq!(sh_ambient(sh_r, sh_g, sh_b, Vec3::Y), Vec3::new(1.0, 0.25, 0.0));
/// assert_eq!(sh_ambient(sh_r, sh_g, sh_b, Vec3::NEG_Y), Vec3::new(0.0, 0.25, 0.0));
/// ```
pub fn sh_ambient(sh_r: Vec4, sh_g: Vec4, sh_b: Vec4, n: Vec3) -> Vec3 {
    let n1 = n.extend(1.0);
    Vec3::new(sh_r.dot(n1), sh_g.dot(n1), sh_b.dot(n1)).max(Vec3::ZERO)
}

/// Perceptual roughness and roughness from smoothness: `pr = 1 − s`, `r = pr²`.
///
/// ```
/// use wgsl_variants_shaders::reference::brdf::roughness;
/// assert_eq!(roughness(0.25), (0.75, 0.5625));
/// ```
pub fn roughness(smoothness: f32) -> (f32, f32) {
    let pr = 1.0 - smoothness;
    (pr, pr * pr)
}

/// The indirect specular light:
/// `surface_reduction · env · fresnel` with `r` the roughness ([`roughness`]),
/// `surface_reduction = 1 / (r² + 1)`, `grazing = saturate(smoothness + 1 − one_minus_reflectivity)`,
/// `nv = saturate(dot(n, v))`, `fresnel = mix(spec_color, grazing, (1 − nv)^5)`.
///
/// `env` is the probe result already multiplied by occlusion; `n` and `v` (towards the camera)
/// are unit vectors.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::indirect_specular;
/// // Looking straight at a mirror (smoothness 1, r = 0): fresnel = spec_color, no reduction.
/// let s = indirect_specular(Vec3::splat(2.0), Vec3::splat(0.04), 1.0, 0.96, Vec3::Z, Vec3::Z);
/// assert_eq!(s, Vec3::splat(0.08));
/// // At grazing angle (nv = 0): fresnel = grazing = saturate(1 + 1 − 0.96) = 1.
/// let g = indirect_specular(Vec3::ONE, Vec3::splat(0.04), 1.0, 0.96, Vec3::Z, Vec3::X);
/// assert_eq!(g, Vec3::ONE);
/// // Fully rough (r = 1): halved.
/// let h = indirect_specular(Vec3::ONE, Vec3::splat(0.5), 0.0, 0.0, Vec3::Z, Vec3::Z);
/// assert_eq!(h, Vec3::splat(0.25));
/// ```
pub fn indirect_specular(
    env: Vec3,
    spec_color: Vec3,
    smoothness: f32,
    one_minus_reflectivity: f32,
    n: Vec3,
    v: Vec3,
) -> Vec3 {
    let (_, r) = roughness(smoothness);
    let surface_reduction = 1.0 / (r * r + 1.0);
    let grazing = (smoothness + 1.0 - one_minus_reflectivity).clamp(0.0, 1.0);
    let nv = n.dot(v).clamp(0.0, 1.0);
    let f = (1.0 - nv).powi(5);
    let fresnel = spec_color * (1.0 - f) + Vec3::splat(grazing) * f;
    surface_reduction * env * fresnel
}

/// The specular exponent for a smoothness: `exp2(1 + 7 · smoothness)` (2 … 256).
///
/// ```
/// use wgsl_variants_shaders::reference::brdf::specular_power;
/// assert_eq!(specular_power(0.0), 2.0);
/// assert_eq!(specular_power(1.0), 256.0);
/// ```
pub fn specular_power(smoothness: f32) -> f32 {
    (1.0 + 7.0 * smoothness).exp2()
}

/// The direct light of one directional light (forward only):
/// `(diffuse + spec_color · spec) · light_color · nl` with `h = normalize(l + v)`,
/// `nl = saturate(dot(n, l))`, `nh = saturate(dot(n, h))`, `p = exp2(1 + 7 · smoothness)`,
/// `spec = (p + 8) / (8π) · nh^p`.
///
/// `n`, `v` (towards the camera) and `l` (towards the light) are unit vectors; `l == −v` has no
/// half vector (NaN). `nh^p` is `f32::powf` (0 for `nh = 0`).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::direct;
/// // Light, view and normal aligned, smoothness 0 (p = 2): spec = 10 / (8π).
/// let d = direct(Vec3::splat(0.5), Vec3::splat(0.04), 0.0, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::ONE);
/// let spec = 10.0 / (8.0 * std::f32::consts::PI);
/// assert!((d - Vec3::splat(0.5 + 0.04 * spec)).abs().max_element() < 1e-6);
/// // Light behind the surface: nothing.
/// let back = direct(Vec3::ONE, Vec3::ONE, 0.5, Vec3::Z, Vec3::Z, Vec3::NEG_Z.lerp(Vec3::X, 0.1).normalize(), Vec3::ONE);
/// assert_eq!(back, Vec3::ZERO);
/// ```
pub fn direct(
    diffuse: Vec3,
    spec_color: Vec3,
    smoothness: f32,
    n: Vec3,
    v: Vec3,
    l: Vec3,
    light_color: Vec3,
) -> Vec3 {
    let h = (l + v).normalize();
    let nl = n.dot(l).clamp(0.0, 1.0);
    let nh = n.dot(h).clamp(0.0, 1.0);
    let p = specular_power(smoothness);
    let spec = (p + 8.0) / (8.0 * std::f32::consts::PI) * nh.powf(p);
    (diffuse + spec_color * spec) * light_color * nl
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f32::consts::PI;

    #[test]
    fn metallic_split() {
        let albedo = Vec3::new(0.8, 0.4, 0.2);
        let (d, s, omr) = diffuse_and_specular_from_metallic(albedo, 0.5);
        assert_eq!(omr, 0.48);
        assert!((s - Vec3::new(0.42, 0.22, 0.12)).abs().max_element() < 1e-7);
        assert!((d - albedo * 0.48).abs().max_element() < 1e-7);
    }

    #[test]
    fn sh_is_linear_plus_constant() {
        let sh = Vec4::new(0.1, 0.2, 0.3, 0.4);
        let n = Vec3::new(0.6, 0.0, 0.8);
        let a = sh_ambient(sh, sh * 2.0, Vec4::ZERO, n);
        let want = 0.1 * 0.6 + 0.3 * 0.8 + 0.4;
        assert!((a.x - want).abs() < 1e-7 && (a.y - 2.0 * want).abs() < 1e-6);
        assert_eq!(a.z, 0.0);
    }

    #[test]
    fn indirect_specular_hand_computed() {
        // smoothness 0.5: pr = 0.5, r = 0.25, reduction = 1/(1 + 1/16) = 16/17.
        // omr = 0.48 → grazing = saturate(0.5 + 1 − 0.48) = 1.
        // nv = 0.5 → (1 − nv)^5 = 1/32. fresnel = spec·31/32 + 1/32.
        let n = Vec3::Z;
        let v = Vec3::new((0.75f32).sqrt(), 0.0, 0.5);
        let spec = Vec3::new(0.42, 0.22, 0.12);
        let env = Vec3::new(1.0, 2.0, 4.0);
        let got = indirect_specular(env, spec, 0.5, 0.48, n, v);
        let want = (16.0 / 17.0) * env * (spec * (31.0 / 32.0) + 1.0 / 32.0);
        assert!((got - want).abs().max_element() < 1e-6, "{got} vs {want}");
        // Grazing below 1: smoothness 0, omr 0.96 → 0.04.
        let g = indirect_specular(Vec3::ONE, Vec3::ZERO, 0.0, 0.96, n, Vec3::X);
        assert!((g - Vec3::splat(0.04 * 0.5)).abs().max_element() < 1e-7);
        // View below the surface: nv clamps to 0.
        let below = indirect_specular(Vec3::ONE, Vec3::ZERO, 0.0, 0.96, n, Vec3::NEG_Z);
        assert_eq!(below, g);
    }

    #[test]
    fn direct_hand_computed() {
        // n = Z, l at 60° from n in the XZ plane, v = n: h = normalize(l + v) is at 30°.
        let n = Vec3::Z;
        let l = Vec3::new((0.75f32).sqrt(), 0.0, 0.5);
        let v = Vec3::Z;
        let smoothness = 3.0 / 7.0; // p = 2^4 = 16
        let diffuse = Vec3::new(0.2, 0.3, 0.4);
        let spec_color = Vec3::splat(0.5);
        let lc = Vec3::new(1.0, 2.0, 0.5);
        let got = direct(diffuse, spec_color, smoothness, n, v, l, lc);
        let nh = (PI / 6.0).cos();
        let spec = 24.0 / (8.0 * PI) * nh.powi(16);
        let want = (diffuse + spec_color * spec) * lc * 0.5;
        assert!((got - want).abs().max_element() < 1e-5, "{got} vs {want}");
        assert!((specular_power(smoothness) - 16.0).abs() < 1e-5);
    }

    #[test]
    fn direct_vanishes_with_grazing_light() {
        let d = direct(
            Vec3::ONE,
            Vec3::ONE,
            0.8,
            Vec3::Z,
            Vec3::Z,
            Vec3::X,
            Vec3::ONE,
        );
        assert_eq!(d, Vec3::ZERO);
    }
}
