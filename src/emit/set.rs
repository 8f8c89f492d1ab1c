//! A whole build set written to a folder, every variant through every requested back end,
//! plus a `manifest.json` describing it.
//!
//! Layout: `DIR/<shader>/<pass>/<name>.<ext>`, where `<name>` is the variant's keywords joined
//! with `+` (`none` when no keyword is on; `v-<16 hex digits>`, a hash of the keywords, when
//! that would be longer than 100 bytes, when a keyword has characters other than ASCII
//! letters, digits, `_` and `-`, or when the only keyword is `none`), and GLSL adds the entry
//! point: `<name>.<entry point>.<vert|frag|comp>`. A name depends on the variant alone, so the
//! shards of a build set (`--shard K/N`) name files as one run does. The manifest records
//! the set's [`crate::fingerprint::fingerprint`] (and its shard), and lists, for each variant in
//! enumeration order: shader, pass, keywords, entry points with their stage, and each file
//! with its target, entry point, size and BLAKE3 content hash (hex). Files and manifest are
//! byte-identical across runs and thread counts.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;

use crate::library::{Library, Variant};
use crate::shader::Pass;
use crate::variants::Choice;

use super::backends::{Options, Output, Slot, Target, TranslateError, translate_all};
use super::write_if_changed;
use crate::plan::{Plan, PlanOptions};
use crate::reflect::{EntryPoint, Stage};
use crate::variants::Shard;

/// One back end's name and version in a manifest.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct ManifestTarget {
    /// `wgsl`, `spirv`, `glsl`, `hlsl` or `msl`.
    pub target: String,
    /// Language version (`450`, `300es`, `5_1`, `2.0`, SPIR-V `1.0`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub version: Option<String>,
}

/// One written file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct ManifestFile {
    /// The back end that wrote it.
    pub target: String,
    /// The entry point, for back ends with one output per entry point (GLSL).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub entry_point: Option<String>,
    /// That entry point's stage.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stage: Option<Stage>,
    /// Path relative to the output folder, `/`-separated.
    pub file: String,
    /// Size in bytes.
    pub bytes: usize,
    /// BLAKE3 hash of the contents, hex.
    pub blake3: String,
    /// GLSL and MSL: the flat slot of each binding (see [`super::backends`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub slots: Vec<Slot>,
}

/// One variant in a manifest.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct ManifestVariant {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Keywords that are on, in set order.
    pub keywords: Vec<String>,
    /// Entry points with their stages.
    pub entry_points: Vec<EntryPoint>,
    /// The files written for it, in target order.
    pub files: Vec<ManifestFile>,
}

/// `manifest.json`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct Manifest {
    /// `wgsl-variants <version>`.
    pub generator: String,
    /// What the set was made from (see [`crate::fingerprint::fingerprint`]); empty when unknown.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub fingerprint: String,
    /// The shard written, if only one was (`K/N`).
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::variants::shard_text"
    )]
    pub shard: Option<Shard>,
    /// The back ends, in the order given.
    pub targets: Vec<ManifestTarget>,
    /// Every variant, pass by pass in enumeration order.
    pub variants: Vec<ManifestVariant>,
}

/// What [`write_set`] wrote (what `emit --out DIR --json` prints).
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct WriteSummary {
    /// The output folder.
    pub out: String,
    /// Number of variants written.
    pub variants: usize,
    /// Number of files written (besides `manifest.json`).
    pub files: usize,
    /// The targets as written (`glsl 450`).
    pub targets: Vec<String>,
}

impl WriteSummary {
    /// The summary of `manifest`, written into `dir` with `targets`.
    pub fn new(dir: &Path, manifest: &Manifest, targets: &[Target]) -> WriteSummary {
        WriteSummary {
            out: dir.display().to_string(),
            variants: manifest.variants.len(),
            files: manifest.variants.iter().map(|v| v.files.len()).sum(),
            targets: targets.iter().map(|t| t.to_string()).collect(),
        }
    }
}

/// Why a build set could not be written.
#[derive(Debug, thiserror::Error)]
pub enum SetError {
    /// Variants failed validation or translation; every failure is listed.
    #[error("{} variant(s) failed", .0.len())]
    Failed(Vec<TranslateError>),
    /// A file could not be written.
    #[error("cannot write `{}`: {source}", .path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// A file or folder name would be longer than file systems allow (255 bytes): a shader,
    /// pass or entry point name too long to be a file name. Nothing is written.
    #[error(
        "`{start}…` ({bytes} bytes) would be a file or folder name of {variant}, longer than the 255 bytes file systems allow: shorten the shader, pass or entry point name"
    )]
    NameTooLong {
        /// The name's first 40 characters.
        start: String,
        /// Its length in bytes.
        bytes: usize,
        /// The variant (`shader/pass {keywords}`).
        variant: String,
    },
    /// Two outputs would be written to the same file: their names differ only in characters
    /// a file name cannot hold (`a/b` and `a-b` are both `a-b`), or only in case (one file on
    /// macOS and Windows). Nothing is written.
    #[error(
        "`{file}` would be written for both {first} and {second}: rename a shader or pass (file names keep ASCII letters, digits, `_` and `-`, and are compared without case)"
    )]
    Collision {
        /// The file, relative to the output folder.
        file: String,
        /// The first variant (`shader/pass {keywords}`) written there.
        first: String,
        /// The second.
        second: String,
    },
}

