//! Single modules on their own: prefixed self-contained WGSL, and naga_oil's dialect composed
//! with naga_oil itself (the release on naga 30, 0.23) and validated by naga.

use std::collections::BTreeSet;
use std::time::Instant;

use naga_oil::compose::{Composer, NagaModuleDescriptor, ShaderDefValue};
use rayon::prelude::*;

use wgsl_variants::emit::export::{ExportError, export_prefixed};
use wgsl_variants::emit::naga_oil::{NagaOilModule, export, export_all};
use wgsl_variants::reflect::{Binding, reflect_module};
use wgsl_variants::snapshot::covering_set;
use wgsl_variants::{Library, Space, Variant};

fn validate(module: &naga::Module) -> naga::valid::ModuleInfo {
    wgsl_variants::validate::validator()
        .validate(module)
        .unwrap_or_else(|e| panic!("invalid: {e:?}"))
}

fn parse_and_validate(wgsl: &str) -> (naga::Module, naga::valid::ModuleInfo) {
    let module = naga::front::wgsl::parse_str(wgsl)
        .unwrap_or_else(|e| panic!("{}\n{wgsl}", e.emit_to_string(wgsl)));
    let info = validate(&module);
    (module, info)
}

fn plain_modules(lib: &Library) -> Vec<String> {
    lib.module_paths()
        .iter()
        .enumerate()
        .filter(|(i, _)| !wgsl_variants::emit::export::is_shader_file(lib, *i))
        .map(|(_, p)| p.clone())
        .collect()
}

// ---------------------------------------------------------------- prefixed WGSL

#[test]
fn every_bundled_module_exports_as_prefixed_self_contained_wgsl() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let modules = plain_modules(&lib);
    assert!(modules.len() >= 8, "{modules:?}");
    for path in &modules {
        // standard/my_lighting is a pass program: it needs the pass's define;
        // universal/main_light_shadow_map holds only what a main-light shadow declares, and
        // universal/light_cookie only what a cookie does.
        let index = lib.module_paths().iter().position(|p| p == path).unwrap();
        let read = wgsl_variants::emit::export::conditions_read(&lib, index);
        let keywords: Vec<&str> = ["FORWARD_BASE_PASS", "_MAIN_LIGHT_SHADOWS", "_LIGHT_COOKIES"]
            .into_iter()
            .filter(|k| read.contains(*k))
            .collect();
        let wgsl = export_prefixed(&lib, path, "wv_", &keywords).unwrap();
        let (module, _) = parse_and_validate(&wgsl);
        let mut names: Vec<&str> = Vec::new();
        names.extend(
            module
                .functions
                .iter()
                .filter_map(|(_, f)| f.name.as_deref()),
        );
        names.extend(
            module
                .global_variables
                .iter()
                .filter_map(|(_, g)| g.name.as_deref()),
        );
        names.extend(
            module
                .constants
                .iter()
                .filter_map(|(_, c)| c.name.as_deref()),
        );
        names.extend(module.entry_points.iter().map(|e| e.name.as_str()));
        // Structs the module declares; not the result types naga predeclares for builtins such
        // as `frexp` (`__frexp_result_f32`: WGSL reserves names starting with `__`).
        let predeclared: Vec<_> = module
            .special_types
            .predeclared_types
            .values()
            .copied()
            .collect();
        names.extend(module.types.iter().filter_map(|(h, t)| match t.inner {
            naga::TypeInner::Struct { .. } if !predeclared.contains(&h) => t.name.as_deref(),
            _ => None,
        }));
        assert!(!names.is_empty(), "{path} exports nothing");
        for name in names {
            assert!(name.starts_with("wv_"), "{path}: `{name}` is not prefixed");
        }
    }
}

