//! Storing values in render-target formats: unorm channels, half floats and the packed
//! `Rgb10a2Unorm` word (docs/shading.md §1, Target formats and quantization).
//!
//! These are the conversions a GPU performs when a fragment shader writes to a target, done the
//! way Vulkan describes them. Where Vulkan leaves a choice (which way a unorm tie rounds), this
//! module makes one fixed choice and [`super::tolerance`] accepts the other.

use glam::{Vec3, Vec4};

/// The largest value of a `bits`-wide unorm channel, `2^bits − 1`.
///
/// # Panics
/// When `bits` is not in `1..=16`.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::unorm_max;
/// assert_eq!(unorm_max(8), 255);
/// assert_eq!(unorm_max(10), 1023);
/// assert_eq!(unorm_max(2), 3);
/// ```
pub fn unorm_max(bits: u32) -> u32 {
    assert!(
        (1..=16).contains(&bits),
        "unorm channels of 1 to 16 bits are supported, not {bits}"
    );
    (1u32 << bits) - 1
}

/// The value a unorm channel of `bits` bits stores for `x`: `round(saturate(x) · (2^bits − 1))`.
///
/// NaN stores 0 (Vulkan). Ties round up (Vulkan allows either way; use
/// [`super::tolerance::unorm_within`] to accept both). The product is formed in `f64`, where it is
/// exact, so the only rounding is the final one.
///
/// # Panics
/// When `bits` is not in `1..=16`.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::unorm;
/// assert_eq!(unorm(1.0, 8), 255);
/// assert_eq!(unorm(2.0, 8), 255);        // saturated
/// assert_eq!(unorm(-1.0, 10), 0);        // saturated
/// assert_eq!(unorm(f32::NAN, 10), 0);    // NaN stores 0
/// assert_eq!(unorm(0.5, 8), 128);        // 127.5: a tie, rounded up (127 is also correct)
/// assert_eq!(unorm(0.25, 10), 256);      // 255.75
/// ```
pub fn unorm(x: f32, bits: u32) -> u32 {
    let max = unorm_max(bits);
    if x.is_nan() {
        return 0;
    }
    let scaled = f64::from(x.clamp(0.0, 1.0)) * f64::from(max);
    // `f64::round` rounds half away from zero, i.e. up for these non-negative values.
    scaled.round() as u32
}

/// The value a shader reads back from a unorm channel holding `q`: `q / (2^bits − 1)`.
///
/// # Panics
/// When `bits` is not in `1..=16` or `q > 2^bits − 1`.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
/// assert_eq!(unorm_to_f32(255, 8), 1.0);
/// assert_eq!(unorm_to_f32(0, 10), 0.0);
/// assert_eq!(unorm_to_f32(3, 2), 1.0);
/// assert!((unorm_to_f32(128, 8) - 128.0 / 255.0).abs() < 1e-7);
/// ```
pub fn unorm_to_f32(q: u32, bits: u32) -> f32 {
    let max = unorm_max(bits);
    assert!(q <= max, "{q} does not fit a {bits}-bit unorm channel");
    (f64::from(q) / f64::from(max)) as f32
}

/// [`unorm`] applied to the four channels of `v`, with the given bit widths per channel
/// (`[8; 4]` for `Rgba8Unorm`, `[10, 10, 10, 2]` for `Rgb10a2Unorm`).
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::quantize::unorm4;
/// assert_eq!(unorm4(Vec4::new(0.0, 0.5, 1.0, 1.0), [10, 10, 10, 2]), [0, 512, 1023, 3]);
/// ```
pub fn unorm4(v: Vec4, bits: [u32; 4]) -> [u32; 4] {
    [
        unorm(v.x, bits[0]),
        unorm(v.y, bits[1]),
        unorm(v.z, bits[2]),
        unorm(v.w, bits[3]),
    ]
}

