// lighting/brdf: the metallic workflow and the lighting terms of Catlike Coding's "My Lighting"
// (docs/shading.md §5). Pure functions, no bindings; callable from any stage.
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
//   fn brdf_indirect_specular(env: vec3f, spec_color: vec3f, smoothness: f32,
//                             one_minus_reflectivity: f32, n: vec3f, v: vec3f) -> vec3f
//   fn brdf_direct(diffuse: vec3f, spec_color: vec3f, smoothness: f32, n: vec3f, v: vec3f,
//                  l: vec3f, light_color: vec3f) -> vec3f

const BRDF_PI: f32 = 3.14159265358979323846;
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

// Fresnel-weighted indirect specular; env is the probe result already times occlusion.
//   grazing = saturate(smoothness + 1 - omr); nv = saturate(dot(n, v));
//   fresnel = mix(spec_color, grazing, (1 - nv)^5); surface_reduction = 1 / (r² + 1);
//   result = surface_reduction · env · fresnel.
fn brdf_indirect_specular(
    env: vec3f,
    spec_color: vec3f,
    smoothness: f32,
    one_minus_reflectivity: f32,
    n: vec3f,
    v: vec3f,
) -> vec3f {
    let grazing = saturate(smoothness + 1.0 - one_minus_reflectivity);
    let nv = saturate(dot(n, v));
    let x = 1.0 - nv;
    let x2 = x * x;
    let fresnel = mix(spec_color, vec3f(grazing), x2 * x2 * x);
    let r = brdf_roughness(smoothness);
    let surface_reduction = 1.0 / (r * r + 1.0);
    return surface_reduction * env * fresnel;
}

// Normalized Blinn-Phong for one directional light (l = unit direction TO the light):
//   h = normalize(l + v); nl = saturate(n·l); nh = saturate(n·h); p = exp2(1 + 7 · smoothness);
//   spec = (p + 8) / (8π) · nh^p; direct = (diffuse + spec_color · spec) · light_color · nl.
// l == -v has no half vector: nh is taken as 0 there (no highlight).
fn brdf_direct(
    diffuse: vec3f,
    spec_color: vec3f,
    smoothness: f32,
    n: vec3f,
    v: vec3f,
    l: vec3f,
    light_color: vec3f,
) -> vec3f {
    let hv = l + v;
    let h = select(vec3f(0.0), normalize(hv), dot(hv, hv) > 0.0);
    let nl = saturate(dot(n, l));
    let nh = saturate(dot(n, h));
    let p = exp2(1.0 + 7.0 * smoothness);
    // pow(0, p) is undefined on GPUs; 0^p = 0 for the p >= 2 used here.
    let nh_p = select(0.0, pow(nh, p), nh > 0.0);
    let spec = (p + 8.0) / (8.0 * BRDF_PI) * nh_p;
    return (diffuse + spec_color * spec) * light_color * nl;
}