#[test]
fn prefixed_exports_from_two_prefixes_live_side_by_side_in_one_shader() {
    let lib = wgsl_variants_shaders::library().unwrap();
    // Another engine's tree: two exports (each with its own copy of deferred/ldr) and its own
    // entry point using both.
    let gbuffer = export_prefixed(&lib, "deferred/gbuffer", "a_", &["UNITY_HDR_ON"]).unwrap();
    let ldr = export_prefixed(&lib, "deferred/ldr", "b_", &[]).unwrap();
    let main = "
@fragment
fn main(@builtin(position) p: vec4f) -> a_GBufferOutput {
    let c = b_ldr_decode(vec3f(0.5));
    return a_gbuffer_pack(vec3f(1.0), 1.0, vec3f(0.04), 0.5, vec3f(0.0, 0.0, 1.0), c);
}
";
    let (module, _) = parse_and_validate(&format!("{gbuffer}\n{ldr}\n{main}"));
    assert_eq!(module.entry_points.len(), 1);
    // The keyword was applied: RT3 = c under UNITY_HDR_ON, so no ldr_encode call remains in
    // a_gbuffer_pack.
    let pack = gbuffer.split("fn a_gbuffer_pack").nth(1).unwrap();
    assert!(!pack.contains("a_ldr_encode"), "{pack}");
    let without = export_prefixed(&lib, "deferred/gbuffer", "a_", &[]).unwrap();
    assert!(
        without
            .split("fn a_gbuffer_pack")
            .nth(1)
            .unwrap()
            .contains("a_ldr_encode")
    );
}

#[test]
fn prefixed_export_errors_are_clear() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let unknown = export_prefixed(&lib, "deferred/gbufer", "wv_", &[]).unwrap_err();
    assert_eq!(
        unknown.to_string(),
        "no module `deferred/gbufer` (did you mean `deferred/gbuffer`?)"
    );
    let shader = export_prefixed(&lib, "standard", "wv_", &[]).unwrap_err();
    assert!(matches!(shader, ExportError::ShaderFile(_)), "{shader}");
    for bad in ["", "1x", "__x", "a-b"] {
        let e = export_prefixed(&lib, "deferred/ldr", bad, &[]).unwrap_err();
        assert!(matches!(e, ExportError::BadPrefix(_)), "{bad:?}: {e}");
    }
    let typo = export_prefixed(&lib, "deferred/gbuffer", "wv_", &["UNITY_HDR_OM"]).unwrap_err();
    assert_eq!(
        typo.to_string(),
        "no `#if` in `deferred/gbuffer` or its imports reads `UNITY_HDR_OM` (did you mean `UNITY_HDR_ON`?)"
    );
    // naga's errors point at the original file.
    let broken =
        Library::from_sources([("m.wgsl", "fn f() -> f32 {\n    return vec2f(1.0);\n}\n")])
            .unwrap();
    let e = export_prefixed(&broken, "m", "p_", &[]).unwrap_err();
    let rendered = e.diagnostic().render(broken.files(), false);
    assert!(rendered.contains("m.wgsl:2:"), "{rendered}");
}

// ---------------------------------------------------------------- naga_oil

fn composer_with(modules: &[NagaOilModule]) -> Composer {
    test_support::naga_oil_composer(modules).unwrap_or_else(|e| panic!("{e}"))
}

fn compose(
    composer: &mut Composer,
    source: &str,
    path: &str,
    defs: &[(&str, ShaderDefValue)],
) -> Result<naga::Module, String> {
    composer
        .make_naga_module(NagaModuleDescriptor {
            source,
            file_path: path,
            shader_defs: defs.iter().map(|(k, v)| (k.to_string(), *v)).collect(),
            ..Default::default()
        })
        .map_err(|e| e.emit_to_string(composer))
}

/// Bindings without names (naga_oil decorates imported names): slot, kind, visibility.
fn slots(bindings: &[Binding]) -> BTreeSet<String> {
    bindings
        .iter()
        .map(|b| format!("{}/{} {} {:?}", b.group, b.binding, b.kind, b.visibility))
        .collect()
}