/// [`unorm_to_f32`] applied to four channels with the given bit widths.
///
/// # Panics
/// As [`unorm_to_f32`].
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::quantize::unorm4_to_vec4;
/// assert_eq!(unorm4_to_vec4([255, 0, 1023, 3], [8, 8, 10, 2]), Vec4::new(1.0, 0.0, 1.0, 1.0));
/// ```
pub fn unorm4_to_vec4(q: [u32; 4], bits: [u32; 4]) -> Vec4 {
    Vec4::new(
        unorm_to_f32(q[0], bits[0]),
        unorm_to_f32(q[1], bits[1]),
        unorm_to_f32(q[2], bits[2]),
        unorm_to_f32(q[3], bits[3]),
    )
}

/// Packs `[r, g, b, a]` (10, 10, 10 and 2 bits) into one `Rgb10a2Unorm` texel word as wgpu and
/// Vulkan (`A2B10G10R10_UNORM_PACK32`) lay it out: r in bits 0–9, g in 10–19, b in 20–29, a in
/// 30–31. Read the word from texture bytes with `u32::from_le_bytes`.
///
/// # Panics
/// When a channel does not fit its width.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::{pack_rgb10a2, unpack_rgb10a2};
/// let word = pack_rgb10a2([1023, 0, 512, 3]);
/// assert_eq!(word, 0xC000_03FF | (512 << 20));
/// assert_eq!(unpack_rgb10a2(word), [1023, 0, 512, 3]);
/// ```
pub fn pack_rgb10a2(c: [u32; 4]) -> u32 {
    assert!(
        c[0] <= 1023 && c[1] <= 1023 && c[2] <= 1023 && c[3] <= 3,
        "{c:?} does not fit Rgb10a2Unorm"
    );
    c[0] | (c[1] << 10) | (c[2] << 20) | (c[3] << 30)
}

/// Splits an `Rgb10a2Unorm` texel word into `[r, g, b, a]`; the inverse of [`pack_rgb10a2`].
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::unpack_rgb10a2;
/// assert_eq!(unpack_rgb10a2(u32::MAX), [1023, 1023, 1023, 3]);
/// ```
pub fn unpack_rgb10a2(word: u32) -> [u32; 4] {
    [
        word & 0x3ff,
        (word >> 10) & 0x3ff,
        (word >> 20) & 0x3ff,
        word >> 30,
    ]
}

