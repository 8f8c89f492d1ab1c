// internal/fullscreen: one triangle covering the whole viewport, from @builtin(vertex_index)
// alone (draw 3 vertices, no vertex buffer): clip positions (-1,-1), (3,-1), (-1,3).
//
// Provides:
//   fn fullscreen_position(vertex_index: u32) -> vec4f
//   fn fullscreen_pixel(frag_position: vec4f) -> vec2i   the pixel of a @builtin(position)

fn fullscreen_position(vertex_index: u32) -> vec4f {
    let uv = vec2f(f32((vertex_index << 1u) & 2u), f32(vertex_index & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

// Fragment positions are pixel centres (x + 0.5, y + 0.5): truncation gives the pixel.
fn fullscreen_pixel(frag_position: vec4f) -> vec2i {
    return vec2i(floor(frag_position.xy));
}
