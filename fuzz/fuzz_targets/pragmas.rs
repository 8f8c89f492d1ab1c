//! Fuzz target `pragmas`: see `checks::pragmas`.
#![no_main]

#[path = "../src/checks.rs"]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::pragmas(data));
