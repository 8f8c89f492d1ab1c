//! Counting distinct composed texts without enumerating the space.
//!
//! The static walk ([`super::deps`]) cuts the composed text into slots: constant runs and
//! regions, each region depending on one class of keyword sets. Each class (a *component*) is
//! enumerated on its own (the other sets fixed), recording the outputs of its regions. If the
//! concatenation of slot outputs is unambiguous — no two different tuples of slot outputs
//! give the same text — the number of distinct texts is the product over components of their
//! numbers of distinct region-output tuples.
//!
//! Unambiguity is checked, not assumed: if two texts are equal but their slot outputs differ,
//! at the first differing slot one output is a proper prefix of the other, and the first line
//! of the excess must be a possible first line of what follows. For every region the check
//! computes those candidate lines (from the region's outputs) and looks for them among the
//! possible first lines of the following slots (up to the first slot that always emits a
//! line). A conflict fuses the slots involved into one (joining their components) and the
//! check runs again. When it passes, the product is exact. When a component grows past the
//! enumeration limit, the whole space is enumerated if it fits the budget (exact); otherwise
//! the product is reported as an upper bound.

use std::collections::{BTreeSet, HashMap, HashSet};

use num_bigint::BigUint;
use num_traits::{One, ToPrimitive, Zero};
use rayon::prelude::*;

use crate::preprocess::compose::ModuleGraph;
use crate::shader::Pass;
use crate::variants::{Factor, Space};

use super::Method;
use super::compose::{IdComposer, IdText, LineIds};
use super::deps::{self, Slot, Template};

/// Rows composed per parallel batch.
const BATCH: usize = 4096;
/// Above this many rows, whole texts are keyed by 128 bits of their BLAKE3 hash instead of
/// kept (a collision among a few million texts has a probability below 2^-80).
const HASH_ABOVE: usize = 1 << 16;

/// Class of every assignment of a component, in mixed-radix order over its factors (the last
/// factor fastest).
#[derive(Clone, Debug)]
pub(crate) struct Table {
    /// Number of choices of each factor of the component.
    pub radix: Vec<usize>,
    /// The class of each row; rows with the same class compose to the same text (given the
    /// same choices elsewhere).
    pub class: Vec<u32>,
    /// Number of classes.
    pub classes: u32,
}

impl Table {
    /// The factor choices of a row.
    pub fn digits(&self, mut row: usize) -> Vec<usize> {
        let mut d = vec![0; self.radix.len()];
        for (i, r) in self.radix.iter().enumerate().rev() {
            d[i] = row % r;
            row /= r;
        }
        d
    }

    /// The row of some factor choices.
    pub fn row(&self, digits: &[usize]) -> usize {
        digits
            .iter()
            .zip(&self.radix)
            .fold(0, |acc, (d, r)| acc * r + d)
    }
}

/// Keyword sets that change code together, and how their assignments group by code.
#[derive(Clone, Debug)]
pub(crate) struct Component {
    /// Factors of the component (indices into [`Analysis::factors`]), ascending.
    pub factors: Vec<usize>,
    /// Keyword sets of the component, ascending.
    pub sets: Vec<usize>,
    /// Number of assignments (product of the factors' sizes).
    pub size: BigUint,
    /// The classes, when the component was enumerated.
    pub table: Option<Table>,
}

/// Distinct texts of one stage of a pass.
#[derive(Clone, Debug)]
pub(crate) struct Analysis<'p> {
    /// The stage.
    pub space: Space<'p>,
    /// The stage as a product of factors ([`Space::factors`]), which rows enumerate.
    pub factors: Vec<Factor>,
    /// Number of variants.
    pub count: BigUint,
    /// Distinct texts: exact when `exact`, else an upper bound.
    pub distinct: BigUint,
    /// Whether `distinct` is exact.
    pub exact: bool,
    /// How it was obtained.
    pub method: Method,
    /// Components that change code (with `Method::Enumeration`, one holding every set).
    pub components: Vec<Component>,
    /// Sets in no component: no variant's text depends on them.
    pub dead: Vec<usize>,
}

