//! How accurately each G-buffer normal encoding keeps a direction: the angle between a unit
//! normal and what the lighting pass decodes after it went through the target, over a dense,
//! evenly spread set of directions (a Fibonacci sphere).
//!
//! The three encodings, each through its CPU quantizer:
//!
//! | [`NormalEncoding`] | target | rounding |
//! |---|---|---|
//! | `Octahedral888` | `Rgba8Unorm`, URP `_GBUFFER_NORMALS_OCT` | 12-bit codes truncated: `trunc(f · 4095.5)` ([`super::normal::pack_float2_to_888`]); the bytes are exact |
//! | `Unorm101010` | `Rgb10a2Unorm`, the built-in path | `n · 0.5 + 0.5` to nearest, ties up ([`crate::reference::quantize::unorm`]) |
//! | `Snorm8` | `Rgba8Snorm`, URP without accurate normals | `n · 127` to nearest, ties away from zero ([`super::normal::snorm8`]) |
//!
//! All three decode by normalizing (the lighting passes of both paths do). A fourth,
//! hypothetical row rounds the octahedral codes to nearest, which shows that URP's truncation
//! is what puts its largest error above the 10-bit encoding's.
//!
//! ```
//! use wgsl_variants_shaders::reference::urp::accuracy::{fibonacci_sphere, measure, NormalEncoding};
//! let dirs = fibonacci_sphere(1000);
//! let oct = measure(NormalEncoding::Octahedral888, &dirs);
//! let snorm = measure(NormalEncoding::Snorm8, &dirs);
//! assert!(oct.max_deg < snorm.max_deg);
//! ```

use glam::{DVec3, Vec2, Vec3};

use super::normal::{
    decode_normal_oct, decode_normal_snorm8, encode_normal_oct, encode_normal_snorm8, oct_decode,
    oct_encode,
};
use crate::reference::gbuffer::{decode_normal, encode_normal};
use crate::reference::quantize::{unorm, unorm_to_f32};

/// A G-buffer normal encoding, quantizer included.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NormalEncoding {
    /// URP's accurate normals: octahedral, 12:12 bits packed into 8:8:8 of `Rgba8Unorm`.
    Octahedral888,
    /// The built-in path's RT2: `n · 0.5 + 0.5` in 10-bit unorm channels (`Rgb10a2Unorm`).
    Unorm101010,
    /// URP without accurate normals: the normal as is in `Rgba8Snorm`.
    Snorm8,
    /// Not a format anyone ships: the octahedral 12:12 codes rounded to nearest
    /// (`round(f · 4095)`) instead of URP's `trunc(f · 4095.5)`, to show what the truncation
    /// costs.
    Octahedral888Nearest,
}

impl NormalEncoding {
    /// All encodings, in the order of the README table.
    pub const ALL: [NormalEncoding; 4] = [
        NormalEncoding::Octahedral888,
        NormalEncoding::Unorm101010,
        NormalEncoding::Snorm8,
        NormalEncoding::Octahedral888Nearest,
    ];

