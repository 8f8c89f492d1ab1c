//! The GPU proof of the library's pure functions: compute kernels that `#import`
//! `deferred/gbuffer`, `deferred/ldr` and `deferred/probe`, run over seeded random inputs and
//! edge cases, compared value by value with the CPU reference (`check::run` with the `kernels`
//! selection).
//!
//! Without a wgpu adapter the tests print a loud SKIPPED line and pass, unless `CI=true` or
//! `WGSL_VARIANTS_REQUIRE_GPU=1`. `WGSL_VARIANTS_ADAPTER=<substring>` selects an adapter.

mod common;

use wgsl_variants::Library;
use wgsl_variants::source::RawFile;
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport, KERNELS, kernels};
use wgsl_variants_shaders::files as bundled_files;

fn run(lib: &Library, pass: Option<&str>) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some(KERNELS.to_owned());
    options.pass = pass.map(str::to_owned);
    options.adapter = common::gpu::adapter_filter();
    options.threads = 1;
    options.sample = 1;
    options.shard = None;
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

#[test]
fn every_kernel_matches_the_reference() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let Some(report) = run(&lib, None) else {
        return;
    };
    assert_eq!(report.kernels.len(), kernels::KERNELS.len());
    for k in &report.kernels {
        eprintln!(
            "kernel {} on {}: {} cases, {} values compared, {} mismatches",
            k.name, report.adapter, k.cases, k.values_compared, k.mismatches
        );
        assert!(k.cases > 0 && k.values_compared >= k.cases, "{report}");
    }
    assert!(report.passed(), "{report}");
    eprintln!(
        "compared {} values over {} kernel cases",
        report
            .kernels
            .iter()
            .map(|k| k.values_compared)
            .sum::<usize>(),
        report.kernel_cases()
    );
}

/// The kernels are not vacuous: an LDR encoding that is off by 0.1 % fails `ldr_encode`,
/// `ldr_accumulate` and `gbuffer_pack`, and a falloff that treats `b = 0` as "always 1" fails
/// `probe_falloff`.
#[test]
fn a_wrong_module_fails_its_kernels() {
    let mutate = |path: &str, from: &str, to: &str| {
        let raw: Vec<RawFile> = bundled_files()
            .into_iter()
            .map(|mut f| {
                if f.path == path {
                    let text = String::from_utf8(f.bytes).unwrap();
                    let wrong = text.replace(from, to);
                    assert_ne!(text, wrong, "the mutation of {path} applies");
                    f.bytes = wrong.into_bytes();
                }
                f
            })
            .collect();
        Library::from_raw(raw, &Default::default()).unwrap()
    };
    let lib = mutate(
        "deferred/ldr.wgsl",
        "return exp2(-min(x, vec3f(200.0)));",
        "return exp2(-min(x, vec3f(200.0))) * 1.001;",
    );
    let Some(report) = run(&lib, None) else {
        return;
    };
    let failed: Vec<&str> = report
        .kernels
        .iter()
        .filter(|k| k.mismatches > 0)
        .map(|k| k.name.as_str())
        .collect();
    assert_eq!(
        failed,
        ["gbuffer_pack", "ldr_encode", "ldr_accumulate"],
        "{report}"
    );

    let lib = mutate(
        "deferred/probe.wgsl",
        "return select(0.0, 1.0, all(dist == vec3f(0.0)));",
        "return 1.0;",
    );
    let Some(report) = run(&lib, Some("probe_falloff")) else {
        return;
    };
    let k = &report.kernels[0];
    assert!(k.mismatches > 0, "{report}");
    eprintln!("a wrong falloff is caught: {}", k.first_mismatches[0]);
}