/// Limits of the analysis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Limits {
    /// Most assignments enumerated for one component.
    pub component: u64,
    /// Most variants enumerated when the components cannot be certified.
    pub whole: u64,
}

struct Ctx<'a> {
    composer: IdComposer<'a>,
    template: Option<&'a Template>,
    pass: &'a Pass,
    factors: &'a [Factor],
    base: Vec<u16>,
}

/// Per-unit outputs of an enumerated component.
struct Enumerated {
    table: Table,
    /// For each unit of the component (in the order given): its distinct outputs, sorted.
    outputs: Vec<Vec<Vec<u32>>>,
}

/// Counts the distinct texts of `space`.
pub(crate) fn analyze<'p>(
    graph: &ModuleGraph<'_>,
    ids: &LineIds,
    pass: &Pass,
    space: Space<'p>,
    limits: Limits,
) -> Analysis<'p> {
    let count = space.count();
    let factors = space.factors();
    let Some(base) = base(&factors, pass.sets.len()) else {
        return Analysis {
            count: count.clone(),
            distinct: BigUint::zero(),
            exact: true,
            method: Method::Components,
            components: Vec::new(),
            dead: (0..pass.sets.len()).collect(),
            space,
            factors,
        };
    };
    let template = deps::analyze(graph, ids, pass, &space).ok();
    let outcome = template
        .as_ref()
        .map(|t| by_components(graph, ids, pass, &factors, &base, t, limits));
    match outcome {
        Some(Ok((components, dead))) => {
            let distinct = components
                .iter()
                .map(|c| BigUint::from(c.table.as_ref().map_or(1, |t| t.classes)))
                .fold(BigUint::one(), |a, b| a * b);
            Analysis {
                count,
                distinct,
                exact: true,
                method: Method::Components,
                components,
                dead,
                space,
                factors,
            }
        }
        other => {
            let fits = count.to_u64().is_some_and(|n| n <= limits.whole);
            if fits {
                whole(graph, ids, pass, space, factors, base, count)
            } else {
                let (components, dead) = match other {
                    Some(Err(partial)) => partial,
                    _ => (Vec::new(), Vec::new()),
                };
                // A text is a function of its components' classes: their product bounds it.
                let distinct = if components.is_empty() && dead.is_empty() {
                    count.clone()
                } else {
                    components
                        .iter()
                        .map(|c| match &c.table {
                            Some(t) => BigUint::from(t.classes),
                            None => c.size.clone(),
                        })
                        .fold(BigUint::one(), |a, b| a * b)
                };
                Analysis {
                    count,
                    distinct,
                    exact: false,
                    method: Method::Bound,
                    components,
                    dead,
                    space,
                    factors,
                }
            }
        }
    }
}

type Parts = (Vec<Component>, Vec<usize>);

/// A component's factors and units: what its enumeration depends on.
type CacheKey = (Vec<usize>, Vec<(usize, usize)>);