/// The IEEE binary16 (half float) bits nearest to `x`, ties to even, as an `Rgba16Float` target
/// stores an `f32`.
///
/// Results below the normal range become subnormals (or ±0), values that round past 65504
/// become ±infinity (65520 is the first such value: it is a tie and 65504's significand is odd),
/// infinities stay infinities and NaN stays a (quiet) NaN with the sign kept.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::f32_to_f16_bits;
/// assert_eq!(f32_to_f16_bits(1.0), 0x3C00);
/// assert_eq!(f32_to_f16_bits(-2.0), 0xC000);
/// assert_eq!(f32_to_f16_bits(65504.0), 0x7BFF);
/// assert_eq!(f32_to_f16_bits(65519.0), 0x7BFF);
/// assert_eq!(f32_to_f16_bits(65520.0), 0x7C00);            // overflow to +inf
/// assert_eq!(f32_to_f16_bits(f32::NEG_INFINITY), 0xFC00);
/// assert_eq!(f32_to_f16_bits(2f32.powi(-24)), 0x0001);     // smallest subnormal
/// assert_eq!(f32_to_f16_bits(2f32.powi(-25)), 0x0000);     // a tie between 0 and it: even
/// assert_eq!(f32_to_f16_bits(1.0 + 2f32.powi(-11)), 0x3C00); // tie: to even
/// assert!(f32_to_f16_bits(f32::NAN) & 0x7FFF > 0x7C00);
/// ```
pub fn f32_to_f16_bits(x: f32) -> u16 {
    let b = x.to_bits();
    let sign = ((b >> 16) & 0x8000) as u16;
    let exp = ((b >> 23) & 0xff) as i32;
    let man = b & 0x007f_ffff;
    if exp == 0xff {
        // Infinity, or NaN: keep it a quiet NaN, with the top payload bits.
        return if man == 0 {
            sign | 0x7c00
        } else {
            sign | 0x7e00 | (man >> 13) as u16
        };
    }
    // Exponent re-biased for f16.
    let e = exp - 127 + 15;
    if e >= 0x1f {
        return sign | 0x7c00;
    }
    // Round `value >> shift` to nearest, ties to even.
    fn round_shift(value: u32, shift: u32) -> u32 {
        let q = value >> shift;
        let rem = value & ((1 << shift) - 1);
        let half = 1 << (shift - 1);
        if rem > half || (rem == half && q & 1 == 1) {
            q + 1
        } else {
            q
        }
    }
    if e <= 0 {
        // Subnormal (or zero) in f16. An f32 subnormal (exp == 0) is far below f16's range.
        if exp == 0 {
            return sign;
        }
        let full = man | 0x0080_0000; // 24-bit significand
        let shift = (14 - e) as u32; // 13 for the first normal exponent, one more per step down
        if shift > 24 {
            return sign; // below half the smallest subnormal
        }
        // A carry out of the subnormal range yields 0x0400, the smallest normal: still correct.
        return sign | round_shift(full, shift) as u16;
    }
    // Normal. A carry out of the significand increments the exponent (up to infinity): correct.
    sign | round_shift(((e as u32) << 23) | man, 13) as u16
}

/// The `f32` value of the half float with bits `h` (exact: every f16 value is an f32 value).
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32;
/// assert_eq!(f16_bits_to_f32(0x3C00), 1.0);
/// assert_eq!(f16_bits_to_f32(0x7BFF), 65504.0);
/// assert_eq!(f16_bits_to_f32(0x0001), 2f32.powi(-24));
/// assert_eq!(f16_bits_to_f32(0xFC00), f32::NEG_INFINITY);
/// assert!(f16_bits_to_f32(0x7E00).is_nan());
/// assert!(f16_bits_to_f32(0x8000).is_sign_negative());
/// ```
pub fn f16_bits_to_f32(h: u16) -> f32 {
    let sign = u32::from(h & 0x8000) << 16;
    let exp = u32::from((h >> 10) & 0x1f);
    let man = u32::from(h & 0x3ff);
    let bits = match exp {
        0 if man == 0 => sign,
        0 => {
            // Subnormal: man · 2^-24, normalised for f32.
            let lz = man.leading_zeros() - 21; // zeros within the 11-bit field above bit 10
            let man = (man << lz) & 0x3ff;
            let e = 127 - 15 + 1 - lz;
            sign | (e << 23) | (man << 13)
        }
        0x1f => sign | 0x7f80_0000 | (man << 13),
        _ => sign | ((exp + 127 - 15) << 23) | (man << 13),
    };
    f32::from_bits(bits)
}

/// `x` rounded to the nearest half float and back: the value an `Rgba16Float` target holds after
/// `x` is written to it.
///
/// ```
/// use wgsl_variants_shaders::reference::quantize::round_f16;
/// assert_eq!(round_f16(1.0), 1.0);
/// assert_eq!(round_f16(0.1), 0.099975586);
/// assert_eq!(round_f16(1e6), f32::INFINITY);
/// ```
pub fn round_f16(x: f32) -> f32 {
    f16_bits_to_f32(f32_to_f16_bits(x))
}

/// [`round_f16`] on each channel.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::quantize::round_f16_vec3;
/// assert_eq!(round_f16_vec3(Vec3::new(1.0, 2.0, 0.5)), Vec3::new(1.0, 2.0, 0.5));
/// ```
pub fn round_f16_vec3(v: Vec3) -> Vec3 {
    Vec3::new(round_f16(v.x), round_f16(v.y), round_f16(v.z))
}

