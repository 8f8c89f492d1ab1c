//! Per-keyword findings over the full space: dead keywords, options that always generate the
//! same code, and keywords that change code only together with others.

use crate::shader::Pass;
use crate::variants::Factor;

use crate::analysis::distinct::{Analysis, Table};

/// What the full-space analysis says about one keyword set.
#[derive(Clone, Debug, Default)]
pub(crate) struct SetFindings {
    /// Whether the findings are known (the set's component was enumerated, or it is dead).
    pub known: bool,
    /// No option of the set changes any code.
    pub dead: bool,
    /// Option groups (≥ 2 options each) that generate identical code in every variant.
    pub equivalent: Vec<Vec<usize>>,
    /// Options that generate the same code as the set's base option in every variant (every
    /// option, base included, when the whole set is dead).
    pub dead_options: Vec<usize>,
    /// Options that change code, but not alone from the all-off variant: the minimal
    /// contexts (other keywords on) in which they do.
    pub together: Vec<(usize, Vec<Vec<String>>)>,
}

/// Most minimal contexts listed for a keyword.
const MAX_CONTEXTS: usize = 8;

/// The base option of a set: its "none" option, else its first.
pub(crate) fn base_option(pass: &Pass, set: usize) -> usize {
    pass.sets[set].none_index().unwrap_or(0)
}

/// Findings for every set of `pass` from its full-space analysis.
pub(crate) fn findings(pass: &Pass, full: &Analysis) -> Vec<SetFindings> {
    let mut out = vec![SetFindings::default(); pass.sets.len()];
    for &s in &full.dead {
        let n = pass.sets[s].len();
        out[s] = SetFindings {
            known: true,
            dead: n > 1,
            equivalent: if n > 1 {
                vec![(0..n).collect()]
            } else {
                Vec::new()
            },
            dead_options: (0..n).filter(|_| n > 1).collect(),
            together: Vec::new(),
        };
    }
    for c in &full.components {
        let Some(table) = &c.table else { continue };
        // Per-set findings read the table one set per digit; a factor that constraints
        // merge spans several sets, so its sets' findings stay unknown.
        if c.factors
            .iter()
            .any(|&f| matches!(full.factors[f], Factor::Joint { .. }))
        {
            continue;
        }
        for (pos, &s) in c.sets.iter().enumerate() {
            out[s] = set_findings(pass, &c.sets, table, pos);
        }
    }
    out
}

fn set_findings(pass: &Pass, sets: &[usize], table: &Table, pos: usize) -> SetFindings {
    let s = sets[pos];
    let n = pass.sets[s].len();
    let base = base_option(pass, s);
    // Signature of each option: the class of every row with that option, the rest varying.
    let rows = table.class.len();
    let mut sig: Vec<Vec<u32>> = vec![Vec::with_capacity(rows / n.max(1)); n];
    for row in 0..rows {
        let mut d = table.digits(row);
        if d[pos] != 0 {
            continue;
        }
        for (o, sig) in sig.iter_mut().enumerate() {
            d[pos] = o;
            sig.push(table.class[table.row(&d)]);
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for o in 0..n {
        match groups.iter_mut().find(|g| sig[g[0]] == sig[o]) {
            Some(g) => g.push(o),
            None => groups.push(vec![o]),
        }
    }
    let dead_options: Vec<usize> = (0..n)
        .filter(|&o| o != base && sig[o] == sig[base])
        .collect();
    let dead = n > 1 && groups.len() == 1;
    let mut together = Vec::new();
    let bases: Vec<usize> = sets.iter().map(|&t| base_option(pass, t)).collect();
    for o in (0..n).filter(|&o| o != base && sig[o] != sig[base]) {
        let mut d = bases.clone();
        let off = table.class[table.row(&d)];
        d[pos] = o;
        if table.class[table.row(&d)] != off {
            continue;
        }
        // Minimal contexts in which switching from the base option to `o` changes code.
        let mut best = usize::MAX;
        let mut contexts: Vec<Vec<String>> = Vec::new();
        for row in 0..rows {
            let mut d = table.digits(row);
            if d[pos] != base {
                continue;
            }
            let weight = (0..d.len()).filter(|&i| d[i] != bases[i]).count();
            if weight > best {
                continue;
            }
            let here = table.class[row];
            d[pos] = o;
            if table.class[table.row(&d)] == here {
                continue;
            }
            if weight < best {
                best = weight;
                contexts.clear();
            }
            if contexts.len() < MAX_CONTEXTS {
                contexts.push(
                    (0..d.len())
                        .filter(|&i| i != pos && d[i] != bases[i])
                        .filter_map(|i| pass.sets[sets[i]].options[d[i]].clone())
                        .collect(),
                );
            }
        }
        together.push((o, contexts));
    }
    SetFindings {
        known: true,
        dead,
        equivalent: groups.into_iter().filter(|g| g.len() > 1).collect(),
        dead_options: if dead { (0..n).collect() } else { dead_options },
        together,
    }
}