/// The component analysis: `Ok` when certified exact, `Err` with what is known otherwise.
fn by_components(
    graph: &ModuleGraph<'_>,
    ids: &LineIds,
    pass: &Pass,
    factors: &[Factor],
    base: &[u16],
    template: &Template,
    limits: Limits,
) -> Result<Parts, Parts> {
    let ctx = Ctx {
        composer: IdComposer {
            graph,
            ids,
            regions: &template.regions,
            slots: template.slots.len(),
        },
        template: Some(template),
        pass,
        factors,
        base: base.to_vec(),
    };
    let mut factor_of = vec![0; pass.sets.len()];
    let mut uf = template.uf.clone();
    for (i, f) in factors.iter().enumerate() {
        let sets = f.sets();
        for &s in &sets {
            factor_of[s] = i;
        }
        for w in sets.windows(2) {
            uf.union(w[0], w[1]);
        }
    }
    // Units: ranges of slots, each its own unit to start with.
    let mut units: Vec<(usize, usize)> = (0..template.slots.len()).map(|i| (i, i)).collect();
    let mut cache: HashMap<CacheKey, Option<Enumerated>> = HashMap::new();
    loop {
        // Components: the classes of the sets that some region depends on.
        let region_set = |slot: usize| match template.slots[slot] {
            Slot::Region(s) => Some(s),
            Slot::Const(_) => None,
        };
        let unit_class: Vec<Option<usize>> = units
            .iter()
            .map(|&(a, b)| (a..=b).find_map(region_set).map(|s| uf.find(s)))
            .collect();
        let roots: BTreeSet<usize> = unit_class.iter().flatten().copied().collect();
        let mut components = Vec::new();
        let mut comp_units = Vec::new();
        for &root in &roots {
            let sets: Vec<usize> = (0..pass.sets.len())
                .filter(|&s| uf.find(s) == root)
                .collect();
            let mine_factors: BTreeSet<usize> = sets.iter().map(|&s| factor_of[s]).collect();
            let mine_factors: Vec<usize> = mine_factors.into_iter().collect();
            let size = mine_factors
                .iter()
                .fold(BigUint::one(), |a, &f| a * BigUint::from(factors[f].len()));
            let mine: Vec<usize> = (0..units.len())
                .filter(|&u| unit_class[u] == Some(root))
                .collect();
            components.push(Component {
                factors: mine_factors,
                sets,
                size,
                table: None,
            });
            comp_units.push(mine);
        }
        let dead: Vec<usize> = (0..pass.sets.len())
            .filter(|&s| !roots.contains(&uf.find(s)))
            .collect();
        let mut outputs: HashMap<usize, Vec<Vec<u32>>> = HashMap::new();
        let mut complete = true;
        for (c, mine) in components.iter_mut().zip(&comp_units) {
            let key = (c.factors.clone(), mine.iter().map(|&u| units[u]).collect());
            let entry = cache.entry(key).or_insert_with(|| {
                let fits = c.size.to_u64().is_some_and(|n| n <= limits.component);
                fits.then(|| enumerate(&ctx, &c.factors, mine, &units))
            });
            match entry {
                Some(e) => {
                    c.table = Some(e.table.clone());
                    for (&u, outs) in mine.iter().zip(&e.outputs) {
                        outputs.insert(u, outs.clone());
                    }
                }
                None => complete = false,
            }
        }
        if !complete {
            return Err((components, dead));
        }
        let conflicts = conflicts(template, &units, &outputs);

        if conflicts.is_empty() {
            return Ok((components, dead));
        }
        // Fuse each conflicting range of units into one unit, joining their components.
        let mut fused: Vec<(usize, usize)> = Vec::new();
        let mut i = 0;
        let mut ranges = conflicts.into_iter().peekable();
        while i < units.len() {
            match ranges.peek() {
                Some(&(a, mut b)) if a == i => {
                    ranges.next();
                    while let Some(&(a2, b2)) = ranges.peek() {
                        if a2 > b {
                            break;
                        }
                        b = b.max(b2);
                        ranges.next();
                    }
                    let members: Vec<usize> = unit_class[a..=b].iter().flatten().copied().collect();
                    for w in members.windows(2) {
                        uf.union(w[0], w[1]);
                    }
                    fused.push((units[a].0, units[b].1));
                    i = b + 1;
                }
                _ => {
                    fused.push(units[i]);
                    i += 1;
                }
            }
        }
        units = fused;
    }
}