/// [`f32_to_f16_bits`] on each channel of `v`, as an `Rgba16Float` texel.
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::quantize::f16x4;
/// assert_eq!(f16x4(Vec4::new(0.0, 1.0, -2.0, 0.5)), [0x0000, 0x3C00, 0xC000, 0x3800]);
/// ```
pub fn f16x4(v: Vec4) -> [u16; 4] {
    [
        f32_to_f16_bits(v.x),
        f32_to_f16_bits(v.y),
        f32_to_f16_bits(v.z),
        f32_to_f16_bits(v.w),
    ]
}

/// The `f32` values of an `Rgba16Float` texel; the inverse of [`f16x4`] on f16 values.
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::quantize::f16x4_to_vec4;
/// assert_eq!(f16x4_to_vec4([0x0000, 0x3C00, 0xC000, 0x3800]), Vec4::new(0.0, 1.0, -2.0, 0.5));
/// ```
pub fn f16x4_to_vec4(h: [u16; 4]) -> Vec4 {
    Vec4::new(
        f16_bits_to_f32(h[0]),
        f16_bits_to_f32(h[1]),
        f16_bits_to_f32(h[2]),
        f16_bits_to_f32(h[3]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The value of f16 bits computed from the IEEE definition, independently of the bit tricks.
    fn f16_value(h: u16) -> f64 {
        let s = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
        let e = i32::from((h >> 10) & 0x1f);
        let m = f64::from(h & 0x3ff);
        match e {
            0 => s * m * 2f64.powi(-24),
            0x1f if m == 0.0 => s * f64::INFINITY,
            0x1f => f64::NAN,
            _ => s * (1.0 + m / 1024.0) * 2f64.powi(e - 15),
        }
    }

    #[test]
    fn every_f16_decodes_to_its_ieee_value() {
        for h in 0..=u16::MAX {
            let got = f16_bits_to_f32(h);
            let want = f16_value(h);
            if want.is_nan() {
                assert!(got.is_nan(), "{h:#06x}");
            } else {
                assert_eq!(f64::from(got), want, "{h:#06x}");
                assert_eq!(got.is_sign_negative(), h & 0x8000 != 0, "{h:#06x} sign");
            }
        }
    }

    #[test]
    fn every_f16_round_trips() {
        for h in 0..=u16::MAX {
            let back = f32_to_f16_bits(f16_bits_to_f32(h));
            if f16_value(h).is_nan() {
                assert!(back & 0x7fff > 0x7c00, "{h:#06x} -> {back:#06x}");
                assert_eq!(back & 0x8000, h & 0x8000);
                // The top payload bits survive, and the result is quiet.
                assert_eq!(back & 0x3ff, (h & 0x3ff) | 0x200);
            } else {
                assert_eq!(back, h, "{h:#06x}");
            }
        }
    }

    /// Between every pair of neighbouring finite f16 values (and past the largest one), the
    /// midpoint rounds to the even one and the f32 values next to it round to the nearer one.
    #[test]
    fn rounding_is_to_nearest_even_everywhere() {
        for lo in 0u16..0x7c00 {
            let a = f64::from(f16_bits_to_f32(lo));
            // The next f16 up, or for 65504 the value 65536 where the exponent range would continue.
            let b = if lo == 0x7bff {
                65536.0
            } else {
                f64::from(f16_bits_to_f32(lo + 1))
            };
            let mid = ((a + b) / 2.0) as f32; // exact: 12 significant bits
            assert_eq!(f64::from(mid), (a + b) / 2.0);
            let up = lo + 1; // for lo = 0x7bff this is 0x7c00, infinity
            let even = if lo & 1 == 0 { lo } else { up };
            for sign in [0u16, 0x8000] {
                let m = if sign == 0 { mid } else { -mid };
                assert_eq!(f32_to_f16_bits(m), even | sign, "mid {m}");
                let below = f32::from_bits(mid.to_bits() - 1);
                let above = f32::from_bits(mid.to_bits() + 1);
                let (below, above) = if sign == 0 {
                    (below, above)
                } else {
                    (-below, -above)
                };
                assert_eq!(f32_to_f16_bits(below), lo | sign, "below mid {below}");
                assert_eq!(f32_to_f16_bits(above), up | sign, "above mid {above}");
            }
        }
    }

    #[test]
    fn f16_conversion_edges() {
        assert_eq!(f32_to_f16_bits(0.0), 0);
        assert_eq!(f32_to_f16_bits(-0.0), 0x8000);
        assert_eq!(f32_to_f16_bits(f32::MIN_POSITIVE), 0);
        assert_eq!(f32_to_f16_bits(f32::from_bits(1)), 0);
        assert_eq!(f32_to_f16_bits(-f32::from_bits(1)), 0x8000);
        assert_eq!(f32_to_f16_bits(f32::MAX), 0x7c00);
        assert_eq!(f32_to_f16_bits(f32::INFINITY), 0x7c00);
        assert_eq!(f32_to_f16_bits(1e-8), 0);
        // Smallest subnormal reached from slightly above half of it.
        assert_eq!(f32_to_f16_bits(2f32.powi(-25) * 1.0001), 1);
        // Largest subnormal rounding up into the smallest normal.
        assert_eq!(
            f32_to_f16_bits(2f32.powi(-14) * (1.0 - 2f32.powi(-20))),
            0x0400
        );
        let n = f32_to_f16_bits(-f32::NAN);
        assert!(n & 0x7fff > 0x7c00 && n & 0x8000 != 0);
    }

    #[test]
    fn unorm_matches_round_of_scaled_value_for_every_code() {
        for bits in [2u32, 8, 10] {
            let max = unorm_max(bits);
            for q in 0..=max {
                let x = unorm_to_f32(q, bits);
                assert_eq!(unorm(x, bits), q, "{bits}-bit code {q}");
                // Just inside either rounding boundary.
                let lo = (f64::from(q) - 0.49) / f64::from(max);
                let hi = (f64::from(q) + 0.49) / f64::from(max);
                assert_eq!(unorm(lo as f32, bits), q);
                assert_eq!(unorm(hi as f32, bits), q);
            }
        }
    }

    #[test]
    fn unorm_saturates_and_maps_nan_to_zero() {
        for bits in [1u32, 2, 8, 10, 16] {
            let max = unorm_max(bits);
            assert_eq!(unorm(f32::INFINITY, bits), max);
            assert_eq!(unorm(f32::NEG_INFINITY, bits), 0);
            assert_eq!(unorm(f32::NAN, bits), 0);
            assert_eq!(unorm(-0.0, bits), 0);
            assert_eq!(unorm(1.0000001, bits), max);
        }
        assert_eq!(unorm(0.5, 10), 512);
        assert_eq!(unorm(0.5, 2), 2);
        assert_eq!(unorm(0.25, 8), 64); // 63.75
    }

    #[test]
    #[should_panic]
    fn unorm_rejects_zero_bits() {
        unorm(0.5, 0);
    }

    #[test]
    #[should_panic]
    fn unorm_to_f32_rejects_out_of_range_codes() {
        unorm_to_f32(256, 8);
    }

    #[test]
    fn rgb10a2_packing_round_trips() {
        for c in [
            [0, 0, 0, 0],
            [1023, 1023, 1023, 3],
            [1, 2, 3, 1],
            [512, 723, 256, 2],
        ] {
            assert_eq!(unpack_rgb10a2(pack_rgb10a2(c)), c);
        }
        assert_eq!(pack_rgb10a2([0, 0, 0, 1]), 1 << 30);
        assert_eq!(pack_rgb10a2([0, 1, 0, 0]), 1 << 10);
    }
}
