// lighting/brdf: the metallic workflow and the indirect terms of Unity's Standard BRDF
// (docs/shading.md §5); the direct term is lighting/direct. Pure functions, no bindings;
// callable from any stage. The tier keyword (none: BRDF1, UNITY_PBS_USE_BRDF2,
// UNITY_PBS_USE_BRDF3) picks the formulas.
//
// Provides:
//   struct BrdfMetallic { diffuse: vec3f, spec_color: vec3f, one_minus_reflectivity: f32 }
//   fn brdf_metallic_setup(albedo: vec3f, metallic: f32) -> BrdfMetallic
//   fn brdf_one_minus_reflectivity_from_specular(spec_color: vec3f) -> f32
//   fn brdf_premultiply_diffuse(diffuse: vec3f, alpha: f32) -> vec3f
//   fn brdf_premultiply_alpha(alpha: f32, one_minus_reflectivity: f32) -> f32
//   fn brdf_roughness(smoothness: f32) -> f32
//   fn brdf_sh_ambient(n: vec3f, sh_r: vec4f, sh_g: vec4f, sh_b: vec4f) -> vec3f
//   fn brdf_view_dir(camera_position: vec3f, world_position: vec3f) -> vec3f
//   fn brdf_reflect_dir(v: vec3f, n: vec3f) -> vec3f
//   fn brdf_pow4(x: f32) -> f32, fn brdf_pow5(x: f32) -> f32
//   fn brdf_safe_normalize(v: vec3f) -> vec3f
//   fn brdf_indirect_specular(env: vec3f, spec_color: vec3f, smoothness: f32,
//                             one_minus_reflectivity: f32, n: vec3f, v: vec3f) -> vec3f

const BRDF_DIELECTRIC_SPEC: f32 = 0.04;

struct BrdfMetallic {
    diffuse: vec3f,
    spec_color: vec3f,
    one_minus_reflectivity: f32,
}

// spec_color = mix(0.04, albedo, metallic); one_minus_reflectivity = 0.96 · (1 - metallic);
// diffuse = albedo · one_minus_reflectivity.
fn brdf_metallic_setup(albedo: vec3f, metallic: f32) -> BrdfMetallic {
    var out: BrdfMetallic;
    out.spec_color = mix(vec3f(BRDF_DIELECTRIC_SPEC), albedo, metallic);
    out.one_minus_reflectivity = (1.0 - BRDF_DIELECTRIC_SPEC) * (1.0 - metallic);
    out.diffuse = albedo * out.one_minus_reflectivity;
    return out;
}

// The G-buffer keeps no metallic value; the deferred reflection pass reconstructs
// one_minus_reflectivity from RT1's specular colour as Unity's Internal-DeferredReflections does:
// 1 - max(spec.r, spec.g, spec.b). Exact for dielectrics (spec 0.04 -> 0.96).
fn brdf_one_minus_reflectivity_from_specular(spec_color: vec3f) -> f32 {
    return 1.0 - max(max(spec_color.r, spec_color.g), spec_color.b);
}

// _RENDERING_TRANSPARENT (forward only): diffuse · alpha.
fn brdf_premultiply_diffuse(diffuse: vec3f, alpha: f32) -> vec3f {
    return diffuse * alpha;
}

// _RENDERING_TRANSPARENT (forward only): 1 - omr + alpha · omr.
fn brdf_premultiply_alpha(alpha: f32, one_minus_reflectivity: f32) -> f32 {
    return 1.0 - one_minus_reflectivity + alpha * one_minus_reflectivity;
}

// r = pr², pr = 1 - smoothness.
fn brdf_roughness(smoothness: f32) -> f32 {
    let pr = 1.0 - smoothness;
    return pr * pr;
}

// Unity's L0+L1 spherical harmonics: max((sh_r·(n,1), sh_g·(n,1), sh_b·(n,1)), 0).
fn brdf_sh_ambient(n: vec3f, sh_r: vec4f, sh_g: vec4f, sh_b: vec4f) -> vec3f {
    let n1 = vec4f(n, 1.0);
    return max(vec3f(dot(sh_r, n1), dot(sh_g, n1), dot(sh_b, n1)), vec3f(0.0));
}

// v = normalize(camera_position - world_position).
fn brdf_view_dir(camera_position: vec3f, world_position: vec3f) -> vec3f {
    return normalize(camera_position - world_position);
}

// r = reflect(-v, n) = -v - 2 · dot(n, -v) · n.
fn brdf_reflect_dir(v: vec3f, n: vec3f) -> vec3f {
    return reflect(-v, n);
}

// x⁴ and x⁵ as Unity's Pow4 / Pow5.
fn brdf_pow4(x: f32) -> f32 {
    let x2 = x * x;
    return x2 * x2;
}

fn brdf_pow5(x: f32) -> f32 {
    let x2 = x * x;
    return x2 * x2 * x;
}

// Unity's Unity_SafeNormalize: v / sqrt(max(|v|², 0.001)) (0 stays 0).
fn brdf_safe_normalize(v: vec3f) -> vec3f {
    return v * inverseSqrt(max(dot(v, v), 0.001));
}

// The indirect specular of the Standard BRDF's tier (docs/shading.md §5); env is the probe
// result already times occlusion. grazing = saturate(smoothness + 1 - omr), pr = 1 - smoothness,
// r = pr²:
//   BRDF1 (no tier keyword): env / (r'² + 1) · mix(spec_color, grazing, (1 - |n·v|)⁵),
//                            r' = max(r, 0.002)
//   UNITY_PBS_USE_BRDF2:     env · (1 - r·pr·(0.6 - 0.08·pr)) · mix(spec, grazing, (1 - nv)⁴)
//   UNITY_PBS_USE_BRDF3:     env · mix(spec_color, grazing, (1 - nv)⁴),   nv = saturate(n·v)
fn brdf_indirect_specular(
    env: vec3f,
    spec_color: vec3f,
    smoothness: f32,
    one_minus_reflectivity: f32,
    n: vec3f,
    v: vec3f,
) -> vec3f {
    let grazing = vec3f(saturate(smoothness + 1.0 - one_minus_reflectivity));
#if defined(UNITY_PBS_USE_BRDF3)
    let nv = saturate(dot(n, v));
    return env * mix(spec_color, grazing, brdf_pow4(1.0 - nv));
#elif defined(UNITY_PBS_USE_BRDF2)
    let nv = saturate(dot(n, v));
    let pr = 1.0 - smoothness;
    let r = pr * pr;
    let surface_reduction = 1.0 - r * pr * (0.6 - 0.08 * pr);
    return surface_reduction * env * mix(spec_color, grazing, brdf_pow4(1.0 - nv));
#else
    let nv = abs(dot(n, v));
    let r = max(brdf_roughness(smoothness), 0.002);
    let surface_reduction = 1.0 / (r * r + 1.0);
    return surface_reduction * env * mix(spec_color, grazing, brdf_pow5(1.0 - nv));
#endif
}
