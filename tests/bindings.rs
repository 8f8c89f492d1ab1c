//! Typed bindings (`wgsl_variants::bindings`): the snapshot of `standard/Deferred`'s module,
//! the offsets it asserts against naga's layouter for structs that need padding, and one
//! crate that compiles the module of every pass of the bundled library (so that every
//! size, alignment and offset assertion is checked by rustc) and runs the typed keys; and that
//! the modules the compile-fail tests (`crates/bindings-compile-fail`) and the `render_variant`
//! example use are current.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

use wgsl_variants::{Library, Pass, Space};

/// A pass whose buffers need every kind of padding: a `vec3` followed by an `f32`, an array
/// of `vec3`, a nested struct, a `mat3x3`, an array of structs and a runtime-sized array.
const PADDING: &str = "#shader padding\n#pass P\n#pragma multi_compile _ WIDE\n\
struct Inner {\n    a: vec2<f32>,\n    b: f32,\n}\n\
struct Params {\n    v: vec3<f32>,\n    s: f32,\n    arr: array<vec3<f32>, 3>,\n    inner: Inner,\n    m: mat3x3<f32>,\n    items: array<Inner, 2>,\n    u: u32,\n#if WIDE\n    w: vec4<f32>,\n#endif\n}\n\
struct Lights {\n    count: u32,\n    lights: array<vec3<f32>>,\n}\n\
@group(0) @binding(0) var<uniform> params: Params;\n\
@group(0) @binding(1) var<storage, read> lights: Lights;\n\
@vertex fn vs(@location(0) position: vec3<f32>, @location(1) uv: vec2<f32>) -> @builtin(position) vec4<f32> {\n\
    return vec4<f32>(position + params.v * params.s + params.m[0] + params.arr[2] + lights.lights[0], uv.x + params.inner.b + params.items[1].b + f32(params.u + lights.count));\n}\n\
@fragment fn fs() -> @location(0) vec4<f32> {\n\
#if WIDE\n    return params.w;\n#else\n    return vec4<f32>(1.0);\n#endif\n}\n#endpass\n";

fn padding_library() -> Library {
    Library::from_sources([("padding.wgsl", PADDING)]).unwrap()
}

/// `(struct, field) → offset` of every `offset_of!` assertion of a generated module.
fn asserted_offsets(code: &str) -> BTreeMap<(String, String), u32> {
    let mut out = BTreeMap::new();
    for line in code.lines() {
        let Some(rest) = line.trim().strip_prefix("assert!(core::mem::offset_of!(") else {
            continue;
        };
        let (args, value) = rest.split_once(") == ").unwrap();
        let (name, field) = args.split_once(", ").unwrap();
        let value: u32 = value.trim_end_matches(");").parse().unwrap();
        out.insert((name.to_string(), field.to_string()), value);
    }
    out
}

/// `struct → size` of every `size_of` assertion.
fn asserted_sizes(code: &str) -> BTreeMap<String, u32> {
    let mut out = BTreeMap::new();
    for line in code.lines() {
        let Some(rest) = line.trim().strip_prefix("assert!(core::mem::size_of::<") else {
            continue;
        };
        let (name, value) = rest.split_once(">() == ").unwrap();
        out.insert(
            name.to_string(),
            value.trim_end_matches(");").parse().unwrap(),
        );
    }
    out
}

