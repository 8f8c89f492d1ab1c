//! t-wise covering sets: a few variants of a huge build set that together contain, for every
//! choice of t keyword sets, every combination of their options that occurs in the build set.
//!
//! Interaction bugs — code that fails only when two or three particular keywords are on
//! together — are caught by building a covering set instead of the whole space: 64 two-way
//! keyword sets (2^64 variants) are covered pairwise by 10 variants.
//!
//! The build set is a product of independent factors ([`Space`]'s keyword sets, with the sets
//! that constraints or materials couple merged into one factor whose values are their allowed
//! combinations). A covering array over those factors (`covering::array`) is a covering set of the
//! keyword sets, and every row is a variant of the build set by construction.
//!
//! ```
//! use wgsl_variants::{Library, Space};
//!
//! let mut shader = String::from("#shader synth\n#pass P\n");
//! for i in 0..64 {
//!     shader.push_str(&format!("#pragma multi_compile _ K{i}\n"));
//! }
//! shader.push_str("#endpass\n");
//! let lib = Library::from_sources([("synth.wgsl", shader)]).unwrap();
//! let pass = lib.pass("synth", "P").unwrap();
//! let cover = Space::full(pass).covering(2).unwrap();
//! assert_eq!(cover.len(), 10); // the optimum for 64 binary sets
//! ```

pub(crate) mod array;

use crate::shader::Pass;
use crate::variants::{Choice, Factor, Space};

/// Strongest supported strength.
pub(crate) const MAX_T: usize = 4;

/// Most values of the t largest factors together: above it the tuples to cover do not fit in
/// memory comfortably.
pub(crate) const MAX_TUPLES: u128 = 1 << 26;

/// Most t-way combinations of options one covering set may have to cover
/// ([`interactions`]): the generator's time and memory grow with them, and past this a
/// generation would run for many minutes (about 2.7 s for 7.8 million on a 2-core machine,
/// measured 2026-11-27 with `validate --cover 4` over 60 two-option sets).
pub const MAX_INTERACTIONS: u128 = 200_000_000;

/// The number of t-way combinations of options that a t-wise covering set of factors with
/// `levels` options each must cover: the sum, over every t factors, of the product of their
/// sizes (exact; saturating at `u128::MAX`).
///
/// ```
/// use wgsl_variants::covering::interactions;
/// assert_eq!(interactions(&[2, 2, 2], 2), 12); // 3 pairs of sets, 4 combinations each
/// assert_eq!(interactions(&[2; 202], 4), 1_077_306_400); // C(202, 4) * 16
/// ```
pub fn interactions(levels: &[usize], t: usize) -> u128 {
    // e[j] = sum over j-subsets of the factors seen so far of the product of their sizes.
    let mut e = vec![0u128; t + 1];
    e[0] = 1;
    for &l in levels {
        for j in (1..=t).rev() {
            e[j] = e[j].saturating_add(e[j - 1].saturating_mul(l as u128));
        }
    }
    e[t]
}

/// Why a covering set could not be made. Every variant names the pass.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CoverError {
    /// t = 0 covers nothing.
    #[error("{shader}/{pass}: covering strength t = 0; give t from 1 to {MAX_T}")]
    ZeroStrength {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
    },
    /// t is past what is supported.
    #[error("{shader}/{pass}: covering strength t = {t} is past the supported {MAX_T}")]
    Unsupported {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The strength asked for.
        t: usize,
    },
    /// t is more than the number of keyword sets.
    #[error(
        "{shader}/{pass}: covering strength t = {t} is more than the pass's {sets} keyword sets"
    )]
    TooStrong {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The strength asked for.
        t: usize,
        /// Number of keyword sets of the pass.
        sets: usize,
    },
    /// The build set has no variant (skip_variants, materials or constraints remove all).
    #[error("{shader}/{pass}: the build set is empty{}", empty_cause(.constraints))]
    Empty {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The pass's constraints as written (`require A B`), if it has any.
        constraints: Vec<String>,
    },
    /// The t largest factors have too many value combinations to list.
    #[error(
        "{shader}/{pass}: t = {t} needs {combinations} combinations of the largest keyword sets together (at most {MAX_TUPLES})"
    )]
    TooLarge {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The strength asked for.
        t: usize,
        /// Product of the t largest factor sizes.
        combinations: u128,
    },
    /// The covering set would take too long to generate: it must cover more t-way
    /// combinations of options than [`MAX_INTERACTIONS`].
    #[error(
        "{shader}/{pass}: a t = {t} covering set of its {sets} keyword sets must cover {interactions} combinations of options, past the limit of {MAX_INTERACTIONS} (it would take many minutes to generate){}",
        lower_hint(*.t, *.lower)
    )]
    TooMuchWork {
        /// Shader.
        shader: String,
        /// Pass.
        pass: String,
        /// The strength asked for.
        t: usize,
        /// Number of keyword sets (factors).
        sets: usize,
        /// Combinations to cover ([`interactions`]).
        interactions: u128,
        /// Combinations a covering set of strength t − 1 covers.
        lower: u128,
    },
}

