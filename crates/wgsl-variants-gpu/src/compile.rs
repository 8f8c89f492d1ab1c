//! Shader-module and pipeline creation inside error scopes.

use super::context::{GpuContext, error_message};
use super::error::GpuError;

/// Runs `create` (which should create the shader module and the pipeline) inside error
/// scopes, turning any captured error into [`GpuError::PipelineCompile`] labelled `label`.
///
/// Shader-module compile errors surface here too, since the module is created inside the
/// same scopes; the first captured error (usually the shader diagnostic) is reported.
pub fn compile_scoped<T>(
    ctx: &GpuContext,
    label: &str,
    create: impl FnOnce() -> T,
) -> Result<T, GpuError> {
    ctx.check_device()?;
    match ctx.capture(create) {
        (value, None) => Ok(value),
        (_, Some(error)) => Err(GpuError::PipelineCompile {
            label: label.to_owned(),
            message: error_message(&error),
        }),
    }
}

/// Creates a WGSL shader module (outside of any scope of its own; wrap it in
/// [`compile_scoped`] to capture errors).
pub fn wgsl_module(ctx: &GpuContext, label: &str, wgsl: &str) -> wgpu::ShaderModule {
    ctx.device
        .create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(wgsl.into()),
        })
}
