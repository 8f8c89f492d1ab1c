//! Planted interaction faults: random libraries with a WGSL error that appears only when one
//! particular t-tuple of keyword values holds. The t-wise covering set must catch every one;
//! a random sample of the same size is measured for comparison (printed, not asserted).

use test_support::shaders::planted_fault_shader;
use wgsl_variants::{Choice, Library, Space, Variant};

/// SplitMix64: a seeded generator so that every run plants the same faults.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Whether any of the variants fails naga validation.
fn caught(lib: &Library, variants: &[Choice]) -> bool {
    let pass = lib.pass("synth", "P").unwrap();
    variants.iter().any(|choice| {
        lib.naga_module(&Variant {
            pass,
            choice: choice.clone(),
        })
        .is_err()
    })
}

#[test]
fn covering_sets_catch_every_planted_fault() {
    const SEEDS: u64 = 300;
    for t in [2usize, 3] {
        let (mut covering_caught, mut random_caught, mut sizes) = (0, 0, 0);
        for seed in 0..SEEDS {
            let mut rng = Rng(seed * 31 + t as u64);
            let n = 8 + rng.below(33);
            let mut sets: Vec<usize> = Vec::new();
            while sets.len() < t {
                let s = rng.below(n);
                if !sets.contains(&s) {
                    sets.push(s);
                }
            }
            let fault: Vec<(usize, bool)> =
                sets.iter().map(|&s| (s, rng.next() & 1 == 1)).collect();
            let lib = Library::from_sources(planted_fault_shader(n, &fault)).unwrap();
            let pass = lib.pass("synth", "P").unwrap();
            let cover = Space::full(pass).covering(t).unwrap();
            sizes += cover.len();
            if caught(&lib, &cover) {
                covering_caught += 1;
            } else {
                panic!(
                    "t={t} seed {seed}: the covering set missed the fault {fault:?} of {n} sets"
                );
            }
            let random: Vec<Choice> = (0..cover.len())
                .map(|_| Choice((0..n).map(|_| (rng.next() & 1) as u16).collect()))
                .collect();
            random_caught += caught(&lib, &random) as u32;
        }
        println!(
            "t={t}: {SEEDS} planted faults (8..40 sets); covering sets (mean {:.1} variants) caught {covering_caught}, random samples of the same sizes caught {random_caught} (missed {})",
            sizes as f64 / SEEDS as f64,
            SEEDS as u32 - random_caught
        );
        assert_eq!(covering_caught, SEEDS);
        // The comparison must be a comparison: random samples do miss some.
        assert!(
            random_caught < SEEDS as u32,
            "t={t}: random samples caught every fault"
        );
    }
}
