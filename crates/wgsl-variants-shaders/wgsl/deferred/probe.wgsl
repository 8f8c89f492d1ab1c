// deferred/probe: reflection probes (docs/shading.md §6, Reflection probes).
//
// Pure functions, no bindings, so compute kernels can call them. The probe record is laid out
// for a uniform buffer (5 × vec4f = 80 bytes):
//   position.xyz  probe centre o (w unused)
//   box_min.xyz   box minimum;  box_min.w = forward blend weight t of probe 0 (ForwardBase and
//                 Deferred without UNITY_ENABLE_REFLECTION_BUFFERS)
//   box_max.xyz   box maximum (w unused)
//   hdr           decode instructions (x, y, _, w): rgb · (x · α^y), α = w · (a - 1) + 1
//   params        x = box projection (0 off, > 0 on), y = blend distance b (deferred only),
//                 z = importance (deferred only; the host orders the draws), w unused
//
// Provides:
//   struct Probe
//   fn probe_box_project_bounds(r: vec3f, p: vec3f, o: vec3f, bmin: vec3f, bmax: vec3f) -> vec3f
//   fn probe_box_project(r: vec3f, p: vec3f, probe: Probe) -> vec3f
//   fn probe_box_project_grown(r: vec3f, p: vec3f, probe: Probe) -> vec3f
//   fn probe_mip_from_smoothness(s: f32) -> f32
//   fn probe_rgbm_decode(texel: vec4f, hdr: vec4f) -> vec3f
//   fn probe_sample(cube: texture_cube<f32>, samp: sampler, dir: vec3f, mip: f32, hdr: vec4f) -> vec3f
//   fn probe_forward_blend(e0: vec3f, e1: vec3f, t: f32) -> vec3f
//   fn probe_falloff(p: vec3f, probe: Probe) -> f32

struct Probe {
    position: vec4f,
    box_min: vec4f,
    box_max: vec4f,
    hdr: vec4f,
    params: vec4f,
}

// The forward blend uses probe 0 alone from this weight on.
const PROBE_BLEND_ONLY_FIRST: f32 = 0.99999;

// Box projection of the reflection direction r at world position p against the box
// [bmin, bmax] of a probe centred at o:
//   d = normalize(r); t = (bmax - p)/d where d > 0, else (bmin - p)/d; fa = min(t);
//   result = (p - o) + d · fa.
// An axis with d == 0 (either sign) is ignored (its t is +inf); nothing divides by zero.
fn probe_box_project_bounds(r: vec3f, p: vec3f, o: vec3f, bmin: vec3f, bmax: vec3f) -> vec3f {
    let d = normalize(r);
    let zero = d == vec3f(0.0);
    let safe_d = select(d, vec3f(1.0), zero);
    let t_axis = select(bmin - p, bmax - p, d > vec3f(0.0)) / safe_d;
    // +inf on ignored axes, built at run time (a constant +inf is a WGSL shader-creation error).
    let t = bitcast<vec3f>(select(bitcast<vec3u>(t_axis), vec3u(0x7f800000u), zero));
    let fa = min(min(t.x, t.y), t.z);
    return (p - o) + d * fa;
}

// The forward (and Deferred-pass) lookup direction: r itself without box projection.
fn probe_box_project(r: vec3f, p: vec3f, probe: Probe) -> vec3f {
    if probe.params.x > 0.0 {
        return probe_box_project_bounds(r, p, probe.position.xyz, probe.box_min.xyz, probe.box_max.xyz);
    }
    return r;
}

// The deferred per-pixel lookup direction: box projection against the box grown by the blend
// distance b = params.y, [box_min - b, box_max + b]; r itself without box projection.
fn probe_box_project_grown(r: vec3f, p: vec3f, probe: Probe) -> vec3f {
    if probe.params.x > 0.0 {
        let b = vec3f(probe.params.y);
        return probe_box_project_bounds(r, p, probe.position.xyz, probe.box_min.xyz - b, probe.box_max.xyz + b);
    }
    return r;
}

// Mip level for smoothness s: pr = 1 - s; pr · (1.7 - 0.7 · pr) · 6 (6 LOD steps).
fn probe_mip_from_smoothness(s: f32) -> f32 {
    let pr = 1.0 - s;
    return pr * (1.7 - 0.7 * pr) * 6.0;
}

// α^y for RGBM decoding, defined where the GPU's pow is not: y == 0 -> 1 (also for α == 0);
// α <= 0 -> 0 (α is clamped to 0 first, then 0^y = 0 for y > 0; y < 0 with α <= 0 is out of
// range and gives 0 too).
fn probe_rgbm_pow(alpha: f32, y: f32) -> f32 {
    if y == 0.0 {
        return 1.0;
    }
    if alpha <= 0.0 {
        return 0.0;
    }
    return pow(alpha, y);
}

// texel.rgb · (hdr.x · α^hdr.y) with α = hdr.w · (texel.a - 1) + 1.
fn probe_rgbm_decode(texel: vec4f, hdr: vec4f) -> vec3f {
    let alpha = hdr.w * (texel.a - 1.0) + 1.0;
    return texel.rgb * (hdr.x * probe_rgbm_pow(alpha, hdr.y));
}

// One decoded probe sample: rgbm_decode(textureSampleLevel(cube, samp, dir, mip), hdr).
fn probe_sample(cube: texture_cube<f32>, samp: sampler, dir: vec3f, mip: f32, hdr: vec4f) -> vec3f {
    return probe_rgbm_decode(textureSampleLevel(cube, samp, dir, mip), hdr);
}

// Forward two-probe blend with probe 0's weight t (probe0.box_min.w):
// t >= 0.99999 -> e0, else t · e0 + (1 - t) · e1.
fn probe_forward_blend(e0: vec3f, e1: vec3f, t: f32) -> vec3f {
    if t >= PROBE_BLEND_ONLY_FIRST {
        return e0;
    }
    return t * e0 + (1.0 - t) * e1;
}

// Deferred per-pixel weight of a probe at world position p:
//   dist = max(p - box_max, box_min - p, 0) per axis (the un-grown box);
//   falloff = saturate(1 - length(dist) / b), b = params.y.
// b <= 0: 1 inside or on the box (dist == 0), 0 outside (our rule; Unity's shader divides by b).
fn probe_falloff(p: vec3f, probe: Probe) -> f32 {
    let dist = max(max(p - probe.box_max.xyz, probe.box_min.xyz - p), vec3f(0.0));
    let b = probe.params.y;
    if b <= 0.0 {
        return select(0.0, 1.0, all(dist == vec3f(0.0)));
    }
    return saturate(1.0 - length(dist) / b);
}
