//! The G-buffer: what the deferred pass writes, quantized as the targets store it, and decoded
//! back to surface values (docs/shading.md §1, §2, §7: Unity's built-in deferred G-buffer).
//!
//! | target | format | contents |
//! |---|---|---|
//! | RT0 | `Rgba8Unorm` | diffuse colour rgb, occlusion a |
//! | RT1 | `Rgba8Unorm` | specular colour rgb, smoothness a |
//! | RT2 | `Rgb10a2Unorm` | `encode_normal(n)`, a = 1 |
//! | RT3 | `Rgb10a2Unorm` holding `ldr_encode(c)`, or `Rgba16Float` holding `c` with `UNITY_HDR_ON`; a = 1 |
//!
//! Decoding a G-buffer read back from the GPU:
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::gbuffer::GBufferTexel;
//! use wgsl_variants_shaders::reference::quantize::pack_rgb10a2;
//! // Bytes as read from the four targets at one pixel (an Rgb10a2Unorm texel is one
//! // little-endian u32: r in bits 0–9, g 10–19, b 20–29, a 30–31).
//! let rt0 = [204u8, 102, 51, 255];
//! let rt1 = [10u8, 10, 10, 128];
//! let rt2 = pack_rgb10a2([512, 512, 1023, 3]).to_le_bytes(); // normal (0, 0, 1)
//! let rt3 = pack_rgb10a2([512, 512, 512, 3]).to_le_bytes(); // 2^-1 per channel: c = 1 (LDR)
//! let texel = GBufferTexel::from_bytes(rt0, rt1, rt2, &rt3).unwrap();
//! let s = texel.decode();
//! assert_eq!(s.diffuse, Vec3::new(0.8, 0.4, 0.2));
//! assert_eq!(s.occlusion, 1.0);
//! assert!((s.normal - Vec3::Z).length() < 2e-3);
//! assert!((s.c - Vec3::ONE).abs().max_element() < 0.01);
//! ```

use glam::{Vec3, Vec4};

use super::ldr::{ldr_decode, ldr_encode};
use super::quantize::{f16x4, f16x4_to_vec4, unorm4, unorm4_to_vec4, unpack_rgb10a2};

/// Bit widths of an `Rgba8Unorm` texel.
pub const RGBA8: [u32; 4] = [8, 8, 8, 8];
/// Bit widths of an `Rgb10a2Unorm` texel.
pub const RGB10A2: [u32; 4] = [10, 10, 10, 2];

/// RT2's colour for a world normal: `normalize(n) · 0.5 + 0.5`.
///
/// Every finite non-zero normal is normalized, including tiny and huge ones whose squared
/// length under- or overflows `f32` (the direction is computed in `f64`, where it does not).
/// The zero normal is taken as (0, 0, 1), which encodes as (0.5, 0.5, 1); so is a normal with
/// an infinite or NaN component, for which `normalize` defines nothing. (A GPU may flush
/// subnormal components to zero; such normals are not comparable.)
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::gbuffer::encode_normal;
/// assert_eq!(encode_normal(Vec3::new(0.0, 0.0, 5.0)), Vec3::new(0.5, 0.5, 1.0));
/// assert_eq!(encode_normal(Vec3::NEG_X), Vec3::new(0.0, 0.5, 0.5));
/// assert_eq!(encode_normal(Vec3::ZERO), Vec3::new(0.5, 0.5, 1.0));
/// assert_eq!(encode_normal(Vec3::new(0.0, -1.0e30, 0.0)), Vec3::new(0.5, 0.0, 0.5));
/// ```
pub fn encode_normal(n: Vec3) -> Vec3 {
    let unit = if n.is_finite() && n != Vec3::ZERO {
        n.as_dvec3().normalize().as_vec3()
    } else {
        Vec3::Z
    };
    unit * 0.5 + 0.5
}

/// The world normal from RT2's colour: `normalize(rgb · 2 − 1)`.
///
/// `rgb · 2 − 1` is never zero for a value read from a 10-bit target (0.5 is not a 10-bit
/// value); for a float input where it is zero (or not normalizable), this returns (0, 0, 1)
/// — where the GPU's `normalize` would give NaN.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::gbuffer::{decode_normal, encode_normal};
/// assert_eq!(decode_normal(Vec3::new(0.5, 0.5, 1.0)), Vec3::Z);
/// let n = Vec3::new(1.0, -2.0, 3.0).normalize();
/// assert!((decode_normal(encode_normal(n)) - n).length() < 1e-6);
/// ```
pub fn decode_normal(rgb: Vec3) -> Vec3 {
    (rgb * 2.0 - 1.0).normalize_or(Vec3::Z)
}