/// Every member offset and struct size naga gives the padding pass's variant, against the
/// generated assertions: `vec3` then `f32` share 16 bytes, arrays of `vec3` have a stride of
/// 16, `mat3x3` columns are 16 bytes apart, a runtime-sized array's head ends at the array.
#[test]
fn padding_offsets_are_naga_layouts() {
    let lib = padding_library();
    let generated = lib.bindings("padding", "P", 100).unwrap();
    let offsets = asserted_offsets(&generated.code);
    let sizes = asserted_sizes(&generated.code);
    for keywords in [&[] as &[&str], &["WIDE"]] {
        let v = lib.variant("padding", "P", keywords).unwrap();
        let (module, _) = lib.naga_module(&v).unwrap();
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).unwrap();
        for (handle, ty) in module.types.iter() {
            let naga::TypeInner::Struct { members, span } = &ty.inner else {
                continue;
            };
            let wgsl = ty.name.clone().unwrap();
            // `Params` has two layouts (with and without `w`): `Params` and `Params2`.
            let rust = match (wgsl.as_str(), keywords.is_empty()) {
                ("Params", false) => "Params2".to_string(),
                _ => wgsl.clone(),
            };
            let mut checked = 0;
            for m in members {
                let name = m.name.clone().unwrap();
                if let naga::TypeInner::Array {
                    size: naga::ArraySize::Dynamic,
                    stride,
                    ..
                } = module.types[m.ty].inner
                {
                    // The head ends where the runtime-sized array starts.
                    assert_eq!(sizes[&rust], m.offset, "{rust}: head size");
                    assert_eq!(stride, 16, "array<vec3<f32>> stride");
                    assert!(
                        generated
                            .code
                            .contains(&format!("pub type {rust}Element = Vec3F32Stride16;"))
                    );
                    continue;
                }
                assert_eq!(
                    offsets.get(&(rust.clone(), name.clone())),
                    Some(&m.offset),
                    "{rust}.{name}"
                );
                checked += 1;
            }
            assert!(checked > 0);
            if rust != "Lights" {
                assert_eq!(sizes[&rust], *span, "{rust}: size");
                assert_eq!(layouter[handle].size, *span);
            }
        }
    }
    // The shapes the WGSL rules give, spelled out.
    assert_eq!(offsets[&("Params".into(), "s".into())], 12);
    assert_eq!(offsets[&("Params".into(), "arr".into())], 16);
    assert_eq!(offsets[&("Params".into(), "inner".into())], 64);
    assert_eq!(offsets[&("Params".into(), "m".into())], 80);
    assert_eq!(sizes["Vec3F32Stride16"], 16);
    assert!(generated.code.contains("pub arr: [Vec3F32Stride16; 3],"));
    assert!(generated.code.contains("pub m: [[f32; 4]; 3],"));
    assert!(generated.code.contains("pub inner: Inner,"));
}

/// The key of the padding pass: a bool for `_ WIDE`, and the interface it picks lists the
/// uniform buffer's Rust type and the packed vertex inputs.
#[test]
fn padding_key_and_interface() {
    let code = padding_library()
        .bindings("padding", "P", 100)
        .unwrap()
        .code;
    assert!(code.contains("    pub wide: bool,"), "{code}");
    assert!(code.contains("rust_type: \"Params2\""));
    assert!(code.contains(
        "VertexAttribute { location: 1, name: \"uv\", format: VertexFormat::Float32x2, offset: 12 }"
    ));
    assert!(code.contains("vertex_stride: 20,"));
}

/// The plain module names no wgpu type; with the wgpu option the module is the same plus the
/// wgpu conversions (compiled and run against wgpu by the GPU crate's `gpu_bindings` tests).
#[test]
fn wgpu_option_adds_only_the_wgpu_conversions() {
    let lib = padding_library();
    let pass = lib.pass("padding", "P").unwrap();
    let plain = wgsl_variants::bindings::generate(&lib, pass, 100)
        .unwrap()
        .code;
    let options = wgsl_variants::bindings::Options::default().wgpu(true);
    let wgpu = wgsl_variants::bindings::generate_with(&lib, pass, 100, &options)
        .unwrap()
        .code;
    assert!(!plain.contains("wgpu::"), "{plain}");
    assert!(wgpu.contains("and `wgpu` 30."));
    assert!(wgpu.contains(
        "pub fn bind_group_layout_entries(&self, group: u32) -> Vec<wgpu::BindGroupLayoutEntry> {"
    ));
    // Every line of the plain module is in the wgpu one, in order (only the header differs),
    // and the wgpu one less its conversions block is the plain one.
    let mut lines = wgpu.lines();
    for line in plain.lines().filter(|l| !l.starts_with("// It needs")) {
        assert!(lines.any(|l| l == line), "missing: {line}");
    }
    assert_eq!(without_wgpu(&wgpu), plain);
}

