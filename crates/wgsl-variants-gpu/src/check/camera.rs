//! What the full-screen deferred passes see of the camera: its view-projection and position
//! and the depth buffer they rebuild each pixel's position from, and the bindings that hand
//! these to a pass (`deferred/depth`).

use glam::{Mat4, Vec3};

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

/// Bindings 3 and 4 of the full-screen deferred passes (`deferred/depth`): the depth buffer as
/// `R32Float` and the `DeferredCamera` uniform (inverse view-projection, position,
/// view-projection).
pub(crate) fn depth_camera_resources(
    (width, height): (u32, u32),
    camera: &LightingCamera<'_>,
) -> Vec<BoundResource> {
    let depth: Vec<u8> = camera.depth.iter().flat_map(|d| d.to_le_bytes()).collect();
    let mut uniform = Vec::new();
    push_mat4(&mut uniform, camera.view_proj.inverse());
    push_vec4(&mut uniform, camera.position.extend(1.0));
    push_mat4(&mut uniform, camera.view_proj);
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
