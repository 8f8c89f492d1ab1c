//! Validating variants with naga, in parallel, with errors mapped to the original modules.

use std::collections::{HashMap, HashSet};
use std::sync::atomic::{AtomicBool, Ordering};

use num_bigint::BigUint;
use rayon::prelude::*;

use crate::cache::{Hash, ValidCache};
use crate::diagnostic::Location;
use crate::library::{Library, Variant};
use crate::plan::{Plan, PlanOptions};
use crate::preprocess::Composed;
use crate::shader::Pass;
use crate::variants::{Choice, Shard, Space};

pub use crate::error::{Stage, VariantError};
use crate::validator::validate_with;
pub use crate::validator::{Profile, ProfileError, validate_composed, validate_for, validator};

/// Composes, validates and compacts a variant (unused items removed, then validated again):
/// the module every back end writes and snapshots are made of.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let v = lib.variant("standard", "Deferred", &["_NORMAL_MAP"]).unwrap();
/// let (module, _info) = wgsl_variants::validate::compile(&lib, &v).unwrap();
/// assert!(module.entry_points.iter().any(|e| e.name == "fs_main"));
/// ```
pub fn compile(
    lib: &Library,
    variant: &Variant<'_>,
) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
    let (mut module, _) = lib.naga_module(variant)?;
    naga::compact::compact(&mut module, naga::compact::KeepUnused::No);
    let info = lib.profile().validator().validate(&module).map_err(|e| {
        VariantError {
            variant: variant.label(),
            stage: Stage::Validate,
            message: format!("after compaction: {}", e.as_inner()),
            labels: Vec::new(),
            notes: Vec::new(),
            source: None,
        }
        .with_source(e)
    })?;
    Ok((module, info))
}

/// A distinct composed text that naga rejected, with every keyword set that produces it.
///
/// Serialized (in `validate --json`) as `stage`, `message`, `location`, `keyword_sets` and
/// `diagnostic`; a shard's report adds `text` and `numbers`, which [`crate::merge`] needs.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Failure {
    /// The error (naming the first such variant).
    pub error: VariantError,
    /// `path:line:col` of the error's first label, when it has one.
    pub location: Option<Location>,
    /// Every keyword set with this text, in enumeration order.
    pub keyword_sets: Vec<Vec<String>>,
    /// The error's diagnostic, rendered without colours.
    pub diagnostic: String,
    /// In a shard's report: the text's dedup key (hex), to join it with the same text in
    /// other shards.
    pub text: Option<String>,
    /// In a shard's report: the variant number (across passes, as [`Shard`] counts) of each
    /// keyword set; empty otherwise.
    pub numbers: Vec<u64>,
    /// Position of each keyword set in the sequence validated.
    positions: Vec<u64>,
    /// The text's dedup key.
    key: u128,
}

impl serde::Serialize for Failure {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut out = s.serialize_struct("Failure", 7)?;
        out.serialize_field("stage", &self.error.stage)?;
        out.serialize_field("message", &self.error.message)?;
        out.serialize_field("location", &self.location.as_ref().map(|l| l.to_string()))?;
        out.serialize_field("keyword_sets", &self.keyword_sets)?;
        out.serialize_field("diagnostic", &self.diagnostic)?;
        if let Some(text) = &self.text {
            out.serialize_field("text", text)?;
        }
        if !self.numbers.is_empty() {
            out.serialize_field("numbers", &self.numbers)?;
        }
        out.end()
    }
}

/// The result of validating one pass.
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct PassReport {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Size of the full space.
    #[serde(serialize_with = "crate::json::exact_count")]
    pub full_space: BigUint,
    /// Variants built.
    pub built: u64,
    /// Distinct composed texts among them (each validated once).
    pub distinct: u64,
    /// Built variants that passed.
    pub valid: u64,
    /// Built variants that failed.
    pub invalid: u64,
    /// The failures, one per distinct failing text.
    pub failures: Vec<Failure>,
    /// In a shard's report, when the audit cannot prove every text of the pass distinct: the
    /// dedup keys (hex, sorted) of the distinct texts, so that [`crate::merge`] counts texts
    /// shared between shards once.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub texts: Option<Vec<String>>,
    /// Dedup keys of the texts seen (when kept; see [`validate_pass_with`]).
    #[serde(skip)]
    seen: Option<HashSet<u128>>,
}

