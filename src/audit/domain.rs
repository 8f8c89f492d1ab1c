//! The variants of one audit stage, as a product of independent factors.
//!
//! Every stage of a pass is a product: the full space and the space after `skip_variants` are
//! products of per-set option lists; with materials, the `shader_feature` sets are one joint
//! factor (the combinations materials use) times the `multi_compile` sets.

use std::collections::BTreeSet;

use num_bigint::BigUint;
use num_traits::One;

use crate::shader::Pass;

/// One independent factor of a stage's variants.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Factor {
    /// One keyword set and the options it may take.
    Set {
        /// The set.
        set: usize,
        /// Allowed options, ascending.
        options: Vec<u16>,
    },
    /// Several sets that take their options together (material combinations).
    Joint {
        /// The sets.
        sets: Vec<usize>,
        /// Allowed tuples, one option per set of `sets`, ascending.
        tuples: Vec<Vec<u16>>,
    },
}

impl Factor {
    /// Number of choices of this factor.
    pub fn len(&self) -> usize {
        match self {
            Factor::Set { options, .. } => options.len(),
            Factor::Joint { tuples, .. } => tuples.len(),
        }
    }

    /// The sets this factor decides.
    pub fn sets(&self) -> Vec<usize> {
        match self {
            Factor::Set { set, .. } => vec![*set],
            Factor::Joint { sets, .. } => sets.clone(),
        }
    }

    /// Writes choice `i` of this factor into `choice` (one option per set of the pass).
    pub fn apply(&self, i: usize, choice: &mut [u16]) {
        match self {
            Factor::Set { set, options } => choice[*set] = options[i],
            Factor::Joint { sets, tuples } => {
                for (&s, &o) in sets.iter().zip(&tuples[i]) {
                    choice[s] = o;
                }
            }
        }
    }
}

/// The variants of one stage: a product of factors covering every set exactly once.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Domain {
    /// The factors; each set of the pass is in exactly one.
    pub factors: Vec<Factor>,
    /// For each set, the factor it belongs to.
    pub factor_of: Vec<usize>,
}

impl Domain {
    fn from_allowed(
        pass: &Pass,
        allowed: Vec<Vec<u16>>,
        joint: Option<BTreeSet<Vec<u16>>>,
    ) -> Domain {
        let sf: Vec<usize> = pass.shader_feature_sets().collect();
        let mut factors = Vec::new();
        let mut factor_of = vec![0; pass.sets.len()];
        let joint_sets = if joint.is_some() {
            sf.clone()
        } else {
            Vec::new()
        };
        for (set, options) in allowed.iter().enumerate() {
            if joint_sets.contains(&set) {
                continue;
            }
            factor_of[set] = factors.len();
            factors.push(Factor::Set {
                set,
                options: options.clone(),
            });
        }
        // With materials the joint factor is there even without shader_feature sets: a shader
        // no material uses builds nothing.
        if let Some(combos) = joint {
            let tuples: Vec<Vec<u16>> = combos
                .into_iter()
                .filter(|c| {
                    c.iter()
                        .zip(&joint_sets)
                        .all(|(o, &s)| allowed[s].contains(o))
                })
                .collect();
            for &s in &joint_sets {
                factor_of[s] = factors.len();
            }
            factors.push(Factor::Joint {
                sets: joint_sets,
                tuples,
            });
        }
        Domain { factors, factor_of }
    }

    /// Every variant of the pass.
    pub fn full(pass: &Pass) -> Domain {
        let allowed = pass
            .sets
            .iter()
            .map(|s| (0..s.len() as u16).collect())
            .collect();
        Domain::from_allowed(pass, allowed, None)
    }

    /// The variants left after `skip_variants`.
    pub fn after_skip(pass: &Pass) -> Domain {
        let allowed = pass
            .sets
            .iter()
            .enumerate()
            .map(|(i, s)| {
                (0..s.len() as u16)
                    .filter(|&o| !pass.is_skipped_option(i, o as usize))
                    .collect()
            })
            .collect();
        Domain::from_allowed(pass, allowed, None)
    }

    /// The build set: after `skip_variants`, with the `shader_feature` sets restricted to
    /// `features` (one option per shader_feature set, in set order) when given.
    pub fn build(pass: &Pass, features: Option<BTreeSet<Vec<u16>>>) -> Domain {
        let after = Domain::after_skip(pass);
        let allowed = (0..pass.sets.len()).map(|s| after.options(s)).collect();
        Domain::from_allowed(pass, allowed, features)
    }

    /// Number of variants.
    pub fn count(&self) -> BigUint {
        self.factors
            .iter()
            .fold(BigUint::one(), |acc, f| acc * BigUint::from(f.len()))
    }

    /// The options `set` takes in some variant, ascending.
    pub fn options(&self, set: usize) -> Vec<u16> {
        match &self.factors[self.factor_of[set]] {
            Factor::Set { options, .. } => options.clone(),
            Factor::Joint { sets, tuples } => {
                let k = sets.iter().position(|&s| s == set).unwrap_or(0);
                let used: BTreeSet<u16> = tuples.iter().map(|t| t[k]).collect();
                used.into_iter().collect()
            }
        }
    }

    /// The option `set` has in every variant, if there is only one.
    pub fn fixed(&self, set: usize) -> Option<u16> {
        match self.options(set).as_slice() {
            [only] => Some(*only),
            _ => None,
        }
    }

    /// The first variant (first choice of every factor), or `None` when the stage is empty.
    pub fn base(&self, sets: usize) -> Option<Vec<u16>> {
        let mut choice = vec![0u16; sets];
        for f in &self.factors {
            if f.len() == 0 {
                return None;
            }
            f.apply(0, &mut choice);
        }
        Some(choice)
    }
}
