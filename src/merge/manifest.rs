//! Merging the `emit --out` folders of N shards into the folder one run writes: the files of
//! every shard, and one `manifest.json` with every variant in enumeration order.
//!
//! Variant number `i` of the whole set is in shard `i % N` (see [`crate::variants::Shard`]),
//! so the merged list takes the shards' variants in turn. Every file a shard's manifest lists
//! is checked against its recorded size and BLAKE3 hash before anything is written.

use std::path::{Component, Path, PathBuf};

use serde_json::{Map, Value};

use super::{MergeError, ShardInfo, order_shards, parse_shard};

/// What [`merge_folders`] wrote.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
#[non_exhaustive]
pub struct MergedSet {
    /// The output folder.
    pub out: String,
    /// Variants in the merged manifest.
    pub variants: usize,
    /// Files written (besides `manifest.json`).
    pub files: usize,
}

/// One shard folder's manifest.
struct ShardSet {
    name: String,
    dir: PathBuf,
    manifest: Map<String, Value>,
    variants: Vec<Value>,
}

fn read_shard(dir: &Path) -> Result<ShardSet, MergeError> {
    let name = dir.display().to_string();
    let path = dir.join("manifest.json");
    let text = std::fs::read_to_string(&path).map_err(|e| MergeError::Read {
        shard: path.display().to_string(),
        source: e,
    })?;
    let kind = |message: String| MergeError::Kind {
        shard: name.clone(),
        expected: "an `emit --out` folder",
        message,
    };
    let mut manifest = match serde_json::from_str::<Value>(&text) {
        Ok(Value::Object(m)) => m,
        Ok(_) => return Err(kind("manifest.json is not an object".into())),
        Err(e) => return Err(kind(format!("manifest.json: {e}"))),
    };
    let variants = match manifest.get_mut("variants").map(Value::take) {
        Some(Value::Array(v)) => v,
        _ => return Err(kind("manifest.json has no `variants` list".into())),
    };
    Ok(ShardSet {
        name,
        dir: dir.to_path_buf(),
        manifest,
        variants,
    })
}

/// Merges the shard folders `dirs` (any order) into `out` (created if needed; files already
/// there with the same contents are left untouched). The merged `manifest.json` is byte for
/// byte the one `emit --out` writes without `--shard`.
pub fn merge_folders(dirs: &[PathBuf], out: &Path) -> Result<MergedSet, MergeError> {
    let sets = dirs
        .iter()
        .map(|d| read_shard(d))
        .collect::<Result<Vec<_>, _>>()?;
    let infos = sets
        .iter()
        .map(|s| {
            let field = |key: &str| s.manifest.get(key).and_then(Value::as_str);
            Ok(ShardInfo {
                name: s.name.clone(),
                shard: parse_shard(&s.name, field("shard"))?,
                fingerprint: field("fingerprint").unwrap_or_default().to_string(),
            })
        })
        .collect::<Result<Vec<_>, MergeError>>()?;
    let order = order_shards(&infos)?;
    let sets: Vec<&ShardSet> = order.iter().map(|&i| &sets[i]).collect();
    let first = sets[0];
    let count = sets.len();
    let total: usize = sets.iter().map(|s| s.variants.len()).sum();
    for (k, s) in sets.iter().enumerate() {
        for key in ["generator", "targets"] {
            if s.manifest.get(key) != first.manifest.get(key) {
                return Err(MergeError::Mismatch {
                    shard: s.name.clone(),
                    message: format!("its `{key}` differs from `{}`'s", first.name),
                });
            }
        }
        // Shard k of N holds the numbers k, k + N, ... below the total.
        let expected = (total + count - 1 - k) / count;
        if s.variants.len() != expected {
            return Err(MergeError::Mismatch {
                shard: s.name.clone(),
                message: format!(
                    "it lists {} variants, but shard {}/{count} of {total} variants has {expected}: a shard's output is incomplete",
                    s.variants.len(),
                    k + 1
                ),
            });
        }
    }
    // Every file: checked first, written only when all are sound.
    let mut files: Vec<(&ShardSet, PathBuf, String)> = Vec::new();
    let mut seen = std::collections::HashMap::new();
    for s in &sets {
        for v in &s.variants {
            for f in v
                .get("files")
                .and_then(Value::as_array)
                .into_iter()
                .flatten()
            {
                let file = check_file(s, f)?;
                if let Some(other) = seen.insert(file.clone(), s.name.clone()) {
                    return Err(MergeError::Mismatch {
                        shard: s.name.clone(),
                        message: format!("`{file}` is also written by `{other}`"),
                    });
                }
                let rel: PathBuf = file.split('/').collect();
                files.push((s, rel, file));
            }
        }
    }
    for (s, rel, _) in &files {
        let bytes = std::fs::read(s.dir.join(rel)).map_err(|e| MergeError::Read {
            shard: s.dir.join(rel).display().to_string(),
            source: e,
        })?;
        let path = out.join(rel);
        let written = path
            .parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .and_then(|()| crate::emit::write_if_changed(&path, &bytes));
        written.map_err(|e| MergeError::Write {
            path: path.display().to_string(),
            source: e,
        })?;
    }
    let mut variants = Vec::with_capacity(total);
    for i in 0..total {
        variants.push(sets[i % count].variants[i / count].clone());
    }
    let mut manifest = first.manifest.clone();
    manifest.shift_remove("shard");
    manifest.insert("variants".into(), Value::Array(variants));
    let mut json = serde_json::to_string_pretty(&manifest).map_err(|e| MergeError::Write {
        path: "manifest.json".into(),
        source: e.into(),
    })?;
    json.push('\n');
    let path = out.join("manifest.json");
    std::fs::create_dir_all(out)
        .and_then(|()| crate::emit::write_if_changed(&path, json.as_bytes()))
        .map_err(|e| MergeError::Write {
            path: path.display().to_string(),
            source: e,
        })?;
    Ok(MergedSet {
        out: out.display().to_string(),
        variants: total,
        files: files.len(),
    })
}

