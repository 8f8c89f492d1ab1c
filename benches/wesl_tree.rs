//! A WESL tree validated by this crate against the `wesl` crate alone compiling the same
//! variants and naga validating its output, measured in the same run (interleaved; medians of
//! `BENCH_ROUNDS`).
//!
//! `cargo bench --bench wesl_tree` runs on `tests/fixtures/wesl`; `WGSL_VARIANTS_TREE=DIR cargo
//! bench --bench wesl_tree` on any WESL tree, one package or several (the declaration file's
//! `[packages]`), e.g. Bevy 0.20.1's (assembled by `scripts/bevy.sh --bevy 0.20.1`):
//! `WGSL_VARIANTS_TREE=target/bevy-0.20.1 WGSL_VARIANTS_PASS=standard_material/Forward/fragment
//! cargo bench --bench wesl_tree`. `WGSL_VARIANTS_PASS=shader/pass` (comma-separated) keeps
//! only those passes. Each pass's 2-wise covering set is the work.
//!
//! - this crate: the tree loaded (`Library::from_dir`, inside the timing: each of the 8
//!   slices of a round is a run of its own, nothing kept from the slice before), then
//!   `validate_pass` (wesl's passes compile each variant from the loaded tree, each module
//!   parsed once, its declarations are put in a fixed order, naga parses and validates it
//!   once; a variant that compiles to a program compiled before takes its verdict), one
//!   thread;
//! - wesl alone: `wesl::compile` with a resolver that maps the declaration's package names to
//!   their folders and reads each module from disk on every compile (as `wesl`'s own
//!   `FileResolver` does), the same features, constants and visibility as the engine, then
//!   naga's parse and validation of the output (the pass's profile), one thread.
//!
//! Before timing, both sides' verdicts are compared: the number of variants wesl alone
//! compiles and validates must be this crate's number of valid variants.
//!
//! Prints the ratio (this crate / wesl alone; lower is faster) and writes it to
//! `target/bench-summary.json`.
//!
//! Measured 2026-11-27 on a shared 2-core machine, `WGSL_VARIANTS_TREE=target/bevy-0.20.1
//! WGSL_VARIANTS_PASS=standard_material/Forward/fragment BENCH_ROUNDS=3 cargo bench
//! --ignore-rust-version --bench wesl_tree` (627 variants): this crate 22.3 s, wesl alone
//! 43.7 s, ratio 0.51 (docs/guide/wesl-trees.md says where the time goes).

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use serde_json::json;
use test_support as common;
use wesl::error::ResolveError;
use wesl::syntax::{ModulePath, PathOrigin};
use wgsl_variants::declaration::DefValue;
use wgsl_variants::plan::{PlanOptions, variants_to_build};
use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Choice, Library, Pass, Variant};

/// What a WESL tree's declaration file says about composing it: `[packages]` (name →
/// folder, relative to the tree) and `[wesl] visibility`.
struct Declared {
    packages: Vec<(String, String)>,
    visibility: bool,
}

fn declared(root: &Path) -> Declared {
    let text = std::fs::read_to_string(root.join("wgsl-variants.toml")).unwrap_or_default();
    let table: toml::Table = text.parse().unwrap_or_default();
    let packages = table
        .get("packages")
        .and_then(|p| p.as_table())
        .map(|p| {
            p.iter()
                .filter_map(|(name, folder)| Some((name.clone(), folder.as_str()?.to_string())))
                .collect()
        })
        .unwrap_or_default();
    let visibility = table
        .get("wesl")
        .and_then(|w| w.get("visibility"))
        .and_then(|v| v.as_bool())
        .unwrap_or(true);
    Declared {
        packages,
        visibility,
    }
}

/// The module path of a tree file (`a/b` without extension), as the declaration names it:
/// `pkg::c` for a file `c` of the deepest package folder holding it, else `package::a::b`.
fn module_path(file: &str, packages: &[(String, String)]) -> ModulePath {
    let name = packages
        .iter()
        .filter_map(|(name, folder)| {
            let rest = file.strip_prefix(folder.as_str())?.strip_prefix('/')?;
            Some((folder.len(), format!("{name}::{}", rest.replace('/', "::"))))
        })
        .max_by_key(|(len, _)| *len)
        .map(|(_, n)| n)
        .unwrap_or_else(|| format!("package::{}", file.replace('/', "::")));
    name.parse().expect("module path")
}

/// `wesl` alone's view of the tree: each package a folder, every module read from disk on
/// every compile (as `wesl::resolver::FileResolver`), and the variant's `constants` package.
struct DirResolver {
    root: PathBuf,
    packages: Vec<(String, String)>,
    constants: String,
}

impl DirResolver {
    fn file(&self, path: &ModulePath) -> Option<PathBuf> {
        let mut file = match &path.origin {
            PathOrigin::Absolute => self.root.clone(),
            // A package imported from inside another comes as `outer/inner`.
            PathOrigin::Package(p) => {
                let name = p.rsplit('/').next().unwrap_or(p);
                let (_, folder) = self.packages.iter().find(|(n, _)| n == name)?;
                self.root.join(folder)
            }
            PathOrigin::Relative(_) => return None,
        };
        file.extend(&path.components);
        file.set_extension("wesl");
        Some(file)
    }
}

