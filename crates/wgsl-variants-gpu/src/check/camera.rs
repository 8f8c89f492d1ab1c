//! What the full-screen deferred passes see of the camera: its view-projection and position
//! and the depth buffer they rebuild each pixel's position from, and the bindings that hand
//! these to a pass (`deferred/depth`).

use glam::{DVec3, DVec4, Mat4, Vec3};

use super::scene::{push_mat4, push_vec4};
use crate::{BoundResource, Resource};

/// What the lighting pass sees of the camera: `view_proj` (its inverse, for positions from
/// depth, and itself, for light volumes) and position (the `DeferredCamera` uniform) and the
/// depth buffer, one `f32` per pixel.
pub(crate) struct LightingCamera<'a> {
    pub(crate) view_proj: Mat4,
    pub(crate) position: Vec3,
    pub(crate) depth: &'a [f32],
}

/// The `DeferredCamera` uniform (`deferred/depth`) of a view: inverse view-projection, the
/// camera's position, view-projection.
pub(crate) fn deferred_camera(view_proj: Mat4, camera: Vec3) -> Vec<u8> {
    let mut out = Vec::new();
    push_mat4(&mut out, view_proj.inverse());
    push_vec4(&mut out, camera.extend(1.0));
    push_mat4(&mut out, view_proj);
    out
}

/// The ray through the target point `(px, py)` (pixels; `(x + 0.5, y + 0.5)` is pixel
/// `(x, y)`'s centre) of a `width × height` view, in `f64`: its point on the near plane and
/// the direction to its point on the far plane.
pub(crate) fn pixel_ray(
    view_proj: Mat4,
    (width, height): (u32, u32),
    px: f64,
    py: f64,
) -> (DVec3, DVec3) {
    let inv = view_proj.as_dmat4().inverse();
    let ndc_x = px / f64::from(width) * 2.0 - 1.0;
    let ndc_y = 1.0 - py / f64::from(height) * 2.0;
    let unproject = |z: f64| {
        let h = inv * DVec4::new(ndc_x, ndc_y, z, 1.0);
        h.truncate() / h.w
    };
    let origin = unproject(0.0);
    (origin, unproject(1.0) - origin)
}

/// Bindings 3 and 4 of the full-screen deferred passes (`deferred/depth`): the depth buffer as
/// `R32Float` and the `DeferredCamera` uniform (inverse view-projection, position,
/// view-projection).
pub(crate) fn depth_camera_resources(
    (width, height): (u32, u32),
    camera: &LightingCamera<'_>,
) -> Vec<BoundResource> {
    let depth: Vec<u8> = camera.depth.iter().flat_map(|d| d.to_le_bytes()).collect();
    let uniform = deferred_camera(camera.view_proj, camera.position);
    vec![
        BoundResource::new(
            0,
            3,
            Resource::Texture2d {
                format: wgpu::TextureFormat::R32Float,
                width,
                height,
                data: depth,
            },
        ),
        BoundResource::new(0, 4, Resource::Uniform(uniform)),
    ]
}
