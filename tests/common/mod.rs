//! Pieces shared by the integration tests (each test file that needs them says `mod common;`).
#![allow(dead_code)] // each test file uses a subset

#[cfg(feature = "gpu")]
pub mod gpu;
pub mod synthetic;
