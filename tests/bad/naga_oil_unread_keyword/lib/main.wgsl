@fragment
fn fs() -> @location(0) vec4<f32> {
#ifdef HALF
    return vec4<f32>(0.5);
#else
    return vec4<f32>(1.0);
#endif
}
