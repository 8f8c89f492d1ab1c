//! Fuzz target `preprocess`: see `checks::preprocess`.
#![no_main]

#[path = "../src/checks.rs"]
mod checks;

libfuzzer_sys::fuzz_target!(|data: &[u8]| checks::preprocess(data));
