//! The `build.rs` API: build and validate a library's build set when the consuming crate
//! compiles, and bake it in — WGSL text and/or SPIR-V words, with a strict lookup from keyword
//! set to variant.
//!
//! ```no_run
//! # #[cfg(feature = "spv-out")] {
//! // build.rs of the consuming crate ([build-dependencies] wgsl-variants)
//! use wgsl_variants::bake::{Bake, BakeTarget};
//!
//! Bake::new("shaders")
//!     .materials("shaders/materials.toml")
//!     .target(BakeTarget::Wgsl)
//!     .target(BakeTarget::SpirV)
//!     .run(); // writes $OUT_DIR/wgsl_variants.rs, or fails the build with diagnostics
//! # }
//! ```
//!
//! ```ignore
//! // src/main.rs
//! mod shaders {
//!     include!(concat!(env!("OUT_DIR"), "/wgsl_variants.rs"));
//! }
//! let v = shaders::variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"])?;
//! let wgsl: &'static str = v.wgsl.unwrap();
//! ```
//!
//! The generated file needs no runtime dependency. It defines `Variant` (shader, pass,
//! keywords, entry points with stages, `wgsl: Option<&str>`, `spirv: Option<&[u32]>`, and the
//! BLAKE3 hash of the canonical WGSL), `Pass`, `Stage`, `EntryPoint`, `LookupError`, and
//! `variant(shader, pass, keywords)` (strict: keywords in any order, exactly the variant asked
//! for or an error saying why — unknown shader, pass or keyword, or a combination that is not in
//! the build set), `variants()` and `passes()`. The texts and words live next to it in
//! `OUT_DIR/wgsl_variants/` (one file per distinct output, named by content hash) and are
//! pulled in with `include_str!`/`include_bytes!`. SPIR-V files are kept 4-aligned and read as
//! words in place on little-endian targets: one `unsafe` block in the generated file (it allows
//! the `unsafe_code` lint for itself; a crate that forbids it includes the file from a crate of
//! its own), because assembling the words in a `const fn` cost the compiler minutes on a large
//! build set. Big-endian targets assemble the words at compile time.
//!
//! `write_to` prints `cargo:rerun-if-changed` for the library root, every module file and the
//! materials file, so edits to any shader rebuild the crate.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

use crate::library::{Library, LoadError, Variant};
use crate::materials::{self, MaterialsError};
use crate::plan::{PlanError, PlanOptions, plan};
use crate::source::RawFile;

use crate::emit::backends::{Contents, Options, Target, TranslateError, translate_all};
use crate::emit::write_if_changed;
use crate::reflect::Stage;

/// What to bake.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BakeTarget {
    /// The canonical WGSL: validated, compacted, written by naga (`Variant::wgsl`).
    Wgsl,
    /// SPIR-V 1.0 words (`Variant::spirv`; feature `spv-out`).
    #[cfg(feature = "spv-out")]
    SpirV,
}

#[derive(Clone, Debug)]
enum Source {
    Dir(PathBuf),
    /// Files given by the caller (a tree embedded into a crate), and how to name them.
    Files(Vec<RawFile>, String),
}

/// A bake of a library's build set; see the [module docs](self).
#[derive(Clone, Debug)]
pub struct Bake {
    source: Source,
    materials: Option<PathBuf>,
    targets: Vec<BakeTarget>,
    file_name: String,
    budget: u64,
    cover: Option<usize>,
    cover_above: Option<u64>,
    options: Options,
    bindings: Option<crate::bindings::Options>,
}

/// What [`Bake::write_to`] wrote.
#[derive(Clone, Debug)]
pub struct Baked {
    /// The generated Rust file.
    pub file: PathBuf,
    /// Variants baked.
    pub variants: usize,
    /// Distinct outputs written next to it.
    pub outputs: usize,
    /// Every path printed as `cargo:rerun-if-changed`.
    pub rerun_if_changed: Vec<PathBuf>,
}

