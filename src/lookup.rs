//! Finding a variant from a keyword set, like Unity's strict variant matching.
//!
//! A keyword set resolves to exactly one variant or fails with an error that names the nearest
//! variants of the build set. The closest-variant fallback (Unity's behaviour without strict
//! matching) is only used when asked for.

use crate::diagnostic::suggest;
use crate::shader::Pass;
use crate::variants::{Choice, Space};

/// Why a keyword set does not name a variant.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LookupError {
    /// No shader of that name.
    #[error("no shader named `{name}`{}", crate::diagnostic::hint(suggestion.as_deref()))]
    UnknownShader {
        /// The name asked for.
        name: String,
        /// The closest existing name.
        suggestion: Option<String>,
    },
    /// The shader has no pass of that name.
    #[error("shader `{shader}` has no pass `{name}` (passes: {})", available.join(", "))]
    UnknownPass {
        /// The shader.
        shader: String,
        /// The name asked for.
        name: String,
        /// The passes it has.
        available: Vec<String>,
    },
    /// A keyword the pass does not declare.
    #[error(
        "pass `{shader}/{pass}` declares no keyword `{keyword}`{}",
        crate::diagnostic::hint(suggestion.as_deref())
    )]
    UnknownKeyword {
        /// The shader.
        shader: String,
        /// The pass.
        pass: String,
        /// The keyword asked for.
        keyword: String,
        /// The closest declared keyword.
        suggestion: Option<String>,
    },
    /// Two keywords of the same set.
    #[error("`{first}` and `{second}` are options of the same set (`{set}`): only one can be on")]
    Conflicting {
        /// The first keyword.
        first: String,
        /// The second keyword.
        second: String,
        /// The set, as written.
        set: String,
    },
    /// A set with no "none" option and none of its keywords given.
    #[error("no keyword of the set `{set}` is given, and the set has no \"none\" option")]
    Missing {
        /// The set, as written.
        set: String,
    },
    /// The keyword set names a variant that is not built.
    #[error("variant {keywords} of `{shader}/{pass}` is not in the build set ({reason}); nearest: {}", nearest.join(" or "))]
    NotBuilt {
        /// The shader.
        shader: String,
        /// The pass.
        pass: String,
        /// The keyword set asked for.
        keywords: String,
        /// Why it was not built.
        reason: String,
        /// The nearest built variants.
        nearest: Vec<String>,
    },
}

/// The strict lookup of [`Pass::resolve`].
pub(crate) fn resolve<S: AsRef<str>>(pass: &Pass, keywords: &[S]) -> Result<Choice, LookupError> {
    let mut options: Vec<Option<u16>> = vec![None; pass.sets.len()];
    for keyword in keywords {
        let keyword = keyword.as_ref();
        let (set, option) = pass
            .keyword(keyword)
            .ok_or_else(|| LookupError::UnknownKeyword {
                shader: pass.shader.clone(),
                pass: pass.name.clone(),
                keyword: keyword.to_string(),
                suggestion: suggest(keyword, pass.keywords()),
            })?;
        if let Some(previous) = options[set] {
            let first = pass.sets[set].options[previous as usize]
                .clone()
                .unwrap_or_default();
            if first != keyword {
                return Err(LookupError::Conflicting {
                    first,
                    second: keyword.to_string(),
                    set: pass.sets[set].to_string(),
                });
            }
        }
        options[set] = Some(option as u16);
    }
    let mut choice = Vec::with_capacity(options.len());
    for (set, option) in options.into_iter().enumerate() {
        match option.or(pass.sets[set].none_index().map(|i| i as u16)) {
            Some(o) => choice.push(o),
            None => {
                return Err(LookupError::Missing {
                    set: pass.sets[set].to_string(),
                });
            }
        }
    }
    Ok(Choice(choice.into_boxed_slice()))
}

