//! The world normal in URP's GBuffer2, and the normal encodings compared in the README.
//!
//! With "Accurate G-buffer normals" (`_GBUFFER_NORMALS_OCT`) URP stores the normal
//! octahedral-encoded and packed as two 12-bit values into the three bytes of an
//! `Rgba8Unorm` target (URP's `UnityGBuffer.hlsl` `PackNormal`, with `PackNormalOctQuadEncode`
//! and `PackFloat2To888` of the SRP core `Packing.hlsl`); without it, the normal is written as
//! is into an `Rgba8Snorm` target. The lighting pass normalizes what it decodes.
//!
//! Octahedral encoding (Cigolle et al., "A Survey of Efficient Representations for Independent
//! Unit Vectors", JCGT 2014): `n / (|x| + |y| + |z|)`; for the lower hemisphere the xy
//! triangle is folded out: `t = saturate(−z)`, `xy += (xy ≥ 0 ? t : −t)`. Decode:
//! `n = (x, y, 1 − |x| − |y|)`, `t = max(−z, 0)`, `xy += (xy ≥ 0 ? −t : t)`, normalize.
//!
//! 12:12 → 8:8:8: `i = trunc(f · 4095.5)` per component (f in [0, 1] after `· 0.5 + 0.5` and
//! saturate); bytes `(i.x & 255, i.y & 255, (i.x >> 8) | (i.y >> 8) << 4)`. Decode:
//! `f = (byte0 | (byte2 & 15) << 8, byte1 | (byte2 >> 4) << 8) / 4095`. The shader writes the
//! bytes as `byte / 255` to a unorm target, which stores exactly that byte.

use glam::{Vec2, Vec3};

/// Octahedral encoding of a direction into [−1, 1]² (URP's `PackNormalOctQuadEncode`).
///
/// `n` need not be unit length; the L1 norm is floored at 1e-6 as URP does, so the zero
/// vector encodes as (0, 0).
///
/// ```
/// use glam::{Vec2, Vec3};
/// use wgsl_variants_shaders::reference::urp::normal::oct_encode;
/// assert_eq!(oct_encode(Vec3::Z), Vec2::ZERO);
/// assert_eq!(oct_encode(Vec3::X), Vec2::X);
/// assert_eq!(oct_encode(Vec3::NEG_Z), Vec2::ONE);   // the fold: every corner is −Z
/// ```
pub fn oct_encode(n: Vec3) -> Vec2 {
    let n = n / n.abs().dot(Vec3::ONE).max(1e-6);
    let t = (-n.z).clamp(0.0, 1.0);
    let fold = |c: f32| if c >= 0.0 { t } else { -t };
    Vec2::new(n.x + fold(n.x), n.y + fold(n.y))
}

/// The unit direction of an octahedral code in [−1, 1]² (URP's `UnpackNormalOctQuadEncode`).
///
/// ```
/// use glam::{Vec2, Vec3};
/// use wgsl_variants_shaders::reference::urp::normal::oct_decode;
/// assert_eq!(oct_decode(Vec2::ZERO), Vec3::Z);
/// assert_eq!(oct_decode(Vec2::new(-1.0, 1.0)), Vec3::NEG_Z);
/// ```
pub fn oct_decode(f: Vec2) -> Vec3 {
    let mut n = Vec3::new(f.x, f.y, 1.0 - f.x.abs() - f.y.abs());
    let t = (-n.z).max(0.0);
    n.x += if n.x >= 0.0 { -t } else { t };
    n.y += if n.y >= 0.0 { -t } else { t };
    n.normalize()
}

