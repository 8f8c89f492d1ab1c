//! The generated bindings of `shaders/keys.wgsl` and of a bake of `baked/lit.wgsl`, for the
//! compile-fail tests in `tests/ui`: what a renderer must not be able to write with them.
//! `keys.rs` is the output of
//!
//! ```sh
//! cargo run --release --ignore-rust-version -p wgsl-variants-cli -- \
//!     --root crates/bindings-compile-fail/shaders bindings keys P \
//!     --out crates/bindings-compile-fail/src/keys.rs
//! ```
//!
//! `baked_keys.rs` is the module a `build.rs` bake with `Bake::bindings(true)` writes for
//! `baked/lit.wgsl` and `baked/materials.toml` (`wgsl_variants_bindings/lit_p.rs`). The
//! workspace's `tests/bindings.rs` fails when either is not current, and says how to
//! regenerate it.

/// The typed module of `keys/P`.
pub mod keys {
    include!("keys.rs");
}

/// The typed module of `lit/P` in a bake for `baked/materials.toml`: `Key::new` refuses what
/// the bake left out.
pub mod baked {
    include!("baked_keys.rs");
}
