//! Pieces shared by the GPU tests (each test file says `mod common;`).
#![allow(dead_code)] // each test file uses a subset

pub mod gpu;
pub mod mutate;
