//! The test scene's cube maps: one uniform RGBA colour per face, the same on every mip level,
//! so that a sample depends only on which face a direction selects — not on filtering, seams or
//! the mip level.
//!
//! Faces are numbered as wgpu's cube layers: 0 = +X, 1 = −X, 2 = +Y, 3 = −Y, 4 = +Z, 5 = −Z.
//! A direction selects the face of its largest-magnitude component (the cube-map rule of
//! Vulkan). Directions where two components tie lie on a face edge and may sample either face
//! on a GPU; tests keep [`face_margin`] well above 0.
//!
//! ```
//! use glam::{Vec3, Vec4};
//! use wgsl_variants_shaders::reference::cube::{face, face_margin, CubeFaces};
//! let cube = CubeFaces::from_fn(|f| Vec4::splat(f as f32));
//! assert_eq!(cube.sample(Vec3::new(0.2, -0.9, 0.1)), Vec4::splat(3.0)); // −Y
//! assert_eq!(face(Vec3::new(0.0, 0.0, -1.0)), 5);
//! assert_eq!(face_margin(Vec3::new(0.5, 0.0, 1.0)), 0.5);
//! ```

use glam::{Vec3, Vec4};

/// Index of the +X face.
pub const POS_X: usize = 0;
/// Index of the −X face.
pub const NEG_X: usize = 1;
/// Index of the +Y face.
pub const POS_Y: usize = 2;
/// Index of the −Y face.
pub const NEG_Y: usize = 3;
/// Index of the +Z face.
pub const POS_Z: usize = 4;
/// Index of the −Z face.
pub const NEG_Z: usize = 5;

/// The face a direction samples: the axis of the largest `|component|`, on its sign's side
/// (+X, −X, +Y, −Y, +Z, −Z = 0 … 5).
///
/// On exact ties between axes this picks X over Y over Z (a GPU may pick either; see
/// [`face_margin`]). The zero vector and vectors with NaN components give +X (0) — they have no
/// meaningful face. A major component of −0 cannot occur (the major one is non-zero).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::cube::{face, NEG_X, POS_Y, POS_Z};
/// assert_eq!(face(Vec3::new(-3.0, 1.0, 2.0)), NEG_X);
/// assert_eq!(face(Vec3::new(0.1, 0.5, -0.4)), POS_Y);
/// assert_eq!(face(Vec3::new(0.0, 0.0, 1e-30)), POS_Z);
/// ```
pub fn face(dir: Vec3) -> usize {
    if dir.is_nan() || dir == Vec3::ZERO {
        return POS_X;
    }
    let a = dir.abs();
    let axis = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    axis * 2 + usize::from(dir[axis] < 0.0)
}

/// How far `dir` is from an edge of the face it selects: `1 − max(|s|, |t|)` where `(s, t)` are
/// the face coordinates (the two minor components divided by the major one's magnitude).
/// 1 at a face centre, 0 on an edge or corner (and for the zero vector or NaN).
///
/// A test direction with margin `m` stays on its face under a perturbation of its minor
/// components of up to about `m · |major|`; margins above 0.01 are far from anything a GPU's
/// rounding can move.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::cube::face_margin;
/// assert_eq!(face_margin(Vec3::X), 1.0);
/// assert_eq!(face_margin(Vec3::new(1.0, 1.0, 0.0)), 0.0);
/// assert_eq!(face_margin(Vec3::new(0.2, -2.0, 0.5)), 0.75);
/// assert_eq!(face_margin(Vec3::ZERO), 0.0);
/// ```
pub fn face_margin(dir: Vec3) -> f32 {
    let a = dir.abs();
    let major = a.max_element();
    if dir.is_nan() || !major.is_finite() || major <= 0.0 {
        return 0.0;
    }
    let minor = if a.x == major {
        a.y.max(a.z)
    } else if a.y == major {
        a.x.max(a.z)
    } else {
        a.x.max(a.y)
    };
    1.0 - minor / major
}

