#import demo::tint

@fragment
fn fs() -> @location(0) vec4<f32> {
#ifdef TINT
    return tint::tint();
#else
    return vec4<f32>(0.0);
#endif
}
