//! The one place where the tolerances for comparing GPU results with this reference are stated.
//!
//! Every GPU test compares through these functions; none states its own epsilon.
//!
//! | result | tolerance | why |
//! |---|---|---|
//! | unorm targets (8- and 10-bit, and the 2-bit alpha) | [`UNORM_LSB`] = 1 step, measured from either correct rounding | docs/shading.md §1: Vulkan may round a tie either way, and the GPU's `f32` value before quantization may differ from the CPU's by a few ULP, which can move it across a rounding boundary — by one step, never more |
//! | `Rgba16Float` targets | [`F16_ULP`] = 1 f16 step from the round-to-nearest-even of the reference `f32` | docs/shading.md §1: the same argument; 1 f16 ULP is 2^13 f32 ULPs, far above any `f32` arithmetic difference |
//! | `Rg11b10Ufloat` targets (URP's GBuffer3 and forward camera target) | [`UFLOAT_ULP`] = 1 step of each channel's format (2^-6 relative on the 11-bit r, g; 2^-5 on the 10-bit b) from the round-to-nearest-even of the reference (where a shadow tap may flip, from the GPU value clamped into the interval of both outcomes) | the conversion may round toward zero and leaves ties open (Khronos Data Format Specification, unsigned 11/10-bit floats): one step either way |
//! | `Rgba8UnormSrgb` colour channels (URP's GBuffer0) | [`UNORM_LSB`] around the exact sRGB encoding's rounding ([`srgb8_within`]) | the GPU may approximate the transfer function before rounding |
//! | `Rgba8Snorm` channels (URP's GBuffer2 without `_GBUFFER_NORMALS_OCT`) | [`UNORM_LSB`] step from either correct rounding ([`snorm8_within`]) | the unorm argument, on `clamp(x, −1, 1) · 127` |
//! | octahedral normals (URP's GBuffer2 with `_GBUFFER_NORMALS_OCT`) | [`OCT_CODE_STEP`] = 1 on each of the two 12-bit codes ([`oct888_within`]) | the codes are truncated (`trunc(f · 4095.5)`), so a few `f32` ULPs in the normal move a code by one; comparing bytes would turn that into 255 steps of the low byte |
//! | `R32Float` (depth as colour) | [`F32_ULP`] / [`F32_ABS`] ([`f32_within`]) | as the kernels |
//! | `R32Uint` (rendering layers) | exact | an integer copied from a uniform |
//! | `f32` outputs of compute kernels | [`F32_ULP`] = 8 ULP, or [`F32_ABS`] = 2^-20 absolute | see [`F32_ULP`] and [`F32_ABS`] |
//! | forward light (ForwardAdd) against deferred light (G-buffer + lighting pass) | [`gbuffer_light_bound`] per pixel, plus [`F16_ULP`] on each side | the deferred pass reads the surface through the 8- and 10-bit G-buffer; the bound propagates those quantization steps through the direct-light formula |
//! | reflection probes blended SrcAlpha / OneMinusSrcAlpha into the `Rgba16Float` reflection buffer | [`f16_store_error`] + [`f16_blend_error`] | Vulkan may blend a float target at the format's precision: the source, alpha and both products may each be rounded to f16 before the sum is stored |
//! | `universal_lit/DepthOnly` depth (`R32Float`, and the `Depth32Float` buffer the same bits) | [`F32_ULP`] / [`F32_ABS`] from the nearest depth the reference takes over the texel's [`SUBPIXEL_WINDOW`] ([`depth_within`]) | as the shadow casters' row below: depth is affine over the triangle, so the window's range is the centre's depth ± its steps along x and y times the window |
//! | `standard/ShadowCaster` depth (16-bit unorm) and cube distance (f16) | [`UNORM_LSB`] / [`F16_ULP`] from the nearest value the reference takes over the texel's [`SUBPIXEL_WINDOW`] ([`window_offsets`]) | the rasterizer interpolates depth over vertices snapped to its sub-pixel grid; on a surface seen at a grazing angle one sixteenth of a pixel is several depth steps |
//! | the frame (docs/shading.md §12): forward and deferred against the reference and each other | per pixel and channel: [`f16_store_error`] of each partial sum (HDR) or [`unorm_store_error`] per draw (forward LDR) or [`ldr_chain_range`] (deferred LDR), plus [`gbuffer_light_bound`] of every deferred light, around the reference's range over [`SUBPIXEL_WINDOW`] ([`window_range`]) | every draw rounds the target once; the rasterizer evaluates a pixel's attributes on vertices snapped to its sub-pixel grid, i.e. at a point up to [`SUBPIXEL_WINDOW`] from the centre; pixels whose window sees two objects (silhouettes) are left out and counted |
//!
//! ```
//! use wgsl_variants_shaders::reference::tolerance::{unorm_within, f16_within, f32_within};
//! assert!(unorm_within(128, 0.5, 8) && unorm_within(127, 0.5, 8));
//! assert!(f16_within(0x3C01, 1.0));
//! assert!(f32_within(1.0 + 4.0 * f32::EPSILON, 1.0));
//! ```

use glam::{Vec3, Vec4};

use super::brdf::{Brdf, DirectFactors, Dots};
use super::quantize::{f32_to_f16_bits, unorm_max};

/// Whether a depth read back as `f32` is within [`f32_within`] of the nearest value of the
/// reference's range `depth ± window` (`expected` = `(depth, window)`: the depth at the texel's
/// centre and how far it moves over the [`SUBPIXEL_WINDOW`]).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::depth_within;
/// assert!(depth_within(0.5004, (0.5, 0.001)));
/// assert!(!depth_within(0.502, (0.5, 0.001)));
/// ```
pub fn depth_within(got: f32, (depth, window): (f32, f32)) -> bool {
    f32_within(got, got.clamp(depth - window, depth + window))
}

/// Allowed difference, in integer steps, between a unorm channel read back from the GPU and
/// either correct rounding of the reference value (applies to 8-bit, 10-bit and 2-bit channels).
pub const UNORM_LSB: u32 = 1;

