//! Planning: which passes and which variants a command builds.
//!
//! `validate`, `emit --out`, [`bake`](crate::bake), the audit's selection and the command line
//! all choose their work here: passes by shader/pass filter, each pass's variants (the build
//! set for the given materials, or the full space), a budget per pass, and optionally one shard
//! of the whole.
//!
//! ```
//! use wgsl_variants::plan::{PlanOptions, plan};
//!
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let mut options = PlanOptions::default();
//! options.pass = Some("Deferred".into());
//! let planned = plan(&lib, &options).unwrap();
//! assert_eq!(planned.len(), 1);
//! assert_eq!(planned[0].1.len(), 110_592);
//! ```

use crate::covering::CoverError;
use crate::library::Library;
use crate::lookup::LookupError;
use crate::materials::{Material, MaterialsError};
use crate::shader::Pass;
use crate::variants::{BudgetError, Choice, Shard, Space};

/// What to build.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct PlanOptions {
    /// The full space of every pass instead of the build set.
    pub all: bool,
    /// Materials restricting `shader_feature` combinations (ignored with `all`).
    pub materials: Option<Vec<Material>>,
    /// Most variants built per pass.
    pub budget: u64,
    /// Only this shader.
    pub shader: Option<String>,
    /// Only passes of this name.
    pub pass: Option<String>,
    /// Only this shard of the whole (every N-th variant, numbered across the selected passes).
    pub shard: Option<Shard>,
    /// Build a t-wise covering set of each pass's space instead of all of it
    /// ([`Space::covering`]; a pass with fewer than t keyword sets is built whole); the
    /// budget then applies to the covering set.
    pub cover: Option<usize>,
    /// With `cover`, only passes whose space holds more than this many variants are covered;
    /// the others are built whole. This is how the tests and CI treat a library with a few huge
    /// passes: every variant of the small passes, a t-wise covering set of the huge ones.
    pub cover_above: Option<u64>,
    /// Validation also validates the text of each variant as composed, before reachability
    /// leaves out the items no entry point reaches ([`crate::Library::compose_unpruned`]), once
    /// per distinct such text: a broken helper nobody calls is an error too.
    pub strict: bool,
}

impl Default for PlanOptions {
    fn default() -> Self {
        PlanOptions {
            all: false,
            materials: None,
            budget: 1_000_000,
            shader: None,
            pass: None,
            shard: None,
            cover: None,
            cover_above: None,
            strict: false,
        }
    }
}

impl PlanOptions {
    /// These options as text for [`crate::fingerprint::fingerprint`]: everything but the shard, so
    /// every shard of one plan has the same fingerprint.
    pub fn fingerprint_text(&self) -> String {
        let whole = PlanOptions {
            shard: None,
            ..self.clone()
        };
        format!("{whole:?}")
    }
}

/// The variants to build, pass by pass, in enumeration order.
pub type Plan<'l> = Vec<(&'l Pass, Vec<Choice>)>;

/// Why a plan could not be made.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlanError {
    /// A pass's space is past the budget.
    #[error("{shader}/{pass}: {error}")]
    Budget {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The budget error.
        error: BudgetError,
    },
    /// A covering set could not be made.
    #[error(transparent)]
    Cover(#[from] CoverError),
    /// The materials do not fit the library.
    #[error(transparent)]
    Materials(#[from] MaterialsError),
    /// The shader filter names no shader of the library.
    #[error("no pass matches {0}")]
    UnknownShader(LookupError),
    /// No pass matched the filters.
    #[error("no pass matches shader {:?} pass {:?}", .shader.as_deref().unwrap_or("*"), .pass.as_deref().unwrap_or("*"))]
    NoMatch {
        /// The shader filter.
        shader: Option<String>,
        /// The pass filter.
        pass: Option<String>,
    },
}

/// The passes selected by `shader`/`pass` filters, in library order.
pub fn select_passes<'l>(
    lib: &'l Library,
    shader: Option<&str>,
    pass: Option<&str>,
) -> Result<Vec<&'l Pass>, PlanError> {
    if let Some(s) = shader {
        lib.shader(s).map_err(PlanError::UnknownShader)?;
    }
    let passes: Vec<&Pass> = lib
        .passes()
        .filter(|p| shader.is_none_or(|s| p.shader == s) && pass.is_none_or(|n| p.name == n))
        .collect();
    if passes.is_empty() {
        return Err(PlanError::NoMatch {
            shader: shader.map(str::to_string),
            pass: pass.map(str::to_string),
        });
    }
    Ok(passes)
}

/// The variants to build for one pass under `options` (the shard aside), in enumeration order
/// (with `cover`, in the covering set's order).
pub fn variants_to_build(
    lib: &Library,
    pass: &Pass,
    options: &PlanOptions,
) -> Result<Vec<Choice>, PlanError> {
    let space = if options.all {
        Space::full(pass)
    } else {
        lib.build_set(pass, options.materials.as_deref())?
    };
    // A pass with fewer keyword sets than t is its own covering set: it is built whole
    // (`Space::covering` refuses it, as it refuses t = 0 everywhere).
    let small = options
        .cover_above
        .is_some_and(|limit| space.count() <= limit.into());
    if let Some(t) = options
        .cover
        .filter(|&t| !small && (t == 0 || t <= pass.sets.len()))
    {
        let cover = space.covering(t)?;
        if cover.len() as u64 > options.budget {
            return Err(PlanError::Budget {
                shader: pass.shader.clone(),
                pass: pass.name.clone(),
                error: BudgetError {
                    count: cover.len().into(),
                    budget: options.budget,
                },
            });
        }
        return Ok(cover);
    }
    space
        .enumerate(options.budget)
        .map_err(|error| PlanError::Budget {
            shader: pass.shader.clone(),
            pass: pass.name.clone(),
            error,
        })
}

