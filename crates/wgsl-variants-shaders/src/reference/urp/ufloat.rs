//! `Rg11b10Ufloat` (Vulkan `B10G11R11_UFLOAT_PACK32`): URP's emission/GI/lighting target.
//!
//! Two unsigned float layouts, both with a 5-bit exponent (bias 15) and no sign bit:
//!
//! | channel | bits | mantissa | largest finite value |
//! |---|---|---|---|
//! | r, g | 11 | 6 bits | 2^15 · (1 + 63/64) = 65024 |
//! | b | 10 | 5 bits | 2^15 · (1 + 31/32) = 64512 |
//!
//! A value with exponent field `E` and mantissa `M` (of `m` bits) is 0 when `E = M = 0`,
//! `2^-14 · M/2^m` when `E = 0` (subnormal), `2^(E−15) · (1 + M/2^m)` for `0 < E < 31`,
//! +∞ for `E = 31, M = 0` and NaN for `E = 31, M ≠ 0`.
//!
//! Converting an `f32` (Khronos Data Format Specification, "Unsigned 11-bit / 10-bit
//! floating-point numbers", which Vulkan's format conversions follow; the same text is in
//! OpenGL 4.6 §2.3.4.3): finite values round to the closest representable value (an
//! implementation may instead always round toward zero); negative values and −∞ become 0;
//! finite values above the largest finite value become that value (not +∞); +∞ stays +∞;
//! NaN of either sign becomes a positive NaN. Ties are not specified; this module rounds them
//! to even, and [`crate::reference::tolerance::ufloat_within`] accepts one step either way.
//!
//! The packed word holds r in bits 0–10, g in 11–21 and b in 22–31.

use glam::Vec3;

/// One of the two unsigned float layouts of `Rg11b10Ufloat`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UFloat {
    /// 11 bits: 5-bit exponent, 6-bit mantissa (the r and g channels).
    F11,
    /// 10 bits: 5-bit exponent, 5-bit mantissa (the b channel).
    F10,
}

impl UFloat {
    /// Mantissa width in bits: 6 for [`UFloat::F11`], 5 for [`UFloat::F10`].
    pub fn mantissa_bits(self) -> u32 {
        match self {
            UFloat::F11 => 6,
            UFloat::F10 => 5,
        }
    }

    /// The bits of +∞ (exponent field 31, mantissa 0).
    pub fn infinity_bits(self) -> u16 {
        31 << self.mantissa_bits()
    }

    /// The bits of the largest finite value (65024 or 64512).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::ufloat::UFloat;
    /// assert_eq!(UFloat::F11.decode(UFloat::F11.max_finite_bits()), 65024.0);
    /// assert_eq!(UFloat::F10.decode(UFloat::F10.max_finite_bits()), 64512.0);
    /// ```
    pub fn max_finite_bits(self) -> u16 {
        self.infinity_bits() - 1
    }

    /// The bits this layout stores for `x` (see the module documentation for the rules).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::ufloat::UFloat;
    /// assert_eq!(UFloat::F11.encode(1.0), 15 << 6);          // 2^0: E = 15, M = 0
    /// assert_eq!(UFloat::F11.encode(-3.0), 0);              // negative: 0
    /// assert_eq!(UFloat::F11.encode(1e9), 0x7BF);           // clamped to 65024, not +inf
    /// assert_eq!(UFloat::F10.encode(f32::INFINITY), 0x3E0);
    /// assert!(UFloat::F10.decode(UFloat::F10.encode(-f32::NAN)).is_nan());
    /// ```
    pub fn encode(self, x: f32) -> u16 {
        let m = self.mantissa_bits();
        if x.is_nan() {
            // A quiet NaN: exponent all ones, top mantissa bit set.
            return self.infinity_bits() | (1 << (m - 1));
        }
        if x == f32::INFINITY {
            return self.infinity_bits();
        }
        if x <= 0.0 {
            return 0;
        }
        let max = self.decode(self.max_finite_bits());
        if x >= max {
            return self.max_finite_bits();
        }
        let x = f64::from(x);
        let scale = f64::from(1u32 << m);
        // Exponent of x's leading bit, exact: x is a positive finite f32.
        let exp = x.log2().floor() as i32;
        let exp = if 2f64.powi(exp) > x {
            exp - 1
        } else if 2f64.powi(exp + 1) <= x {
            exp + 1
        } else {
            exp
        };
        if exp < -14 {
            // Subnormal: M = x / 2^-14 · 2^m. Scaling by powers of two is exact in f64, so
            // `round_ties_even` is the only rounding. M = 2^m is the smallest normal's bits.
            return (x * 2f64.powi(14) * scale).round_ties_even() as u16;
        }
        let frac = (x / 2f64.powi(exp) - 1.0) * scale; // exact: at most 24 significant bits
        let r = frac.round_ties_even() as u32;
        // A carry out of the mantissa increments the exponent: the bits still add up.
        ((((exp + 15) as u32) << m) + r) as u16
    }