/// A module generated with the wgpu option, less its wgpu conversions (one block) and with the
/// plain module's header line: the plain module (`wgpu_option_adds_only_the_wgpu_conversions`).
fn without_wgpu(wgpu: &str) -> String {
    let start = wgpu.find("/// The interfaces as wgpu's types").unwrap();
    let end = wgpu.find("pub use tables::").unwrap();
    format!("{}{}", &wgpu[..start], &wgpu[end..]).replace(
        "// It needs `bytemuck` with the `derive` and `min_const_generics` features, and `wgpu` 30.",
        "// It needs `bytemuck` with the `derive` and `min_const_generics` features.",
    )
}

/// The passes the `render_variant` example draws through (their committed modules are
/// generated with the wgpu option).
const EXAMPLE_MODULES: [(&str, &str); 2] = [
    ("standard", "Deferred"),
    ("universal_lit", "UniversalGBuffer"),
];

/// One bundled pass through the generator.
struct Bundled {
    shader: String,
    pass: String,
    /// The plain module.
    generated: wgsl_variants::bindings::Generated,
    /// The module with the wgpu option, for [`EXAMPLE_MODULES`]' passes.
    wgpu: Option<String>,
    /// How long the generator took.
    seconds: f64,
}

/// The passes of the bundled library that CI generates, through the generator (plain data),
/// each with the time it took, generated once for the tests that read them: every pass the
/// tests' selection builds whole (`test_support::selection::FULL_UP_TO`, 8192 variants) and
/// the example's two ([`EXAMPLE_MODULES`]). The generator compiles every distinct text of a
/// pass's full space, so the three other large passes (`ForwardBase`, `ForwardAdd`,
/// `UniversalForward`: 2.5 minutes on 2 cores) are [`full_space_every_pass_compiles`]'s.
fn bundled_modules() -> &'static [Bundled] {
    static MODULES: std::sync::OnceLock<Vec<Bundled>> = std::sync::OnceLock::new();
    MODULES.get_or_init(|| {
        let lib = wgsl_variants_shaders::library().unwrap();
        lib.passes()
            .filter(|pass| {
                is_example(pass)
                    || Space::full(pass).count()
                        <= num_bigint::BigUint::from(test_support::selection::FULL_UP_TO)
            })
            .map(|pass| generate(&lib, pass))
            .collect()
    })
}

/// Whether `pass` is one of [`EXAMPLE_MODULES`].
fn is_example(pass: &Pass) -> bool {
    EXAMPLE_MODULES
        .iter()
        .any(|(s, p)| pass.shader == *s && pass.name == *p)
}

/// `pass` through the generator. The example's passes are generated once, with the wgpu
/// option; their plain module is that less its wgpu block ([`without_wgpu`]).
fn generate(lib: &Library, pass: &Pass) -> Bundled {
    let one = std::time::Instant::now();
    let example = is_example(pass);
    let options = wgsl_variants::bindings::Options::default().wgpu(example);
    let mut generated =
        wgsl_variants::bindings::generate_with(lib, pass, 1_000_000, &options).unwrap();
    let wgpu = example.then(|| {
        let plain = without_wgpu(&generated.code);
        std::mem::replace(&mut generated.code, plain)
    });
    Bundled {
        shader: pass.shader.clone(),
        pass: pass.name.clone(),
        generated,
        wgpu,
        seconds: one.elapsed().as_secs_f64(),
    }
}

/// The bundled pass `shader/pass`.
fn bundled(shader: &str, pass: &str) -> &'static Bundled {
    bundled_modules()
        .iter()
        .find(|b| b.shader == shader && b.pass == pass)
        .unwrap()
}

