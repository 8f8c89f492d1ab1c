//! Region-aware covering: the audit's analysis says which keyword sets change code together
//! (coupled groups) and which change none (dead). Dead sets need no coverage; a coupled group
//! is one factor whose values are its distinct outputs (one representative assignment each),
//! so each distinct piece of code appears, t-wise with the other groups.

use crate::library::Library;
use crate::variants::{Choice, Space};

use crate::covering::{CoverError, check};

/// A region-aware t-wise covering set of `space`: every variant is in the space; every
/// distinct output of every coupled group of keyword sets appears, and every t of them from
/// different groups appear together. Dead sets stay at their first allowed option. Usually
/// smaller than [`Space::covering`] when keywords are dead or coupled; never a weaker test of
/// the code the variants generate.
///
/// ```
/// use wgsl_variants::{Library, Space, analysis::region_aware};
/// let lib = Library::from_sources([
///     (
///         "s.wgsl",
///         "#shader s\n#pass P\n#pragma multi_compile _ A\n#pragma multi_compile _ B\n\
///          #pragma multi_compile _ DEAD\n#import lib\n#endpass",
///     ),
///     ("lib.wgsl", "#if defined(A) && defined(B)\nfn ab() {}\n#endif\n"),
/// ])
/// .unwrap();
/// let space = Space::full(lib.pass("s", "P").unwrap());
/// // A and B are one group with two outputs (with or without `ab`); DEAD changes nothing.
/// assert_eq!(region_aware(&lib, &space, 1).unwrap().len(), 2);
/// assert_eq!(space.covering(1).unwrap().len(), 2);
/// assert_eq!(space.covering(2).unwrap().len(), 4);
/// assert_eq!(region_aware(&lib, &space, 2).unwrap().len(), 2);
/// ```
pub fn region_aware(lib: &Library, space: &Space<'_>, t: usize) -> Result<Vec<Choice>, CoverError> {
    let pass = space.pass();
    let regions = super::regions(lib, space);
    check(pass, &regions.factors, t)?;
    // One covering factor per enumerated group (its representatives), or per factor of a
    // group too large to enumerate.
    let mut units: Vec<Unit> = Vec::new();
    for (factors, reps) in &regions.groups {
        match reps {
            Some(reps) => units.push(Unit::Group {
                factors: factors.clone(),
                reps: reps.clone(),
            }),
            None => units.extend(factors.iter().map(|&f| Unit::Factor(f))),
        }
    }
    let levels: Vec<usize> = units
        .iter()
        .map(|u| match u {
            Unit::Group { reps, .. } => reps.len(),
            Unit::Factor(f) => regions.factors[*f].len(),
        })
        .collect();
    let rows = crate::covering::array::covering_array(&levels, t);
    let mut seen = std::collections::HashSet::new();
    Ok(rows
        .into_iter()
        .map(|row| {
            let mut options = vec![0u16; pass.sets.len()];
            // Every factor at its first choice (dead ones stay there), then the units.
            for f in &regions.factors {
                f.apply(0, &mut options);
            }
            for (unit, &v) in units.iter().zip(&row) {
                match unit {
                    Unit::Group { factors, reps } => {
                        for (&f, &d) in factors.iter().zip(&reps[v as usize]) {
                            regions.factors[f].apply(d, &mut options);
                        }
                    }
                    Unit::Factor(f) => regions.factors[*f].apply(v as usize, &mut options),
                }
            }
            Choice(options.into_boxed_slice())
        })
        .filter(|c| seen.insert(c.clone()))
        .collect())
}

enum Unit {
    Group {
        factors: Vec<usize>,
        reps: Vec<Vec<usize>>,
    },
    Factor(usize),
}