    /// The value of the bits `h` (the low 11 or 10 bits; higher bits are ignored).
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::ufloat::UFloat;
    /// assert_eq!(UFloat::F11.decode(1), 2f32.powi(-20));    // smallest subnormal: 2^-14 · 1/64
    /// assert_eq!(UFloat::F10.decode(0x3E0), f32::INFINITY);
    /// ```
    pub fn decode(self, h: u16) -> f32 {
        let m = self.mantissa_bits();
        let h = u32::from(h) & ((1 << (m + 5)) - 1);
        let e = (h >> m) as i32;
        let man = f64::from(h & ((1 << m) - 1));
        let scale = f64::from(1u32 << m);
        match e {
            0 => (2f64.powi(-14) * man / scale) as f32,
            31 if man == 0.0 => f32::INFINITY,
            31 => f32::NAN,
            _ => (2f64.powi(e - 15) * (1.0 + man / scale)) as f32,
        }
    }

    /// `x` stored and read back: the value the target holds after `x` is written.
    ///
    /// ```
    /// use wgsl_variants_shaders::reference::urp::ufloat::UFloat;
    /// assert_eq!(UFloat::F10.round(0.1), 0.099609375);
    /// ```
    pub fn round(self, x: f32) -> f32 {
        self.decode(self.encode(x))
    }
}

/// The packed `Rg11b10Ufloat` word for a colour (r, g 11-bit; b 10-bit).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::urp::ufloat::{pack_rg11b10, unpack_rg11b10};
/// let w = pack_rg11b10(Vec3::new(1.0, 2.0, 0.5));
/// assert_eq!(w, (15 << 6) | ((16 << 6) << 11) | ((14 << 5) << 22));
/// assert_eq!(unpack_rg11b10(w), Vec3::new(1.0, 2.0, 0.5));
/// ```
pub fn pack_rg11b10(c: Vec3) -> u32 {
    u32::from(UFloat::F11.encode(c.x))
        | (u32::from(UFloat::F11.encode(c.y)) << 11)
        | (u32::from(UFloat::F10.encode(c.z)) << 22)
}

/// The three channel bit fields of a packed word: `[r, g, b]`.
///
/// ```
/// use wgsl_variants_shaders::reference::urp::ufloat::split_rg11b10;
/// assert_eq!(split_rg11b10(u32::MAX), [0x7FF, 0x7FF, 0x3FF]);
/// ```
pub fn split_rg11b10(word: u32) -> [u16; 3] {
    [
        (word & 0x7ff) as u16,
        ((word >> 11) & 0x7ff) as u16,
        (word >> 22) as u16,
    ]
}

