//! Which `@group/@binding` resources a set of entry points actually uses (naga reflection).
//!
//! wgpu's automatic pipeline layout (`layout: None`) only contains the bindings that the
//! pipeline's entry points statically use, so binding anything else is a validation error.
//! These helpers compute exactly that set, the same way wgpu does (naga's per-entry-point
//! global-use analysis).

use std::collections::BTreeSet;

use super::error::GpuError;

/// A resource slot: `(group, binding)`.
pub type Slot = (u32, u32);

/// Parses and validates `wgsl` with naga and returns the `(group, binding)` slots statically
/// used by the named entry points (any stage).
///
/// Parse or validation failures, and entry points that do not exist, are reported as
/// [`GpuError::PipelineCompile`] labelled `label`.
pub fn used_bindings(
    label: &str,
    wgsl: &str,
    entries: &[&str],
) -> Result<BTreeSet<Slot>, GpuError> {
    let fail = |message: String| GpuError::PipelineCompile {
        label: label.to_owned(),
        message,
    };
    let module = naga::front::wgsl::parse_str(wgsl).map_err(|e| fail(e.emit_to_string(wgsl)))?;
    let info = wgsl_variants::validate::validator()
        .validate(&module)
        .map_err(|e| fail(e.emit_to_string(wgsl)))?;
    used_bindings_in(label, &module, &info, entries)
}

/// Like [`used_bindings`], for a module the caller has already parsed and validated.
pub fn used_bindings_in(
    label: &str,
    module: &naga::Module,
    info: &naga::valid::ModuleInfo,
    entries: &[&str],
) -> Result<BTreeSet<Slot>, GpuError> {
    let mut used = BTreeSet::new();
    for name in entries {
        let index = module
            .entry_points
            .iter()
            .position(|ep| ep.name == *name)
            .ok_or_else(|| GpuError::PipelineCompile {
                label: label.to_owned(),
                message: format!("entry point `{name}` not found"),
            })?;
        let function_info = info.get_entry_point(index);
        for (handle, var) in module.global_variables.iter() {
            if let Some(binding) = &var.binding
                && !function_info[handle].is_empty()
            {
                used.insert((binding.group, binding.binding));
            }
        }
    }
    Ok(used)
}
