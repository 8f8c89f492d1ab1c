//! Variant spaces: counting exactly, enumerating within a budget, and membership.
//!
//! A variant of a pass is one option per keyword set ([`Choice`]). The *full space* is the
//! product of the sets' sizes; `skip_variants` removes every variant with a skipped keyword
//! on; the *build set* is every `multi_compile` combination × the `shader_feature`
//! combinations that materials use (all of them when no materials are given), minus skipped
//! variants. Counting never enumerates and never overflows (arbitrary precision).

use std::collections::{BTreeSet, HashMap};

use num_bigint::BigUint;
use num_traits::{One, ToPrimitive};

use crate::keywords::{Constraint, KeywordError};
use crate::shader::Pass;

/// One option index per keyword set of a pass, in set order: a variant's keyword set.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Choice(pub Box<[u16]>);

impl Choice {
    /// The keywords that are on, in set order (placeholders left out).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let pass = lib.pass("standard", "Deferred").unwrap();
    /// let choice = pass.resolve(&["_NORMAL_MAP", "UNITY_HDR_ON"]).unwrap();
    /// assert_eq!(choice.keywords(pass), vec!["_NORMAL_MAP", "UNITY_HDR_ON"]);
    /// ```
    pub fn keywords<'p>(&self, pass: &'p Pass) -> Vec<&'p str> {
        self.0
            .iter()
            .zip(&pass.sets)
            .filter_map(|(&o, set)| set.options[o as usize].as_deref())
            .collect()
    }

    /// The defines a variant starts with: each keyword that is on, with value 1.
    pub fn defines(&self, pass: &Pass) -> HashMap<Box<str>, i64> {
        pass.defs(self.keywords(pass))
            .into_iter()
            .map(|(name, value)| (Box::from(name), value.as_i64()))
            .collect()
    }

    /// Whether `skip_variants` removes this variant.
    pub fn is_skipped(&self, pass: &Pass) -> bool {
        self.0
            .iter()
            .enumerate()
            .any(|(set, &o)| pass.is_skipped_option(set, o as usize))
    }

    /// The keyword set as people write it: `{_NORMAL_MAP, UNITY_HDR_ON}`, or `{}`.
    pub fn label(&self, pass: &Pass) -> String {
        format!("{{{}}}", self.keywords(pass).join(", "))
    }

    /// Number of sets in which two choices differ.
    pub fn distance(&self, other: &Choice) -> usize {
        self.0
            .iter()
            .zip(other.0.iter())
            .filter(|(a, b)| a != b)
            .count()
    }
}

/// The enumeration would exceed the build budget.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{count} variants is past the build budget of {budget} (raise it with --max-variants)")]
pub struct BudgetError {
    /// Exact number of variants.
    pub count: BigUint,
    /// The budget.
    pub budget: u64,
}

/// A set of variants of one pass: the options allowed per set, optionally restricted to the
/// `shader_feature` combinations some material uses.
///
/// Two spaces are equal when they are of the same pass (the same [`Pass`] in memory) with the
/// same allowed options and the same material combinations.
#[derive(Clone, Debug)]
pub struct Space<'p> {
    pass: &'p Pass,
    allowed: Vec<Vec<u16>>,
    /// Options of the shader_feature sets (in set order), one entry per material combination.
    features: Option<BTreeSet<Vec<u16>>>,
}

