//! Build + validate speed against the naga floor (and naga_oil), measured in the same run.
//!
//! `cargo bench --bench build` prints a table and writes `target/bench-summary.json` with each
//! measurement and the ratios `ratio_vs_naga_floor` and `ratio_vs_naga_oil` (lower is faster).
//! Every figure is the median of several rounds; ratios compare figures from this run only.

mod common;

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

fn naga_floor(texts: &[String]) {
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    );
    for text in texts {
        let module = naga::front::wgsl::parse_str(text).expect("parses");
        validator.validate(&module).expect("valid");
    }
}

fn main() {
    if common::memory_child() {
        return;
    }
    let rounds = std::env::var("BENCH_ROUNDS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(3);
    let lib = Library::bundled().expect("bundled library");
    let pass = lib.pass("standard", "Deferred").expect("Deferred");
    let choices = Space::full(pass).enumerate(1_000_000).expect("enumerable");
    let n = choices.len() as f64;
    let texts: Vec<String> = choices
        .iter()
        .map(|c| {
            lib.wgsl(&Variant {
                pass,
                choice: c.clone(),
            })
        })
        .collect();
    let bytes = texts.iter().map(String::len).sum::<usize>() as f64 / n;
    println!(
        "standard/Deferred: {} variants, composed texts {:.1} KB on average",
        choices.len(),
        bytes / 1024.0
    );

    let one = pool(1);
    let two = pool(2);
    let floor = common::median(rounds, || one.install(|| naga_floor(&texts)));
    let ours = common::median(rounds, || {
        one.install(|| assert_eq!(validate_pass(&lib, pass, &choices, &|_| {}).invalid, 0));
    });
    let ours_2 = common::median(rounds, || {
        two.install(|| assert_eq!(validate_pass(&lib, pass, &choices, &|_| {}).invalid, 0));
    });
    let floor_2 = common::median(rounds, || {
        two.install(|| texts.par_chunks(64).for_each(naga_floor))
    });
    let naga_oil = common::naga_oil_deferred(&lib, pass, &choices, rounds);
    let naga_oil_cold = common::naga_oil_cold(&lib, rounds * 3);

    let one_variant = &choices[choices.len() / 2];
    let cold = common::median(rounds * 3, || {
        let lib = Library::bundled().expect("bundled");
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
    let ratio_floor = ours.as_secs_f64() / floor.as_secs_f64();
    let ratio_oil = naga_oil.map(|o| ours.as_secs_f64() / o.as_secs_f64());
    println!(
        "{:<46} {:>10} {:>12}",
        "measurement (3072 variants, median)", "total", "per variant"
    );
    for (name, d) in [
        ("naga floor: parse + validate final texts, 1 thread", floor),
        ("wgsl-variants: compose + validate, 1 thread", ours),
        ("naga floor, 2 threads", floor_2),
        ("wgsl-variants, 2 threads", ours_2),
    ] {
        println!(
            "{name:<46} {:>8.0}ms {:>9.3}ms",
            d.as_secs_f64() * 1e3,
            per(d)
        );
    }
    if let Some(o) = naga_oil {
        println!(
            "{:<46} {:>8.0}ms {:>9.3}ms",
            "naga_oil 0.23: compose + validate, 1 thread",
            o.as_secs_f64() * 1e3,
            per(o)
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
    println!(
        "ratio vs naga floor (1 thread): {ratio_floor:.3}   speed-up on 2 threads: {:.2}x",
        ours.as_secs_f64() / ours_2.as_secs_f64()
    );
    if let Some(r) = ratio_oil {
        println!(
            "ratio vs naga_oil (1 thread): {r:.3} ({:.2}x faster)",
            1.0 / r
        );
    }

    let memory = common::memory_flatness();
    common::write_summary(json!({
        "machine": common::machine(),
        "rounds": rounds,
        "variants": choices.len(),
        "composed_bytes_avg": bytes,
        "naga_floor_ms_per_variant": per(floor),
        "ours_ms_per_variant": per(ours),
        "ours_2_threads_ms_per_variant": per(ours_2),
        "naga_floor_2_threads_ms_per_variant": per(floor_2),
        "naga_oil_ms_per_variant": naga_oil.map(per),
        "single_variant_cold_ms": cold.as_secs_f64() * 1e3,
        "single_variant_warm_ms": warm.as_secs_f64() * 1e3,
        "naga_oil_cold_start_ms": naga_oil_cold.map(|c| c.as_secs_f64() * 1e3),
        "ratio_vs_naga_floor": ratio_floor,
        "ratio_vs_naga_oil": ratio_oil,
        "speedup_2_threads": ours.as_secs_f64() / ours_2.as_secs_f64(),
        "memory": memory,
    }));
}
