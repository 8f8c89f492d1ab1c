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
    let info = lib
        .pass_profile(variant.pass)
        .validator()
        .validate(&module)
        .map_err(|e| {
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
/// `diagnostic`; when the run validates for several profiles, `profiles` (after `location`)
/// lists those this error happens on; a shard's report adds `text` and `numbers`, which
/// [`crate::merge`] needs.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Failure {
    /// The error (naming the first such variant).
    pub error: VariantError,
    /// `path:line:col` of the error's first label, when it has one.
    pub location: Option<Location>,
    /// Every keyword set with this text, in enumeration order.
    pub keyword_sets: Vec<Vec<String>>,
    /// When the run validates for several profiles: the names of the profiles this error
    /// happens on, in the order the profiles were given ([`Profile::name`]); empty otherwise.
    pub profiles: Vec<String>,
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
        if !self.profiles.is_empty() {
            out.serialize_field("profiles", &self.profiles)?;
        }
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
    /// Built variants that passed (on every profile, when several are validated).
    pub valid: u64,
    /// Built variants that failed (on at least one profile, when several are validated).
    pub invalid: u64,
    /// When the run validates for several profiles: the pass's verdicts per profile, in the
    /// order the profiles were given; empty (and left out of JSON) otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub profiles: Vec<ProfileCounts>,
    /// The failures, one per distinct failing text (and, with several profiles, per distinct
    /// error of that text: [`Failure::profiles`]).
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

/// A failing variant and the profiles it fails on ([`PassReport::failing_variants`]).
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct FailingVariant {
    /// The keywords on.
    pub keywords: Vec<String>,
    /// The profiles it fails on, in the order the pass's profiles were given; empty when the
    /// run validates for one profile.
    pub profiles: Vec<String>,
}

impl PassReport {
    /// Each failing variant with the profiles it fails on, in enumeration order: a variant
    /// that fails on several profiles with different errors is in several [`Failure`]s, and
    /// once here.
    ///
    /// ```
    /// use wgsl_variants::validate::{Profile, validate_pass};
    /// let mut lib = wgsl_variants::Library::from_sources([
    ///     ("f.wgsl", "@fragment fn fs() -> @location(0) vec4f {\n    var c = vec4f(0.0);\n#ifdef WIDE\n    let w: f64 = 1.0lf;\n    c.x = f32(w);\n#endif\n    return c;\n}\n"),
    ///     ("main.wgsl", "#shader s\n#pass P\n#pragma multi_compile _ WIDE\n#import f\n#endpass\n"),
    /// ])
    /// .unwrap();
    /// lib.set_profiles(&[Profile::WebGpu, Profile::Desktop]);
    /// let pass = lib.pass("s", "P").unwrap();
    /// let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    /// let report = validate_pass(&lib, pass, &choices, &|_| {});
    /// let failing = report.failing_variants();
    /// assert_eq!(failing.len(), 1);
    /// assert_eq!((failing[0].keywords.as_slice(), failing[0].profiles.as_slice()), (&["WIDE".to_string()][..], &["webgpu".to_string()][..]));
    /// ```
    pub fn failing_variants(&self) -> Vec<FailingVariant> {
        let order: Vec<&str> = self.profiles.iter().map(|p| p.profile.as_str()).collect();
        let mut by_position: std::collections::BTreeMap<u64, FailingVariant> =
            std::collections::BTreeMap::new();
        for f in &self.failures {
            for (position, keywords) in f.positions.iter().zip(&f.keyword_sets) {
                let v = by_position
                    .entry(*position)
                    .or_insert_with(|| FailingVariant {
                        keywords: keywords.clone(),
                        profiles: Vec::new(),
                    });
                for p in &f.profiles {
                    if !v.profiles.contains(p) {
                        v.profiles.push(p.clone());
                    }
                }
            }
        }
        let rank = |p: &String| order.iter().position(|o| o == p);
        by_position
            .into_values()
            .map(|mut v| {
                v.profiles.sort_by_key(rank);
                v
            })
            .collect()
    }
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

/// One profile's verdicts over a pass or a whole run, when several profiles are validated
/// (`validate --json`: `{"profile": "webgpu", "valid": 3, "invalid": 1}`).
#[derive(Clone, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[non_exhaustive]
pub struct ProfileCounts {
    /// The profile's name ([`Profile::name`]).
    pub profile: String,
    /// Variants valid on it.
    pub valid: u64,
    /// Variants that fail on it.
    pub invalid: u64,
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
    /// Variants that passed (on every profile they were validated for).
    pub valid: u64,
    /// Variants that failed (on at least one profile).
    pub invalid: u64,
    /// When several profiles are validated: each profile's sums over the passes validated
    /// for it, profiles in order of first appearance; empty (and left out of JSON) otherwise.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub profiles: Vec<ProfileCounts>,
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
            for c in &r.profiles {
                match totals.profiles.iter_mut().find(|t| t.profile == c.profile) {
                    Some(t) => {
                        t.valid += c.valid;
                        t.invalid += c.invalid;
                    }
                    None => totals.profiles.push(c.clone()),
                }
            }
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
/// each failing text is found (once per profile it fails on). `None` when `how.cancel`
/// stopped it.
pub(crate) fn validate_keyed(
    lib: &Library,
    pass: &Pass,
    choices: impl IntoIterator<Item = Choice>,
    cache: Option<&ValidCache>,
    progress: &(dyn Fn(u64) + Sync),
    how: Keyed<'_>,
    found: &mut dyn FnMut(u128, &VariantError),
) -> Option<PassReport> {
    let targets = Targets::of(lib, pass);
    // Keys (128 bits of the text's hash) of the texts seen; not kept when the audit proves
    // that no two variants share a text, so memory does not grow with the space.
    let mut seen: Option<HashSet<u128>> =
        (!crate::analysis::proves_all_distinct(lib, pass)).then(HashSet::new);
    let mut failing = Found::default();
    // With `strict`: the keys of the unpruned texts seen (kept whatever the audit proves: a
    // pruned text can stand for several unpruned ones).
    let mut seen_unpruned: HashSet<u128> = HashSet::new();
    let batch = BATCH_PER_THREAD * rayon::current_num_threads().max(1);
    let mut choices = choices.into_iter();
    let (mut built, mut distinct) = (0u64, 0u64);
    let every = |_: usize, _: usize| true;
    loop {
        if how.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
            return None;
        }
        let chunk: Vec<Choice> = choices.by_ref().take(batch).collect();
        if chunk.is_empty() {
            break;
        }
        built += chunk.len() as u64;
        let variant = |j: usize| Variant {
            pass,
            choice: chunk[j].clone(),
        };
        // No line map on the hot path: a failing text is composed again with it.
        let composed: Vec<Compositions> = (0..chunk.len())
            .into_par_iter()
            .map(|j| targets.compose(lib, &variant(j), true))
            .collect();
        let keys: Vec<u128> = composed.iter().map(|c| key(&c.hash)).collect();
        // A variant whose composition failed has no text to compare: its key is its error's,
        // which groups the failure, but it counts as a program of its own (naga_oil's or
        // wesl's message is the same for programs that differ), in shards too.
        let dedup: Vec<u128> = (0..chunk.len())
            .map(|j| {
                if composed[j].texts.iter().any(|t| t.failure.is_some()) {
                    let options: Vec<u8> =
                        chunk[j].0.iter().flat_map(|o| o.to_le_bytes()).collect();
                    let k = keys[j].to_le_bytes();
                    let h = crate::fingerprint::hash_parts([&k[..], &options[..]]);
                    key(h.as_bytes())
                } else {
                    keys[j]
                }
            })
            .collect();
        let fresh: Vec<usize> = (0..chunk.len())
            .filter(|&j| seen.as_mut().is_none_or(|s| s.insert(dedup[j])))
            .collect();
        distinct += fresh.len() as u64;
        let results = validate_fresh(
            &variant,
            (&fresh, targets.profiles.len()),
            &every,
            |v, j, i, validators| targets.check(lib, v, &composed[j], i, cache, validators, true),
        );
        drop(composed);
        for (j, i, error) in results {
            // Failed compositions with one error are one failure.
            if !failing.at.contains_key(&(keys[j], i)) {
                failing.record(error, keys[j], i, found);
            }
        }
        // The unpruned texts of the variants whose program is valid (on a profile), each
        // validated once (on each profile where the program is valid).
        let mut unpruned_keys: Vec<Option<u128>> = vec![None; chunk.len()];
        if how.strict {
            let valid_on = |j: usize, i: usize| !failing.at.contains_key(&(keys[j], i));
            let texts: Vec<Option<Compositions>> = (0..chunk.len())
                .into_par_iter()
                .map(|j| {
                    (0..targets.profiles.len())
                        .any(|i| valid_on(j, i))
                        .then(|| targets.compose(lib, &variant(j), false))
                })
                .collect();
            for (j, text) in texts.iter().enumerate() {
                unpruned_keys[j] = text.as_ref().map(|c| key(&c.hash));
            }
            let fresh: Vec<usize> = (0..chunk.len())
                .filter(|&j| unpruned_keys[j].is_some_and(|k| seen_unpruned.insert(k)))
                .collect();
            let results = validate_fresh(
                &variant,
                (&fresh, targets.profiles.len()),
                &valid_on,
                |v, j, i, validators| {
                    let text = texts[j].as_ref().expect("composed above");
                    targets
                        .check(lib, v, text, i, cache, validators, false)
                        .map(|mut e| {
                            e.notes.push(
                                "in code no entry point of this variant reaches (--strict)".into(),
                            );
                            e
                        })
                },
            );
            for (j, i, error) in results {
                let k = unpruned_keys[j].expect("composed above");
                failing.record(error, k, i, found);
            }
        }
        let first = built - keys.len() as u64;
        if !failing.at.is_empty() {
            for (j, (choice, k)) in chunk.iter().zip(&keys).enumerate() {
                for i in 0..targets.profiles.len() {
                    let failure = failing
                        .at
                        .get(&(*k, i))
                        .or_else(|| unpruned_keys[j].and_then(|u| failing.at.get(&(u, i))));
                    if let Some(&f) = failure {
                        failing.entries[f]
                            .sets
                            .push((first + j as u64, choice.clone()));
                    }
                }
            }
        }
        progress(keys.len() as u64);
    }
    Some(failing.report(lib, pass, &targets, (built, distinct), seen, how.keep_seen))
}

/// The devices one pass is validated for, and how its variants are composed for them.
struct Targets {
    /// The pass's profiles ([`Library::pass_profiles`]).
    profiles: Vec<Profile>,
    /// The profile each composition of a variant is made for: one per profile, or, when the
    /// engine composes alike for every device, one for their capabilities' union.
    compose_for: Vec<Profile>,
    /// Index into `compose_for` of each profile's composition.
    group: Vec<usize>,
    /// The run validates for several profiles: counts and failures name theirs.
    named: bool,
}

/// A variant's compositions ([`Targets::compose_for`]) and their dedup hash.
struct Compositions {
    hash: Hash,
    texts: Vec<Composed>,
}

impl Targets {
    fn of(lib: &Library, pass: &Pass) -> Targets {
        let profiles = lib.pass_profiles(pass).to_vec();
        let (compose_for, group) = if profiles.len() > 1 && lib.composes_alike() {
            let union = profiles
                .iter()
                .fold(naga::valid::Capabilities::empty(), |all, p| {
                    all | p.capabilities()
                });
            (vec![Profile::Capabilities(union)], vec![0; profiles.len()])
        } else {
            (profiles.clone(), (0..profiles.len()).collect())
        };
        Targets {
            profiles,
            compose_for,
            group,
            named: lib.several_profiles(),
        }
    }

    /// The lean compositions of `variant` (pruned or not) and their dedup hash: for one
    /// profile the text's [`text_hash`], for several a hash of every composition.
    fn compose(&self, lib: &Library, variant: &Variant<'_>, prune: bool) -> Compositions {
        let texts: Vec<Composed> = self
            .compose_for
            .iter()
            .map(|&p| lib.compose_for(variant, false, prune, p))
            .collect();
        let hash = match self.profiles.as_slice() {
            [one] => text_hash(*one, &texts[0].text),
            several => {
                let names: Vec<String> = several.iter().map(|p| p.name()).collect();
                let parts = std::iter::once(&b"profiles"[..])
                    .chain(names.iter().map(|n| n.as_bytes()))
                    .chain(texts.iter().map(|t| t.text.as_bytes()));
                *crate::fingerprint::hash_parts(parts).as_bytes()
            }
        };
        Compositions { hash, texts }
    }

    /// Validates profile `i`'s composition of `variant` ([`check`]); a failure is composed
    /// again for that profile, with its line map (`prune` as the composition was made).
    #[allow(clippy::too_many_arguments)]
    fn check(
        &self,
        lib: &Library,
        variant: &Variant<'_>,
        composed: &Compositions,
        i: usize,
        cache: Option<&ValidCache>,
        validators: &mut Validators,
        prune: bool,
    ) -> Option<VariantError> {
        let profile = self.profiles[i];
        let text = &composed.texts[self.group[i]];
        let hash = if self.profiles.len() == 1 {
            composed.hash
        } else {
            text_hash(profile, &text.text)
        };
        check(
            variant,
            &hash,
            text,
            cache,
            validators.get(profile),
            profile,
            |v| lib.compose_for(v, true, prune, profile),
        )
    }
}

/// One naga validator per profile, made as first needed (one set per worker thread).
#[derive(Default)]
pub(crate) struct Validators(Vec<(Profile, naga::valid::Validator)>);

impl Validators {
    /// The validator of `profile`.
    pub(crate) fn get(&mut self, profile: Profile) -> &mut naga::valid::Validator {
        let at = match self.0.iter().position(|(p, _)| *p == profile) {
            Some(at) => at,
            None => {
                self.0.push((profile, profile.validator()));
                self.0.len() - 1
            }
        };
        &mut self.0[at].1
    }
}

/// A pass's failing texts as found: per text key and profile (index into
/// [`Targets::profiles`]), the error and the keyword sets with their positions, in order of
/// first appearance.
#[derive(Default)]
struct Found {
    entries: Vec<Entry>,
    /// (text key, profile) → its entry.
    at: HashMap<(u128, usize), usize>,
}

/// One failing text on one profile.
struct Entry {
    error: VariantError,
    /// The text's dedup key.
    key: u128,
    /// The profile (index into [`Targets::profiles`]).
    profile: usize,
    /// The keyword sets with this text, with their positions.
    sets: Vec<(u64, Choice)>,
}

impl Found {
    fn record(
        &mut self,
        error: VariantError,
        key: u128,
        profile: usize,
        found: &mut dyn FnMut(u128, &VariantError),
    ) {
        found(key, &error);
        self.at.insert((key, profile), self.entries.len());
        self.entries.push(Entry {
            error,
            key,
            profile,
            sets: Vec::new(),
        });
    }

    /// The pass's report: counts (per profile when the run names them) and failures, those
    /// of one text with the same error and keyword sets on several profiles as one.
    fn report(
        self,
        lib: &Library,
        pass: &Pass,
        targets: &Targets,
        (built, distinct): (u64, u64),
        seen: Option<HashSet<u128>>,
        keep_seen: bool,
    ) -> PassReport {
        let mut per_profile = vec![0u64; targets.profiles.len()];
        for e in &self.entries {
            per_profile[e.profile] += e.sets.len() as u64;
        }
        let invalid = if targets.profiles.len() == 1 {
            per_profile[0]
        } else {
            let failing: HashSet<u64> = self
                .entries
                .iter()
                .flat_map(|e| e.sets.iter().map(|(p, _)| *p))
                .collect();
            failing.len() as u64
        };
        let profiles = if targets.named {
            targets
                .profiles
                .iter()
                .zip(&per_profile)
                .map(|(p, &invalid)| ProfileCounts {
                    profile: p.name(),
                    valid: built - invalid,
                    invalid,
                })
                .collect()
        } else {
            Vec::new()
        };
        let mut failures: Vec<Failure> = Vec::new();
        // (text key, diagnostic) → the failure with them, to join profiles failing alike.
        let mut alike: HashMap<(u128, String), usize> = HashMap::new();
        for Entry {
            error,
            key,
            profile: i,
            sets,
        } in self.entries
        {
            let diagnostic = error.diagnostic().render(lib.files(), false);
            let positions: Vec<u64> = sets.iter().map(|(p, _)| *p).collect();
            let name = targets.profiles[i].name();
            if targets.named
                && let Some(&f) = alike.get(&(key, diagnostic.clone()))
                && failures[f].positions == positions
            {
                failures[f].profiles.push(name);
                continue;
            }
            alike.insert((key, diagnostic.clone()), failures.len());
            failures.push(Failure {
                location: error.location(lib.files()),
                diagnostic,
                error,
                keyword_sets: sets
                    .iter()
                    .map(|(_, c)| c.keywords(pass).into_iter().map(str::to_string).collect())
                    .collect(),
                profiles: if targets.named {
                    vec![name]
                } else {
                    Vec::new()
                },
                text: None,
                numbers: Vec::new(),
                positions,
                key,
            });
        }
        PassReport {
            shader: pass.shader.clone(),
            pass: pass.name.clone(),
            full_space: Space::full(pass).count(),
            built,
            distinct,
            valid: built - invalid,
            invalid,
            profiles,
            failures,
            texts: None,
            seen: seen.filter(|_| keep_seen),
        }
    }
}

/// Validates the variants at the indices `fresh` in parallel (one set of validators per
/// worker) on each of the `profiles` profiles `i` that `wanted(j, i)`, with
/// `validate(variant, j, i, validators)`; the failures `(j, i, error)`, in order.
fn validate_fresh<'p>(
    variant: &(dyn Fn(usize) -> Variant<'p> + Sync),
    (fresh, profiles): (&[usize], usize),
    wanted: &(dyn Fn(usize, usize) -> bool + Sync),
    validate: impl Fn(&Variant<'_>, usize, usize, &mut Validators) -> Option<VariantError> + Sync,
) -> Vec<(usize, usize, VariantError)> {
    let results: Vec<Vec<(usize, VariantError)>> = fresh
        .par_iter()
        .map_init(Validators::default, |validators, &j| {
            let v = variant(j);
            (0..profiles)
                .filter(|&i| wanted(j, i))
                .filter_map(|i| validate(&v, j, i, validators).map(|e| (i, e)))
                .collect()
        })
        .collect();
    fresh
        .iter()
        .zip(results)
        .flat_map(|(&j, r)| r.into_iter().map(move |(i, e)| (j, i, e)))
        .collect()
}

/// A composed text's hash (its dedup key for one profile, and its key in the cache of valid
/// texts): the text's for WebGPU, the text's with the profile's name for any other profile,
/// so that a text valid on one device is never taken as valid on another.
fn text_hash(profile: Profile, text: &str) -> Hash {
    match profile {
        Profile::WebGpu => crate::cache::hash(text),
        other => crate::cache::hash(&format!("{text}\0profile {}", other.name())),
    }
}

/// Composes and validates one variant on each of its pass's profiles (unless `cache` knows
/// its text valid there): its dedup key and the error of the first profile it fails on.
pub(crate) fn validate_variant(
    lib: &Library,
    variant: &Variant<'_>,
    cache: Option<&ValidCache>,
    validators: &mut Validators,
) -> (u128, Option<VariantError>) {
    let targets = Targets::of(lib, variant.pass);
    let composed = targets.compose(lib, variant, true);
    let error = (0..targets.profiles.len())
        .find_map(|i| targets.check(lib, variant, &composed, i, cache, validators, true));
    (key(&composed.hash), error)
}

/// Validates one composed text of `variant` (its cache key `hash`) unless `cache` knows it
/// valid (and remembers it when it is); a failing text is composed again with its line map
/// (`with_map`) to locate the error.
fn check(
    variant: &Variant<'_>,
    hash: &Hash,
    text: &Composed,
    cache: Option<&ValidCache>,
    validator: &mut naga::valid::Validator,
    profile: Profile,
    with_map: impl Fn(&Variant<'_>) -> Composed,
) -> Option<VariantError> {
    if cache.is_some_and(|c| c.contains(hash)) {
        return None;
    }
    let result = if text.validated == Some(profile) {
        // Its composer parsed and validated this very text for this profile.
        None
    } else {
        match validate_with(text, &variant.label(), validator, profile) {
            Ok(_) => None,
            // A composer's failure: composing again with the line map gives the same one (the
            // engines that can fail keep no line map).
            Err(e) if text.failure.is_some() => Some(e),
            Err(_) => validate_with(&with_map(variant), &variant.label(), validator, profile).err(),
        }
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