/// Which variants a validation covered.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Selection {
    /// Each pass's build set.
    BuildSet,
    /// Each pass's full space.
    FullSpace,
}

/// Sums over the passes of a [`ValidateReport`].
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub struct ValidateTotals {
    /// Number of passes.
    pub passes: usize,
    /// Variants built.
    pub built: u64,
    /// Distinct composed texts.
    pub distinct: u64,
    /// Variants that passed.
    pub valid: u64,
    /// Variants that failed.
    pub invalid: u64,
}

/// The result of validating a plan (what `validate --json` prints).
#[derive(Clone, Debug, serde::Serialize)]
#[non_exhaustive]
pub struct ValidateReport {
    /// No variant failed.
    pub ok: bool,
    /// Build sets or full spaces.
    pub selection: Selection,
    /// What the report was made from (see [`crate::fingerprint::fingerprint`]); the same for every
    /// shard of one run and for the run on one machine.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub fingerprint: String,
    /// The shard validated, if only one was (`K/N` in JSON).
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "crate::variants::shard_text"
    )]
    pub shard: Option<Shard>,
    /// One report per pass, in plan order.
    pub passes: Vec<PassReport>,
    /// Sums over the passes.
    pub totals: ValidateTotals,
}

impl ValidateReport {
    /// The report of `passes`, with its totals (and no fingerprint).
    pub fn new(passes: Vec<PassReport>, selection: Selection, shard: Option<Shard>) -> Self {
        let mut totals = ValidateTotals {
            passes: passes.len(),
            ..ValidateTotals::default()
        };
        for r in &passes {
            totals.built += r.built;
            totals.distinct += r.distinct;
            totals.valid += r.valid;
            totals.invalid += r.invalid;
        }
        ValidateReport {
            ok: totals.invalid == 0,
            selection,
            fingerprint: String::new(),
            shard,
            passes,
            totals,
        }
    }
}

/// Validates every variant of a plan made with `options` (see [`crate::plan::plan`]), with an
/// optional cache of valid texts; `progress(n)` is called as each batch of `n` variants is
/// done.
///
/// ```
/// use wgsl_variants::plan::{PlanOptions, plan};
///
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let mut options = PlanOptions::default();
/// options.pass = Some("Final".into());
/// let planned = plan(&lib, &options).unwrap();
/// let report = wgsl_variants::validate::validate_plan(&lib, &planned, &options, None, &|_| {});
/// assert!(report.ok && report.totals.passes == 1);
/// ```
pub fn validate_plan(
    lib: &Library,
    plan: &Plan<'_>,
    options: &PlanOptions,
    cache: Option<&ValidCache>,
    progress: &(dyn Fn(u64) + Sync),
) -> ValidateReport {
    // Variants of the shard before the current pass: with the shard, they give each keyword
    // set's number across passes.
    let mut offset = 0u64;
    let passes = plan
        .iter()
        .map(|(pass, choices)| {
            let mut report = validate_keyed(
                lib,
                pass,
                choices.iter().cloned(),
                cache,
                progress,
                Keyed {
                    keep_seen: options.shard.is_some(),
                    strict: options.strict,
                    cancel: None,
                },
                &mut |_, _| {},
            )
            .expect("nothing cancels it");
            let seen = report.seen.take();
            if let Some(shard) = options.shard {
                report.texts = seen.map(|seen| {
                    let mut keys: Vec<u128> = seen.into_iter().collect();
                    keys.sort_unstable();
                    keys.iter().map(|k| format!("{k:032x}")).collect()
                });
                for f in &mut report.failures {
                    f.text = Some(format!("{:032x}", f.key));
                    f.numbers = f
                        .positions
                        .iter()
                        .map(|p| shard.index + (offset + p) * shard.count)
                        .collect();
                }
            }
            offset += report.built;
            report
        })
        .collect();
    plan_report(lib, passes, options)
}

