//! Fuzz target `lean`: see `checks::lean`.
#![no_main]

use wgsl_variants_fuzz_checks as checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::lean(data));