#[test]
fn naga_oil_export_composes_standard_variants_like_the_variants_themselves() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let modules = export_all(&lib, Some("wv")).unwrap();
    assert_eq!(modules.len(), plain_modules(&lib).len());
    let lighting = modules
        .iter()
        .find(|m| m.path == "standard/my_lighting")
        .unwrap()
        .source
        .clone();
    let started = Instant::now();
    let plan = test_support::selection::plan_of(&lib);
    let mut composed = 0usize;
    for (pass_name, define) in [
        ("ForwardBase", "FORWARD_BASE_PASS"),
        ("Deferred", "DEFERRED_PASS"),
    ] {
        let pass = lib.pass("standard", pass_name).unwrap();
        // The covering set (all off, each keyword alone, all on), the tests' 3-wise covering
        // set (every triple of options) and every 97th variant of the enumeration (97 is a
        // prime above every set size, so each set takes every option in every position):
        // naga_oil (one composer per thread) against our own composition. (Every 7th, 23,698
        // variants, took 125 s of CI's 2 cores; 97 keeps the spread at a fourteenth of it.)
        let mut choices: Vec<_> = Space::full(pass)
            .enumerate(1_000_000)
            .unwrap()
            .into_iter()
            .step_by(97)
            .collect();
        let selected = plan
            .iter()
            .find(|(p, _)| std::ptr::eq(*p, pass))
            .map(|(_, c)| c.clone())
            .unwrap();
        for choice in covering_set(pass)
            .into_iter()
            .map(|(_, c)| c)
            .chain(selected)
        {
            if !choices.contains(&choice) {
                choices.push(choice);
            }
        }
        let results: Vec<Result<(), String>> = choices
            .par_iter()
            .map_init(
                || composer_with(&modules),
                |composer, choice| {
                    let variant = Variant {
                        pass,
                        choice: choice.clone(),
                    };
                    let mut defs = vec![(define, ShaderDefValue::Bool(true))];
                    defs.extend(
                        variant
                            .keywords()
                            .into_iter()
                            .map(|k| (k, ShaderDefValue::Bool(true))),
                    );
                    let module = compose(composer, &lighting, "standard/my_lighting.wgsl", &defs)
                        .map_err(|e| format!("{}: {e}", variant.label()))?;
                    let info = wgsl_variants::validate::validator()
                        .validate(&module)
                        .map_err(|e| format!("{}: invalid: {e:?}", variant.label()))?;
                    let theirs = reflect_module(&module, &info);
                    let ours = lib.reflect(&variant).map_err(|e| e.to_string())?;
                    if theirs.entry_points != ours.entry_points
                        || slots(&theirs.bindings) != slots(&ours.bindings)
                    {
                        return Err(format!(
                            "{}: naga_oil {:?} {:?}\nours {:?} {:?}",
                            variant.label(),
                            theirs.entry_points,
                            slots(&theirs.bindings),
                            ours.entry_points,
                            slots(&ours.bindings)
                        ));
                    }
                    // Same fragment output: G-buffer struct or one colour.
                    let outputs = |m: &naga::Module| {
                        let fs = m.entry_points.iter().find(|e| e.name == "fs_main").unwrap();
                        let ty = fs.function.result.as_ref().unwrap().ty;
                        match &m.types[ty].inner {
                            naga::TypeInner::Struct { members, .. } => members.len(),
                            _ => 1,
                        }
                    };
                    let (our_module, _) = lib.naga_module(&variant).map_err(|e| e.to_string())?;
                    if outputs(&module) != outputs(&our_module) {
                        return Err(format!("{}: fragment outputs differ", variant.label()));
                    }
                    Ok(())
                },
            )
            .collect();
        let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
        assert!(
            failures.is_empty(),
            "{} failures, first: {}",
            failures.len(),
            failures[0]
        );
        composed += choices.len();
    }
    assert!(composed > (55_296 + 110_592) / 97, "{composed}");
    println!(
        "naga_oil composed and validated {composed} standard variants in {:.1?}",
        started.elapsed()
    );
}

