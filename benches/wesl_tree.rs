//! A WESL tree validated by this crate against the `wesl` crate alone compiling the same
//! variants and naga validating its output, measured in the same run (interleaved; medians of
//! `BENCH_ROUNDS`).
//!
//! `cargo bench --bench wesl_tree` runs on `tests/fixtures/wesl`; `WGSL_VARIANTS_TREE=DIR cargo
//! bench --bench wesl_tree` on any WESL tree, e.g. the bundled library exported with
//! `wgsl-variants export --dialect wesl --all --out DIR`. Each pass's 2-wise covering set is
//! the work.
//!
//! - this crate: `validate_pass` (wesl compiles each variant from the loaded tree, its
//!   declarations are put in a fixed order, naga parses and validates it; then the validation
//!   stage parses and validates that text: what is validated is what is emitted), one thread;
//! - wesl alone: `wesl::Compiler` reading the files itself, the same features and constants,
//!   `compile`, then naga's parse and validation of the output, one thread.
//!
//! Prints the ratio (this crate / wesl alone; lower is faster) and writes it to
//! `target/bench-summary.json`.

use serde_json::json;
use test_support as common;
use wgsl_types::inst::LiteralInstance;
use wgsl_variants::declaration::{DefValue, def_of};
use wgsl_variants::plan::{PlanOptions, variants_to_build};
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Choice, Library, Variant};

/// The `wesl` crate's value for a def.
fn literal(value: DefValue) -> LiteralInstance {
    match value {
        DefValue::Bool(b) => LiteralInstance::Bool(b),
        DefValue::Int(i) => LiteralInstance::AbstractInt(i.into()),
        DefValue::UInt(u) => LiteralInstance::U32(u),
    }
}

fn main() {
    let root = std::env::var("WGSL_VARIANTS_TREE").unwrap_or_else(|_| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/wesl").to_string()
    });
    let lib = Library::from_dir(&root).unwrap_or_else(|e| panic!("{root}: {e}"));
    assert_eq!(
        lib.dialect(),
        wgsl_variants::Dialect::Wesl,
        "{root}: not a WESL tree"
    );
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut options = PlanOptions::default();
    options.cover = Some(2);
    let mut results = Vec::new();
    for pass in lib.passes() {
        let choices = variants_to_build(&lib, pass, &options).expect("covering set");
        let entry = &lib.module_paths()[pass.module()];
        let module_path: wesl::syntax::ModulePath =
            format!("package::{}", entry.replace('/', "::"))
                .parse()
                .expect("module path");
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
                // As the engine composes (src/library/wesl.rs): keywords off unless set, every
                // def a constant, a Bool def a feature, a valued def a feature that is on.
                let mut options = wesl::CompileOptions::default();
                for k in pass.keywords() {
                    options.features.set(def_of(k).0, false);
                }
                for (name, value) in pass.defs(v.keywords()) {
                    options
                        .features
                        .set(name, !matches!(value, DefValue::Bool(false)));
                    options.constants.set(name, literal(value));
                }
                let compiler = wesl::Compiler::new(options);
                if let Ok(out) = compiler.compile_module(&root, &module_path)
                    && let Ok(module) = naga::front::wgsl::parse_str(&out.to_string())
                {
                    let _ = wgsl_variants::validate::validator().validate(&module);
                }
            }
        };
        results.push(common::versus(
            &format!("{}/{}", pass.shader, pass.name),
            ("wesl", "wesl_alone"),
            &choices,
            &mut ours,
            &mut alone,
        ));
    }
    common::write_summary(json!({ "wesl_tree": { "root": root, "passes": results } }));
}
