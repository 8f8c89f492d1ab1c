//! Reflection probes: box projection, mip selection, RGBM decoding, the forward two-probe
//! blend and the deferred per-pixel probes (docs/shading.md §6, Reflection probes).
//!
//! ```
//! use glam::Vec3;
//! use wgsl_variants_shaders::reference::probe::{falloff, Probe};
//! let p = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
//! assert_eq!(falloff(Vec3::new(1.5, 0.0, 0.0), &p), 0.5);
//! ```

use glam::{Vec3, Vec4};

use super::cube::CubeFaces;

/// A reflection probe's parameters (Unity's `unity_SpecCube0_*` / `_SpecCube0_*` uniforms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probe {
    /// Probe centre `o` (`unity_SpecCube0_ProbePosition.xyz`), used by box projection.
    pub position: Vec3,
    /// Minimum corner of the probe's box (`unity_SpecCube0_BoxMin.xyz`).
    pub box_min: Vec3,
    /// Maximum corner of the probe's box (`unity_SpecCube0_BoxMax.xyz`).
    pub box_max: Vec3,
    /// Decode instructions `(x, y, w)` for [`rgbm_decode`] (`unity_SpecCube0_HDR.xyw`);
    /// `(1, 1, 0)` decodes to the texel's rgb unchanged.
    pub hdr: Vec3,
    /// Whether box projection is enabled (`unity_SpecCube0_ProbePosition.w > 0`).
    pub box_projection: bool,
    /// Blend distance `b` (deferred only): the box used for box projection is grown by `b`,
    /// and the weight falls from 1 to 0 over `b` outside the box. Unity's default is 1.
    pub blend_distance: f32,
    /// Importance (deferred only): a probe with higher importance always draws later, on top.
    pub importance: i32,
    /// Forward blend weight `t` (Unity keeps it in `unity_SpecCube0_BoxMin.w`); only probe 0's
    /// is used, see [`forward_blend`].
    pub forward_weight: f32,
}

/// Probe parameters that make the deferred pass's math undefined (a box with no volume, where
/// the box projection divides by zero-length spans; NaN; a negative blend distance).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ProbeError {
    /// A parameter holds NaN or an infinity.
    #[error("probe {what} is not finite: {value}")]
    NonFinite {
        /// The parameter.
        what: &'static str,
        /// Its value, printed.
        value: String,
    },
    /// `box_max` not greater than `box_min` on some axis.
    #[error(
        "probe box {box_min} .. {box_max} has no volume (box_max must exceed box_min on every axis)"
    )]
    EmptyBox {
        /// The minimum corner given.
        box_min: Vec3,
        /// The maximum corner given.
        box_max: Vec3,
    },
    /// A blend distance below 0.
    #[error("probe blend distance {0} must be ≥ 0")]
    BlendDistance(f32),
}