/// The four colours the deferred pass writes at one pixel, before the targets quantize them
/// (`rtN` is target N's `vec4<f32>` output).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GBuffer {
    /// RT0: diffuse colour rgb, occlusion a.
    pub rt0: Vec4,
    /// RT1: specular colour rgb, smoothness a.
    pub rt1: Vec4,
    /// RT2: `encode_normal(n)` rgb, a = 1.
    pub rt2: Vec4,
    /// RT3: `c` (HDR) or `ldr_encode(c)` (LDR) rgb, a = 1.
    pub rt3: Vec4,
}

impl GBuffer {
    /// The G-buffer pass's outputs for the given surface values; `c` is the light in RT3
    /// (emission + ambient + reflections), stored as is when `hdr` (`UNITY_HDR_ON`), else
    /// `ldr_encode`d.
    ///
    /// ```
    /// use glam::{Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::gbuffer::GBuffer;
    /// let g = GBuffer::pack(Vec3::splat(0.5), 0.75, Vec3::splat(0.04), 0.3, Vec3::Y,
    ///                       Vec3::new(0.0, 1.0, 2.0), false);
    /// assert_eq!(g.rt0, Vec4::new(0.5, 0.5, 0.5, 0.75));
    /// assert_eq!(g.rt1, Vec4::new(0.04, 0.04, 0.04, 0.3));
    /// assert_eq!(g.rt2, Vec4::new(0.5, 1.0, 0.5, 1.0));
    /// assert_eq!(g.rt3, Vec4::new(1.0, 0.5, 0.25, 1.0));
    /// let h = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ZERO, 0.0, Vec3::Y, Vec3::new(0.0, 1.0, 2.0), true);
    /// assert_eq!(h.rt3, Vec4::new(0.0, 1.0, 2.0, 1.0));
    /// ```
    pub fn pack(
        diffuse: Vec3,
        occlusion: f32,
        specular: Vec3,
        smoothness: f32,
        normal: Vec3,
        c: Vec3,
        hdr: bool,
    ) -> GBuffer {
        let light = if hdr { c } else { ldr_encode(c) };
        GBuffer {
            rt0: diffuse.extend(occlusion),
            rt1: specular.extend(smoothness),
            rt2: encode_normal(normal).extend(1.0),
            rt3: light.extend(1.0),
        }
    }
}

/// RT3 as stored: 10-bit unorm channels (LDR) or half-float bits (`UNITY_HDR_ON`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rt3Texel {
    /// `Rgb10a2Unorm` channels `[r, g, b, a]` (10, 10, 10, 2 bits), holding `ldr_encode(c)`.
    Ldr([u32; 4]),
    /// `Rgba16Float` channel bits, holding `c`.
    Hdr([u16; 4]),
}

impl Rt3Texel {
    /// Whether this is the HDR (`Rgba16Float`) form.
    pub fn is_hdr(&self) -> bool {
        matches!(self, Rt3Texel::Hdr(_))
    }

    /// The value a shader reads from this texel (unorm → `[0, 1]`, f16 → `f32`).
    ///
    /// ```
    /// use glam::Vec4;
    /// use wgsl_variants_shaders::reference::gbuffer::Rt3Texel;
    /// assert_eq!(Rt3Texel::Ldr([1023, 0, 0, 3]).to_vec4(), Vec4::new(1.0, 0.0, 0.0, 1.0));
    /// assert_eq!(Rt3Texel::Hdr([0x4000, 0, 0, 0x3C00]).to_vec4(), Vec4::new(2.0, 0.0, 0.0, 1.0));
    /// ```
    pub fn to_vec4(&self) -> Vec4 {
        match *self {
            Rt3Texel::Ldr(q) => unorm4_to_vec4(q, RGB10A2),
            Rt3Texel::Hdr(h) => f16x4_to_vec4(h),
        }
    }
}

