//! The LDR encoding of RT3 (docs/shading.md §3: Unity's `exp2(-c)` / `-log2` pair).
//!
//! Without `UNITY_HDR_ON`, RT3 is a 10-bit unorm target and the G-buffer pass stores
//! `2^(−c)` per channel instead of the light `c ≥ 0`. Light passes multiply into it
//! (`DstColor · src`), which adds in the exponent, and the final pass decodes `−log2(stored)`.
//! Black is stored as white, and everything from `c ≈ 11` up is stored as 0 and decodes to +∞.
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::ldr::{ldr_accumulate, ldr_decode, ldr_encode};
//! let stored = ldr_encode(Vec3::new(0.0, 1.0, 2.0));
//! assert_eq!(stored, Vec3::new(1.0, 0.5, 0.25));
//! let lit = ldr_accumulate(stored, Vec3::splat(1.0));
//! assert_eq!(ldr_decode(lit), Vec3::new(1.0, 2.0, 3.0));
//! ```

use glam::Vec3;

/// One channel of [`ldr_encode`]: `exp2(−max(c, 0))`; NaN is treated as 0 (stores 1).
///
/// ```
/// use wgsl_variants_shaders::reference::ldr::ldr_encode1;
/// assert_eq!(ldr_encode1(3.0), 0.125);
/// assert_eq!(ldr_encode1(-5.0), 1.0);
/// assert_eq!(ldr_encode1(f32::INFINITY), 0.0);
/// assert_eq!(ldr_encode1(f32::NAN), 1.0);
/// ```
pub fn ldr_encode1(c: f32) -> f32 {
    let c = if c > 0.0 { c } else { 0.0 }; // NaN and negatives (and -0) become +0
    (-c).exp2()
}

/// The RT3 value the G-buffer pass writes without `UNITY_HDR_ON`: `exp2(−max(c, 0))` per
/// channel (c < 0 → 1, +∞ → 0, NaN → 1).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::ldr::ldr_encode;
/// assert_eq!(ldr_encode(Vec3::new(-1.0, 0.0, 1.0)), Vec3::new(1.0, 1.0, 0.5));
/// ```
pub fn ldr_encode(c: Vec3) -> Vec3 {
    Vec3::new(ldr_encode1(c.x), ldr_encode1(c.y), ldr_encode1(c.z))
}

/// One channel of [`ldr_decode`]: `max(−log2(s), 0)` (s = 0 → +∞; s ≥ 1 → 0; NaN or negative
/// s → 0). The result is never −0.
///
/// ```
/// use wgsl_variants_shaders::reference::ldr::ldr_decode1;
/// assert_eq!(ldr_decode1(0.25), 2.0);
/// assert_eq!(ldr_decode1(0.0), f32::INFINITY);
/// assert_eq!(ldr_decode1(1.5), 0.0);
/// assert!(ldr_decode1(1.0).is_sign_positive());
/// ```
pub fn ldr_decode1(s: f32) -> f32 {
    let c = -s.log2();
    if c > 0.0 { c } else { 0.0 }
}

/// What the final deferred pass (LDR only) computes from RT3: `−log2(s)` per channel, clamped
/// to ≥ 0 (s = 0 → +∞, which the 8-bit output target clamps to 1; s ≥ 1 → 0).
///
/// For values that went through a 10-bit target, decode `quantize::unorm_to_f32(q, 10)`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::ldr::ldr_decode;
/// use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
/// assert_eq!(ldr_decode(Vec3::new(1.0, 0.5, 0.0)), Vec3::new(0.0, 1.0, f32::INFINITY));
/// // The smallest non-zero 10-bit value decodes to just under 10.
/// let c = ldr_decode(Vec3::splat(unorm_to_f32(1, 10))).x;
/// assert!((c - 9.998590).abs() < 1e-5);
/// ```
pub fn ldr_decode(s: Vec3) -> Vec3 {
    Vec3::new(ldr_decode1(s.x), ldr_decode1(s.y), ldr_decode1(s.z))
}

