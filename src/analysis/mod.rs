//! The static analysis of a pass's variant space, shared by validation, covering and the
//! audit: which lines of the composed text depend on which keyword sets, how many distinct
//! texts a space composes to (exactly, without composing it when the groups allow), which
//! keyword sets change code together (regions), and which items no variant reaches.
//!
//! It sits below [`crate::validate`] (which skips its index of seen texts when
//! [`proves_all_distinct`] holds) and [`crate::audit`] (which reports it); it reads the tree
//! through [`crate::Library`] and the preprocessor's module graph only.

pub(crate) mod bits;
pub(crate) mod compose;
pub(crate) mod deps;
pub(crate) mod distinct;
mod regions;
mod unreached;

use crate::library::Library;
use crate::shader::Pass;
use crate::variants::Space;

use compose::LineIds;
use distinct::Limits;

pub use regions::region_aware;
pub use unreached::{Unreached, prunes_nothing, unreached};

/// Most assignments enumerated for one group of coupled keyword sets, by default (the audit's
/// `AuditOptions::component_limit`).
pub const COMPONENT_LIMIT: u64 = 1 << 16;

/// How a distinct count was obtained.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// Exact: the product over components of coupled keyword sets, each enumerated on its
    /// own, with the composed text proven to be an unambiguous concatenation of their regions.
    Components,
    /// Exact: every variant of the stage was composed and compared.
    Enumeration,
    /// An upper bound: a component was too large to enumerate and so was the whole stage.
    Bound,
}

/// The code regions of a space, for region-aware covering: the space's factors and, per group
/// of factors whose code depends on each other, one representative assignment (a choice per
/// factor of the group) for each distinct output of the group, or `None` when the group was
/// too large to enumerate. Factors in no group change no code.
pub(crate) struct Regions {
    /// The space's factors ([`Space::factors`](crate::variants::Space)).
    pub factors: Vec<crate::variants::Factor>,
    /// `(factors of the group, representatives)`.
    pub groups: Vec<(Vec<usize>, Option<Representatives>)>,
}

/// One assignment (a choice per factor of a group) per distinct output of the group.
pub(crate) type Representatives = Vec<Vec<usize>>;

/// The regions of `space` (see [`Regions`]), from the same analysis as the audit's.
pub(crate) fn regions(lib: &Library, space: &Space<'_>) -> Regions {
    let graph = lib.module_graph();
    let ids = LineIds::new(&graph);
    let limits = Limits {
        component: COMPONENT_LIMIT,
        whole: 0,
    };
    let analysis = distinct::analyze(&graph, &ids, space.pass(), space.clone(), limits);
    let groups = analysis
        .components
        .iter()
        .map(|c| {
            let reps = c.table.as_ref().map(|table| {
                let mut reps: Vec<Option<Vec<usize>>> = vec![None; table.classes as usize];
                for (row, &class) in table.class.iter().enumerate() {
                    if reps[class as usize].is_none() {
                        reps[class as usize] = Some(table.digits(row));
                    }
                }
                reps.into_iter().flatten().collect()
            });
            (c.factors.clone(), reps)
        })
        .collect();
    Regions {
        factors: analysis.factors,
        groups,
    }
}

/// Whether every variant of `pass`'s full space composes to a different text, proved by the
/// static analysis alone (never by enumerating the space). `false` means "not proved": some
/// variants share a text, or the analysis could not certify an exact count within its default
/// per-component limit.
///
/// The texts are the ones validated: pruned of unreached items ([`crate::reach`]). The static
/// analysis proves the composed texts distinct, so the proof also needs pruning to leave every
/// variant as composed ([`prunes_nothing`]): otherwise two variants that differ
/// only in items no entry point reaches would share a pruned text.
///
/// Validation uses this to skip its index of seen texts: when every text is different, each
/// variant is validated once anyway, and memory stays the same however large the space.
/// For a tree in another dialect (naga_oil) it is never proved.
///
/// ```
/// use wgsl_variants::{Library, analysis};
///
/// // A changes what the entry point returns: two programs.
/// let lib = Library::from_sources([(
///     "s.wgsl",
///     "#shader s\n#pass P\n#pragma multi_compile _ A\n#ifdef A\nconst X = 1.0;\n#else\n\
///      const X = 0.0;\n#endif\n@fragment fn fs() -> @location(0) vec4f { return vec4f(X); }\n#endpass",
/// )])
/// .unwrap();
/// assert!(analysis::proves_all_distinct(&lib, lib.pass("s", "P").unwrap()));
///
/// // The bundled shadow casters compose the surface functions, and reach none of them.
/// let lib = wgsl_variants_shaders::library().unwrap();
/// assert!(!analysis::proves_all_distinct(&lib, lib.pass("standard", "ShadowCaster").unwrap()));
///
/// // DEAD changes no code: both of its variants compose to the same text.
/// let lib = Library::from_sources([(
///     "s.wgsl",
///     "#shader s\n#pass P\n#pragma multi_compile _ DEAD\nfn f() {}\n#endpass",
/// )])
/// .unwrap();
/// assert!(!analysis::proves_all_distinct(&lib, lib.pass("s", "P").unwrap()));
/// ```
pub fn proves_all_distinct(lib: &Library, pass: &Pass) -> bool {
    // The analysis proves preprocessed texts distinct; naga_oil keeps only the imported items
    // a program uses, so two different texts can still compose to one program there.
    if lib.dialect() != crate::preprocess::Dialect::WgslVariants {
        return false;
    }
    let graph = lib.module_graph();
    let ids = LineIds::new(&graph);
    let limits = Limits {
        component: COMPONENT_LIMIT,
        whole: 0,
    };
    let full = distinct::analyze(&graph, &ids, pass, Space::full(pass), limits);
    full.exact && full.distinct == full.count && unreached::prunes_nothing(lib, pass)
}