fn io_error(path: &Path, e: std::io::Error) -> SetError {
    SetError::Io {
        path: path.to_path_buf(),
        source: e,
    }
}

/// A file-name-safe form of a shader or pass name.
pub(crate) fn file_safe(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// The file stem of a variant (see the module docs): its keywords joined with `+`, or a hash
/// of them where that name would be too long or could collide with another's.
pub(crate) fn variant_stem(keywords: &[&str]) -> String {
    if keywords.is_empty() {
        return "none".to_string();
    }
    let joined = keywords.join("+");
    let plain = keywords.iter().all(|k| *k == file_safe(k)) && joined != "none";
    if plain && joined.len() <= 100 {
        return joined;
    }
    // Keywords cannot hold a space: joined with one, different sets hash different bytes.
    let hash = blake3::hash(keywords.join(" ").as_bytes()).to_hex();
    format!("v-{}", &hash[..16])
}

/// Where a build set comes from, as its manifest records it: the fingerprint of the library,
/// plan options, targets and back-end options, and the shard.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct SetOrigin {
    /// See [`crate::fingerprint::fingerprint`].
    pub fingerprint: String,
    /// The shard written, if only one is.
    pub shard: Option<Shard>,
}

impl SetOrigin {
    /// The origin of the set that `plan_options` selects, written through `targets`.
    pub fn new(
        lib: &Library,
        plan_options: &PlanOptions,
        targets: &[Target],
        options: &Options,
    ) -> SetOrigin {
        let text = format!(
            "{} {targets:?} {options:?}",
            plan_options.fingerprint_text()
        );
        SetOrigin {
            fingerprint: crate::fingerprint::fingerprint(lib, "emit", &text),
            shard: plan_options.shard,
        }
    }
}

/// Writes every variant of `selection` through every target into `dir` (created if needed)
/// and `dir/manifest.json`. Returns the manifest. Nothing is written when any variant fails
/// (every failure is returned) or when two outputs would share a file name
/// ([`SetError::Collision`]).
///
/// The manifest always describes exactly the files beside it: an old `manifest.json` is
/// removed before the first file is written, the new one is written last (to a temporary file
/// renamed into place), and files the old manifest listed that the new set does not hold are
/// removed. Other files in `dir` are left alone; files whose contents did not change keep
/// their modification times.
pub fn write_set(
    lib: &Library,
    selection: &Plan<'_>,
    targets: &[Target],
    options: &Options,
    dir: &Path,
) -> Result<Manifest, SetError> {
    write_set_from(lib, selection, &SetOrigin::default(), targets, options, dir)
}

