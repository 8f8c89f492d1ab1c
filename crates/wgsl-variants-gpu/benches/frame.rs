//! The documents' performance claim, measured (docs/shading.md §12): deferred shading draws
//! each object once and each light once, forward draws each object once per light. The frame
//! of `check::frame` at 1280×720 with 1, 4, 16, 64 and 256 point lights (and the main light),
//! HDR, rendered forward (objects × lights + objects draws) and deferred (objects + lights
//! draws, each point light as its volume), interleaved, the median of `BENCH_ROUNDS` rounds
//! (default 5; 3 is enough on a slow adapter).
//!
//! `cargo bench -p wgsl-variants-gpu --bench frame` (needs a wgpu adapter; lavapipe is
//! enough). `FRAME_LIGHTS=1,4,16` picks the light counts. Both timings cover one whole frame
//! as this harness renders it: the draws, the upload of what they bind, and the read-back of
//! the result; the deferred one also reads the G-buffer back and uploads it for the lighting
//! pass (a renderer keeps it on the GPU), so its figure is an upper bound.

use test_support as common;

use serde_json::json;
use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::frame::{
    FrameScene, render_deferred, render_forward, render_shadows,
};

fn main() {
    let rounds = common::rounds();
    let ctx = match GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref()) {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("SKIPPED: the frame bench needs a wgpu adapter: {e}");
            return;
        }
    };
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let counts: Vec<usize> = std::env::var("FRAME_LIGHTS")
        .ok()
        .map(|s| s.split(',').filter_map(|n| n.trim().parse().ok()).collect())
        .unwrap_or_else(|| vec![1, 4, 16, 64, 256]);
    println!("adapter: {}", ctx.adapter_name());
    println!(
        "lights | forward draws | forward ms | deferred draws | deferred ms | deferred / forward"
    );
    let mut rows = Vec::new();
    let mut crossover = None;
    for &n in &counts {
        let frame = FrameScene::sized(1280, 720).with_point_lights(n);
        // The bench's point lights cast no shadows: no maps to render.
        let shadows = render_shadows(&ctx, &lib, &frame).expect("shadows");
        let (mut forward_draws, mut deferred_draws) = (0, 0);
        let times = common::interleaved(
            rounds,
            1,
            &mut [
                &mut |_| {
                    forward_draws = render_forward(&ctx, &lib, &frame, &shadows, true)
                        .expect("forward")
                        .draws;
                },
                &mut |_| {
                    deferred_draws = render_deferred(&ctx, &lib, &frame, &shadows, true)
                        .expect("deferred")
                        .draws;
                },
            ],
        );
        let forward = common::median_of(&times[0]).as_secs_f64() * 1e3;
        let deferred = common::median_of(&times[1]).as_secs_f64() * 1e3;
        let ratio = common::median_ratio(&times[1], &times[0]);
        println!(
            "{n:6} | {forward_draws:13} | {forward:10.1} | {deferred_draws:14} | {deferred:11.1} | {ratio:.2}"
        );
        if ratio < 1.0 && crossover.is_none() {
            crossover = Some(n);
        }
        rows.push(json!({
            "lights": n,
            "forward_draws": forward_draws,
            "forward_ms": forward,
            "deferred_draws": deferred_draws,
            "deferred_ms": deferred,
            "deferred_over_forward": ratio,
        }));
    }
    match crossover {
        Some(n) => println!("deferred is faster from {n} point lights on"),
        None => println!("deferred was not faster at any light count measured"),
    }
    common::write_summary(json!({
        "frame_adapter": ctx.adapter_name(),
        "frame_1280x720": rows,
        "frame_crossover_lights": crossover,
    }));
}