/// Allowed difference, in f16 steps (units in the last place), between an `Rgba16Float` channel
/// read back from the GPU and the round-to-nearest-even of the reference `f32` value.
pub const F16_ULP: u32 = 1;

/// Allowed difference, in `f32` ULPs, between an `f32` written by a compute kernel and the
/// reference; [`F32_ABS`] is the absolute floor used near zero.
///
/// Why 8: Vulkan (and so WGSL on lavapipe) evaluates `+ − ×` correctly rounded but lets the
/// compiler contract `a·b + c` into a fused multiply-add (a difference of up to ½ ULP per
/// operation), allows 2.5 ULP for division, 2 ULP for `inverseSqrt` (so `normalize` and
/// `length` are a few ULP off) and 3 ULP for `exp2`/`log2` near the origin. The kernels this
/// bound is meant for chain two or three such operations (`normalize` then a division, a box
/// projection, a falloff), which stays within about 8 ULP. Any actual formula error shows up
/// as a relative difference of 10⁻⁴ or more, i.e. thousands of ULPs, so 8 ULP keeps the tests
/// sharp.
///
/// Not for long chains or large exponents: `exp2(x)` may be off by `3 + 2·|x|` ULP and
/// `pow(x, p)` amplifies the relative error of `x` by `p` (the specular lobe has `p` up to 256).
/// Compare those through a quantized target (1 LSB of 8 bits is 2^15 ULP of `f32`) or with
/// [`f32_within_ulp`] and a bound derived for the case.
pub const F32_ULP: u32 = 8;

/// Absolute floor (2^-20 ≈ 9.5·10⁻⁷) for `f32` comparisons: a result within this distance of
/// the reference is accepted whatever its ULP distance.
///
/// Near zero, ULPs become arbitrarily small while the error of a result obtained by
/// cancellation (`1 − length(dist)/b` in a falloff, `(p − o) + d·fa` in a box projection,
/// `−log2(s)` for `s` near 1, where Vulkan bounds `log2` only by 2^-21 absolute) is a few ULPs
/// of the *operands*. The kernels' operands are of unit scale (colours, unit vectors,
/// smoothness, unit-sized boxes), so the floor is [`F32_ULP`] ULPs of 1.0: 8 · 2^-23 = 2^-20.
/// For operands of magnitude `s` > 1 (positions in a larger scene) pass `F32_ABS · s` as the
/// floor to [`f32_within_ulp`].
pub const F32_ABS: f32 = 1.0 / 1_048_576.0;

/// Whether the unorm channel value `got` (an integer of `bits` bits) is acceptable for the
/// reference value `expected`.
///
/// The correct roundings of `expected` are `round(saturate(expected) · (2^bits − 1))` with the
/// tie going either way (NaN: 0); `got` is accepted when it is within [`UNORM_LSB`] of one of
/// them. So at 8 bits, 0.5 (127.5, a tie) accepts 126 ..= 129 and 127.2/255 accepts
/// 126 ..= 128. Values above `2^bits − 1` are never accepted.
///
/// # Panics
/// When `bits` is not in `1..=16`.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::unorm_within;
/// // A tie: 127 and 128 are both correct, and one step further either way is tolerated.
/// for got in 126..=129 { assert!(unorm_within(got, 0.5, 8)); }
/// assert!(!unorm_within(125, 0.5, 8) && !unorm_within(130, 0.5, 8));
/// // Not a tie: 127.2 rounds to 127 only.
/// assert!(unorm_within(128, 127.2 / 255.0, 8));
/// assert!(!unorm_within(129, 127.2 / 255.0, 8));
/// // Saturation and NaN.
/// assert!(unorm_within(1023, 7.0, 10) && unorm_within(1022, 7.0, 10));
/// assert!(unorm_within(1, f32::NAN, 10) && !unorm_within(2, f32::NAN, 10));
/// assert!(!unorm_within(256, 1.0, 8));
/// ```
pub fn unorm_within(got: u32, expected: f32, bits: u32) -> bool {
    let max = unorm_max(bits);
    if got > max {
        return false;
    }
    let x = if expected.is_nan() {
        0.0
    } else {
        // Exact in f64 (24-bit significand times an integer below 2^16).
        f64::from(expected.clamp(0.0, 1.0)) * f64::from(max)
    };
    let lowest = (x - 0.5).ceil() as i64; // ties down
    let highest = (x + 0.5).floor() as i64; // ties up
    let got = i64::from(got);
    let lsb = i64::from(UNORM_LSB);
    got >= lowest - lsb && got <= highest + lsb
}

/// [`unorm_within`] on four channels with their bit widths (`[8; 4]` for `Rgba8Unorm`,
/// `[10, 10, 10, 2]` for `Rgb10a2Unorm`).
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::tolerance::unorm4_within;
/// assert!(unorm4_within([0, 511, 1023, 3], Vec4::new(0.0, 0.5, 1.0, 1.0), [10, 10, 10, 2]));
/// ```
pub fn unorm4_within(got: [u32; 4], expected: Vec4, bits: [u32; 4]) -> bool {
    (0..4).all(|i| unorm_within(got[i], expected[i], bits[i]))
}

/// The f16 values in order: position of `h` on the number line (±0 both at 0), or `None` for NaN.
fn f16_ordinal(h: u16) -> Option<i32> {
    let mag = i32::from(h & 0x7fff);
    if mag > 0x7c00 {
        None
    } else if h & 0x8000 != 0 {
        Some(-mag)
    } else {
        Some(mag)
    }
}

