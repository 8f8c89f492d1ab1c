//! One-shot compute dispatches: storage buffer in, storage buffer out.

use super::bindings::used_bindings;
use super::compile::{compile_scoped, wgsl_module};
use super::context::GpuContext;
use super::error::GpuError;
use super::readback::{align_up, map_buffers};

/// Runs the compute entry point `entry` of `wgsl` once and returns the first `output_len`
/// bytes of its output buffer.
///
/// Bind group 0 must declare (the auto layout keeps whichever of them the entry point uses):
///
/// - `@binding(0)`: `var<storage, read>` initialised with `input` (zero-padded to a multiple
///   of 4 bytes, at least 4);
/// - `@binding(1)`: `var<storage, read_write>` of `output_len` bytes (rounded up likewise),
///   zero-initialised.
///
/// The dispatch is `workgroups x 1 x 1`. Shader or pipeline errors come back as
/// [`GpuError::PipelineCompile`], buffers over the device limits and other wgpu errors as
/// [`GpuError::Validation`], and the wait is bounded by [`GpuContext::timeout`].
pub fn run_compute(
    ctx: &GpuContext,
    label: &str,
    wgsl: &str,
    entry: &str,
    input: &[u8],
    output_len: usize,
    workgroups: u32,
) -> Result<Vec<u8>, GpuError> {
    let invalid = |message: String| GpuError::Validation {
        label: label.to_owned(),
        message,
    };
    let limits = ctx.device.limits();
    let input_size = align_up(input.len() as u64, 4).max(4);
    let output_size = align_up(output_len as u64, 4).max(4);
    let max_binding = limits
        .max_storage_buffer_binding_size
        .min(limits.max_buffer_size);
    for (what, size) in [("input", input_size), ("output", output_size)] {
        if size > max_binding {
            return Err(invalid(format!(
                "{what} buffer of {size} bytes exceeds the storage binding limit of {max_binding} bytes"
            )));
        }
    }

    let pipeline = compile_scoped(ctx, label, || {
        let module = wgsl_module(ctx, label, wgsl);
        ctx.device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
    })?;
    let used = used_bindings(label, wgsl, &[entry])?;
    if let Some((group, binding)) = used.iter().find(|&&(g, b)| g != 0 || b > 1) {
        return Err(invalid(format!(
            "compute shader uses @group({group}) @binding({binding}); only @group(0) bindings 0 and 1 are provided"
        )));
    }

    let staging = ctx.scoped(label, || {
        let input_buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compute input"),
            size: input_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut padded = input.to_vec();
        padded.resize(input_size as usize, 0);
        ctx.queue.write_buffer(&input_buffer, 0, &padded);
        let output_buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compute output"),
            size: output_size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("compute staging"),
            size: output_size,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });

        let mut entries = Vec::new();
        if used.contains(&(0, 0)) {
            entries.push(wgpu::BindGroupEntry {
                binding: 0,
                resource: input_buffer.as_entire_binding(),
            });
        }
        if used.contains(&(0, 1)) {
            entries.push(wgpu::BindGroupEntry {
                binding: 1,
                resource: output_buffer.as_entire_binding(),
            });
        }
        let bind_group = (!entries.is_empty()).then(|| {
            ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            })
        });

        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(label),
                timestamp_writes: None,
            });
            pass.set_pipeline(&pipeline);
            if let Some(bind_group) = &bind_group {
                pass.set_bind_group(0, bind_group, &[]);
            }
            pass.dispatch_workgroups(workgroups, 1, 1);
        }
        encoder.copy_buffer_to_buffer(&output_buffer, 0, &staging, 0, output_size);
        ctx.queue.submit([encoder.finish()]);
        staging
    })?;

    let mut out = map_buffers(ctx, label, &[&staging])?
        .pop()
        .unwrap_or_default();
    out.truncate(output_len);
    Ok(out)
}