/// Output range of a unit in a composed text.
fn unit_range(template: &Template, text: &IdText, (first, last): (usize, usize)) -> (usize, usize) {
    let start = match template.slots[first] {
        Slot::Region(_) => text.spans[first].0 as usize,
        // Units that start with a constant slot are never enumerated.
        Slot::Const(_) => 0,
    };
    let end = match template.slots[last] {
        Slot::Region(_) => text.spans[last].1 as usize,
        Slot::Const(_) => match template.slots.get(last + 1) {
            Some(_) => text.spans[last + 1].0 as usize,
            None => text.lines.len(),
        },
    };
    (start, end)
}

/// Enumerates a component: every assignment of its factors, the rest at the base variant.
fn enumerate(
    ctx: &Ctx<'_>,
    factors: &[usize],
    mine: &[usize],
    units: &[(usize, usize)],
) -> Enumerated {
    let radix: Vec<usize> = factors.iter().map(|&f| ctx.factors[f].len()).collect();
    let rows: usize = radix.iter().product();
    let template = ctx.template.expect("components come from a template");
    let template_units: Vec<(usize, usize)> = mine.iter().map(|&u| units[u]).collect();
    let mut table = Table {
        radix,
        class: Vec::with_capacity(rows),
        classes: 0,
    };
    let mut index: HashMap<Vec<u32>, u32> = HashMap::new();
    let mut outs: Vec<HashSet<Vec<u32>>> = vec![HashSet::new(); mine.len()];
    let mut start = 0;
    while start < rows {
        let end = (start + BATCH).min(rows);
        let parts: Vec<Vec<Vec<u32>>> = (start..end)
            .into_par_iter()
            .map(|row| {
                let choice = choice_of(ctx, factors, &table.digits(row));
                let text = ctx.composer.compose(ctx.pass, &choice);
                template_units
                    .iter()
                    .map(|&u| {
                        let (a, b) = unit_range(template, &text, u);
                        text.lines[a..b].to_vec()
                    })
                    .collect()
            })
            .collect();
        for p in parts {
            let mut key = Vec::with_capacity(p.iter().map(|o| o.len() + 1).sum());
            for o in &p {
                key.extend_from_slice(o);
                key.push(u32::MAX);
            }
            let next = index.len() as u32;
            table.class.push(*index.entry(key).or_insert(next));
            for (set, o) in outs.iter_mut().zip(p) {
                set.insert(o);
            }
        }
        start = end;
    }
    table.classes = index.len() as u32;
    let outputs = outs
        .into_iter()
        .map(|set| {
            let mut v: Vec<Vec<u32>> = set.into_iter().collect();
            v.sort();
            v
        })
        .collect();
    Enumerated { table, outputs }
}

/// The full choice for some factor digits, the other factors at the base variant.
fn choice_of(ctx: &Ctx<'_>, factors: &[usize], digits: &[usize]) -> Vec<u16> {
    let mut choice = ctx.base.clone();
    for (&f, &d) in factors.iter().zip(digits) {
        ctx.factors[f].apply(d, &mut choice);
    }
    choice
}

/// Conflicting unit ranges `(i, j)` (unit indices), ascending by `i`.
fn conflicts(
    template: &Template,
    units: &[(usize, usize)],
    outputs: &HashMap<usize, Vec<Vec<u32>>>,
) -> Vec<(usize, usize)> {
    // First lines and nullability of each unit.
    let info: Vec<(HashSet<u32>, bool)> = (0..units.len())
        .map(|u| match outputs.get(&u) {
            Some(outs) => (
                outs.iter().filter_map(|o| o.first().copied()).collect(),
                outs.iter().any(Vec::is_empty),
            ),
            None => {
                let (a, b) = units[u];
                let lines: Vec<u32> = (a..=b)
                    .flat_map(|s| match &template.slots[s] {
                        Slot::Const(l) => l.clone(),
                        Slot::Region(_) => Vec::new(),
                    })
                    .collect();
                (
                    lines.first().copied().into_iter().collect(),
                    lines.is_empty(),
                )
            }
        })
        .collect();
    let mut found = Vec::new();
    for (u, outs) in outputs_sorted(outputs) {
        let candidates = prefix_extensions(outs);
        if candidates.is_empty() {
            continue;
        }
        let mut reach = None;
        for (j, (first, nullable)) in info.iter().enumerate().skip(u + 1) {
            if first.iter().any(|l| candidates.contains(l)) {
                reach = Some(j);
            }
            if !nullable {
                break;
            }
        }
        if let Some(j) = reach {
            found.push((u, j));
        }
    }
    found
}