/// `wgsl-variants bindings standard Deferred`, as a snapshot (`snapshots/bindings.*`), and
/// with the wgpu option the module the `render_variant` example draws through, committed
/// there.
#[test]
fn snapshot_standard_deferred() {
    let deferred = bundled("standard", "Deferred");
    let wgpu = deferred.wgpu.as_deref().unwrap();
    assert_example_module_is_current(wgpu, "standard", "Deferred", "standard_deferred.rs");
    insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
        insta::assert_snapshot!("bindings.standard.Deferred", deferred.generated.code);
    });
}

/// The module of `universal_lit/UniversalGBuffer` with the wgpu option, that the
/// `render_variant` example draws URP's G-buffer through, is current.
#[test]
fn example_universal_gbuffer_module_is_current() {
    let gbuffer = bundled("universal_lit", "UniversalGBuffer");
    assert_example_module_is_current(
        gbuffer.wgpu.as_deref().unwrap(),
        "universal_lit",
        "UniversalGBuffer",
        "universal_gbuffer.rs",
    );
}

/// `code` is the committed `file` of the `render_variant` example: the module of
/// `shader/pass` generated with the wgpu option.
fn assert_example_module_is_current(code: &str, shader: &str, pass: &str, file: &str) {
    let dir = "crates/wgsl-variants-gpu/examples/render_variant";
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir).join(file);
    assert!(
        std::fs::read_to_string(&example).unwrap() == code,
        "{} differs from the generator's output; regenerate with\n  cargo run --release \
         --ignore-rust-version -p wgsl-variants-cli -- bindings {shader} {pass} --wgpu \
         --out {dir}/{file}",
        example.display()
    );
}

/// The folder the check crate builds in: kept between runs, so `bytemuck` builds once.
fn check_target() -> PathBuf {
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("target"));
    target.join("bindings-check")
}

/// What the check crate's `main` runs: the typed keys refuse impossible combinations with a
/// typed error, and give the keywords and interfaces of possible ones.
const CHECK_MAIN: &str = r#"
fn main() {
    use deferred_shading_lighting::{keywords, Key, KeyError, Keywords};
    let err = Key::new(Keywords {
        set0: keywords::Set0::Point,
        shadows: keywords::Shadows::Depth,
        ..Keywords::default()
    })
    .unwrap_err();
    assert_eq!(
        err,
        KeyError::Excludes {
            keyword: "SHADOWS_DEPTH",
            excluded: "POINT"
        }
    );
    let ok = Key::new(Keywords {
        set0: keywords::Set0::Spot,
        shadows: keywords::Shadows::Depth,
        ..Keywords::default()
    })
    .unwrap();
    assert_eq!(ok.keywords(), ["SPOT", "SHADOWS_DEPTH"]);

    use stencil_deferred_directionallit as dl;
    let err = dl::Key::new(dl::Keywords {
        main_light_shadows: dl::keywords::MainLightShadows::On,
        ..dl::Keywords::DEFAULT
    })
    .unwrap_err();
    assert_eq!(
        err,
        dl::KeyError::Requires {
            keyword: "_MAIN_LIGHT_SHADOWS",
            required: "_DEFERRED_MAIN_LIGHT"
        }
    );
    assert!(err.to_string().contains("requires"));
    // A requirement with alternatives: soft shadows need one of the two shadow modes.
    let err = dl::Key::new(dl::Keywords {
        deferred_main_light: true,
        shadows_soft: true,
        ..dl::Keywords::DEFAULT
    })
    .unwrap_err();
    assert_eq!(
        err,
        dl::KeyError::Requires {
            keyword: "_SHADOWS_SOFT",
            required: "_MAIN_LIGHT_SHADOWS or _MAIN_LIGHT_SHADOWS_CASCADE"
        }
    );
    let soft = dl::Key::new(dl::Keywords {
        deferred_main_light: true,
        main_light_shadows: dl::keywords::MainLightShadows::Cascade,
        shadows_soft: true,
        ..dl::Keywords::DEFAULT
    })
    .unwrap();
    assert!(soft.keywords().contains(&"_MAIN_LIGHT_SHADOWS_CASCADE"));

    use standard_deferred as sd;
    const KEY: sd::Key = sd::Key::checked(sd::Keywords {
        normal_map: true,
        ..sd::Keywords::DEFAULT
    });
    assert_eq!(KEY.keywords(), ["_NORMAL_MAP"]);
    let with = KEY.interface();
    let without = sd::Key::new(sd::Keywords::DEFAULT).unwrap().interface();
    let normal_map = |i: &sd::Interface| i.bindings.iter().any(|b| b.name == "normal_map");
    assert!(normal_map(with) && !normal_map(without));
    assert!(KEY.index() < sd::Key::COMBINATIONS);
    println!("keys ok");
}
"#;

