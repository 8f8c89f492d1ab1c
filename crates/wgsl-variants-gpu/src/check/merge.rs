//! Merging the `check-gpu --json` reports of N shards (`--shard K/N`) into one verdict.
//!
//! A shard checks every N-th variant of the standard passes and the whole of the other passes
//! and kernels. The merged report sums the standard passes' counts (variants, shaders, draws,
//! texels, mismatches, keyword pairs; the first mismatches in shard order) and keeps the other
//! passes and kernels once, after checking that every shard got the same counts for them. A
//! keyword pair split between two shards is compared by neither, so keyword coverage is
//! judged by an unsharded run only (the merged notes say so). Times differ from run to run.

use serde_json::{Map, Value};
use wgsl_variants::merge::{MergeError, ShardInfo, order_shards, parse_shard};

use super::report::MAX_LISTED_MISMATCHES;

fn mismatch(name: &str, message: String) -> MergeError {
    MergeError::Mismatch {
        shard: name.to_string(),
        message,
    }
}

fn parse(name: &str, text: &str) -> Result<Map<String, Value>, MergeError> {
    let kind = |message: String| MergeError::Kind {
        shard: name.to_string(),
        expected: "a `check-gpu --json` report",
        message,
    };
    match serde_json::from_str::<Value>(text) {
        Ok(Value::Object(m)) if m.get("passes").is_some_and(Value::is_array) => Ok(m),
        Ok(_) => Err(kind("no `passes` list".into())),
        Err(e) => Err(kind(e.to_string())),
    }
}

fn count(v: &Value, key: &str) -> u64 {
    v.get(key).and_then(Value::as_u64).unwrap_or(0)
}

fn add(into: &mut Value, from: &Value, key: &str) {
    let sum = count(into, key) + count(from, key);
    into[key] = Value::from(sum);
}

fn list<'v>(v: &'v Value, key: &str) -> &'v [Value] {
    v.get(key)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

/// What a shard must agree on with the first for a pass or kernel it runs whole.
fn counts(v: &Value) -> [u64; 4] {
    ["variants_run", "pixels_compared", "cases", "mismatches"].map(|k| count(v, k))
}

