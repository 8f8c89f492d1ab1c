// standard/shadow_caster: the standard shader's ShadowCaster pass (docs/shading.md §11). The
// camera binding holds the light's view: view_proj = the light's view-projection (a spot's, or
// one cube face's), position.xyz = the light's position, position.w = 1 / range
// (SHADOWS_CUBE; Unity's _LightPositionRange).
//
// Provides the entry points:
//   @vertex   vs_main(CasterInput) -> CasterOutput
//   @fragment fs_main(CasterOutput)                        (SHADOWS_DEPTH: depth only)
//   @fragment fs_main(CasterOutput) -> @location(0) vec4f  (SHADOWS_CUBE: r = |p - light| / range)

#import standard/bindings
#import standard/surface

// The lit passes' vertex layout, of which the caster reads the position and the uv.
struct CasterInput {
    @location(0) position: vec3f,
    @location(3) uv: vec2f,
}

struct CasterOutput {
    @builtin(position) clip_position: vec4f,
    @location(0) world_position: vec3f,
    @location(1) uv: vec2f,
}

@vertex
fn vs_main(in: CasterInput) -> CasterOutput {
    var out: CasterOutput;
    let world = object.model * vec4f(in.position, 1.0);
    out.clip_position = camera.view_proj * world;
    out.world_position = world.xyz;
    out.uv = in.uv;
    return out;
}

#if defined(SHADOWS_CUBE)
// Unity writes the light-to-fragment distance over the range into a colour cube (its RFloat /
// RHalf target): a perspective depth would depend on the face, a distance does not, so the
// receiver compares |p - light| / range whatever face it samples.
@fragment
fn fs_main(in: CasterOutput) -> @location(0) vec4f {
    surface_clip(surface_alpha(in.uv));
    let dist = length(in.world_position - camera.position.xyz) * camera.position.w;
    return vec4f(dist, 0.0, 0.0, 1.0);
}
#else
// Depth only: the rasterizer's depth is the map; the fragment stage only discards.
@fragment
fn fs_main(in: CasterOutput) {
    surface_clip(surface_alpha(in.uv));
}
#endif
