//! The generated bindings of `shaders/keys.wgsl`, for the compile-fail tests in `tests/ui`:
//! what a renderer must not be able to write with them. `keys.rs` is the output of
//!
//! ```sh
//! cargo run --release --ignore-rust-version -p wgsl-variants-cli -- \
//!     --root crates/bindings-compile-fail/shaders bindings keys P \
//!     --out crates/bindings-compile-fail/src/keys.rs
//! ```
//!
//! and the workspace's `tests/bindings.rs` fails when it is not current.

/// The typed module of `keys/P`.
pub mod keys {
    include!("keys.rs");
}
