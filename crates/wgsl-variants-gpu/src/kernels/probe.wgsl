#shader check_probe
// Compute kernels over deferred/probe for the GPU check (src/gpu/check/kernels.rs). A probe is
// read as its five vec4f (position, box_min, box_max, hdr, params).
//   group 0: 0 input array<vec4f>, 1 output array<vec4f> (check/io)

#pass BoxProject
// in: r, p, probe (5) -> out: probe_box_project(r, p, probe), probe_box_project_grown(r, p, probe)
#import check/io
#import deferred/probe

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(7u) {
        return;
    }
    let base = 7u * i;
    let probe = Probe(input[base + 2u], input[base + 3u], input[base + 4u], input[base + 5u], input[base + 6u]);
    let r = input[base].xyz;
    let p = input[base + 1u].xyz;
    output[2u * i] = vec4f(probe_box_project(r, p, probe), 0.0);
    output[2u * i + 1u] = vec4f(probe_box_project_grown(r, p, probe), 0.0);
}
#endpass

#pass Mip
// in: four smoothness values -> out: probe_mip_from_smoothness of each
#import check/io
#import deferred/probe

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(1u) {
        return;
    }
    let s = input[i];
    output[i] = vec4f(
        probe_mip_from_smoothness(s.x),
        probe_mip_from_smoothness(s.y),
        probe_mip_from_smoothness(s.z),
        probe_mip_from_smoothness(s.w),
    );
}
#endpass

#pass RgbmDecode
// in: texel, hdr -> out: probe_rgbm_decode(texel, hdr)
#import check/io
#import deferred/probe

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(2u) {
        return;
    }
    output[i] = vec4f(probe_rgbm_decode(input[2u * i], input[2u * i + 1u]), 0.0);
}
#endpass

#pass ForwardBlend
// in: e0, e1, (t, _, _, _) -> out: probe_forward_blend(e0, e1, t)
#import check/io
#import deferred/probe

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(3u) {
        return;
    }
    let base = 3u * i;
    output[i] = vec4f(probe_forward_blend(input[base].xyz, input[base + 1u].xyz, input[base + 2u].x), 0.0);
}
#endpass

#pass Falloff
// in: p, probe (5) -> out: (probe_falloff(p, probe), 0, 0, 0)
#import check/io
#import deferred/probe

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(6u) {
        return;
    }
    let base = 6u * i;
    let probe = Probe(input[base + 1u], input[base + 2u], input[base + 3u], input[base + 4u], input[base + 5u]);
    output[i] = vec4f(probe_falloff(input[base].xyz, probe), 0.0, 0.0, 0.0);
}
#endpass
