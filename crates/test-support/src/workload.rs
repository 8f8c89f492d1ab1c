//! The work every build bench measures: the final texts of a pass's variants and the naga
//! floor over them. Shared by `benches/build.rs` and the WESL crate.

use naga::valid::Validator;
pub use wgsl_variants::validate::validator;
use wgsl_variants::{Choice, Library, Pass, Variant};

/// The naga floor: parse + validate final texts.
pub fn naga_floor(validator: &mut Validator, texts: &[String]) {
    for text in texts {
        let module = naga::front::wgsl::parse_str(text).expect("parses");
        validator.validate(&module).expect("valid");
    }
}

/// This crate's final (lean) text of each variant: what it validates, and what the floor parses.
pub fn final_texts(lib: &Library, pass: &Pass, choices: &[Choice]) -> Vec<String> {
    choices
        .iter()
        .map(|c| {
            lib.wgsl(&Variant {
                pass,
                choice: c.clone(),
            })
        })
        .collect()
}