/// Generates the module of each of CI's passes ([`bundled_modules`]: every pass of up to 8192
/// variants and the example's two) and of the padding pass, checks each with `rustfmt
/// --check`, compiles them all in one crate depending on `bytemuck` (offline, the version of
/// the workspace's lock file) and runs the typed keys. (That an impossible `Key::checked`
/// constant does not compile is the compile-fail tests' job: `crates/bindings-compile-fail`.)
#[test]
fn passes_compile_with_their_layout_assertions() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let bundled: Vec<&Bundled> = bundled_modules().iter().collect();
    let left: Vec<String> = lib
        .passes()
        .filter(|p| {
            !bundled
                .iter()
                .any(|b| b.shader == p.shader && b.pass == p.name)
        })
        .map(|p| format!("{}/{}", p.shader, p.name))
        .collect();
    assert_eq!(
        left,
        [
            "standard/ForwardBase",
            "standard/ForwardAdd",
            "universal_lit/UniversalForward"
        ]
    );
    compile_with_layout_assertions(&bundled);
}

/// [`passes_compile_with_their_layout_assertions`] over every pass of the bundled library,
/// the three large ones the example does not use included. About 4 minutes on 2 cores (the
/// fresh-clone CI run of 2026-11-29, when this was CI's form):
/// `cargo test --release --ignore-rust-version --test bindings -- --ignored`.
#[test]
#[ignore = "every pass's full space: cargo test --release --test bindings -- --ignored"]
fn full_space_every_pass_compiles() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let rest: Vec<Bundled> = lib
        .passes()
        .filter(|pass| {
            !bundled_modules()
                .iter()
                .any(|b| b.shader == pass.shader && b.pass == pass.name)
        })
        .map(|pass| generate(&lib, pass))
        .collect();
    let mut bundled: Vec<&Bundled> = bundled_modules().iter().chain(&rest).collect();
    assert_eq!(bundled.len(), lib.passes().count());
    bundled.sort_by_key(|b| {
        lib.passes()
            .position(|p| p.shader == b.shader && p.name == b.pass)
    });
    compile_with_layout_assertions(&bundled);
}