impl<'p> Space<'p> {
    /// Every variant: the product of the sets' sizes.
    pub fn full(pass: &'p Pass) -> Space<'p> {
        let allowed = pass
            .sets
            .iter()
            .map(|s| (0..s.len() as u16).collect())
            .collect();
        Space {
            pass,
            allowed,
            features: None,
        }
    }

    /// The full space minus variants with a `skip_variants` keyword on.
    pub fn after_skip(pass: &'p Pass) -> Space<'p> {
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
        Space {
            pass,
            allowed,
            features: None,
        }
    }

    /// The build set: [`Space::after_skip`], with the `shader_feature` sets restricted to
    /// `features` (each entry: one option per shader_feature set, in set order) when given.
    pub fn build_set(pass: &'p Pass, features: Option<BTreeSet<Vec<u16>>>) -> Space<'p> {
        let mut space = Space::after_skip(pass);
        if let Some(combos) = features {
            let sf: Vec<usize> = pass.shader_feature_sets().collect();
            let kept = combos
                .into_iter()
                .filter(|c| {
                    c.iter()
                        .zip(&sf)
                        .all(|(&o, &set)| space.allowed[set].contains(&o))
                })
                .collect();
            space.features = Some(kept);
        }
        space
    }

    /// The pass this space belongs to.
    pub fn pass(&self) -> &'p Pass {
        self.pass
    }

    /// The options `set` takes in some variant, ascending.
    ///
    /// ```
    /// use wgsl_variants::{Library, Space};
    /// let lib = Library::from_sources([(
    ///     "s.wgsl",
    ///     "#shader s\n#pass P\n#pragma multi_compile A B C\n#pragma skip_variants B\n#endpass",
    /// )])
    /// .unwrap();
    /// let pass = lib.pass("s", "P").unwrap();
    /// assert_eq!(Space::full(pass).options(0), vec![0, 1, 2]);
    /// assert_eq!(Space::after_skip(pass).options(0), vec![0, 2]);
    /// ```
    pub fn options(&self, set: usize) -> Vec<u16> {
        let feature = self
            .features
            .as_ref()
            .zip(self.pass.shader_feature_sets().position(|s| s == set));
        match feature {
            None => self.allowed[set].clone(),
            Some((combos, k)) => {
                let used: BTreeSet<u16> = combos.iter().map(|c| c[k]).collect();
                used.into_iter().collect()
            }
        }
    }

    /// The space as a product of independent factors, each set in exactly one: a factor per
    /// set, except that with materials the `shader_feature` sets are one joint factor (the
    /// combinations materials use), last. The joint factor is there even without
    /// `shader_feature` sets: a shader no material uses builds nothing.
    pub(crate) fn factors(&self) -> Vec<Factor> {
        let joint: Vec<usize> = match self.features {
            Some(_) => self.pass.shader_feature_sets().collect(),
            None => Vec::new(),
        };
        let mut factors: Vec<Factor> = (0..self.allowed.len())
            .filter(|set| !joint.contains(set))
            .map(|set| Factor::Set {
                set,
                options: self.allowed[set].clone(),
            })
            .collect();
        if let Some(combos) = &self.features {
            factors.push(Factor::Joint {
                sets: joint,
                tuples: combos.iter().cloned().collect(),
            });
        }
        constrain(factors, &self.pass.constraints, self.allowed.len())
    }

    /// Exact number of variants, without enumerating (constraints honoured: the sets they
    /// couple are counted together, the rest multiply).
    pub fn count(&self) -> BigUint {
        if !self.pass.constraints.is_empty() {
            return self
                .factors()
                .iter()
                .map(|f| BigUint::from(f.len()))
                .fold(BigUint::one(), |acc, n| acc * n);
        }
        match &self.features {
            None => self
                .allowed
                .iter()
                .map(|a| BigUint::from(a.len()))
                .fold(BigUint::one(), |acc, n| acc * n),
            Some(combos) => {
                let mc: BigUint = self
                    .pass
                    .multi_compile_sets()
                    .map(|s| BigUint::from(self.allowed[s].len()))
                    .fold(BigUint::one(), |a, n| a * n);
                mc * BigUint::from(combos.len())
            }
        }
    }

    /// Whether a choice is in this space.
    pub fn contains(&self, choice: &Choice) -> bool {
        if choice.0.len() != self.allowed.len()
            || !choice
                .0
                .iter()
                .zip(&self.allowed)
                .all(|(o, a)| a.contains(o))
        {
            return false;
        }
        if !self.pass.constraints.iter().all(|c| c.holds(&choice.0)) {
            return false;
        }
        match &self.features {
            None => true,
            Some(combos) => {
                let key: Vec<u16> = self
                    .pass
                    .shader_feature_sets()
                    .map(|s| choice.0[s])
                    .collect();
                combos.contains(&key)
            }
        }
    }

    /// Every variant, in [`Space::iter`] order, if there are at most `budget`.
    /// Cost is proportional to the result, whatever the size of the full space.
    pub fn enumerate(&self, budget: u64) -> Result<Vec<Choice>, BudgetError> {
        let count = self.count();
        let n = count
            .to_u64()
            .filter(|&n| n <= budget)
            .ok_or(BudgetError { count, budget })?;
        let mut out = Vec::with_capacity(n as usize);
        out.extend(self.iter());
        Ok(out)
    }

    /// The variants one at a time, without holding them: lexicographic order of set options
    /// (last set fastest); with materials, each material combination of the `shader_feature`
    /// sets in sorted order, then every `multi_compile` combination.
    pub fn iter(&self) -> SpaceIter<'_> {
        let (free, fixed, combos): (Vec<usize>, Vec<usize>, Vec<Vec<u16>>) = match &self.features {
            None => (
                (0..self.allowed.len()).collect(),
                Vec::new(),
                vec![Vec::new()],
            ),
            Some(c) => (
                self.pass.multi_compile_sets().collect(),
                self.pass.shader_feature_sets().collect(),
                c.iter().cloned().collect(),
            ),
        };
        let empty = self.allowed.iter().any(Vec::is_empty) || combos.is_empty();
        SpaceIter {
            constraints: &self.pass.constraints,
            allowed: &self.allowed,
            digits: vec![0; free.len()],
            free,
            fixed,
            combos,
            combo: 0,
            done: empty,
        }
    }
}

impl PartialEq for Space<'_> {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self.pass, other.pass)
            && self.allowed == other.allowed
            && self.features == other.features
    }
}