impl wesl::Resolver for DirResolver {
    fn resolve_source<'a>(&'a self, path: &ModulePath) -> Result<Cow<'a, str>, ResolveError> {
        if path.components.is_empty()
            && matches!(&path.origin, PathOrigin::Package(p) if p.rsplit('/').next() == Some("constants"))
        {
            return Ok(Cow::Borrowed(self.constants.as_str()));
        }
        let file = self.file(path).ok_or_else(|| {
            ResolveError::ModuleNotFound(path.clone(), "no package of this name".into())
        })?;
        std::fs::read_to_string(&file)
            .map(Cow::Owned)
            .map_err(|_| ResolveError::FileNotFound(file, "physical file".into()))
    }

    fn display_name(&self, path: &ModulePath) -> Option<String> {
        self.file(path).map(|f| f.display().to_string())
    }

    fn canonical_path(&self, path: &ModulePath) -> ModulePath {
        match &path.origin {
            PathOrigin::Package(p) if p.contains('/') => ModulePath {
                origin: PathOrigin::Package(p.rsplit('/').next().unwrap_or(p).to_string()),
                components: path.components.clone(),
            },
            _ => path.clone(),
        }
    }
}

/// wesl alone on `choices`: compiles each and validates the output; how many are valid.
fn alone(
    lib: &Library,
    pass: &Pass,
    (root, declared, entry): (&Path, &Declared, &ModulePath),
    choices: &[Choice],
) -> usize {
    let mut validator = lib.pass_profile(pass).validator();
    let mut valid = 0;
    for c in choices {
        let v = Variant {
            pass,
            choice: c.clone(),
        };
        // As the engine composes (src/library/wesl/mod.rs): every keyword's defs off unless set,
        // every def a constant, a Bool def a feature, a valued def a feature that is on.
        let defs = pass.defs(v.keywords());
        let mut options = wesl::CompileOptions {
            visibility: declared.visibility,
            ..wesl::CompileOptions::default()
        };
        for k in pass.keywords() {
            for (name, _) in pass.keyword_defs(k) {
                options.features.set(name, false);
            }
        }
        let mut constants = String::new();
        for (name, value) in &defs {
            options
                .features
                .set(*name, !matches!(value, DefValue::Bool(false)));
            constants.push_str(&format!("public const {name} = {value};\n"));
        }
        let resolver = DirResolver {
            root: root.to_path_buf(),
            packages: declared.packages.clone(),
            constants,
        };
        if let Ok(out) = wesl::compile(entry, &options, &resolver)
            && let Ok(module) = naga::front::wgsl::parse_str(&out.to_string())
            && validator.validate(&module).is_ok()
        {
            valid += 1;
        }
    }
    valid
}

fn main() {
    let root = std::env::var("WGSL_VARIANTS_TREE").unwrap_or_else(|_| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/wesl").to_string()
    });
    let only: Option<Vec<String>> = std::env::var("WGSL_VARIANTS_PASS")
        .ok()
        .map(|p| p.split(',').map(str::to_string).collect());
    let lib = Library::from_dir(&root).unwrap_or_else(|e| panic!("{root}: {e}"));
    assert_eq!(
        lib.dialect(),
        wgsl_variants::Dialect::Wesl,
        "{root}: not a WESL tree"
    );
    let declared = declared(Path::new(&root));
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let mut options = PlanOptions::default();
    options.cover = Some(2);
    let mut results = Vec::new();
    for pass in lib.passes() {
        let label = format!("{}/{}", pass.shader, pass.name);
        if only.as_ref().is_some_and(|o| !o.contains(&label)) {
            continue;
        }
        let choices = variants_to_build(&lib, pass, &options).expect("covering set");
        let entry = module_path(&lib.module_paths()[pass.module()], &declared.packages);
        let how = (Path::new(&root), &declared, &entry);
        // The same work on both sides: the same verdicts.
        let ours_valid = one.install(|| validate_pass(&lib, pass, &choices, &|_| {}).valid);
        let alone_valid = alone(&lib, pass, how, &choices);
        assert_eq!(
            ours_valid as usize, alone_valid,
            "{label}: this crate and wesl alone disagree on the number of valid variants"
        );
        // Each slice is a run of its own: the tree loaded anew, so nothing the engine keeps
        // per loaded tree (parsed modules, checked modules, compiled programs) outlives it.
        let pass_index = lib.passes().position(|p| std::ptr::eq(p, pass));
        let mut ours = |slice: &[Choice]| {
            let fresh = Library::from_dir(&root).unwrap_or_else(|e| panic!("{root}: {e}"));
            let pass = fresh
                .passes()
                .nth(pass_index.expect("the pass"))
                .expect("the pass");
            one.install(|| {
                validate_pass(&fresh, pass, slice, &|_| {});
            })
        };
        let mut alone = |slice: &[Choice]| {
            alone(&lib, pass, how, slice);
        };
        results.push(common::versus(
            &label,
            ("wesl", "wesl_alone"),
            &choices,
            &mut ours,
            &mut alone,
        ));
    }
    assert!(!results.is_empty(), "no pass matches WGSL_VARIANTS_PASS");
    common::write_summary(json!({ "wesl_tree": { "root": root, "passes": results } }));
}
