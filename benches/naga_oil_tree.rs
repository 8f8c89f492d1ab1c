//! A naga_oil tree validated by this crate against naga_oil alone composing the same variants,
//! measured in the same run (interleaved; medians of `BENCH_ROUNDS`).
//!
//! `cargo bench --bench naga_oil_tree` runs on `tests/fixtures/naga_oil`;
//! `WGSL_VARIANTS_TREE=target/bevy-0.19.1 cargo bench --bench naga_oil_tree` on Bevy's PBR
//! shaders (assembled by `scripts/bevy.sh`). Each pass's 2-wise covering set is the work.
//!
//! - this crate: `validate_pass` (naga_oil composes each variant and validates it, naga writes
//!   it back as WGSL, which is parsed and validated again: what is validated is what is
//!   emitted), on one thread;
//! - naga_oil alone: one `Composer` with the tree's modules, `make_naga_module` per variant
//!   with the same defs (naga_oil validates the module), on one thread.
//!
//! Both keep their composers across rounds, so naga_oil's per-def-set module cache is warm
//! for both alike after the first round. Prints the ratio (this crate / naga_oil; lower is
//! faster) and writes it to `target/bench-summary.json`.

use std::collections::HashMap;

use naga_oil::compose::{
    ComposableModuleDescriptor, Composer, NagaModuleDescriptor, ShaderDefValue, ShaderLanguage,
};
use serde_json::json;
use test_support as common;
use wgsl_variants::plan::{PlanOptions, variants_to_build};
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Choice, Library, Pass, Variant};

/// naga_oil alone: a composer holding every named module of the tree (added once its imports
/// are), and the entry's text.
fn naga_oil_alone(lib: &Library) -> Composer {
    let files = lib.files();
    let mut pending: Vec<usize> = (0..lib.module_paths().len())
        .filter(|&f| files.text(f).contains("#define_import_path"))
        .collect();
    let mut composer = Composer::default();
    while !pending.is_empty() {
        let before = pending.len();
        pending.retain(|&f| {
            composer
                .add_composable_module(ComposableModuleDescriptor {
                    source: files.text(f),
                    file_path: files.path(f),
                    language: ShaderLanguage::Wgsl,
                    ..Default::default()
                })
                .is_err()
        });
        if pending.len() == before {
            // What remains imports something missing: the entries never reach it.
            break;
        }
    }
    composer
}

fn defs(pass: &Pass, keywords: &[&str]) -> HashMap<String, ShaderDefValue> {
    pass.defs(keywords.iter().copied())
        .into_iter()
        .map(|(name, value)| (name.to_string(), value.to_naga_oil()))
        .collect()
}

fn main() {
    let root = std::env::var("WGSL_VARIANTS_TREE").unwrap_or_else(|_| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/naga_oil").to_string()
    });
    let lib = Library::from_dir(&root).unwrap_or_else(|e| panic!("{root}: {e}"));
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut options = PlanOptions::default();
    options.cover = Some(2);
    let mut results = Vec::new();
    for pass in lib.passes() {
        let choices = variants_to_build(&lib, pass, &options).expect("covering set");
        // Module ids are file ids: the module the pass composes.
        let entry = lib.files().path(pass.module());
        let source = lib.files().text(pass.module());
        let mut composer = naga_oil_alone(&lib);
        let mut ours = |slice: &[Choice]| {
            one.install(|| {
                validate_pass(&lib, pass, slice, &|_| {});
            })
        };
        let mut alone = |slice: &[Choice]| {
            for c in slice {
                let v = Variant {
                    pass,
                    choice: c.clone(),
                };
                let _ = composer.make_naga_module(NagaModuleDescriptor {
                    source,
                    file_path: entry,
                    shader_defs: defs(pass, &v.keywords()),
                    ..Default::default()
                });
            }
        };
        results.push(common::versus(
            &format!("{}/{}", pass.shader, pass.name),
            ("naga_oil", "naga_oil_alone"),
            &choices,
            &mut ours,
            &mut alone,
        ));
    }
    common::write_summary(json!({ "naga_oil_tree": { "root": root, "passes": results } }));
}
