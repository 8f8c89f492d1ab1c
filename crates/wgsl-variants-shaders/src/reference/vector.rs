//! Vector functions WGSL has built in, and the view and reflection directions every pass
//! computes the same way: one home for the surface and light math below both.

use glam::Vec3;

/// `reflect(i, n) = i − 2 · dot(n, i) · n` (WGSL's `reflect`).
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::vector::reflect;
/// assert_eq!(reflect(Vec3::new(1.0, -1.0, 0.0), Vec3::Y), Vec3::new(1.0, 1.0, 0.0));
/// ```
pub fn reflect(i: Vec3, n: Vec3) -> Vec3 {
    i - 2.0 * n.dot(i) * n
}

/// The view vector `v = normalize(camera_position − world_position)` and the reflection
/// direction `r = reflect(−v, n)`.
///
/// ```
/// use glam::Vec3;
/// use wgsl_variants_shaders::reference::vector::view_and_reflection;
/// let (v, r) = view_and_reflection(Vec3::new(0.0, 2.0, 2.0), Vec3::ZERO, Vec3::Y);
/// assert!((v - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6);
/// assert!((r - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
/// ```
pub fn view_and_reflection(camera_position: Vec3, world_position: Vec3, n: Vec3) -> (Vec3, Vec3) {
    let v = (camera_position - world_position).normalize();
    (v, reflect(-v, n))
}