/// One pixel of the G-buffer as the targets store it: unorm channel integers and half-float
/// bits. Build it from texture bytes (see the module example) or with [`GBufferTexel::quantize`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GBufferTexel {
    /// RT0 (`Rgba8Unorm`): diffuse rgb, occlusion a; each 0 ..= 255.
    pub rt0: [u32; 4],
    /// RT1 (`Rgba8Unorm`): specular rgb, smoothness a; each 0 ..= 255.
    pub rt1: [u32; 4],
    /// RT2 (`Rgb10a2Unorm`): encoded normal rgb (0 ..= 1023), a (0 ..= 3).
    pub rt2: [u32; 4],
    /// RT3: 10-bit light exponent (LDR) or half-float light (HDR).
    pub rt3: Rt3Texel,
}

/// Surface values decoded from a G-buffer pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecodedSurface {
    /// Diffuse colour (RT0.rgb).
    pub diffuse: Vec3,
    /// Occlusion (RT0.a).
    pub occlusion: f32,
    /// Specular colour (RT1.rgb).
    pub specular: Vec3,
    /// Smoothness (RT1.a).
    pub smoothness: f32,
    /// Unit world normal, `decode_normal(RT2.rgb)`.
    pub normal: Vec3,
    /// The light in RT3: `ldr_decode(RT3.rgb)` for LDR (+∞ where a channel stores 0), RT3.rgb
    /// for HDR. After the light and reflection passes this includes their contributions.
    pub c: Vec3,
}

impl GBufferTexel {
    /// The texel from the raw bytes of the four targets at one pixel, as read back from wgpu:
    /// RT0 and RT1 `Rgba8Unorm` (4 bytes), RT2 `Rgb10a2Unorm` (one little-endian `u32`), RT3
    /// either `Rgb10a2Unorm` (4 bytes: LDR) or `Rgba16Float` (8 bytes, four little-endian
    /// `u16`: HDR). `None` when `rt3` has another length.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::gbuffer::GBufferTexel;
    /// use wgsl_variants_shaders::reference::quantize::pack_rgb10a2;
    /// let rt2 = pack_rgb10a2([1023, 512, 512, 3]).to_le_bytes(); // normal +X
    /// let rt3: Vec<u8> = [0x4000u16, 0x3C00, 0, 0x3C00].iter().flat_map(|h| h.to_le_bytes()).collect();
    /// let t = GBufferTexel::from_bytes([255, 0, 0, 255], [10, 10, 10, 0], rt2, &rt3).unwrap();
    /// let s = t.decode();
    /// assert_eq!(s.c, Vec3::new(2.0, 1.0, 0.0));
    /// assert!((s.normal - Vec3::X).length() < 2e-3);
    /// assert!(GBufferTexel::from_bytes([0; 4], [0; 4], [0; 4], &[0; 6]).is_none());
    /// ```
    pub fn from_bytes(
        rt0: [u8; 4],
        rt1: [u8; 4],
        rt2: [u8; 4],
        rt3: &[u8],
    ) -> Option<GBufferTexel> {
        let rt3 = match rt3.len() {
            4 => Rt3Texel::Ldr(unpack_rgb10a2(u32::from_le_bytes(rt3.try_into().ok()?))),
            8 => Rt3Texel::Hdr(std::array::from_fn(|i| {
                u16::from_le_bytes([rt3[2 * i], rt3[2 * i + 1]])
            })),
            _ => return None,
        };
        Some(GBufferTexel {
            rt0: rt0.map(u32::from),
            rt1: rt1.map(u32::from),
            rt2: unpack_rgb10a2(u32::from_le_bytes(rt2)),
            rt3,
        })
    }