/// A bake failed. Its `Display` is the report a build script prints: every diagnostic
/// rendered with its file, line and keyword set.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BakeError {
    /// The library could not be loaded.
    #[error("{}error: the shader library could not be loaded ({} problem(s))", .0.render(false), .0.problems.len())]
    Load(LoadError),
    /// The materials file could not be read.
    #[error("error: {0}")]
    Materials(#[from] MaterialsError),
    /// The build set could not be planned (e.g. a pass over the budget).
    #[error("error: {0}")]
    Plan(Box<PlanError>),
    /// Variants failed to build; nothing was baked.
    #[error("{rendered}error: {} of {variants} variants failed to build; nothing was baked", .failures.len())]
    Failed {
        /// Every failure, in build order.
        failures: Vec<TranslateError>,
        /// How many variants were built.
        variants: usize,
        /// The failures rendered against the library's sources.
        rendered: String,
    },
    /// The typed Rust of a pass could not be generated ([`Bake::bindings`]).
    #[error("error: {0}")]
    Bindings(Box<crate::bindings::BindingsError>),
    /// An output could not be written.
    #[error("error: cannot write `{}`: {source}", .path.display())]
    Io {
        /// The path.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
}

impl Bake {
    /// Bakes the library in the folder `root` (relative paths are relative to the build
    /// script's working directory, the consuming crate's root).
    pub fn new(root: impl Into<PathBuf>) -> Bake {
        Bake::with_source(Source::Dir(root.into()))
    }

    /// Bakes the library made of `files` (e.g. a tree embedded into a crate, as
    /// `wgsl_variants_shaders::bake` does); `origin` names it in the generated file.
    pub fn from_files(files: Vec<RawFile>, origin: impl Into<String>) -> Bake {
        Bake::with_source(Source::Files(files, origin.into()))
    }

    fn with_source(source: Source) -> Bake {
        Bake {
            source,
            materials: None,
            targets: Vec::new(),
            file_name: "wgsl_variants.rs".into(),
            budget: 1_000_000,
            cover: None,
            cover_above: None,
            options: Options::default(),
            bindings: None,
        }
    }

    /// Restricts `shader_feature` combinations to those the materials (JSON or TOML) use;
    /// as in a Unity build, a shader no material uses is not baked.
    pub fn materials(mut self, path: impl Into<PathBuf>) -> Bake {
        self.materials = Some(path.into());
        self
    }

    /// Adds a target (WGSL when none is added).
    pub fn target(mut self, target: BakeTarget) -> Bake {
        if !self.targets.contains(&target) {
            self.targets.push(target);
        }
        self
    }

    /// Name of the generated file in the output folder (default `wgsl_variants.rs`).
    pub fn file_name(mut self, name: impl Into<String>) -> Bake {
        self.file_name = name.into();
        self
    }

    /// Most variants per pass (default 1,000,000); past it the bake fails.
    pub fn max_variants(mut self, budget: u64) -> Bake {
        self.budget = budget;
        self
    }

    /// Bakes only a t-wise covering set of each pass (t from 1 to 4;
    /// [`Space::covering`](crate::Space::covering)) instead of its whole build set: every
    /// combination of options of every t keyword sets is validated and translated, in a few
    /// variants. For test builds of huge spaces: the other variants are not in the generated
    /// file.
    pub fn cover(mut self, t: usize) -> Bake {
        self.cover = Some(t);
        self
    }

    /// With [`cover`](Bake::cover): covers only passes whose build set holds more than `n`
    /// variants and bakes the others whole.
    ///
    /// ```
    /// let bake = wgsl_variants::bake::Bake::new("wgsl").cover(2).cover_above(4096);
    /// # let _ = bake;
    /// ```
    pub fn cover_above(mut self, n: u64) -> Bake {
        self.cover_above = Some(n);
        self
    }

    /// Keeps WGSL's coordinate space in SPIR-V (see
    /// [`Options::keep_coordinate_space`](crate::emit::backends::Options)); set it when the SPIR-V
    /// is given back to wgpu.
    pub fn keep_coordinate_space(mut self, keep: bool) -> Bake {
        self.options.keep_coordinate_space = keep;
        self
    }

    /// Also writes the typed Rust of every baked pass ([`bindings`](crate::bindings)) into
    /// `$OUT_DIR/wgsl_variants_bindings/`, and `$OUT_DIR/wgsl_variants_bindings.rs`, which holds
    /// `pub mod <shader>_<pass> { … }` (lower case) for each: include it in a module of its
    /// own. The consuming crate then depends on `bytemuck` with the `derive` and
    /// `min_const_generics` features. Each module knows this bake: its `Key::new` refuses the
    /// combinations the bake leaves out (materials, cover, budget: `KeyError::NotBaked`), and
    /// `key.baked(shaders::variants())` is the key's baked variant, found by `Key::index`
    /// without keyword strings.
    pub fn bindings(mut self, on: bool) -> Bake {
        self.bindings = on.then(crate::bindings::Options::default);
        self
    }

    /// [`Bake::bindings`] with the generator's [`Options`](crate::bindings::Options): with
    /// `wgpu`, each module also converts its interfaces to wgpu's types (the consuming crate
    /// then depends on `wgpu` 30 as well).
    pub fn bindings_with(mut self, options: crate::bindings::Options) -> Bake {
        self.bindings = Some(options);
        self
    }

    /// For `build.rs`: [`Bake::write_to`] `$OUT_DIR`; on failure prints the diagnostics to
    /// stderr and exits with status 1, so the build fails showing them.
    pub fn run(self) -> Baked {
        let out_dir = match std::env::var_os("OUT_DIR") {
            Some(dir) => PathBuf::from(dir),
            None => {
                eprintln!("error: OUT_DIR is not set: Bake::run is meant for build scripts");
                std::process::exit(1);
            }
        };
        match self.write_to(&out_dir) {
            Ok(baked) => baked,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        }
    }

    /// Loads, builds and validates the build set, writes the generated Rust file and the
    /// outputs into `out_dir`, and prints `cargo:rerun-if-changed` lines. Files are rewritten
    /// only when their contents change; stale outputs are removed.
    pub fn write_to(self, out_dir: impl AsRef<Path>) -> Result<Baked, BakeError> {
        let out_dir = out_dir.as_ref();
        let mut rerun = Vec::new();
        if let Source::Dir(root) = &self.source {
            rerun.push(root.clone());
        }
        if let Some(m) = &self.materials {
            rerun.push(m.clone());
        }
        // Printed before loading, so that a failing library is watched too.
        for path in &rerun {
            println!("cargo:rerun-if-changed={}", path.display());
        }
        let lib = match &self.source {
            Source::Dir(root) => Library::from_dir(root),
            Source::Files(files, _) => Library::from_raw(files.clone(), &Default::default()),
        }
        .map_err(BakeError::Load)?;
        if let Source::Dir(root) = &self.source {
            for module in lib.module_paths() {
                let path = root.join(format!("{module}.wgsl"));
                println!("cargo:rerun-if-changed={}", path.display());
                rerun.push(path);
            }
        }
        let materials = match &self.materials {
            Some(path) => Some(materials::load(path)?),
            None => None,
        };
        let options = PlanOptions {
            materials,
            budget: self.budget,
            cover: self.cover,
            cover_above: self.cover_above,
            ..PlanOptions::default()
        };
        let selection = plan(&lib, &options).map_err(|e| BakeError::Plan(Box::new(e)))?;
        let targets = if self.targets.is_empty() {
            vec![BakeTarget::Wgsl]
        } else {
            self.targets.clone()
        };

        // Build, validate and translate every variant in parallel.
        let jobs: Vec<Variant<'_>> = selection
            .iter()
            .flat_map(|(pass, choices)| {
                choices.iter().map(|choice| Variant {
                    pass,
                    choice: choice.clone(),
                })
            })
            .collect();
        let results: Vec<Result<BakedVariant, TranslateError>> = jobs
            .par_iter()
            .map(|variant| bake_variant(&lib, variant, &targets, &self.options))
            .collect();
        let (baked, failures): (Vec<_>, Vec<_>) = results.into_iter().partition(Result::is_ok);
        if !failures.is_empty() {
            let failures: Vec<TranslateError> =
                failures.into_iter().filter_map(Result::err).collect();
            let rendered = failures
                .iter()
                .map(|e| match e {
                    TranslateError::Invalid(v) => v.diagnostic().render(lib.files(), false),
                    other => format!("error: {other}\n"),
                })
                .collect();
            return Err(BakeError::Failed {
                failures,
                variants: jobs.len(),
                rendered,
            });
        }
        let baked: Vec<BakedVariant> = baked.into_iter().filter_map(Result::ok).collect();
        let origin = match &self.source {
            Source::Dir(root) => root.display().to_string(),
            Source::Files(_, origin) => origin.clone(),
        };
        let outputs = generate(out_dir, &self.file_name, &origin, &selection, &jobs, &baked)?;
        if let Some(options) = &self.bindings {
            write_bindings(&lib, out_dir, &selection, self.budget, options)?;
        }
        Ok(Baked {
            file: out_dir.join(&self.file_name),
            variants: jobs.len(),
            outputs,
            rerun_if_changed: rerun,
        })
    }
}

/// Writes the typed module of each pass of `selection` into `wgsl_variants_bindings/`, and
/// `wgsl_variants_bindings.rs`, which includes them, one module per pass.
fn write_bindings(
    lib: &Library,
    out_dir: &Path,
    selection: &crate::plan::Plan<'_>,
    budget: u64,
    options: &crate::bindings::Options,
) -> Result<(), BakeError> {
    let dir = out_dir.join("wgsl_variants_bindings");
    std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
    let mut index = format!(
        "// @generated by wgsl-variants {} (wgsl_variants::bake): the typed Rust of each baked\n// pass. Do not edit.\n",
        env!("CARGO_PKG_VERSION")
    );
    let variants: usize = selection.iter().map(|(_, choices)| choices.len()).sum();
    let mut start = 0;
    for (pass, choices) in selection {
        // `Key::index`: the options in set order, the last set fastest. The bindings generator
        // refuses passes with more combinations than it can table, before this is read.
        let combinations = pass
            .sets
            .iter()
            .try_fold(1usize, |n, s| n.checked_mul(s.len()))
            .filter(|&n| n <= crate::bindings::MAX_COMBINATIONS as usize);
        let mut slots = vec![u32::MAX; combinations.unwrap_or(0)];
        for (n, choice) in choices.iter().enumerate() {
            let at = crate::bindings::combination_index(pass, choice);
            if let Some(slot) = slots.get_mut(at) {
                *slot = (start + n) as u32;
            }
        }
        start += choices.len();
        let table = crate::bindings::BakedTable {
            index: slots,
            variants,
        };
        let generated = crate::bindings::generate_baked(lib, pass, budget, options, Some(&table))
            .map_err(|e| BakeError::Bindings(Box::new(e)))?;
        let name: String = format!("{}_{}", pass.shader, pass.name)
            .to_lowercase()
            .chars()
            .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
            .collect();
        let path = dir.join(format!("{name}.rs"));
        write_if_changed(&path, generated.code.as_bytes()).map_err(|e| io(&path, e))?;
        let _ = writeln!(
            index,
            "\n/// `{}/{}`.\n#[allow(dead_code)]\npub mod {name} {{\n    include!({});\n}}",
            pass.shader,
            pass.name,
            lit(&path.display().to_string())
        );
    }
    let path = out_dir.join("wgsl_variants_bindings.rs");
    write_if_changed(&path, index.as_bytes()).map_err(|e| io(&path, e))
}

struct BakedVariant {
    entry_points: Vec<(String, Stage)>,
    wgsl: Option<String>,
    spirv: Option<Vec<u8>>,
    hash: String,
}

fn bake_variant(
    lib: &Library,
    variant: &Variant<'_>,
    targets: &[BakeTarget],
    options: &Options,
) -> Result<BakedVariant, TranslateError> {
    // WGSL always: its hash keys the variant. Each of these back ends writes one output.
    #[cfg_attr(not(feature = "spv-out"), allow(unused_mut))]
    let mut wanted = vec![Target::Wgsl];
    #[cfg(feature = "spv-out")]
    if targets.contains(&BakeTarget::SpirV) {
        wanted.push(Target::SpirV);
    }
    let all = translate_all(lib, variant, &wanted, options)?;
    let mut contents = all.outputs.into_iter().map(|(_, o)| o.contents);
    let wgsl = match contents.next() {
        Some(Contents::Text(text)) => text,
        _ => unreachable!("the WGSL back end writes one text"),
    };
    let spirv = contents.next().map(|c| c.to_bytes());
    Ok(BakedVariant {
        entry_points: all
            .entry_points
            .into_iter()
            .map(|e| (e.name, e.stage))
            .collect(),
        hash: blake3::hash(wgsl.as_bytes()).to_hex().to_string(),
        wgsl: targets.contains(&BakeTarget::Wgsl).then_some(wgsl),
        spirv,
    })
}

const PRELUDE: &str = include_str!("prelude.rs");

fn io(path: &Path, e: std::io::Error) -> BakeError {
    BakeError::Io {
        path: path.to_path_buf(),
        source: e,
    }
}

fn lit(text: &str) -> String {
    format!("{text:?}")
}

fn str_list<'a>(items: impl IntoIterator<Item = &'a str>) -> String {
    let items: Vec<String> = items.into_iter().map(lit).collect();
    format!("&[{}]", items.join(", "))
}

