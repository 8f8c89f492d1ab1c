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

/// Checks a 3-wise covering set of `standard/<pass>` plus, for each of its `keywords`, a
/// partner pair whose reference says the keyword matters, and asserts that it passed with
/// every keyword seen to change pixels; returns the report's pass (`None`: skipped).
pub fn standard_covering_set_matches(
    lib: &wgsl_variants::Library,
    pass: &str,
    keywords: usize,
) -> Option<wgsl_variants_gpu::check::PassReport> {
    let mut options = wgsl_variants_gpu::check::CheckOptions::default();
    options.shader = Some("standard".to_owned());
    options.pass = Some(pass.to_owned());
    options.adapter = adapter_filter();
    options.cover = Some(3);
    let report = or_skip(
        wgsl_variants_gpu::check::run(lib, &options),
        "the GPU check",
    )?;
    let p = report.passes[0].clone();
    let space = lib.pass("standard", pass).unwrap();
    let covering = wgsl_variants::Space::full(space).covering(3).unwrap().len();
    eprintln!(
        "standard/{pass} on {}: {} pixels over {} variants ({covering} covering, {} discarded) in {:.1} s",
        report.adapter, p.pixels_compared, p.variants_run, p.discarded_compared, p.seconds
    );
    assert!(p.passed(), "{report}");
    assert_eq!(p.mismatches, 0, "{report}");
    assert!(
        p.variants_run > covering && p.variants_run <= covering + keywords,
        "{report}"
    );
    assert!(p.pixels_compared > 0 && p.draws > 0, "{report}");
    assert_eq!(
        p.keywords.len(),
        keywords,
        "every keyword of the pass is covered"
    );
    assert!(p.untested_keywords.is_empty(), "{report}");
    Some(p)
}
