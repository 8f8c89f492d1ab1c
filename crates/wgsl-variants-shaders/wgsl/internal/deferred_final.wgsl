#shader deferred_final
// Unity's deferred final pass, LDR only (docs/shading.md §7): decodes the exp2(-c) that RT3
// accumulated back to c = -log2(stored), clamped to 1 as the 8-bit target would, a = 1.
//   group 0: 0 rt3 (Rgb10a2Unorm, read with textureLoad)

#pass Final
#import internal/fullscreen
#import deferred/ldr

@group(0) @binding(0) var rt3: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4f {
    return fullscreen_position(vertex_index);
}

@fragment
fn fs_main(@builtin(position) frag_position: vec4f) -> @location(0) vec4f {
    let stored = textureLoad(rt3, fullscreen_pixel(frag_position), 0).rgb;
    // The 8-bit target clamps to [0, 1] anyway; clamping here keeps +inf (RT3 = 0) out of the
    // float -> unorm conversion, which lavapipe (Mesa 22.3) gets wrong in some shaders: it
    // stores 0 for +inf (and, with LP_NATIVE_VECTOR_WIDTH=128, for any value past ~1e36).
    return vec4f(min(ldr_decode(stored), vec3f(1.0)), 1.0);
}
#endpass
