//! Fuzz target `cache`: see `checks::cache`.
#![no_main]

use wgsl_variants_fuzz_checks as checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::cache(data));
