//! A WESL 0.6 tree of two packages (`tests/fixtures/wesl_packages`, written for this test):
//! it loads with the declaration file's `[packages]`, every variant is what `wesl` 0.6
//! compiles for the same features, and the audit reads the conditions of module-scope blocks
//! (`@if(X) { … } @else { … }`) in the other package.

use wgsl_variants::validate::validate_pass;
use wgsl_variants::{Dialect, Library, Space};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/wesl_packages");

const FILES: [(&str, &str); 5] = [
    ("package::app::main", "app/main.wesl"),
    ("package::app::util", "app/util.wesl"),
    ("engine::lighting", "engine/src/lighting.wesl"),
    ("engine::shadow", "engine/src/shadow.wesl"),
    ("engine::fog", "engine/src/fog.wesl"),
];

fn fixture(path: &str) -> String {
    std::fs::read_to_string(format!("{ROOT}/{path}")).unwrap()
}

/// The program `wesl` 0.6 compiles from the fixture's modules for these features (a
/// `VirtualResolver` holding each module at its package path, as a host registering two
/// packages would; the host's numbers in the `constants` package; visibility off).
fn direct(on: &[&str]) -> String {
    let mut resolver = Packages(wesl::resolver::VirtualResolver::new());
    for (path, file) in FILES {
        resolver
            .0
            .add_module(path.parse().unwrap(), fixture(file).into());
    }
    resolver.0.add_module(
        "constants".parse().unwrap(),
        "public const MAX_LIGHTS = 2u;\n".into(),
    );
    let mut options = wesl::CompileOptions {
        visibility: false,
        ..Default::default()
    };
    for f in ["SHADOWS", "FOG", "LIGHTMAP", "HEAVY_FOG"] {
        options.features.set(f, on.contains(&f));
    }
    wesl::compile(&"package::app::main".parse().unwrap(), &options, &resolver)
        .unwrap()
        .to_string()
}

/// A `VirtualResolver` that reads a package named from inside another (`engine/constants`,
/// as `wesl` 0.6 joins package paths) as that package (`constants`), as Bevy's resolver does.
struct Packages(wesl::resolver::VirtualResolver<'static>);

impl wesl::Resolver for Packages {
    fn resolve_source<'a>(
        &'a self,
        path: &wesl::syntax::ModulePath,
    ) -> Result<std::borrow::Cow<'a, str>, wesl::error::ResolveError> {
        self.0.resolve_source(&self.canonical_path(path))
    }

    fn canonical_path(&self, path: &wesl::syntax::ModulePath) -> wesl::syntax::ModulePath {
        let mut path = path.clone();
        if let wesl::syntax::PathOrigin::Package(p) = &path.origin
            && let Some((_, last)) = p.rsplit_once('/')
        {
            path.origin = wesl::syntax::PathOrigin::Package(last.to_string());
        }
        path
    }
}

/// A program's top-level blocks (wesl writes a blank line between declarations), sorted.
fn blocks(text: &str) -> Vec<&str> {
    let mut b: Vec<&str> = text.split("\n\n").map(str::trim).collect();
    b.sort();
    b
}

#[test]
fn a_tree_of_packages_loads_with_module_scope_blocks_cycles_and_inline_paths() {
    let lib = Library::from_dir(ROOT).unwrap();
    assert_eq!(lib.dialect(), Dialect::Wesl);
    // Every keyword is read somewhere the pass composes: `LIGHTMAP` only in a module-scope
    // block of the other package, `HEAVY_FOG` only in `engine::fog`, which only an inline
    // path reaches (`engine::fog::apply(c)`). No "never read" warning.
    assert!(lib.warnings().is_empty(), "{:#?}", lib.warnings());
    assert_eq!(
        lib.module_paths(),
        [
            "app/main",
            "app/util",
            "engine/src/fog",
            "engine/src/lighting",
            "engine/src/shadow"
        ]
    );
}

#[test]
fn every_variant_is_what_wesl_compiles() {
    let lib = Library::from_dir(ROOT).unwrap();
    let pass = lib.pass("app", "Forward").unwrap();
    let choices: Vec<_> = Space::full(pass).iter().collect();
    assert_eq!(choices.len(), 16);
    for choice in &choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let on: Vec<&str> = variant.keywords();
        let ours = lib
            .naga_module(&variant)
            .map(|_| lib.wgsl(&variant))
            .unwrap_or_else(|e| panic!("{on:?}: {e}"));
        assert_eq!(blocks(&ours), blocks(&direct(&on)), "{on:?}");
        // The module-scope block is taken or not as the keyword says.
        assert_eq!(
            ours.contains("lightmap"),
            on.contains(&"LIGHTMAP"),
            "{ours}"
        );
    }
    let report = validate_pass(&lib, pass, &choices, &|_| {});
    assert_eq!((report.built, report.valid, report.invalid), (16, 16, 0));
}