/// [`write_set`], with the set's origin recorded in the manifest (what `emit --out` writes,
/// and what [`crate::merge::manifest`] checks).
pub fn write_set_from(
    lib: &Library,
    selection: &Plan<'_>,
    origin: &SetOrigin,
    targets: &[Target],
    options: &Options,
    dir: &Path,
) -> Result<Manifest, SetError> {
    struct Job<'a> {
        pass: &'a Pass,
        choice: &'a Choice,
    }
    let jobs: Vec<Job<'_>> = selection
        .iter()
        .flat_map(|(pass, choices)| choices.iter().map(move |choice| Job { pass, choice }))
        .collect();
    // First compile and translate everything (in parallel); write only when all succeeded.
    type Done = (Vec<EntryPoint>, Vec<(Target, Output, Vec<Slot>)>);
    let results: Vec<Result<Done, TranslateError>> = jobs
        .par_iter()
        .map(|job| {
            let variant = Variant {
                pass: job.pass,
                choice: job.choice.clone(),
            };
            let all = translate_all(lib, &variant, targets, options)?;
            let outputs = all
                .outputs
                .into_iter()
                .map(|(target, o)| {
                    // Equal targets have equal slots: the first one's will do.
                    let t = targets.iter().position(|t| *t == target);
                    let slots = t.map(|t| all.slots[t].clone()).unwrap_or_default();
                    (target, o, slots)
                })
                .collect();
            Ok((all.entry_points, outputs))
        })
        .collect();
    let failures: Vec<TranslateError> = results
        .iter()
        .filter_map(|r| r.as_ref().err().cloned())
        .collect();
    if !failures.is_empty() {
        return Err(SetError::Failed(failures));
    }

    // Every file's path first: a collision is refused before anything is written.
    let mut variants = Vec::with_capacity(jobs.len());
    let mut contents = Vec::new();
    let mut taken: std::collections::HashMap<String, String> = std::collections::HashMap::new();
    for (job, result) in jobs.iter().zip(results) {
        let (eps, outputs) = result.expect("failures returned above");
        let keywords = job.choice.keywords(job.pass);
        let label = format!(
            "{}/{} {{{}}}",
            job.pass.shader,
            job.pass.name,
            keywords.join(", ")
        );
        let folder = format!(
            "{}/{}",
            file_safe(&job.pass.shader),
            file_safe(&job.pass.name)
        );
        let stem = variant_stem(&keywords);
        let mut files = Vec::new();
        for (target, output, slots) in outputs {
            let (entry_point, stage) = match &output.entry_point {
                Some(ep) => (Some(ep.name.clone()), Some(ep.stage)),
                None => (None, None),
            };
            let file = match &entry_point {
                Some(name) => format!(
                    "{folder}/{stem}.{}.{}",
                    file_safe(name),
                    target.extension(stage)
                ),
                None => format!("{folder}/{stem}.{}", target.extension(None)),
            };
            if let Some(long) = file.split('/').find(|c| c.len() > 255) {
                return Err(SetError::NameTooLong {
                    start: long.chars().take(40).collect(),
                    bytes: long.len(),
                    variant: label,
                });
            }
            match taken.entry(file.to_lowercase()) {
                std::collections::hash_map::Entry::Occupied(first) => {
                    return Err(SetError::Collision {
                        file,
                        first: first.get().clone(),
                        second: label,
                    });
                }
                std::collections::hash_map::Entry::Vacant(slot) => {
                    slot.insert(label.clone());
                }
            }
            let bytes = output.contents.to_bytes();
            files.push(ManifestFile {
                target: target.name().to_string(),
                entry_point,
                stage,
                file,
                bytes: bytes.len(),
                blake3: blake3::hash(&bytes).to_hex().to_string(),
                slots,
            });
            contents.push(bytes);
        }
        variants.push(ManifestVariant {
            shader: job.pass.shader.clone(),
            pass: job.pass.name.clone(),
            keywords: keywords.into_iter().map(str::to_string).collect(),
            entry_points: eps,
            files,
        });
    }

    std::fs::create_dir_all(dir).map_err(|e| io_error(dir, e))?;
    let manifest_path = dir.join("manifest.json");
    let old_files = listed_files(&manifest_path);
    match std::fs::remove_file(&manifest_path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
            return Err(io_error(&manifest_path, e));
        }
        _ => {}
    }
    let written = variants.iter().flat_map(|v| &v.files);
    for (file, bytes) in written.clone().zip(&contents) {
        let path = dir.join(&file.file);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).map_err(|e| io_error(parent, e))?;
        }
        write_if_changed(&path, bytes).map_err(|e| io_error(&path, e))?;
    }
    let manifest = Manifest {
        generator: format!("wgsl-variants {}", env!("CARGO_PKG_VERSION")),
        fingerprint: origin.fingerprint.clone(),
        shard: origin.shard,
        targets: targets
            .iter()
            .map(|t| ManifestTarget {
                target: t.name().to_string(),
                version: t.version(),
            })
            .collect(),
        variants,
    };
    // Files of the old set that the new one does not hold would be described by nothing.
    let new_files: std::collections::HashSet<&str> = manifest
        .variants
        .iter()
        .flat_map(|v| &v.files)
        .map(|f| f.file.as_str())
        .collect();
    for stale in old_files.iter().filter(|f| !new_files.contains(f.as_str())) {
        let path = dir.join(stale);
        match std::fs::remove_file(&path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(io_error(&path, e)),
            _ => {}
        }
    }
    let mut json = serde_json::to_string_pretty(&manifest).expect("manifest serializes");
    json.push('\n');
    let temporary = dir.join(format!(".manifest.json.{}.tmp", std::process::id()));
    std::fs::write(&temporary, json.as_bytes()).map_err(|e| io_error(&temporary, e))?;
    std::fs::rename(&temporary, &manifest_path).map_err(|e| io_error(&manifest_path, e))?;
    Ok(manifest)
}

/// The files an existing manifest lists (relative paths inside its folder only); empty when
/// there is none or it cannot be read.
fn listed_files(manifest: &Path) -> Vec<String> {
    let Ok(text) = std::fs::read_to_string(manifest) else {
        return Vec::new();
    };
    let Ok(value) = serde_json::from_str::<serde_json::Value>(&text) else {
        return Vec::new();
    };
    let inside = |file: &&str| {
        !file.is_empty()
            && Path::new(file)
                .components()
                .all(|c| matches!(c, std::path::Component::Normal(_)))
    };
    value["variants"]
        .as_array()
        .into_iter()
        .flatten()
        .filter_map(|v| v["files"].as_array())
        .flatten()
        .filter_map(|f| f["file"].as_str())
        .filter(inside)
        .map(str::to_string)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn variant_stem_names() {
        assert_eq!(variant_stem(&[]), "none");
        assert_eq!(variant_stem(&["_NORMAL_MAP", "FOG"]), "_NORMAL_MAP+FOG");
        assert!(variant_stem(&["A.B"]).starts_with("v-"));
        assert_ne!(variant_stem(&["A.B"]), variant_stem(&["A-B"]));
    }
}