/// Whether the half float with bits `got_bits` is acceptable for the reference value `expected`:
/// within [`F16_ULP`] f16 steps of `expected` rounded to nearest even.
///
/// NaN only matches NaN (any payload). +0 and −0 are the same value. Infinity is one step above
/// 65504, so each accepts the other — this is what "1 ULP" means at the end of the range, and
/// covers targets that convert by rounding toward zero.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f16_within;
/// assert!(f16_within(0x3C00, 1.0));
/// assert!(f16_within(0x3BFF, 1.0) && f16_within(0x3C01, 1.0));
/// assert!(!f16_within(0x3C02, 1.0));
/// assert!(f16_within(0x8000, 0.0) && f16_within(0x8001, 0.0));
/// assert!(f16_within(0x7E00, f32::NAN) && !f16_within(0x7C00, f32::NAN));
/// assert!(f16_within(0x7C00, 1e9) && !f16_within(0xFC00, 1e9));
/// ```
pub fn f16_within(got_bits: u16, expected: f32) -> bool {
    let want = f16_ordinal(f32_to_f16_bits(expected));
    match (f16_ordinal(got_bits), want) {
        (None, None) => true,
        (Some(g), Some(w)) => g.abs_diff(w) <= F16_ULP,
        _ => false,
    }
}

/// [`f16_within`] on the four channels of an `Rgba16Float` texel.
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::tolerance::f16x4_within;
/// assert!(f16x4_within([0x3C00, 0x4000, 0, 0x3C00], Vec4::new(1.0, 2.0, 0.0, 1.0)));
/// ```
pub fn f16x4_within(got: [u16; 4], expected: Vec4) -> bool {
    (0..4).all(|i| f16_within(got[i], expected[i]))
}

/// Position of a non-NaN `f32` on the number line in ULP steps (±0 both at 0).
fn f32_ordinal(x: f32) -> i64 {
    let bits = x.to_bits();
    let mag = i64::from(bits & 0x7fff_ffff);
    if bits & 0x8000_0000 != 0 { -mag } else { mag }
}

/// Distance between two `f32` values in units in the last place (0 for +0 and −0; one step
/// from the largest finite value to infinity), or `None` when either is NaN.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f32_ulp_distance;
/// assert_eq!(f32_ulp_distance(1.0, 1.0 + f32::EPSILON), Some(1));
/// assert_eq!(f32_ulp_distance(-0.0, 0.0), Some(0));
/// assert_eq!(f32_ulp_distance(-f32::from_bits(1), f32::from_bits(1)), Some(2));
/// assert_eq!(f32_ulp_distance(f32::NAN, 1.0), None);
/// ```
pub fn f32_ulp_distance(a: f32, b: f32) -> Option<u64> {
    if a.is_nan() || b.is_nan() {
        None
    } else {
        Some(f32_ordinal(a).abs_diff(f32_ordinal(b)))
    }
}

/// Whether `got` is within `max_ulp` ULPs of `expected` or within `abs_floor` of it.
/// NaN matches NaN; an infinity matches only the same infinity.
///
/// For results whose error bound differs from the default of [`f32_within`]; say why at the
/// call site.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f32_within_ulp;
/// assert!(f32_within_ulp(1.0 + 20.0 * f32::EPSILON, 1.0, 32, 0.0));
/// assert!(!f32_within_ulp(1.0 + 20.0 * f32::EPSILON, 1.0, 16, 0.0));
/// ```
pub fn f32_within_ulp(got: f32, expected: f32, max_ulp: u32, abs_floor: f32) -> bool {
    if got.is_nan() || expected.is_nan() {
        return got.is_nan() && expected.is_nan();
    }
    if got.is_infinite() || expected.is_infinite() {
        return got == expected;
    }
    (got - expected).abs() <= abs_floor
        || f32_ulp_distance(got, expected).is_some_and(|d| d <= u64::from(max_ulp))
}

/// Whether the `f32` a compute kernel produced is acceptable for the reference value:
/// within [`F32_ULP`] ULPs or [`F32_ABS`] absolute. NaN matches NaN; an infinity matches only
/// the same infinity.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f32_within;
/// assert!(f32_within(1.0 + 8.0 * f32::EPSILON, 1.0));
/// assert!(!f32_within(1.0 + 9.0 * f32::EPSILON, 1.0));
/// assert!(f32_within(9e-7, 0.0));            // the absolute floor
/// assert!(!f32_within(1e-6, 0.0));
/// assert!(f32_within(f32::NAN, f32::NAN));
/// assert!(f32_within(f32::INFINITY, f32::INFINITY));
/// assert!(!f32_within(f32::NEG_INFINITY, f32::INFINITY));
/// assert!(!f32_within(f32::MAX, f32::INFINITY));
/// ```
pub fn f32_within(got: f32, expected: f32) -> bool {
    f32_within_ulp(got, expected, F32_ULP, F32_ABS)
}

/// [`f32_within`] on each component.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::tolerance::vec3_within;
/// assert!(vec3_within(Vec3::new(1.0, 0.0, -2.0), Vec3::new(1.0, 5e-7, -2.0)));
/// ```
pub fn vec3_within(got: Vec3, expected: Vec3) -> bool {
    (0..3).all(|i| f32_within(got[i], expected[i]))
}

/// [`f32_within`] on each component.
///
/// ```
/// use glam::Vec4;
/// use wgsl_variants_shaders::reference::tolerance::vec4_within;
/// assert!(!vec4_within(Vec4::ONE, Vec4::new(1.0, 1.0, 1.0, 1.001)));
/// ```
pub fn vec4_within(got: Vec4, expected: Vec4) -> bool {
    (0..4).all(|i| f32_within(got[i], expected[i]))
}

/// The largest error, in steps, of a value read back from an 8-bit G-buffer channel (RT0, RT1):
/// half a step of rounding, widened to [`UNORM_LSB`] + ½ for the GPU's rounding freedom.
pub const GBUFFER_8BIT_STEP: f32 = (UNORM_LSB as f32 + 0.5) / 255.0;