/// Two values in [0, 1] packed as 12 bits each into three bytes (SRP core's
/// `PackFloat2To888`). Inputs outside [0, 1] are saturated first (NaN as 0).
///
/// ```
/// use glam::Vec2;
/// use wgsl_variants_shaders::reference::urp::normal::pack_float2_to_888;
/// // 1.0 · 4095.5 = 4095.5 → 4095 = 0xFFF; 0.5 · 4095.5 = 2047.75 → 2047 = 0x7FF.
/// assert_eq!(pack_float2_to_888(Vec2::new(1.0, 0.5)), [0xFF, 0xFF, 0x7F]);
/// ```
pub fn pack_float2_to_888(f: Vec2) -> [u8; 3] {
    let code = |v: f32| {
        let v = if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) };
        (f64::from(v) * 4095.5).trunc() as u32
    };
    let (x, y) = (code(f.x), code(f.y));
    [
        (x & 255) as u8,
        (y & 255) as u8,
        ((x >> 8) | ((y >> 8) << 4)) as u8,
    ]
}

/// The two values of three packed bytes, each `code / 4095` (SRP core's `Unpack888ToFloat2`).
///
/// ```
/// use glam::Vec2;
/// use wgsl_variants_shaders::reference::urp::normal::unpack_888_to_float2;
/// assert_eq!(unpack_888_to_float2([0xFF, 0x00, 0x0F]), Vec2::new(1.0, 0.0));
/// ```
pub fn unpack_888_to_float2(b: [u8; 3]) -> Vec2 {
    let x = u32::from(b[0]) | (u32::from(b[2] & 15) << 8);
    let y = u32::from(b[1]) | (u32::from(b[2] >> 4) << 8);
    Vec2::new(x as f32 / 4095.0, y as f32 / 4095.0)
}

/// GBuffer2's rgb bytes for a world normal under `_GBUFFER_NORMALS_OCT`:
/// `pack_float2_to_888(saturate(oct_encode(n) · 0.5 + 0.5))`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::normal::encode_normal_oct;
/// // (0, 0) → (0.5, 0.5) → 2047 = 0x7FF each → bytes (0xFF, 0xFF, 0x77).
/// assert_eq!(encode_normal_oct(Vec3::Z), [0xFF, 0xFF, 0x77]);
/// ```
pub fn encode_normal_oct(n: Vec3) -> [u8; 3] {
    let f = oct_encode(n) * 0.5 + Vec2::splat(0.5);
    pack_float2_to_888(f.clamp(Vec2::ZERO, Vec2::ONE))
}

/// The unit world normal of GBuffer2's rgb bytes under `_GBUFFER_NORMALS_OCT`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::normal::{decode_normal_oct, encode_normal_oct};
/// let n = decode_normal_oct(encode_normal_oct(Vec3::new(0.0, 0.6, -0.8)));
/// assert!((n - Vec3::new(0.0, 0.6, -0.8)).length() < 1e-3);
/// ```
pub fn decode_normal_oct(b: [u8; 3]) -> Vec3 {
    oct_decode(unpack_888_to_float2(b) * 2.0 - Vec2::ONE)
}

/// The byte an 8-bit snorm channel stores for `x` (Vulkan: `round(clamp(x, −1, 1) · 127)`;
/// this rounds ties away from zero, Vulkan leaves ties to the implementation; NaN stores 0).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::normal::snorm8;
/// assert_eq!(snorm8(1.0), 127);
/// assert_eq!(snorm8(-1.0), -127);
/// assert_eq!(snorm8(0.5), 64);     // 63.5: a tie, away from zero
/// assert_eq!(snorm8(-7.0), -127);  // saturated; −128 is never written
/// ```
pub fn snorm8(x: f32) -> i8 {
    if x.is_nan() {
        return 0;
    }
    (f64::from(x.clamp(-1.0, 1.0)) * 127.0).round() as i8
}

/// The value a shader reads from an 8-bit snorm channel: `max(c / 127, −1)` (−128 reads as −1).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::normal::snorm8_to_f32;
/// assert_eq!(snorm8_to_f32(-128), -1.0);
/// assert_eq!(snorm8_to_f32(127), 1.0);
/// ```
pub fn snorm8_to_f32(c: i8) -> f32 {
    (f32::from(c) / 127.0).max(-1.0)
}