#[test]
fn naga_oil_export_of_one_module_brings_its_imports_first() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let modules = export(&lib, "internal/fullscreen", None).unwrap();
    assert_eq!(modules.len(), 1);
    assert_eq!(modules[0].import_path, "internal::fullscreen");
    let gbuffer = export(&lib, "deferred/gbuffer", None).unwrap();
    let paths: Vec<&str> = gbuffer.iter().map(|m| m.path.as_str()).collect();
    assert_eq!(paths, ["deferred/ldr", "deferred/gbuffer"]);
    // A top-level shader of another engine, using our modules through naga_oil's imports.
    let mut all = export(&lib, "internal/fullscreen", None).unwrap();
    all.extend(gbuffer);
    let mut composer = composer_with(&all);
    let shader = "
#import internal::fullscreen::{fullscreen_position, fullscreen_pixel}
#import deferred::gbuffer::{GBufferOutput, gbuffer_pack}

@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    return fullscreen_position(i);
}

@fragment
fn fs(@builtin(position) p: vec4f) -> GBufferOutput {
    let px = vec2f(fullscreen_pixel(p));
    return gbuffer_pack(vec3f(px.x), 1.0, vec3f(0.04), 0.5, vec3f(0.0, 0.0, 1.0), vec3f(1.0));
}
";
    for defs in [vec![], vec![("UNITY_HDR_ON", ShaderDefValue::Bool(true))]] {
        let module = compose(&mut composer, shader, "engine.wgsl", &defs).unwrap();
        validate(&module);
        assert_eq!(module.entry_points.len(), 2);
    }
}

fn oil_lib(module: &str) -> Library {
    Library::from_sources([("m.wgsl", module)]).unwrap()
}

#[test]
fn naga_oil_conditions_translate_or_fail_clearly() {
    // `||`, `&&`, `!`, `#elif` and valued comparisons become nested naga_oil conditionals;
    // the composed result follows our semantics for every def combination.
    let source = "\
#if defined(A) || (B && !defined(C))
fn f() -> i32 { return 1; }
#elif COUNT >= 2
fn f() -> i32 { return 2; }
#elif 3 > COUNT
fn f() -> i32 { return 3; }
#else
fn f() -> i32 { return 4; }
#endif
";
    let lib = oil_lib(source);
    let modules = export(&lib, "m", Some("t")).unwrap();
    assert!(!modules[0].source.contains("||"), "{}", modules[0].source);
    let mut composer = composer_with(&modules);
    let main = "#import t::m::{f}\n@compute @workgroup_size(1)\nfn main() { let x = f(); }\n";
    let expected = |a: bool, b: bool, c: bool, count: Option<i32>| -> i32 {
        let count = count.unwrap_or(0);
        if a || (b && !c) {
            1
        } else if count >= 2 {
            2
        } else if 3 > count {
            3
        } else {
            4
        }
    };
    let mut checked = 0;
    for bits in 0..8u32 {
        // naga_oil needs valued defines to be given: our "undefined" is 0 there.
        for count in [Some(0), Some(2), Some(3), Some(5)] {
            let (a, b, c) = (bits & 1 != 0, bits & 2 != 0, bits & 4 != 0);
            let mut defs = Vec::new();
            for (on, name) in [(a, "A"), (b, "B"), (c, "C")] {
                if on {
                    defs.push((name, ShaderDefValue::Bool(true)));
                }
            }
            if let Some(n) = count {
                defs.push(("COUNT", ShaderDefValue::Int(n)));
            }
            let module = compose(&mut composer, main, "main.wgsl", &defs).unwrap();
            let f = module
                .functions
                .iter()
                .find(|(_, f)| f.name.as_deref().is_some_and(|n| n.starts_with('f')))
                .unwrap()
                .1;
            let returned = f
                .expressions
                .iter()
                .find_map(|(_, e)| match e {
                    naga::Expression::Literal(naga::Literal::I32(v)) => Some(*v),
                    _ => None,
                })
                .unwrap();
            assert_eq!(returned, expected(a, b, c, count), "defs {defs:?}");
            checked += 1;
        }
    }
    assert_eq!(checked, 32);

    for (source, message) in [
        ("#define X 2\nfn f() {}\n", "`#define X` inside a module"),
        ("#undef X\nfn f() {}\n", "`#undef X`"),
        (
            "#if A == B\nfn f() {}\n#endif\n",
            "a comparison other than NAME op INTEGER",
        ),
        ("#if -A\nfn f() {}\n#endif\n", "unary `-` on a name"),
        (
            "#if -A > 1\nfn f() {}\n#endif\n",
            "a comparison other than NAME op INTEGER",
        ),
    ] {
        let e = export(&oil_lib(source), "m", None).unwrap_err();
        assert!(
            matches!(e, ExportError::Inexpressible { .. }) && e.to_string().contains(message),
            "{source:?}: {e}"
        );
    }
    let dashed = Library::from_sources([("my-mod.wgsl", "fn f() {}\n")]).unwrap();
    assert!(
        export(&dashed, "my-mod", None)
            .unwrap_err()
            .to_string()
            .contains("naga_oil import path")
    );
}

