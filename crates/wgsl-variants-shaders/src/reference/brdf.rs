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

/// Unity's Standard BRDF tiers (`UNITY_BRDF_PBS`, docs/shading.md §5): which one a variant
/// uses is its tier keyword — none for BRDF1 (what Unity's desktop graphics tiers select),
/// `UNITY_PBS_USE_BRDF2` or `UNITY_PBS_USE_BRDF3`.
///
/// ```
/// use wgsl_variants_shaders::reference::brdf::Brdf;
/// assert_eq!(Brdf::default(), Brdf::Brdf1);
/// assert_eq!(Brdf::Brdf3.keyword(), Some("UNITY_PBS_USE_BRDF3"));
/// assert_eq!(Brdf::Brdf1.keyword(), None);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Brdf {
    /// GGX with Smith-joint visibility, Disney diffuse, Schlick Fresnel (the default).
    #[default]
    Brdf1,
    /// `UNITY_PBS_USE_BRDF2`: a cheaper GGX-like lobe without Fresnel on the direct light.
    Brdf2,
    /// `UNITY_PBS_USE_BRDF3`: normalized Blinn-Phong read from a lookup table
    /// ([`crate::brdf_lut`]).
    Brdf3,
}

impl Brdf {
    /// The three tiers, in keyword order.
    pub const ALL: [Brdf; 3] = [Brdf::Brdf1, Brdf::Brdf2, Brdf::Brdf3];

    /// The keyword that selects this tier (`None`: BRDF1, the set's "none").
    pub fn keyword(self) -> Option<&'static str> {
        match self {
            Brdf::Brdf1 => None,
            Brdf::Brdf2 => Some("UNITY_PBS_USE_BRDF2"),
            Brdf::Brdf3 => Some("UNITY_PBS_USE_BRDF3"),
        }
    }
}

/// `x⁵` as Unity's `Pow5` writes it (`x·x · x·x · x`).
fn pow5(x: f32) -> f32 {
    x * x * (x * x) * x
}

/// `x⁴` as Unity's `Pow4`.
fn pow4(x: f32) -> f32 {
    x * x * (x * x)
}

/// The indirect specular light of each tier, with `env` the probe result already multiplied
/// by occlusion, `grazing = saturate(smoothness + 1 − one_minus_reflectivity)`, `pr = 1 −
/// smoothness`, `r = pr²`:
///
/// - BRDF1: `env / (r'² + 1) · mix(spec_color, grazing, (1 − |n·v|)⁵)`, `r' = max(r, 0.002)`;
/// - BRDF2: `env · (1 − r·pr·(0.6 − 0.08·pr)) · mix(spec_color, grazing, (1 − nv)⁴)`;
/// - BRDF3: `env · mix(spec_color, grazing, (1 − nv)⁴)`,
///
/// with `nv = saturate(n·v)`. `n` and `v` (towards the camera) are unit vectors.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::{indirect_specular, Brdf};
/// // Looking straight at a mirror (smoothness 1, r = 0): fresnel = spec_color, no reduction.
/// let s = indirect_specular(Brdf::Brdf1, Vec3::splat(2.0), Vec3::splat(0.04), 1.0, 0.96, Vec3::Z, Vec3::Z);
/// assert!((s - Vec3::splat(0.08)).abs().max_element() < 1e-6);
/// // At grazing angle (nv = 0): fresnel = grazing = saturate(1 + 1 − 0.96) = 1.
/// let g = indirect_specular(Brdf::Brdf3, Vec3::ONE, Vec3::splat(0.04), 1.0, 0.96, Vec3::Z, Vec3::X);
/// assert_eq!(g, Vec3::ONE);
/// // Fully rough (r = 1): BRDF1 halves, BRDF2 keeps 1 − 0.52.
/// let h = indirect_specular(Brdf::Brdf1, Vec3::ONE, Vec3::splat(0.5), 0.0, 0.0, Vec3::Z, Vec3::Z);
/// assert_eq!(h, Vec3::splat(0.25));
/// let h2 = indirect_specular(Brdf::Brdf2, Vec3::ONE, Vec3::splat(0.5), 0.0, 0.0, Vec3::Z, Vec3::Z);
/// assert!((h2 - Vec3::splat(0.5 * 0.48)).abs().max_element() < 1e-6);
/// ```
pub fn indirect_specular(
    brdf: Brdf,
    env: Vec3,
    spec_color: Vec3,
    smoothness: f32,
    one_minus_reflectivity: f32,
    n: Vec3,
    v: Vec3,
) -> Vec3 {
    let grazing = Vec3::splat((smoothness + 1.0 - one_minus_reflectivity).clamp(0.0, 1.0));
    let (pr, r) = roughness(smoothness);
    let mix = |t: f32| spec_color * (1.0 - t) + grazing * t;
    let nv = n.dot(v).clamp(0.0, 1.0);
    match brdf {
        Brdf::Brdf1 => {
            let r = r.max(0.002);
            let surface_reduction = 1.0 / (r * r + 1.0);
            surface_reduction * env * mix(pow5(1.0 - n.dot(v).abs()))
        }
        Brdf::Brdf2 => {
            let surface_reduction = 1.0 - r * pr * (0.6 - 0.08 * pr);
            surface_reduction * env * mix(pow4(1.0 - nv))
        }
        Brdf::Brdf3 => env * mix(pow4(1.0 - nv)),
    }
}