fn lower_hint(t: usize, lower: u128) -> String {
    if t > 1 {
        format!("; t = {} covers {lower}", t - 1)
    } else {
        String::new()
    }
}

impl CoverError {
    /// The shader and pass the error is about.
    pub fn pass(&self) -> (&str, &str) {
        match self {
            CoverError::ZeroStrength { shader, pass }
            | CoverError::Unsupported { shader, pass, .. }
            | CoverError::TooStrong { shader, pass, .. }
            | CoverError::Empty { shader, pass, .. }
            | CoverError::TooLarge { shader, pass, .. }
            | CoverError::TooMuchWork { shader, pass, .. } => (shader, pass),
        }
    }
}

fn empty_cause(constraints: &[String]) -> String {
    if constraints.is_empty() {
        String::new()
    } else {
        format!(" under its constraints ({})", constraints.join(", "))
    }
}

/// The checks every covering entry point makes: t in range and the build set not empty.
pub(crate) fn check(pass: &Pass, factors: &[Factor], t: usize) -> Result<(), CoverError> {
    let (shader, name) = (pass.shader.clone(), pass.name.clone());
    if t == 0 {
        return Err(CoverError::ZeroStrength { shader, pass: name });
    }
    if t > MAX_T {
        return Err(CoverError::Unsupported {
            shader,
            pass: name,
            t,
        });
    }
    if t > pass.sets.len() {
        return Err(CoverError::TooStrong {
            shader,
            pass: name,
            t,
            sets: pass.sets.len(),
        });
    }
    if factors.iter().any(|f| f.len() == 0) {
        return Err(CoverError::Empty {
            shader,
            pass: name,
            constraints: pass.constraints.iter().map(|c| c.to_string()).collect(),
        });
    }
    let mut levels: Vec<u128> = factors.iter().map(|f| f.len() as u128).collect();
    levels.sort_unstable_by(|a, b| b.cmp(a));
    let combinations = levels
        .iter()
        .take(t)
        .fold(1u128, |a, &l| a.saturating_mul(l));
    if combinations > MAX_TUPLES {
        return Err(CoverError::TooLarge {
            shader,
            pass: name,
            t,
            combinations,
        });
    }
    let sizes: Vec<usize> = factors.iter().map(Factor::len).collect();
    let work = interactions(&sizes, t);
    if work > MAX_INTERACTIONS {
        return Err(CoverError::TooMuchWork {
            shader,
            pass: name,
            t,
            sets: factors.len(),
            interactions: work,
            lower: interactions(&sizes, t - 1),
        });
    }
    Ok(())
}

/// A t-wise covering set of `space` (see [`Space::covering`]).
pub(crate) fn cover(space: &Space<'_>, t: usize) -> Result<Vec<Choice>, CoverError> {
    let factors = space.factors();
    check(space.pass(), &factors, t)?;
    Ok(rows_to_choices(space.pass(), &factors, t))
}

/// The covering array over `factors`, as variants, duplicates dropped (first kept).
pub(crate) fn rows_to_choices(pass: &Pass, factors: &[Factor], t: usize) -> Vec<Choice> {
    let levels: Vec<usize> = factors.iter().map(Factor::len).collect();
    let rows = array::covering_array(&levels, t);
    let mut seen = std::collections::HashSet::new();
    rows.into_iter()
        .map(|row| {
            let mut options = vec![0u16; pass.sets.len()];
            for (f, &v) in factors.iter().zip(&row) {
                f.apply(v as usize, &mut options);
            }
            Choice(options.into_boxed_slice())
        })
        .filter(|c| seen.insert(c.clone()))
        .collect()
}

/// A combination of options of t keyword sets: `(set, option)` pairs, sets ascending.
pub type Tuple = Vec<(usize, u16)>;

/// The t-tuples of keyword-set options that variant `index` of `variants` is the first to
/// contain, in set order (what a failing variant of a covering set newly exercises).
pub fn first_covered(variants: &[Choice], index: usize, t: usize) -> Vec<Tuple> {
    let Some(target) = variants.get(index) else {
        return Vec::new();
    };
    let k = target.0.len();
    let t = t.min(k);
    let mut out = Vec::new();
    if t == 0 {
        return out;
    }
    let mut subset: Vec<usize> = (0..t).collect();
    loop {
        let seen_before = variants[..index]
            .iter()
            .any(|v| subset.iter().all(|&s| v.0[s] == target.0[s]));
        if !seen_before {
            out.push(subset.iter().map(|&s| (s, target.0[s])).collect());
        }
        if !array::next_combination(&mut subset, k) {
            return out;
        }
    }
}

