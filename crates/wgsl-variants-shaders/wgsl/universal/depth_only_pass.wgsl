// universal/depth_only_pass: URP Lit's DepthOnly program (URP's DepthOnlyPass.hlsl; docs/urp.md
// §13): the depth prepass URP draws before the opaques when a pass after it reads the camera's
// depth in the forward path (the screen-space shadow pass). The mesh through the camera, the
// same product as the other Lit passes' vertex stage (so the same depth); _ALPHATEST_ON
// discards as they do; the fragment writes its depth (URP's positionCS.z: the value the depth
// buffer gets) to its one colour channel (URP's ColorMask R; R32Float here), the texture the
// passes after it read.
//
//   group 0: 0 camera (Camera: view_proj)
//   group 1: 0 material, 1 material_sampler, 2 base_map   group 2: 0 object (universal/bindings)
//
// Provides the entry points:
//   @vertex   vs_main(UrpDepthInput) -> UrpDepthOutput
//   @fragment fs_main(UrpDepthOutput) -> @location(0) f32

#import universal/bindings
#import universal/surface

struct UrpDepthInput {
    @location(0) position: vec3f,
    @location(3) uv: vec2f,
}

struct UrpDepthOutput {
    @builtin(position) clip_position: vec4f,
    @location(0) uv: vec2f,
}

@vertex
fn vs_main(in: UrpDepthInput) -> UrpDepthOutput {
    var out: UrpDepthOutput;
    out.clip_position = camera.view_proj * (object.model * vec4f(in.position, 1.0));
    out.uv = in.uv;
    return out;
}

@fragment
fn fs_main(in: UrpDepthOutput) -> @location(0) f32 {
    urp_alpha(textureSample(base_map, material_sampler, in.uv).a);
    return in.clip_position.z;
}
