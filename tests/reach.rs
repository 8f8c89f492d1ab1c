//! Reachability (`src/reach`) on the bundled library: pruning a variant never changes its
//! program, and the audit's unreached items are reached by no variant.

use std::collections::BTreeSet;

use rayon::prelude::*;
use wgsl_variants::Library;
use wgsl_variants::plan::{PlanOptions, plan};

/// The functions, module-scope variables and named types of `text` after naga's compaction
/// (every item no entry point uses removed), by name: what the program is made of. Constants
/// are left out: naga's compaction keeps every named constant.
fn program_items(text: &str, label: &str) -> BTreeSet<String> {
    let mut module = naga::front::wgsl::parse_str(text)
        .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(text)));
    wgsl_variants::validate::validator()
        .validate(&module)
        .unwrap_or_else(|e| panic!("{label}: {}", e.emit_to_string(text)));
    naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
    let functions = module
        .functions
        .iter()
        .map(|(_, f)| format!("fn {:?}", f.name));
    let globals = module
        .global_variables
        .iter()
        .map(|(_, g)| format!("var {:?} {:?}", g.name, g.binding));
    let types = module
        .types
        .iter()
        // naga keeps the predeclared result types of `frexp` and `modf` (`__frexp_result_f32`…).
        .filter_map(|(_, t)| t.name.as_ref().filter(|n| !n.starts_with("__")))
        .map(|n| format!("type {n}"));
    let entries = module
        .entry_points
        .iter()
        .map(|e| format!("entry {}", e.name));
    functions
        .chain(globals)
        .chain(types)
        .chain(entries)
        .collect()
}

/// A pairwise covering set of every pass (every pass with at most 64 variants whole).
fn covered(lib: &Library) -> Vec<wgsl_variants::Variant<'_>> {
    let mut options = PlanOptions::default();
    options.all = true;
    options.cover = Some(2);
    options.cover_above = Some(64);
    plan(lib, &options)
        .unwrap()
        .into_iter()
        .flat_map(|(pass, choices)| {
            choices
                .into_iter()
                .map(move |choice| wgsl_variants::Variant { pass, choice })
        })
        .collect()
}

#[test]
fn pruning_keeps_every_item_the_program_uses_and_only_removes() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let variants = covered(&lib);
    let sizes: Vec<(usize, usize)> = variants
        .par_iter()
        .map(|v| {
            let label = v.label();
            let pruned = lib.compose_text(v).text;
            let full = lib.compose_unpruned(v, false).text;
            // Whole lines of the composed text, in order.
            let mut rest = full.split_inclusive('\n');
            for line in pruned.split_inclusive('\n') {
                assert!(rest.any(|l| l == line), "{label}: {line:?} is not in order");
            }
            // naga resolves every name of the pruned text (nothing the program uses was left
            // out), and its own compaction of either text keeps the same program.
            let (kept, needed) = (program_items(&pruned, &label), program_items(&full, &label));
            assert!(
                kept == needed,
                "{label}: only after pruning {:?}, only without {:?}",
                kept.difference(&needed).collect::<Vec<_>>(),
                needed.difference(&kept).collect::<Vec<_>>()
            );
            (pruned.len(), full.len())
        })
        .collect();
    let (pruned, full) = sizes.iter().fold((0, 0), |(p, f), &(a, b)| (p + a, f + b));
    eprintln!(
        "{} variants: {pruned} of {full} bytes kept ({:.1}%)",
        variants.len(),
        100.0 * pruned as f64 / full as f64
    );
    assert!(pruned < full, "nothing was pruned");
}

#[test]
fn what_the_audit_calls_unreached_is_in_no_variant() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let variants = covered(&lib);
    let mut listed = 0;
    for pass in lib.passes() {
        let unreached = wgsl_variants::analysis::unreached(&lib, pass);
        for u in &unreached {
            listed += u.names.len();
            eprintln!(
                "{}/{}: {}: {}",
                pass.shader,
                pass.name,
                u.module,
                u.names.join(", ")
            );
        }
        for v in variants.iter().filter(|v| std::ptr::eq(v.pass, pass)) {
            let (module, _) = lib.naga_module(v).unwrap();
            for u in &unreached {
                for name in &u.names {
                    let declared = module
                        .functions
                        .iter()
                        .any(|(_, f)| f.name.as_deref() == Some(name))
                        || module
                            .global_variables
                            .iter()
                            .any(|(_, g)| g.name.as_deref() == Some(name))
                        || module
                            .constants
                            .iter()
                            .any(|(_, c)| c.name.as_deref() == Some(name))
                        || module
                            .types
                            .iter()
                            .any(|(_, t)| t.name.as_deref() == Some(name));
                    assert!(
                        !declared,
                        "{}: {} from {} is in the text",
                        v.label(),
                        name,
                        u.module
                    );
                }
            }
        }
    }
    eprintln!("{listed} unreached items listed");
}
