//! The variants a run validates before its full sweep: those most likely to show what a
//! change broke, soon.

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

use crate::cache::ValidCache;
use crate::error::VariantError;
use crate::library::{Library, Variant};
use crate::plan::{Plan, PlanOptions, variants_to_build};
use crate::validate::{Validators, validate_variant};
use crate::variants::Choice;

use super::Recent;

/// A pass built whole, not covered, in the early step when its plan has at most this many
/// variants.
const WHOLE: usize = 64;

/// The early variants of the `stale` passes of `plan` (indices into it), in order: the
/// recently failing keyword sets (most recent first) that the plan still builds, then a
/// pairwise covering set of each pass (its first [`WHOLE`] variants when it is that small or
/// cannot be covered; the plan's own order when the plan is a covering set already).
pub(super) fn candidates<'l>(
    lib: &Library,
    plan: &Plan<'l>,
    stale: &[usize],
    recent: &[Recent],
    options: &PlanOptions,
) -> Vec<Variant<'l>> {
    let mut out = Vec::new();
    for r in recent {
        let Some(&i) = stale
            .iter()
            .find(|&&i| plan[i].0.shader == r.shader && plan[i].0.name == r.pass)
        else {
            continue;
        };
        let (pass, choices) = &plan[i];
        if let Ok(choice) = pass.resolve(&r.keywords)
            && choices.contains(&choice)
        {
            out.push(Variant { pass, choice });
        }
    }
    let pairwise = PlanOptions {
        cover: Some(2),
        cover_above: None,
        budget: u64::MAX,
        ..options.clone()
    };
    for &i in stale {
        let (pass, choices) = &plan[i];
        let cover: Vec<Choice> = if options.cover.is_some() || choices.len() <= WHOLE {
            choices.iter().take(WHOLE).cloned().collect()
        } else {
            variants_to_build(lib, pass, &pairwise)
                .unwrap_or_else(|_| choices.iter().take(WHOLE).cloned().collect())
        };
        out.extend(cover.into_iter().map(|choice| Variant { pass, choice }));
    }
    out
}

/// Validates `variants` in small parallel chunks (so the first failures come out early), with
/// the cache; `found(key, error)` for each failure, in order. `false` when `cancel` stopped it.
pub(super) fn validate(
    lib: &Library,
    variants: &[Variant<'_>],
    cache: &ValidCache,
    cancel: &AtomicBool,
    found: &mut dyn FnMut(u128, &VariantError),
) -> bool {
    let chunk = 2 * rayon::current_num_threads().max(1);
    for chunk in variants.chunks(chunk) {
        if cancel.load(Ordering::Relaxed) {
            return false;
        }
        let results: Vec<(u128, Option<VariantError>)> = chunk
            .par_iter()
            .map_init(Validators::default, |v, variant| {
                validate_variant(lib, variant, Some(cache), v)
            })
            .collect();
        for (key, error) in results {
            if let Some(error) = error {
                found(key, &error);
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 81 variants: past [`WHOLE`], so the pass is covered pairwise.
    fn library() -> Library {
        Library::from_sources([(
            "s.wgsl",
            "#shader s\n#pass P\n#pragma multi_compile _ A1 A2\n#pragma multi_compile _ B1 B2\n\
             #pragma multi_compile _ C1 C2\n#pragma multi_compile _ D1 D2\n#endpass\n",
        )])
        .unwrap()
    }

    fn recent(pass: &str, keywords: &[&str]) -> Recent {
        Recent {
            shader: "s".into(),
            pass: pass.into(),
            keywords: keywords.iter().map(|k| k.to_string()).collect(),
        }
    }

    /// Recent failures of the plan come first, most recent first; those of other passes or
    /// outside the plan are left out; then a pairwise covering set, smaller than the pass.
    #[test]
    fn recent_failures_then_a_pairwise_cover() {
        let lib = library();
        let options = PlanOptions::default();
        let plan = crate::plan::plan(&lib, &options).unwrap();
        let recent = [
            recent("P", &["A2", "D2"]),
            recent("Other", &["A1"]),
            recent("P", &["NOT_A_KEYWORD"]),
            recent("P", &["B1"]),
        ];
        let out = candidates(&lib, &plan, &[0], &recent, &options);
        let labels: Vec<String> = out.iter().map(|v| v.choice.label(v.pass)).collect();
        assert_eq!(labels[..2], ["{A2, D2}", "{B1}"]);
        let cover = &out[2..];
        assert!(cover.len() >= 9 && cover.len() < 20, "{}", cover.len());
        let pass = plan[0].0;
        for (a, b) in [(0, 1), (0, 3), (2, 3)] {
            for (x, y) in [(0u16, 0u16), (1, 2), (2, 1), (2, 2)] {
                assert!(
                    cover
                        .iter()
                        .any(|v| v.choice.0[a] == x && v.choice.0[b] == y),
                    "sets {a} and {b}, options {x} and {y} uncovered in {}",
                    pass.name
                );
            }
        }
        // Nothing stale: nothing early.
        assert!(candidates(&lib, &plan, &[], &recent, &options).is_empty());
    }
}
