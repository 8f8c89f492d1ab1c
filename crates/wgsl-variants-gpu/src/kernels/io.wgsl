// check/io: the storage buffers of the GPU check's compute kernels (src/gpu/check/kernels.rs):
// each case reads IN consecutive vec4f of `input` and writes OUT consecutive vec4f of `output`.
//   group 0: 0 input (read), 1 output (read_write)

@group(0) @binding(0) var<storage, read> input: array<vec4f>;
@group(0) @binding(1) var<storage, read_write> output: array<vec4f>;

// The number of cases of IN vec4f each in `input`.
fn io_cases(per_case: u32) -> u32 {
    return arrayLength(&input) / per_case;
}