/// A tuple as people read it: `K3=on, K7=off` style, each set by its chosen option
/// (`_` for a set's "none" option, named by the set's keywords).
pub fn tuple_label(pass: &Pass, tuple: &Tuple) -> String {
    tuple
        .iter()
        .map(|&(set, o)| match &pass.sets[set].options[o as usize] {
            Some(k) => k.clone(),
            None => format!(
                "!{}",
                pass.sets[set].keywords().collect::<Vec<_>>().join("|")
            ),
        })
        .collect::<Vec<_>>()
        .join(" & ")
}

/// Shrinks a failing variant like a property-test shrinker: moves its sets to their base
/// option (the "none" option, or the first the space allows where a set has none) one at a
/// time, keeping each change that still fails, until no set can move. A move that breaks a
/// `require`/`exclude` constraint takes the keywords that constraint ties to it along (a
/// keyword whose requirement is turned off is turned off too), so the result is minimal under
/// the pass's constraints. Returns the smallest failing variant found (`fails` is called at
/// most a few times per set).
pub fn shrink(
    space: &Space<'_>,
    failing: &Choice,
    mut fails: impl FnMut(&Choice) -> bool,
) -> Choice {
    let sets = space.pass().sets.len();
    let mut current = failing.clone();
    loop {
        let mut changed = false;
        for set in 0..sets {
            if Some(current.0[set]) == base(space, set) {
                continue;
            }
            if let Some(candidate) = to_base(space, &current, set)
                && fails(&candidate)
            {
                current = candidate;
                changed = true;
            }
        }
        if !changed {
            return current;
        }
    }
}

/// A set's base option in `space`: its "none" option where the space allows it, else the
/// first option it allows.
fn base(space: &Space<'_>, set: usize) -> Option<u16> {
    let allowed = space.options(set);
    let none = space.pass().sets[set].none_index().map(|n| n as u16);
    none.filter(|n| allowed.contains(n))
        .or_else(|| allowed.first().copied())
}

/// `current` with `set` at its base option, and with each keyword a broken constraint then
/// ties to it at its base too, if that ends in the space.
fn to_base(space: &Space<'_>, current: &Choice, set: usize) -> Option<Choice> {
    let pass = space.pass();
    let mut candidate = current.clone();
    candidate.0[set] = base(space, set)?;
    for _ in 0..pass.sets.len() {
        if space.contains(&candidate) {
            return Some(candidate);
        }
        // Only materials (not a constraint) rule it out: no repair.
        let broken = pass.constraints.iter().find(|c| !c.holds(&candidate.0))?;
        let (other, _) = match broken.kind {
            crate::keywords::ConstraintKind::Require => broken.at[0],
            crate::keywords::ConstraintKind::Exclude if broken.at[0].0 == set => broken.at[1],
            crate::keywords::ConstraintKind::Exclude => broken.at[0],
        };
        let other_base = base(space, other)?;
        if candidate.0[other] == other_base {
            return None;
        }
        candidate.0[other] = other_base;
    }
    space.contains(&candidate).then_some(candidate)
}

impl Space<'_> {
    /// The t-way combinations of options a t-wise covering set of this space must cover
    /// ([`interactions`] of its factors): what the generation's time grows with, for a caller
    /// that wants to say how long it will take before it starts.
    ///
    /// ```
    /// use wgsl_variants::{Library, Space};
    /// let lib = Library::from_sources([(
    ///     "s.wgsl",
    ///     "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma multi_compile _ B\n\
    ///      #pragma multi_compile _ C\n#endpass",
    /// )])
    /// .unwrap();
    /// assert_eq!(Space::full(lib.pass("s", "P").unwrap()).covering_work(2), 12);
    /// ```
    pub fn covering_work(&self, t: usize) -> u128 {
        let sizes: Vec<usize> = self.factors().iter().map(Factor::len).collect();
        interactions(&sizes, t)
    }

    /// A deterministic t-wise covering set of this space (t from 1 to 4): every variant is in
    /// the space, and every combination of options of every t keyword sets that occurs in
    /// the space occurs in one of them. Sets coupled by materials or constraints are covered
    /// as one factor (every allowed combination of them appears). See [`crate::covering`].
    ///
    /// ```
    /// use wgsl_variants::{Library, Space};
    /// let lib = Library::from_sources([(
    ///     "s.wgsl",
    ///     "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma multi_compile _ B\n\
    ///      #pragma multi_compile _ C\n#pragma multi_compile _ D\n#endpass",
    /// )])
    /// .unwrap();
    /// let pass = lib.pass("s", "P").unwrap();
    /// let space = Space::full(pass);
    /// let cover = space.covering(2).unwrap();
    /// assert_eq!(cover.len(), 5); // of 16: every pair of A..D, each way, in 5 variants
    /// assert!(cover.iter().all(|c| space.contains(c)));
    /// assert!(space.covering(0).is_err() && space.covering(5).is_err());
    /// ```
    pub fn covering(&self, t: usize) -> Result<Vec<Choice>, CoverError> {
        cover(self, t)
    }
}

#[cfg(test)]
mod tests;
