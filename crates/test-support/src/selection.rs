//! Which variants the whole-library tests build.
//!
//! CI compiles the full space of every bundled pass once, as the main job (`validate --all`).
//! The tests run over this selection instead: every variant of a pass whose space holds at
//! most [`FULL_UP_TO`] variants, and a t = [`COVER_T`] covering set of a larger one (the
//! standard shader's three lit passes, 55,296, 18,432 and 110,592 variants; URP's
//! `UniversalGBuffer`, 49,152, and `UniversalForward`, 786,432). The full-space form of each
//! such test is an `#[ignore]`d test of its own, run by `cargo test --release -- --ignored`
//! (`docs/guide/testing.md` gives each command and its time).

use wgsl_variants::Library;
use wgsl_variants::plan::{Plan, PlanOptions, plan};

/// Passes with at most this many variants are built whole.
pub const FULL_UP_TO: u64 = 8192;

/// The covering strength used for larger passes.
pub const COVER_T: usize = 3;

/// [`PlanOptions`] of the selection over the full space of every pass.
pub fn options() -> PlanOptions {
    let mut options = PlanOptions::default();
    options.all = true;
    options.cover = Some(COVER_T);
    options.cover_above = Some(FULL_UP_TO);
    options
}

/// The selection's plan for `lib`.
pub fn plan_of(lib: &Library) -> Plan<'_> {
    plan(lib, &options()).expect("the bundled library plans")
}