/// The report of a plan made with `options`, from its passes' reports: totals, selection,
/// shard and fingerprint.
pub(crate) fn plan_report(
    lib: &Library,
    passes: Vec<PassReport>,
    options: &PlanOptions,
) -> ValidateReport {
    let selection = if options.all {
        Selection::FullSpace
    } else {
        Selection::BuildSet
    };
    let mut report = ValidateReport::new(passes, selection, options.shard);
    report.fingerprint =
        crate::fingerprint::fingerprint(lib, "validate", &options.fingerprint_text());
    report
}

/// Validates one pass's variants; `progress(n)` is called as each batch of `n` variants is done.
pub fn validate_pass(
    lib: &Library,
    pass: &Pass,
    choices: &[Choice],
    progress: &(dyn Fn(u64) + Sync),
) -> PassReport {
    validate_pass_with(lib, pass, choices.iter().cloned(), None, progress)
}

/// Variants composed and hashed per batch, per worker thread: enough that the end of a batch
/// (where workers wait for the slowest) costs little, few enough that the texts alive at once
/// stay a few megabytes.
const BATCH_PER_THREAD: usize = 256;

/// [`validate_pass`] over any sequence of variants (e.g. [`Space::iter`], never collected),
/// with an optional cache of texts known to be valid.
///
/// Variants are composed in parallel batches; each text is hashed (BLAKE3) and only the first
/// variant with a given text is validated. Texts are dropped batch by batch; what is kept is
/// the failing variants and, unless [`crate::analysis::proves_all_distinct`] shows that every
/// variant of the pass has its own text, 16 bytes per distinct text seen. Results are in
/// enumeration order whatever the thread count.
///
/// `choices` are expected to be different keyword sets, as every [`Space`] gives them; when
/// the audit proves all texts distinct, a keyword set given twice is validated twice.
pub fn validate_pass_with(
    lib: &Library,
    pass: &Pass,
    choices: impl IntoIterator<Item = Choice>,
    cache: Option<&ValidCache>,
    progress: &(dyn Fn(u64) + Sync),
) -> PassReport {
    validate_keyed(
        lib,
        pass,
        choices,
        cache,
        progress,
        Keyed::default(),
        &mut |_, _| {},
    )
    .expect("nothing cancels it")
}

/// How [`validate_keyed`] runs beyond [`validate_pass_with`].
#[derive(Clone, Copy, Default)]
pub(crate) struct Keyed<'c> {
    /// The report keeps the dedup keys of the texts seen (when they were collected) for a
    /// shard's `texts`.
    pub keep_seen: bool,
    /// Also validate each distinct unpruned text ([`PlanOptions::strict`]).
    pub strict: bool,
    /// Checked between batches: once set, validation stops and gives no report.
    pub cancel: Option<&'c AtomicBool>,
}

