//! What generated bindings refuse at compile time (trybuild compares rustc's errors with
//! `tests/ui/*.stderr`): a keyword combination the pass's `require` or `exclude` rules out, a
//! keyword the pass does not have, and a `vec3` array field written without its padding.
//! `TRYBUILD=overwrite` rewrites the expectations.

#[test]
fn compile_fail() {
    trybuild::TestCases::new().compile_fail("tests/ui/*.rs");
}
