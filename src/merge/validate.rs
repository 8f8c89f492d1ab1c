//! Merging the `validate --json` reports of N shards into the report of the whole run.
//!
//! Totals are sums, except distinct texts: a text produced in two shards is counted once
//! (joined by the dedup keys a shard lists when the audit cannot prove every text distinct).
//! Failures of one text in several shards become one failure whose keyword sets are in
//! enumeration order (by the variant numbers a shard records), taken from the shard that saw
//! the text first; failures are ordered by their first variant, as one machine orders them.

use std::collections::{BTreeMap, HashMap, HashSet};

use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;

use super::{MergeError, ShardInfo, order_shards, parse_shard};
use crate::error::Stage;
use crate::validate::{Selection, ValidateTotals};
use crate::variants::Shard;

/// A failure as `validate --json` writes it (field order as [`crate::validate::Failure`]).
#[derive(Clone, Debug, Deserialize, Serialize)]
struct FailureJson {
    stage: Stage,
    message: String,
    location: Option<String>,
    keyword_sets: Vec<Vec<String>>,
    diagnostic: String,
    #[serde(default, skip_serializing)]
    text: Option<String>,
    #[serde(default, skip_serializing)]
    numbers: Vec<u64>,
}

/// A pass as `validate --json` writes it (field order as [`crate::validate::PassReport`]).
#[derive(Debug, Deserialize, Serialize)]
struct PassJson {
    shader: String,
    pass: String,
    /// Written as an exact integer of any size: kept as written.
    full_space: Box<RawValue>,
    built: u64,
    distinct: u64,
    valid: u64,
    invalid: u64,
    failures: Vec<FailureJson>,
    #[serde(default, skip_serializing)]
    texts: Option<Vec<String>>,
}

/// A report as `validate --json` writes it (field order as
/// [`crate::validate::ValidateReport`]).
#[derive(Debug, Deserialize, Serialize)]
struct ReportJson {
    ok: bool,
    selection: Selection,
    #[serde(default, skip_serializing_if = "String::is_empty")]
    fingerprint: String,
    #[serde(default, skip_serializing)]
    shard: Option<String>,
    passes: Vec<PassJson>,
    totals: ValidateTotals,
}