impl Probe {
    /// Checks that the deferred pass's math is defined for this probe: finite values, a box
    /// with volume, a blend distance ≥ 0.
    ///
    /// # Errors
    /// The first [`ProbeError`] found.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::probe::{Probe, ProbeError};
    /// assert!(Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0)).check().is_ok());
    /// let flat = Probe::new(Vec3::ZERO, Vec3::new(-1.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 1.0));
    /// assert!(matches!(flat.check(), Err(ProbeError::EmptyBox { .. })));
    /// let nan = Probe::new(Vec3::NAN, Vec3::splat(-1.0), Vec3::splat(1.0));
    /// assert!(matches!(nan.check(), Err(ProbeError::NonFinite { what: "position", .. })));
    /// ```
    pub fn check(&self) -> Result<(), ProbeError> {
        let finite = |what: &'static str, v: Vec3| {
            if v.is_finite() {
                Ok(())
            } else {
                Err(ProbeError::NonFinite {
                    what,
                    value: v.to_string(),
                })
            }
        };
        finite("position", self.position)?;
        finite("box_min", self.box_min)?;
        finite("box_max", self.box_max)?;
        finite("hdr", self.hdr)?;
        if !self.blend_distance.is_finite() {
            return Err(ProbeError::NonFinite {
                what: "blend distance",
                value: self.blend_distance.to_string(),
            });
        }
        if self.blend_distance < 0.0 {
            return Err(ProbeError::BlendDistance(self.blend_distance));
        }
        if !self.box_max.cmpgt(self.box_min).all() {
            return Err(ProbeError::EmptyBox {
                box_min: self.box_min,
                box_max: self.box_max,
            });
        }
        Ok(())
    }

    /// A probe with the given centre and box, no box projection, identity decode
    /// (`hdr = (1, 1, 0)`), blend distance 1, importance 1 and forward weight 1.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::probe::Probe;
    /// let p = Probe::new(Vec3::ZERO, Vec3::splat(-2.0), Vec3::splat(2.0));
    /// assert_eq!(p.blend_distance, 1.0);
    /// assert!(!p.box_projection);
    /// ```
    pub fn new(position: Vec3, box_min: Vec3, box_max: Vec3) -> Probe {
        Probe {
            position,
            box_min,
            box_max,
            hdr: Vec3::new(1.0, 1.0, 0.0),
            box_projection: false,
            blend_distance: 1.0,
            importance: 1,
            forward_weight: 1.0,
        }
    }

    /// The volume of the (un-grown) box, `Π (box_max − box_min)`, which orders deferred probes.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::probe::Probe;
    /// assert_eq!(Probe::new(Vec3::ZERO, Vec3::ZERO, Vec3::new(1.0, 2.0, 3.0)).volume(), 6.0);
    /// ```
    pub fn volume(&self) -> f32 {
        (self.box_max - self.box_min).element_product()
    }

    /// The probe with its box grown by the blend distance: `[box_min − b, box_max + b]`
    /// (what the deferred pass box-projects against).
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::probe::Probe;
    /// let g = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0)).grown();
    /// assert_eq!((g.box_min, g.box_max), (Vec3::splat(-2.0), Vec3::splat(2.0)));
    /// ```
    pub fn grown(&self) -> Probe {
        Probe {
            box_min: self.box_min - self.blend_distance,
            box_max: self.box_max + self.blend_distance,
            ..*self
        }
    }
}

/// The direction to sample the probe's cube map for reflection direction `r` at world position
/// `p`.
///
/// Without box projection this is `r` unchanged. With it, `d = normalize(r)`; per axis
/// `t = (box_max − p)/d` where `d > 0`, `(box_min − p)/d` where `d < 0`, and `+∞` where
/// `d == 0` (±0: that axis is ignored); `fa = min(t)`; the result is `(p − o) + d · fa`, the
/// point where the ray from `p` leaves the box, seen from the probe centre `o`.
/// `r` must be non-zero (a zero `r` gives NaN, as on the GPU).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::{box_project, Probe};
/// let mut probe = Probe::new(Vec3::new(0.0, 0.0, 0.5), Vec3::splat(-1.0), Vec3::splat(1.0));
/// let r = Vec3::new(1.0, 1.0, 0.0);
/// assert_eq!(box_project(r, Vec3::ZERO, &probe), r); // off: unchanged
/// probe.box_projection = true;
/// // From the origin along +X (the Y and Z components are 0 and ignored) the box ends at x = 1.
/// assert_eq!(box_project(Vec3::new(4.0, 0.0, 0.0), Vec3::ZERO, &probe), Vec3::new(1.0, 0.0, -0.5));
/// // From (0.5, 0, 0) along (1, 1, 0)/√2: x reaches 1 first, after 0.5·√2.
/// let d = box_project(r, Vec3::new(0.5, 0.0, 0.0), &probe);
/// assert!((d - Vec3::new(1.0, 0.5, -0.5)).length() < 1e-6);
/// ```
pub fn box_project(r: Vec3, p: Vec3, probe: &Probe) -> Vec3 {
    if !probe.box_projection {
        return r;
    }
    let d = r.normalize();
    let axis = |i: usize| {
        if d[i] > 0.0 {
            (probe.box_max[i] - p[i]) / d[i]
        } else if d[i] < 0.0 {
            (probe.box_min[i] - p[i]) / d[i]
        } else if d[i] == 0.0 {
            f32::INFINITY
        } else {
            f32::NAN
        }
    };
    let fa = axis(0).min(axis(1)).min(axis(2));
    let fa = if d.is_nan() { f32::NAN } else { fa };
    (p - probe.position) + d * fa
}