/// The largest angle (radians, ≈ length of the difference) between a unit normal and the one
/// decoded from the 10-bit RT2: each component of `n` moves by at most
/// ([`UNORM_LSB`] + ½)/1023 · 2 in `rgb · 2 − 1`, so the vector by `√3 · 3/1023 ≈ 5.1·10⁻³`
/// before renormalization, which does not lengthen the error of a unit vector's direction.
pub const GBUFFER_NORMAL_ANGLE: f32 = 1.732_050_8 * 3.0 / 1023.0;

/// How far the deferred light of one pixel may be from the forward light of the same surface
/// (docs/shading.md §10), per channel, before the targets round it.
///
/// Both passes evaluate the Standard BRDF's direct term in tier `brdf`,
/// `light = k · (diffuse · kd + ks · (spec + (1 − spec) · f))` ([`DirectFactors`]), with
/// `k = colour · attenuation`; the deferred one reads `diffuse`, `spec` and `smoothness` from
/// 8-bit targets, which clamp to [0, 1] and round (each off by at most
/// `δ_x = |x − saturate(x)| + `[`GBUFFER_8BIT_STEP`] per channel: a detail albedo can push the colours above 1, and then
/// forward and deferred differ by design), and `n` from the 10-bit RT2 (off by at most
/// [`GBUFFER_NORMAL_ANGLE`] = ε: the angle between `n` and `l`, `h` or `v` moves by at most ε,
/// and the angle between `r = reflect(v, n)` and `l` by at most 2ε, a reflection doubling the
/// normal's rotation; each dot product then lies between the cosines of its angle ± that).
///
/// The light is increasing in `diffuse` and in `spec` (`kd, ks ≥ 0`, `f ≤ 1`), so for given
/// factors its range is reached at `diffuse ± δ`, `spec ± δ`. The factors are monotonic in each
/// dot product over the box except where a range crosses 0 (BRDF3's `(r·l)⁴`), which is added
/// as a point, and not in smoothness, whose interval is sampled at 9 points plus the lobe's
/// peak in roughness (`r² = (1 − (n·h)²)/(n·h)²`, BRDF1 and BRDF2) and the table's row centres
/// (BRDF3, linear between them). The bound is the largest distance from the forward value to
/// the light over all those corners:
///
/// ```text
/// Δ = max over corners of max(hi − light, light − lo)
/// ```
///
/// The arguments are the forward pass's exact values. Positions (interpolated vs. rebuilt from
/// depth) differ by a few `f32` ULP, far below these terms.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::brdf::{Brdf, Dots};
/// use wgsl_variants_shaders::reference::tolerance::gbuffer_light_bound;
/// // A matte surface (no specular) under a unit light, head-on: the diffuse step and the
/// // normal angle.
/// let dots = Dots::new(Vec3::Z, Vec3::Z, Vec3::Z);
/// let b = gbuffer_light_bound(Brdf::Brdf2, Vec3::splat(0.5), Vec3::ZERO, 0.0, &dots, Vec3::ONE);
/// assert!(b.x > 0.003 && b.x < 0.02, "{b}");
/// ```
pub fn gbuffer_light_bound(
    brdf: Brdf,
    diffuse: Vec3,
    spec: Vec3,
    smoothness: f32,
    dots: &Dots,
    k: Vec3,
) -> Vec3 {
    let delta = GBUFFER_8BIT_STEP;
    let eps = GBUFFER_NORMAL_ANGLE;
    let light = DirectFactors::new(brdf, smoothness, dots).apply(diffuse, spec, k);

    // The smoothness candidates.
    let (s_lo, s_hi) = ((smoothness - delta).max(0.0), (smoothness + delta).min(1.0));
    let mut smooth: Vec<f32> = (0..9)
        .map(|i| s_lo + (s_hi - s_lo) * i as f32 / 8.0)
        .collect();
    for nh in [dots.nh - eps, dots.nh + eps] {
        let nh = nh.clamp(1e-3, 1.0);
        // The lobe a² / (c + nh²a²)² peaks at a² = c / nh² with c = 1 − nh²: pr = a^(1/2).
        let a = ((1.0 - nh * nh).max(0.0) / (nh * nh)).sqrt();
        smooth.push(1.0 - a.sqrt());
    }
    if brdf == Brdf::Brdf3 {
        let rows = crate::brdf_lut::HEIGHT as f32;
        smooth.extend((0..crate::brdf_lut::HEIGHT).map(|j| 1.0 - (j as f32 + 0.5) / rows));
    }
    smooth.retain(|s| (s_lo..=s_hi).contains(s));

    // cos(θ ± e), the angle θ = acos(x) kept in [0, π].
    let range = |x: f32, e: f32| {
        let theta = x.clamp(-1.0, 1.0).acos();
        [
            (theta + e).min(std::f32::consts::PI).cos(),
            (theta - e).max(0.0).cos(),
        ]
    };
    let mut rl = range(dots.rl, 2.0 * eps).to_vec();
    if rl[0] < 0.0 && rl[1] > 0.0 {
        rl.push(0.0);
    }
    let stored = |x: Vec3| (x - x.clamp(Vec3::ZERO, Vec3::ONE)).abs() + Vec3::splat(delta);
    let (d_diffuse, d_spec) = (stored(diffuse), stored(spec));
    let (diffuse_lo, diffuse_hi) = ((diffuse - d_diffuse).max(Vec3::ZERO), diffuse + d_diffuse);
    let (spec_lo, spec_hi) = ((spec - d_spec).max(Vec3::ZERO), spec + d_spec);

    let mut bound = Vec3::ZERO;
    for &nl in &range(dots.nl, eps) {
        for &nh in &range(dots.nh, eps) {
            for &nv in &range(dots.nv, eps) {
                for &rl in &rl {
                    for &s in &smooth {
                        let corner = Dots {
                            nl,
                            nh,
                            nv,
                            rl,
                            ..*dots
                        };
                        let f = DirectFactors::new(brdf, s, &corner);
                        let hi = f.apply(diffuse_hi, spec_hi, k);
                        let lo = f.apply(diffuse_lo, spec_lo, k);
                        bound = bound.max(hi - light).max(light - lo);
                    }
                }
            }
        }
    }
    bound
}

