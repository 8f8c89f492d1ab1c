//! Colour-target formats the harness can render into and decode.

use wgsl_variants::reference::quantize::f16_bits_to_f32;

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
}

impl TargetFormat {
    /// Every supported format.
    pub const ALL: [TargetFormat; 4] = [
        TargetFormat::Rgba8Unorm,
        TargetFormat::Rgb10a2Unorm,
        TargetFormat::Rgba16Float,
        TargetFormat::Rgba32Float,
    ];

    /// The corresponding wgpu texture format.
    pub fn wgpu_format(self) -> wgpu::TextureFormat {
        match self {
            TargetFormat::Rgba8Unorm => wgpu::TextureFormat::Rgba8Unorm,
            TargetFormat::Rgb10a2Unorm => wgpu::TextureFormat::Rgb10a2Unorm,
            TargetFormat::Rgba16Float => wgpu::TextureFormat::Rgba16Float,
            TargetFormat::Rgba32Float => wgpu::TextureFormat::Rgba32Float,
        }
    }

    /// The harness format for a wgpu format, if it is one of the supported ones.
    pub fn from_wgpu(format: wgpu::TextureFormat) -> Option<Self> {
        Self::ALL.into_iter().find(|f| f.wgpu_format() == format)
    }

    /// Size of one pixel in bytes.
    pub fn bytes_per_pixel(self) -> usize {
        match self {
            TargetFormat::Rgba8Unorm | TargetFormat::Rgb10a2Unorm => 4,
            TargetFormat::Rgba16Float => 8,
            TargetFormat::Rgba32Float => 16,
        }
    }

    /// Whether the channels are unsigned normalized integers.
    pub fn is_unorm(self) -> bool {
        matches!(self, TargetFormat::Rgba8Unorm | TargetFormat::Rgb10a2Unorm)
    }

    /// Largest raw value of each channel for unorm formats (`255` or `[1023, 1023, 1023, 3]`);
    /// `None` for float formats.
    pub fn unorm_max(self) -> Option<[u32; 4]> {
        match self {
            TargetFormat::Rgba8Unorm => Some([255; 4]),
            TargetFormat::Rgb10a2Unorm => Some([1023, 1023, 1023, 3]),
            TargetFormat::Rgba16Float | TargetFormat::Rgba32Float => None,
        }
    }

    /// Decodes the raw channel values of the first pixel in `bytes`.
    ///
    /// For unorm formats these are the integer channel values (0..=255, or 0..=1023 for the
    /// 10-bit channels and 0..=3 for the 2-bit alpha). For float formats they are the bit
    /// patterns (f16 bits for `Rgba16Float`, f32 bits for `Rgba32Float`); use
    /// [`TargetFormat::decode_pixel_f32`] for values.
    ///
    /// # Panics
    ///
    /// If `bytes` is shorter than [`TargetFormat::bytes_per_pixel`].
    pub fn decode_pixel(self, bytes: &[u8]) -> [u32; 4] {
        let px = &bytes[..self.bytes_per_pixel()];
        match self {
            TargetFormat::Rgba8Unorm => [
                u32::from(px[0]),
                u32::from(px[1]),
                u32::from(px[2]),
                u32::from(px[3]),
            ],
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
    /// float channels are converted exactly.
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
    use wgsl_variants::reference::quantize::f16_bits_to_f32 as f16_to_f32;

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
}