fn outputs_sorted(outputs: &HashMap<usize, Vec<Vec<u32>>>) -> Vec<(usize, &Vec<Vec<u32>>)> {
    let mut v: Vec<_> = outputs.iter().map(|(&u, o)| (u, o)).collect();
    v.sort_by_key(|x| x.0);
    v
}

/// Lines `v[len(u)]` for outputs `u`, `v` where `u` is a proper prefix of `v` (`outs` sorted).
fn prefix_extensions(outs: &[Vec<u32>]) -> HashSet<u32> {
    let mut lines = HashSet::new();
    for (p, u) in outs.iter().enumerate() {
        for v in &outs[p + 1..] {
            if !v.starts_with(u) {
                break;
            }
            if v.len() > u.len() {
                lines.insert(v[u.len()]);
            }
        }
    }
    lines
}

/// Enumerates the whole space: exact, within the budget.
fn whole<'p>(
    graph: &ModuleGraph<'_>,
    ids: &LineIds,
    pass: &Pass,
    space: Space<'p>,
    factors: Vec<Factor>,
    base: Vec<u16>,
    count: BigUint,
) -> Analysis<'p> {
    let regions = HashMap::new();
    let ctx = Ctx {
        composer: IdComposer {
            graph,
            ids,
            regions: &regions,
            slots: 0,
        },
        template: None,
        pass,
        factors: &factors,
        base,
    };
    let all: Vec<usize> = (0..factors.len()).collect();
    let radix: Vec<usize> = factors.iter().map(|f| f.len()).collect();
    let rows: usize = radix.iter().product();
    let hashed = rows > HASH_ABOVE;
    let mut table = Table {
        radix,
        class: Vec::with_capacity(rows),
        classes: 0,
    };
    let mut index: HashMap<Vec<u32>, u32> = HashMap::new();
    let mut start = 0;
    while start < rows {
        let end = (start + BATCH).min(rows);
        let keys: Vec<Vec<u32>> = (start..end)
            .into_par_iter()
            .map(|row| {
                let choice = choice_of(&ctx, &all, &table.digits(row));
                let lines = ctx.composer.compose(pass, &choice).lines;
                if hashed { hash128(&lines) } else { lines }
            })
            .collect();
        for key in keys {
            let next = index.len() as u32;
            table.class.push(*index.entry(key).or_insert(next));
        }
        start = end;
    }
    table.classes = index.len() as u32;
    let sets: Vec<usize> = (0..pass.sets.len()).collect();
    let distinct = BigUint::from(table.classes);
    Analysis {
        space,
        factors,
        count: count.clone(),
        distinct,
        exact: true,
        method: Method::Enumeration,
        components: vec![Component {
            factors: all,
            sets,
            size: count,
            table: Some(table),
        }],
        dead: Vec::new(),
    }
}

/// A BLAKE3 hash of a line sequence (128 of its bits, as four words).
fn hash128(lines: &[u32]) -> Vec<u32> {
    let mut h = blake3::Hasher::new();
    for l in lines {
        h.update(&l.to_le_bytes());
    }
    let digest = h.finalize();
    digest.as_bytes()[..16]
        .chunks(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

/// The first variant (first choice of every factor), or `None` when the space is empty.
fn base(factors: &[Factor], sets: usize) -> Option<Vec<u16>> {
    let mut choice = vec![0u16; sets];
    for f in factors {
        if f.len() == 0 {
            return None;
        }
        f.apply(0, &mut choice);
    }
    Some(choice)
}
