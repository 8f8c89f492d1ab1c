#shader check_ldr
// Compute kernels over deferred/ldr for the GPU check (src/gpu/check/kernels.rs).
//   group 0: 0 input array<vec4f>, 1 output array<vec4f> (check/io)

#pass Encode
// in: c -> out: ldr_encode(c) (xyz), ldr_encode(c.www).x (w)
#import check/io
#import deferred/ldr

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(1u) {
        return;
    }
    let c = input[i];
    output[i] = vec4f(ldr_encode(c.xyz), ldr_encode(c.www).x);
}
#endpass

#pass Decode
// in: s -> out: ldr_decode(s) (xyz), ldr_decode(s.www).x (w)
#import check/io
#import deferred/ldr

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(1u) {
        return;
    }
    let s = input[i];
    output[i] = vec4f(ldr_decode(s.xyz), ldr_decode(s.www).x);
}
#endpass

#pass Accumulate
// in: stored, light -> out: ldr_accumulate(stored, light)
#import check/io
#import deferred/ldr

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= io_cases(2u) {
        return;
    }
    output[i] = vec4f(ldr_accumulate(input[2u * i].xyz, input[2u * i + 1u].xyz), 0.0);
}
#endpass
