//! Fuzz target `naga_oil`: see `checks::naga_oil`.
#![no_main]

use wgsl_variants_fuzz_checks as checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::naga_oil(data));