/// GBuffer2's rgb without `_GBUFFER_NORMALS_OCT`: the normal as is, in `Rgba8Snorm`.
pub fn encode_normal_snorm8(n: Vec3) -> [i8; 3] {
    [snorm8(n.x), snorm8(n.y), snorm8(n.z)]
}

/// The unit world normal of `Rgba8Snorm` rgb (normalized, as URP's lighting pass does).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::normal::{decode_normal_snorm8, encode_normal_snorm8};
/// assert_eq!(decode_normal_snorm8(encode_normal_snorm8(Vec3::NEG_Y)), Vec3::NEG_Y);
/// ```
pub fn decode_normal_snorm8(c: [i8; 3]) -> Vec3 {
    Vec3::new(
        snorm8_to_f32(c[0]),
        snorm8_to_f32(c[1]),
        snorm8_to_f32(c[2]),
    )
    .normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn octahedral_values_computed_on_paper() {
        // n = (0.6, 0, −0.8): L1 = 1.4 → (0.428571, 0, −0.571429); t = 0.571429;
        // x ≥ 0 → x + t = 1.0; y = 0 ≥ 0 → 0 + t = 0.571429.
        let e = oct_encode(Vec3::new(0.6, 0.0, -0.8));
        assert!(
            (e - Vec2::new(1.0, 0.571_429)).abs().max_element() < 1e-6,
            "{e}"
        );
        // Remap: (1.0, 0.785714); · 4095.5 → (4095.5, 3217.89) → (4095, 3217)
        // = (0xFFF, 0xC91); bytes (0xFF, 0x91, 0xF | 0xC << 4 = 0xCF).
        assert_eq!(
            encode_normal_oct(Vec3::new(0.6, 0.0, -0.8)),
            [0xFF, 0x91, 0xCF]
        );
        // Decode: (4095, 3217)/4095 = (1, 0.785592) → (1, 0.571184); z = 1 − 1 − 0.571184
        // = −0.571184; t = 0.571184; x: 1 − t = 0.428816; y: 0.571184 − t = 0;
        // normalize (0.428816, 0, −0.571184): length 0.714237 → (0.600383, 0, −0.799713).
        let d = decode_normal_oct([0xFF, 0x91, 0xCF]);
        assert!(
            (d - Vec3::new(0.600_383, 0.0, -0.799_713))
                .abs()
                .max_element()
                < 2e-6,
            "{d}"
        );
        // n = (1, 1, 1)/√3: L1 = √3 → (1/3, 1/3, 1/3); z > 0: no fold. Remap 2/3:
        // 0.666667 · 4095.5 = 2730.33 → 2730 = 0xAAA; bytes (0xAA, 0xAA, 0xA | 0xA << 4 = 0xAA).
        assert_eq!(encode_normal_oct(Vec3::ONE.normalize()), [0xAA, 0xAA, 0xAA]);
    }

    #[test]
    fn every_888_code_round_trips() {
        for x in (0..4096u32).step_by(7) {
            for y in (0..4096u32).step_by(13) {
                let f = Vec2::new(x as f32 / 4095.0, y as f32 / 4095.0);
                let b = pack_float2_to_888(f);
                let back = unpack_888_to_float2(b);
                assert_eq!(back, f, "{x} {y}");
            }
        }
    }

    #[test]
    fn snorm_values_computed_on_paper() {
        // 0.6 · 127 = 76.2 → 76; −0.8 · 127 = −101.6 → −102.
        assert_eq!(
            encode_normal_snorm8(Vec3::new(0.6, 0.0, -0.8)),
            [76, 0, -102]
        );
        // Decode: (76, 0, −102)/127 → (0.598425, 0, −0.803150); length 1.001580
        // → (0.597481, 0, −0.801883).
        let d = decode_normal_snorm8([76, 0, -102]);
        assert!(
            (d - Vec3::new(0.597_481, 0.0, -0.801_883))
                .abs()
                .max_element()
                < 2e-6,
            "{d}"
        );
    }
}