impl Eq for Space<'_> {}

/// One independent factor of a [`Space`] (see [`Space::factors`]).
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

/// Most combinations of the keyword sets that constraints couple together (they are listed).
pub(crate) const MAX_COUPLED: u128 = 1 << 16;

/// Checks a pass's constraints against its full space: the sets they couple have at most
/// [`MAX_COUPLED`] combinations, and every keyword a constraint names is on in some variant.
pub(crate) fn check_constraints(pass: &Pass) -> Result<(), KeywordError> {
    if pass.constraints.is_empty() {
        return Ok(());
    }
    let full = Space::full(pass);
    let mut component = (0..pass.sets.len()).collect::<Vec<usize>>();
    fn root(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for c in &pass.constraints {
        let [a, b] = c.sets();
        let (ra, rb) = (root(&mut component, a), root(&mut component, b));
        component[ra.max(rb)] = ra.min(rb);
    }
    let mut product = vec![1u128; pass.sets.len()];
    for set in 0..pass.sets.len() {
        let r = root(&mut component, set);
        product[r] = product[r].saturating_mul(pass.sets[set].len() as u128);
    }
    for c in &pass.constraints {
        let r = root(&mut component, c.sets()[0]);
        if product[r] > MAX_COUPLED {
            return Err(KeywordError::TooCoupled {
                pass: pass.name.clone(),
                combinations: product[r],
                limit: MAX_COUPLED,
                span: c.span,
            });
        }
    }
    let factors = full.factors();
    for c in &pass.constraints {
        for (keyword, &(set, option)) in c.keywords.iter().zip(&c.at) {
            let possible = factors.iter().any(|f| match f {
                Factor::Set { set: s, options } => *s != set || options.contains(&(option as u16)),
                Factor::Joint { sets, tuples } => match sets.iter().position(|&s| s == set) {
                    None => false,
                    Some(k) => tuples.iter().any(|t| t[k] as usize == option),
                },
            } && f.sets().contains(&set));
            if !possible {
                // Name the first constraint that mentions the keyword.
                let first = pass
                    .constraints
                    .iter()
                    .find(|d| d.keywords.contains(keyword))
                    .unwrap_or(c);
                return Err(KeywordError::Contradictory {
                    constraint: first.to_string(),
                    keyword: keyword.clone(),
                    pass: pass.name.clone(),
                    span: first.span,
                });
            }
        }
    }
    Ok(())
}

/// Merges the factors that constraints couple into joint factors of the combinations that
/// satisfy them (`sets` is the number of sets of the pass). Factors no constraint touches are
/// kept as they are; a merged factor takes the place of its first member.
pub(crate) fn constrain(
    factors: Vec<Factor>,
    constraints: &[Constraint],
    sets: usize,
) -> Vec<Factor> {
    if constraints.is_empty() {
        return factors;
    }
    let mut owner = vec![usize::MAX; sets];
    for (i, f) in factors.iter().enumerate() {
        for s in f.sets() {
            owner[s] = i;
        }
    }
    // Union-find over factors.
    let mut parent: Vec<usize> = (0..factors.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut touched = vec![false; factors.len()];
    for c in constraints {
        let [a, b] = c.sets().map(|s| owner[s]);
        touched[a] = true;
        touched[b] = true;
        let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
        parent[ra.max(rb)] = ra.min(rb);
    }
    let mut out = Vec::with_capacity(factors.len());
    for i in 0..factors.len() {
        if !touched[i] {
            out.push(factors[i].clone());
            continue;
        }
        if root(&mut parent, i) != i {
            continue;
        }
        let members: Vec<usize> = (0..factors.len())
            .filter(|&j| touched[j] && root(&mut parent, j) == i)
            .collect();
        let mut joint_sets: Vec<usize> = members.iter().flat_map(|&j| factors[j].sets()).collect();
        joint_sets.sort_unstable();
        let local: Vec<&Constraint> = constraints
            .iter()
            .filter(|c| members.contains(&owner[c.sets()[0]]))
            .collect();
        let mut scratch = vec![0u16; sets];
        let mut digits = vec![0usize; members.len()];
        let mut tuples = Vec::new();
        let empty = members.iter().any(|&j| factors[j].len() == 0);
        if !empty {
            loop {
                for (&j, &d) in members.iter().zip(&digits) {
                    factors[j].apply(d, &mut scratch);
                }
                if local.iter().all(|c| c.holds(&scratch)) {
                    tuples.push(joint_sets.iter().map(|&s| scratch[s]).collect::<Vec<u16>>());
                }
                // Odometer over the members' choices, last fastest.
                let mut m = members.len();
                loop {
                    if m == 0 {
                        break;
                    }
                    m -= 1;
                    digits[m] += 1;
                    if digits[m] < factors[members[m]].len() {
                        break;
                    }
                    digits[m] = 0;
                }
                if digits.iter().all(|&d| d == 0) {
                    break;
                }
            }
        }
        tuples.sort();
        out.push(Factor::Joint {
            sets: joint_sets,
            tuples,
        });
    }
    out
}

/// Iterator over a [`Space`]; see [`Space::iter`].
#[derive(Clone, Debug)]
pub struct SpaceIter<'s> {
    constraints: &'s [Constraint],
    allowed: &'s [Vec<u16>],
    free: Vec<usize>,
    fixed: Vec<usize>,
    combos: Vec<Vec<u16>>,
    combo: usize,
    digits: Vec<usize>,
    done: bool,
}

impl Iterator for SpaceIter<'_> {
    type Item = Choice;

    fn next(&mut self) -> Option<Choice> {
        // Variants that break a constraint are passed over.
        loop {
            let choice = self.next_unconstrained()?;
            if self.constraints.iter().all(|c| c.holds(&choice.0)) {
                return Some(choice);
            }
        }
    }
}