/// Writes the modules of `bundled` and of the padding pass into one crate, checks each with
/// `rustfmt --check`, builds the crate and runs [`CHECK_MAIN`].
fn compile_with_layout_assertions(bundled: &[&Bundled]) {
    // Kept after the run (under the target folder), to read or build again by hand.
    let crate_dir = check_target().join("crate");
    let _ = std::fs::remove_dir_all(&crate_dir);
    let src = crate_dir.join("src");
    std::fs::create_dir_all(&src).unwrap();
    let mut lib_rs = String::new();
    let started = std::time::Instant::now();
    let padding = padding_library().bindings("padding", "P", 100).unwrap();
    let mut modules = vec![("padding_p".to_string(), &padding)];
    for b in bundled {
        let generated = &b.generated;
        eprintln!(
            "{}/{}: {} variants, {} distinct texts, {} structs, {} interfaces in {:.1} s",
            b.shader,
            b.pass,
            generated.variants,
            generated.distinct_texts,
            generated.structs,
            generated.interfaces,
            b.seconds,
        );
        let name = format!("{}_{}", b.shader, b.pass).to_lowercase();
        modules.push((name, generated));
    }
    eprintln!(
        "generated {} modules in {:.1?}",
        modules.len(),
        started.elapsed()
    );
    let mut unformatted = String::new();
    for (name, generated) in &modules {
        let file = src.join(format!("{name}.rs"));
        std::fs::write(&file, &generated.code).unwrap();
        let fmt = Command::new("rustfmt")
            .args(["--check", "--edition", "2024"])
            .arg(&file)
            .output();
        match fmt {
            Ok(out) if !out.status.success() => {
                unformatted.push_str(&format!(
                    "{name}: not rustfmt-clean:\n{}\n",
                    String::from_utf8_lossy(&out.stdout)
                ));
            }
            Ok(_) => {}
            Err(e) => eprintln!("rustfmt not run ({e})"),
        }
        lib_rs.push_str(&format!(
            "#[allow(dead_code)]\nmod {name} {{\n    include!(\"{name}.rs\");\n}}\n"
        ));
    }
    assert!(unformatted.is_empty(), "{unformatted}");
    lib_rs.push_str(CHECK_MAIN);
    std::fs::write(src.join("main.rs"), lib_rs).unwrap();
    std::fs::write(
        crate_dir.as_path().join("Cargo.toml"),
        "[package]\nname = \"bindings-check\"\nversion = \"0.0.0\"\nedition = \"2024\"\npublish = false\n\n\
         [dependencies]\nbytemuck = { version = \"1\", features = [\"derive\", \"min_const_generics\"] }\n\n\
         [workspace]\n",
    )
    .unwrap();
    // The workspace's lock file pins bytemuck and its derive's dependencies: offline works.
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.lock"),
        crate_dir.as_path().join("Cargo.lock"),
    )
    .unwrap();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let started = std::time::Instant::now();
    let out = Command::new(&cargo)
        .args(["run", "--offline", "--quiet"])
        .current_dir(crate_dir.as_path())
        .env("CARGO_TARGET_DIR", check_target())
        .env_remove("RUSTFLAGS")
        .output()
        .unwrap();
    eprintln!("check crate built and ran in {:.1?}", started.elapsed());
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&out.stdout), "keys ok\n");
}

/// The module the compile-fail tests (`crates/bindings-compile-fail`, trybuild) compile
/// against is committed there, so that their build needs only `bytemuck`: it must be what the
/// generator writes for its `shaders/keys.wgsl` today.
#[test]
fn compile_fail_module_is_current() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/bindings-compile-fail");
    let lib = Library::from_dir(dir.join("shaders")).unwrap();
    let code = lib.bindings("keys", "P", 100).unwrap().code;
    let committed = std::fs::read_to_string(dir.join("src/keys.rs")).unwrap();
    assert!(
        code == committed,
        "crates/bindings-compile-fail/src/keys.rs differs from the generator's output; \
         regenerate with\n  cargo run --release --ignore-rust-version -p wgsl-variants-cli -- \
         --root crates/bindings-compile-fail/shaders bindings keys P \
         --out crates/bindings-compile-fail/src/keys.rs"
    );
}

