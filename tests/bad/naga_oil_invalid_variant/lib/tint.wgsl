#define_import_path demo::tint

fn tint() -> vec4<f32> {
#ifdef HALF
    return vec3<f32>(0.5);
#else
    return vec4<f32>(1.0);
#endif
}