    /// A short label for tables.
    pub fn label(self) -> &'static str {
        match self {
            NormalEncoding::Octahedral888 => "octahedral 12:12 in Rgba8Unorm (URP accurate)",
            NormalEncoding::Unorm101010 => "n·0.5+0.5 in Rgb10a2Unorm (built-in)",
            NormalEncoding::Snorm8 => "n in Rgba8Snorm (URP default)",
            NormalEncoding::Octahedral888Nearest => {
                "octahedral 12:12, codes rounded to nearest (hypothetical)"
            }
        }
    }

    /// The unit normal the lighting pass decodes after `n` was stored.
    ///
    /// ```
    /// use glam::Vec3;
    /// use wgsl_variants_shaders::reference::urp::accuracy::NormalEncoding;
    /// for e in NormalEncoding::ALL {
    ///     assert!((e.round_trip(Vec3::Y) - Vec3::Y).length() < 2e-3);
    /// }
    /// // Neither 12-bit nor 10-bit unorm has a code at 0.5 (2047/4095, 512/1023), so those
    /// // encodings bring even the axes back slightly off; snorm has 0 and keeps them.
    /// assert_ne!(NormalEncoding::Octahedral888.round_trip(Vec3::Y), Vec3::Y);
    /// assert_eq!(NormalEncoding::Snorm8.round_trip(Vec3::Y), Vec3::Y);
    /// ```
    pub fn round_trip(self, n: Vec3) -> Vec3 {
        match self {
            NormalEncoding::Octahedral888 => decode_normal_oct(encode_normal_oct(n)),
            NormalEncoding::Unorm101010 => {
                let e = encode_normal(n);
                let q = |c: f32| unorm_to_f32(unorm(c, 10), 10);
                decode_normal(Vec3::new(q(e.x), q(e.y), q(e.z)))
            }
            NormalEncoding::Snorm8 => decode_normal_snorm8(encode_normal_snorm8(n)),
            NormalEncoding::Octahedral888Nearest => {
                let f = (oct_encode(n) * 0.5 + Vec2::splat(0.5)).clamp(Vec2::ZERO, Vec2::ONE);
                let code = |v: f32| (f64::from(v) * 4095.0).round() as f32 / 4095.0;
                oct_decode(Vec2::new(code(f.x), code(f.y)) * 2.0 - Vec2::ONE)
            }
        }
    }
}

/// `count` unit directions spread evenly over the sphere (the Fibonacci lattice: heights
/// `z = 1 − (2i + 1)/count`, azimuths stepped by the golden angle).
///
/// ```
/// use wgsl_variants_shaders::reference::urp::accuracy::fibonacci_sphere;
/// let d = fibonacci_sphere(100);
/// assert_eq!(d.len(), 100);
/// assert!(d.iter().all(|v| (v.length() - 1.0).abs() < 1e-6));
/// ```
pub fn fibonacci_sphere(count: usize) -> Vec<Vec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - (2.0 * i as f64 + 1.0) / count as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * i as f64;
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
                .normalize()
                .as_vec3()
        })
        .collect()
}

/// Angular round-trip error of one encoding over a set of directions, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AngularError {
    /// The largest error.
    pub max_deg: f64,
    /// The mean error.
    pub mean_deg: f64,
    /// How many directions were measured.
    pub count: usize,
}

/// The angle in degrees between two unit vectors, computed in `f64` with `atan2(|a×b|, a·b)`
/// (accurate for tiny angles, where `acos` of the dot product is not).
pub fn angle_deg(a: Vec3, b: Vec3) -> f64 {
    let (a, b) = (a.as_dvec3(), b.as_dvec3());
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

/// Max and mean angular error of `encoding` over `dirs` (an empty set gives zeros).
pub fn measure(encoding: NormalEncoding, dirs: &[Vec3]) -> AngularError {
    let mut max = 0.0f64;
    let mut sum = 0.0f64;
    for &n in dirs {
        let e = angle_deg(n, encoding.round_trip(n));
        max = max.max(e);
        sum += e;
    }
    AngularError {
        max_deg: max,
        mean_deg: if dirs.is_empty() {
            0.0
        } else {
            sum / dirs.len() as f64
        },
        count: dirs.len(),
    }
}

/// The README's table: one Markdown row per encoding, measured over `count` directions.
pub fn table(count: usize) -> String {
    let dirs = fibonacci_sphere(count);
    let mut out = format!(
        "| encoding ({count} directions) | max error (°) | mean error (°) |\n|---|---|---|\n"
    );
    for e in NormalEncoding::ALL {
        let m = measure(e, &dirs);
        out.push_str(&format!(
            "| {} | {:.4} | {:.4} |\n",
            e.label(),
            m.max_deg,
            m.mean_deg
        ));
    }
    out
}