    /// What the targets store for the shader outputs `g`: `unorm` on RT0/RT1 (8 bits) and
    /// RT2 (10/10/10/2), and on RT3 10/10/10/2 unorm (`hdr == false`) or f16 (`hdr == true`).
    /// Unorm ties round up here; `tolerance::unorm_within` accepts either way.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::gbuffer::{GBuffer, GBufferTexel, Rt3Texel};
    /// let g = GBuffer::pack(Vec3::ONE, 1.0, Vec3::ZERO, 0.5, Vec3::Z, Vec3::new(0.0, 1.0, 2.0), false);
    /// let t = GBufferTexel::quantize(&g, false);
    /// assert_eq!(t.rt0, [255, 255, 255, 255]);
    /// assert_eq!(t.rt1, [0, 0, 0, 128]);
    /// assert_eq!(t.rt2, [512, 512, 1023, 3]);
    /// assert_eq!(t.rt3, Rt3Texel::Ldr([1023, 512, 256, 3]));
    /// let h = GBufferTexel::quantize(&GBuffer::pack(Vec3::ONE, 1.0, Vec3::ZERO, 0.5, Vec3::Z,
    ///                                              Vec3::new(0.0, 1.0, 2.0), true), true);
    /// assert_eq!(h.rt3, Rt3Texel::Hdr([0x0000, 0x3C00, 0x4000, 0x3C00]));
    /// ```
    pub fn quantize(g: &GBuffer, hdr: bool) -> GBufferTexel {
        GBufferTexel {
            rt0: unorm4(g.rt0, RGBA8),
            rt1: unorm4(g.rt1, RGBA8),
            rt2: unorm4(g.rt2, RGB10A2),
            rt3: if hdr {
                Rt3Texel::Hdr(f16x4(g.rt3))
            } else {
                Rt3Texel::Ldr(unorm4(g.rt3, RGB10A2))
            },
        }
    }

    /// The values a shader reads from these texels (what the deferred reflection and final
    /// passes see).
    ///
    /// # Panics
    /// When a unorm channel is out of range for its width.
    ///
    /// ```
    /// use glam::Vec4;
    /// use wgsl_variants_shaders::reference::gbuffer::{GBufferTexel, Rt3Texel};
    /// let t = GBufferTexel { rt0: [255, 0, 0, 255], rt1: [0; 4], rt2: [1023, 0, 0, 3],
    ///                        rt3: Rt3Texel::Hdr([0; 4]) };
    /// let g = t.to_gbuffer();
    /// assert_eq!(g.rt0, Vec4::new(1.0, 0.0, 0.0, 1.0));
    /// assert_eq!(g.rt2, Vec4::new(1.0, 0.0, 0.0, 1.0));
    /// ```
    pub fn to_gbuffer(&self) -> GBuffer {
        GBuffer {
            rt0: unorm4_to_vec4(self.rt0, RGBA8),
            rt1: unorm4_to_vec4(self.rt1, RGBA8),
            rt2: unorm4_to_vec4(self.rt2, RGB10A2),
            rt3: self.rt3.to_vec4(),
        }
    }