impl SpaceIter<'_> {
    fn next_unconstrained(&mut self) -> Option<Choice> {
        if self.done {
            return None;
        }
        let mut choice = vec![0u16; self.allowed.len()];
        for (&set, &o) in self.fixed.iter().zip(&self.combos[self.combo]) {
            choice[set] = o;
        }
        for (&set, &d) in self.free.iter().zip(&self.digits) {
            choice[set] = self.allowed[set][d];
        }
        // Odometer increment, last set fastest; then the next material combination.
        let mut i = self.free.len();
        loop {
            if i == 0 {
                self.combo += 1;
                self.done = self.combo == self.combos.len();
                break;
            }
            i -= 1;
            self.digits[i] += 1;
            if self.digits[i] < self.allowed[self.free[i]].len() {
                break;
            }
            self.digits[i] = 0;
        }
        Some(Choice(choice.into_boxed_slice()))
    }
}

/// One of N shards of a build: variant number `i` (counted across all selected passes, in
/// enumeration order) belongs to shard `i % N`. Written `K/N` with K from 1 to N, so a CI job
/// matrix of N jobs covers every variant exactly once.
///
/// ```
/// use wgsl_variants::variants::Shard;
/// let s: Shard = "2/3".parse().unwrap();
/// assert!(s.contains(1) && s.contains(4) && !s.contains(2));
/// assert!("0/3".parse::<Shard>().is_err() && "4/3".parse::<Shard>().is_err());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// 0-based shard number.
    pub index: u64,
    /// Number of shards.
    pub count: u64,
}