/// Allowed difference, in steps of the channel's own format (units in the last place),
/// between an `Rg11b10Ufloat` channel read back from the GPU and the reference value rounded
/// to nearest even by [`super::urp::ufloat::UFloat::encode`]: the conversion rules let an
/// implementation round toward zero instead and leave ties open, each at most one step away.
/// One step is 2^-6 relative on r and g (11-bit, 6-bit mantissa) and 2^-5 on b (10-bit).
pub const UFLOAT_ULP: u32 = 1;

/// Whether the unsigned float bits `got` (an 11- or 10-bit channel of an `Rg11b10Ufloat`
/// texel) are acceptable for the reference value `expected`: within [`UFLOAT_ULP`] steps of
/// its correct conversion. Unsigned float bits order like their values (+∞ one step above
/// the largest finite value); NaN only matches NaN.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::ufloat_within;
/// use wgsl_variants_shaders::reference::urp::ufloat::UFloat;
/// let one = UFloat::F11.encode(1.0);
/// assert!(ufloat_within(one + 1, 1.0, UFloat::F11) && ufloat_within(one - 1, 1.0, UFloat::F11));
/// assert!(!ufloat_within(one + 2, 1.0, UFloat::F11));
/// assert!(ufloat_within(0, -5.0, UFloat::F10));   // negative values store 0
/// ```
pub fn ufloat_within(got: u16, expected: f32, format: super::urp::ufloat::UFloat) -> bool {
    let inf = format.infinity_bits();
    let want = format.encode(expected);
    match (got > inf, want > inf) {
        (true, true) => true,
        (false, false) => got.abs_diff(want) <= UFLOAT_ULP as u16,
        _ => false,
    }
}

/// [`ufloat_within`] on the three channels of a packed `Rg11b10Ufloat` word.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::tolerance::rg11b10_within;
/// use wgsl_variants_shaders::reference::urp::ufloat::pack_rg11b10;
/// assert!(rg11b10_within(pack_rg11b10(Vec3::new(1.0, 2.0, 3.0)), Vec3::new(1.0, 2.0, 3.0)));
/// assert!(!rg11b10_within(pack_rg11b10(Vec3::new(1.1, 2.0, 3.0)), Vec3::new(1.0, 2.0, 3.0)));
/// ```
pub fn rg11b10_within(word: u32, expected: Vec3) -> bool {
    use super::urp::ufloat::{UFloat, split_rg11b10};
    let [r, g, b] = split_rg11b10(word);
    ufloat_within(r, expected.x, UFloat::F11)
        && ufloat_within(g, expected.y, UFloat::F11)
        && ufloat_within(b, expected.z, UFloat::F10)
}

/// Whether the byte `got` of an `Rgba8UnormSrgb` colour channel is acceptable for the linear
/// reference value: within [`UNORM_LSB`] of a correct rounding of its exact sRGB encoding
/// (GPUs may approximate the transfer function before rounding; the step absorbs it).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::srgb8_within;
/// assert!(srgb8_within(188, 0.5) && srgb8_within(187, 0.5) && !srgb8_within(186, 0.5));
/// ```
pub fn srgb8_within(got: u8, expected_linear: f32) -> bool {
    let encoded = if expected_linear.is_nan() {
        f32::NAN
    } else {
        super::urp::srgb::srgb_encode(expected_linear)
    };
    unorm_within(u32::from(got), encoded, 8)
}

/// Whether the `Rgba8Snorm` channel `got` is acceptable for the reference value `expected`:
/// within [`UNORM_LSB`] of either correct rounding of `clamp(expected, −1, 1) · 127` (NaN: 0).
/// −128 reads as −1, like −127, and is accepted where −127 is.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::snorm8_within;
/// assert!(snorm8_within(64, 0.5) && snorm8_within(63, 0.5) && snorm8_within(65, 0.5));
/// assert!(!snorm8_within(66, 0.5) && !snorm8_within(61, 0.5));
/// assert!(snorm8_within(-128, -1.0) && snorm8_within(-127, -7.0));
/// ```
pub fn snorm8_within(got: i8, expected: f32) -> bool {
    let x = if expected.is_nan() {
        0.0
    } else {
        f64::from(expected.clamp(-1.0, 1.0)) * 127.0
    };
    let lowest = (x - 0.5).ceil() as i64;
    let highest = (x + 0.5).floor() as i64;
    let got = i64::from(got.max(-127));
    let lsb = i64::from(UNORM_LSB);
    got >= lowest - lsb && got <= highest + lsb
}

/// Allowed difference, in 12-bit codes, between each of the two codes of an octahedral normal
/// read back from the GPU and the reference's (URP truncates `f · 4095.5`, so a normal a few
/// `f32` ULPs away may land on the neighbouring code).
pub const OCT_CODE_STEP: u32 = 1;

/// Whether the three octahedral bytes `got` hold codes within [`OCT_CODE_STEP`] of those of
/// `expected` ([`super::urp::normal::unpack_888_to_float2`]'s layout: byte 0 and the low
/// nibble of byte 2 are x, byte 1 and the high nibble y).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::oct888_within;
/// // x code 0x0FF against 0x100: one code apart although every byte differs.
/// assert!(oct888_within([0xFF, 0x10, 0x00], [0x00, 0x10, 0x01]));
/// assert!(!oct888_within([0xFE, 0x10, 0x00], [0x00, 0x10, 0x01]));
/// ```
pub fn oct888_within(got: [u8; 3], expected: [u8; 3]) -> bool {
    let codes = |b: [u8; 3]| {
        (
            u32::from(b[0]) | (u32::from(b[2] & 15) << 8),
            u32::from(b[1]) | (u32::from(b[2] >> 4) << 8),
        )
    };
    let (gx, gy) = codes(got);
    let (ex, ey) = codes(expected);
    gx.abs_diff(ex) <= OCT_CODE_STEP && gy.abs_diff(ey) <= OCT_CODE_STEP
}

