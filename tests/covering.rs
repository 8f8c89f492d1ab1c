//! Planted interaction faults: random libraries with a WGSL error that appears only when one
//! particular t-tuple of keyword values holds. The t-wise covering set must catch every one;
//! a random sample of the same size is measured for comparison (printed, not asserted).

use test_support::shaders::planted_fault_shader;
use wgsl_variants::analysis::region_aware;
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
        let (mut covering_caught, mut random_caught, mut sizes, mut region_sizes) = (0, 0, 0, 0);
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
            // The region-aware set (coupled keywords as one factor of their distinct code,
            // dead ones fixed) must catch it too.
            let regional = region_aware(&lib, &Space::full(pass), t).unwrap();
            region_sizes += regional.len();
            assert!(
                caught(&lib, &regional),
                "t={t} seed {seed}: the region-aware set missed {fault:?}"
            );
            let random: Vec<Choice> = (0..cover.len())
                .map(|_| Choice((0..n).map(|_| (rng.next() & 1) as u16).collect()))
                .collect();
            random_caught += caught(&lib, &random) as u32;
        }
        println!(
            "t={t}: {SEEDS} planted faults (8..40 sets); covering sets (mean {:.1} variants) caught {covering_caught}, region-aware sets (mean {:.1}) caught all, random samples of the covering sets' sizes caught {random_caught} (missed {})",
            sizes as f64 / SEEDS as f64,
            region_sizes as f64 / SEEDS as f64,
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

/// On the grouped 64-keyword shader (per four keywords: one with code of its own, two that
/// change code only together, one dead) the region-aware pairwise set covers 32 two-valued
/// regions: CAN(2, 32, 2) = 8 variants, against 10 for the 64 sets.
#[test]
fn region_aware_is_smaller_on_grouped_keywords() {
    let lib = Library::from_sources(test_support::shaders::keyword_shader(64, true)).unwrap();
    let space = Space::full(lib.pass("synth", "P").unwrap());
    assert_eq!(space.covering(2).unwrap().len(), 10);
    let regional = region_aware(&lib, &space, 2).unwrap();
    assert_eq!(regional.len(), 8);
    assert!(regional.iter().all(|c| space.contains(c)));
}