#[test]
fn the_audit_reads_module_scope_blocks() {
    let lib = Library::from_dir(ROOT).unwrap();
    let pass = lib.pass("app", "Forward").unwrap();
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert!(audit.dead_keywords.is_empty(), "{:?}", audit.dead_keywords);
    // HEAVY_FOG changes the text only with FOG: 8 + 4 distinct of 16.
    assert_eq!(audit.distinct_full_space.count, 12u32.into());
}

/// The same tree with WESL's visibility rules on (`wesl`'s default): `engine`'s items are not
/// `public`, so every variant fails with `wesl`'s own message, located in the user's tree.
#[test]
fn visibility_rules_apply_unless_the_declaration_turns_them_off() {
    let declaration = fixture("wgsl-variants.toml").replace("visibility = false", "");
    let sources: Vec<(&str, String)> = FILES.iter().map(|(_, f)| (*f, fixture(f))).collect();
    let lib =
        Library::from_declared_sources(&declaration, sources.iter().map(|(p, t)| (*p, t.as_str())))
            .unwrap();
    let pass = lib.pass("app", "Forward").unwrap();
    let choices: Vec<_> = Space::full(pass).iter().collect();
    let report = validate_pass(&lib, pass, &choices, &|_| {});
    assert_eq!(report.invalid, 16);
    assert!(
        report
            .failures
            .iter()
            .any(|f| f.error.message.contains("visibility")),
        "{:#?}",
        report.failures
    );
}

#[test]
fn packages_are_checked_and_missing_ones_are_named() {
    let problem = |declaration: &str, sources: &[(&str, &str)]| {
        let e = Library::from_declared_sources(declaration, sources.iter().copied()).unwrap_err();
        e.to_string()
            + &e.problems
                .iter()
                .map(|p| p.diagnostic().message)
                .collect::<Vec<_>>()
                .join("\n")
    };
    let shader = "[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\n";
    let main = (
        "main.wesl",
        "import engin::lighting::shade;\n@fragment fn f() {}\n",
    );
    let lighting = ("engine/lighting.wesl", "fn shade() {}\n");
    // A package name that is not declared, with a suggestion.
    let e = problem(
        &format!("dialect = \"wesl\"\n[packages]\nengine = \"engine\"\n{shader}"),
        &[main, lighting],
    );
    assert!(e.contains("no package of this name is declared"), "{e}");
    assert!(e.contains("did you mean `engine::lighting::shade`"), "{e}");
    // WESL reserves `package`, `self`, `super` and `constants`.
    let e = problem(
        &format!("dialect = \"wesl\"\n[packages]\nconstants = \"engine\"\n{shader}"),
        &[main, lighting],
    );
    assert!(e.contains("package name `constants`"), "{e}");
    // Packages are WESL's.
    let e = problem(
        &format!(
            "dialect = \"naga-oil\"\n[packages]\nengine = \"engine\"\n{}",
            shader.replace(".wesl", ".wgsl")
        ),
        &[("main.wgsl", "fn f() {}\n")],
    );
    assert!(e.contains("this tree is not WESL"), "{e}");
}

/// A misspelt keyword (within two edits of a name the modules read) stops the load, naming the
/// name read; every other unread keyword is labelled where it is written, not only the first.
#[test]
fn a_misspelt_keyword_is_an_error_and_every_unread_one_is_labelled() {
    let sources = [(
        "main.wesl",
        "@fragment\nfn f() -> @location(0) vec4<f32> {\n    var c = vec4<f32>(1.0);\n    @if(SRGB_OUTPUT) {\n        c = c * 0.5;\n    }\n    return c;\n}\n",
    )];
    let declaration = |sets: &str| {
        format!(
            "dialect = \"wesl\"\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = {sets}\n"
        )
    };
    let e = Library::from_declared_sources(&declaration(r#"[["MARKER", "SRGB_OUPUT"]]"#), sources)
        .unwrap_err();
    let shown = e.render(false);
    assert!(
        shown.contains("keyword `SRGB_OUPUT` of `s/P` is read by none of the modules it composes, which read `SRGB_OUTPUT`"),
        "{shown}"
    );
    // The caret is under the misspelt keyword, not under the marker before it.
    let at = e.locations();
    assert_eq!(at, ["wgsl-variants.toml:7:29"], "{shown}");

    let lib = Library::from_declared_sources(
        &declaration(r#"[["UNUSED_A", "SRGB_OUTPUT"], ["_", "UNUSED_B"]]"#),
        sources,
    )
    .unwrap();
    let warning = &lib.warnings()[0];
    let shown = warning.render(lib.files(), false);
    assert!(shown.contains("UNUSED_A, UNUSED_B"), "{shown}");
    assert_eq!(shown.matches("never read").count(), 2, "{shown}");
}
