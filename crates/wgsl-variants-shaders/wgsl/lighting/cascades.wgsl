// lighting/cascades: a directional light's cascaded shadow map as Unity's screen-space shadow
// collector reads it (Internal-ScreenSpaceShadows with UnityShadowLibrary; docs/shading.md
// §11). The camera's view is split into 1, 2 or 4 slices by view depth; each slice has its own
// orthographic shadow view, rendered into one tile of an atlas. The keywords of Unity's
// multi_compile_shadowcollector pick how a pixel finds its cascade:
//   (none)                  the slice its view depth falls in: near <= z < far (Unity's
//                           _LightSplitsNear / _LightSplitsFar, getCascadeWeights)
//   SHADOWS_SPLIT_SPHERES   the first slice whose bounding sphere holds it (Unity's
//                           unity_ShadowSplitSpheres / unity_ShadowSplitSqRadii,
//                           getCascadeWeights_splitSpheres: weights.yzw -= weights.xyz)
//   SHADOWS_SINGLE_CASCADE  cascade 0, nothing selected (getShadowCoord_SingleCascade)
// URP's _MAIN_LIGHT_SHADOWS_CASCADE (universal/main_light_shadow) selects as
// SHADOWS_SPLIT_SPHERES does: its ComputeCascadeIndex is the same subtraction.
// A pixel in no cascade gets the coordinate (0, 0, 0): depth 0 is in front of every caster, so
// it is lit (Unity moves it in front of the casters likewise).
//
// The record is laid out for a uniform buffer (400 bytes):
//   world_to_shadow[i]   world to cascade i's tile of the atlas (clip space: the tile's
//                        orthographic view, scaled and offset into the tile)
//   split_spheres[i]     xyz: the centre of slice i's bounding sphere (w unused)
//   split_sq_radii       their squared radii (0: an unused cascade)
//   splits_near/far      each slice's view depths (an unused cascade: an empty range)
//   view_axis            xyz: the camera's forward axis, w: dot(forward, camera position), so
//                        view depth = dot(p, xyz) - w
//   params               x: strength, y: the depth bias subtracted from the receiver
//
// Provides:
//   struct CascadedShadow
//   fn cascade_weights(c: CascadedShadow, p: vec3f) -> vec4f   one-hot (or zero: no cascade)
//   fn cascade_coords(c: CascadedShadow, p: vec3f) -> vec3f    atlas uv (row 0 at the top), depth

#import lighting/shadow

struct CascadedShadow {
    world_to_shadow: array<mat4x4f, 4>,
    split_spheres: array<vec4f, 4>,
    split_sq_radii: vec4f,
    splits_near: vec4f,
    splits_far: vec4f,
    view_axis: vec4f,
    params: vec4f,
}

fn cascade_weights(c: CascadedShadow, p: vec3f) -> vec4f {
#if defined(SHADOWS_SPLIT_SPHERES) || defined(_MAIN_LIGHT_SHADOWS_CASCADE)
    let d0 = p - c.split_spheres[0].xyz;
    let d1 = p - c.split_spheres[1].xyz;
    let d2 = p - c.split_spheres[2].xyz;
    let d3 = p - c.split_spheres[3].xyz;
    let distances2 = vec4f(dot(d0, d0), dot(d1, d1), dot(d2, d2), dot(d3, d3));
    let inside = select(vec4f(0.0), vec4f(1.0), distances2 < c.split_sq_radii);
    // Each cascade only where no earlier one holds the point.
    return vec4f(inside.x, saturate(inside.yzw - inside.xyz));
#else
    let z = dot(p, c.view_axis.xyz) - c.view_axis.w;
    let near = select(vec4f(0.0), vec4f(1.0), vec4f(z) >= c.splits_near);
    let far = select(vec4f(0.0), vec4f(1.0), vec4f(z) < c.splits_far);
    return near * far;
#endif
}

fn cascade_coords(c: CascadedShadow, p: vec3f) -> vec3f {
#if defined(SHADOWS_SINGLE_CASCADE)
    return shadow_coords(c.world_to_shadow[0], p);
#else
    let w = cascade_weights(c, p);
    return shadow_coords(c.world_to_shadow[0], p) * w.x + shadow_coords(c.world_to_shadow[1], p) * w.y
        + shadow_coords(c.world_to_shadow[2], p) * w.z + shadow_coords(c.world_to_shadow[3], p) * w.w;
#endif
}