/// [`box_project`] against the box grown by the blend distance, `[box_min − b, box_max + b]`
/// (the deferred per-pixel probe).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::{box_project_grown, Probe};
/// let mut probe = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// probe.box_projection = true;
/// probe.blend_distance = 0.5;
/// assert_eq!(box_project_grown(Vec3::NEG_Y, Vec3::ZERO, &probe), Vec3::new(0.0, -1.5, 0.0));
/// ```
pub fn box_project_grown(r: Vec3, p: Vec3, probe: &Probe) -> Vec3 {
    box_project(r, p, &probe.grown())
}

/// The cube-map mip level for a smoothness: `pr · (1.7 − 0.7 · pr) · 6` with `pr = 1 − s`
/// (0 for a mirror, 6 for smoothness 0). Smoothness is used as given, not clamped.
///
/// ```
/// use wgsl_variants_shaders::reference::probe::mip_from_smoothness;
/// assert_eq!(mip_from_smoothness(1.0), 0.0);
/// assert_eq!(mip_from_smoothness(0.0), 6.0);
/// assert!((mip_from_smoothness(0.5) - 4.05).abs() < 1e-6);
/// ```
pub fn mip_from_smoothness(smoothness: f32) -> f32 {
    let pr = 1.0 - smoothness;
    pr * (1.7 - 0.7 * pr) * 6.0
}

/// Decodes a probe texel: `texel.rgb · (hdr.x · α^hdr.y)` with `α = hdr.w · (texel.a − 1) + 1`
/// (`hdr = (x, y, w)`: with `w = 0` the alpha is ignored; `(1, 1, 0)` is the identity).
/// `α^y` is `f32::powf` (α = 0 with y > 0 gives 0).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::probe::rgbm_decode;
/// let texel = Vec4::new(0.5, 0.25, 1.0, 0.5);
/// assert_eq!(rgbm_decode(texel, Vec3::new(1.0, 1.0, 0.0)), Vec3::new(0.5, 0.25, 1.0));
/// // RGBM with range 5 (x = 5, y = 1, w = 1): rgb · 5 · a.
/// assert_eq!(rgbm_decode(texel, Vec3::new(5.0, 1.0, 1.0)), Vec3::new(1.25, 0.625, 2.5));
/// // Gamma-space RGBM (y = 2.2): rgb · x · a^2.2.
/// let v = rgbm_decode(Vec4::new(1.0, 1.0, 1.0, 0.5), Vec3::new(2.0, 2.2, 1.0));
/// assert!((v.x - 2.0 * 0.5f32.powf(2.2)).abs() < 1e-6);
/// ```
pub fn rgbm_decode(texel: Vec4, hdr: Vec3) -> Vec3 {
    let alpha = hdr.z * (texel.w - 1.0) + 1.0;
    texel.truncate() * (hdr.x * alpha.powf(hdr.y))
}

/// The decoded colour of a probe's cube map in direction `dir` at mip level `mip`:
/// `rgbm_decode(sample(cube, dir, mip), probe.hdr)`. The test cubes are the same on every mip,
/// so `mip` does not change the result; it is taken to keep the contract's signature.
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::cube::CubeFaces;
/// use wgsl_variants_shaders::reference::probe::{sample_probe, Probe};
/// let mut probe = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// probe.hdr = Vec3::new(2.0, 1.0, 0.0);
/// let cube = CubeFaces::uniform(Vec4::new(0.25, 0.5, 1.0, 1.0));
/// assert_eq!(sample_probe(&probe, &cube, Vec3::X, 3.0), Vec3::new(0.5, 1.0, 2.0));
/// ```
pub fn sample_probe(probe: &Probe, cube: &CubeFaces, dir: Vec3, mip: f32) -> Vec3 {
    let _ = mip; // uniform faces: every mip level holds the same colour
    rgbm_decode(cube.sample(dir), probe.hdr)
}

/// `mix(a, b, t) = a · (1 − t) + b · t`, WGSL's `mix` (the form both sides use).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::mix;
/// assert_eq!(mix(Vec3::ZERO, Vec3::splat(2.0), 0.25), Vec3::splat(0.5));
/// ```
pub fn mix(a: Vec3, b: Vec3, t: f32) -> Vec3 {
    a * (1.0 - t) + b * t
}