/// [`validate_pass_with`], with the options of [`Keyed`]; `found(key, error)` is called as
/// each failing text is found. `None` when `how.cancel` stopped it.
pub(crate) fn validate_keyed(
    lib: &Library,
    pass: &Pass,
    choices: impl IntoIterator<Item = Choice>,
    cache: Option<&ValidCache>,
    progress: &(dyn Fn(u64) + Sync),
    how: Keyed<'_>,
    found: &mut dyn FnMut(u128, &VariantError),
) -> Option<PassReport> {
    // Keys (128 bits of the text's hash) of the texts seen; not kept when the audit proves
    // that no two variants share a text, so memory does not grow with the space.
    let mut seen: Option<HashSet<u128>> =
        (!crate::analysis::proves_all_distinct(lib, pass)).then(HashSet::new);
    // One entry per failing text, in order of first appearance: error, text key and keyword
    // sets with their positions.
    type Failing = (VariantError, u128, Vec<(u64, Choice)>);
    let mut failures: Vec<Failing> = Vec::new();
    let mut failing: HashMap<u128, usize> = HashMap::new();
    // With `strict`: the keys of the unpruned texts seen (kept whatever the audit proves: a
    // pruned text can stand for several unpruned ones).
    let mut seen_unpruned: HashSet<u128> = HashSet::new();
    let batch = BATCH_PER_THREAD * rayon::current_num_threads().max(1);
    let mut choices = choices.into_iter();
    let (mut built, mut distinct) = (0u64, 0u64);
    let mut record = |error: VariantError,
                      k: u128,
                      failing: &mut HashMap<u128, usize>,
                      failures: &mut Vec<Failing>| {
        found(k, &error);
        failing.insert(k, failures.len());
        failures.push((error, k, Vec::new()));
    };
    loop {
        if how.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return None;
        }
        let chunk: Vec<Choice> = choices.by_ref().take(batch).collect();
        if chunk.is_empty() {
            break;
        }
        built += chunk.len() as u64;
        let composed: Vec<(Hash, Composed)> = chunk
            .par_iter()
            .map(|c| {
                // No line map on the hot path: a failing text is composed again with it.
                let composed = lib.compose_text(&Variant {
                    pass,
                    choice: c.clone(),
                });
                (text_hash(lib, &composed.text), composed)
            })
            .collect();
        let keys: Vec<u128> = composed.iter().map(|(h, _)| key(h)).collect();
        // A variant whose composition failed has no text to compare: its key is its error's,
        // which groups the failure, but it counts as a program of its own (naga_oil's or
        // wesl's message is the same for programs that differ), in shards too.
        let dedup: Vec<u128> = (0..chunk.len())
            .map(|j| match composed[j].1.failure {
                Some(_) => {
                    let options: Vec<u8> =
                        chunk[j].0.iter().flat_map(|o| o.to_le_bytes()).collect();
                    let k = keys[j].to_le_bytes();
                    let h = crate::fingerprint::hash_parts([&k[..], &options[..]]);
                    key(h.as_bytes())
                }
                None => keys[j],
            })
            .collect();
        let fresh: Vec<usize> = (0..chunk.len())
            .filter(|&j| seen.as_mut().is_none_or(|s| s.insert(dedup[j])))
            .collect();
        distinct += fresh.len() as u64;
        let results = validate_fresh(
            pass,
            &chunk,
            &fresh,
            lib.profile(),
            |variant, j, validator| {
                check(
                    variant,
                    &composed[j],
                    cache,
                    validator,
                    lib.profile(),
                    |v| lib.compose(v),
                )
            },
        );
        drop(composed);
        for (j, error) in results {
            // Failed compositions with one error are one failure.
            if !failing.contains_key(&keys[j]) {
                record(error, keys[j], &mut failing, &mut failures);
            }
        }
        // The unpruned texts of the variants whose program is valid, each validated once.
        let mut unpruned_keys: Vec<Option<u128>> = vec![None; chunk.len()];
        if how.strict {
            let texts: Vec<Option<(Hash, Composed)>> = (0..chunk.len())
                .into_par_iter()
                .map(|j| {
                    (!failing.contains_key(&keys[j])).then(|| {
                        let text = lib.compose_unpruned(
                            &Variant {
                                pass,
                                choice: chunk[j].clone(),
                            },
                            false,
                        );
                        (text_hash(lib, &text.text), text)
                    })
                })
                .collect();
            for (j, text) in texts.iter().enumerate() {
                unpruned_keys[j] = text.as_ref().map(|(h, _)| key(h));
            }
            let fresh: Vec<usize> = (0..chunk.len())
                .filter(|&j| unpruned_keys[j].is_some_and(|k| seen_unpruned.insert(k)))
                .collect();
            let results = validate_fresh(
                pass,
                &chunk,
                &fresh,
                lib.profile(),
                |variant, j, validator| {
                    let text = texts[j].as_ref().expect("composed above");
                    check(variant, text, cache, validator, lib.profile(), |v| {
                        lib.compose_unpruned(v, true)
                    })
                    .map(|mut e| {
                        e.notes.push(
                            "in code no entry point of this variant reaches (--strict)".into(),
                        );
                        e
                    })
                },
            );
            for (j, error) in results {
                let k = unpruned_keys[j].expect("composed above");
                record(error, k, &mut failing, &mut failures);
            }
        }
        let first = built - keys.len() as u64;
        if !failing.is_empty() {
            for (j, (choice, k)) in chunk.into_iter().zip(&keys).enumerate() {
                let failure = failing
                    .get(k)
                    .or_else(|| unpruned_keys[j].and_then(|u| failing.get(&u)));
                if let Some(&f) = failure {
                    failures[f].2.push((first + j as u64, choice));
                }
            }
        }
        progress(keys.len() as u64);
    }
    let invalid: u64 = failures.iter().map(|(_, _, sets)| sets.len() as u64).sum();
    Some(PassReport {
        shader: pass.shader.clone(),
        pass: pass.name.clone(),
        full_space: Space::full(pass).count(),
        built,
        distinct,
        valid: built - invalid,
        invalid,
        failures: failures
            .into_iter()
            .map(|(error, key, sets)| Failure {
                location: error.location(lib.files()),
                diagnostic: error.diagnostic().render(lib.files(), false),
                error,
                keyword_sets: sets
                    .iter()
                    .map(|(_, c)| c.keywords(pass).into_iter().map(str::to_string).collect())
                    .collect(),
                text: None,
                numbers: Vec::new(),
                positions: sets.iter().map(|(p, _)| *p).collect(),
                key,
            })
            .collect(),
        texts: None,
        seen: seen.filter(|_| how.keep_seen),
    })
}

