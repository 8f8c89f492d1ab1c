// deferred/depth: the world position of a pixel rebuilt from the depth buffer (docs/shading.md
// §10), so the deferred passes need no position target, and the camera uniform those
// full-screen passes share. No bindings.
//
// Provides:
//   struct DeferredCamera
//   fn depth_world_position(depth_buffer: texture_2d<f32>, inv_view_proj: mat4x4f, pixel: vec2i) -> vec3f
//       depth = depth_buffer[pixel] (the screen-sized depth buffer or its R32Float copy, (w, h) its size);
//       ndc = ((x + 0.5) / w · 2 - 1, 1 - (y + 0.5) / h · 2, depth) (wgpu: y up, depth in [0, 1]);
//       h = inv_view_proj · (ndc, 1); p = h.xyz / h.w

// inv_view_proj: clip to world (the inverse of the G-buffer pass's view_proj);
// position.xyz: the camera's world position; view_proj: world to clip (light volumes).
struct DeferredCamera {
    inv_view_proj: mat4x4f,
    position: vec4f,
    view_proj: mat4x4f,
}

fn depth_world_position(depth_buffer: texture_2d<f32>, inv_view_proj: mat4x4f, pixel: vec2i) -> vec3f {
    let depth = textureLoad(depth_buffer, pixel, 0).r;
    let uv = (vec2f(pixel) + 0.5) / vec2f(textureDimensions(depth_buffer));
    let ndc = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    let h = inv_view_proj * ndc;
    return h.xyz / h.w;
}