// ---------------------------------------------------------------- WESL

/// Compiles a pass's WESL export with the `wesl` crate (modules in a `VirtualResolver`, as a
/// WESL user embedding them would register them), the pass's `#define`s and the variant's
/// keywords as features, every other keyword of the pass off.
fn wesl_compile(
    p: &wgsl_variants::emit::wesl::WeslPass,
    pass: &wgsl_variants::Pass,
    on: &[&str],
) -> Result<String, String> {
    let mut resolver = wesl::resolver::VirtualResolver::new();
    for m in p.modules.iter().chain([&p.root]) {
        resolver.add_module(
            m.module_path.parse().map_err(|e| format!("{e:?}"))?,
            std::borrow::Cow::Owned(m.source.clone()),
        );
    }
    let mut options = wesl::CompileOptions::default();
    for f in &p.features {
        options.features.set(f, true);
    }
    for k in pass.keywords() {
        options.features.set(k, on.contains(&k));
    }
    let root = p.root.module_path.parse().map_err(|e| format!("{e:?}"))?;
    wesl::compile(&root, &options, &resolver)
        .map(|r| r.to_string())
        .map_err(|e| e.to_string())
}

/// The WESL export of every bundled pass, compiled by the `wesl` crate for each variant of a
/// 3-wise covering set of the pass (its whole space when it has at most three sets), gives a
/// program naga validates and that shows a renderer what our text does: the same entry
/// points, bindings (slot, kind, visibility) and fragment outputs.
#[test]
fn wesl_export_compiles_every_covering_variant_of_every_pass_like_ours() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let mut options = wgsl_variants::plan::PlanOptions::default();
    options.all = true;
    options.cover = Some(3);
    let plan = wgsl_variants::plan::plan(&lib, &options).unwrap();
    let started = Instant::now();
    let mut compiled = 0usize;
    let mut failures = Vec::new();
    for (pass, choices) in &plan {
        let exported = wgsl_variants::emit::wesl::export_pass(&lib, pass)
            .unwrap_or_else(|e| panic!("{}/{}: {e}", pass.shader, pass.name));
        for choice in choices {
            let variant = Variant {
                pass,
                choice: choice.clone(),
            };
            let on = variant.keywords();
            let result = wesl_compile(&exported, pass, &on).and_then(|text| {
                let module = naga::front::wgsl::parse_str(&text)
                    .map_err(|e| format!("naga parse: {}\n{text}", e.emit_to_string(&text)))?;
                let info = wgsl_variants::validate::validator()
                    .validate(&module)
                    .map_err(|e| format!("invalid: {:?}", e.into_inner()))?;
                let theirs = reflect_module(&module, &info);
                let ours = lib.reflect(&variant).map_err(|e| e.to_string())?;
                let outputs = |m: &naga::Module| -> Vec<usize> {
                    m.entry_points
                        .iter()
                        .filter_map(|e| e.function.result.as_ref())
                        .map(|r| match &m.types[r.ty].inner {
                            naga::TypeInner::Struct { members, .. } => members.len(),
                            _ => 1,
                        })
                        .collect()
                };
                let (our_module, _) = lib.naga_module(&variant).map_err(|e| e.to_string())?;
                if theirs.entry_points != ours.entry_points
                    || slots(&theirs.bindings) != slots(&ours.bindings)
                    || outputs(&module) != outputs(&our_module)
                {
                    return Err(format!(
                        "WESL {:?} {:?} {:?}\nours {:?} {:?} {:?}",
                        theirs.entry_points,
                        slots(&theirs.bindings),
                        outputs(&module),
                        ours.entry_points,
                        slots(&ours.bindings),
                        outputs(&our_module)
                    ));
                }
                Ok(())
            });
            compiled += 1;
            if let Err(e) = result {
                failures.push(format!("{}: {e}", variant.label()));
            }
        }
    }
    let mut by_pass = std::collections::BTreeMap::new();
    for f in &failures {
        *by_pass
            .entry(f.split(' ').next().unwrap_or(""))
            .or_insert(0) += 1;
    }
    assert!(
        failures.is_empty(),
        "{} of {compiled} failed ({by_pass:?}); first: {}",
        failures.len(),
        failures[0]
    );
    assert!(compiled > 100, "{compiled}");
    println!(
        "WESL compiled and naga validated {compiled} covering variants of {} passes in {:.1?}",
        plan.len(),
        started.elapsed()
    );
}

