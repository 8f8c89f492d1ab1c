#shader skybox
// Unity's built-in "Skybox/Cubemap" shader (docs/shading.md §15): the background the camera
// sees where no surface was drawn, drawn after the opaque objects and before the transparent
// ones. Here one full-screen triangle at the far plane (depth 1) with the host's depth test
// LEqual and no depth writes, so only the pixels still at the cleared depth take the sky; each
// pixel's view direction comes from the camera's inverse view-projection, rotated about +Y
// by -_Rotation (Unity turns the sky mesh by +_Rotation and samples at the unturned vertex).
//   c = DecodeHDR(cube(dir), _Tex_HDR) · _Tint.rgb · unity_ColorSpaceDouble · _Exposure, a = 1
// The cube is sampled at mip 0 (Unity's texCUBE picks the level from the derivatives; a sky
// is magnified at any practical resolution, so that is level 0 too).
//   group 0: 0 camera (DeferredCamera), 1 sky (Skybox), 2 sky_cube, 3 sky_sampler

#pass Cubemap
#import internal/fullscreen
#import deferred/depth
#import deferred/probe

struct Skybox {
    // _Tint (rgb; a unused).
    tint: vec4f,
    // _Tex_HDR: the cube's decode instructions (x, y, _, w), as probe_rgbm_decode reads them.
    decode: vec4f,
    // x: _Exposure; y: _Rotation in degrees; z: unity_ColorSpaceDouble (2^2.2 = 4.5947938 in
    // linear colour space, 2 in gamma space); w unused.
    params: vec4f,
}

@group(0) @binding(0) var<uniform> camera: DeferredCamera;
@group(0) @binding(1) var<uniform> sky: Skybox;
@group(0) @binding(2) var sky_cube: texture_cube<f32>;
@group(0) @binding(3) var sky_sampler: sampler;

struct SkyVertex {
    @builtin(position) position: vec4f,
    // The world direction from the camera to the far plane; affine in screen space, so the
    // rasterizer's interpolation is exact.
    @location(0) direction: vec3f,
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> SkyVertex {
    let ndc = vec4f(fullscreen_position(vertex_index).xy, 1.0, 1.0);
    let far = camera.inv_view_proj * ndc;
    var out: SkyVertex;
    out.position = ndc;
    out.direction = far.xyz / far.w - camera.position.xyz;
    return out;
}

// Unity's RotateAroundYInDegrees with -degrees: the direction in the cube's unturned frame.
fn sky_unrotate(d: vec3f, degrees: f32) -> vec3f {
    let a = radians(degrees);
    let c = cos(a);
    let s = sin(a);
    return vec3f(c * d.x + s * d.z, d.y, c * d.z - s * d.x);
}

@fragment
fn fs_main(in: SkyVertex) -> @location(0) vec4f {
    let dir = sky_unrotate(in.direction, sky.params.y);
    let texel = textureSampleLevel(sky_cube, sky_sampler, dir, 0.0);
    let c = probe_rgbm_decode(texel, sky.decode) * sky.tint.rgb * (sky.params.z * sky.params.x);
    return vec4f(c, 1.0);
}
#endpass
