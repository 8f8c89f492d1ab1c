//! The lookup texture of the Standard BRDF's lowest tier (BRDF3, `UNITY_PBS_USE_BRDF3`):
//! Unity's `unity_NHxRoughness`, generated from its definition (docs/shading.md §5).
//!
//! Unity's engine fills this texture in code it does not publish; its shader sources
//! (`UnityStandardBRDF.cginc`) say what it holds: a normalized Blinn-Phong "in RDF form" (a
//! lobe around the reflected view direction), indexed by `(r·l)⁴` horizontally ("power exponent
//! must match kHorizontalWarpExp") and perceptual roughness vertically, scaled into [0, 1] by a
//! range of 16 (`LUT_RANGE`). This module writes that down as one definition ([`value`]):
//!
//! ```text
//! n = max(2 / max(r², 10⁻⁴) − 2, 10⁻⁴)        r = pr², Unity's PerceptualRoughnessToSpecPower
//! value(x, pr) = min((n + 2) / 2 · x^(n/4), 16) / 16       x = (r·l)⁴, so x^(n/4) = (r·l)^n
//! ```
//!
//! `(n + 2)/(2π)` normalizes the Phong lobe; the factor π is Unity's convention for every
//! specular term (its diffuse term is not divided by π, `UnityStandardBRDF.cginc`), so the table
//! holds `π · (n + 2)/(2π)`. The shader reads the table with `textureLoad` at the four
//! texels around `(x, pr)` (texel centres at `(i + ½)/size`, clamped to the edge) and
//! interpolates in `f32` ([`sample`]) instead of the sampler's bilinear filter, whose sub-texel
//! precision is implementation-defined (Vulkan requires 4 bits): the result is the same function
//! on every GPU and the reference can state it exactly. The table is stored as `R16Float`
//! ([`texels_f16`]); [`table`] gives the values already rounded to `f16`.
//!
//! ```
//! use wgsl_variants_shaders::brdf_lut::{sample, table, value, WIDTH, HEIGHT};
//! let t = table();
//! assert_eq!(t.len(), (WIDTH * HEIGHT) as usize);
//! // Rough surface (pr = 1, n ≈ 0): a flat lobe of (0 + 2)/2 = 1, i.e. 1/16 of the range.
//! assert!((value(0.5, 1.0) - 1.0 / 16.0).abs() < 1e-4);
//! // Sampling between texel centres interpolates.
//! let s = sample(&t, 0.5, 0.5);
//! assert!(s > 0.0 && s <= 1.0);
//! ```

use crate::reference::quantize::{f16_bits_to_f32, f32_to_f16_bits};

/// Texels along `x = (r·l)⁴`.
pub const WIDTH: u32 = 256;
/// Texels along perceptual roughness.
pub const HEIGHT: u32 = 64;
/// Unity's `LUT_RANGE`: the shader multiplies the table's value by it.
pub const RANGE: f32 = 16.0;

/// Unity's `PerceptualRoughnessToSpecPower`: `n = max(2 / max(r², 10⁻⁴) − 2, 10⁻⁴)` with
/// `r = pr²` (the Blinn-Phong exponent that matches the GGX roughness `r`).
///
/// ```
/// use wgsl_variants_shaders::brdf_lut::spec_power;
/// assert_eq!(spec_power(1.0), 1e-4); // 2/1 − 2 = 0, floored
/// assert_eq!(spec_power(0.5), 30.0); // r = 0.25, r² = 1/16
/// ```
pub fn spec_power(perceptual_roughness: f32) -> f32 {
    let r = perceptual_roughness * perceptual_roughness;
    let sq = (r * r).max(1e-4);
    (2.0 / sq - 2.0).max(1e-4)
}

/// The table's definition at `x = (r·l)⁴` and perceptual roughness `pr`, in [0, 1]:
/// `min((n + 2)/2 · x^(n/4), 16) / 16` with `n` = [`spec_power`]`(pr)`.
///
/// ```
/// use wgsl_variants_shaders::brdf_lut::value;
/// // pr = 0.5 (n = 30): at r·l = 1 the lobe is 16, the top of the range.
/// assert_eq!(value(1.0, 0.5), 1.0);
/// assert_eq!(value(0.0, 0.5), 0.0);
/// ```
pub fn value(x: f32, perceptual_roughness: f32) -> f32 {
    let n = spec_power(perceptual_roughness);
    let lobe = (n + 2.0) / 2.0 * x.max(0.0).powf(n / 4.0);
    lobe.min(RANGE) / RANGE
}

/// The table, row by row (`pr` rows of `x`): [`value`] at each texel centre, rounded to `f16`
/// (the values [`texels_f16`] stores).
pub fn table() -> Vec<f32> {
    texels_f16().into_iter().map(f16_bits_to_f32).collect()
}