/// Every selected pass with its variants, then the shard of the whole if one is asked for.
pub fn plan<'l>(lib: &'l Library, options: &PlanOptions) -> Result<Plan<'l>, PlanError> {
    let plan = select_passes(lib, options.shader.as_deref(), options.pass.as_deref())?
        .into_iter()
        .map(|pass| Ok((pass, variants_to_build(lib, pass, options)?)))
        .collect::<Result<Plan<'l>, PlanError>>()?;
    Ok(match options.shard {
        Some(shard) => shard.select(plan),
        None => plan,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Shader `a` with passes `P` (2 variants) and `Q` (3, one skipped); shader `b` with pass
    /// `P` (3 variants).
    fn library() -> Library {
        Library::from_sources([
            (
                "a.wgsl",
                "#shader a\n#pass P\n#pragma multi_compile A B\n#endpass\n\
                 #pass Q\n#pragma multi_compile _ C D\n#pragma skip_variants D\n#endpass\n",
            ),
            (
                "b.wgsl",
                "#shader b\n#pass P\n#pragma multi_compile X Y Z\n#endpass\n",
            ),
        ])
        .unwrap()
    }

    fn names(passes: &[&Pass]) -> Vec<String> {
        passes
            .iter()
            .map(|p| format!("{}/{}", p.shader, p.name))
            .collect()
    }

    /// The shader and pass filters select in library order, alone or together.
    #[test]
    fn select_passes_filters() {
        let lib = library();
        let all = select_passes(&lib, None, None).unwrap();
        assert_eq!(names(&all), ["a/P", "a/Q", "b/P"]);
        let a = select_passes(&lib, Some("a"), None).unwrap();
        assert_eq!(names(&a), ["a/P", "a/Q"]);
        let p = select_passes(&lib, None, Some("P")).unwrap();
        assert_eq!(names(&p), ["a/P", "b/P"]);
        let bp = select_passes(&lib, Some("b"), Some("P")).unwrap();
        assert_eq!(names(&bp), ["b/P"]);
    }

    /// An unknown shader is `UnknownShader` (with a suggestion); filters that match nothing
    /// are `NoMatch`.
    #[test]
    fn select_passes_errors() {
        let lib = library();
        let err = select_passes(&lib, Some("bb"), None).unwrap_err();
        assert!(
            matches!(&err, PlanError::UnknownShader(LookupError::UnknownShader { name, .. }) if name == "bb"),
            "{err:?}"
        );
        let err = select_passes(&lib, Some("b"), Some("Q")).unwrap_err();
        assert!(
            matches!(&err, PlanError::NoMatch { shader: Some(s), pass: Some(p) } if s == "b" && p == "Q"),
            "{err:?}"
        );
        let err = select_passes(&lib, None, Some("R")).unwrap_err();
        assert!(
            matches!(&err, PlanError::NoMatch { shader: None, pass: Some(p) } if p == "R"),
            "{err:?}"
        );
    }

    /// Without `all` the build set (skipped variants left out) is built; with `all` the full
    /// space; past the budget, an error naming the pass.
    #[test]
    fn variants_to_build_all_and_budget() {
        let lib = library();
        let q = lib.pass("a", "Q").unwrap();
        let mut options = PlanOptions::default();
        let built = variants_to_build(&lib, q, &options).unwrap();
        assert_eq!(built, vec![Choice(vec![0].into()), Choice(vec![1].into())]);
        options.all = true;
        let full = variants_to_build(&lib, q, &options).unwrap();
        assert_eq!(full.len(), 3);
        assert_eq!(full[2], Choice(vec![2].into()));
        options.budget = 2;
        let err = variants_to_build(&lib, q, &options).unwrap_err();
        let PlanError::Budget {
            shader,
            pass,
            error,
        } = err
        else {
            panic!("expected Budget: {err:?}");
        };
        assert_eq!((shader.as_str(), pass.as_str()), ("a", "Q"));
        assert_eq!(error.count, 3u32.into());
        assert_eq!(error.budget, 2);
        options.all = false;
        assert_eq!(variants_to_build(&lib, q, &options).unwrap().len(), 2);
    }

    /// `plan` builds every selected pass; a budget error in any pass fails the plan; a shard
    /// keeps every N-th variant numbered across passes, and the shards cover the plan once.
    #[test]
    fn plan_with_shard() {
        let lib = library();
        let mut options = PlanOptions::default();
        let whole = plan(&lib, &options).unwrap();
        let sizes: Vec<usize> = whole.iter().map(|(_, c)| c.len()).collect();
        assert_eq!(sizes, [2, 2, 3]);
        options.shard = Some("2/2".parse().unwrap());
        let second = plan(&lib, &options).unwrap();
        // Global numbers 0..7; shard 2/2 keeps 1, 3, 5: a/P's second, a/Q's second, b/P's
        // second.
        assert_eq!(second.len(), 3);
        assert_eq!(second[0].1, vec![whole[0].1[1].clone()]);
        assert_eq!(second[1].1, vec![whole[1].1[1].clone()]);
        assert_eq!(second[2].1, vec![whole[2].1[1].clone()]);
        options.shard = Some("1/2".parse().unwrap());
        let first = plan(&lib, &options).unwrap();
        let first_sizes: Vec<usize> = first.iter().map(|(_, c)| c.len()).collect();
        assert_eq!(first_sizes, [1, 1, 2]);
        options.shard = None;
        options.budget = 2;
        assert!(matches!(
            plan(&lib, &options),
            Err(PlanError::Budget { shader, .. }) if shader == "b"
        ));
        options.pass = Some("Q".into());
        assert_eq!(plan(&lib, &options).unwrap().len(), 1);
    }
}