/// The WESL export written as a tree with its declaration file (`export --dialect wesl --all
/// --out DIR`) loads back as a WESL tree: the same passes and variant spaces, and every variant
/// of a 2-wise covering set of each pass composes through the `wesl` crate, validates, and shows
/// a renderer what our text does (entry points and binding slots).
#[test]
fn wesl_export_reads_back_as_a_wesl_tree_with_the_same_variants() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let dir = tempfile::tempdir().unwrap();
    for (path, text) in wgsl_variants::emit::wesl::export_tree(&lib).unwrap() {
        let path = dir.path().join(path);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    let tree = Library::from_dir(dir.path()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(tree.dialect(), wgsl_variants::Dialect::Wesl);
    assert!(tree.warnings().is_empty(), "{:?}", tree.warnings());
    let mut options = wgsl_variants::plan::PlanOptions::default();
    options.all = true;
    options.cover = Some(2);
    let plan = wgsl_variants::plan::plan(&tree, &options).unwrap();
    assert_eq!(plan.len(), lib.passes().count());
    let mut checked = 0;
    for (pass, choices) in &plan {
        let ours = lib.pass(&pass.shader, &pass.name).unwrap();
        assert_eq!(Space::full(pass).count(), Space::full(ours).count());
        for choice in choices {
            let theirs = Variant {
                pass,
                choice: choice.clone(),
            };
            let keywords = theirs.keywords();
            let mine = lib.variant(&pass.shader, &pass.name, &keywords).unwrap();
            let a = tree
                .reflect(&theirs)
                .unwrap_or_else(|e| panic!("{}: {e}", theirs.label()));
            let b = lib.reflect(&mine).unwrap();
            assert_eq!(a.entry_points, b.entry_points, "{}", theirs.label());
            assert_eq!(slots(&a.bindings), slots(&b.bindings), "{}", theirs.label());
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}