/// `Bake::bindings`: a `build.rs` bake writes the module per pass that `bindings` writes, with
/// the bake's table added (`Key::baked`, `KeyError::NotBaked`), and an index file that includes
/// each in a module of its own.
#[test]
fn bake_writes_the_bindings_of_each_pass() {
    let tree = tempfile::tempdir().unwrap();
    std::fs::write(tree.path().join("padding.wgsl"), PADDING).unwrap();
    let out = tempfile::tempdir().unwrap();
    wgsl_variants::bake::Bake::new(tree.path())
        .bindings(true)
        .write_to(out.path())
        .unwrap();
    let index = std::fs::read_to_string(out.path().join("wgsl_variants_bindings.rs")).unwrap();
    assert!(index.contains("pub mod padding_p {"), "{index}");
    let module =
        std::fs::read_to_string(out.path().join("wgsl_variants_bindings/padding_p.rs")).unwrap();
    let plain = padding_library()
        .bindings("padding", "P", 100)
        .unwrap()
        .code;
    assert!(module.contains("pub fn baked<V>(") && module.contains("KeyError::NotBaked"));
    assert!(!plain.contains("pub fn baked<V>(") && !plain.contains("NotBaked"));
    // The structs, written after the tables, are the same.
    let structs =
        |code: &str| code[code.find("/// The types of the pass's buffers").unwrap()..].to_string();
    assert_eq!(structs(&module), structs(&plain));
}

/// The bake fixture of the compile-fail tests: a pass with two `shader_feature` sets and a
/// `multi_compile`, and one material that uses `NORMAL_MAP`, so a bake strips every variant
/// with `DETAIL` or without `NORMAL_MAP`.
fn baked_fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/bindings-compile-fail/baked")
}

/// Bakes the fixture with bindings into `out`.
fn bake_fixture(out: &Path) -> wgsl_variants::bake::Baked {
    let tree = tempfile::tempdir().unwrap();
    std::fs::copy(
        baked_fixture().join("lit.wgsl"),
        tree.path().join("lit.wgsl"),
    )
    .unwrap();
    wgsl_variants::bake::Bake::new(tree.path())
        .materials(baked_fixture().join("materials.toml"))
        .file_name("shaders.rs")
        .bindings(true)
        .write_to(out)
        .unwrap()
}

/// The baked module the `NotBaked` compile-fail case compiles against
/// (`crates/bindings-compile-fail/src/baked_keys.rs`) is what a bake of its fixture writes
/// today. `WGSL_VARIANTS_UPDATE=1` rewrites it.
#[test]
fn compile_fail_baked_module_is_current() {
    let out = tempfile::tempdir().unwrap();
    bake_fixture(out.path());
    let code = std::fs::read_to_string(out.path().join("wgsl_variants_bindings/lit_p.rs")).unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("crates/bindings-compile-fail/src/baked_keys.rs");
    if std::env::var("WGSL_VARIANTS_UPDATE").is_ok_and(|v| v == "1") {
        std::fs::write(&path, &code).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        code == committed,
        "crates/bindings-compile-fail/src/baked_keys.rs differs from what the bake writes; \
         regenerate with\n  WGSL_VARIANTS_UPDATE=1 cargo test --release --ignore-rust-version \
         --test bindings compile_fail_baked_module_is_current"
    );
}

/// What the bake crate's `main` runs: a typed key finds the variant the string lookup finds,
/// and a combination the materials strip is refused with a typed error.
const BAKE_MAIN: &str = r#"
mod shaders {
    include!(concat!(env!("OUT"), "/shaders.rs"));
}
mod bindings {
    include!(concat!(env!("OUT"), "/wgsl_variants_bindings.rs"));
}

