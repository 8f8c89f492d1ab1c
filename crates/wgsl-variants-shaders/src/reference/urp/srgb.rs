//! The sRGB transfer function and the 8-bit rounding of an `Rgba8UnormSrgb` target (URP's
//! GBuffer0 is `R8G8B8A8_SRGB`: the fragment shader writes linear albedo and the target stores
//! it sRGB-encoded; alpha, the material flags, is stored linearly).
//!
//! The transfer function is IEC 61966-2-1's, as the Khronos Data Format Specification
//! ("sRGB transfer functions") gives it:
//!
//! - encode: `12.92 · L` for `L ≤ 0.0031308`, else `1.055 · L^(1/2.4) − 0.055`;
//! - decode: `S / 12.92` for `S ≤ 0.04045`, else `((S + 0.055) / 1.055)^2.4`.
//!
//! Both are evaluated in `f64` here, so the only rounding that matters is the final one to
//! 8 bits (`round(saturate(S) · 255)`, as [`crate::reference::quantize::unorm`]). GPUs may
//! approximate the encode (Vulkan and D3D allow a small error before the rounding), which
//! [`crate::reference::tolerance::UNORM_LSB`] absorbs.

use glam::Vec3;

use crate::reference::quantize::unorm;

/// The sRGB encoding of a linear value (no clamping; NaN stays NaN).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::srgb::srgb_encode;
/// assert_eq!(srgb_encode(0.0), 0.0);
/// assert!((srgb_encode(1.0) - 1.0).abs() < 1e-7);
/// assert!((srgb_encode(0.5) - 0.735_356_7).abs() < 1e-6);
/// ```
pub fn srgb_encode(linear: f32) -> f32 {
    srgb_encode_f64(f64::from(linear)) as f32
}

fn srgb_encode_f64(l: f64) -> f64 {
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// The linear value of an sRGB-encoded one (no clamping; NaN stays NaN).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::srgb::srgb_decode;
/// assert_eq!(srgb_decode(0.0), 0.0);
/// assert!((srgb_decode(1.0) - 1.0).abs() < 1e-7);
/// assert!((srgb_decode(0.735_356_7) - 0.5).abs() < 1e-6);
/// ```
pub fn srgb_decode(encoded: f32) -> f32 {
    let s = f64::from(encoded);
    let l = if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    };
    l as f32
}

/// The byte an `Rgba8UnormSrgb` colour channel stores for a linear value:
/// `round(saturate(encode(L)) · 255)` (NaN stores 0).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::srgb::srgb8;
/// assert_eq!(srgb8(0.0), 0);
/// assert_eq!(srgb8(1.0), 255);
/// assert_eq!(srgb8(0.5), 188);   // 0.7353567 · 255 = 187.52
/// assert_eq!(srgb8(2.0), 255);   // saturated
/// ```
pub fn srgb8(linear: f32) -> u8 {
    if linear.is_nan() {
        return 0;
    }
    let s = srgb_encode_f64(f64::from(linear)).clamp(0.0, 1.0);
    unorm(s as f32, 8) as u8
}

/// The linear value a shader reads from an `Rgba8UnormSrgb` channel holding `byte`.
///
/// ```
/// use wgsl_variants_shaders::reference::urp::srgb::{srgb8, srgb8_to_linear};
/// assert_eq!(srgb8_to_linear(255), 1.0);
/// assert_eq!(srgb8(srgb8_to_linear(77)), 77);
/// ```
pub fn srgb8_to_linear(byte: u8) -> f32 {
    srgb_decode(f32::from(byte) / 255.0)
}

/// [`srgb8`] on the three colour channels.
pub fn srgb8_vec3(linear: Vec3) -> [u8; 3] {
    [srgb8(linear.x), srgb8(linear.y), srgb8(linear.z)]
}

/// [`srgb8_to_linear`] on the three colour channels.
pub fn srgb8_to_linear_vec3(bytes: [u8; 3]) -> Vec3 {
    Vec3::new(
        srgb8_to_linear(bytes[0]),
        srgb8_to_linear(bytes[1]),
        srgb8_to_linear(bytes[2]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_computed_on_paper() {
        // Linear segment: 0.002 · 12.92 = 0.02584; · 255 = 6.589 → 7.
        assert_eq!(srgb8(0.002), 7);
        // 0.5: 0.5^(1/2.4) = e^(−0.693147/2.4) = e^(−0.288811) = 0.749154;
        // 1.055 · 0.749154 − 0.055 = 0.735357; · 255 = 187.516 → 188.
        assert!((srgb_encode(0.5) - 0.735_357).abs() < 1e-6);
        assert_eq!(srgb8(0.5), 188);
        // 0.2: 0.2^(1/2.4) = e^(−1.609438/2.4) = e^(−0.670599) = 0.511402;
        // 1.055 · 0.511402 − 0.055 = 0.484529; · 255 = 123.55 → 124.
        assert_eq!(srgb8(0.2), 124);
        // Decode 128: 128/255 = 0.501961; (0.501961 + 0.055)/1.055 = 0.527925;
        // 0.527925^2.4 = e^(2.4 · ln 0.527925) = e^(2.4 · −0.638800) = e^(−1.533123) = 0.215861.
        assert!((srgb8_to_linear(128) - 0.215_861).abs() < 1e-5);
        // Decode 10: 10/255 = 0.039216 ≤ 0.04045 → 0.039216 / 12.92 = 0.0030353.
        assert!((srgb8_to_linear(10) - 0.003_035_3).abs() < 1e-7);
    }

    #[test]
    fn every_byte_round_trips_and_the_curve_is_monotonic() {
        let mut last = -1.0f32;
        for b in 0..=255u8 {
            let l = srgb8_to_linear(b);
            assert!(l > last, "{b}");
            last = l;
            assert_eq!(srgb8(l), b);
        }
        assert_eq!(srgb8(-1.0), 0);
        assert_eq!(srgb8(f32::NAN), 0);
    }
}
