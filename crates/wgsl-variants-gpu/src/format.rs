//! Colour-target formats the harness can render into and decode.
//!
//! URP's G-buffer formats (`Rgba8UnormSrgb`, `Rgba8Snorm`, `Rg11b10Ufloat`, `R32Float`,
//! `R32Uint`) are decoded with [`wgsl_variants_shaders::reference::urp`]'s functions, so the harness
//! reads them exactly as a CPU user of the reference would.

use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32;
use wgsl_variants_shaders::reference::urp::normal::snorm8_to_f32;
use wgsl_variants_shaders::reference::urp::srgb::srgb8_to_linear;
use wgsl_variants_shaders::reference::urp::ufloat::{split_rg11b10, unpack_rg11b10};

/// A colour-target format supported by the render harness and its decoders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TargetFormat {
    /// 8-bit unsigned normalized RGBA.
    Rgba8Unorm,
    /// 10/10/10/2-bit unsigned normalized RGBA, packed little-endian into one `u32`
    /// with red in the low bits.
    Rgb10a2Unorm,
    /// Four IEEE half-precision floats.
    Rgba16Float,
    /// Four IEEE single-precision floats.
    Rgba32Float,
    /// 8-bit RGBA whose colour channels hold sRGB-encoded values (alpha is linear): URP's
    /// GBuffer0.
    Rgba8UnormSrgb,
    /// 8-bit signed normalized RGBA: URP's GBuffer2 without `_GBUFFER_NORMALS_OCT`.
    Rgba8Snorm,
    /// Unsigned 11-bit r and g and 10-bit b floats packed into one little-endian `u32` (r in
    /// bits 0–10): URP's GBuffer3.
    Rg11b10Ufloat,
    /// One IEEE single-precision float: URP's depth as colour.
    R32Float,
    /// One 32-bit unsigned integer: URP's rendering layers.
    R32Uint,
}

impl TargetFormat {
    /// Every supported format.
    pub const ALL: [TargetFormat; 9] = [
        TargetFormat::Rgba8Unorm,
        TargetFormat::Rgb10a2Unorm,
        TargetFormat::Rgba16Float,
        TargetFormat::Rgba32Float,
        TargetFormat::Rgba8UnormSrgb,
        TargetFormat::Rgba8Snorm,
        TargetFormat::Rg11b10Ufloat,
        TargetFormat::R32Float,
        TargetFormat::R32Uint,
    ];

    /// The corresponding wgpu texture format.
    pub fn wgpu_format(self) -> wgpu::TextureFormat {
        match self {
            TargetFormat::Rgba8Unorm => wgpu::TextureFormat::Rgba8Unorm,
            TargetFormat::Rgb10a2Unorm => wgpu::TextureFormat::Rgb10a2Unorm,
            TargetFormat::Rgba16Float => wgpu::TextureFormat::Rgba16Float,
            TargetFormat::Rgba32Float => wgpu::TextureFormat::Rgba32Float,
            TargetFormat::Rgba8UnormSrgb => wgpu::TextureFormat::Rgba8UnormSrgb,
            TargetFormat::Rgba8Snorm => wgpu::TextureFormat::Rgba8Snorm,
            TargetFormat::Rg11b10Ufloat => wgpu::TextureFormat::Rg11b10Ufloat,
            TargetFormat::R32Float => wgpu::TextureFormat::R32Float,
            TargetFormat::R32Uint => wgpu::TextureFormat::R32Uint,
        }
    }