/// The forward two-probe blend with probe 0's weight `t`: `e0` when `t ≥ 0.99999` (probe 1 is
/// not sampled then), else `mix(e1, e0, t)` = `t · e0 + (1 − t) · e1`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::forward_blend;
/// let (e0, e1) = (Vec3::ONE, Vec3::new(3.0, f32::NAN, 0.0));
/// assert_eq!(forward_blend(e0, e1, 1.0), e0);            // e1 is ignored, even NaN
/// assert_eq!(forward_blend(e0, e1, 0.99999), e0);
/// let m = forward_blend(e0, Vec3::splat(3.0), 0.25);
/// assert_eq!(m, Vec3::splat(2.5));
/// ```
pub fn forward_blend(e0: Vec3, e1: Vec3, t: f32) -> Vec3 {
    if t >= 0.99999 { e0 } else { mix(e1, e0, t) }
}

/// A deferred probe's weight at world position `p`: with `dist = max(p − box_max, box_min − p,
/// 0)` per axis (distance outside the un-grown box) and `b` the blend distance,
/// `saturate(1 − length(dist) / b)`; with `b == 0`, 1 inside or on the box and 0 outside.
/// (A negative `b` makes the weight 1 everywhere; don't use one.)
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::{falloff, Probe};
/// let mut p = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// assert_eq!(falloff(Vec3::ZERO, &p), 1.0);
/// assert_eq!(falloff(Vec3::new(1.5, 0.0, 0.0), &p), 0.5);
/// assert!((falloff(Vec3::new(1.5, 1.5, 0.0), &p) - 0.29289).abs() < 1e-5);
/// assert_eq!(falloff(Vec3::new(2.0, 0.0, 0.0), &p), 0.0);
/// p.blend_distance = 0.0;
/// assert_eq!(falloff(Vec3::new(1.0, -1.0, 0.0), &p), 1.0); // on the box
/// assert_eq!(falloff(Vec3::new(1.001, 0.0, 0.0), &p), 0.0);
/// ```
pub fn falloff(p: Vec3, probe: &Probe) -> f32 {
    let dist = (p - probe.box_max).max(probe.box_min - p).max(Vec3::ZERO);
    let b = probe.blend_distance;
    if b == 0.0 {
        return if dist == Vec3::ZERO { 1.0 } else { 0.0 };
    }
    (1.0 - dist.length() / b).clamp(0.0, 1.0)
}

/// The order in which the deferred pass draws probes, as indices into `probes`: ascending
/// importance (higher importance draws later, on top), within equal importance larger box
/// volume first ([`Probe::volume`] of the un-grown box), and equal keys in the given order
/// (a stable sort).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::{draw_order, Probe};
/// let small = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
/// let big = Probe::new(Vec3::ZERO, Vec3::splat(-5.0), Vec3::splat(5.0));
/// assert_eq!(draw_order(&[small, big]), vec![1, 0]);
/// let important = Probe { importance: 2, ..small };
/// assert_eq!(draw_order(&[important, big, small]), vec![1, 2, 0]);
/// assert_eq!(draw_order(&[small, small]), vec![0, 1]);
/// ```
pub fn draw_order(probes: &[Probe]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..probes.len()).collect();
    order.sort_by(|&a, &b| {
        let (pa, pb) = (&probes[a], &probes[b]);
        pa.importance
            .cmp(&pb.importance)
            .then_with(|| pb.volume().total_cmp(&pa.volume()))
    });
    order
}

/// The deferred reflection buffer after drawing `samples` over `previous`, in draw order: each
/// `(rgb, falloff)` blends SrcAlpha / OneMinusSrcAlpha, `result = mix(result, rgb, falloff)`.
/// Computed in `f32`; see [`composite_f16`] for the `Rgba16Float` buffer's rounding.
/// The buffer starts cleared to 0: pass `Vec3::ZERO` as `previous` for the first probe.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::composite;
/// let r = composite(Vec3::ZERO, &[(Vec3::splat(2.0), 1.0), (Vec3::splat(4.0), 0.25)]);
/// assert_eq!(r, Vec3::splat(2.5));
/// ```
pub fn composite(previous: Vec3, samples: &[(Vec3, f32)]) -> Vec3 {
    samples
        .iter()
        .fold(previous, |acc, &(rgb, a)| mix(acc, rgb, a))
}

