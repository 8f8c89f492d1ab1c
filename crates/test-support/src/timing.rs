//! Timing and the summary file, shared by every bench (also by the WESL comparison crate
//! under `benches/wesl/`, which includes this file by path).

use std::path::PathBuf;
use std::time::{Duration, Instant};

use serde_json::{Value, json};

/// Rounds per measurement: `BENCH_ROUNDS`, default 5.
pub fn rounds() -> usize {
    std::env::var("BENCH_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(5)
}

/// Median wall time of `rounds` runs of `f` (after one warm-up run).
pub fn median(rounds: usize, mut f: impl FnMut()) -> Duration {
    f();
    let mut times: Vec<Duration> = (0..rounds.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    times.sort();
    times[times.len() / 2]
}

/// The median of some durations.
pub fn median_of(times: &[Duration]) -> Duration {
    let mut times = times.to_vec();
    times.sort();
    times[times.len() / 2]
}

/// The median over rounds of `a[r] / b[r]`: a paired ratio, so that a slow moment of the
/// machine, which slows both sides of a round alike, does not move it.
pub fn median_ratio(a: &[Duration], b: &[Duration]) -> f64 {
    let mut ratios: Vec<f64> = a
        .iter()
        .zip(b)
        .map(|(a, b)| a.as_secs_f64() / b.as_secs_f64())
        .collect();
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// Times contestants doing the same work, interleaved: in each round every contestant runs
/// on each of `slices` slices of the work in turn, the order rotating, so that drift of a
/// noisy machine falls on all of them alike. Returns, per contestant, its total time in each
/// round (after one warm-up pass over the first slice).
pub fn interleaved(
    rounds: usize,
    slices: usize,
    contestants: &mut [&mut dyn FnMut(usize)],
) -> Vec<Vec<Duration>> {
    let n = contestants.len();
    for c in contestants.iter_mut() {
        c(0);
    }
    let mut totals = vec![vec![Duration::ZERO; rounds.max(1)]; n];
    for (round, step) in (0..rounds.max(1)).flat_map(|r| (0..slices).map(move |s| (r, s))) {
        for k in 0..n {
            let c = (k + round + step) % n;
            let t = Instant::now();
            contestants[c](step);
            totals[c][round] += t.elapsed();
        }
    }
    totals
}

/// One pass's variants (`choices`, labelled `label`) timed two ways, interleaved over up to
/// 8 slices: `ours` and `alone` (the same variants by another engine, named `alone_name` in the
/// printed line and `alone_key` in the JSON). Prints one line and returns the figures
/// (`ours_ms`, `{alone_key}_ms`, `ratio_vs_{alone_key}`: ours / alone, lower is faster).
pub fn versus<C>(
    label: &str,
    (alone_name, alone_key): (&str, &str),
    choices: &[C],
    ours: &mut dyn FnMut(&[C]),
    alone: &mut dyn FnMut(&[C]),
) -> Value {
    let slices = choices.len().clamp(1, 8);
    let per = choices.len().div_ceil(slices).max(1);
    // The last slices may be short or empty (12 variants in 8 slices of 2).
    let slice =
        |s: usize| &choices[(s * per).min(choices.len())..((s + 1) * per).min(choices.len())];
    let mut a = |s: usize| ours(slice(s));
    let mut b = |s: usize| alone(slice(s));
    let times = interleaved(rounds(), slices, &mut [&mut a, &mut b]);
    let ratio = median_ratio(&times[0], &times[1]);
    let (t_ours, t_alone) = (median_of(&times[0]), median_of(&times[1]));
    println!(
        "{label}: {} covering variants: this crate {:.1} ms, {alone_name} alone {:.1} ms, ratio {ratio:.2}",
        choices.len(),
        t_ours.as_secs_f64() * 1e3,
        t_alone.as_secs_f64() * 1e3,
    );
    json!({
        "pass": label,
        "variants": choices.len(),
        "ours_ms": t_ours.as_secs_f64() * 1e3,
        format!("{alone_key}_ms"): t_alone.as_secs_f64() * 1e3,
        format!("ratio_vs_{alone_key}"): ratio,
    })
}

/// What the numbers were measured on.
pub fn machine() -> Value {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_default();
    json!({ "cpu": cpu, "cores": std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1) })
}

/// `bench-summary.json` in cargo's target folder: `CARGO_TARGET_DIR`, else the `target` folder
/// the running bench was built into (this crate's own folder is not the workspace's).
fn summary_path() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .or_else(|| {
            let exe = std::env::current_exe().ok()?;
            exe.ancestors()
                .find(|p| p.file_name().is_some_and(|n| n == "target"))
                .map(PathBuf::from)
        })
        .unwrap_or_else(|| PathBuf::from("target"));
    target.join("bench-summary.json")
}

/// Merges `values` (an object) into `target/bench-summary.json`, so every bench adds its
/// measurements to one file.
pub fn write_summary(values: Value) {
    let path = summary_path();
    let mut summary: Value = std::fs::read_to_string(&path)
        .ok()
        .and_then(|s| serde_json::from_str(&s).ok())
        .unwrap_or_else(|| json!({}));
    if let (Some(into), Some(from)) = (summary.as_object_mut(), values.as_object()) {
        for (k, v) in from {
            into.insert(k.clone(), v.clone());
        }
    }
    let text = serde_json::to_string_pretty(&summary).expect("json");
    std::fs::create_dir_all(path.parent().expect("parent")).expect("target dir");
    std::fs::write(&path, text + "\n").expect("write bench summary");
    println!("wrote {}", path.display());
}