/// The dot products the direct term depends on, unclamped (each tier clamps as Unity does):
/// `h = l + v` normalized with Unity's `Unity_SafeNormalize` (`h · 1/√max(|h|², 0.001)`),
/// `r = reflect(v, n)` (BRDF3's mirrored view direction).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dots {
    /// `n·l`.
    pub nl: f32,
    /// `n·h`.
    pub nh: f32,
    /// `n·v`.
    pub nv: f32,
    /// `l·h`.
    pub lh: f32,
    /// `r·l`.
    pub rl: f32,
}

impl Dots {
    /// The dot products of unit vectors `n`, `v` (towards the camera) and `l` (towards the
    /// light).
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::brdf::Dots;
    /// let d = Dots::new(Vec3::Z, Vec3::Z, Vec3::Z);
    /// // r = reflect(v, n) = −n here: BRDF3 takes (r·l)⁴, so the sign does not matter.
    /// assert_eq!((d.nl, d.nh, d.nv, d.lh, d.rl), (1.0, 1.0, 1.0, 1.0, -1.0));
    /// // l = −v: no half vector, h = 0.
    /// assert_eq!(Dots::new(Vec3::Z, Vec3::X, Vec3::NEG_X).nh, 0.0);
    /// ```
    pub fn new(n: Vec3, v: Vec3, l: Vec3) -> Dots {
        let hv = l + v;
        let h = hv * hv.dot(hv).max(0.001).sqrt().recip();
        let r = super::vector::reflect(v, n);
        Dots {
            nl: n.dot(l),
            nh: n.dot(h),
            nv: n.dot(v),
            lh: l.dot(h),
            rl: r.dot(l),
        }
    }
}

/// The direct term's factors: `direct = light · (diffuse · kd + ks · fresnel(spec_color))`
/// with `fresnel(s) = s + (1 − s) · f` per channel ([`DirectFactors::apply`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectFactors {
    /// The diffuse factor (`nl` times BRDF1's Disney diffuse).
    pub kd: f32,
    /// The specular factor, before the specular colour.
    pub ks: f32,
    /// The Schlick weight `f` ((1 − l·h)⁵ for BRDF1; 0 for BRDF2 and BRDF3, which have no
    /// Fresnel on the direct light).
    pub f: f32,
}

impl DirectFactors {
    /// The factors of `brdf` at `smoothness` and `dots`; BRDF3 reads
    /// [`crate::brdf_lut::shared_table`].
    ///
    /// - BRDF1: `nl, nh, lh` saturated, `nv = |n·v|`, `pr = 1 − smoothness`,
    ///   `r = max(pr², 0.002)`; `fd90 = 0.5 + 2·lh²·pr`,
    ///   `kd = (1 + (fd90 − 1)(1 − nl)⁵)(1 + (fd90 − 1)(1 − nv)⁵) · nl`;
    ///   `V = 0.5 / (nl(nv(1 − r) + r) + nv(nl(1 − r) + r) + 10⁻⁵)`,
    ///   `d = (nh·r² − nh)·nh + 1`, `ks = max(V · r² / (d² + 10⁻⁷) · nl, 0)` (Unity's
    ///   `V · D · π · nl` with `D = r² / (π(d² + 10⁻⁷))`), `f = (1 − lh)⁵`.
    /// - BRDF2: `kd = nl`, `a = pr²`, `d = nh²(a² − 1) + 1.00001`,
    ///   `ks = a² / (max(0.1, lh²)·(a + 0.5)·d²·4) · nl`, `f = 0`.
    /// - BRDF3: `kd = nl`, `ks = lut((r·l)⁴, pr) · 16 · nl`, `f = 0`.
    pub fn new(brdf: Brdf, smoothness: f32, dots: &Dots) -> DirectFactors {
        let sat = |x: f32| x.clamp(0.0, 1.0);
        let nl = sat(dots.nl);
        let pr = 1.0 - smoothness;
        match brdf {
            Brdf::Brdf1 => {
                let (nh, lh, nv) = (sat(dots.nh), sat(dots.lh), dots.nv.abs());
                let fd90 = 0.5 + 2.0 * lh * lh * pr;
                let kd = (1.0 + (fd90 - 1.0) * pow5(1.0 - nl))
                    * (1.0 + (fd90 - 1.0) * pow5(1.0 - nv))
                    * nl;
                let r = (pr * pr).max(0.002);
                let lambda_v = nl * (nv * (1.0 - r) + r);
                let lambda_l = nv * (nl * (1.0 - r) + r);
                let vis = 0.5 / (lambda_v + lambda_l + 1e-5);
                let a2 = r * r;
                let d = (nh * a2 - nh) * nh + 1.0;
                let ks = (vis * a2 / (d * d + 1e-7) * nl).max(0.0);
                DirectFactors {
                    kd,
                    ks,
                    f: pow5(1.0 - lh),
                }
            }
            Brdf::Brdf2 => {
                let (nh, lh) = (sat(dots.nh), sat(dots.lh));
                let a = pr * pr;
                let a2 = a * a;
                let d = nh * nh * (a2 - 1.0) + 1.00001;
                let ks = a2 / ((lh * lh).max(0.1) * (a + 0.5) * (d * d) * 4.0);
                DirectFactors {
                    kd: nl,
                    ks: ks * nl,
                    f: 0.0,
                }
            }
            Brdf::Brdf3 => {
                let x = pow4(dots.rl);
                let lut = crate::brdf_lut::shared_table();
                let ks = crate::brdf_lut::sample(lut, x, pr) * crate::brdf_lut::RANGE;
                DirectFactors {
                    kd: nl,
                    ks: ks * nl,
                    f: 0.0,
                }
            }
        }
    }