impl Shard {
    /// Whether the variant with global number `i` is in this shard.
    pub fn contains(&self, i: u64) -> bool {
        i % self.count == self.index
    }

    /// Keeps this shard's variants of `plans` (per pass, in order), numbering across passes.
    pub fn select<P>(&self, plans: Vec<(P, Vec<Choice>)>) -> Vec<(P, Vec<Choice>)> {
        let mut next = 0u64;
        plans
            .into_iter()
            .map(|(pass, choices)| {
                let kept = choices
                    .into_iter()
                    .filter(|_| {
                        let keep = self.contains(next);
                        next += 1;
                        keep
                    })
                    .collect();
                (pass, kept)
            })
            .collect()
    }
}

/// A shard written wrongly: not `K/N` with `1 <= K <= N`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{text}` is not a shard: write K/N with 1 <= K <= N, e.g. 2/4")]
pub struct ShardError {
    /// The text as written.
    pub text: String,
}

impl std::str::FromStr for Shard {
    type Err = ShardError;

    fn from_str(s: &str) -> Result<Shard, ShardError> {
        let err = || ShardError {
            text: s.to_string(),
        };
        let (k, n) = s.split_once('/').ok_or_else(err)?;
        let (k, n): (u64, u64) = (
            k.trim().parse().map_err(|_| err())?,
            n.trim().parse().map_err(|_| err())?,
        );
        if n == 0 || k == 0 || k > n {
            return Err(err());
        }
        Ok(Shard {
            index: k - 1,
            count: n,
        })
    }
}

