//! Covering sets of real spaces: membership, coverage of the build set, constraints, errors.

use std::collections::HashSet;

use super::*;
use crate::Library;

/// A pass with `head` as its pragmas.
fn library(head: &str) -> Library {
    Library::from_sources([("s.wgsl", format!("#shader s\n#pass P\n{head}#endpass\n"))]).unwrap()
}

/// Every t-combination of set options that occurs in `all` occurs in `cover`.
fn covers_space(all: &[Choice], cover: &[Choice], t: usize) -> bool {
    let k = all[0].0.len();
    let t = t.min(k);
    let mut subset: Vec<usize> = (0..t).collect();
    loop {
        let project = |c: &Choice| subset.iter().map(|&s| c.0[s]).collect::<Vec<u16>>();
        let want: HashSet<Vec<u16>> = all.iter().map(project).collect();
        let got: HashSet<Vec<u16>> = cover.iter().map(project).collect();
        if !want.is_subset(&got) {
            return false;
        }
        if !array::next_combination(&mut subset, k) {
            return true;
        }
    }
}

const MIXED: &str = "#pragma multi_compile A0 A1 A2\n#pragma multi_compile _ B1 B2 B3\n\
    #pragma multi_compile _ C\n#pragma shader_feature _ D\n#pragma multi_compile _ E\n\
    #pragma multi_compile F0 F1 F2\n#pragma shader_feature _ G1 G2\n";

/// On mixed-size sets with skip_variants and constraints, for t = 1..4: every variant is in
/// the build set and every t-combination of the build set is covered.
#[test]
fn covers_the_build_set() {
    for extra in [
        "",
        "#pragma skip_variants B2\n",
        "#pragma require E C\n#pragma exclude G1 B3\n",
        "#pragma require D C\n#pragma exclude A1 F1 G2\n#pragma skip_variants F0\n",
    ] {
        let lib = library(&format!("{MIXED}{extra}"));
        let pass = lib.pass("s", "P").unwrap();
        let space = Space::after_skip(pass);
        let all = space.enumerate(100_000).unwrap();
        for t in 1..=4 {
            let cover = space.covering(t).unwrap();
            assert!(cover.iter().all(|c| space.contains(c)), "{extra:?} t={t}");
            assert!(covers_space(&all, &cover, t), "{extra:?} t={t}");
            assert!(cover.len() <= all.len());
            let unique: HashSet<&Choice> = cover.iter().collect();
            assert_eq!(unique.len(), cover.len(), "duplicates at t={t}");
        }
    }
}

/// Constraints change the count exactly as enumeration does, and a required keyword is on
/// wherever its dependent is.
#[test]
fn constraints_count_and_hold() {
    let lib = library(&format!(
        "{MIXED}#pragma require E C\n#pragma exclude G1 B3\n"
    ));
    let pass = lib.pass("s", "P").unwrap();
    let full = Space::full(pass);
    let listed = full.enumerate(100_000).unwrap();
    assert_eq!(num_bigint::BigUint::from(listed.len()), full.count());
    // 3*4*2*2*2*3*3 = 864; E without C removes a quarter of the E/C combinations, G1 with
    // B3 one in twelve of the B/G ones.
    assert_eq!(listed.len(), 864 / 4 * 3 / 12 * 11);
    for c in &listed {
        let on = c.keywords(pass);
        assert!(!on.contains(&"E") || on.contains(&"C"));
        assert!(!(on.contains(&"G1") && on.contains(&"B3")));
    }
}

/// Materials' combinations: the covering set stays inside the build set.
#[test]
fn materials_respected() {
    let lib = library(MIXED);
    let pass = lib.pass("s", "P").unwrap();
    let combos: std::collections::BTreeSet<Vec<u16>> =
        [vec![0, 0], vec![1, 2], vec![1, 1]].into_iter().collect();
    let space = Space::build_set(pass, Some(combos));
    let all = space.enumerate(100_000).unwrap();
    for t in 1..=3 {
        let cover = space.covering(t).unwrap();
        assert!(cover.iter().all(|c| space.contains(c)));
        assert!(covers_space(&all, &cover, t));
    }
}

