//! GPU time of the frame forward and deferred (docs/shading.md §12, docs/guide/gpu-proof.md):
//! the frame of `check::frame` at 1920×1080 with 1, 4, 16, 64, 256 and 1024 unshadowed point
//! lights (and the main light; without the semi-transparent objects, whose forward part both
//! paths share), rendered as a renderer does it ([`ResidentFrame`]: every target
//! stays on the GPU between passes, nothing is read back while a frame runs), each pass timed
//! with wgpu timestamp queries:
//!
//! - forward: `forward base` (ForwardBase per object), `forward add` (ForwardAdd per light and
//!   object);
//! - deferred: `G-buffer`, `lighting` (one draw per light, point lights as their volumes) and,
//!   in LDR, `final`.
//!
//! Per light count it prints the per-pass GPU times (median of `BENCH_ROUNDS` rounds, default
//! 5, the two paths interleaved), the frame's GPU time and the wall-clock time per frame
//! (recording, submission and the wait), deferred / forward, the crossover (the first light
//! count where deferred takes less GPU time), and for the deferred Lighting pass the fragments
//! it shades, its bytes read per fragment
//! (`bpp(RT0) + bpp(RT1) + bpp(RT2) + bpp(depth) + bpp(RT3)` of the formats bound, RT3 read by
//! the blend; `bpp(RT3)` written: see [`LightingTraffic`]) and, given the card's memory
//! bandwidth, the floor `bytes moved / bandwidth` and the measured time over it.
//!
//! An adapter without `TIMESTAMP_QUERY` is named as such, and the bench falls back to the wall
//! clock per frame, labelled so (also with `FRAME_TIMESTAMPS=off`).
//!
//! Environment: `FRAME_LIGHTS=1,4,16` (light counts), `FRAME_MODES=hdr,ldr` (default both),
//! `FRAME_SIZE=1920x1080`, `FRAME_BANDWIDTH_GBS=4800` (the card's memory bandwidth in GB/s:
//! H200 ≈ 4800, H100 SXM ≈ 3350), `BENCH_ROUNDS`, `WGSL_VARIANTS_ADAPTER` (adapter name
//! filter). `cargo bench -p wgsl-variants-gpu --bench frame` (needs a wgpu adapter; lavapipe
//! is enough for small light counts). Results are merged into `bench-summary.json` in the
//! target folder (`CARGO_TARGET_DIR`, else the `target` folder above the binary, else
//! `./target`).

use std::collections::BTreeMap;
use std::time::Duration;

use test_support as common;

use serde_json::{Value, json};
use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::frame::{
    FrameScene, FrameTime, LightingTraffic, ResidentFrame, render_shadows,
};

/// A comma-separated list from `var`, or `default`.
fn list<T: std::str::FromStr>(var: &str, default: Vec<T>) -> Vec<T> {
    std::env::var(var)
        .ok()
        .map(|s| s.split(',').filter_map(|n| n.trim().parse().ok()).collect())
        .filter(|v: &Vec<T>| !v.is_empty())
        .unwrap_or(default)
}

/// The median of `values` (0 for none).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(0.0)
}

/// One path's medians over the rounds.
struct PathTimes {
    /// Per pass: name and median GPU ms (empty without timestamps).
    passes: Vec<(String, f64)>,
    /// Median GPU ms of the whole frame (`None` without timestamps).
    gpu_ms: Option<f64>,
    /// Median wall-clock ms per frame.
    wall_ms: f64,
}

impl PathTimes {
    fn of(frame: &ResidentFrame, runs: &[FrameTime]) -> PathTimes {
        let names = frame.pass_names();
        let passes = if frame.timed() {
            (0..names.len())
                .map(|i| {
                    let ms = runs.iter().filter_map(|r| Some(r.passes.as_ref()?[i].ms()));
                    (names[i].to_owned(), median(ms.collect()))
                })
                .collect()
        } else {
            Vec::new()
        };
        let gpu: Vec<f64> = runs.iter().filter_map(FrameTime::gpu_ms).collect();
        PathTimes {
            passes,
            gpu_ms: (!gpu.is_empty()).then(|| median(gpu)),
            wall_ms: median(runs.iter().map(|r| r.wall.as_secs_f64() * 1e3).collect()),
        }
    }

    /// The time compared between the paths: GPU time where measured, else the wall clock.
    fn ms(&self) -> f64 {
        self.gpu_ms.unwrap_or(self.wall_ms)
    }