/// The colour a packed `Rg11b10Ufloat` word holds; the inverse of [`pack_rg11b10`] on
/// representable values. Read the word from texture bytes with `u32::from_le_bytes`.
pub fn unpack_rg11b10(word: u32) -> Vec3 {
    let [r, g, b] = split_rg11b10(word);
    Vec3::new(
        UFloat::F11.decode(r),
        UFloat::F11.decode(g),
        UFloat::F10.decode(b),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_computed_on_paper() {
        // 1.0 = 2^0 · (1 + 0): E = 0 + 15 = 15, M = 0 → 15 << 6 = 960 = 0x3C0.
        assert_eq!(UFloat::F11.encode(1.0), 0x3C0);
        // 0.1 in F10: 0.1 = 2^-4 · 1.6; mantissa 0.6 · 32 = 19.2 → 19;
        // E = -4 + 15 = 11 → (11 << 5) | 19 = 371; value 2^-4 · (1 + 19/32) = 0.099609375.
        assert_eq!(UFloat::F10.encode(0.1), 371);
        assert_eq!(UFloat::F10.decode(371), 0.099_609_375);
        // 0.1 in F11: mantissa 0.6 · 64 = 38.4 → 38; (11 << 6) | 38 = 742;
        // value 2^-4 · (1 + 38/64) = 0.099609375 as well (38/64 = 19/32).
        assert_eq!(UFloat::F11.encode(0.1), 742);
        // 3.0 = 2^1 · 1.5: E = 16, M = 0.5 · 64 = 32 → 1024 + 32 = 1056.
        assert_eq!(UFloat::F11.encode(3.0), 1056);
        // A tie in F11: 1 + 1/128 lies halfway between 1 (M = 0) and 1 + 1/64 (M = 1):
        // to even → M = 0. And 1 + 3/128 lies between M = 1 and M = 2: to even → M = 2.
        assert_eq!(UFloat::F11.encode(1.0 + 1.0 / 128.0), 0x3C0);
        assert_eq!(UFloat::F11.encode(1.0 + 3.0 / 128.0), 0x3C2);
        // A tie in F10: 1 + 1/64 is halfway between M = 0 and M = 1 (steps of 1/32) → 0.
        assert_eq!(UFloat::F10.encode(1.0 + 1.0 / 64.0), 0x3C0 >> 1);
        // Largest subnormal of F11: 2^-14 · 63/64; smallest normal 2^-14 = E 1, M 0 = 64.
        assert_eq!(UFloat::F11.encode(2f32.powi(-14) * 63.0 / 64.0), 63);
        assert_eq!(UFloat::F11.encode(2f32.powi(-14)), 64);
        // Half the smallest subnormal (2^-21) is a tie between 0 and 1 → 0 (even);
        // slightly more rounds up to 1.
        assert_eq!(UFloat::F11.encode(2f32.powi(-21)), 0);
        assert_eq!(UFloat::F11.encode(2f32.powi(-21) * 1.01), 1);
        // Largest finite: 2^15 · (1 + 63/64) = 32768 + 32256 = 65024 = (30 << 6) | 63 = 0x7BF.
        assert_eq!(UFloat::F11.encode(65024.0), 0x7BF);
        assert_eq!(UFloat::F11.encode(65535.0), 0x7BF); // beyond: clamped, not +inf
        assert_eq!(UFloat::F11.encode(f32::MAX), 0x7BF);
        // F10: 2^15 · (1 + 31/32) = 64512 = (30 << 5) | 31 = 0x3DF.
        assert_eq!(UFloat::F10.encode(70000.0), 0x3DF);
        assert_eq!(UFloat::F10.decode(0x3DF), 64512.0);
    }

    #[test]
    fn special_values() {
        for f in [UFloat::F11, UFloat::F10] {
            assert_eq!(f.encode(0.0), 0);
            assert_eq!(f.encode(-0.0), 0);
            assert_eq!(f.encode(-1e-30), 0);
            assert_eq!(f.encode(f32::NEG_INFINITY), 0);
            assert_eq!(f.encode(f32::INFINITY), f.infinity_bits());
            assert!(f.decode(f.encode(f32::NAN)).is_nan());
            assert!(f.decode(f.encode(-f32::NAN)).is_nan());
            assert_eq!(f.encode(f32::MIN_POSITIVE), 0);
        }
    }

    #[test]
    fn every_code_round_trips_and_midpoints_round_to_even() {
        for f in [UFloat::F11, UFloat::F10] {
            for h in 0..f.max_finite_bits() {
                let a = f.decode(h);
                assert_eq!(f.encode(a), h, "{f:?} {h:#x}");
                let b = f.decode(h + 1);
                let mid = ((f64::from(a) + f64::from(b)) / 2.0) as f32; // exact
                let even = if h & 1 == 0 { h } else { h + 1 };
                assert_eq!(f.encode(mid), even, "{f:?} mid of {h:#x}");
                assert_eq!(f.encode(f32::from_bits(mid.to_bits() - 1)), h);
                assert_eq!(f.encode(f32::from_bits(mid.to_bits() + 1)), h + 1);
            }
        }
    }
}
