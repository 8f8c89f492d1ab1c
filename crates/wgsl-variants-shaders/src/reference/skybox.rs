//! The background: Unity's built-in `Skybox/Cubemap` shader (docs/shading.md §15), as the
//! `skybox/Cubemap` pass draws it behind every surface.
//!
//! The sky in world direction `d` is the cube map's texel in direction `R⁻¹(d)` (Unity turns
//! the sky mesh about +Y by `_Rotation` degrees and samples at the unturned vertex), decoded
//! as the probes are (`DecodeHDR`, [`rgbm_decode`]), times `_Tint.rgb`, Unity's
//! `unity_ColorSpaceDouble` and `_Exposure`.
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::skybox::Skybox;
//! let sky = Skybox { rotation_degrees: 90.0, ..Skybox::default() };
//! // Turned a quarter turn: what lies along +Z in the world is the cube's +X face.
//! assert!((sky.texcoord(Vec3::Z) - Vec3::X).length() < 1e-6);
//! // The default tint (½ grey) times 2^2.2 (linear colour space) leaves a texel of
//! // white at 2.3: Unity's default tint is not neutral.
//! let c = sky.color(Vec4::ONE);
//! assert!((c - Vec3::splat(0.5 * 4.594_794)).abs().max_element() < 1e-5);
//! ```

use glam::{Vec3, Vec4};

use super::probe::rgbm_decode;

/// `unity_ColorSpaceDouble` in linear colour space: `2^2.2` (2 in gamma space).
pub const COLOR_SPACE_DOUBLE_LINEAR: f32 = 4.594_794;

/// A `Skybox/Cubemap` material (its properties and the cube's decode instructions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Skybox {
    /// `_Tint.rgb` (Unity's default: ½ grey).
    pub tint: Vec3,
    /// `_Exposure` (default 1).
    pub exposure: f32,
    /// `_Rotation`: degrees about +Y (default 0).
    pub rotation_degrees: f32,
    /// `_Tex_HDR`: the cube's decode instructions `(x, y, _, w)` ([`rgbm_decode`]).
    pub decode: Vec4,
    /// `unity_ColorSpaceDouble` ([`COLOR_SPACE_DOUBLE_LINEAR`]; 2 in gamma space).
    pub color_space_double: f32,
}

impl Default for Skybox {
    /// Unity's defaults in linear colour space, with an 8-bit cube decoded as is.
    fn default() -> Skybox {
        Skybox {
            tint: Vec3::splat(0.5),
            exposure: 1.0,
            rotation_degrees: 0.0,
            decode: Vec4::new(1.0, 1.0, 0.0, 0.0),
            color_space_double: COLOR_SPACE_DOUBLE_LINEAR,
        }
    }
}

impl Skybox {
    /// The direction the cube is sampled in for world direction `dir`: `dir` turned about +Y
    /// by `−rotation_degrees` (`(c·x + s·z, y, c·z − s·x)`).
    pub fn texcoord(&self, dir: Vec3) -> Vec3 {
        let (s, c) = self.rotation_degrees.to_radians().sin_cos();
        Vec3::new(c * dir.x + s * dir.z, dir.y, c * dir.z - s * dir.x)
    }

    /// The sky's colour for a sampled (filtered, still encoded) cube texel: `DecodeHDR ·
    /// tint · unity_ColorSpaceDouble · exposure`. Increasing in each of the texel's
    /// components (for the decodes of [`rgbm_decode`]), so the colour of an interval of
    /// texels lies between the colours of its ends.
    pub fn color(&self, texel: Vec4) -> Vec3 {
        let hdr = Vec3::new(self.decode.x, self.decode.y, self.decode.w);
        rgbm_decode(texel, hdr) * self.tint * (self.color_space_double * self.exposure)
    }

    /// The uniform the pass reads (`Skybox`, 48 bytes): tint, decode, `(exposure, rotation,
    /// colour-space double, 0)`.
    pub fn uniform(&self) -> [f32; 12] {
        [
            self.tint.x,
            self.tint.y,
            self.tint.z,
            1.0,
            self.decode.x,
            self.decode.y,
            self.decode.z,
            self.decode.w,
            self.exposure,
            self.rotation_degrees,
            self.color_space_double,
            0.0,
        ]
    }
}

/// The faces a linearly filtered sample of a cube map with `size`-texel faces may read in
/// direction `dir`: its own face and, within half a texel of an edge, the face across that
/// edge (and across the corner's third edge), in wgpu's layer order. A cube with one colour
/// per face gives a sample between those faces' colours.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::skybox::seam_faces;
/// assert_eq!(seam_faces(Vec3::new(0.1, 0.0, 1.0), 64), vec![4]); // +Z only
/// assert_eq!(seam_faces(Vec3::new(0.995, 0.0, -1.0), 64), vec![0, 5]); // +X / −Z edge
/// ```
pub fn seam_faces(dir: Vec3, size: u32) -> Vec<usize> {
    let a = dir.abs();
    let major = a.max_element();
    // Half a texel of the face's [−1, 1] coordinates, and a margin for the GPU's rounding.
    let band = 1.0 / size as f32 + 1e-3;
    (0..3)
        .filter(|&k| a[k] >= major * (1.0 - band))
        .map(|k| 2 * k + usize::from(dir[k] < 0.0))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rotation_turns_the_sky_about_y() {
        let sky = Skybox {
            rotation_degrees: 30.0,
            ..Skybox::default()
        };
        let d = Vec3::new(0.3, 0.5, -0.8);
        let t = sky.texcoord(d);
        // About Y: the height and the length stay, the angle in xz moves by −30°.
        assert!((t.y - d.y).abs() < 1e-6 && (t.length() - d.length()).abs() < 1e-6);
        let angle = |v: Vec3| v.z.atan2(v.x).to_degrees();
        let turned = angle(d) - angle(t);
        assert!((turned - 30.0).abs() < 1e-4, "{turned}");
    }

    #[test]
    fn the_colour_is_increasing_in_the_texel() {
        let sky = Skybox {
            decode: Vec4::new(5.0, 2.2, 0.0, 1.0),
            ..Skybox::default()
        };
        let lo = sky.color(Vec4::new(0.2, 0.4, 0.6, 0.3));
        let hi = sky.color(Vec4::new(0.3, 0.4, 0.7, 0.5));
        assert!(lo.cmple(hi).all(), "{lo} {hi}");
        assert!(sky.color(Vec4::new(1.0, 1.0, 1.0, 0.0)) == Vec3::ZERO);
    }

    #[test]
    fn a_corner_reads_three_faces() {
        assert_eq!(seam_faces(Vec3::new(-1.0, 0.999, 0.998), 64), vec![1, 2, 4]);
        assert_eq!(seam_faces(Vec3::new(0.0, -1.0, 0.0), 64), vec![3]);
    }
}
