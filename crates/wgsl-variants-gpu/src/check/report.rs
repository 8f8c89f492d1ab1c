//! What the GPU check compared and what did not match, as text and as JSON.

use std::collections::BTreeMap;
use std::fmt;

use serde::Serialize;

/// How many mismatches a report keeps in full (all are counted).
pub const MAX_LISTED_MISMATCHES: usize = 20;

/// One value the GPU produced that the reference does not accept.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[non_exhaustive]
pub struct Mismatch {
    /// Shader (or `kernels`).
    pub shader: String,
    /// Pass (or kernel name).
    pub pass: String,
    /// The variant's keyword set, `{A, B}` (or the kernel case's inputs).
    pub keywords: String,
    /// The target (`RT0 Rgba8Unorm`, …) or kernel output.
    pub target: String,
    /// Pixel `[x, y]` (for kernels: `[case, component]`).
    pub pixel: [u32; 2],
    /// What the reference expects, as the shader would read it (the clear colour where the
    /// pixel is discarded). JSON writes non-finite values (+inf) as `null`.
    pub expected: Vec<f32>,
    /// What the GPU stored, decoded to floats.
    pub got: Vec<f32>,
    /// The raw stored values (unorm codes, f16 or f32 bits).
    pub got_raw: Vec<u32>,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}/{} {} {} pixel ({}, {}): expected {:?}, got {:?} (raw {:?})",
            self.shader,
            self.pass,
            self.keywords,
            self.target,
            self.pixel[0],
            self.pixel[1],
            self.expected,
            self.got,
            self.got_raw
        )
    }
}

/// Whether toggling one keyword changed any output.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[non_exhaustive]
pub struct KeywordCoverage {
    /// The keyword.
    pub keyword: String,
    /// Variant pairs (keyword on / its set's first option) compared.
    pub pairs: usize,
    /// Pairs whose outputs differ in at least one pixel.
    pub pairs_changed: usize,
}

/// The result of one pass.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[non_exhaustive]
pub struct PassReport {
    /// Shader name.
    pub shader: String,
    /// Pass name.
    pub pass: String,
    /// Variants compared (each with its own reference).
    pub variants_run: usize,
    /// Distinct composed WGSL texts rendered (identical texts are rendered once).
    pub distinct_shaders: usize,
    /// Draws submitted.
    pub draws: usize,
    /// Target texels compared: variants × targets × pixels (× draws for multi-draw passes).
    pub pixels_compared: usize,
    /// Of those, discarded pixels checked to keep the clear colour.
    pub discarded_compared: usize,
    /// Texels the reference does not accept.
    pub mismatches: usize,
    /// The first [`MAX_LISTED_MISMATCHES`] mismatches.
    pub first_mismatches: Vec<Mismatch>,
    /// Every mismatch counted per variant, by the keyword label the check gives it
    /// ([`Mismatch::keywords`]): where a fault shows, all of it, not only the listed ones.
    pub mismatches_by_variant: BTreeMap<String, usize>,
    /// Per keyword of the pass: whether toggling it changed an output.
    pub keywords: Vec<KeywordCoverage>,
    /// Keywords whose toggling changed nothing in any variant pair (a failure: a path the
    /// check does not see).
    pub untested_keywords: Vec<String>,
    /// Notes on what was compared.
    pub notes: Vec<String>,
    /// Seconds spent.
    pub seconds: f64,
}

impl PassReport {
    /// An empty report for `shader/pass`.
    pub fn new(shader: &str, pass: &str) -> PassReport {
        PassReport {
            shader: shader.to_owned(),
            pass: pass.to_owned(),
            variants_run: 0,
            distinct_shaders: 0,
            draws: 0,
            pixels_compared: 0,
            discarded_compared: 0,
            mismatches: 0,
            first_mismatches: Vec::new(),
            mismatches_by_variant: BTreeMap::new(),
            keywords: Vec::new(),
            untested_keywords: Vec::new(),
            notes: Vec::new(),
            seconds: 0.0,
        }
    }

    /// Judges keyword coverage from `keywords`: every keyword no pair of checked variants showed
    /// changing a pixel is listed in `untested_keywords` (which fails the report).
    pub fn judge_keywords(&mut self) {
        self.untested_keywords = self
            .keywords
            .iter()
            .filter(|k| k.pairs_changed == 0)
            .map(|k| k.keyword.clone())
            .collect();
    }

    /// Records one comparison; `mismatch` is built only when the value is not accepted.
    pub fn record(&mut self, ok: bool, mismatch: impl FnOnce() -> Mismatch) {
        self.pixels_compared += 1;
        if !ok {
            self.mismatches += 1;
            let m = mismatch();
            *self
                .mismatches_by_variant
                .entry(m.keywords.clone())
                .or_default() += 1;
            if self.first_mismatches.len() < MAX_LISTED_MISMATCHES {
                self.first_mismatches.push(m);
            }
        }
    }

    /// Whether everything matched and every keyword was seen to matter.
    pub fn passed(&self) -> bool {
        self.mismatches == 0 && self.untested_keywords.is_empty() && self.pixels_compared > 0
    }
}

