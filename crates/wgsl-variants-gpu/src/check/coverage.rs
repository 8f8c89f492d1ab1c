//! Which variants a check runs and how keyword coverage is judged over them: the pairs that
//! differ in one keyword, the partners a covering set needs for that, and the small passes
//! that are run whole (or through the covering set the options ask for).

use std::collections::{HashMap, HashSet};

use super::options::CheckOptions;
use super::report::{KeywordCoverage, PassReport};
use crate::{CheckError, GpuError};
use wgsl_variants::Library;
use wgsl_variants::shader::Pass;
use wgsl_variants::variants::Choice;

/// The most variants any check enumerates in one pass: the command line's default budget
/// (`--max-variants`), above the largest bundled pass (standard/Deferred, 110,592).
pub(crate) const MAX_VARIANTS: u64 = 1_000_000;

/// For each keyword of `pass`: the variant pairs that differ only in that keyword's set (the
/// keyword on, against the set's first option), and how many of them `differs` says changed.
pub fn keyword_coverage(
    pass: &Pass,
    choices: &[Choice],
    differs: impl Fn(usize, usize) -> bool,
) -> Vec<KeywordCoverage> {
    let index: HashMap<&Choice, usize> = choices.iter().enumerate().map(|(i, c)| (c, i)).collect();
    let mut out = Vec::new();
    for (s, set) in pass.sets.iter().enumerate() {
        for (o, name) in set.options.iter().enumerate().skip(1) {
            let Some(name) = name else { continue };
            let mut coverage = KeywordCoverage {
                keyword: name.clone(),
                pairs: 0,
                pairs_changed: 0,
            };
            for (v, choice) in choices.iter().enumerate() {
                if usize::from(choice.0[s]) != o {
                    continue;
                }
                let mut partner = choice.0.clone();
                partner[s] = 0;
                if let Some(&p) = index.get(&Choice(partner)) {
                    coverage.pairs += 1;
                    coverage.pairs_changed += usize::from(differs(v, p));
                }
            }
            out.push(coverage);
        }
    }
    out
}

/// Closes a check that built and ran every variant in `choices` as its own shader, one output
/// each in `outputs`: counts them and judges each keyword by whether turning it off changed
/// the output of some pair.
pub(crate) fn judge_every_variant<T: PartialEq>(
    report: &mut PassReport,
    pass: &Pass,
    choices: &[Choice],
    outputs: &[T],
) {
    debug_assert_eq!(choices.len(), outputs.len(), "one output per variant");
    report.variants_run += choices.len();
    report.distinct_shaders += choices.len();
    report.keywords = keyword_coverage(pass, choices, |a, b| outputs[a] != outputs[b]);
    report.judge_keywords();
}

/// For each keyword: the first variant with it on whose reference changes when it is turned
/// off, and that partner added to `choices` unless already there. Returns how many were
/// added. With these, a covering set's keyword coverage can be judged: each keyword has a
/// pair whose reference says it matters.
pub(crate) fn add_partners<T: PartialEq>(
    pass: &Pass,
    choices: &mut Vec<Choice>,
    image_of: &impl Fn(&Choice) -> Result<T, GpuError>,
) -> Result<usize, GpuError> {
    let mut present: HashSet<Choice> = choices.iter().cloned().collect();
    let original = choices.len();
    for (s, set) in pass.sets.iter().enumerate() {
        for (o, name) in set.options.iter().enumerate().skip(1) {
            if name.is_none() {
                continue;
            }
            for v in 0..original {
                if usize::from(choices[v].0[s]) != o {
                    continue;
                }
                let mut partner = choices[v].0.clone();
                partner[s] = 0;
                let partner = Choice(partner);
                if image_of(&partner)? == image_of(&choices[v])? {
                    continue;
                }
                if present.insert(partner.clone()) {
                    choices.push(partner);
                }
                break;
            }
        }
    }
    Ok(choices.len() - original)
}

/// A pass the checks run whole (at most 1000 variants), and the variants one check of it runs:
/// all of them, or the covering set the options ask for ([`CheckOptions::cover_for`]: the
/// command line's `--cover T` without `--cover-above`).
pub(crate) struct SmallPass<'l> {
    /// The pass.
    pub(crate) pass: &'l Pass,
    /// The variants to run.
    pub(crate) choices: Vec<Choice>,
    /// The covering strength, when `choices` is a covering set.
    cover: Option<usize>,
    /// The size of the full space.
    full: usize,
}

impl<'l> SmallPass<'l> {
    /// `shader/pass` of `lib` and the variants `options` select in it.
    pub(crate) fn new(
        lib: &'l Library,
        shader: &str,
        pass: &str,
        options: &CheckOptions,
    ) -> Result<SmallPass<'l>, GpuError> {
        let what = format!("{shader}/{pass}");
        let pass = lib
            .pass(shader, pass)
            .map_err(|e| CheckError::lookup(&what, e))?;
        let every = wgsl_variants::Space::full(pass).enumerate(1000);
        let every = every.map_err(|source| GpuError::from(CheckError::Budget { what, source }))?;
        let full = every.len();
        // A strength of at least the pass's keyword sets covers its whole space.
        let cover = options
            .cover_for(full as u64)
            .filter(|&t| t < pass.sets.len());
        let choices = match cover {
            Some(t) => wgsl_variants::Space::full(pass)
                .covering(t)
                .map_err(CheckError::from)?,
            None => every,
        };
        Ok(SmallPass {
            pass,
            choices,
            cover,
            full,
        })
    }

    /// Records the variants run with their `outputs` (one per variant, in order): over the
    /// full space, whether each keyword changed some pair's output
    /// ([`judge_every_variant`]); over a covering set, which holds few such pairs, a note
    /// instead (keyword coverage is judged on the full space only, as with `--sample`).
    pub(crate) fn judge<T: PartialEq>(&self, report: &mut PassReport, outputs: &[T]) {
        match self.cover {
            None => judge_every_variant(report, self.pass, &self.choices, outputs),
            Some(t) => {
                report.variants_run += self.choices.len();
                report.distinct_shaders += self.choices.len();
                report.notes.push(format!(
                    "{t}-wise covering set of {} of the {} variants (keyword coverage is judged on the full space only)",
                    self.choices.len(),
                    self.full
                ));
            }
        }
    }
}

/// The number of variants in a pass's full space (saturated at `u64::MAX`): what
/// [`CheckOptions::cover_for`](super::options::CheckOptions::cover_for) decides on.
pub(crate) fn space_size(pass: &Pass) -> u64 {
    u64::try_from(wgsl_variants::Space::full(pass).count()).unwrap_or(u64::MAX)
}