/// Strict lookup of `keywords` in `space`: exactly that variant, or an error naming the nearest
/// (at most three) variants of the space. `budget` bounds the search for neighbours.
pub fn lookup_strict<S: AsRef<str>>(
    space: &Space<'_>,
    keywords: &[S],
    budget: u64,
) -> Result<Choice, LookupError> {
    let pass = space.pass();
    let choice = pass.resolve(keywords)?;
    if space.contains(&choice) {
        return Ok(choice);
    }
    let reason = match choice
        .keywords(pass)
        .into_iter()
        .find(|k| pass.skip_variants.iter().any(|s| s == k))
    {
        Some(k) => format!("`{k}` is in skip_variants"),
        None => "no material uses this shader_feature combination".to_string(),
    };
    let nearest = nearest(space, &choice, 3, budget)
        .iter()
        .map(|c| c.label(pass))
        .collect();
    Err(LookupError::NotBuilt {
        shader: pass.shader.clone(),
        pass: pass.name.clone(),
        keywords: choice.label(pass),
        reason,
        nearest,
    })
}

/// The built variant closest to `keywords` (fewest sets that differ; ties go to the first in
/// enumeration order) — Unity's behaviour without strict variant matching. Use only when a
/// fallback is wanted.
pub fn lookup_closest<S: AsRef<str>>(
    space: &Space<'_>,
    keywords: &[S],
    budget: u64,
) -> Result<Choice, LookupError> {
    let choice = space.pass().resolve(keywords)?;
    if space.contains(&choice) {
        return Ok(choice);
    }
    nearest(space, &choice, 1, budget)
        .into_iter()
        .next()
        .ok_or_else(|| LookupError::NotBuilt {
            shader: space.pass().shader.clone(),
            pass: space.pass().name.clone(),
            keywords: choice.label(space.pass()),
            reason: "the build set is empty".into(),
            nearest: Vec::new(),
        })
}

fn nearest(space: &Space<'_>, choice: &Choice, n: usize, budget: u64) -> Vec<Choice> {
    let Ok(all) = space.enumerate(budget) else {
        return Vec::new();
    };
    let mut scored: Vec<(usize, Choice)> =
        all.into_iter().map(|c| (c.distance(choice), c)).collect();
    scored.sort();
    scored.into_iter().take(n).map(|(_, c)| c).collect()
}

