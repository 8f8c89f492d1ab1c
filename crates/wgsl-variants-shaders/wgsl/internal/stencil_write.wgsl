#shader stencil_write
// Unity's Internal-StencilWrite: the stencil pre-pass of a light volume
// (docs/shading.md §10, "Light volumes").
// Depth only: the host draws the volume's front faces (Cull Back) with depth test LessEqual
// against the scene's depth, depth writes off, colour writes off, and stencil Always with
// depth-fail Replace: the pixels whose geometry lies in front of the volume are marked, and
// the light (deferred_shading/Lighting, vs_volume) skips them. Its fragment stage returns 0,
// as Unity's compiled Internal-StencilWrite does, so that it can draw in the Lighting pass,
// whose colour target it leaves alone under colour writes off.
//   group 0: 0 camera (StencilCamera)

#pass StencilWrite

// view_proj: world to clip, the same matrix as the light draw's.
struct StencilCamera {
    view_proj: mat4x4f,
}

@group(0) @binding(0) var<uniform> stencil_camera: StencilCamera;

@vertex
fn vs_main(@location(0) world_position: vec3f) -> @builtin(position) vec4f {
    return stencil_camera.view_proj * vec4f(world_position, 1.0);
}

@fragment
fn fs_main() -> @location(0) vec4f {
    return vec4f(0.0);
}
#endpass
