//! Fuzz target `declaration`: see `checks::declaration`.
#![no_main]

use wgsl_variants_fuzz_checks as checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::declaration(data));