    /// The harness format for a wgpu format, if it is one of the supported ones.
    pub fn from_wgpu(format: wgpu::TextureFormat) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.wgpu_format() == format)
    }

    /// Size of one pixel in bytes.
    pub fn bytes_per_pixel(self) -> usize {
        match self {
            TargetFormat::Rgba8Unorm
            | TargetFormat::Rgb10a2Unorm
            | TargetFormat::Rgba8UnormSrgb
            | TargetFormat::Rgba8Snorm
            | TargetFormat::Rg11b10Ufloat
            | TargetFormat::R32Float
            | TargetFormat::R32Uint => 4,
            TargetFormat::Rgba16Float => 8,
            TargetFormat::Rgba32Float => 16,
        }
    }

    /// Whether the channels are unsigned normalized integers stored linearly (not
    /// `Rgba8UnormSrgb`, whose colour channels are sRGB-encoded).
    pub fn is_unorm(self) -> bool {
        matches!(self, TargetFormat::Rgba8Unorm | TargetFormat::Rgb10a2Unorm)
    }

    /// Largest raw value of each channel for unorm formats (`255` or `[1023, 1023, 1023, 3]`);
    /// `None` for float formats.
    pub fn unorm_max(self) -> Option<[u32; 4]> {
        match self {
            TargetFormat::Rgba8Unorm => Some([255; 4]),
            TargetFormat::Rgb10a2Unorm => Some([1023, 1023, 1023, 3]),
            _ => None,
        }
    }

    /// Decodes the raw channel values of the first pixel in `bytes`.
    ///
    /// For unorm formats these are the integer channel values (0..=255, or 0..=1023 for the
    /// 10-bit channels and 0..=3 for the 2-bit alpha). For float formats they are the bit
    /// patterns (f16 bits for `Rgba16Float`, f32 bits for `Rgba32Float`); use
    /// [`TargetFormat::decode_pixel_f32`] for values. `Rgba8UnormSrgb` gives its four bytes,
    /// `Rgba8Snorm` its four bytes as two's complement (0..=255), `Rg11b10Ufloat` the bits of
    /// r, g and b and 0, `R32Float` the f32 bits and `R32Uint` the value, each followed by
    /// zeros.
    ///
    /// ```
    /// use wgsl_variants_gpu::TargetFormat;
    /// let word: u32 = 0x3C0 | (0x400 << 11) | (0x1C0 << 22); // 1.0, 2.0, 0.5
    /// assert_eq!(TargetFormat::Rg11b10Ufloat.decode_pixel(&word.to_le_bytes()), [0x3C0, 0x400, 0x1C0, 0]);
    /// assert_eq!(TargetFormat::Rg11b10Ufloat.decode_pixel_f32(&word.to_le_bytes()), [1.0, 2.0, 0.5, 1.0]);
    /// assert_eq!(TargetFormat::Rgba8Snorm.decode_pixel_f32(&[0x81, 0x80, 127, 0]), [-1.0, -1.0, 1.0, 0.0]);
    /// ```
    ///
    /// # Panics
    ///
    /// If `bytes` is shorter than [`TargetFormat::bytes_per_pixel`].
    pub fn decode_pixel(self, bytes: &[u8]) -> [u32; 4] {
        let px = &bytes[..self.bytes_per_pixel()];
        match self {
            TargetFormat::Rgba8Unorm | TargetFormat::Rgba8UnormSrgb | TargetFormat::Rgba8Snorm => {
                [0, 1, 2, 3].map(|i| u32::from(px[i]))
            }
            TargetFormat::Rg11b10Ufloat => {
                let [r, g, b] = split_rg11b10(u32::from_le_bytes([px[0], px[1], px[2], px[3]]));
                [u32::from(r), u32::from(g), u32::from(b), 0]
            }
            TargetFormat::R32Float | TargetFormat::R32Uint => {
                [u32::from_le_bytes([px[0], px[1], px[2], px[3]]), 0, 0, 0]
            }
            TargetFormat::Rgb10a2Unorm => {
                let v = u32::from_le_bytes([px[0], px[1], px[2], px[3]]);
                [v & 0x3ff, (v >> 10) & 0x3ff, (v >> 20) & 0x3ff, v >> 30]
            }
            TargetFormat::Rgba16Float => {
                std::array::from_fn(|i| u32::from(u16::from_le_bytes([px[2 * i], px[2 * i + 1]])))
            }
            TargetFormat::Rgba32Float => std::array::from_fn(|i| {
                u32::from_le_bytes([px[4 * i], px[4 * i + 1], px[4 * i + 2], px[4 * i + 3]])
            }),
        }
    }

    /// Decodes the first pixel in `bytes` to floats: unorm channels are normalized to 0..=1,
    /// float channels are converted exactly; `Rgba8UnormSrgb` colour channels are decoded to
    /// linear ([`srgb8_to_linear`]), `Rgba8Snorm` channels read as `max(c / 127, −1)`, and the
    /// one- and three-channel formats fill the missing channels with 0 (g, b) and 1 (alpha).
    /// `R32Uint` converts its value to `f32` (rounded above 2^24).
    ///
    /// # Panics
    ///
    /// If `bytes` is shorter than [`TargetFormat::bytes_per_pixel`].
    pub fn decode_pixel_f32(self, bytes: &[u8]) -> [f32; 4] {
        let raw = self.decode_pixel(bytes);
        match self {
            TargetFormat::Rgba8Unorm | TargetFormat::Rgb10a2Unorm => {
                let max = self.unorm_max().unwrap_or([1; 4]);
                std::array::from_fn(|i| raw[i] as f32 / max[i] as f32)
            }
            // Channels hold 16-bit patterns, so the truncation is lossless.
            TargetFormat::Rgba16Float => std::array::from_fn(|i| f16_bits_to_f32(raw[i] as u16)),
            TargetFormat::Rgba32Float => raw.map(f32::from_bits),
            TargetFormat::Rgba8UnormSrgb => {
                let byte = |i: usize| raw[i] as u8; // bytes: lossless
                [
                    srgb8_to_linear(byte(0)),
                    srgb8_to_linear(byte(1)),
                    srgb8_to_linear(byte(2)),
                    f32::from(byte(3)) / 255.0,
                ]
            }
            TargetFormat::Rgba8Snorm => raw.map(|c| snorm8_to_f32(c as u8 as i8)),
            TargetFormat::Rg11b10Ufloat => {
                let word = u32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]);
                unpack_rg11b10(word).extend(1.0).to_array()
            }
            TargetFormat::R32Float => [f32::from_bits(raw[0]), 0.0, 0.0, 1.0],
            TargetFormat::R32Uint => [raw[0] as f32, 0.0, 0.0, 1.0],
        }
    }

    /// Decodes a tightly packed image into raw channel values, one entry per pixel
    /// (see [`TargetFormat::decode_pixel`]). A trailing partial pixel is ignored.
    pub fn decode_image(self, bytes: &[u8]) -> Vec<[u32; 4]> {
        bytes
            .chunks_exact(self.bytes_per_pixel())
            .map(|px| self.decode_pixel(px))
            .collect()
    }

    /// Decodes a tightly packed image into floats, one entry per pixel
    /// (see [`TargetFormat::decode_pixel_f32`]). A trailing partial pixel is ignored.
    pub fn decode_image_f32(self, bytes: &[u8]) -> Vec<[f32; 4]> {
        bytes
            .chunks_exact(self.bytes_per_pixel())
            .map(|px| self.decode_pixel_f32(px))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    // The harness decodes with the library's converter: these pin it for render targets.
    use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32 as f16_to_f32;

    #[test]
    fn f16_normal_values() {
        assert_eq!(f16_to_f32(0x3c00), 1.0);
        assert_eq!(f16_to_f32(0xc000), -2.0);
        assert_eq!(f16_to_f32(0x3800), 0.5);
        assert_eq!(f16_to_f32(0x3555), 0.333_251_95);
        assert_eq!(f16_to_f32(0x7bff), 65504.0);
        assert_eq!(f16_to_f32(0x0400), 6.103_515_6e-5);
    }

    #[test]
    fn f16_zero_and_subnormals() {
        assert_eq!(f16_to_f32(0x0000).to_bits(), 0.0f32.to_bits());
        assert_eq!(f16_to_f32(0x8000).to_bits(), (-0.0f32).to_bits());
        assert_eq!(f16_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(f16_to_f32(0x8001), -(2f32.powi(-24)));
        assert_eq!(f16_to_f32(0x03ff), 1023.0 * 2f32.powi(-24));
        assert_eq!(f16_to_f32(0x0200), 2f32.powi(-15));
    }

    #[test]
    fn f16_inf_and_nan() {
        assert_eq!(f16_to_f32(0x7c00), f32::INFINITY);
        assert_eq!(f16_to_f32(0xfc00), f32::NEG_INFINITY);
        assert!(f16_to_f32(0x7e00).is_nan());
        assert!(f16_to_f32(0x7c01).is_nan());
        assert!(f16_to_f32(0xfe00).is_nan());
    }

    #[test]
    fn f16_exhaustive_round_trip_of_finite_values() {
        // Every finite f16 maps to an f32 that converts back to the same bits.
        for bits in 0u16..=0xffff {
            let value = f16_to_f32(bits);
            if value.is_nan() {
                continue;
            }
            let back = f32_to_f16_exact(value);
            assert_eq!(back, Some(bits), "bits {bits:#06x} -> {value}");
        }
    }

    /// Reference inverse for exactly representable values only.
    fn f32_to_f16_exact(value: f32) -> Option<u16> {
        let sign = if value.is_sign_negative() {
            0x8000u16
        } else {
            0
        };
        let magnitude = value.abs();
        if magnitude.is_infinite() {
            return Some(sign | 0x7c00);
        }
        if magnitude < 2f32.powi(-14) {
            let m = magnitude / 2f32.powi(-24);
            return (m.fract() == 0.0 && m < 1024.0).then_some(sign | m as u16);
        }
        let exponent = magnitude.log2().floor() as i32;
        let mantissa = magnitude / 2f32.powi(exponent) - 1.0;
        let m = mantissa * 1024.0;
        if m.fract() != 0.0 || !(-14..=15).contains(&exponent) {
            return None;
        }
        Some(sign | (((exponent + 15) as u16) << 10) | m as u16)
    }

    #[test]
    fn unorm_decoding() {
        let px = [1u8, 2, 3, 255];
        assert_eq!(TargetFormat::Rgba8Unorm.decode_pixel(&px), [1, 2, 3, 255]);
        let packed: u32 = 256 | (1023 << 10) | (5 << 20) | (2 << 30);
        let px = packed.to_le_bytes();
        assert_eq!(
            TargetFormat::Rgb10a2Unorm.decode_pixel(&px),
            [256, 1023, 5, 2]
        );
        let f = TargetFormat::Rgb10a2Unorm.decode_pixel_f32(&px);
        assert_eq!(f[1], 1.0);
        assert!((f[3] - 2.0 / 3.0).abs() < 1e-6);
    }

    #[test]
    fn float_decoding() {
        let mut px = Vec::new();
        for h in [0x3c00u16, 0x3800, 0xc000, 0x0000] {
            px.extend_from_slice(&h.to_le_bytes());
        }
        assert_eq!(
            TargetFormat::Rgba16Float.decode_pixel(&px),
            [0x3c00, 0x3800, 0xc000, 0]
        );
        assert_eq!(
            TargetFormat::Rgba16Float.decode_pixel_f32(&px),
            [1.0, 0.5, -2.0, 0.0]
        );
        let px: Vec<u8> = [1.5f32, -0.25, 8.0, 0.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        assert_eq!(
            TargetFormat::Rgba32Float.decode_pixel_f32(&px),
            [1.5, -0.25, 8.0, 0.0]
        );
        assert_eq!(TargetFormat::Rgba32Float.decode_image_f32(&px).len(), 1);
    }

    #[test]
    fn urp_format_decoding() {
        // sRGB bytes decode through the reference's transfer function; alpha is linear.
        let srgb = TargetFormat::Rgba8UnormSrgb;
        assert_eq!(srgb.decode_pixel(&[188, 0, 255, 51]), [188, 0, 255, 51]);
        let f = srgb.decode_pixel_f32(&[188, 0, 255, 51]);
        assert!((f[0] - 0.5).abs() < 3e-3 && f[1] == 0.0 && f[2] == 1.0 && f[3] == 0.2);
        // Snorm: two's complement bytes, −128 reads as −1.
        let snorm = TargetFormat::Rgba8Snorm;
        assert_eq!(
            snorm.decode_pixel(&[0x80, 0x81, 0, 64]),
            [0x80, 0x81, 0, 64]
        );
        assert_eq!(
            snorm.decode_pixel_f32(&[0x80, 0x81, 0, 127]),
            [-1.0, -1.0, 0.0, 1.0]
        );
        // One-channel formats.
        let depth = 0.5f32.to_bits().to_le_bytes();
        assert_eq!(
            TargetFormat::R32Float.decode_pixel_f32(&depth),
            [0.5, 0.0, 0.0, 1.0]
        );
        let layers = 0x8000_0005u32.to_le_bytes();
        assert_eq!(
            TargetFormat::R32Uint.decode_pixel(&layers),
            [0x8000_0005, 0, 0, 0]
        );
        for format in TargetFormat::ALL {
            assert_eq!(TargetFormat::from_wgpu(format.wgpu_format()), Some(format));
        }
    }
}