/// A light pass in LDR: `stored · exp2(−max(light, 0))` per channel — the `DstColor · src`
/// blend of `src = ldr_encode(light)` onto RT3, which adds `light` to the encoded exponent.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::ldr::{ldr_accumulate, ldr_decode, ldr_encode};
/// let a = Vec3::new(0.5, 1.0, 3.0);
/// let b = Vec3::new(1.5, -2.0, 0.25);
/// let sum = ldr_decode(ldr_accumulate(ldr_encode(a), b));
/// assert_eq!(sum, Vec3::new(2.0, 1.0, 3.25)); // negative light adds nothing
/// ```
pub fn ldr_accumulate(stored: Vec3, light: Vec3) -> Vec3 {
    stored * ldr_encode(light)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::quantize::{unorm, unorm_to_f32};
    use crate::reference::tolerance::unorm_within;

    fn stored(c: f32, bits: u32) -> u32 {
        unorm(ldr_encode1(c), bits)
    }

    #[test]
    fn ten_bit_table() {
        // 1023 · 2^-c, rounded: recomputed by hand.
        assert_eq!(stored(0.0, 10), 1023);
        assert_eq!(stored(0.5, 10), 723); // 1023/√2 = 723.37
        // c = 1: 511.5, a tie; this reference rounds up to 512, and 511 is also right (Vulkan).
        assert_eq!(stored(1.0, 10), 512);
        assert!(unorm_within(511, ldr_encode1(1.0), 10));
        assert_eq!(stored(2.0, 10), 256); // 255.75
        assert_eq!(stored(8.0, 10), 4); // 3.996
        assert_eq!(stored(10.0, 10), 1); // 0.999
        assert_eq!(stored(11.0, 10), 0); // 0.4995
        assert_eq!(stored(f32::INFINITY, 10), 0);
        // The exact threshold: 1023 · 2^-c < 0.5 ⇔ c > log2(2046) ≈ 10.9986.
        assert_eq!(stored(10.99, 10), 1);
        let threshold = 2046f32.log2();
        assert_eq!(stored(threshold + 1e-3, 10), 0);
        assert_eq!(stored(threshold - 1e-3, 10), 1);
    }

    #[test]
    fn eight_bit_zero() {
        // 255 · 2^-c < 0.5 ⇔ c > log2(510) ≈ 8.994: 8 bits are already 0 at c = 9 (and at 10).
        assert_eq!(stored(8.0, 8), 1); // 0.996
        assert_eq!(stored(9.0, 8), 0); // 0.498
        assert_eq!(stored(10.0, 8), 0); // 0.249
        assert_eq!(stored(0.0, 8), 255);
        assert_eq!(stored(1.0, 8), 128); // 127.5, a tie
    }

    #[test]
    fn encode_rules() {
        assert_eq!(ldr_encode1(-0.0), 1.0);
        assert_eq!(ldr_encode1(f32::NEG_INFINITY), 1.0);
        assert_eq!(ldr_encode1(-f32::NAN), 1.0);
        assert_eq!(ldr_encode1(1.0), 0.5);
        assert_eq!(ldr_encode1(200.0), 0.0); // underflows
        assert_eq!(ldr_encode1(0.5), std::f32::consts::FRAC_1_SQRT_2);
    }

    #[test]
    fn decode_rules() {
        assert_eq!(ldr_decode1(0.5), 1.0);
        assert_eq!(ldr_decode1(1.0).to_bits(), 0); // +0, not -0
        assert_eq!(ldr_decode1(2.0), 0.0);
        assert_eq!(ldr_decode1(-0.5), 0.0);
        assert_eq!(ldr_decode1(f32::NAN), 0.0);
        assert_eq!(ldr_decode1(-0.0), f32::INFINITY);
        assert_eq!(ldr_decode1(f32::INFINITY), 0.0);
    }

    #[test]
    fn decode_inverts_encode_for_non_negative_light() {
        for i in 0..=400 {
            let c = i as f32 * 0.05;
            let back = ldr_decode1(ldr_encode1(c));
            assert!((back - c).abs() <= 1e-5 * c.max(1.0), "{c} -> {back}");
        }
    }

    #[test]
    fn decoding_every_ten_bit_code_is_monotonic() {
        let mut previous = f32::INFINITY;
        for q in 0..=1023 {
            let c = ldr_decode1(unorm_to_f32(q, 10));
            assert!(c < previous || q == 0, "code {q}");
            previous = c;
            // Re-encoding gives the same code back.
            assert_eq!(unorm(ldr_encode1(c), 10), q);
        }
        assert_eq!(previous, 0.0);
    }

    #[test]
    fn accumulation_adds_in_the_exponent() {
        let stored = ldr_encode(Vec3::new(1.0, 2.0, 0.0));
        let lit = ldr_accumulate(
            ldr_accumulate(stored, Vec3::splat(1.0)),
            Vec3::new(0.5, -1.0, f32::NAN),
        );
        assert_eq!(ldr_decode(lit), Vec3::new(2.5, 3.0, 1.0));
    }
}