fn main() {
    use bindings::lit_p::{Key, KeyError, Keywords};
    for fog in [false, true] {
        let key = Key::new(Keywords {
            normal_map: true,
            fog,
            ..Keywords::DEFAULT
        })
        .unwrap();
        let typed = key.baked(shaders::variants());
        let by_strings = shaders::variant("lit", "P", &key.keywords()).unwrap();
        assert!(std::ptr::eq(typed, by_strings));
        assert_eq!(typed.keywords, key.keywords());
        assert!(typed.wgsl.unwrap().contains("0.5"));
    }
    // Stripped by the materials: refused by the key and by the string lookup alike.
    for keywords in [
        Keywords::DEFAULT,
        Keywords {
            normal_map: true,
            detail: true,
            fog: false,
        },
    ] {
        assert_eq!(Key::new(keywords), Err(KeyError::NotBaked));
        let mut on = Vec::new();
        for (is_on, k) in [
            (keywords.normal_map, "NORMAL_MAP"),
            (keywords.detail, "DETAIL"),
            (keywords.fog, "FOG"),
        ] {
            if is_on {
                on.push(k);
            }
        }
        assert!(matches!(
            shaders::variant("lit", "P", &on),
            Err(shaders::LookupError::NotBaked { .. })
        ));
    }
    assert_eq!(
        KeyError::NotBaked.to_string(),
        "not in the bake's build set"
    );
    // What a refused `Key::checked` constant says.
    assert_eq!(
        KeyError::NotBaked.rule(),
        "the bake left the combination out (materials, cover, budget)"
    );
    const KEY: Key = Key::checked(Keywords {
        normal_map: true,
        ..Keywords::DEFAULT
    });
    assert_eq!(KEY.baked(shaders::variants()).keywords, ["NORMAL_MAP"]);
    println!("baked ok");
}
"#;

/// `Bake::bindings` with materials: each key indexes the bake's `variants()` directly
/// (`Key::baked`, no keyword strings) and finds the entry the string lookup finds; `Key::new`
/// refuses what the materials strip (`KeyError::NotBaked`). The generated module is
/// rustfmt-clean, and a small crate including both generated files builds and runs.
#[test]
fn bake_bindings_key_finds_its_baked_variant() {
    let crate_dir = check_target().join("bake-crate");
    let _ = std::fs::remove_dir_all(&crate_dir);
    let out = crate_dir.join("out");
    std::fs::create_dir_all(crate_dir.join("src")).unwrap();
    let baked = bake_fixture(&out);
    // NORMAL_MAP on, DETAIL off (the material) × FOG off and on.
    assert_eq!(baked.variants, 2);
    let module = out.join("wgsl_variants_bindings/lit_p.rs");
    let code = std::fs::read_to_string(&module).unwrap();
    assert!(
        code.contains("pub const BAKED_VARIANTS: usize = 2;"),
        "{code}"
    );
    // Key::index: NORMAL_MAP, DETAIL, FOG, the last fastest; the 2 baked are 4 and 5.
    assert!(
        code.contains(
            "pub const BAKED: [u32; 8] = [\n        4294967295, 4294967295, 4294967295, \
             4294967295, 0, 1, 4294967295, 4294967295,\n    ];"
        ),
        "{code}"
    );
    let fmt = Command::new("rustfmt")
        .args(["--check", "--edition", "2024"])
        .arg(&module)
        .output()
        .expect("rustfmt runs");
    assert!(
        fmt.status.success(),
        "not rustfmt-clean:\n{}",
        String::from_utf8_lossy(&fmt.stdout)
    );
    std::fs::write(crate_dir.join("src/main.rs"), BAKE_MAIN).unwrap();
    std::fs::write(
        crate_dir.join("Cargo.toml"),
        "[package]\nname = \"bake-check\"\nversion = \"0.0.0\"\nedition = \"2024\"\npublish = false\n\n\
         [dependencies]\nbytemuck = { version = \"1\", features = [\"derive\", \"min_const_generics\"] }\n\n\
         [workspace]\n",
    )
    .unwrap();
    // The workspace's lock file pins bytemuck and its derive's dependencies: offline works.
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.lock"),
        crate_dir.join("Cargo.lock"),
    )
    .unwrap();
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let started = std::time::Instant::now();
    let run = Command::new(&cargo)
        .args(["run", "--offline", "--quiet"])
        .current_dir(&crate_dir)
        .env("CARGO_TARGET_DIR", check_target())
        .env("OUT", &out)
        .env_remove("RUSTFLAGS")
        .output()
        .unwrap();
    eprintln!("bake crate built and ran in {:.1?}", started.elapsed());
    assert!(
        run.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&run.stdout),
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(String::from_utf8_lossy(&run.stdout), "baked ok\n");
}
