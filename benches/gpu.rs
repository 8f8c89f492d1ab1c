//! The Deferred G-buffer pass at 1920×1080 against the bandwidth floor of the device: a pass
//! that writes constants to the same four targets, from the same quad, measured in the same run.
//!
//! `cargo bench --bench gpu` (needs a wgpu adapter; Mesa's lavapipe is enough). Both timings
//! include the draw, the submission and the read-back of the four targets, so the ratio is the
//! cost of the G-buffer shading over writing the same bytes.

mod common;

use serde_json::json;
use wgsl_variants::Library;
use wgsl_variants::gpu::check::TestScene;
use wgsl_variants::gpu::check::passes::standard_job;
use wgsl_variants::gpu::check::scene::DEFAULT_SEED;
use wgsl_variants::gpu::{GpuContext, render};

const CONSTANTS: &str = "
struct VertexInput {
    @location(0) position: vec3f,
    @location(1) normal: vec3f,
    @location(2) tangent: vec4f,
    @location(3) uv: vec2f,
}
struct Out {
    @location(0) rt0: vec4f,
    @location(1) rt1: vec4f,
    @location(2) rt2: vec4f,
    @location(3) rt3: vec4f,
}
@vertex fn vs_main(v: VertexInput) -> @builtin(position) vec4f {
    return vec4f(v.position.xy, 0.5, 1.0);
}
@fragment fn fs_main() -> Out {
    return Out(vec4f(0.5), vec4f(0.25), vec4f(0.5, 0.5, 1.0, 1.0), vec4f(0.75));
}
";

fn main() {
    let rounds = std::env::var("BENCH_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(3);
    let ctx = match GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref()) {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("SKIPPED: the GPU bench needs a wgpu adapter: {e}");
            return;
        }
    };
    let lib = Library::bundled().expect("bundled library");
    let keywords = [
        "_METALLIC_MAP",
        "_SMOOTHNESS_METALLIC",
        "_NORMAL_MAP",
        "_OCCLUSION_MAP",
        "_EMISSION_MAP",
        "_DETAIL_MASK",
        "_DETAIL_ALBEDO_MAP",
        "_DETAIL_NORMAL_MAP",
    ];
    let variant = lib
        .variant("standard", "Deferred", &keywords)
        .expect("variant");
    let mut scene = TestScene::new(DEFAULT_SEED);
    scene.width = 1920;
    scene.height = 1080;
    let mut deferred = standard_job(&scene, &variant.label(), &lib.wgsl(&variant), true, false);
    deferred.resources = scene.standard_resources();
    let mut floor = standard_job(&scene, "constants", CONSTANTS, true, false);
    floor.resources = Vec::new();
    let time = |job: &wgsl_variants::gpu::RenderJob| {
        common::median(rounds, || {
            render(&ctx, job).expect("renders");
        })
    };
    let shading = time(&deferred);
    let constants = time(&floor);
    let ratio = shading.as_secs_f64() / constants.as_secs_f64();
    println!("adapter: {}", ctx.adapter_name());
    println!(
        "Deferred G-buffer pass, 1920x1080, 4 MRTs: {:.1} ms",
        shading.as_secs_f64() * 1e3
    );
    println!(
        "constants to the same 4 targets (floor):   {:.1} ms",
        constants.as_secs_f64() * 1e3
    );
    println!("ratio vs the bandwidth floor: {ratio:.2}");
    common::write_summary(json!({
        "gpu_adapter": ctx.adapter_name(),
        "gpu_deferred_1080p_ms": shading.as_secs_f64() * 1e3,
        "gpu_constants_1080p_ms": constants.as_secs_f64() * 1e3,
        "gpu_ratio_vs_bandwidth_floor": ratio,
    }));
}
