//! Programs the engine compiled before, reused for a variant that compiles to the same one.
//!
//! What `wesl` compiles from a root module is a function of the modules it loads as their
//! conditions leave them and of the `constants` package: which modules it loads follows from
//! the imports those conditions keep, and what a condition keeps from the values of the
//! features its module's text names. So a variant whose features give every module an earlier
//! compile loaded the same values ([`super::WeslEngine::feature_key`]), with the same
//! constants, compiles to the same program: its text, and naga's verdict for the same
//! profile, are the earlier ones. On Bevy 0.20.1's covering sets a fifth to four fifths of
//! the variants are such repeats (the keywords that set them change no module the stage
//! loads).
//!
//! Only programs that compiled and validated are kept: a failure's diagnostic names the
//! variant's keywords, so a failing variant is compiled again.

use std::collections::HashMap;
use std::sync::Mutex;

/// Most programs kept before the memo starts again (memory stays bounded: a Bevy program is
/// about 100 kB).
const KEPT_MAX: usize = 2048;

/// A compiled program and what it was compiled from.
#[derive(Debug)]
struct Entry {
    /// Each module the compile loaded other than the root, with its feature values.
    modules: Vec<(usize, String)>,
    /// The program (canonical text) and whether the profile takes it.
    text: String,
    taken: bool,
}

/// Where programs compiled from one root with the same constants and root feature values
/// are looked up: root module, profile (its `Debug` text), constants package, root's
/// feature values.
type Bucket = (usize, String, String, String);

/// The engine's compiled programs (see the module's documentation).
#[derive(Debug, Default)]
pub(super) struct Programs {
    buckets: Mutex<HashMap<Bucket, Vec<Entry>>>,
}

/// The variant side of a lookup: what identifies its compile.
pub(super) struct Probe<'a> {
    /// The root module.
    pub root: usize,
    /// The profile's `Debug` text.
    pub profile: String,
    /// The `constants` package's text.
    pub constants: &'a str,
    /// The feature values of a module as this variant sets them.
    pub features: &'a dyn Fn(usize) -> String,
}

impl Programs {
    /// The program and the profile's verdict of an earlier compile this variant repeats.
    pub(super) fn get(&self, probe: &Probe<'_>) -> Option<(String, bool)> {
        let bucket = self.bucket(probe);
        let buckets = self.buckets.lock().ok()?;
        let entries = buckets.get(&bucket)?;
        // Feature values of each module asked about, computed once for this variant.
        let mut values: HashMap<usize, String> = HashMap::new();
        entries
            .iter()
            .find(|entry| {
                entry
                    .modules
                    .iter()
                    .all(|(m, key)| values.entry(*m).or_insert_with(|| (probe.features)(*m)) == key)
            })
            .map(|entry| (entry.text.clone(), entry.taken))
    }

    /// Keeps a compile's program: `loaded` are the tree modules it loaded.
    pub(super) fn put(&self, probe: &Probe<'_>, loaded: &[usize], text: &str, taken: bool) {
        let bucket = self.bucket(probe);
        let mut modules: Vec<(usize, String)> = loaded
            .iter()
            .filter(|&&m| m != probe.root)
            .map(|&m| (m, (probe.features)(m)))
            .collect();
        modules.sort_unstable();
        modules.dedup();
        let Ok(mut buckets) = self.buckets.lock() else {
            return;
        };
        if buckets.values().map(Vec::len).sum::<usize>() >= KEPT_MAX {
            buckets.clear();
        }
        let entries = buckets.entry(bucket).or_default();
        if !entries.iter().any(|e| e.modules == modules) {
            entries.push(Entry {
                modules,
                text: text.to_string(),
                taken,
            });
        }
    }

    fn bucket(&self, probe: &Probe<'_>) -> Bucket {
        (
            probe.root,
            probe.profile.clone(),
            probe.constants.to_string(),
            (probe.features)(probe.root),
        )
    }
}