/// Writes the outputs and the Rust file; returns the number of distinct outputs.
fn generate(
    out_dir: &Path,
    file_name: &str,
    origin: &str,
    selection: &crate::plan::Plan<'_>,
    jobs: &[Variant<'_>],
    baked: &[BakedVariant],
) -> Result<usize, BakeError> {
    let blob_dir = out_dir.join("wgsl_variants");
    std::fs::create_dir_all(&blob_dir).map_err(|e| io(&blob_dir, e))?;
    // Distinct outputs by content hash, in first-use order: name -> (static name, item).
    let mut blobs: BTreeMap<String, String> = BTreeMap::new();
    let mut items = String::new();
    let mut blob_for = |bytes: &[u8], ext: &str, items: &mut String| -> Result<String, BakeError> {
        let hash = blake3::hash(bytes).to_hex()[..32].to_string();
        let name = format!("{hash}.{ext}");
        if let Some(ident) = blobs.get(&name) {
            return Ok(ident.clone());
        }
        let path = blob_dir.join(&name);
        write_if_changed(&path, bytes).map_err(|e| io(&path, e))?;
        let path_lit = lit(&path.display().to_string());
        let ident = format!("{}_{}", ext.to_uppercase(), blobs.len());
        if ext == "spv" {
            let words = bytes.len() / 4;
            let _ = writeln!(
                items,
                "#[allow(dead_code)]\nstatic {ident}: &[u32] = spirv_words!({words}, {path_lit});"
            );
        } else {
            let _ = writeln!(
                items,
                "#[allow(dead_code)]\nstatic {ident}: &str = include_str!({path_lit});"
            );
        }
        blobs.insert(name, ident.clone());
        Ok(ident)
    };

    let mut variants = String::new();
    for (variant, b) in jobs.iter().zip(baked) {
        let keywords = variant.keywords();
        let mut sorted = keywords.clone();
        sorted.sort_unstable();
        let wgsl = match &b.wgsl {
            Some(text) => format!("Some({})", blob_for(text.as_bytes(), "wgsl", &mut items)?),
            None => "None".into(),
        };
        let spirv = match &b.spirv {
            Some(bytes) => format!("Some({})", blob_for(bytes, "spv", &mut items)?),
            None => "None".into(),
        };
        let eps: Vec<String> = b
            .entry_points
            .iter()
            .map(|(name, stage)| {
                let stage = match stage {
                    Stage::Vertex => "Vertex",
                    Stage::Fragment => "Fragment",
                    Stage::Compute => "Compute",
                    _ => "Other",
                };
                format!(
                    "EntryPoint {{ name: {}, stage: Stage::{stage} }}",
                    lit(name)
                )
            })
            .collect();
        let _ = writeln!(
            variants,
            "    Variant {{\n        shader: {},\n        pass: {},\n        keywords: {},\n        entry_points: &[{}],\n        wgsl: {wgsl},\n        spirv: {spirv},\n        hash: {},\n        sorted_keywords: {},\n    }},",
            lit(&variant.pass.shader),
            lit(&variant.pass.name),
            str_list(keywords.iter().copied()),
            eps.join(", "),
            lit(&b.hash),
            str_list(sorted.iter().copied()),
        );
    }

    let mut passes = String::new();
    let mut start = 0;
    for (pass, choices) in selection {
        let range = start..start + choices.len();
        start = range.end;
        let mut declared: Vec<&str> = pass
            .sets
            .iter()
            .flat_map(|s| s.options.iter().flatten().map(String::as_str))
            .collect();
        declared.sort_unstable();
        declared.dedup();
        let mut index: Vec<usize> = range.collect();
        let key = |i: &usize| {
            let mut k = jobs[*i].keywords();
            k.sort_unstable();
            k
        };
        index.sort_by_key(key);
        let index: Vec<String> = index.iter().map(usize::to_string).collect();
        let _ = writeln!(
            passes,
            "    Pass {{\n        shader: {},\n        pass: {},\n        keywords: {},\n        index: &[{}],\n    }},",
            lit(&pass.shader),
            lit(&pass.name),
            str_list(declared),
            index.join(", ")
        );
    }

    // Remove outputs of earlier bakes that are no longer referenced.
    if let Ok(entries) = std::fs::read_dir(&blob_dir) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if !blobs.contains_key(&name) && (name.ends_with(".wgsl") || name.ends_with(".spv")) {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }

    let code = format!(
        "// @generated by wgsl-variants {} (wgsl_variants::bake) from {}:\n// {} variants of {} passes. Do not edit. Include it in a module of its own:\n//     mod shaders {{ include!(concat!(env!(\"OUT_DIR\"), \"/{file_name}\")); }}\n\n{PRELUDE}\n{items}\n#[allow(dead_code)]\nstatic VARIANTS: &[Variant] = &[\n{variants}];\n\n#[allow(dead_code)]\nstatic PASSES: &[Pass] = &[\n{passes}];\n",
        env!("CARGO_PKG_VERSION"),
        origin.replace('\n', " "),
        jobs.len(),
        selection.len(),
    );
    let path = out_dir.join(file_name);
    write_if_changed(&path, code.as_bytes()).map_err(|e| io(&path, e))?;
    Ok(blobs.len())
}
