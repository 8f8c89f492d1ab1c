//! A loaded library: its modules, shaders and passes, and composing variants.

mod declared;
mod engine;
mod error;
mod load;
#[cfg(feature = "naga-oil")]
mod naga_oil;
#[cfg(feature = "wesl")]
mod wesl;

use std::path::Path;

use crate::diagnostic::SourceFiles;
use crate::diagnostic::suggest;
use crate::error::VariantError;
use crate::lookup::LookupError;
use crate::materials::{self, Material, MaterialsError};
use crate::preprocess::Composed;
use crate::preprocess::compose::ModuleGraph;
use crate::preprocess::tree::ParsedModule;
use crate::shader::{Pass, Shader};
use crate::source::{self, Origin, RawFile};
use crate::variants::{Choice, Space};

pub use error::{LinkError, LoadError, LoadProblem};
pub use load::LoadOptions;

/// A library of WGSL modules and the shaders built from them.
///
/// ```
/// use wgsl_variants::Library;
///
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let pass = lib.pass("standard", "Deferred").unwrap();
/// assert_eq!(wgsl_variants::variants::Space::full(pass).count(), 110_592u32.into());
/// let variant = lib.variant("standard", "Deferred", &["_NORMAL_MAP", "UNITY_HDR_ON"]).unwrap();
/// let wgsl = lib.wgsl(&variant);
/// assert!(wgsl.contains("normal_map"));
/// ```
pub struct Library {
    files: SourceFiles,
    modules: Vec<ParsedModule>,
    paths: Vec<String>,
    resolved: Vec<Vec<usize>>,
    shaders: Vec<Shader>,
    origin: Origin,
    dialect: crate::preprocess::Dialect,
    warnings: Vec<crate::diagnostic::Diagnostic>,
    /// The devices its variants are validated for (never empty): the declaration file's,
    /// or those set by [`Library::set_profiles`].
    profiles: Vec<crate::validator::Profile>,
    /// `profiles` was set by [`Library::set_profiles`]: it overrides every pass's own.
    profiles_set: bool,
    /// What composes its variants (chosen by the dialect when it loaded).
    engine: Box<dyn engine::Engine>,
}

impl std::fmt::Debug for Library {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Library")
            .field("origin", &self.origin)
            .field("modules", &self.paths)
            .field(
                "shaders",
                &self.shaders.iter().map(|s| &s.name).collect::<Vec<_>>(),
            )
            .finish()
    }
}

/// One variant: a pass and the option chosen in each of its keyword sets.
#[derive(Clone, Debug)]
pub struct Variant<'l> {
    /// The pass.
    pub pass: &'l Pass,
    /// The keyword set, one option per set.
    pub choice: Choice,
}

impl Variant<'_> {
    /// The keywords that are on.
    pub fn keywords(&self) -> Vec<&str> {
        self.choice.keywords(self.pass)
    }

    /// `shader/pass {KEYWORDS}`, the way diagnostics name a variant.
    pub fn label(&self) -> String {
        format!(
            "{}/{} {}",
            self.pass.shader,
            self.pass.name,
            self.choice.label(self.pass)
        )
    }
}

/// In-memory `(path, text)` pairs as files, sorted by path (the order a folder loads in).
fn raw_files<P: Into<String>, T: Into<String>>(
    sources: impl IntoIterator<Item = (P, T)>,
) -> Vec<RawFile> {
    let mut raw: Vec<RawFile> = sources
        .into_iter()
        .map(|(p, t)| RawFile {
            path: p.into(),
            bytes: t.into().into_bytes(),
        })
        .collect();
    raw.sort_by(|a, b| a.path.cmp(&b.path));
    raw
}

/// A variant's failure that has no place in the sources.
pub(crate) fn unlocated(
    variant: &Variant<'_>,
    stage: crate::error::Stage,
    message: String,
) -> VariantError {
    VariantError {
        variant: variant.label(),
        stage,
        message,
        labels: Vec::new(),
        notes: Vec::new(),
        source: None,
    }
}

