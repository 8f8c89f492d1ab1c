#shader lit
// The fixture of the `NotBaked` compile-fail case (crates/bindings-compile-fail) and of the
// workspace's bake tests: two `shader_feature` sets and a `multi_compile`. The one material
// (materials.toml) uses NORMAL_MAP, so a bake strips every variant with DETAIL or without
// NORMAL_MAP.
#pass P
#pragma shader_feature _ NORMAL_MAP
#pragma shader_feature _ DETAIL
#pragma multi_compile _ FOG
@fragment fn fs() -> @location(0) vec4<f32> {
#if NORMAL_MAP
    return vec4<f32>(0.5);
#else
    return vec4<f32>(1.0);
#endif
}
#endpass