/// The result of one compute kernel.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[non_exhaustive]
pub struct KernelReport {
    /// Kernel name (`shader/pass` of the kernel library).
    pub name: String,
    /// What it evaluates.
    pub description: String,
    /// Input cases run.
    pub cases: usize,
    /// Output values compared.
    pub values_compared: usize,
    /// Values the reference does not accept.
    pub mismatches: usize,
    /// The first [`MAX_LISTED_MISMATCHES`] mismatches.
    pub first_mismatches: Vec<Mismatch>,
}

impl KernelReport {
    /// An empty report.
    pub fn new(name: &str, description: &str) -> KernelReport {
        KernelReport {
            name: name.to_owned(),
            description: description.to_owned(),
            cases: 0,
            values_compared: 0,
            mismatches: 0,
            first_mismatches: Vec::new(),
        }
    }

    /// Records one compared value.
    pub fn record(&mut self, ok: bool, mismatch: impl FnOnce() -> Mismatch) {
        self.values_compared += 1;
        if !ok {
            self.mismatches += 1;
            if self.first_mismatches.len() < MAX_LISTED_MISMATCHES {
                self.first_mismatches.push(mismatch());
            }
        }
    }

    /// Whether every value matched.
    pub fn passed(&self) -> bool {
        self.mismatches == 0 && self.cases > 0
    }
}

/// Everything one run of the GPU check compared.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[non_exhaustive]
pub struct CheckReport {
    /// The adapter's name.
    pub adapter: String,
    /// The adapter's backend and driver.
    pub driver: String,
    /// What the check was made from (see [`wgsl_variants::merge::fingerprint`]).
    #[serde(skip_serializing_if = "String::is_empty")]
    pub fingerprint: String,
    /// The shard checked, if only one was (`K/N`).
    #[serde(
        skip_serializing_if = "Option::is_none",
        serialize_with = "wgsl_variants::merge::shard_text"
    )]
    pub shard: Option<wgsl_variants::variants::Shard>,
    /// Render passes checked.
    pub passes: Vec<PassReport>,
    /// Compute kernels checked.
    pub kernels: Vec<KernelReport>,
    /// Seconds the whole check took.
    pub seconds: f64,
}

impl CheckReport {
    /// Whether every pass and kernel passed.
    pub fn passed(&self) -> bool {
        self.passes.iter().all(PassReport::passed) && self.kernels.iter().all(KernelReport::passed)
    }

    /// Total mismatches over passes and kernels.
    pub fn mismatches(&self) -> usize {
        self.passes.iter().map(|p| p.mismatches).sum::<usize>()
            + self.kernels.iter().map(|k| k.mismatches).sum::<usize>()
    }

    /// Total target texels compared over all passes.
    pub fn pixels_compared(&self) -> usize {
        self.passes.iter().map(|p| p.pixels_compared).sum()
    }

    /// Total variants compared over all passes.
    pub fn variants_run(&self) -> usize {
        self.passes.iter().map(|p| p.variants_run).sum()
    }

    /// Total kernel cases.
    pub fn kernel_cases(&self) -> usize {
        self.kernels.iter().map(|k| k.cases).sum()
    }
}

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "adapter: {} ({})", self.adapter, self.driver)?;
        for p in &self.passes {
            writeln!(
                f,
                "{} {}/{}: {} variants ({} distinct shaders, {} draws), {} texels compared ({} discarded), {} mismatches ({:.1} s)",
                if p.passed() { "ok  " } else { "FAIL" },
                p.shader,
                p.pass,
                p.variants_run,
                p.distinct_shaders,
                p.draws,
                p.pixels_compared,
                p.discarded_compared,
                p.mismatches,
                p.seconds
            )?;
            for note in &p.notes {
                writeln!(f, "       {note}")?;
            }
            for m in &p.first_mismatches {
                writeln!(f, "       mismatch: {m}")?;
            }
            if p.mismatches > p.first_mismatches.len() {
                writeln!(
                    f,
                    "       ... and {} more mismatches",
                    p.mismatches - p.first_mismatches.len()
                )?;
            }
            for k in &p.untested_keywords {
                writeln!(
                    f,
                    "       untested keyword: toggling {k} changed no output in any variant pair"
                )?;
            }
        }
        for k in &self.kernels {
            writeln!(
                f,
                "{} kernel {}: {} cases, {} values compared, {} mismatches ({})",
                if k.passed() { "ok  " } else { "FAIL" },
                k.name,
                k.cases,
                k.values_compared,
                k.mismatches,
                k.description
            )?;
            for m in &k.first_mismatches {
                writeln!(f, "       mismatch: {m}")?;
            }
        }
        write!(
            f,
            "{}: {} variants, {} texels, {} kernel cases, {} mismatches in {:.1} s",
            if self.passed() { "PASSED" } else { "FAILED" },
            self.variants_run(),
            self.pixels_compared(),
            self.kernel_cases(),
            self.mismatches(),
            self.seconds
        )
    }
}