/// A cube map with one uniform RGBA colour per face (wgpu layer order, see [`face`]), the same
/// on every mip level.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CubeFaces(pub [Vec4; 6]);

impl CubeFaces {
    /// A cube whose face `f` has colour `colour(f)`.
    ///
    /// ```
    /// use glam::Vec4;
    /// use wgsl_variants_shaders::reference::cube::CubeFaces;
    /// let c = CubeFaces::from_fn(|f| Vec4::new(f as f32 / 5.0, 0.0, 0.0, 1.0));
    /// assert_eq!(c.0[5].x, 1.0);
    /// ```
    pub fn from_fn(colour: impl FnMut(usize) -> Vec4) -> CubeFaces {
        CubeFaces(std::array::from_fn(colour))
    }

    /// A cube with the same colour on every face.
    ///
    /// ```
    /// use glam::{Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::cube::CubeFaces;
    /// assert_eq!(CubeFaces::uniform(Vec4::ONE).sample(Vec3::NEG_Y), Vec4::ONE);
    /// ```
    pub fn uniform(colour: Vec4) -> CubeFaces {
        CubeFaces([colour; 6])
    }

    /// The colour sampled in direction `dir` (at any mip level): the colour of [`face`]`(dir)`.
    ///
    /// ```
    /// use glam::{Vec3, Vec4};
    /// use wgsl_variants_shaders::reference::cube::CubeFaces;
    /// let c = CubeFaces::from_fn(|f| Vec4::splat(f as f32));
    /// assert_eq!(c.sample(Vec3::new(0.1, 0.2, -0.3)), Vec4::splat(5.0));
    /// ```
    pub fn sample(&self, dir: Vec3) -> Vec4 {
        self.0[face(dir)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_directions_select_their_faces() {
        let axes = [
            Vec3::X,
            Vec3::NEG_X,
            Vec3::Y,
            Vec3::NEG_Y,
            Vec3::Z,
            Vec3::NEG_Z,
        ];
        for (i, a) in axes.iter().enumerate() {
            assert_eq!(face(*a), i);
            assert_eq!(face(*a * 7.5 + a.any_orthonormal_vector() * 3.0), i);
            assert_eq!(face_margin(*a), 1.0);
        }
    }

    #[test]
    fn ties_and_degenerate_directions() {
        assert_eq!(face(Vec3::new(1.0, 1.0, 1.0)), POS_X);
        assert_eq!(face(Vec3::new(0.0, -1.0, 1.0)), NEG_Y);
        assert_eq!(face(Vec3::new(0.0, 1.0, -1.0)), POS_Y);
        assert_eq!(face(Vec3::ZERO), POS_X);
        assert_eq!(face(Vec3::new(f32::NAN, 1.0, 0.0)), POS_X);
        assert_eq!(face_margin(Vec3::new(f32::NAN, 1.0, 0.0)), 0.0);
        assert_eq!(face_margin(Vec3::new(f32::INFINITY, 1.0, 0.0)), 0.0);
        assert_eq!(face_margin(Vec3::new(-1.0, 0.0, 1.0)), 0.0);
    }

    #[test]
    fn margin_measures_distance_to_the_edge() {
        assert_eq!(face_margin(Vec3::new(1.0, 0.25, -0.5)), 0.5);
        assert_eq!(face_margin(Vec3::new(0.9, 1.0, 0.0)), 1.0 - 0.9);
        assert_eq!(face_margin(Vec3::new(0.0, 0.0, -4.0)), 1.0);
        // Crossing an edge flips the face; the margin goes through 0.
        let a = Vec3::new(1.0, 0.99, 0.0);
        let b = Vec3::new(0.99, 1.0, 0.0);
        assert_eq!(face(a), POS_X);
        assert_eq!(face(b), POS_Y);
        assert!(face_margin(a) < 0.011 && face_margin(b) < 0.011);
    }
}
