//! The one policy for GPU tests without an adapter: under `CI=true` or
//! `WGSL_VARIANTS_REQUIRE_GPU=1` the test fails; elsewhere it prints a loud SKIPPED banner and
//! passes. `WGSL_VARIANTS_ADAPTER=<substring>` selects an adapter by name.

use wgsl_variants_gpu::GpuError;

/// The adapter filter from `WGSL_VARIANTS_ADAPTER`.
pub fn adapter_filter() -> Option<String> {
    std::env::var("WGSL_VARIANTS_ADAPTER").ok()
}

/// `Some(value)` on success; `None` after the SKIPPED banner when there is no adapter and none
/// is required. Any other GPU error fails the test, with `what` naming the step.
pub fn or_skip<T>(result: Result<T, GpuError>, what: &str) -> Option<T> {
    match result {
        Ok(value) => Some(value),
        Err(e @ GpuError::NoAdapter { .. }) => {
            let required = std::env::var("CI").is_ok_and(|v| v == "true")
                || std::env::var("WGSL_VARIANTS_REQUIRE_GPU").is_ok_and(|v| v == "1");
            assert!(
                !required,
                "a GPU adapter is required (CI / WGSL_VARIANTS_REQUIRE_GPU): {e}"
            );
            eprintln!("==================================================================");
            eprintln!("SKIPPED: no GPU adapter: {e}");
            eprintln!("==================================================================");
            None
        }
        Err(e) => panic!("{what} failed: {e}"),
    }
}
