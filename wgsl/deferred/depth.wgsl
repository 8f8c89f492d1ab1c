// deferred/depth: the world position of a pixel rebuilt from the depth buffer (docs/shading.md
// §10), so the deferred passes need no position target. Pure function, no bindings.
//
// Provides:
//   fn depth_world_position(inv_view_proj: mat4x4f, pixel: vec2i, size: vec2u, depth: f32) -> vec3f
//       ndc = ((x + 0.5) / w · 2 - 1, 1 - (y + 0.5) / h · 2, depth) (wgpu: y up, depth in [0, 1]);
//       h = inv_view_proj · (ndc, 1); p = h.xyz / h.w

fn depth_world_position(inv_view_proj: mat4x4f, pixel: vec2i, size: vec2u, depth: f32) -> vec3f {
    let uv = (vec2f(pixel) + 0.5) / vec2f(size);
    let ndc = vec4f(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, depth, 1.0);
    let h = inv_view_proj * ndc;
    return h.xyz / h.w;
}
