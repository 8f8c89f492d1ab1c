//! URP's material-flags byte, stored in GBuffer0's alpha (URP's `UnityGBuffer.hlsl`,
//! `PackMaterialFlags` / `UnpackMaterialFlags`; the bit meanings are in URP's manual,
//! "Deferred Rendering Path", G-buffer layout).
//!
//! | bit | flag | set by |
//! |---|---|---|
//! | 0 | ReceiveShadowsOff | `_RECEIVE_SHADOWS_OFF` |
//! | 1 | SpecularHighlightsOff | `_SPECULARHIGHLIGHTS_OFF` |
//! | 2 | SubtractiveMixedLighting | `LIGHTMAP_ON` and `_MIXED_LIGHTING_SUBTRACTIVE` |
//! | 3 | SpecularSetup | `_SPECULAR_SETUP` |
//! | 4–7 | reserved | never |
//!
//! The shader writes `flags / 255` into the alpha of an `Rgba8UnormSrgb` target (alpha is not
//! sRGB-encoded), so the stored byte is the flags byte itself; a shader reads it back as
//! `floor(a · 255 + 0.5)`.

/// Bit 0: the pixel receives no dynamic shadows.
pub const RECEIVE_SHADOWS_OFF: u8 = 1;
/// Bit 1: the pixel receives no specular highlights.
pub const SPECULAR_HIGHLIGHTS_OFF: u8 = 2;
/// Bit 2: the pixel uses subtractive mixed lighting.
pub const SUBTRACTIVE_MIXED_LIGHTING: u8 = 4;
/// Bit 3: the material uses the specular workflow.
pub const SPECULAR_SETUP: u8 = 8;
/// Bits 4–7, reserved by URP: a G-buffer with any of them set was not written by URP's layout.
pub const RESERVED: u8 = 0xf0;

/// The flags of one G-buffer texel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MaterialFlags {
    /// Bit 0.
    pub receive_shadows_off: bool,
    /// Bit 1.
    pub specular_highlights_off: bool,
    /// Bit 2.
    pub subtractive_mixed_lighting: bool,
    /// Bit 3.
    pub specular_setup: bool,
}

/// A flags byte that URP's layout cannot hold.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum FlagsError {
    /// One of the reserved bits 4–7 is set.
    #[error(
        "material flags byte {byte:#04x} sets reserved bits {reserved:#04x} (only bits 0-3 are defined)"
    )]
    ReservedBits {
        /// The whole byte as read.
        byte: u8,
        /// The reserved bits that are set.
        reserved: u8,
    },
}

impl MaterialFlags {
    /// The flags byte.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::flags::MaterialFlags;
    /// let f = MaterialFlags { specular_setup: true, receive_shadows_off: true, ..Default::default() };
    /// assert_eq!(f.to_byte(), 0b1001);
    /// ```
    pub fn to_byte(self) -> u8 {
        let bit = |on: bool, bit: u8| if on { bit } else { 0 };
        bit(self.receive_shadows_off, RECEIVE_SHADOWS_OFF)
            | bit(self.specular_highlights_off, SPECULAR_HIGHLIGHTS_OFF)
            | bit(self.subtractive_mixed_lighting, SUBTRACTIVE_MIXED_LIGHTING)
            | bit(self.specular_setup, SPECULAR_SETUP)
    }

    /// The flags of a byte read from GBuffer0's alpha; a byte with reserved bits set is an
    /// error, never masked.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::flags::{FlagsError, MaterialFlags};
    /// assert!(MaterialFlags::from_byte(0b0010).unwrap().specular_highlights_off);
    /// assert_eq!(
    ///     MaterialFlags::from_byte(0x13),
    ///     Err(FlagsError::ReservedBits { byte: 0x13, reserved: 0x10 })
    /// );
    /// ```
    pub fn from_byte(byte: u8) -> Result<MaterialFlags, FlagsError> {
        let reserved = byte & RESERVED;
        if reserved != 0 {
            return Err(FlagsError::ReservedBits { byte, reserved });
        }
        Ok(MaterialFlags {
            receive_shadows_off: byte & RECEIVE_SHADOWS_OFF != 0,
            specular_highlights_off: byte & SPECULAR_HIGHLIGHTS_OFF != 0,
            subtractive_mixed_lighting: byte & SUBTRACTIVE_MIXED_LIGHTING != 0,
            specular_setup: byte & SPECULAR_SETUP != 0,
        })
    }

    /// The alpha value the shader writes: `byte / 255` (URP's `PackMaterialFlags`).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::flags::MaterialFlags;
    /// let f = MaterialFlags { specular_setup: true, ..Default::default() };
    /// assert_eq!(f.pack(), 8.0 / 255.0);
    /// ```
    pub fn pack(self) -> f32 {
        f32::from(self.to_byte()) / 255.0
    }
}

/// The byte a shader reads back from an alpha value `a`: `floor(a · 255 + 0.5)`, saturated to
/// 0..=255 (URP's `UnpackMaterialFlags`; an unorm alpha is in [0, 1], so the saturation only
/// matters for hand-made inputs; NaN gives 0).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::flags::unpack_flags_byte;
/// assert_eq!(unpack_flags_byte(8.0 / 255.0), 8);
/// assert_eq!(unpack_flags_byte(8.4 / 255.0), 8);
/// assert_eq!(unpack_flags_byte(1.0), 255);
/// ```
pub fn unpack_flags_byte(a: f32) -> u8 {
    (f64::from(a) * 255.0 + 0.5).floor().clamp(0.0, 255.0) as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_valid_byte_round_trips_and_every_reserved_byte_is_refused() {
        for byte in 0..=255u8 {
            match MaterialFlags::from_byte(byte) {
                Ok(f) => {
                    assert!(byte < 16);
                    assert_eq!(f.to_byte(), byte);
                    // Written as byte/255 into an 8-bit unorm alpha, read back as the same byte.
                    assert_eq!(unpack_flags_byte(f.pack()), byte);
                }
                Err(FlagsError::ReservedBits { reserved, .. }) => {
                    assert!(byte >= 16);
                    assert_eq!(reserved, byte & 0xf0);
                }
            }
        }
    }

    #[test]
    fn values_computed_on_paper() {
        // SpecularHighlightsOff | SpecularSetup = 2 + 8 = 10; stored 10/255 = 0.0392157;
        // read 0.0392157 · 255 + 0.5 = 10.5 → floor 10.
        let f = MaterialFlags::from_byte(10).unwrap();
        assert!(f.specular_highlights_off && f.specular_setup);
        assert!(!f.receive_shadows_off && !f.subtractive_mixed_lighting);
        assert_eq!(unpack_flags_byte(10.0 / 255.0), 10);
        let err = MaterialFlags::from_byte(0x80).unwrap_err();
        assert!(err.to_string().contains("0x80"), "{err}");
    }
}
