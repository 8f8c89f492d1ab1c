//! Pieces shared by the GPU tests (each test file says `mod common;`).
#![allow(dead_code)] // each test file uses a subset

pub mod gpu;
pub mod mutate;

/// `ours` equals `check`, target for target, byte for byte (`what` names the draw).
pub fn assert_same_targets(what: &str, ours: &[Vec<u8>], check: &[Vec<u8>]) {
    assert_eq!(ours.len(), check.len(), "{what}: targets");
    for (i, (a, b)) in ours.iter().zip(check).enumerate() {
        assert_eq!(a.len(), b.len(), "{what}: target {i}");
        let differ = a.iter().zip(b).filter(|(x, y)| x != y).count();
        assert_eq!(
            differ,
            0,
            "{what}: target {i}: {differ} of {} bytes differ",
            a.len()
        );
    }
}
