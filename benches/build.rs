//! Build + validate speed against the naga floor (and naga_oil), measured in the same run.
//!
//! `cargo bench --bench build` prints a table and writes `target/bench-summary.json` with each
//! measurement and the ratios `ratio_vs_naga_floor` and `ratio_vs_naga_oil` (lower is faster).
//! The contestants (the naga floor, this crate, naga_oil, and both sides again on 2 threads)
//! build the same slices of the space in turn, round after round (`BENCH_ROUNDS`, default 5),
//! so that a slow moment of a noisy machine slows them alike. Each ratio is the median over
//! rounds of the ratio within a round; times are medians over rounds.

use test_support as common;

use std::time::Duration;

use rayon::prelude::*;
use serde_json::json;
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Library, Space, Variant};

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

/// Average sizes per variant before and after reachability (`src/reach`): the lean text (what
/// is validated), the text `emit` prints (with comments), and the SPIR-V naga writes from each
/// text as it is (what a renderer that hands the text to wgpu pays), every 8th variant.
fn sizes(
    lib: &Library,
    pass: &wgsl_variants::Pass,
    choices: &[wgsl_variants::Choice],
) -> serde_json::Value {
    let spirv = |text: &str| {
        let module = naga::front::wgsl::parse_str(text).expect("parses");
        let info = common::validator().validate(&module).expect("valid");
        naga::back::spv::write_vec(&module, &info, &naga::back::spv::Options::default(), None)
            .expect("SPIR-V")
            .len()
            * 4
    };
    let per: Vec<[usize; 6]> = choices
        .par_iter()
        .enumerate()
        .map(|(i, c)| {
            let v = Variant {
                pass,
                choice: c.clone(),
            };
            let (lean, lean_all) = (lib.wgsl(&v), lib.compose_unpruned(&v, false).text);
            let emitted = lib.compose(&v).text.len();
            let emitted_all = lib.compose_unpruned(&v, true).text.len();
            let (spv, spv_all) = if i % 8 == 0 {
                (spirv(&lean), spirv(&lean_all))
            } else {
                (0, 0)
            };
            [
                lean.len(),
                lean_all.len(),
                emitted,
                emitted_all,
                spv,
                spv_all,
            ]
        })
        .collect();
    let avg = |k: usize, every: usize| {
        let n = per.iter().step_by(every).count() as f64;
        per.iter().step_by(every).map(|p| p[k]).sum::<usize>() as f64 / n / 1024.0
    };
    let rows = [
        ("lean text (validated)", avg(0, 1), avg(1, 1)),
        ("emitted text (`emit`)", avg(2, 1), avg(3, 1)),
        ("SPIR-V of the text (every 8th)", avg(4, 8), avg(5, 8)),
    ];
    println!("per variant, KB on average: after reachability / before");
    for (name, after, before) in rows {
        println!(
            "  {name:<32} {after:>7.1} / {before:>7.1} ({:.0} %)",
            100.0 * after / before
        );
    }
    json!(rows
        .iter()
        .map(|(name, after, before)| json!({"size": name, "kb_after": after, "kb_before": before}))
        .collect::<Vec<_>>())
}