    /// The surface values this pixel holds (see [`DecodedSurface`]).
    ///
    /// # Panics
    /// When a unorm channel is out of range for its width.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::gbuffer::{GBuffer, GBufferTexel};
    /// let c = Vec3::new(0.25, 1.5, 4.0);
    /// let g = GBuffer::pack(Vec3::splat(0.2), 0.5, Vec3::splat(0.04), 0.8, Vec3::X, c, true);
    /// let s = GBufferTexel::quantize(&g, true).decode();
    /// assert_eq!(s.c, c); // exact in f16
    /// assert!((s.normal - Vec3::X).length() < 2e-3);
    /// assert!((s.smoothness - 0.8).abs() <= 0.5 / 255.0);
    /// ```
    pub fn decode(&self) -> DecodedSurface {
        let g = self.to_gbuffer();
        DecodedSurface {
            diffuse: g.rt0.truncate(),
            occlusion: g.rt0.w,
            specular: g.rt1.truncate(),
            smoothness: g.rt1.w,
            normal: decode_normal(g.rt2.truncate()),
            c: if self.rt3.is_hdr() {
                g.rt3.truncate()
            } else {
                ldr_decode(g.rt3.truncate())
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::quantize::{unorm, unorm_to_f32};

    #[test]
    fn normal_encoding_edges() {
        assert_eq!(
            encode_normal(Vec3::new(f32::NAN, 0.0, 0.0)),
            Vec3::new(0.5, 0.5, 1.0)
        );
        // Tiny and huge normals are normalized like any other (their squared length under- or
        // overflows f32).
        let diagonal = Vec3::splat(1.0 / 3f32.sqrt()) * 0.5 + 0.5;
        assert!(
            (encode_normal(Vec3::splat(1e-30)) - diagonal)
                .abs()
                .max_element()
                < 1e-7
        );
        assert!(
            (encode_normal(Vec3::splat(-3e30)) - (1.0 - diagonal))
                .abs()
                .max_element()
                < 1e-7
        );
        assert_eq!(
            encode_normal(Vec3::new(f32::MAX, 0.0, 0.0)),
            Vec3::new(1.0, 0.5, 0.5)
        );
        assert_eq!(
            encode_normal(Vec3::new(f32::INFINITY, 0.0, 0.0)),
            Vec3::new(0.5, 0.5, 1.0)
        );
        assert_eq!(
            encode_normal(Vec3::new(3.0, 0.0, 4.0)),
            Vec3::new(0.8, 0.5, 0.9)
        );
        assert_eq!(decode_normal(Vec3::splat(0.5)), Vec3::Z);
        assert_eq!(decode_normal(Vec3::new(0.0, 0.5, 0.5)), Vec3::NEG_X);
    }

    #[test]
    fn ten_bit_normals_round_trip_within_a_step() {
        // Directions over the sphere; the 10-bit quantization error of a unit normal is at most
        // about √3 · 1/1023 in angle.
        for i in 0..40 {
            for j in 0..80 {
                let theta = std::f32::consts::PI * (i as f32 + 0.5) / 40.0;
                let phi = std::f32::consts::TAU * j as f32 / 80.0;
                let n = Vec3::new(
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                );
                let e = encode_normal(n);
                let q = e.to_array().map(|x| unorm_to_f32(unorm(x, 10), 10));
                let back = decode_normal(Vec3::from_array(q));
                assert!((back - n).length() < 2e-3, "{n} -> {back}");
                assert!((back.length() - 1.0).abs() < 1e-6);
            }
        }
    }

    #[test]
    fn ldr_texel_round_trip() {
        let diffuse = Vec3::new(0.1, 0.5, 0.9);
        let spec = Vec3::new(0.04, 0.3, 0.7);
        let n = Vec3::new(0.3, -0.4, 0.866).normalize();
        let c = Vec3::new(0.0, 0.7, 3.0);
        let g = GBuffer::pack(diffuse, 0.6, spec, 0.45, n, c, false);
        let t = GBufferTexel::quantize(&g, false);
        assert!(matches!(t.rt3, Rt3Texel::Ldr([1023, _, _, 3])));
        assert_eq!(t.rt2[3], 3);
        let s = t.decode();
        let step8 = 0.5 / 255.0 + 1e-7;
        assert!((s.diffuse - diffuse).abs().max_element() <= step8);
        assert!((s.specular - spec).abs().max_element() <= step8);
        assert!((s.occlusion - 0.6).abs() <= step8);
        assert!((s.smoothness - 0.45).abs() <= step8);
        assert!((s.normal - n).length() < 2e-3);
        // LDR: the 10-bit step of 2^-c is relative, so c comes back within 1/(1023·2^-c·ln 2)/2.
        for i in 0..3 {
            let bound = 0.5 / (1023.0 * (-c[i]).exp2() * std::f32::consts::LN_2) + 1e-6;
            assert!((s.c[i] - c[i]).abs() <= bound, "{} vs {}", s.c[i], c[i]);
        }
    }

    #[test]
    fn hdr_texel_round_trip_and_black_is_white_in_ldr() {
        let c = Vec3::new(0.0, 10.0, 1000.0);
        let g = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ZERO, 0.0, Vec3::Z, c, true);
        assert_eq!(GBufferTexel::quantize(&g, true).decode().c, c);
        let l = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ZERO, 0.0, Vec3::Z, Vec3::ZERO, false);
        let t = GBufferTexel::quantize(&l, false);
        assert_eq!(t.rt3, Rt3Texel::Ldr([1023, 1023, 1023, 3]));
        assert_eq!(t.decode().c, Vec3::ZERO);
        // Bright LDR light saturates to 0, decoding to +inf.
        let b = GBuffer::pack(
            Vec3::ZERO,
            1.0,
            Vec3::ZERO,
            0.0,
            Vec3::Z,
            Vec3::splat(12.0),
            false,
        );
        assert_eq!(GBufferTexel::quantize(&b, false).decode().c, Vec3::INFINITY);
    }

    #[test]
    fn negative_light_stores_white_in_ldr() {
        let g = GBuffer::pack(
            Vec3::ZERO,
            1.0,
            Vec3::ZERO,
            0.0,
            Vec3::Z,
            Vec3::splat(-3.0),
            false,
        );
        assert_eq!(g.rt3, Vec4::ONE);
    }
}
