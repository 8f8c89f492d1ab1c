// lighting/direct: the direct term of Unity's Standard BRDF for one light (UNITY_BRDF_PBS with
// no indirect light; docs/shading.md §5), in the variant's tier. Shared by the forward passes
// and the deferred lighting pass. With UNITY_PBS_USE_BRDF3 it reads the lookup table of
// lighting/brdf_lut (group 0, binding 17).
//
// Provides:
//   fn brdf_direct(diffuse: vec3f, spec_color: vec3f, smoothness: f32, n: vec3f, v: vec3f,
//                  l: vec3f, light_color: vec3f) -> vec3f
//
// n, v (towards the camera) and l (towards the light) are unit vectors; light_color is the
// light's colour times its attenuation. pr = 1 - smoothness; nl = saturate(n·l).
//   BRDF1 (no tier keyword): h = safe_normalize(l + v), nh, lh saturated, nv = |n·v|,
//     r = max(pr², 0.002); Disney diffuse fd90 = 0.5 + 2·lh²·pr,
//     kd = (1 + (fd90 - 1)(1 - nl)⁵)(1 + (fd90 - 1)(1 - nv)⁵)·nl;
//     V = 0.5 / (nl(nv(1 - r) + r) + nv(nl(1 - r) + r) + 1e-5), d = (nh·r² - nh)·nh + 1,
//     ks = max(V·r² / (d² + 1e-7)·nl, 0) (Unity's V·D·π·nl, the π cancelling D's 1/π), 0 when
//     spec_color is 0; direct = light · (diffuse·kd + ks·(spec + (1 - spec)(1 - lh)⁵)).
//   UNITY_PBS_USE_BRDF2: a = pr², d = nh²(a² - 1) + 1.00001,
//     ks = a² / (max(0.1, lh²)·(a + 0.5)·d²·4); direct = (diffuse + ks·spec)·light·nl.
//   UNITY_PBS_USE_BRDF3: x = (reflect(v, n)·l)⁴, ks = brdf_lut_sample(x, pr)·16;
//     direct = (diffuse + ks·spec)·light·nl.

#import lighting/brdf
#if defined(UNITY_PBS_USE_BRDF3)
#import lighting/brdf_lut
#endif

fn brdf_direct(
    diffuse: vec3f,
    spec_color: vec3f,
    smoothness: f32,
    n: vec3f,
    v: vec3f,
    l: vec3f,
    light_color: vec3f,
) -> vec3f {
    let nl = saturate(dot(n, l));
    let pr = 1.0 - smoothness;
#if defined(UNITY_PBS_USE_BRDF3)
    let x = brdf_pow4(dot(reflect(v, n), l));
    let ks = brdf_lut_sample(x, pr) * BRDF_LUT_RANGE;
    return (diffuse + ks * spec_color) * light_color * nl;
#else
    let h = brdf_safe_normalize(l + v);
    let nh = saturate(dot(n, h));
    let lh = saturate(dot(l, h));
#if defined(UNITY_PBS_USE_BRDF2)
    let a = pr * pr;
    let a2 = a * a;
    let d = nh * nh * (a2 - 1.0) + 1.00001;
    let ks = a2 / (max(0.1, lh * lh) * (a + 0.5) * (d * d) * 4.0);
    return (diffuse + ks * spec_color) * light_color * nl;
#else
    let nv = abs(dot(n, v));
    let fd90 = 0.5 + 2.0 * lh * lh * pr;
    let kd = (1.0 + (fd90 - 1.0) * brdf_pow5(1.0 - nl)) * (1.0 + (fd90 - 1.0) * brdf_pow5(1.0 - nv)) * nl;
    let r = max(pr * pr, 0.002);
    let lambda_v = nl * (nv * (1.0 - r) + r);
    let lambda_l = nv * (nl * (1.0 - r) + r);
    let vis = 0.5 / (lambda_v + lambda_l + 1e-5);
    let a2 = r * r;
    let d = (nh * a2 - nh) * nh + 1.0;
    let has_specular = any(spec_color != vec3f(0.0));
    let ks = select(0.0, max(vis * a2 / (d * d + 1e-7) * nl, 0.0), has_specular);
    let fresnel = spec_color + (1.0 - spec_color) * brdf_pow5(1.0 - lh);
    return light_color * (diffuse * kd + ks * fresnel);
#endif
#endif
}
