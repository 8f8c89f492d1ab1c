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
//! let lib = wgsl_variants::Library::bundled().unwrap();
//! let mut options = PlanOptions::default();
//! options.pass = Some("Deferred".into());
//! let planned = plan(&lib, &options).unwrap();
//! assert_eq!(planned.len(), 1);
//! assert_eq!(planned[0].1.len(), 3072);
//! ```

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
        }
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

/// The variants to build for one pass under `options` (the shard aside), in enumeration order.
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