/// The declaration file's bytes, its size checked before it is read.
fn read_declaration(path: &Path, limit: usize) -> Result<Vec<u8>, source::DirError> {
    use std::io::Read;
    let io = |e| source::DirError::Io {
        path: path.to_path_buf(),
        source: e,
    };
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(limit as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() > limit {
        return Err(source::DirError::TooLarge {
            root: path.parent().unwrap_or(path).to_path_buf(),
            path: crate::declaration::FILE_NAME.to_string(),
            bytes: bytes.len(),
            limit,
        });
    }
    Ok(bytes)
}

/// The failure of a variant whose composer (naga_oil, wesl) panicked: the variant fails, the
/// tool goes on.
#[cfg(any(feature = "naga-oil", feature = "wesl"))]
fn composer_panicked(
    variant: &Variant<'_>,
    composer: &str,
    payload: Box<dyn std::any::Any + Send>,
) -> VariantError {
    let what = payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_default();
    unlocated(
        variant,
        crate::error::Stage::Compose,
        format!(
            "{composer} panicked composing this variant ({what}); a bug to report to {composer}"
        ),
    )
}

impl Library {
    /// Loads every `.wgsl` file under `root`.
    pub fn from_dir(root: impl AsRef<Path>) -> Result<Library, LoadError> {
        Library::from_dir_with(root, &LoadOptions::default())
    }

    /// Loads every `.wgsl` file under `root` with explicit limits. A tree with a
    /// [declaration file](crate::declaration) (`wgsl-variants.toml`) at its root is read in
    /// the file's dialect (naga_oil's); any other tree in this crate's own.
    pub fn from_dir_with(
        root: impl AsRef<Path>,
        options: &LoadOptions,
    ) -> Result<Library, LoadError> {
        let root = root.as_ref();
        let limits = source::DirLimits {
            max_files: options.max_files,
            max_total_bytes: options.max_total_bytes,
        };
        let tree = source::read_dir_tree(root, limits).map_err(|e| LoadError {
            files: SourceFiles::new(),
            problems: vec![e.into()],
        })?;
        let skipped: Vec<crate::diagnostic::Diagnostic> = tree
            .skipped
            .iter()
            .map(|(path, why)| {
                crate::diagnostic::Diagnostic::new(format!("`{path}` is {why}"))
                    .warning()
                    .note("only regular files and folders are read from a tree")
            })
            .collect();
        let declaration = root.join(crate::declaration::FILE_NAME);
        let mut lib = if declaration.is_file() {
            let bytes =
                read_declaration(&declaration, options.max_total_bytes).map_err(|e| LoadError {
                    files: SourceFiles::new(),
                    problems: vec![e.into()],
                })?;
            let declaration = RawFile {
                path: crate::declaration::FILE_NAME.to_string(),
                bytes,
            };
            // Included files are read as the declaration is: whole, within the byte limit.
            let read_include = |path: &str| {
                read_declaration(&root.join(path), options.max_total_bytes)
                    .map_err(|e| e.to_string())
            };
            Library::load_declared(
                tree.files,
                declaration,
                &read_include,
                Origin::Dir(root.to_path_buf()),
                options,
            )?
        } else {
            Library::load(
                tree.files,
                &tree.escaping,
                Origin::Dir(root.to_path_buf()),
                options,
            )?
        };
        lib.warnings.splice(0..0, skipped);
        Ok(lib)
    }

    /// Builds a library from in-memory modules and a [declaration file](crate::declaration)'s
    /// text: a naga_oil tree.
    ///
    /// ```
    /// let lib = wgsl_variants::Library::from_declared_sources(
    ///     "[[shader]]\nname = \"main\"\nentry = \"main.wgsl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"RED\"]]\n",
    ///     [
    ///         ("color.wgsl", "#define_import_path my::color\nfn tint() -> f32 {\n#ifdef RED\n    return 1.0;\n#else\n    return 0.5;\n#endif\n}\n"),
    ///         ("main.wgsl", "#import my::color::tint\n@fragment fn fs() -> @location(0) vec4f { return vec4f(tint()); }\n"),
    ///     ],
    /// ).unwrap();
    /// let v = lib.variant("main", "P", &["RED"]).unwrap();
    /// assert!(lib.naga_module(&v).is_ok());
    /// assert!(lib.wgsl(&v).contains("return 1f;"));
    /// ```
    pub fn from_declared_sources<P: Into<String>, T: Into<String>>(
        declaration: &str,
        sources: impl IntoIterator<Item = (P, T)>,
    ) -> Result<Library, LoadError> {
        // `.toml` sources are the files the declaration may include, the rest its modules.
        let (includes, raw): (Vec<RawFile>, Vec<RawFile>) = raw_files(sources)
            .into_iter()
            .partition(|f| f.path.ends_with(".toml"));
        let declaration = RawFile {
            path: crate::declaration::FILE_NAME.to_string(),
            bytes: declaration.as_bytes().to_vec(),
        };
        let read_include = |path: &str| {
            includes
                .iter()
                .find(|f| f.path == path)
                .map(|f| f.bytes.clone())
                .ok_or_else(|| "no such file among the sources".to_string())
        };
        Library::load_declared(
            raw,
            declaration,
            &read_include,
            Origin::Memory,
            &LoadOptions::default(),
        )
    }

    fn load_declared(
        raw: Vec<RawFile>,
        declaration: RawFile,
        read_include: &dyn Fn(&str) -> Result<Vec<u8>, String>,
        origin: Origin,
        options: &LoadOptions,
    ) -> Result<Library, LoadError> {
        let l = load::load_declared(raw, declaration, read_include, options)?;
        Ok(Library::from_loaded(l, origin))
    }

    /// The library of a loaded tree (with the engine that composes it when it is a naga_oil
    /// or WESL tree).
    fn from_loaded(l: load::Loaded, origin: Origin) -> Library {
        let dialect = l.dialect;
        let engine: Box<dyn engine::Engine> = match dialect {
            crate::preprocess::Dialect::WgslVariants => Box::new(engine::Preprocessor),
            #[cfg(feature = "naga-oil")]
            crate::preprocess::Dialect::NagaOil => Box::new(naga_oil::NagaOilEngine::new(
                &l.modules,
                &l.resolved,
                l.shaders
                    .iter()
                    .flat_map(|s| s.passes.iter().map(|p| p.module)),
            )),
            #[cfg(feature = "wesl")]
            crate::preprocess::Dialect::Wesl => Box::new(wesl::WeslEngine::new(&l.modules, l.wesl)),
            #[allow(unreachable_patterns)]
            other => Box::new(engine::Unavailable(other)),
        };
        Library {
            files: l.files,
            modules: l.modules,
            paths: l.paths,
            resolved: l.resolved,
            shaders: l.shaders,
            origin,
            dialect,
            warnings: l.warnings,
            profiles: if l.profiles.is_empty() {
                vec![crate::validator::Profile::default()]
            } else {
                l.profiles
            },
            profiles_set: false,
            engine,
        }
    }

    /// Builds a library from in-memory `(path, text)` pairs; paths are library-relative with
    /// `/` separators and end in `.wgsl`.
    ///
    /// ```
    /// let lib = wgsl_variants::Library::from_sources([
    ///     ("lib/color.wgsl", "fn tint() -> f32 { return 0.5; }"),
    ///     ("main.wgsl", "#shader main\n#pass P\n#pragma multi_compile _ RED\n#import lib/color\n#endpass"),
    /// ]).unwrap();
    /// assert_eq!(lib.shaders()[0].name, "main");
    /// ```
    pub fn from_sources<P: Into<String>, T: Into<String>>(
        sources: impl IntoIterator<Item = (P, T)>,
    ) -> Result<Library, LoadError> {
        Library::from_sources_with(sources, &LoadOptions::default())
    }

    /// [`Library::from_sources`] with explicit limits.
    pub fn from_sources_with<P: Into<String>, T: Into<String>>(
        sources: impl IntoIterator<Item = (P, T)>,
        options: &LoadOptions,
    ) -> Result<Library, LoadError> {
        Library::load(raw_files(sources), &[], Origin::Memory, options)
    }

    /// Builds a library from raw bytes (which need not be UTF-8), e.g. read by the caller.
    pub fn from_raw(mut raw: Vec<RawFile>, options: &LoadOptions) -> Result<Library, LoadError> {
        raw.sort_by(|a, b| a.path.cmp(&b.path));
        Library::load(raw, &[], Origin::Memory, options)
    }

    fn load(
        raw: Vec<RawFile>,
        escaping: &[String],
        origin: Origin,
        options: &LoadOptions,
    ) -> Result<Library, LoadError> {
        let l = load::load(raw, escaping, options)?;
        Ok(Library::from_loaded(l, origin))
    }

    /// What loaded but is probably not meant, to show the user (render with
    /// [`Library::files`]): declared keywords that no module of their pass reads.
    pub fn warnings(&self) -> &[crate::diagnostic::Diagnostic] {
        &self.warnings
    }

    /// The dialect the library's modules are written in.
    pub fn dialect(&self) -> crate::preprocess::Dialect {
        self.dialect
    }

    /// Where the library was loaded from.
    pub fn origin(&self) -> &Origin {
        &self.origin
    }

    /// The source files, for rendering diagnostics.
    pub fn files(&self) -> &SourceFiles {
        &self.files
    }

    /// Module paths (relative, without `.wgsl`), in load order.
    pub fn module_paths(&self) -> &[String] {
        &self.paths
    }

    /// Every shader, sorted by file path.
    pub fn shaders(&self) -> &[Shader] {
        &self.shaders
    }

    /// The shader with this name.
    pub fn shader(&self, name: &str) -> Result<&Shader, LookupError> {
        self.shaders
            .iter()
            .find(|s| s.name == name)
            .ok_or_else(|| LookupError::UnknownShader {
                name: name.to_string(),
                suggestion: suggest(name, self.shaders.iter().map(|s| s.name.as_str())),
            })
    }

    /// A pass of a shader.
    pub fn pass(&self, shader: &str, pass: &str) -> Result<&Pass, LookupError> {
        let s = self.shader(shader)?;
        s.pass(pass).ok_or_else(|| LookupError::UnknownPass {
            shader: shader.to_string(),
            name: pass.to_string(),
            available: s.passes.iter().map(|p| p.name.clone()).collect(),
        })
    }

    /// Every pass of every shader, in order.
    pub fn passes(&self) -> impl Iterator<Item = &Pass> {
        self.shaders.iter().flat_map(|s| s.passes.iter())
    }

    /// The variant of `shader/pass` with exactly `keywords` on (strict; see [`Pass::resolve`]).
    pub fn variant<S: AsRef<str>>(
        &self,
        shader: &str,
        pass: &str,
        keywords: &[S],
    ) -> Result<Variant<'_>, LookupError> {
        let pass = self.pass(shader, pass)?;
        Ok(Variant {
            pass,
            choice: pass.resolve(keywords)?,
        })
    }

    /// Every shader with its passes, keyword sets and variant counts (the build set for
    /// `materials`).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let listing = lib.listing(None).unwrap();
    /// let deferred = listing.shaders.iter().flat_map(|s| &s.passes)
    ///     .find(|p| p.pass.name == "Deferred").unwrap();
    /// assert_eq!(deferred.full_space, 110_592u32.into());
    /// ```
    pub fn listing(
        &self,
        materials: Option<&[Material]>,
    ) -> Result<crate::shader::Listing<'_>, MaterialsError> {
        let mut shaders = Vec::new();
        for shader in &self.shaders {
            let mut passes = Vec::new();
            for pass in &shader.passes {
                passes.push(crate::shader::PassListing {
                    pass,
                    full_space: Space::full(pass).count(),
                    after_skip: Space::after_skip(pass).count(),
                    build_set: self.build_set(pass, materials)?.count(),
                });
            }
            shaders.push(crate::shader::ShaderListing {
                name: &shader.name,
                file: self.files().path(shader.file),
                passes,
            });
        }
        Ok(crate::shader::Listing { shaders })
    }

    /// The build set of a pass: the full space minus `skip_variants`, and, when `materials`
    /// are given, only the `shader_feature` combinations they use.
    pub fn build_set<'p>(
        &self,
        pass: &'p Pass,
        materials: Option<&[Material]>,
    ) -> Result<Space<'p>, MaterialsError> {
        let features = match materials {
            None => None,
            Some(m) => {
                materials::check(m, &self.shaders)?;
                Some(materials::feature_combinations(pass, m)?)
            }
        };
        Ok(Space::build_set(pass, features))
    }

    /// Composes a variant: the final WGSL text and its map back to the original files. The text
    /// keeps only the top-level items the entry points reach ([`crate::reach`]).
    pub fn compose(&self, variant: &Variant<'_>) -> Composed {
        self.compose_with(variant, true, true)
    }

    /// The lean composition of a variant: the same program as [`Library::compose`] without
    /// blank and comment-only lines and without the line map (for hashing and validating;
    /// compose again with the map to locate an error).
    pub fn compose_text(&self, variant: &Variant<'_>) -> Composed {
        self.compose_with(variant, false, true)
    }

    /// The composition of a variant with every item of every module it imports, reached or not
    /// (what `validate --strict` also validates), lean or `with_map`. For a tree in another
    /// dialect this is [`Library::compose`]'s text: its composer decides what it keeps.
    pub fn compose_unpruned(&self, variant: &Variant<'_>, with_map: bool) -> Composed {
        self.compose_with(variant, with_map, false)
    }

    fn compose_with(&self, variant: &Variant<'_>, with_map: bool, prune: bool) -> Composed {
        self.compose_for(variant, with_map, prune, self.pass_profile(variant.pass))
    }

    /// [`Library::compose`] (`with_map`, `prune`) for `profile`'s device: the engines that
    /// validate while composing (naga_oil, WESL) validate for it.
    pub(crate) fn compose_for(
        &self,
        variant: &Variant<'_>,
        with_map: bool,
        prune: bool,
        profile: crate::validator::Profile,
    ) -> Composed {
        self.engine.compose(
            &self.module_graph(),
            variant,
            engine::How {
                with_map,
                prune,
                profile,
            },
        )
    }

    /// Whether a variant's composition is the same for every profile (this crate's dialect
    /// and WESL), so that several profiles' verdicts come from one composition; naga_oil's
    /// composer is built with the device's capabilities and composes once per profile.
    pub(crate) fn composes_alike(&self) -> bool {
        self.engine.composes_alike()
    }

    /// The source files a pass's variants are composed from: its module and every module it
    /// imports, or, in a naga_oil or WESL tree (whose composer decides what it reads), every
    /// file. A variant's text can change only when one of them does (or the pass's
    /// declaration).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let pass = lib.pass("standard", "Deferred").unwrap();
    /// let paths: Vec<&str> = lib.pass_files(pass).iter().map(|&f| lib.files().path(f)).collect();
    /// assert!(paths.contains(&"standard/surface.wgsl"));
    /// assert!(!paths.iter().any(|p| p.starts_with("universal/")));
    /// ```
    pub fn pass_files(&self, pass: &Pass) -> Vec<crate::diagnostic::FileId> {
        if self.dialect != crate::preprocess::Dialect::WgslVariants {
            return (0..self.files.len()).collect();
        }
        self.module_graph()
            .reach(pass.module())
            .into_iter()
            .map(|m| self.modules[m].file)
            .collect()
    }

    /// The parsed modules with their imports resolved (module ids index
    /// [`Library::module_paths`]), e.g. to compose or export a module on its own.
    pub(crate) fn module_graph(&self) -> ModuleGraph<'_> {
        ModuleGraph {
            modules: &self.modules,
            resolved: &self.resolved,
            files: &self.files,
        }
    }

    /// The final WGSL text of a variant, lean: blank and comment-only lines left out (use
    /// [`Library::compose`] for the text with every line and its map to the sources).
    pub fn wgsl(&self, variant: &Variant<'_>) -> String {
        self.compose_text(variant).text
    }

    /// Composes, parses and validates one variant (the validation stage:
    /// [`validate`](crate::validate)).
    ///
    /// ```
    /// let lib = wgsl_variants_shaders::library().unwrap();
    /// let v = lib.variant("standard", "Deferred", &["UNITY_HDR_ON"]).unwrap();
    /// let (module, _info) = lib.naga_module(&v).unwrap();
    /// assert!(module.entry_points.iter().any(|e| e.name == "fs_main"));
    /// ```
    pub fn naga_module(
        &self,
        variant: &Variant<'_>,
    ) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
        crate::validator::validate_for(
            &self.compose(variant),
            &variant.label(),
            self.pass_profile(variant.pass),
        )
    }

    /// [`Library::naga_module`] for `profile`'s device, whatever the pass's profiles.
    pub fn naga_module_for(
        &self,
        variant: &Variant<'_>,
        profile: crate::validator::Profile,
    ) -> Result<(naga::Module, naga::valid::ModuleInfo), VariantError> {
        crate::validator::validate_for(
            &self.compose_for(variant, true, true, profile),
            &variant.label(),
            profile,
        )
    }

    /// The first device this library's variants are validated for: the declaration file's
    /// `profile` (the first listed), the one [`Library::set_profile`] set, or WebGPU
    /// ([`Profile::WebGpu`](crate::validate::Profile)). A pass may name its own
    /// ([`Library::pass_profiles`]).
    pub fn profile(&self) -> crate::validator::Profile {
        self.profiles[0]
    }

    /// Every device this library's variants are validated for, in order (see
    /// [`Library::profile`]); never empty.
    pub fn profiles(&self) -> &[crate::validator::Profile] {
        &self.profiles
    }

    /// The devices `pass`'s variants are validated for, one verdict each: those set by
    /// [`Library::set_profiles`] (the command line's `--profile`), else the pass's own in the
    /// declaration file, else the tree's ([`Library::profiles`]). Never empty.
    pub fn pass_profiles<'a>(&'a self, pass: &'a Pass) -> &'a [crate::validator::Profile] {
        if self.profiles_set || pass.profiles.is_empty() {
            &self.profiles
        } else {
            &pass.profiles
        }
    }

    /// The first of [`Library::pass_profiles`]: the device a single program of the pass is
    /// built for ([`Library::naga_module`], emit, bake, reflect).
    pub fn pass_profile(&self, pass: &Pass) -> crate::validator::Profile {
        self.pass_profiles(pass)[0]
    }

    /// Whether the passes are validated for more than one device in all (a pass for several,
    /// or passes for different ones): `validate` then reports one verdict per device
    /// ([`crate::validate::PassReport::profiles`]).
    pub fn several_profiles(&self) -> bool {
        let mut all = self.passes().flat_map(|p| self.pass_profiles(p));
        let first = all.next();
        self.profiles.len() > 1 || all.any(|p| Some(p) != first)
    }

    /// Validates this library's variants for another device from now on (`--profile`), for
    /// every pass (a pass's own `profile` included): [`Library::set_profiles`] with one.
    ///
    /// ```
    /// use wgsl_variants::validate::Profile;
    /// let mut lib = wgsl_variants::Library::from_sources([
    ///     (
    ///         "count.wgsl",
    ///         "@group(0) @binding(0) var<storage, read_write> out: array<u32>;\n\
    ///          @compute @workgroup_size(1) fn main() { out[0] = 1u; }\n",
    ///     ),
    ///     ("main.wgsl", "#shader s\n#pass P\n#import count\n#endpass\n"),
    /// ])
    /// .unwrap();
    /// let none: &[&str] = &[];
    /// assert!(lib.naga_module(&lib.variant("s", "P", none).unwrap()).is_ok());
    /// lib.set_profile(Profile::WebGl2);
    /// let e = lib.naga_module(&lib.variant("s", "P", none).unwrap()).unwrap_err();
    /// assert!(e.message.contains("storage buffer"), "{}", e.message);
    /// ```
    pub fn set_profile(&mut self, profile: crate::validator::Profile) {
        self.set_profiles(&[profile]);
    }

    /// Validates this library's variants for every device of `profiles` from now on (the
    /// command line's repeated `--profile`), overriding the passes' own: validation gives one
    /// verdict per profile ([`crate::validate::PassReport::profiles`]), composing each variant
    /// once where its composition does not depend on the device. A profile listed twice
    /// counts once; an empty list means WebGPU.
    ///
    /// ```
    /// use wgsl_variants::validate::Profile;
    /// let mut lib = wgsl_variants_shaders::library().unwrap();
    /// lib.set_profiles(&[Profile::WebGpu, Profile::Desktop, Profile::WebGpu]);
    /// assert_eq!(lib.profiles(), [Profile::WebGpu, Profile::Desktop]);
    /// assert!(lib.several_profiles());
    /// ```
    pub fn set_profiles(&mut self, profiles: &[crate::validator::Profile]) {
        let mut unique: Vec<crate::validator::Profile> = Vec::new();
        for p in profiles {
            if !unique.contains(p) {
                unique.push(*p);
            }
        }
        if unique.is_empty() {
            unique.push(crate::validator::Profile::default());
        }
        self.profiles = unique;
        self.profiles_set = true;
    }
}