/// Merges shard reports, given as `(name, JSON text)` in any order, into the JSON text that
/// `validate --json` prints for the whole run (pretty, with a final newline), byte for byte.
/// Returns the text and whether no variant failed.
pub fn merge_reports(inputs: &[(String, String)]) -> Result<(String, bool), MergeError> {
    let reports = inputs
        .iter()
        .map(|(name, text)| {
            let report =
                serde_json::from_str::<ReportJson>(text).map_err(|e| MergeError::Kind {
                    shard: name.clone(),
                    expected: "a `validate --json` report",
                    message: e.to_string(),
                })?;
            one_profile(name, &report)?;
            Ok(report)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let infos = inputs
        .iter()
        .zip(&reports)
        .map(|((name, _), r)| {
            Ok(ShardInfo {
                name: name.clone(),
                shard: parse_shard(name, r.shard.as_deref())?,
                fingerprint: r.fingerprint.clone(),
            })
        })
        .collect::<Result<Vec<_>, MergeError>>()?;
    for ((name, _), (report, info)) in inputs.iter().zip(reports.iter().zip(&infos)) {
        self_check(name, report, info.shard)?;
    }
    let order = order_shards(&infos)?;
    let mut shards: Vec<(String, ReportJson)> = Vec::new();
    let mut reports: Vec<Option<ReportJson>> = reports.into_iter().map(Some).collect();
    for i in order {
        if let Some(r) = reports[i].take() {
            shards.push((inputs[i].0.clone(), r));
        }
    }
    let merged = merge(shards)?;
    let mut text = serde_json::to_string_pretty(&merged).map_err(|e| MergeError::Write {
        path: "<stdout>".into(),
        source: e.into(),
    })?;
    text.push('\n');
    Ok((text, merged.ok))
}

/// A report of several profiles' verdicts is not merged (its per-profile counts and failures
/// would need their own joining): validate and merge each profile's shards apart.
fn one_profile(name: &str, report: &ReportJson) -> Result<(), MergeError> {
    if report.totals.profiles.is_empty() {
        return Ok(());
    }
    let names: Vec<&str> = report
        .totals
        .profiles
        .iter()
        .map(|p| p.profile.as_str())
        .collect();
    Err(MergeError::Kind {
        shard: name.to_string(),
        expected: "a report of one profile",
        message: format!(
            "it validates for several ({}); run and merge the shards of each `--profile` apart",
            names.join(", ")
        ),
    })
}

fn mismatch(name: &str, message: String) -> MergeError {
    MergeError::Mismatch {
        shard: name.to_string(),
        message,
    }
}

/// Merges reports already in shard order.
fn merge(shards: Vec<(String, ReportJson)>) -> Result<ReportJson, MergeError> {
    let mut shards = shards.into_iter();
    let (_, mut merged) = shards.next().ok_or(MergeError::Empty)?;
    merged.shard = None;
    // Per pass: distinct keys when listed, and failures by text key.
    let mut keys: Vec<Option<HashSet<String>>> = Vec::new();
    let mut failures: Vec<Vec<FailureJson>> = Vec::new();
    for pass in &mut merged.passes {
        keys.push(pass.texts.take().map(|t| t.into_iter().collect()));
        failures.push(std::mem::take(&mut pass.failures));
    }
    for (name, r) in shards {
        check(&name, &r, &merged)?;
        for (i, p) in r.passes.into_iter().enumerate() {
            let m = &mut merged.passes[i];
            for (sum, count) in [
                (&mut m.built, p.built),
                (&mut m.distinct, p.distinct),
                (&mut m.valid, p.valid),
                (&mut m.invalid, p.invalid),
            ] {
                add(sum, count, &name)?;
            }
            match (&mut keys[i], p.texts) {
                (Some(k), Some(t)) => k.extend(t),
                (None, None) => {}
                _ => {
                    return Err(mismatch(
                        &name,
                        format!("{}/{}: texts listed in some shards only", p.shader, p.pass),
                    ));
                }
            }
            failures[i].extend(p.failures);
        }
    }
    for ((pass, keys), failures) in merged.passes.iter_mut().zip(keys).zip(failures) {
        if let Some(keys) = keys {
            pass.distinct = keys.len() as u64;
        }
        pass.failures = join_failures(failures);
    }
    let mut totals = ValidateTotals {
        passes: merged.passes.len(),
        ..ValidateTotals::default()
    };
    for p in &merged.passes {
        add(&mut totals.built, p.built, "the merged report")?;
        add(&mut totals.distinct, p.distinct, "the merged report")?;
        add(&mut totals.valid, p.valid, "the merged report")?;
        add(&mut totals.invalid, p.invalid, "the merged report")?;
    }
    merged.ok = totals.invalid == 0;
    merged.totals = totals;
    Ok(merged)
}

/// `sum += count`, or an error naming `name` when no run could count that far.
fn add(sum: &mut u64, count: u64, name: &str) -> Result<(), MergeError> {
    *sum = sum.checked_add(count).ok_or_else(|| {
        mismatch(
            name,
            "its counts add up past 2^64: not a real report".into(),
        )
    })?;
    Ok(())
}

/// Checks that a report agrees with itself: the counts of each pass are those its failures
/// give (`invalid` = the failing keyword sets, `valid + invalid = built`, no more distinct
/// texts than variants), its totals are the sums of its passes, and each failing variant's
/// number lies in its shard. An edited report is refused, not merged into wrong totals.
fn self_check(name: &str, r: &ReportJson, shard: Option<Shard>) -> Result<(), MergeError> {
    let mut sums = ValidateTotals {
        passes: r.passes.len(),
        ..ValidateTotals::default()
    };
    for p in &r.passes {
        let at = |what: String| mismatch(name, format!("{}/{}: {what}", p.shader, p.pass));
        let failing: u64 = p.failures.iter().map(|f| f.keyword_sets.len() as u64).sum();
        if p.invalid != failing {
            return Err(at(format!(
                "{} invalid, but its failures list {failing} failing variant(s)",
                p.invalid
            )));
        }
        if p.valid.checked_add(p.invalid) != Some(p.built) {
            return Err(at(format!(
                "{} valid + {} invalid is not the {} built",
                p.valid, p.invalid, p.built
            )));
        }
        if p.distinct > p.built {
            return Err(at(format!(
                "{} distinct texts of {} variants",
                p.distinct, p.built
            )));
        }
        for f in &p.failures {
            if !f.numbers.is_empty() && f.numbers.len() != f.keyword_sets.len() {
                return Err(at(format!(
                    "a failure lists {} variant number(s) for {} keyword set(s)",
                    f.numbers.len(),
                    f.keyword_sets.len()
                )));
            }
            if let Some(shard) = shard
                && let Some(n) = f.numbers.iter().find(|n| !shard.contains(**n))
            {
                return Err(at(format!("variant number {n} is not in shard {shard}")));
            }
        }
        add(&mut sums.built, p.built, name)?;
        add(&mut sums.distinct, p.distinct, name)?;
        add(&mut sums.valid, p.valid, name)?;
        add(&mut sums.invalid, p.invalid, name)?;
    }
    if sums != r.totals {
        return Err(mismatch(
            name,
            format!(
                "its totals ({} built, {} valid, {} invalid) are not the sums of its passes ({} built, {} valid, {} invalid)",
                r.totals.built,
                r.totals.valid,
                r.totals.invalid,
                sums.built,
                sums.valid,
                sums.invalid
            ),
        ));
    }
    Ok(())
}

/// Checks that shard `r` selects what the first shard (`first`) does.
fn check(name: &str, r: &ReportJson, first: &ReportJson) -> Result<(), MergeError> {
    if r.selection != first.selection {
        return Err(mismatch(
            name,
            format!("selection {:?} differs", r.selection),
        ));
    }
    let a = r
        .passes
        .iter()
        .map(|p| (&p.shader, &p.pass, p.full_space.get()));
    let b = first
        .passes
        .iter()
        .map(|p| (&p.shader, &p.pass, p.full_space.get()));
    if !a.eq(b) {
        return Err(mismatch(
            name,
            "its passes differ from the first shard's".into(),
        ));
    }
    Ok(())
}

/// One failure per text, keyword sets in variant order, failures by first variant.
fn join_failures(failures: Vec<FailureJson>) -> Vec<FailureJson> {
    // Text key -> (first variant, the failure from the shard that saw it first, keyword sets).
    type Joined = (u64, FailureJson, BTreeMap<u64, Vec<String>>);
    let mut by_text: HashMap<String, Joined> = HashMap::new();
    for (i, f) in failures.into_iter().enumerate() {
        // A report from before texts were recorded: keep the failure on its own.
        let key = f.text.clone().unwrap_or_else(|| format!("#{i}"));
        let first = f.numbers.first().copied().unwrap_or(u64::MAX);
        let sets: Vec<(u64, Vec<String>)> = f
            .numbers
            .iter()
            .copied()
            .zip(f.keyword_sets.clone())
            .collect();
        let entry = by_text
            .entry(key)
            .or_insert_with(|| (first, f.clone(), BTreeMap::new()));
        if first < entry.0 {
            entry.0 = first;
            entry.1 = f;
        }
        entry.2.extend(sets);
    }
    let mut joined: Vec<Joined> = by_text.into_values().collect();
    joined.sort_by_key(|(first, _, _)| *first);
    joined
        .into_iter()
        .map(|(_, mut f, sets)| {
            if !sets.is_empty() {
                f.keyword_sets = sets.into_values().collect();
            }
            f
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Library;
    use crate::plan::{PlanOptions, plan};
    use crate::validate::validate_plan;

    /// Two failing keywords and a set of three keywords that change nothing: failing texts
    /// shared by variants in different shards, and texts the audit cannot prove distinct.
    fn library() -> Library {
        Library::from_sources([(
            "s.wgsl",
            "#shader s\n#pass P\n#pragma multi_compile _ BAD\n#pragma multi_compile _ WORSE\n\
             #pragma multi_compile X Y Z\n\
             #ifdef BAD\nfn f() -> f32 { return vec2f(1.0); }\n#endif\n\
             #ifdef WORSE\nfn g() -> i32 { return 1.0; }\n#endif\n\
             @fragment fn fs() -> @location(0) vec4f {\n#ifdef BAD\n_ = f();\n#endif\n\
             #ifdef WORSE\n_ = g();\n#endif\nreturn vec4f(1.0);\n}\n#endpass\n",
        )])
        .unwrap()
    }

    fn report_json(lib: &Library, shard: Option<&str>) -> String {
        let options = PlanOptions {
            all: true,
            shard: shard.map(|s| s.parse().unwrap()),
            ..PlanOptions::default()
        };
        let planned = plan(lib, &options).unwrap();
        let report = validate_plan(lib, &planned, &options, None, &|_| {});
        serde_json::to_string_pretty(&report).unwrap() + "\n"
    }

    #[test]
    fn shards_merge_to_the_whole_report_byte_for_byte() {
        let lib = library();
        let whole = report_json(&lib, None);
        for n in 1..=5 {
            let mut inputs: Vec<(String, String)> = (1..=n)
                .map(|k| {
                    (
                        format!("{k}/{n}"),
                        report_json(&lib, Some(&format!("{k}/{n}"))),
                    )
                })
                .collect();
            inputs.reverse();
            let (merged, ok) = merge_reports(&inputs).unwrap();
            assert!(!ok);
            assert_eq!(merged, whole, "{n} shards");
        }
        // The merge had something to join: shared failing texts and repeated texts.
        let parsed: ReportJson = serde_json::from_str(&whole).unwrap();
        assert_eq!((parsed.totals.built, parsed.totals.distinct), (12, 4));
        assert_eq!(parsed.passes[0].failures.len(), 3);
        assert!(
            parsed.passes[0]
                .failures
                .iter()
                .all(|f| f.keyword_sets.len() == 3)
        );
    }

    /// Counts edited by hand (or by an attacker) contradict the shard's own failures: the
    /// shard is refused, naming what does not add up.
    #[test]
    fn a_shard_whose_counts_were_edited_is_refused() {
        let lib = library();
        let inputs = |edit: &dyn Fn(&mut serde_json::Value)| -> Vec<(String, String)> {
            (1..=2)
                .map(|k| {
                    let text = report_json(&lib, Some(&format!("{k}/2")));
                    let mut value: serde_json::Value = serde_json::from_str(&text).unwrap();
                    if k == 2 {
                        edit(&mut value);
                    }
                    (
                        format!("{k}/2"),
                        serde_json::to_string_pretty(&value).unwrap(),
                    )
                })
                .collect()
        };
        assert!(merge_reports(&inputs(&|_| {})).is_ok());
        let moved = |v: &mut serde_json::Value| {
            let pass = &mut v["passes"][0];
            let (valid, invalid) = (
                pass["valid"].as_u64().unwrap(),
                pass["invalid"].as_u64().unwrap(),
            );
            pass["valid"] = (valid + 2).into();
            pass["invalid"] = (invalid - 2).into();
        };
        let err = merge_reports(&inputs(&moved)).unwrap_err().to_string();
        assert!(err.contains("invalid, but its failures list"), "{err}");
        let built = |v: &mut serde_json::Value| {
            let b = v["passes"][0]["built"].as_u64().unwrap();
            v["passes"][0]["built"] = (b + 1).into();
        };
        let err = merge_reports(&inputs(&built)).unwrap_err().to_string();
        assert!(err.contains("is not the"), "{err}");
        let totals = |v: &mut serde_json::Value| {
            v["totals"]["valid"] = 100.into();
        };
        let err = merge_reports(&inputs(&totals)).unwrap_err().to_string();
        assert!(err.contains("are not the sums of its passes"), "{err}");
        // A failing variant's number from the other shard (2/2 holds odd numbers only).
        let foreign = |v: &mut serde_json::Value| {
            v["passes"][0]["failures"][0]["numbers"][0] = 0.into();
        };
        let err = merge_reports(&inputs(&foreign)).unwrap_err().to_string();
        assert!(
            err.contains("variant number 0 is not in shard 2/2"),
            "{err}"
        );
    }

    #[test]
    fn a_report_of_another_kind_is_named() {
        let inputs = [(
            "manifest.json".to_string(),
            "{\"variants\": []}".to_string(),
        )];
        let err = merge_reports(&inputs).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("`manifest.json` is not a `validate --json` report"),
            "{err}"
        );
    }
}