/// Validates the variants of `chunk` at the indices `fresh` in parallel (one validator per
/// worker), with `validate(variant, index, validator)`; the failures, in order.
fn validate_fresh(
    pass: &Pass,
    chunk: &[Choice],
    fresh: &[usize],
    profile: crate::validator::Profile,
    validate: impl Fn(&Variant<'_>, usize, &mut naga::valid::Validator) -> Option<VariantError> + Sync,
) -> Vec<(usize, VariantError)> {
    let results: Vec<Option<VariantError>> = fresh
        .par_iter()
        .map_init(
            || profile.validator(),
            |validator, &j| {
                let variant = Variant {
                    pass,
                    choice: chunk[j].clone(),
                };
                validate(&variant, j, validator)
            },
        )
        .collect();
    fresh
        .iter()
        .zip(results)
        .filter_map(|(&j, r)| r.map(|e| (j, e)))
        .collect()
}

/// A composed text's hash (its dedup key and its key in the cache of valid texts): the text's
/// for WebGPU, the text's with the profile's name for any other profile, so that a text valid
/// on one device is never taken as valid on another.
fn text_hash(lib: &Library, text: &str) -> Hash {
    match lib.profile() {
        crate::validator::Profile::WebGpu => crate::cache::hash(text),
        other => crate::cache::hash(&format!("{text}\0profile {}", other.name())),
    }
}

/// Composes and validates one variant (unless `cache` knows its text valid): its text's
/// dedup key and its error.
pub(crate) fn validate_variant(
    lib: &Library,
    variant: &Variant<'_>,
    cache: Option<&ValidCache>,
    validator: &mut naga::valid::Validator,
) -> (u128, Option<VariantError>) {
    let text = lib.compose_text(variant);
    let hash = text_hash(lib, &text.text);
    let error = check(
        variant,
        &(hash, text),
        cache,
        validator,
        lib.profile(),
        |v| lib.compose(v),
    );
    (key(&hash), error)
}

/// Validates one composed text of `variant` unless `cache` knows it valid (and remembers it
/// when it is); a failing text is composed again with its line map (`with_map`) to locate the
/// error.
fn check(
    variant: &Variant<'_>,
    (hash, text): &(Hash, Composed),
    cache: Option<&ValidCache>,
    validator: &mut naga::valid::Validator,
    profile: crate::validator::Profile,
    with_map: impl Fn(&Variant<'_>) -> Composed,
) -> Option<VariantError> {
    if cache.is_some_and(|c| c.contains(hash)) {
        return None;
    }
    let result = match validate_with(text, &variant.label(), validator, profile) {
        Ok(_) => None,
        Err(_) => validate_with(&with_map(variant), &variant.label(), validator, profile).err(),
    };
    if let (None, Some(cache)) = (&result, cache) {
        cache.insert(*hash);
    }
    result
}

/// The dedup key of a text: 128 bits of its BLAKE3 hash (a collision among 10^12 texts has a
/// probability below 2^-48).
fn key(hash: &Hash) -> u128 {
    let mut bytes = [0u8; 16];
    bytes.copy_from_slice(&hash[..16]);
    u128::from_le_bytes(bytes)
}
