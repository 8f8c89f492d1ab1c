//! Benchmark of the audit: exact distinct counts of synthetic 20-, 40- and 64-keyword shaders
//! (2^20, 2^40 and 2^64 variants) without enumerating them, against two baselines measured in
//! the same run: auditing the 20-keyword shader by enumeration (compose all 2^20 variants and
//! hash their texts) and one naga parse + validate of a bundled variant.
//!
//! `cargo bench --bench audit` (plain `std::time::Instant`; medians of several runs).

use test_support as common;
use test_support::shaders;

use std::collections::HashSet;
use std::hash::{DefaultHasher, Hash, Hasher};
use std::hint::black_box;
use std::time::{Duration, Instant};

use wgsl_variants::audit::{self, AuditOptions};
use wgsl_variants::{Library, Space, Variant};

/// The synthetic keyword shader of the audit's tests, as a library.
fn synthetic(n: usize, grouped: bool) -> Library {
    Library::from_sources(shaders::keyword_shader(n, grouped)).expect("synthetic")
}

fn ms(d: Duration) -> String {
    format!("{:.3} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let options = AuditOptions::default();

    // Baseline 1: the 20-keyword shader audited by enumeration.
    let lib20 = synthetic(20, false);
    let pass20 = lib20.pass("synth", "P").unwrap();
    let t = Instant::now();
    let choices = Space::full(pass20).enumerate(1 << 20).unwrap();
    let hashes: HashSet<u64> = choices
        .into_iter()
        .map(|choice| {
            let text = lib20.wgsl(&Variant {
                pass: pass20,
                choice,
            });
            let mut h = DefaultHasher::new();
            text.hash(&mut h);
            h.finish()
        })
        .collect();
    let enumeration = t.elapsed();
    assert_eq!(hashes.len(), 1 << 20);

    // Baseline 2: one naga parse + validate of a bundled variant.
    let bundled = wgsl_variants_shaders::library().unwrap();
    let variant = bundled
        .variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"])
        .unwrap();
    let naga = common::median(21, || {
        black_box(bundled.naga_module(&variant).unwrap());
    });

    println!("baselines (same run):");
    println!(
        "  audit of 20 keywords by enumeration (2^20 composes): {}",
        ms(enumeration)
    );
    println!(
        "  one naga parse + validate of standard/Deferred:     {}",
        ms(naga)
    );
    println!();
    println!(
        "{:<44} {:>12} {:>14} {:>12} {:>22}",
        "exact audit (no enumeration)", "median", "vs enumerate", "vs naga", "distinct"
    );
    let cases: Vec<(&str, Library)> = vec![
        (
            "20 keywords, each guards its own code",
            synthetic(20, false),
        ),
        (
            "40 keywords, each guards its own code",
            synthetic(40, false),
        ),
        ("40 keywords, dead and coupled ones", synthetic(40, true)),
        (
            "64 keywords, each guards its own code",
            synthetic(64, false),
        ),
        ("64 keywords, dead and coupled ones", synthetic(64, true)),
        (
            "bundled standard/Deferred (6144 variants)",
            wgsl_variants_shaders::library().unwrap(),
        ),
    ];
    for (name, lib) in &cases {
        let pass = lib
            .pass("synth", "P")
            .or_else(|_| lib.pass("standard", "Deferred"))
            .unwrap();
        let mut distinct = String::new();
        let time = common::median(11, || {
            let a = audit::audit_pass(lib, pass, &options).unwrap();
            assert!(a.distinct.exact);
            distinct = a.distinct.count.to_string();
        });
        println!(
            "{:<44} {:>12} {:>13.0}x {:>11.2}x {:>22}",
            name,
            ms(time),
            enumeration.as_secs_f64() / time.as_secs_f64(),
            time.as_secs_f64() / naga.as_secs_f64(),
            distinct
        );
    }
    println!();
    println!("vs enumerate: how many times faster than the enumeration baseline;");
    println!("vs naga: the audit's time in units of one naga parse + validate.");
}