/// Checks one file entry of shard `s`: a relative path inside the folder, whose contents have
/// the recorded size and hash. Returns the path.
fn check_file(s: &ShardSet, entry: &Value) -> Result<String, MergeError> {
    let bad = |message: String| MergeError::Mismatch {
        shard: s.name.clone(),
        message,
    };
    let file = entry
        .get("file")
        .and_then(Value::as_str)
        .ok_or_else(|| bad("a file entry has no `file`".into()))?;
    let rel: PathBuf = file.split('/').collect();
    if file.is_empty() || !rel.components().all(|c| matches!(c, Component::Normal(_))) {
        return Err(bad(format!("`{file}` is not a path inside the folder")));
    }
    let bytes = std::fs::read(s.dir.join(&rel)).map_err(|e| MergeError::Read {
        shard: s.dir.join(&rel).display().to_string(),
        source: e,
    })?;
    let hash = blake3::hash(&bytes).to_hex();
    let size_ok = entry.get("bytes").and_then(Value::as_u64) == Some(bytes.len() as u64);
    if !size_ok || entry.get("blake3").and_then(Value::as_str) != Some(hash.as_str()) {
        return Err(bad(format!(
            "`{file}` does not match its manifest entry (size or BLAKE3 hash): the folder was changed after it was written"
        )));
    }
    Ok(file.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::emit::backends::{Options, Target};
    use crate::emit::set::{SetOrigin, write_set_from};
    use crate::plan::{PlanOptions, plan};

    fn write(lib: &crate::Library, shard: Option<&str>, dir: &Path) {
        let options = PlanOptions {
            shard: shard.map(|s| s.parse().unwrap()),
            shader: Some("probe".into()),
            ..PlanOptions::default()
        };
        let targets = [Target::Wgsl];
        let origin = SetOrigin::new(lib, &options, &targets, &Options::default());
        let planned = plan(lib, &options).unwrap();
        write_set_from(lib, &planned, &origin, &targets, &Options::default(), dir).unwrap();
    }

    fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
        let mut out = Vec::new();
        let mut stack = vec![dir.to_path_buf()];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).unwrap() {
                let p = e.unwrap().path();
                if p.is_dir() {
                    stack.push(p);
                } else {
                    out.push((
                        p.strip_prefix(dir).unwrap().to_path_buf(),
                        std::fs::read(&p).unwrap(),
                    ));
                }
            }
        }
        out.sort();
        out
    }

    #[test]
    fn shard_folders_merge_to_the_whole_folder() {
        // Four variants, so that each of the two shards holds some.
        let lib = crate::Library::from_sources([(
            "probe.wgsl",
            "#shader probe\n#pass P\n#pragma multi_compile _ A\n#pragma multi_compile _ B\n\
             @fragment fn fs() -> @location(0) vec4f {\n\
             #if A\n    return vec4f(1.0);\n#elif B\n    return vec4f(0.5);\n#else\n    return vec4f(0.0);\n#endif\n}\n#endpass\n",
        )])
        .unwrap();
        let tmp = tempfile::tempdir().unwrap();
        write(&lib, None, &tmp.path().join("whole"));
        let shards: Vec<PathBuf> = (1..=2)
            .map(|k| {
                let dir = tmp.path().join(format!("s{k}"));
                write(&lib, Some(&format!("{k}/2")), &dir);
                dir
            })
            .collect();
        let merged = merge_folders(
            &[shards[1].clone(), shards[0].clone()],
            &tmp.path().join("m"),
        )
        .unwrap();
        assert_eq!((merged.variants, merged.files), (4, 4));
        assert_eq!(
            files(&tmp.path().join("whole")),
            files(&tmp.path().join("m"))
        );

        // A file changed after it was written: refused, naming the shard, nothing written.
        let manifest = std::fs::read_to_string(shards[1].join("manifest.json")).unwrap();
        let value: Value = serde_json::from_str(&manifest).unwrap();
        let file = value["variants"][0]["files"][0]["file"].as_str().unwrap();
        std::fs::write(shards[1].join(file), "// changed\n").unwrap();
        let err = merge_folders(&shards, &tmp.path().join("n")).unwrap_err();
        assert!(
            matches!(&err, MergeError::Mismatch { shard, .. } if *shard == shards[1].display().to_string()),
            "{err}"
        );
        assert!(!tmp.path().join("n").exists());
    }
}