/// Whether the four bytes of a URP target's texel, as read back, are acceptable for the
/// reference texel `expected` (which also says how the target stores it).
///
/// ```
/// use glam::{Vec3, Vec4};
/// use wgsl_variants_shaders::reference::tolerance::urp_texel_within;
/// use wgsl_variants_shaders::reference::urp::gbuffer::UrpTexel;
/// use wgsl_variants_shaders::reference::urp::ufloat::pack_rg11b10;
/// assert!(urp_texel_within([188, 0, 255, 8], &UrpTexel::Srgb8(Vec4::new(0.5, 0.0, 1.0, 8.0 / 255.0))));
/// let word = pack_rg11b10(Vec3::new(0.25, 1.5, 3.0)).to_le_bytes();
/// assert!(urp_texel_within(word, &UrpTexel::Ufloat(Vec3::new(0.25, 1.5, 3.0))));
/// assert!(urp_texel_within(7u32.to_le_bytes(), &UrpTexel::U32(7)));
/// assert!(!urp_texel_within(6u32.to_le_bytes(), &UrpTexel::U32(7)));
/// ```
pub fn urp_texel_within(got: [u8; 4], expected: &super::urp::gbuffer::UrpTexel) -> bool {
    use super::urp::gbuffer::UrpTexel;
    let word = u32::from_le_bytes(got);
    let unorm8 = |i: usize, x: f32| unorm_within(u32::from(got[i]), x, 8);
    match *expected {
        UrpTexel::Srgb8(v) => (0..3).all(|i| srgb8_within(got[i], v[i])) && unorm8(3, v.w),
        UrpTexel::Unorm8(v) => (0..4).all(|i| unorm8(i, v[i])),
        UrpTexel::OctNormal { bytes, smoothness } => {
            oct888_within([got[0], got[1], got[2]], bytes) && unorm8(3, smoothness)
        }
        UrpTexel::Snorm8(v) => (0..4).all(|i| snorm8_within(got[i] as i8, v[i])),
        UrpTexel::Ufloat(v) => rg11b10_within(word, v),
        UrpTexel::UfloatBetween(a, b) => {
            // The GPU value clamped into the interval, then within one step of the clamped value.
            let got = super::urp::ufloat::unpack_rg11b10(word);
            rg11b10_within(word, got.clamp(a.min(b), a.max(b)))
        }
        UrpTexel::F32(x) => f32_within(f32::from_bits(word), x),
        UrpTexel::U32(x) => word == x,
    }
}

/// Whether a URP texel read back at a pixel is acceptable for the reference texels `window`
/// takes over the pixel's sub-pixel window ([`window_offsets`]): [`urp_texel_within`] one of
/// them, or, for octahedral normals (whose 12-bit codes move by several steps across the
/// window of a curved, normal-mapped surface), both codes within the window's range of codes
/// widened by [`OCT_CODE_STEP`] and the smoothness within 1 LSB of the first's.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::urp_texel_within_window;
/// use wgsl_variants_shaders::reference::urp::gbuffer::UrpTexel;
/// let oct = |x: u32| UrpTexel::OctNormal { bytes: [x as u8, 16, 0], smoothness: 0.5 };
/// let window = [oct(100), oct(104)];
/// assert!(urp_texel_within_window([102, 16, 0, 128], &window));
/// assert!(urp_texel_within_window([105, 16, 0, 128], &window));
/// assert!(!urp_texel_within_window([106, 16, 0, 128], &window));
/// ```
pub fn urp_texel_within_window(got: [u8; 4], window: &[super::urp::gbuffer::UrpTexel]) -> bool {
    use super::urp::gbuffer::UrpTexel;
    if window.iter().any(|e| urp_texel_within(got, e)) {
        return true;
    }
    let codes = |b: [u8; 3]| {
        [
            u32::from(b[0]) | (u32::from(b[2] & 15) << 8),
            u32::from(b[1]) | (u32::from(b[2] >> 4) << 8),
        ]
    };
    let mut hull = [(u32::MAX, 0u32); 2];
    for e in window {
        let UrpTexel::OctNormal { bytes, .. } = e else {
            return false;
        };
        for (h, c) in hull.iter_mut().zip(codes(*bytes)) {
            *h = (h.0.min(c), h.1.max(c));
        }
    }
    let Some(UrpTexel::OctNormal { smoothness, .. }) = window.first() else {
        return false;
    };
    let in_hull = hull
        .iter()
        .zip(codes([got[0], got[1], got[2]]))
        .all(|(&(lo, hi), c)| c + OCT_CODE_STEP >= lo && c <= hi + OCT_CODE_STEP);
    in_hull && unorm_within(u32::from(got[3]), *smoothness, 8)
}

/// How far from a pixel's centre (in pixels, along x and along y) the rasterizer may evaluate
/// the attributes it interpolates for that pixel.
///
/// Vulkan snaps vertex positions to a grid of `2^-subPixelPrecisionBits` pixels, with at least
/// 4 bits (lavapipe has 8); an affine attribute evaluated at the centre of the snapped
/// triangle equals the original triangle's value at a point moved by no more than the
/// vertices moved, half a grid step per axis: 1/32 pixel at 4 bits. The window is twice that.
/// The frame's comparisons allow, per pixel, the reference's whole range over the window
/// ([`window_range`]); a pixel whose window reaches another object is an edge pixel
/// and is left out (counted).
pub const SUBPIXEL_WINDOW: f32 = 1.0 / 16.0;