fn main() {
    if common::memory_child() {
        return;
    }
    let rounds = common::rounds();
    let lib = wgsl_variants_shaders::library().expect("bundled library");
    let pass = lib.pass("standard", "Deferred").expect("Deferred");
    let choices = Space::full(pass).enumerate(1_000_000).expect("enumerable");
    let n = choices.len() as f64;
    let texts = common::final_texts(&lib, pass, &choices);
    let bytes = texts.iter().map(String::len).sum::<usize>() as f64 / n;
    println!(
        "standard/Deferred: {} variants, composed texts {:.1} KB on average",
        choices.len(),
        bytes / 1024.0
    );

    let sizes = sizes(&lib, pass, &choices);

    let one = pool(1);
    let two = pool(2);
    // Every contestant builds the same slices of the space, interleaved (see common::interleaved).
    let slices = 12;
    let per_slice = choices.len().div_ceil(slices);
    let range = |s: usize| s * per_slice..((s + 1) * per_slice).min(choices.len());
    let mut oil = common::NagaOil::new(&lib, pass, &choices);
    let mut oil_ok = oil.is_some();
    let oil_texts = oil
        .as_mut()
        .and_then(common::NagaOil::output_texts)
        .unwrap_or_default();
    let oil_bytes = oil_texts.iter().map(String::len).sum::<usize>() as f64 / n;
    let times = common::interleaved(
        rounds,
        slices,
        &mut [
            &mut |s| one.install(|| common::naga_floor(&mut common::validator(), &texts[range(s)])),
            &mut |s| {
                one.install(|| {
                    let report = validate_pass(&lib, pass, &choices[range(s)], &|_| {});
                    assert_eq!(report.invalid, 0);
                })
            },
            &mut |s| {
                if let Some(o) = oil.as_mut() {
                    oil_ok &= o.build(range(s));
                }
            },
            &mut |s| {
                two.install(|| {
                    texts[range(s)]
                        .par_chunks(16)
                        .for_each(|c| common::naga_floor(&mut common::validator(), c))
                })
            },
            &mut |s| {
                if !oil_texts.is_empty() {
                    one.install(|| {
                        common::naga_floor(&mut common::validator(), &oil_texts[range(s)])
                    })
                }
            },
            &mut |s| {
                two.install(|| {
                    let report = validate_pass(&lib, pass, &choices[range(s)], &|_| {});
                    assert_eq!(report.invalid, 0);
                })
            },
        ],
    );
    let [floor, ours, naga_oil, floor_2, oil_floor, ours_2] = [0, 1, 2, 3, 4, 5].map(|i| &times[i]);
    let naga_oil = oil_ok.then_some(naga_oil);
    let naga_oil_cold = common::naga_oil_cold(&lib, rounds * 3);

    let one_variant = &choices[choices.len() / 2];
    let cold = common::median(rounds * 3, || {
        let lib = wgsl_variants_shaders::library().expect("bundled");
        let pass = lib.pass("standard", "Deferred").expect("Deferred");
        lib.naga_module(&Variant {
            pass,
            choice: one_variant.clone(),
        })
        .expect("valid");
    });
    let warm = common::median(rounds * 3, || {
        lib.naga_module(&Variant {
            pass,
            choice: one_variant.clone(),
        })
        .expect("valid");
    });

    let per = |d: Duration| d.as_secs_f64() * 1e3 / n;
    let ratio_floor = common::median_ratio(ours, floor);
    let ratio_oil = naga_oil.map(|o| common::median_ratio(ours, o));
    let speedup = common::median_ratio(ours, ours_2);
    let floor_speedup = common::median_ratio(floor, floor_2);
    println!(
        "{:<46} {:>10} {:>12}",
        format!("{} variants, {rounds} rounds, median", choices.len()),
        "total",
        "per variant"
    );
    let mut rows = vec![
        ("naga floor: parse + validate final texts, 1 thread", floor),
        ("wgsl-variants: compose + validate, 1 thread", ours),
        ("naga floor, 2 threads", floor_2),
        ("wgsl-variants, 2 threads", ours_2),
    ];
    if let Some(o) = naga_oil {
        rows.push(("naga_oil 0.23: compose + validate, 1 thread", o));
        rows.push(("naga floor on naga_oil's own outputs", oil_floor));
    }
    for (name, times) in rows {
        let d = common::median_of(times);
        println!(
            "{name:<46} {:>8.0}ms {:>9.3}ms",
            d.as_secs_f64() * 1e3,
            per(d)
        );
    }
    println!(
        "single variant: cold (load library + build) {:.2} ms, warm {:.3} ms",
        cold.as_secs_f64() * 1e3,
        warm.as_secs_f64() * 1e3
    );
    if let Some(c) = naga_oil_cold {
        println!(
            "naga_oil cold start (new Composer + register the modules): {:.2} ms",
            c.as_secs_f64() * 1e3
        );
    }
    let oil_over_own_floor = naga_oil.map(|o| common::median_ratio(o, oil_floor));
    if naga_oil.is_some() {
        println!(
            "naga_oil's outputs (written back to WGSL): {:.1} KB on average (ours {:.1} KB)",
            oil_bytes / 1024.0,
            bytes / 1024.0
        );
    }
    println!("ratios are medians over rounds of the ratio within each round:");
    println!("  ratio vs naga floor (1 thread): {ratio_floor:.3}");
    println!("  speed-up on 2 threads: {speedup:.2}x (the naga floor itself: {floor_speedup:.2}x)");
    if let Some(r) = ratio_oil {
        println!(
            "  ratio vs naga_oil (1 thread): {r:.3} ({:.2}x faster)",
            1.0 / r
        );
    }
    if let Some(r) = oil_over_own_floor {
        println!("  naga_oil vs the naga floor of its own outputs: {r:.3}");
    }

    let memory = common::memory_flatness();
    common::write_summary(json!({
        "machine": common::machine(),
        "rounds": rounds,
        "variants": choices.len(),
        "composed_bytes_avg": bytes,
        "sizes_before_and_after_reachability": sizes,
        "method": "contestants interleaved slice by slice; ratios are medians of per-round ratios",
        "naga_floor_ms_per_variant": per(common::median_of(floor)),
        "ours_ms_per_variant": per(common::median_of(ours)),
        "ours_2_threads_ms_per_variant": per(common::median_of(ours_2)),
        "naga_floor_2_threads_ms_per_variant": per(common::median_of(floor_2)),
        "naga_oil_ms_per_variant": naga_oil.map(|o| per(common::median_of(o))),
        "single_variant_cold_ms": cold.as_secs_f64() * 1e3,
        "single_variant_warm_ms": warm.as_secs_f64() * 1e3,
        "naga_oil_cold_start_ms": naga_oil_cold.map(|c| c.as_secs_f64() * 1e3),
        "ratio_vs_naga_floor": ratio_floor,
        "ratio_vs_naga_oil": ratio_oil,
        "naga_oil_ratio_vs_own_output_floor": oil_over_own_floor,
        "naga_oil_output_bytes_avg": naga_oil.map(|_| oil_bytes),
        "speedup_2_threads": speedup,
        "naga_floor_speedup_2_threads": floor_speedup,
        "memory": memory,
    }));
}
