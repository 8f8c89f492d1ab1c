#shader keys
// The fixture of the compile-fail tests (crates/bindings-compile-fail): keywords with a
// `require` and an `exclude` constraint, and a uniform struct whose layout needs padding.
//   group 0: 0 light (uniform)

#pass P
#pragma multi_compile _ SHADOWS
#pragma multi_compile _ SOFT
#pragma multi_compile _ FOG
// Soft shadows are a kind of shadows; fog and soft shadows never meet (a made-up rule).
#pragma require SOFT SHADOWS
#pragma exclude SOFT FOG

struct Light {
    direction: vec3<f32>,
    intensity: f32,
    colors: array<vec3<f32>, 2>,
}

@group(0) @binding(0) var<uniform> light: Light;

@fragment
fn fs() -> @location(0) vec4<f32> {
    var c = light.colors[0] * light.intensity;
#if SHADOWS
    c *= 0.5;
#endif
#if SOFT
    c += light.colors[1] * 0.25;
#endif
#if FOG
    c = mix(c, vec3<f32>(0.5), 0.5);
#endif
    return vec4<f32>(c * max(light.direction.z, 0.0), 1.0);
}
#endpass