/// [`composite`] with the result rounded to half float after every probe, as the
/// `Rgba16Float` reflection buffer holds it between draws (`previous` is rounded too).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::probe::composite_f16;
/// let r = composite_f16(Vec3::ZERO, &[(Vec3::splat(0.1), 1.0)]);
/// assert_eq!(r, Vec3::splat(0.099975586));
/// ```
pub fn composite_f16(previous: Vec3, samples: &[(Vec3, f32)]) -> Vec3 {
    use super::quantize::round_f16_vec3;
    samples
        .iter()
        .fold(round_f16_vec3(previous), |acc, &(rgb, a)| {
            round_f16_vec3(mix(acc, rgb, a))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Probe {
        Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0))
    }

    #[test]
    fn falloff_reference_values() {
        let p = unit_box();
        assert_eq!(falloff(Vec3::ZERO, &p), 1.0);
        assert_eq!(falloff(Vec3::new(1.5, 0.0, 0.0), &p), 0.5);
        let f = falloff(Vec3::new(1.5, 1.5, 0.0), &p);
        assert!((f - (1.0 - 0.5f32.hypot(0.5))).abs() < 1e-7 && (f - 0.2929).abs() < 1e-4);
        assert_eq!(falloff(Vec3::new(2.0, 0.0, 0.0), &p), 0.0);
        assert_eq!(falloff(Vec3::new(-9.0, 0.0, 0.0), &p), 0.0);
        assert_eq!(falloff(Vec3::new(1.0, 1.0, 1.0), &p), 1.0); // on the corner
        assert_eq!(falloff(Vec3::new(0.0, -1.25, 0.0), &p), 0.75);
        // Larger blend distance.
        let wide = Probe {
            blend_distance: 2.0,
            ..p
        };
        assert_eq!(falloff(Vec3::new(0.0, 0.0, 2.0), &wide), 0.5);
    }

    #[test]
    fn falloff_with_zero_blend_distance() {
        let p = Probe {
            blend_distance: 0.0,
            ..unit_box()
        };
        assert_eq!(falloff(Vec3::ZERO, &p), 1.0);
        assert_eq!(falloff(Vec3::splat(1.0), &p), 1.0);
        assert_eq!(falloff(Vec3::splat(-1.0), &p), 1.0);
        assert_eq!(falloff(Vec3::new(0.0, 0.0, 1.0 + f32::EPSILON), &p), 0.0);
        assert_eq!(falloff(Vec3::new(5.0, 0.0, 0.0), &p), 0.0);
    }

    #[test]
    fn box_projection_hand_computed() {
        let mut p = Probe::new(
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(-1.0, -2.0, -3.0),
            Vec3::new(1.0, 2.0, 3.0),
        );
        p.box_projection = true;
        // From the origin along −Z: hits z = −3; relative to o = (0.5, 0, 0).
        assert_eq!(
            box_project(Vec3::new(0.0, 0.0, -2.0), Vec3::ZERO, &p),
            Vec3::new(-0.5, 0.0, -3.0)
        );
        // From (0, 1, 0) along (0, 1, 1)/√2: y reaches 2 after √2 (z would need 3√2).
        let d = box_project(Vec3::new(0.0, 1.0, 1.0), Vec3::new(0.0, 1.0, 0.0), &p);
        assert!((d - Vec3::new(-0.5, 2.0, 1.0)).length() < 1e-6, "{d}");
        // From (0.5, 0, 0) along (−1, −1, −1)/√3: x reaches −1 after 1.5√3, at y = z = −1.5.
        let d = box_project(Vec3::splat(-1.0), Vec3::new(0.5, 0.0, 0.0), &p);
        assert!((d - Vec3::new(-1.5, -1.5, -1.5)).length() < 1e-5, "{d}");
        // -0 components are ignored like +0.
        assert_eq!(
            box_project(Vec3::new(-0.0, 3.0, -0.0), Vec3::ZERO, &p),
            Vec3::new(-0.5, 2.0, 0.0)
        );
        // Off: r untouched, not even normalized.
        p.box_projection = false;
        assert_eq!(
            box_project(Vec3::splat(-3.0), Vec3::ZERO, &p),
            Vec3::splat(-3.0)
        );
    }

    #[test]
    fn box_projection_grown_and_degenerate() {
        let mut p = unit_box();
        p.box_projection = true;
        p.blend_distance = 1.0;
        assert_eq!(
            box_project_grown(Vec3::X, Vec3::ZERO, &p),
            Vec3::new(2.0, 0.0, 0.0)
        );
        assert_eq!(
            box_project(Vec3::X, Vec3::ZERO, &p),
            Vec3::new(1.0, 0.0, 0.0)
        );
        assert!(box_project(Vec3::ZERO, Vec3::ZERO, &p).is_nan());
    }

    #[test]
    fn mip_levels() {
        assert_eq!(mip_from_smoothness(0.0), 6.0);
        assert_eq!(mip_from_smoothness(0.5), 0.5 * (1.7 - 0.35) * 6.0);
        assert_eq!(mip_from_smoothness(1.0), 0.0);
        // Monotonic in between.
        let mut last = f32::INFINITY;
        for i in 0..=100 {
            let m = mip_from_smoothness(i as f32 / 100.0);
            assert!(m <= last);
            last = m;
        }
    }

    #[test]
    fn forward_blend_threshold() {
        let e0 = Vec3::splat(1.0);
        let e1 = Vec3::splat(0.0);
        assert_eq!(forward_blend(e0, e1, 0.0), e1);
        assert_eq!(forward_blend(e0, e1, 0.5), Vec3::splat(0.5));
        assert_eq!(forward_blend(e0, Vec3::splat(f32::NAN), 0.999995), e0);
        assert!(forward_blend(e0, Vec3::splat(f32::NAN), 0.9999).is_nan());
    }

    #[test]
    fn draw_order_rules() {
        let a = unit_box(); // volume 8
        let b = Probe::new(Vec3::ZERO, Vec3::ZERO, Vec3::splat(3.0)); // 27
        let c = Probe::new(Vec3::ZERO, Vec3::ZERO, Vec3::splat(1.0)); // 1
        assert_eq!(draw_order(&[a, b, c]), vec![1, 0, 2]);
        // Importance beats volume.
        let c2 = Probe { importance: 5, ..c };
        let a2 = Probe { importance: 0, ..a };
        assert_eq!(draw_order(&[c2, a, b]), vec![2, 1, 0]);
        assert_eq!(draw_order(&[c2, a2, b]), vec![1, 2, 0]);
        // Ties are stable.
        assert_eq!(draw_order(&[a, a, b, a]), vec![2, 0, 1, 3]);
        assert!(draw_order(&[]).is_empty());
    }

    #[test]
    fn composite_blends_in_order() {
        let first = Vec3::new(1.0, 0.0, 0.0);
        let second = Vec3::new(0.0, 1.0, 0.0);
        assert_eq!(composite(Vec3::ZERO, &[(first, 1.0), (second, 0.0)]), first);
        assert_eq!(
            composite(Vec3::ZERO, &[(first, 1.0), (second, 1.0)]),
            second
        );
        assert_eq!(
            composite(Vec3::ZERO, &[(first, 0.5)]),
            Vec3::new(0.5, 0.0, 0.0)
        );
        assert_eq!(
            composite(Vec3::ZERO, &[(first, 1.0), (second, 0.5)]),
            Vec3::new(0.5, 0.5, 0.0)
        );
        assert_eq!(composite(Vec3::ONE, &[]), Vec3::ONE);
        let r = composite_f16(
            Vec3::ZERO,
            &[(Vec3::splat(0.3), 0.7), (Vec3::splat(0.9), 0.2)],
        );
        let exact = composite(
            Vec3::ZERO,
            &[(Vec3::splat(0.3), 0.7), (Vec3::splat(0.9), 0.2)],
        );
        assert!((r - exact).abs().max_element() < 1e-3);
    }

    #[test]
    fn rgbm_rules() {
        let t = Vec4::new(0.2, 0.4, 0.6, 0.25);
        assert_eq!(rgbm_decode(t, Vec3::new(1.0, 1.0, 0.0)), t.truncate());
        assert_eq!(rgbm_decode(t, Vec3::new(4.0, 1.0, 1.0)), t.truncate());
        assert_eq!(rgbm_decode(t, Vec3::new(8.0, 2.0, 1.0)), t.truncate() * 0.5);
        // w = 0.5: α = 0.5·(0.25 − 1) + 1 = 0.625.
        assert_eq!(
            rgbm_decode(t, Vec3::new(2.0, 1.0, 0.5)),
            t.truncate() * 1.25
        );
    }
}