/// What storing any value of `[lo, hi]` (per channel) into an `Rg11b10Ufloat` target may
/// give: from [`UFLOAT_ULP`] steps below the conversion of `lo` to as many above the
/// conversion of `hi`, decoded (steps stop at 0 and at +∞; negative values store 0). A chain
/// of stores — URP's lights blended One/One onto GBuffer3 one after another — applies it once
/// per store.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::tolerance::rg11b10_store_range;
/// let (lo, hi) = rg11b10_store_range(Vec3::splat(1.0), Vec3::splat(1.0));
/// // One step of the 11-bit r and g (6 mantissa bits) and of the 10-bit b (5) either way.
/// assert_eq!((lo.x, hi.x), (1.0 - 1.0 / 128.0, 1.0 + 1.0 / 64.0));
/// assert_eq!((lo.z, hi.z), (1.0 - 1.0 / 64.0, 1.0 + 1.0 / 32.0));
/// assert_eq!(rg11b10_store_range(Vec3::splat(-1.0), Vec3::ZERO).0, Vec3::ZERO);
/// ```
pub fn rg11b10_store_range(lo: Vec3, hi: Vec3) -> (Vec3, Vec3) {
    use super::urp::ufloat::UFloat;
    let step = UFLOAT_ULP as u16;
    let mut out = (lo, hi);
    for (k, format) in [UFloat::F11, UFloat::F11, UFloat::F10]
        .into_iter()
        .enumerate()
    {
        let below = format.encode(lo[k]).saturating_sub(step);
        let above = (format.encode(hi[k]) + step).min(format.infinity_bits());
        out.0[k] = format.decode(below);
        out.1[k] = format.decode(above);
    }
    out
}

/// The pixel-space offsets of a pixel's [`SUBPIXEL_WINDOW`] where a reference is evaluated:
/// the centre, then the eight points `±SUBPIXEL_WINDOW` away along each axis and diagonal.
/// An affine quantity (depth across a triangle) takes its extremes at the corners; the edge
/// midpoints catch a curved one.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::{SUBPIXEL_WINDOW, window_offsets};
/// let w = window_offsets();
/// assert_eq!(w[0], (0.0, 0.0));
/// assert!(w.iter().all(|&(x, y)| x.abs() <= SUBPIXEL_WINDOW && y.abs() <= SUBPIXEL_WINDOW));
/// ```
pub fn window_offsets() -> [(f32, f32); 9] {
    let w = SUBPIXEL_WINDOW;
    [
        (0.0, 0.0),
        (-w, -w),
        (0.0, -w),
        (w, -w),
        (-w, 0.0),
        (w, 0.0),
        (-w, w),
        (0.0, w),
        (w, w),
    ]
}

/// The reference's range, per channel, over the values it takes at a pixel's centre and the
/// points of its [`SUBPIXEL_WINDOW`]: `(min, max)`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::tolerance::window_range;
/// let (lo, hi) = window_range(&[Vec3::splat(1.0), Vec3::new(1.1, 1.0, 0.8)]);
/// assert_eq!((lo, hi), (Vec3::new(1.0, 1.0, 0.8), Vec3::new(1.1, 1.0, 1.0)));
/// ```
pub fn window_range(values: &[Vec3]) -> (Vec3, Vec3) {
    values.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), v| (lo.min(*v), hi.max(*v)),
    )
}

/// The spacing of half floats around `x`: `2^(e − 10)` for `2^e ≤ |x| < 2^(e+1)`, and the
/// subnormal spacing `2^-24` below `2^-14`.
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f16_step;
/// assert_eq!(f16_step(1.5), 2f32.powi(-10));
/// assert_eq!(f16_step(2.0), 2f32.powi(-9));
/// assert_eq!(f16_step(0.0), 2f32.powi(-24));
/// ```
pub fn f16_step(x: f32) -> f32 {
    let e = x.abs().max(f32::MIN_POSITIVE).log2().floor().max(-14.0);
    (e - 10.0).exp2()
}

/// The most a value `x` stored in an `Rgba16Float` target may be off: half a step of
/// rounding plus [`F16_ULP`] steps of freedom (as [`f16_within`]).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::f16_store_error;
/// assert_eq!(f16_store_error(1.0), 1.5 / 1024.0);
/// ```
pub fn f16_store_error(x: f32) -> f32 {
    (F16_ULP as f32 + 0.5) * f16_step(x)
}

/// The most an `Rgba16Float` channel blended `src · a + dst · (1 − a)` (blend factors
/// SrcAlpha / OneMinusSrcAlpha) may be off beyond the store's own rounding
/// ([`f16_store_error`]), when the blend runs at the target's precision.
///
/// Vulkan blends a floating-point attachment "with at least the precision and dynamic range
/// of the format": for a 16-bit float target the blend unit may round the source colour and
/// alpha to f16 and then each product (NVIDIA's does; lavapipe blends in f32). Each rounding
/// is at most half an f16 step of the value rounded, so to first order the result moves by
/// `a · ½step(src) + ½step(a) · (|src| + |dst|) + ½step(src · a) + ½step(dst · (1 − a))`
/// (the alpha's error enters both factors).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::{f16_blend_error, f16_step};
/// // 0.25 over 0.25 at a = 0.5: 1.25 steps of 0.25 on top of the store's rounding.
/// let e = f16_blend_error(0.25, 0.5, 0.25);
/// assert!(e > f16_step(0.25) && e < 2.5 * f16_step(0.25));
/// assert_eq!(f16_blend_error(0.25, 0.5, 0.25), 1.25 * f16_step(0.25));
/// assert_eq!(f16_blend_error(0.0, 0.0, 0.0), f16_step(0.0));
/// ```
pub fn f16_blend_error(src: f32, a: f32, dst: f32) -> f32 {
    0.5 * (a.abs() * f16_step(src)
        + f16_step(a) * (src.abs() + dst.abs())
        + f16_step(src * a)
        + f16_step(dst * (1.0 - a)))
}

/// The most a value stored in a unorm channel of `bits` bits may be off, in value units: half
/// a step of rounding plus [`UNORM_LSB`] steps (as [`unorm_within`]).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::{GBUFFER_8BIT_STEP, unorm_store_error};
/// assert_eq!(unorm_store_error(8), GBUFFER_8BIT_STEP);
/// assert_eq!(unorm_store_error(10), 1.5 / 1023.0);
/// ```
pub fn unorm_store_error(bits: u32) -> f32 {
    (UNORM_LSB as f32 + 0.5) / unorm_max(bits) as f32
}