/// Bad strengths and an empty build set are typed errors naming the pass.
#[test]
fn errors() {
    let lib = library("#pragma multi_compile _ A\n#pragma multi_compile _ B\n");
    let pass = lib.pass("s", "P").unwrap();
    let space = Space::full(pass);
    assert!(matches!(space.covering(0), Err(CoverError::ZeroStrength { pass, .. }) if pass == "P"));
    assert!(matches!(
        space.covering(3),
        Err(CoverError::TooStrong { t: 3, sets: 2, .. })
    ));
    assert!(matches!(
        space.covering(5),
        Err(CoverError::Unsupported { t: 5, .. })
    ));
    // t = the number of sets: the whole space.
    assert_eq!(space.covering(2).unwrap().len(), 4);
    // `require A B` with B skipped and a set without a "none" option for A: nothing left.
    let lib = library(
        "#pragma multi_compile A X\n#pragma multi_compile _ B\n#pragma require A B\n#pragma require X B\n#pragma skip_variants B\n",
    );
    let pass = lib.pass("s", "P").unwrap();
    let err = Space::after_skip(pass).covering(1).unwrap_err();
    assert!(
        matches!(&err, CoverError::Empty { constraints, .. } if constraints.len() == 2),
        "{err:?}"
    );
    assert!(err.to_string().contains("s/P") && err.to_string().contains("require A B"));
}

/// Same space, same covering set; with 64 binary sets, the optimum 10.
#[test]
fn deterministic_and_optimal_pairs() {
    let head: String = (0..64)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let lib = library(&head);
    let pass = lib.pass("s", "P").unwrap();
    let a = Space::full(pass).covering(2).unwrap();
    assert_eq!(a.len(), 10);
    assert_eq!(a, Space::full(pass).covering(2).unwrap());
}

/// The first variant covers every tuple it has; later ones only new ones.
#[test]
fn first_covered_counts() {
    let head: String = (0..4)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let lib = library(&head);
    let pass = lib.pass("s", "P").unwrap();
    let cover = Space::full(pass).covering(2).unwrap();
    assert_eq!(first_covered(&cover, 0, 2).len(), 6);
    let total: usize = (0..cover.len())
        .map(|i| first_covered(&cover, i, 2).len())
        .sum();
    assert_eq!(total, 6 * 4);
}

/// Shrinking keeps only the keywords the failure needs.
#[test]
fn shrink_to_the_culprits() {
    let head: String = (0..6)
        .map(|i| format!("#pragma multi_compile _ K{i}\n"))
        .collect();
    let lib = library(&head);
    let pass = lib.pass("s", "P").unwrap();
    let space = Space::full(pass);
    let all_on = pass.resolve(&["K0", "K1", "K2", "K3", "K4", "K5"]).unwrap();
    let fails = |c: &Choice| {
        let on = c.keywords(pass);
        on.contains(&"K1") && on.contains(&"K4")
    };
    let small = shrink(&space, &all_on, fails);
    assert_eq!(small.keywords(pass), vec!["K1", "K4"]);
}

/// Under `require`, turning one keyword off may leave the space; the shrinker takes the
/// keywords that need it along, and moves sets without a "none" option to their first.
#[test]
fn shrink_is_minimal_under_constraints() {
    let lib = library(
        "#pragma multi_compile _ TANGENTS\n#pragma multi_compile _ TONEMAP\n\
         #pragma multi_compile OFF NONE ACES\n#pragma require NONE TONEMAP\n\
         #pragma require ACES TONEMAP\n#pragma exclude OFF TONEMAP\n",
    );
    let pass = lib.pass("s", "P").unwrap();
    let space = Space::full(pass);
    let start = pass.resolve(&["TANGENTS", "TONEMAP", "NONE"]).unwrap();
    assert!(space.contains(&start));
    let fails = |c: &Choice| c.keywords(pass).contains(&"TANGENTS");
    let small = shrink(&space, &start, fails);
    assert_eq!(small.keywords(pass), vec!["TANGENTS", "OFF"]);
}
