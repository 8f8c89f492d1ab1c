//! Benchmark of t-wise covering sets: sizes against the best known covering-array numbers
//! CAN(t, k, 2) of Colbourn's covering array tables (t = 2, 3; k = 10, 20, 40, 64, 128), and
//! the time to generate each, against a baseline measured in the same run (enumerating the
//! 2^20 variants of a 20-keyword pass). Mixed-size spaces (3- and 4-way sets) are reported
//! too, against the lower bound v1·v2·…·vt of their t largest sets.
//!
//! `cargo bench --bench covering` (plain `std::time::Instant`; medians of `BENCH_ROUNDS`).

use std::time::Duration;

use test_support as common;
use wgsl_variants::{Library, Space};

/// A published size and the construction that gives it; `None` where CAN(2, k, 2) is computed.
type Published = Option<(usize, &'static str)>;

/// Best known covering-array numbers CAN(t, k, 2), with where each comes from. t = 2 is exact,
/// the smallest N with C(N−1, ⌈N/2⌉) ≥ k (Kleitman & Spencer 1973; Katona 1973), and is what
/// C. J. Colbourn's "Covering Array Tables for t=2,3,4,5,6" list. The t = 3 values are that
/// table's upper bounds (status November 2024, as archived in U. Grömping's R package CAs,
/// data set `colbournBigFrame`), with the construction the table names; CAN(3, 10, 2) = 12 is
/// exact (it meets the lower bound 2·CAN(2, 9, 2)).
const CASES: [(usize, usize, Published); 11] = [
    (2, 10, None),
    (2, 20, None),
    (2, 40, None),
    (2, 64, None),
    (2, 128, None),
    (3, 10, Some((12, "exact"))),
    (3, 16, Some((17, "from t=4"))),
    (3, 20, Some((18, "CK doubling"))),
    (3, 40, Some((25, "annealing"))),
    (3, 64, Some((31, "annealing"))),
    (3, 128, Some((37, "annealing"))),
];

/// CAN(2, k, 2), exactly.
fn can2(k: usize) -> usize {
    let binomial = |n: usize, r: usize| -> u128 {
        (0..r).fold(1u128, |acc, i| acc * (n - i) as u128 / (i + 1) as u128)
    };
    (2..)
        .find(|&n: &usize| binomial(n - 1, n.div_ceil(2)) >= k as u128)
        .unwrap()
}

/// A pass of `sizes.len()` multi_compile sets, set i with `sizes[i]` options (`_` first).
fn library(sizes: &[usize]) -> Library {
    let mut pass = String::from("#shader synth\n#pass P\n");
    for (i, &n) in sizes.iter().enumerate() {
        pass.push_str("#pragma multi_compile _");
        for o in 1..n {
            pass.push_str(&format!(" K{i}_{o}"));
        }
        pass.push('\n');
    }
    pass.push_str("#endpass\n");
    Library::from_sources([("synth.wgsl", pass)]).expect("synthetic")
}

fn ms(d: Duration) -> String {
    format!("{:.2} ms", d.as_secs_f64() * 1e3)
}

fn main() {
    let rounds = common::rounds();
    let lib20 = library(&[2; 20]);
    let pass20 = lib20.pass("synth", "P").unwrap();
    let baseline = common::median(rounds, || {
        std::hint::black_box(Space::full(pass20).enumerate(1 << 20).unwrap());
    });
    println!(
        "baseline (same run): enumerate 2^20 variants: {}",
        ms(baseline)
    );
    println!();
    println!(
        "{:<26} {:>6} {:>16} {:>7} {:>12} {:>12}",
        "binary space", "ours", "table", "ratio", "time", "vs baseline"
    );
    for (t, k, quoted) in CASES {
        let (table, label) = match quoted {
            Some((n, source)) => (n, format!("{n} {source}")),
            None => (can2(k), format!("{} CAN", can2(k))),
        };
        let lib = library(&vec![2; k]);
        let pass = lib.pass("synth", "P").unwrap();
        let space = Space::full(pass);
        let size = space.covering(t).unwrap().len();
        let time = common::median(rounds, || {
            std::hint::black_box(space.covering(t).unwrap());
        });
        println!(
            "{:<26} {:>6} {:>16} {:>7.2} {:>12} {:>11.2}x",
            format!("t={t}, k={k} (2^{k})"),
            size,
            label,
            size as f64 / table as f64,
            ms(time),
            time.as_secs_f64() / baseline.as_secs_f64()
        );
    }
    println!();
    println!(
        "{:<34} {:>6} {:>12} {:>12}",
        "mixed space", "ours", "lower bound", "time"
    );
    let mixed: Vec<(&str, Vec<usize>)> = vec![
        ("3^10 4^10", [vec![3; 10], vec![4; 10]].concat()),
        (
            "2^40 3^10 4^5",
            [vec![2; 40], vec![3; 10], vec![4; 5]].concat(),
        ),
    ];
    for (name, sizes) in mixed {
        let lib = library(&sizes);
        let pass = lib.pass("synth", "P").unwrap();
        let space = Space::full(pass);
        let mut sorted = sizes.clone();
        sorted.sort_unstable_by(|a, b| b.cmp(a));
        for t in 2..=3 {
            let size = space.covering(t).unwrap().len();
            let time = common::median(rounds, || {
                std::hint::black_box(space.covering(t).unwrap());
            });
            let bound: usize = sorted[..t].iter().product();
            println!(
                "{:<34} {:>6} {:>12} {:>12}",
                format!("t={t}, {name}"),
                size,
                bound,
                ms(time)
            );
        }
    }
}
