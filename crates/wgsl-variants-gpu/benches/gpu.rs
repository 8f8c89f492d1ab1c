//! The Deferred G-buffer pass at 1920×1080 against the bandwidth floor of the device: a pass
//! that writes constants to the same four targets, from the same quad, measured in the same run.
//!
//! `cargo bench --bench gpu` (needs a wgpu adapter; Mesa's lavapipe is enough). Both timings
//! include the draw, the submission and the read-back of the four targets, so the ratio is the
//! cost of the G-buffer shading over writing the same bytes.

use test_support as common;

use serde_json::json;
use wgsl_variants_gpu::check::TestScene;
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;
use wgsl_variants_gpu::check::{StandardOutput, standard_job};
use wgsl_variants_gpu::{
    BoundResource, GpuContext, GpuResources, RenderJob, Resource, render, render_with,
};
use wgsl_variants_shaders::reference::surface::Keywords;

/// The G-buffer both draws write: LDR, no RT4.
const LDR_GBUFFER: StandardOutput = StandardOutput::GBuffer {
    hdr: false,
    shadowmask: false,
};

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

/// `count` 16×16 renders of a full-screen triangle, each with a shader of its own when
/// `distinct` (a new pipeline every time: what `check-gpu` pays per variant), else all with
/// one shader (the pipeline is cached by source after the first).
fn small_renders(ctx: &GpuContext, count: usize, distinct: bool) -> std::time::Duration {
    let resources = GpuResources::upload(
        ctx,
        "shared",
        &[BoundResource::new(
            0,
            0,
            Resource::Uniform(bytemuck::cast_slice(&[0.5f32; 4]).to_vec()),
        )],
    )
    .expect("upload");
    let start = std::time::Instant::now();
    for i in 0..count {
        let k = if distinct { i } else { 0 };
        let wgsl = format!(
            "@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {{
    let p = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(p * 2.0 - 1.0, 0.0, 1.0);
}}
struct P {{ v: vec4f }}
@group(0) @binding(0) var<uniform> p: P;
@fragment fn fs(@builtin(position) pos: vec4f) -> @location(0) vec4f {{
    return p.v * {k}.0 / {count}.0 + vec4f(pos.x / 16.0, 0.0, 0.0, 0.0);
}}"
        );
        let job = RenderJob::new(&format!("variant-{k}"), &wgsl, "vs", "fs");
        let out = render_with(ctx, &job, &resources).expect("render");
        assert_eq!(out[0].len(), 16 * 16 * 4);
    }
    start.elapsed()
}

fn main() {
    let rounds = common::rounds();
    // New pipelines must be compiled, not found in Mesa's on-disk cache from an earlier run.
    // SAFETY: set before any other thread exists (the GPU context is created after).
    unsafe { std::env::set_var("MESA_SHADER_CACHE_DISABLE", "true") };
    let ctx = match GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref()) {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("SKIPPED: the GPU bench needs a wgpu adapter: {e}");
            return;
        }
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let keywords = Keywords::EVERY_MAP.names();
    let variant = lib
        .variant("standard", "Deferred", &keywords)
        .expect("variant");
    let mut scene = TestScene::new(DEFAULT_SEED);
    scene.width = 1920;
    scene.height = 1080;
    let mut deferred = standard_job(&scene, &variant.label(), &lib.wgsl(&variant), LDR_GBUFFER);
    deferred.resources = scene.standard_resources();
    let mut floor = standard_job(&scene, "constants", CONSTANTS, LDR_GBUFFER);
    floor.resources = Vec::new();
    // Interleaved, so that a slow moment of the machine slows both alike.
    let times = common::interleaved(
        rounds,
        1,
        &mut [
            &mut |_| {
                render(&ctx, &deferred).expect("renders");
            },
            &mut |_| {
                render(&ctx, &floor).expect("renders");
            },
        ],
    );
    let shading = common::median_of(&times[0]);
    let constants = common::median_of(&times[1]);
    let ratio = common::median_ratio(&times[0], &times[1]);
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
    let count = 200;
    let new_pipelines = small_renders(&ctx, count, true);
    let cached = small_renders(&ctx, count, false);
    let pipeline_ratio = new_pipelines.as_secs_f64() / cached.as_secs_f64();
    println!(
        "{count} 16x16 renders, a new pipeline each: {:.2} ms each; one cached pipeline: {:.2} ms each (ratio {pipeline_ratio:.1})",
        new_pipelines.as_secs_f64() * 1e3 / count as f64,
        cached.as_secs_f64() * 1e3 / count as f64,
    );
    common::write_summary(json!({
        "gpu_adapter": ctx.adapter_name(),
        "gpu_small_render_new_pipeline_ms": new_pipelines.as_secs_f64() * 1e3 / count as f64,
        "gpu_small_render_cached_pipeline_ms": cached.as_secs_f64() * 1e3 / count as f64,
        "gpu_new_pipeline_ratio_vs_cached": pipeline_ratio,
        "gpu_deferred_1080p_ms": shading.as_secs_f64() * 1e3,
        "gpu_constants_1080p_ms": constants.as_secs_f64() * 1e3,
        "gpu_ratio_vs_bandwidth_floor": ratio,
    }));
}
