//! Comparing a target texel read back from the GPU with the reference value, through
//! [`wgsl_variants_shaders::reference::tolerance`] (and nothing else).

use glam::Vec4;

use super::report::{Mismatch, PassReport};
use crate::TargetFormat;
use wgsl_variants_shaders::reference::gbuffer::{RGB10A2, RGBA8};
use wgsl_variants_shaders::reference::tolerance::{
    f16x4_within, f32_within, snorm8_within, srgb8_within, ufloat_within, unorm_within,
    unorm4_within, vec4_within,
};
use wgsl_variants_shaders::reference::urp::ufloat::UFloat;

/// Whether the raw texel `raw` of a `format` target is acceptable for the reference value
/// `expected` (what the shader wrote, before the target stored it): 1 LSB on unorm channels
/// (either correct rounding), 1 f16 ULP on `Rgba16Float`, the `f32` bound on `Rgba32Float`
/// and `R32Float`; `Rgba8UnormSrgb` colour channels within 1 LSB of the exact sRGB encoding of
/// the linear value, `Rgba8Snorm` 1 LSB, `Rg11b10Ufloat` 1 step of each channel's format, and
/// `R32Uint` exactly (`expected.x` an integer). URP's octahedral normals are compared by their
/// 12-bit codes instead (`urp::compare_texel`).
pub fn texel_within(format: TargetFormat, raw: [u32; 4], expected: Vec4) -> bool {
    match format {
        TargetFormat::Rgba8Unorm => unorm4_within(raw, expected, RGBA8),
        TargetFormat::Rgb10a2Unorm => unorm4_within(raw, expected, RGB10A2),
        // The channels hold 16-bit patterns.
        TargetFormat::Rgba16Float => f16x4_within(raw.map(|h| h as u16), expected),
        TargetFormat::Rgba32Float => {
            vec4_within(Vec4::from_array(raw.map(f32::from_bits)), expected)
        }
        // Raw channels are bytes here.
        TargetFormat::Rgba8UnormSrgb => {
            (0..3).all(|i| srgb8_within(raw[i] as u8, expected[i]))
                && unorm_within(raw[3], expected.w, 8)
        }
        TargetFormat::Rgba8Snorm => (0..4).all(|i| snorm8_within(raw[i] as u8 as i8, expected[i])),
        TargetFormat::Rg11b10Ufloat => [UFloat::F11, UFloat::F11, UFloat::F10]
            .into_iter()
            .enumerate()
            .all(|(i, f)| ufloat_within(raw[i] as u16, expected[i], f)),
        TargetFormat::R32Float => f32_within(f32::from_bits(raw[0]), expected.x),
        TargetFormat::R32Uint => f64::from(raw[0]) == f64::from(expected.x),
    }
}

/// Whether the 8-bit code of a shadow mask is within 1 LSB of the reference's factor, the
/// interval between `lo` and `hi` (either order; an interval where a tap or a cascade split is
/// within a hair of flipping): the value of the interval nearest the code is the one compared.
pub fn mask_code_within(code: u8, lo: f32, hi: f32) -> bool {
    let nearest = (f32::from(code) / 255.0).clamp(lo.min(hi), lo.max(hi));
    unorm_within(u32::from(code), nearest, 8)
}

/// The clear colour as the shader-side value a cleared texel is compared with.
pub fn clear_value(clear: [f64; 4]) -> Vec4 {
    Vec4::from_array(clear.map(|c| c as f32))
}

/// One decoded pixel of a tightly packed image: raw channel values and floats.
pub fn pixel(format: TargetFormat, bytes: &[u8], index: usize) -> ([u32; 4], [f32; 4]) {
    let size = format.bytes_per_pixel();
    let px = &bytes[index * size..(index + 1) * size];
    (format.decode_pixel(px), format.decode_pixel_f32(px))
}

/// A short name of a format, for reports.
pub fn format_name(format: TargetFormat) -> &'static str {
    match format {
        TargetFormat::Rgba8Unorm => "Rgba8Unorm",
        TargetFormat::Rgb10a2Unorm => "Rgb10a2Unorm",
        TargetFormat::Rgba16Float => "Rgba16Float",
        TargetFormat::Rgba32Float => "Rgba32Float",
        TargetFormat::Rgba8UnormSrgb => "Rgba8UnormSrgb",
        TargetFormat::Rgba8Snorm => "Rgba8Snorm",
        TargetFormat::Rg11b10Ufloat => "Rg11b10Ufloat",
        TargetFormat::R32Float => "R32Float",
        TargetFormat::R32Uint => "R32Uint",
    }
}

/// Records the comparison of one texel.
#[allow(clippy::too_many_arguments)]
pub(crate) fn compare_texel(
    report: &mut PassReport,
    keywords: &str,
    target: &str,
    format: TargetFormat,
    bytes: &[u8],
    index: usize,
    width: u32,
    expected: Vec4,
) {
    let (raw, got) = pixel(format, bytes, index);
    let ok = texel_within(format, raw, expected);
    let (shader, pass) = (report.shader.clone(), report.pass.clone());
    report.record(ok, || Mismatch {
        shader,
        pass,
        keywords: keywords.to_owned(),
        target: target.to_owned(),
        pixel: [index as u32 % width, index as u32 / width],
        expected: expected.to_array().to_vec(),
        got: got.to_vec(),
        got_raw: raw.to_vec(),
    });
}