/// Serializes an optional shard as `K/N` (for `#[serde(serialize_with)]`).
pub fn shard_text<S: serde::Serializer>(shard: &Option<Shard>, s: S) -> Result<S::Ok, S::Error> {
    match shard {
        Some(shard) => s.collect_str(shard),
        None => s.serialize_none(),
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index + 1, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Library;

    /// Sets of sizes 2 (`A B`), 3 (`_ C D`) and 2 (`E F`), with `skip` as its
    /// `skip_variants` (empty: none).
    fn library(skip: &str) -> Library {
        let skip = if skip.is_empty() {
            String::new()
        } else {
            format!("#pragma skip_variants {skip}\n")
        };
        Library::from_sources([(
            "s.wgsl",
            format!(
                "#shader s\n#pass P\n#pragma multi_compile A B\n#pragma multi_compile _ C D\n\
                 #pragma multi_compile E F\n{skip}#endpass\n"
            ),
        )])
        .unwrap()
    }

    fn choice(options: &[u16]) -> Choice {
        Choice(options.into())
    }

    /// The full space is the product of the set sizes: 2 × 3 × 2.
    #[test]
    fn full_count() {
        let lib = library("");
        let pass = lib.pass("s", "P").unwrap();
        assert_eq!(Space::full(pass).count(), BigUint::from(12u32));
        assert_eq!(Space::after_skip(pass).count(), BigUint::from(12u32));
    }

    /// `skip_variants C` removes exactly the variants with `C` on; `after_skip` keeps the
    /// full space's other variants, and `is_skipped` agrees.
    #[test]
    fn skip_variants_removes_the_right_ones() {
        let lib = library("C");
        let pass = lib.pass("s", "P").unwrap();
        let full = Space::full(pass);
        let kept = Space::after_skip(pass);
        assert_eq!(kept.count(), BigUint::from(8u32));
        assert_eq!(kept.options(1), vec![0, 2]);
        let all = full.enumerate(100).unwrap();
        let expected: Vec<Choice> = all.iter().filter(|c| c.0[1] != 1).cloned().collect();
        assert_eq!(kept.enumerate(100).unwrap(), expected);
        for c in &all {
            assert_eq!(c.is_skipped(pass), c.keywords(pass).contains(&"C"));
            assert_eq!(kept.contains(c), !c.is_skipped(pass));
            assert!(full.contains(c));
        }
        // Skipping two keywords of two sets.
        let lib = library("B D");
        let pass = lib.pass("s", "P").unwrap();
        assert_eq!(Space::after_skip(pass).count(), BigUint::from(4u32));
    }

    /// Enumeration is lexicographic, last set fastest.
    #[test]
    fn enumerate_order() {
        let lib = library("");
        let pass = lib.pass("s", "P").unwrap();
        let all = Space::full(pass).enumerate(12).unwrap();
        assert_eq!(all.len(), 12);
        assert_eq!(all[0], choice(&[0, 0, 0]));
        assert_eq!(all[1], choice(&[0, 0, 1]));
        assert_eq!(all[2], choice(&[0, 1, 0]));
        assert_eq!(all[6], choice(&[1, 0, 0]));
        assert_eq!(all[11], choice(&[1, 2, 1]));
        assert!(all.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(all[3].keywords(pass), vec!["A", "C", "F"]);
        assert_eq!(all[0].label(pass), "{A, E}");
    }

    /// Past the budget, enumeration fails with the exact count and the budget.
    #[test]
    fn enumerate_budget() {
        let lib = library("");
        let pass = lib.pass("s", "P").unwrap();
        let err = Space::full(pass).enumerate(11).unwrap_err();
        assert_eq!(
            err,
            BudgetError {
                count: BigUint::from(12u32),
                budget: 11
            }
        );
        assert!(Space::full(pass).enumerate(12).is_ok());
        assert_eq!(Space::after_skip(pass).enumerate(0).unwrap_err().budget, 0);
    }

    /// `iter` yields the same variants as `enumerate`, in the same order.
    #[test]
    fn iter_matches_enumerate() {
        for skip in ["", "C", "A E"] {
            let lib = library(skip);
            let pass = lib.pass("s", "P").unwrap();
            for space in [Space::full(pass), Space::after_skip(pass)] {
                let iterated: Vec<Choice> = space.iter().collect();
                assert_eq!(iterated, space.enumerate(1000).unwrap(), "skip {skip:?}");
                assert_eq!(BigUint::from(iterated.len()), space.count());
            }
        }
    }

    /// `K/N` parses to 0-based index K-1 of N; 0, K > N and non-numbers are rejected.
    #[test]
    fn shard_parsing() {
        let s: Shard = "2/3".parse().unwrap();
        assert_eq!(s, Shard { index: 1, count: 3 });
        assert_eq!(s.to_string(), "2/3");
        for bad in ["0/3", "4/3", "x", "1/0", "1", "a/3", "/"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
        assert!("3/3".parse::<Shard>().is_ok());
    }

    /// The shards of a split partition every pass's variants: together they are the whole,
    /// no variant is in two, and numbering continues across passes.
    #[test]
    fn shard_select_partitions() {
        let lib = library("");
        let pass = lib.pass("s", "P").unwrap();
        let all = Space::full(pass).enumerate(12).unwrap();
        let plans = vec![
            ("p1", all[..5].to_vec()),
            ("p2", Vec::new()),
            ("p3", all[5..].to_vec()),
        ];
        let n = 3;
        let shards: Vec<Vec<(&str, Vec<Choice>)>> = (1..=n)
            .map(|k| {
                format!("{k}/{n}")
                    .parse::<Shard>()
                    .unwrap()
                    .select(plans.clone())
            })
            .collect();
        // Shard 2/3 of global numbers 0..12 is 1, 4, 7, 10: two in p1, two in p3.
        assert_eq!(shards[1][0].1, vec![all[1].clone(), all[4].clone()]);
        assert_eq!(shards[1][2].1, vec![all[7].clone(), all[10].clone()]);
        for (i, (name, choices)) in plans.iter().enumerate() {
            let mut union: Vec<Choice> = Vec::new();
            for shard in &shards {
                assert_eq!(shard[i].0, *name);
                union.extend(shard[i].1.iter().cloned());
            }
            let total: usize = shards.iter().map(|s| s[i].1.len()).sum();
            assert_eq!(total, choices.len(), "overlap in {name}");
            union.sort();
            assert_eq!(&union, choices, "union of {name}");
        }
    }
}
