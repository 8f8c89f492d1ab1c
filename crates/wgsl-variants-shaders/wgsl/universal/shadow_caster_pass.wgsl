// universal/shadow_caster_pass: URP Lit's ShadowCaster program (URP's ShadowCasterPass.hlsl,
// Shadows.hlsl ApplyShadowBias; docs/urp.md §10): the mesh into a light's depth map, pushed away
// from the light by the depth bias and inset along the normal by the normal bias, flattened
// onto the near plane ("pancaking"); _ALPHATEST_ON discards as the G-buffer pass does.
//
//   group 0: 0 camera (Camera: view_proj = the light's view-projection),
//            4 shadow_caster (UrpShadowCaster)
//   group 1: 0 material, 1 material_sampler, 2 base_map   group 2: 0 object (universal/bindings)
//
// Provides the entry points:
//   @vertex   vs_main(UrpCasterInput) -> UrpCasterOutput
//   @fragment fs_main(UrpCasterOutput)   depth only (no colour target)

#import universal/bindings
#import universal/surface

// light_direction.xyz: unit direction TO a directional light (URP's _LightDirection);
// light_position.xyz: a point or spot light's position (_LightPosition,
// _CASTING_PUNCTUAL_LIGHT_SHADOW); bias: x depth bias, y normal bias (URP's _ShadowBias, world
// units, negative: away from the light, into the surface).
struct UrpShadowCaster {
    light_direction: vec4f,
    light_position: vec4f,
    bias: vec4f,
}

@group(0) @binding(4) var<uniform> shadow_caster: UrpShadowCaster;

struct UrpCasterInput {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(3) uv: vec2f,
}

struct UrpCasterOutput {
    @builtin(position) clip_position: vec4f,
    @location(0) uv: vec2f,
}

// ApplyShadowBias: p + l · bias.x + n · (1 - saturate(l·n)) · bias.y.
fn urp_apply_shadow_bias(p: vec3f, n: vec3f, l: vec3f) -> vec3f {
    let scale = (1.0 - saturate(dot(l, n))) * shadow_caster.bias.y;
    return p + l * shadow_caster.bias.x + n * scale;
}

@vertex
fn vs_main(in: UrpCasterInput) -> UrpCasterOutput {
    var out: UrpCasterOutput;
    let p = (object.model * vec4f(in.position, 1.0)).xyz;
    let n = normalize((object.normal_matrix * vec4f(in.normal, 0.0)).xyz);
#if defined(_CASTING_PUNCTUAL_LIGHT_SHADOW)
    let l = normalize(shadow_caster.light_position.xyz - p);
#else
    let l = shadow_caster.light_direction.xyz;
#endif
    var clip = camera.view_proj * vec4f(urp_apply_shadow_bias(p, n, l), 1.0);
    // Casters in front of the near plane land on it (depth 0 in wgpu's clip space).
    clip.z = max(clip.z, 0.0);
    out.clip_position = clip;
    out.uv = in.uv;
    return out;
}

@fragment
fn fs_main(in: UrpCasterOutput) {
    urp_alpha(textureSample(base_map, material_sampler, in.uv).a);
}