/// [`table`], computed once per process (the reference reads it for every BRDF3 pixel).
pub fn shared_table() -> &'static [f32] {
    static TABLE: std::sync::OnceLock<Vec<f32>> = std::sync::OnceLock::new();
    TABLE.get_or_init(table)
}

/// The table as `R16Float` texels (the bits of each `f16`), row by row, for a
/// `WIDTH × HEIGHT` texture bound as the passes' `brdf_lut` (group 0, binding 17).
pub fn texels_f16() -> Vec<u16> {
    let mut out = Vec::with_capacity((WIDTH * HEIGHT) as usize);
    for j in 0..HEIGHT {
        let pr = (j as f32 + 0.5) / HEIGHT as f32;
        for i in 0..WIDTH {
            let x = (i as f32 + 0.5) / WIDTH as f32;
            out.push(f32_to_f16_bits(value(x, pr)));
        }
    }
    out
}

/// The shader's read of the table at `(x, pr)`: `t = clamp((x, pr) · size − ½, 0, size − 1)`,
/// the four texels at `floor(t)` and `min(floor(t) + 1, size − 1)`, interpolated with
/// `f = t − floor(t)` as `mix(mix(a, b, f.x), mix(c, d, f.x), f.y)` (`mix(a, b, t) =
/// a·(1 − t) + b·t`).
///
/// # Panics
/// When `table` is not `WIDTH × HEIGHT` long.
pub fn sample(table: &[f32], x: f32, perceptual_roughness: f32) -> f32 {
    assert_eq!(table.len(), (WIDTH * HEIGHT) as usize, "a BRDF3 table");
    let axis = |u: f32, size: u32| {
        let t = (u * size as f32 - 0.5).clamp(0.0, (size - 1) as f32);
        let i = t.floor();
        let lo = i as usize;
        (lo, (lo + 1).min(size as usize - 1), t - i)
    };
    let (x0, x1, fx) = axis(x, WIDTH);
    let (y0, y1, fy) = axis(perceptual_roughness, HEIGHT);
    let at = |x: usize, y: usize| table[y * WIDTH as usize + x];
    let mix = |a: f32, b: f32, t: f32| a * (1.0 - t) + b * t;
    mix(
        mix(at(x0, y0), at(x1, y0), fx),
        mix(at(x0, y1), at(x1, y1), fx),
        fy,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The generator writes the definition at every texel centre (to f16 rounding) and is
    /// monotonic where the definition is: increasing in `x`, and at `x = 1` the narrowing lobe
    /// grows as roughness falls until it saturates.
    #[test]
    fn table_is_the_definition_at_texel_centres() {
        let t = table();
        for j in [0, 17, HEIGHT - 1] {
            for i in [0, 100, WIDTH - 1] {
                let x = (i as f32 + 0.5) / WIDTH as f32;
                let pr = (j as f32 + 0.5) / HEIGHT as f32;
                let want = value(x, pr);
                let got = t[(j * WIDTH + i) as usize];
                assert!(
                    (got - want).abs() <= want * 1e-3 + 1e-7,
                    "{i},{j}: {got} {want}"
                );
                // At a texel centre the interpolation returns the texel.
                assert_eq!(sample(&t, x, pr), got);
            }
        }
        for row in t.chunks(WIDTH as usize) {
            assert!(row.windows(2).all(|w| w[0] <= w[1]), "increasing in x");
        }
        assert!(t.iter().all(|v| (0.0..=1.0).contains(v)));
    }

    /// Hand-computed: pr = 0.75 → r = 0.5625, r² = 0.31640625, n = 2/r² − 2 = 4.3209…;
    /// at r·l = 0.9 the lobe is (n + 2)/2 · 0.9^n.
    #[test]
    fn value_hand_computed() {
        let n = 2.0 / 0.316_406_25f64 - 2.0;
        let want = (n + 2.0) / 2.0 * 0.9f64.powf(n) / 16.0;
        let got = value(0.9f32.powi(4), 0.75) as f64;
        assert!((got - want).abs() < 1e-5, "{got} {want}");
    }

    /// Between texel centres the read is linear in each axis; outside the centres it clamps.
    #[test]
    fn sample_interpolates_and_clamps() {
        let t = table();
        let (x0, x1) = (10.5 / WIDTH as f32, 11.5 / WIDTH as f32);
        let pr = 20.5 / HEIGHT as f32;
        let mid = sample(&t, 11.0 / WIDTH as f32, pr);
        let (a, b) = (sample(&t, x0, pr), sample(&t, x1, pr));
        assert!((mid - (a + b) / 2.0).abs() < 1e-6);
        assert_eq!(sample(&t, 0.0, pr), sample(&t, 0.5 / WIDTH as f32, pr));
        assert_eq!(sample(&t, 1.0, 1.0), t[t.len() - 1]);
    }
}