impl Pass {
    /// The variant with exactly these keywords on, in the full space.
    ///
    /// Every keyword must be declared by the pass, at most one per set; a set none of whose
    /// keywords is given takes its "none" option.
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let pass = lib.pass("standard", "Deferred").unwrap();
    /// assert!(pass.resolve(&["_NORMAL_MAP"]).is_ok());
    /// assert!(pass.resolve(&["_NORMAL_MAPP"]).unwrap_err().to_string().contains("did you mean `_NORMAL_MAP`"));
    /// ```
    pub fn resolve<S: AsRef<str>>(&self, keywords: &[S]) -> Result<Choice, LookupError> {
        resolve(self, keywords)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Library;

    /// Sets `A B`, `_ C D`, `E F`; `skip_variants C`.
    fn library() -> Library {
        Library::from_sources([(
            "s.wgsl",
            "#shader s\n#pass P\n#pragma multi_compile A B\n#pragma multi_compile _ C D\n\
             #pragma multi_compile E F\n#pragma skip_variants C\n#endpass\n",
        )])
        .unwrap()
    }

    fn choice(options: &[u16]) -> Choice {
        Choice(options.into())
    }

    /// An exact keyword set finds its variant, whatever the order; an omitted set with a
    /// "none" option takes it.
    #[test]
    fn strict_exact() {
        let lib = library();
        let pass = lib.pass("s", "P").unwrap();
        let space = Space::after_skip(pass);
        assert_eq!(
            lookup_strict(&space, &["B", "D", "F"], 100).unwrap(),
            choice(&[1, 2, 1])
        );
        assert_eq!(
            lookup_strict(&space, &["F", "B"], 100).unwrap(),
            choice(&[1, 0, 1])
        );
        // The same keyword twice is not a conflict.
        assert_eq!(
            lookup_strict(&space, &["A", "A", "E"], 100).unwrap(),
            choice(&[0, 0, 0])
        );
    }

    /// An undeclared keyword fails, suggesting the closest declared one.
    #[test]
    fn strict_unknown_keyword() {
        let lib = library();
        let pass = lib.pass("s", "P").unwrap();
        let err = lookup_strict(&Space::full(pass), &["A", "FF"], 100).unwrap_err();
        assert_eq!(
            err,
            LookupError::UnknownKeyword {
                shader: "s".into(),
                pass: "P".into(),
                keyword: "FF".into(),
                suggestion: Some("F".into()),
            }
        );
        let err = lookup_strict(&Space::full(pass), &["A", "NOTHING_LIKE_IT"], 100).unwrap_err();
        assert!(matches!(
            err,
            LookupError::UnknownKeyword {
                suggestion: None,
                ..
            }
        ));
    }

    /// Two keywords of one set conflict; a set with no "none" option and no keyword is
    /// missing.
    #[test]
    fn strict_conflict_and_missing() {
        let lib = library();
        let pass = lib.pass("s", "P").unwrap();
        let err = lookup_strict(&Space::full(pass), &["A", "C", "D"], 100).unwrap_err();
        assert!(
            matches!(&err, LookupError::Conflicting { first, second, .. } if first == "C" && second == "D"),
            "{err:?}"
        );
        let err = lookup_strict(&Space::full(pass), &["C"], 100).unwrap_err();
        assert!(matches!(err, LookupError::Missing { .. }), "{err:?}");
    }

    /// A skipped variant is not built: the error says why and names built neighbours, the
    /// nearest first; in the full space the same keywords resolve.
    #[test]
    fn strict_skipped_variant() {
        let lib = library();
        let pass = lib.pass("s", "P").unwrap();
        let err = lookup_strict(&Space::after_skip(pass), &["B", "C", "F"], 100).unwrap_err();
        let LookupError::NotBuilt {
            keywords,
            reason,
            nearest,
            ..
        } = err
        else {
            panic!("expected NotBuilt: {err:?}");
        };
        assert_eq!(keywords, "{B, C, F}");
        assert!(reason.contains("`C` is in skip_variants"), "{reason}");
        assert_eq!(nearest, vec!["{B, F}", "{B, D, F}", "{A, F}"]);
        assert_eq!(
            lookup_strict(&Space::full(pass), &["B", "C", "F"], 100).unwrap(),
            choice(&[1, 1, 1])
        );
    }

    /// Closest lookup returns a built variant unchanged, else the one differing in the fewest
    /// sets, ties going to the first in enumeration order.
    #[test]
    fn closest() {
        let lib = library();
        let pass = lib.pass("s", "P").unwrap();
        let space = Space::after_skip(pass);
        assert_eq!(
            lookup_closest(&space, &["B", "D", "E"], 100).unwrap(),
            choice(&[1, 2, 0])
        );
        // {B, C, F}: {B, F} and {B, D, F} differ in one set; {B, F} comes first. {A, E}, the
        // first variant of all, differs in three.
        assert_eq!(
            lookup_closest(&space, &["B", "C", "F"], 100).unwrap(),
            choice(&[1, 0, 1])
        );
        assert_eq!(
            lookup_closest(&space, &["A", "C", "E"], 100).unwrap(),
            choice(&[0, 0, 0])
        );
        // Keyword errors still come first.
        assert!(matches!(
            lookup_closest(&space, &["A", "B"], 100),
            Err(LookupError::Conflicting { .. })
        ));
        // Past the budget no neighbour is searched.
        assert!(matches!(
            lookup_closest(&space, &["B", "C", "F"], 1),
            Err(LookupError::NotBuilt { .. })
        ));
    }

    /// `suggest` picks the closest candidate within the distance limit.
    #[test]
    fn suggest_closest_within_limit() {
        assert_eq!(
            suggest("_NORMAL_MAPP", ["_NORMAL_MAP", "_EMISSION"]),
            Some("_NORMAL_MAP".into())
        );
        assert_eq!(suggest("XYZW", ["_NORMAL_MAP", "A"]), None);
    }
}