    fn pass_ms(&self, name: &str) -> Option<f64> {
        self.passes.iter().find(|(n, _)| n == name).map(|p| p.1)
    }

    fn json(&self) -> Value {
        let passes: serde_json::Map<String, Value> = self
            .passes
            .iter()
            .map(|(n, ms)| (n.clone(), json!(ms)))
            .collect();
        json!({ "passes_ms": passes, "gpu_ms": self.gpu_ms, "wall_ms": self.wall_ms })
    }
}

/// `x` in ms with 3 decimals (4 below 1 ms: a GPU's pass at 1080p takes tens of µs), or `-`.
fn cell(x: Option<f64>) -> String {
    match x {
        Some(x) if x.abs() < 1.0 => format!("{x:.4}"),
        Some(x) => format!("{x:.3}"),
        None => String::from("-"),
    }
}

fn main() {
    let rounds = common::rounds();
    let mut ctx = match GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref()) {
        Ok(ctx) => ctx,
        Err(e) => {
            eprintln!("SKIPPED: the frame bench needs a wgpu adapter: {e}");
            return;
        }
    };
    // 1024 lights forward on a software adapter take long; the bound is for a hung GPU.
    ctx.timeout = Duration::from_secs(600);
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let counts: Vec<usize> = list("FRAME_LIGHTS", vec![1, 4, 16, 64, 256, 1024]);
    let modes: Vec<String> = list(
        "FRAME_MODES",
        vec![String::from("hdr"), String::from("ldr")],
    );
    let size: Vec<u32> = std::env::var("FRAME_SIZE")
        .ok()
        .map(|s| s.split('x').filter_map(|n| n.trim().parse().ok()).collect())
        .filter(|v: &Vec<u32>| v.len() == 2)
        .unwrap_or(vec![1920, 1080]);
    let (w, h) = (size[0], size[1]);
    let bandwidth: Option<f64> = std::env::var("FRAME_BANDWIDTH_GBS")
        .ok()
        .and_then(|s| s.trim().parse().ok());
    let forced_off = std::env::var("FRAME_TIMESTAMPS").is_ok_and(|v| v == "off");
    let timestamps = ctx.has_timestamps() && !forced_off;
    println!(
        "adapter: {} ({:?})",
        ctx.adapter_name(),
        ctx.adapter_info().backend
    );
    let clock = if timestamps {
        println!(
            "clock: GPU timestamp queries, {} ns per tick; per-pass times are GPU time",
            ctx.queue.get_timestamp_period()
        );
        "gpu timestamps"
    } else {
        let why = if forced_off {
            "FRAME_TIMESTAMPS=off"
        } else {
            "the adapter has no TIMESTAMP_QUERY"
        };
        println!(
            "NO GPU TIMESTAMPS ({why}): no per-pass times; each frame is timed by the WALL \
             CLOCK (recording, submission and the wait for the GPU), which is not GPU time"
        );
        "wall clock"
    };
    println!(
        "{w}×{h}, {rounds} rounds, median ms; memory bandwidth: {}",
        bandwidth.map_or_else(
            || String::from("not given (FRAME_BANDWIDTH_GBS), no floor"),
            |b| format!("{b} GB/s")
        )
    );
    let mut rows = Vec::new();
    let mut crossovers = BTreeMap::new();
    for mode in &modes {
        let hdr = mode != "ldr";
        println!("\n{} ({clock})", if hdr { "HDR" } else { "LDR" });
        println!(
            "lights | fwd draws | fwd base | fwd add | forward | def draws | G-buffer | lighting | final | deferred | def / fwd | fwd wall | def wall"
        );
        let mut traffic_rows = Vec::new();
        let mut crossover = None;
        for &n in &counts {
            let frame = FrameScene::sized(w, h).with_point_lights(n);
            // The bench's point lights cast no shadows: no maps to render.
            let shadows = render_shadows(&ctx, &lib, &frame).expect("shadows");
            let prepare = |f: ResidentFrame| {
                if timestamps {
                    f
                } else {
                    f.without_timestamps()
                }
            };
            let forward = prepare(
                ResidentFrame::forward(&ctx, &lib, &frame, &shadows, hdr).expect("forward"),
            );
            let deferred = prepare(
                ResidentFrame::deferred(&ctx, &lib, &frame, &shadows, hdr).expect("deferred"),
            );
            let (mut f_runs, mut d_runs) = (Vec::new(), Vec::new());
            // One warm-up frame each, then the rounds, the order alternating.
            forward.run(&ctx).expect("forward frame");
            deferred.run(&ctx).expect("deferred frame");
            for r in 0..rounds.max(1) {
                if r % 2 == 0 {
                    f_runs.push(forward.run(&ctx).expect("forward frame"));
                    d_runs.push(deferred.run(&ctx).expect("deferred frame"));
                } else {
                    d_runs.push(deferred.run(&ctx).expect("deferred frame"));
                    f_runs.push(forward.run(&ctx).expect("forward frame"));
                }
            }
            let (f, d) = (
                PathTimes::of(&forward, &f_runs),
                PathTimes::of(&deferred, &d_runs),
            );
            let ratio = d.ms() / f.ms();
            if ratio < 1.0 && crossover.is_none() {
                crossover = Some(n);
            }
            println!(
                "{n:6} | {:9} | {:>8} | {:>7} | {:>7} | {:9} | {:>8} | {:>8} | {:>5} | {:>8} | {ratio:9.2} | {:8.2} | {:8.2}",
                forward.draws(),
                cell(f.pass_ms("forward base")),
                cell(f.pass_ms("forward add")),
                cell(f.gpu_ms),
                deferred.draws(),
                cell(d.pass_ms("G-buffer")),
                cell(d.pass_ms("lighting")),
                cell(d.pass_ms("final")),
                cell(d.gpu_ms),
                f.wall_ms,
                d.wall_ms,
            );
            let traffic = deferred
                .lighting_traffic(&ctx)
                .expect("lighting fragments")
                .expect("the deferred path counts its fragments");
            let lighting_ms = d.pass_ms("lighting");
            traffic_rows.push((n, traffic, lighting_ms));
            let floor = bandwidth.map(|b| traffic.floor_ms(b));
            rows.push(json!({
                "mode": if hdr { "hdr" } else { "ldr" },
                "lights": n,
                "forward_draws": forward.draws(),
                "forward_ms": f.ms(),
                "deferred_draws": deferred.draws(),
                "deferred_volumes": deferred.volumes(),
                "deferred_ms": d.ms(),
                "deferred_over_forward": ratio,
                "forward": f.json(),
                "deferred": d.json(),
                "lighting_fragments": traffic.fragments,
                "lighting_bytes_read_per_fragment": traffic.bytes_read_per_fragment,
                "lighting_bytes_written_per_fragment": traffic.bytes_written_per_fragment,
                "lighting_bytes_moved": traffic.bytes_moved(),
                "lighting_floor_ms": floor,
                "lighting_over_floor": lighting_ms.zip(floor).map(|(m, fl)| m / fl),
            }));
        }
        match crossover {
            Some(n) => {
                println!("crossover ({clock}): deferred takes less time from {n} point lights on")
            }
            None => {
                println!("crossover ({clock}): deferred took less time at no light count measured")
            }
        }
        crossovers.insert(mode.clone(), crossover);
        print_traffic(&traffic_rows, bandwidth);
    }
    let first = modes
        .first()
        .and_then(|m| crossovers.get(m).copied().flatten());
    common::write_summary(json!({
        "frame_adapter": ctx.adapter_name(),
        "frame_clock": clock,
        "frame_timestamps": timestamps,
        "frame_size": [w, h],
        "frame_rounds": rounds,
        "frame_bandwidth_gbs": bandwidth,
        format!("frame_{w}x{h}"): rows,
        "frame_crossover_lights": first,
        "frame_crossover_lights_by_mode": crossovers,
    }));
}

/// The deferred Lighting pass's traffic per light count, and its floor where the bandwidth is
/// known.
fn print_traffic(rows: &[(usize, LightingTraffic, Option<f64>)], bandwidth: Option<f64>) {
    println!(
        "lighting pass: lights | fragments | B read / frag | B written / frag | MB moved | floor ms | measured ms | measured / floor"
    );
    for (n, t, ms) in rows {
        let floor = bandwidth.map(|b| t.floor_ms(b));
        println!(
            "               {n:6} | {:9} | {:13} | {:16} | {:8.1} | {:>8} | {:>11} | {:>16}",
            t.fragments,
            t.bytes_read_per_fragment,
            t.bytes_written_per_fragment,
            t.bytes_moved() as f64 / 1e6,
            floor.map_or_else(|| String::from("-"), |f| format!("{f:.4}")),
            cell(*ms),
            ms.zip(floor)
                .map_or_else(|| String::from("-"), |(m, f)| format!("{:.1}", m / f)),
        );
    }
}