    /// `light · (diffuse · kd + ks · (spec_color + (1 − spec_color) · f))`; the specular part is
    /// 0 when `spec_color` is 0 (BRDF1's `any(specColor)`; the other tiers multiply by it).
    pub fn apply(&self, diffuse: Vec3, spec_color: Vec3, light: Vec3) -> Vec3 {
        let fresnel = spec_color + (Vec3::ONE - spec_color) * self.f;
        let ks = if spec_color == Vec3::ZERO {
            0.0
        } else {
            self.ks
        };
        light * (diffuse * self.kd + ks * fresnel)
    }
}

/// The direct light of one light with colour (times attenuation) `light_color` from direction
/// `l`, in tier `brdf` ([`DirectFactors`]). `n`, `v` (towards the camera) and `l` (towards the
/// light) are unit vectors.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::{direct, Brdf};
/// // BRDF2, light and view along the normal, smoothness 0 (a = 1): the lobe is
/// // 1 / (1 · 1.5 · 1.00001² · 4).
/// let d = direct(Brdf::Brdf2, Vec3::splat(0.5), Vec3::splat(0.04), 0.0, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::ONE);
/// assert!((d - Vec3::splat(0.5 + 0.04 / 6.0)).abs().max_element() < 1e-5);
/// // Light behind the surface: nothing, in every tier.
/// for brdf in Brdf::ALL {
///     let back = direct(brdf, Vec3::ONE, Vec3::ONE, 0.5, Vec3::Z, Vec3::Z, Vec3::NEG_Z, Vec3::ONE);
///     assert_eq!(back, Vec3::ZERO);
/// }
/// ```
#[allow(clippy::too_many_arguments)]
pub fn direct(
    brdf: Brdf,
    diffuse: Vec3,
    spec_color: Vec3,
    smoothness: f32,
    n: Vec3,
    v: Vec3,
    l: Vec3,
    light_color: Vec3,
) -> Vec3 {
    DirectFactors::new(brdf, smoothness, &Dots::new(n, v, l)).apply(
        diffuse,
        spec_color,
        light_color,
    )
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
        // smoothness 0.5: pr = 0.5, r = 0.25, BRDF1's reduction = 1/(1 + 1/16) = 16/17.
        // omr = 0.48 → grazing = saturate(0.5 + 1 − 0.48) = 1.
        // nv = 0.5 → (1 − nv)^5 = 1/32. fresnel = spec·31/32 + 1/32.
        let n = Vec3::Z;
        let v = Vec3::new((0.75f32).sqrt(), 0.0, 0.5);
        let spec = Vec3::new(0.42, 0.22, 0.12);
        let env = Vec3::new(1.0, 2.0, 4.0);
        let got = indirect_specular(Brdf::Brdf1, env, spec, 0.5, 0.48, n, v);
        let want = (16.0 / 17.0) * env * (spec * (31.0 / 32.0) + 1.0 / 32.0);
        assert!((got - want).abs().max_element() < 1e-6, "{got} vs {want}");
        // BRDF2: reduction 1 − 0.25·0.5·(0.6 − 0.04) = 0.93, (1 − nv)^4 = 1/16.
        let got = indirect_specular(Brdf::Brdf2, env, spec, 0.5, 0.48, n, v);
        let want = 0.93 * env * (spec * (15.0 / 16.0) + 1.0 / 16.0);
        assert!((got - want).abs().max_element() < 1e-6, "{got} vs {want}");
        // BRDF3: no reduction.
        let got = indirect_specular(Brdf::Brdf3, env, spec, 0.5, 0.48, n, v);
        let want = env * (spec * (15.0 / 16.0) + 1.0 / 16.0);
        assert!((got - want).abs().max_element() < 1e-6, "{got} vs {want}");
        // BRDF1 takes |n·v|: a view below the surface mirrors the one above; the others clamp.
        let below = Vec3::new(v.x, 0.0, -v.z);
        assert_eq!(
            indirect_specular(Brdf::Brdf1, env, spec, 0.5, 0.48, n, below),
            indirect_specular(Brdf::Brdf1, env, spec, 0.5, 0.48, n, v)
        );
        let flat = indirect_specular(Brdf::Brdf3, env, spec, 0.5, 0.48, n, Vec3::X);
        assert_eq!(
            indirect_specular(Brdf::Brdf3, env, spec, 0.5, 0.48, n, below),
            flat
        );
    }

    /// BRDF1 at a hand-computed configuration: n = Z, l at 60° from n, v = n, so h is at 30°.
    #[test]
    fn brdf1_direct_hand_computed() {
        let n = Vec3::Z;
        let l = Vec3::new((0.75f32).sqrt(), 0.0, 0.5);
        let v = Vec3::Z;
        let smoothness = 0.5f32; // pr = 0.5, r = 0.25
        let (nl, nv) = (0.5f32, 1.0f32);
        let nh = (PI / 6.0).cos();
        let lh = nh; // h bisects l and v
        let pr = 0.5f32;
        let fd90 = 0.5 + 2.0 * lh * lh * pr;
        let kd = (1.0 + (fd90 - 1.0) * (1.0 - nl).powi(5)) * 1.0 * nl;
        let r = 0.25f32;
        let vis = 0.5 / (nl * (nv * (1.0 - r) + r) + nv * (nl * (1.0 - r) + r) + 1e-5);
        let d = nh * nh * (r * r - 1.0) + 1.0;
        let dist = r * r / (PI * (d * d + 1e-7));
        let ks = vis * dist * PI * nl;
        let spec = Vec3::new(0.04, 0.5, 1.0);
        let diffuse = Vec3::new(0.2, 0.3, 0.4);
        let lc = Vec3::new(1.0, 2.0, 0.5);
        let fresnel = spec + (Vec3::ONE - spec) * (1.0 - lh).powi(5);
        let want = diffuse * lc * kd + ks * lc * fresnel;
        let got = direct(Brdf::Brdf1, diffuse, spec, smoothness, n, v, l, lc);
        assert!((got - want).abs().max_element() < 1e-5, "{got} vs {want}");
        // No specular colour, no specular at all (Unity's any(specColor)).
        let matte = direct(Brdf::Brdf1, diffuse, Vec3::ZERO, smoothness, n, v, l, lc);
        assert!((matte - diffuse * lc * kd).abs().max_element() < 1e-6);
    }

    /// BRDF3 reads the table at ((r·l)⁴, pr) and scales by 16.
    #[test]
    fn brdf3_direct_reads_the_table() {
        let n = Vec3::Z;
        let v = Vec3::new(0.6, 0.0, 0.8);
        let l = Vec3::new(-0.6, 0.0, 0.8); // the mirror direction: r·l = 1
        let got = direct(Brdf::Brdf3, Vec3::ZERO, Vec3::ONE, 0.5, n, v, l, Vec3::ONE);
        let want = crate::brdf_lut::sample(crate::brdf_lut::shared_table(), 1.0, 0.5) * 16.0 * 0.8;
        assert!(
            (got - Vec3::splat(want)).abs().max_element() < 1e-6,
            "{got} {want}"
        );
        assert!(
            want > 10.0,
            "a bright highlight at the mirror direction: {want}"
        );
    }

    /// Each tier vanishes with a grazing light and stays finite for l = −v.
    #[test]
    fn direct_vanishes_with_grazing_light() {
        for brdf in Brdf::ALL {
            let d = direct(
                brdf,
                Vec3::ONE,
                Vec3::ONE,
                0.8,
                Vec3::Z,
                Vec3::Z,
                Vec3::X,
                Vec3::ONE,
            );
            assert_eq!(d, Vec3::ZERO, "{brdf:?}");
            let opposite = direct(
                brdf,
                Vec3::ONE,
                Vec3::ONE,
                0.8,
                Vec3::Z,
                Vec3::X,
                Vec3::NEG_X,
                Vec3::ONE,
            );
            assert!(opposite.is_finite(), "{brdf:?}");
        }
    }
}