/// Merges shard reports, given as `(name, JSON text)` in any order, into one report (pretty
/// JSON with a final newline). Returns the text and whether the merged check passed.
pub fn merge_reports(inputs: &[(String, String)]) -> Result<(String, bool), MergeError> {
    let reports = inputs
        .iter()
        .map(|(name, text)| parse(name, text))
        .collect::<Result<Vec<_>, _>>()?;
    let infos = inputs
        .iter()
        .zip(&reports)
        .map(|((name, _), r)| {
            Ok(ShardInfo {
                name: name.clone(),
                shard: parse_shard(name, r.get("shard").and_then(Value::as_str))?,
                fingerprint: r
                    .get("fingerprint")
                    .and_then(Value::as_str)
                    .unwrap_or_default()
                    .to_string(),
            })
        })
        .collect::<Result<Vec<_>, MergeError>>()?;
    let order = order_shards(&infos)?;
    let n = order.len();
    let first_name = &inputs[order[0]].0;
    let mut merged = reports[order[0]].clone();
    merged.shift_remove("shard");
    let mut passes: Vec<Value> = list(&Value::Object(merged.clone()), "passes").to_vec();
    let kernels: Vec<Value> = list(&Value::Object(merged.clone()), "kernels").to_vec();
    let mut seconds = merged.get("seconds").and_then(Value::as_f64).unwrap_or(0.0);
    for &i in &order[1..] {
        let (name, r) = (&inputs[i].0, Value::Object(reports[i].clone()));
        for key in ["adapter", "driver"] {
            if r.get(key) != merged.get(key) {
                return Err(mismatch(
                    name,
                    format!("it ran on another {key} than `{first_name}`: {}", r[key]),
                ));
            }
        }
        let theirs = list(&r, "passes");
        let same_passes = theirs.len() == passes.len()
            && theirs
                .iter()
                .zip(&passes)
                .all(|(a, b)| a["shader"] == b["shader"] && a["pass"] == b["pass"]);
        if !same_passes {
            return Err(mismatch(
                name,
                "its passes differ from the first shard's".into(),
            ));
        }
        for (mine, theirs) in passes.iter_mut().zip(theirs) {
            if mine["shader"] != "standard" {
                if counts(mine) != counts(theirs) {
                    return Err(mismatch(
                        name,
                        format!(
                            "{}/{} differs from `{first_name}`'s",
                            mine["shader"], mine["pass"]
                        ),
                    ));
                }
                continue;
            }
            for key in [
                "variants_run",
                "distinct_shaders",
                "draws",
                "pixels_compared",
                "discarded_compared",
                "mismatches",
            ] {
                add(mine, theirs, key);
            }
            let mut first: Vec<Value> = list(mine, "first_mismatches").to_vec();
            first.extend(list(theirs, "first_mismatches").iter().cloned());
            first.truncate(MAX_LISTED_MISMATCHES);
            mine["first_mismatches"] = Value::Array(first);
            // Every mismatch per variant: the shards' tallies summed by variant.
            let mut tally = mine
                .get("mismatches_by_variant")
                .and_then(Value::as_object)
                .cloned()
                .unwrap_or_default();
            if let Some(t) = theirs
                .get("mismatches_by_variant")
                .and_then(Value::as_object)
            {
                for (variant, n) in t {
                    let sum = tally.get(variant).and_then(Value::as_u64).unwrap_or(0)
                        + n.as_u64().unwrap_or(0);
                    tally.insert(variant.clone(), Value::from(sum));
                }
            }
            mine["mismatches_by_variant"] = Value::Object(tally);
            let mut keywords = list(mine, "keywords").to_vec();
            for (k, t) in keywords.iter_mut().zip(list(theirs, "keywords")) {
                add(k, t, "pairs");
                add(k, t, "pairs_changed");
            }
            mine["keywords"] = Value::Array(keywords);
            let s =
                mine["seconds"].as_f64().unwrap_or(0.0) + theirs["seconds"].as_f64().unwrap_or(0.0);
            mine["seconds"] = Value::from(s);
        }
        let their_kernels = list(&r, "kernels");
        if their_kernels
            .iter()
            .map(counts)
            .ne(kernels.iter().map(counts))
        {
            return Err(mismatch(
                name,
                format!("its kernels differ from `{first_name}`'s"),
            ));
        }
        seconds = seconds.max(r.get("seconds").and_then(Value::as_f64).unwrap_or(0.0));
    }
    for p in passes.iter_mut().filter(|p| p["shader"] == "standard") {
        let note =
            format!("merged from {n} shards: keyword coverage is judged on the full space only");
        let mut notes: Vec<Value> = list(p, "notes")
            .iter()
            .filter(|t| !t.as_str().is_some_and(|t| t.contains(" of shard ")))
            .cloned()
            .collect();
        notes.insert(0, Value::from(note));
        p["notes"] = Value::Array(notes);
    }
    let passed = passes.iter().all(|p| {
        count(p, "mismatches") == 0
            && list(p, "untested_keywords").is_empty()
            && count(p, "pixels_compared") > 0
    }) && kernels
        .iter()
        .all(|k| count(k, "mismatches") == 0 && count(k, "cases") > 0);
    merged.insert("passes".into(), Value::Array(passes));
    merged.insert("seconds".into(), Value::from(seconds));
    let mut text = serde_json::to_string_pretty(&merged).map_err(|e| MergeError::Write {
        path: "<stdout>".into(),
        source: e.into(),
    })?;
    text.push('\n');
    Ok((text, passed))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report(shard: &str, fingerprint: &str, variants: u64, mismatches: u64) -> String {
        serde_json::json!({
            "adapter": "llvmpipe", "driver": "Vulkan", "fingerprint": fingerprint,
            "shard": shard,
            "passes": [
                {"shader": "standard", "pass": "Deferred", "variants_run": variants,
                 "distinct_shaders": variants, "draws": variants, "pixels_compared": variants * 10,
                 "discarded_compared": 0, "mismatches": mismatches, "first_mismatches": [],
                 "keywords": [{"keyword": "A", "pairs": 1, "pairs_changed": 1}],
                 "untested_keywords": [], "notes": [format!("sampled every 1th variant of shard {shard}: ...")],
                 "seconds": 1.0},
                {"shader": "deferred_final", "pass": "Final", "variants_run": 1,
                 "pixels_compared": 5, "mismatches": 0, "untested_keywords": [], "seconds": 0.5}
            ],
            "kernels": [{"name": "k", "cases": 3, "values_compared": 3, "mismatches": 0}],
            "seconds": 2.0
        })
        .to_string()
    }

    #[test]
    fn sums_the_sharded_passes_and_keeps_the_rest_once() {
        let inputs = [
            ("b".to_string(), report("2/2", "f", 5, 1)),
            ("a".to_string(), report("1/2", "f", 6, 0)),
        ];
        let (text, passed) = merge_reports(&inputs).unwrap();
        let v: Value = serde_json::from_str(&text).unwrap();
        assert!(!passed, "one mismatch fails the merged check");
        assert!(v.get("shard").is_none());
        assert_eq!(v["passes"][0]["variants_run"], 11);
        assert_eq!(v["passes"][0]["pixels_compared"], 110);
        assert_eq!(v["passes"][0]["keywords"][0]["pairs"], 2);
        assert_eq!(v["passes"][1]["variants_run"], 1);
        assert!(
            v["passes"][0]["notes"][0]
                .as_str()
                .unwrap()
                .starts_with("merged from 2 shards")
        );
    }

    #[test]
    fn the_mismatches_per_variant_are_summed_by_variant() {
        let with = |shard: &str, tally: Value| {
            let mut v: Value = serde_json::from_str(&report(shard, "f", 4, 0)).unwrap();
            v["passes"][0]["mismatches_by_variant"] = tally;
            v.to_string()
        };
        let inputs = [
            ("a".to_string(), with("1/2", serde_json::json!({"{A}": 2}))),
            (
                "b".to_string(),
                with("2/2", serde_json::json!({"{A}": 1, "{B}": 4})),
            ),
        ];
        let (text, _) = merge_reports(&inputs).unwrap();
        let v: Value = serde_json::from_str(&text).unwrap();
        assert_eq!(
            v["passes"][0]["mismatches_by_variant"],
            serde_json::json!({"{A}": 3, "{B}": 4})
        );
    }

    #[test]
    fn a_shard_from_another_run_is_named() {
        let inputs = [
            ("a".to_string(), report("1/2", "f", 6, 0)),
            ("b".to_string(), report("2/2", "g", 5, 0)),
        ];
        let err = merge_reports(&inputs).unwrap_err();
        assert!(
            matches!(&err, MergeError::Fingerprint { shard, .. } if shard == "b"),
            "{err}"
        );
    }
}