/// The range the deferred LDR path's decoded light `−log2(s)` may take after `stores`
/// roundings of the 10-bit `exp2(−c)` chain (docs/shading.md §12), when the exact light lies
/// in `[c_lo, c_hi]`.
///
/// RT3 starts as the G-buffer pass's `s₀ = exp2(−c₀)` and each light multiplies it by
/// `exp2(−lᵢ)` (blend DstColor / Zero); every store rounds by at most
/// `e = `[`unorm_store_error`]`(10)`, and a multiplication by a factor ≤ 1 does not grow an
/// earlier error, so the stored `s` is within `stores · e` of `exp2(−c)`. Decoding is
/// monotonic, so the decoded value lies between `−log2` of the ends of that interval (+∞ when
/// it reaches 0: the final pass then writes 1).
///
/// ```
/// use wgsl_variants_shaders::reference::tolerance::ldr_chain_range;
/// let (lo, hi) = ldr_chain_range(1.0, 1.0, 3);
/// assert!(lo < 1.0 && hi > 1.0 && hi - lo < 0.03);
/// assert_eq!(ldr_chain_range(0.0, 12.0, 3).1, f32::INFINITY);
/// ```
pub fn ldr_chain_range(c_lo: f32, c_hi: f32, stores: u32) -> (f32, f32) {
    let e = stores as f32 * unorm_store_error(10);
    let s_hi = ((-c_lo.max(0.0)).exp2() + e).min(1.0);
    let s_lo = (-c_hi.max(0.0)).exp2() - e;
    let hi = if s_lo > 0.0 {
        -s_lo.log2()
    } else {
        f32::INFINITY
    };
    (-s_hi.log2(), hi)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::quantize::{f16_bits_to_f32, unorm};
    use crate::reference::urp::ufloat::UFloat;

    #[test]
    fn ufloat_tolerance_is_one_step_of_the_channel() {
        for f in [UFloat::F11, UFloat::F10] {
            for h in 1..f.max_finite_bits() {
                let x = f.decode(h);
                assert!(ufloat_within(h, x, f) && ufloat_within(h - 1, x, f));
                assert!(ufloat_within(h + 1, x, f), "{f:?} {h:#x}");
                assert!(!ufloat_within(h + 2, x, f) && (h < 2 || !ufloat_within(h - 2, x, f)));
            }
            // NaN only matches NaN; +inf one step above the largest finite value.
            assert!(ufloat_within(f.encode(f32::NAN), f32::NAN, f));
            assert!(!ufloat_within(f.encode(1.0), f32::NAN, f));
            assert!(ufloat_within(f.infinity_bits(), 1e9, f));
        }
    }

    #[test]
    fn unorm_tolerance_is_one_step_around_the_correct_roundings() {
        for bits in [2u32, 8, 10] {
            let max = unorm_max(bits);
            for q in 0..=max {
                // Exactly on a code: q ± 1 accepted, q ± 2 not.
                let x = q as f32 / max as f32;
                for got in 0..=max {
                    let ok = got.abs_diff(q) <= UNORM_LSB;
                    assert_eq!(
                        unorm_within(got, x, bits),
                        ok,
                        "{bits} bits, code {q}, got {got}"
                    );
                }
                // A tie between q and q + 1: q − 1 ..= q + 2 accepted.
                if q < max {
                    let tie = (f64::from(q) + 0.5) / f64::from(max);
                    let tie32 = tie as f32;
                    if f64::from(tie32) * f64::from(max) == f64::from(q) + 0.5 {
                        for got in 0..=max {
                            let ok = got + 1 >= q && got <= q + 2;
                            assert_eq!(unorm_within(got, tie32, bits), ok, "tie {q}.5 got {got}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn unorm_quantize_is_always_within_tolerance() {
        let mut x = -0.1f32;
        while x < 1.1 {
            for bits in [2u32, 8, 10] {
                assert!(unorm_within(unorm(x, bits), x, bits));
            }
            x += 0.000_37;
        }
    }

    #[test]
    fn f16_tolerance_is_one_step() {
        for h in 0u16..0x7c00 {
            let x = f16_bits_to_f32(h);
            assert!(f16_within(h, x));
            assert!(f16_within(h + 1, x), "{h:#06x}");
            if h > 0 {
                assert!(f16_within(h - 1, x));
            } else {
                assert!(f16_within(0x8001, x));
            }
            if h < 0x7bff {
                assert!(!f16_within(h + 2, x));
            }
        }
        assert!(!f16_within(0x3c00, f32::NAN));
        assert!(!f16_within(0x7e00, 1.0));
    }

    #[test]
    fn f32_tolerance_edges() {
        let one_ulp = |x: f32, n: i32| f32::from_bits((x.to_bits() as i32 + n) as u32);
        for x in [1.0f32, 3.5, 1e6, -7.25, -1.5] {
            assert!(f32_within(one_ulp(x, F32_ULP as i32), x));
            assert!(f32_within(one_ulp(x, -(F32_ULP as i32)), x));
            assert!(!f32_within(one_ulp(x, F32_ULP as i32 + 1), x));
        }
        assert!(f32_within(-F32_ABS, 0.0) && f32_within(F32_ABS, 0.0));
        // Small values: the floor, not the ULP distance, decides.
        assert!(f32_within(1e-3 + 9e-7, 1e-3) && !f32_within(1e-3 + 1e-6, 1e-3));
        assert!(!f32_within(F32_ABS * 1.01, 0.0));
        assert!(!f32_within(f32::NAN, 0.0) && !f32_within(0.0, f32::NAN));
        assert!(!f32_within(f32::INFINITY, f32::NAN));
        assert!(f32_within(f32::NEG_INFINITY, f32::NEG_INFINITY));
    }
}
