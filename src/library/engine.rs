//! One trait for what composes a loaded tree's variants: this crate's preprocessor for its own
//! dialect, naga_oil for naga_oil trees, the `wesl` crate for WESL trees — or, when this build
//! lacks the dialect's cargo feature, an engine that says so for every variant.

use crate::error::Stage;
#[cfg(any(feature = "naga-oil", feature = "wesl"))]
use crate::error::VariantError;
use crate::preprocess::compose::{ModuleGraph, compose};
use crate::preprocess::{Composed, Dialect};

use super::Variant;

/// How a variant is composed (meaningful for this crate's own dialect; the other engines
/// decide what their programs keep and have no line map).
#[derive(Clone, Copy, Debug)]
pub(crate) struct How {
    /// Keep a line map back to the original modules.
    pub with_map: bool,
    /// Leave out the items the entry points do not reach ([`crate::reach`]).
    pub prune: bool,
    /// The device the engines that validate while composing (naga_oil, WESL) validate for.
    #[cfg_attr(not(any(feature = "naga-oil", feature = "wesl")), allow(dead_code))]
    pub profile: crate::validator::Profile,
}

/// What turns a variant of a loaded tree into WGSL.
pub(crate) trait Engine: Send + Sync {
    /// The variant's program, or (in [`Composed::failure`]) why it has none.
    fn compose(&self, tree: &ModuleGraph<'_>, variant: &Variant<'_>, how: How) -> Composed;

    /// Whether the program does not depend on `How::profile` beyond being validated for it:
    /// one composition then serves every profile (composed for their union, validated per
    /// profile, composed again for one profile only to locate its error).
    fn composes_alike(&self) -> bool {
        true
    }
}

/// This crate's own dialect: the preprocessor composes the text, keeping its line map.
pub(crate) struct Preprocessor;

impl Engine for Preprocessor {
    fn compose(&self, tree: &ModuleGraph<'_>, variant: &Variant<'_>, how: How) -> Composed {
        let composed = compose(
            tree,
            variant.pass.module,
            &variant.pass.body,
            variant.choice.defines(variant.pass),
            how.with_map,
        );
        if how.prune {
            crate::reach::prune(composed)
        } else {
            composed
        }
    }
}

/// A tree whose dialect this build cannot compose (its cargo feature off): it loads and
/// audits, and every variant fails with an error that names the feature.
pub(crate) struct Unavailable(pub Dialect);

impl Engine for Unavailable {
    fn compose(&self, _: &ModuleGraph<'_>, variant: &Variant<'_>, _: How) -> Composed {
        Composed::failed(super::unlocated(
            variant,
            Stage::Compose,
            format!(
                "this build of wgsl-variants cannot compose `{}` trees (cargo feature `{}` off): they load and audit, but cannot compose",
                self.0.name(),
                self.0.name()
            ),
        ))
    }
}

/// An engine's result as a [`Composed`]: the program's text, or the failure.
#[cfg(any(feature = "naga-oil", feature = "wesl"))]
pub(crate) fn composed(result: Result<String, VariantError>) -> Composed {
    match result {
        Ok(text) => Composed {
            text,
            ..Composed::default()
        },
        Err(e) => Composed::failed(e),
    }
}
