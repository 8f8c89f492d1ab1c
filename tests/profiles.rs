//! Device profiles: the same variant is valid on one device and not on another — binding
//! arrays need a desktop device, WebGL2 has no cube array textures, storage buffers or compute
//! shaders — and the profile comes from the declaration file, the API or the command line.

use wgsl_variants::Library;
use wgsl_variants::validate::{Profile, validate_pass};

/// One pass per feature of the device: `ARRAY` reads a binding array of textures, `CUBES` a
/// cube array texture, `STORAGE` a storage buffer; with none the pass needs nothing.
const SHADER: &str = "#shader s
#pass P
#pragma multi_compile _ ARRAY CUBES STORAGE
#import lit
#endpass
";

const TREE: &str = "#ifdef ARRAY
enable wgpu_binding_array;
@group(0) @binding(0) var textures: binding_array<texture_2d<f32>, 4>;
#endif
#ifdef CUBES
@group(0) @binding(1) var cubes: texture_cube_array<f32>;
#endif
#ifdef STORAGE
@group(0) @binding(2) var<storage> values: array<vec4<f32>>;
#endif
@group(0) @binding(3) var s: sampler;

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    var c = vec4<f32>(0.0);
#ifdef ARRAY
    c += textureSample(textures[1], s, vec2<f32>(0.5));
#endif
#ifdef CUBES
    c += textureSample(cubes, s, vec3<f32>(0.0, 0.0, 1.0), 0);
#endif
#ifdef STORAGE
    c += values[0];
#endif
    return c;
}
";

/// The keyword sets that fail on `profile`, with the first error's message.
fn failing(profile: Profile) -> Vec<(String, String)> {
    let mut lib = Library::from_sources([("main.wgsl", SHADER), ("lit.wgsl", TREE)]).unwrap();
    lib.set_profile(profile);
    let pass = lib.pass("s", "P").unwrap();
    let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    let report = validate_pass(&lib, pass, &choices, &|_| {});
    assert_eq!(report.built, 4);
    report
        .failures
        .iter()
        .map(|f| (f.keyword_sets[0].join(" "), f.error.message.clone()))
        .collect()
}

#[test]
fn each_profile_refuses_what_its_device_lacks() {
    let webgpu = failing(Profile::WebGpu);
    assert_eq!(webgpu.len(), 1, "{webgpu:?}");
    assert_eq!(webgpu[0].0, "ARRAY");
    assert!(
        webgpu[0].1.contains("TEXTURE_AND_SAMPLER_BINDING_ARRAY"),
        "{webgpu:?}"
    );

    assert!(failing(Profile::Desktop).is_empty());

    let webgl2 = failing(Profile::WebGl2);
    let sets: Vec<&str> = webgl2.iter().map(|(k, _)| k.as_str()).collect();
    assert_eq!(sets, ["ARRAY", "CUBES", "STORAGE"], "{webgl2:?}");
    assert!(webgl2[1].1.contains("CUBE_ARRAY_TEXTURES"), "{webgl2:?}");
    assert!(
        webgl2[2].1.contains("on profile `webgl2`")
            && webgl2[2].1.contains("`values` is a storage buffer"),
        "{webgl2:?}"
    );

    // An explicit list: binding arrays and nothing else.
    let listed: Profile = "TEXTURE_AND_SAMPLER_BINDING_ARRAY".parse().unwrap();
    let sets: Vec<String> = failing(listed).into_iter().map(|(k, _)| k).collect();
    assert_eq!(sets, ["CUBES"]);
}

/// The WebGL2 refusal is located at the declaration in the user's module.
#[test]
fn a_webgl2_refusal_points_at_the_resource() {
    let mut lib = Library::from_sources([("main.wgsl", SHADER), ("lit.wgsl", TREE)]).unwrap();
    lib.set_profile(Profile::WebGl2);
    let v = lib.variant("s", "P", &["STORAGE"]).unwrap();
    let e = lib.naga_module(&v).unwrap_err();
    let at = e
        .labels
        .first()
        .map(|(span, _)| lib.files().location(*span).to_string());
    assert_eq!(at.as_deref(), Some("lit.wgsl:9:23"), "{e:?}");
}

/// A declaration file names the tree's profile; an unknown name is an error at it.
#[test]
fn the_declaration_file_names_the_profile() {
    let sources = [(
        "main.wesl",
        "@group(0) @binding(0) var<storage> values: array<vec4<f32>>;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return values[0];\n}\n",
    )];
    let declaration = |profile: &str| {
        format!(
            "dialect = \"wesl\"\nprofile = \"{profile}\"\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\n"
        )
    };
    let lib = Library::from_declared_sources(&declaration("webgl2"), sources).unwrap();
    assert_eq!(lib.profile(), Profile::WebGl2);
    let v = lib.variant("s", "P", &[] as &[&str]).unwrap();
    assert!(
        lib.naga_module(&v)
            .unwrap_err()
            .message
            .contains("storage buffer")
    );
    let lib = Library::from_declared_sources(&declaration("webgpu"), sources).unwrap();
    assert!(
        lib.naga_module(&lib.variant("s", "P", &[] as &[&str]).unwrap())
            .is_ok()
    );

    let e = Library::from_declared_sources(&declaration("webgl3"), sources).unwrap_err();
    let shown = e.render(false);
    assert!(shown.contains("unknown profile `webgl3`"), "{shown}");
    assert_eq!(e.locations(), ["wgsl-variants.toml:2:11"], "{shown}");
}

/// The keyword sets failing on each profile when the library validates for all three at once.
fn failing_on_each(
    lib: &Library,
    pass: &str,
) -> (wgsl_variants::validate::PassReport, Vec<Vec<String>>) {
    let pass = lib.pass("s", pass).unwrap();
    let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
    let report = validate_pass(lib, pass, &choices, &|_| {});
    let per_profile = report
        .profiles
        .iter()
        .map(|counts| {
            let mut sets: Vec<String> = report
                .failing_variants()
                .into_iter()
                .filter(|v| v.profiles.contains(&counts.profile))
                .map(|v| v.keywords.join(" "))
                .collect();
            sets.sort();
            sets
        })
        .collect();
    (report, per_profile)
}

/// Several profiles in one run give each profile the verdicts a run of that profile alone
/// gives, per variant, and name the profiles each failure happens on.
#[test]
fn several_profiles_in_one_run_agree_with_one_run_each() {
    let all = [Profile::WebGpu, Profile::WebGl2, Profile::Desktop];
    let mut lib = Library::from_sources([("main.wgsl", SHADER), ("lit.wgsl", TREE)]).unwrap();
    lib.set_profiles(&all);
    let (report, per_profile) = failing_on_each(&lib, "P");
    for (profile, sets) in all.iter().zip(&per_profile) {
        let mut alone: Vec<String> = failing(*profile).into_iter().map(|(k, _)| k).collect();
        alone.sort();
        assert_eq!(&alone, sets, "{}", profile.name());
    }
    let counts: Vec<(String, u64, u64)> = report
        .profiles
        .iter()
        .map(|c| (c.profile.clone(), c.valid, c.invalid))
        .collect();
    assert_eq!(
        counts,
        [
            ("webgpu".to_string(), 3, 1),
            ("webgl2".to_string(), 1, 3),
            ("desktop".to_string(), 4, 0)
        ]
    );
    // Valid on every profile: the variant with no keyword only.
    assert_eq!((report.valid, report.invalid, report.distinct), (1, 3, 4));
    // `ARRAY` fails alike on WebGPU and WebGL2: one failure naming both.
    let array = &report.failures[0];
    assert_eq!(array.keyword_sets, [["ARRAY"]]);
    assert_eq!(array.profiles, ["webgpu", "webgl2"]);
    assert_eq!(report.failures.len(), 3);
}

/// A WESL tree composes each variant once for every profile and locates each profile's error
/// as a run of that profile alone does; a naga_oil tree composes per profile.
#[test]
fn wesl_and_naga_oil_trees_give_each_profile_its_own_error() {
    let wesl = (
        "dialect = \"wesl\"\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"WIDE\", \"STORAGE\"]]\n",
        "@if(STORAGE) @group(0) @binding(0) var<storage> values: array<vec4<f32>>;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    var c = vec4<f32>(0.0);\n    @if(WIDE) { let w: f64 = 1.0lf; c.x = f32(w); }\n    @if(STORAGE) { c = values[0]; }\n    return c;\n}\n",
        "main.wesl",
    );
    // naga_oil's text is naga's WGSL written back, which cannot say `f32(w)` of an `f64`
    // (naga 30 writes a cast its own front end refuses): the desktop-only feature here is a
    // binding array.
    let naga_oil = (
        "[[shader]]\nname = \"s\"\nentry = \"main.wgsl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"WIDE\", \"STORAGE\"]]\n",
        "#ifdef WIDE\nenable wgpu_binding_array;\n@group(0) @binding(1) var textures: binding_array<texture_2d<f32>, 4>;\n@group(0) @binding(2) var smp: sampler;\n#endif\n#ifdef STORAGE\n@group(0) @binding(0) var<storage> values: array<vec4<f32>>;\n#endif\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    var c = vec4<f32>(0.0);\n#ifdef WIDE\n    c = textureSample(textures[1], smp, vec2<f32>(0.5));\n#endif\n#ifdef STORAGE\n    c = values[0];\n#endif\n    return c;\n}\n",
        "main.wgsl",
    );
    for (declaration, source, path) in [wesl, naga_oil] {
        let mut lib = Library::from_declared_sources(declaration, [(path, source)]).unwrap();
        let all = [Profile::WebGpu, Profile::WebGl2, Profile::Desktop];
        lib.set_profiles(&all);
        let (report, per_profile) = failing_on_each(&lib, "P");
        assert_eq!(
            per_profile,
            [vec!["WIDE"], vec!["STORAGE", "WIDE"], vec![]],
            "{path}: {:?}",
            report.failures
        );
        // Each profile's error is the one a run of that profile alone reports.
        for f in &report.failures {
            for name in &f.profiles {
                let profile: Profile = name.parse().unwrap();
                let v = lib.variant("s", "P", &f.keyword_sets[0]).unwrap();
                let alone = lib.naga_module_for(&v, profile).unwrap_err();
                assert_eq!(alone.message, f.error.message, "{path} on {name}");
                assert_eq!(alone.labels, f.error.labels, "{path} on {name}");
            }
        }
    }
}

/// A pass names its own profile in the declaration file, overriding the tree's; the
/// command line's (`set_profiles`) overrides both. The tree may list several.
#[test]
fn a_pass_names_its_own_profile() {
    let sources = [(
        "main.wesl",
        "@group(0) @binding(0) var<storage> values: array<vec4<f32>>;\n@fragment\nfn fs() -> @location(0) vec4<f32> {\n    return values[0];\n}\n",
    )];
    let declaration = |tree: &str, pass: &str| {
        format!(
            "dialect = \"wesl\"\n{tree}\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"Web\"\n{pass}\n[[shader.pass]]\nname = \"Tree\"\n"
        )
    };
    let verdicts = |lib: &Library| -> Vec<(String, Vec<String>, u64)> {
        lib.passes()
            .map(|pass| {
                let choices: Vec<_> = wgsl_variants::Space::full(pass).iter().collect();
                let r = validate_pass(lib, pass, &choices, &|_| {});
                let names = lib.pass_profiles(pass).iter().map(|p| p.name()).collect();
                (pass.name.clone(), names, r.invalid)
            })
            .collect()
    };
    let lib =
        Library::from_declared_sources(&declaration("", "profile = \"webgl2\""), sources).unwrap();
    assert_eq!(
        verdicts(&lib),
        [
            ("Web".to_string(), vec!["webgl2".to_string()], 1),
            ("Tree".to_string(), vec!["webgpu".to_string()], 0)
        ]
    );
    // Two passes on two devices: the reports name their profiles.
    let pass = lib.pass("s", "Web").unwrap();
    let r = validate_pass(
        &lib,
        pass,
        &[wgsl_variants::Space::full(pass).iter().next().unwrap()],
        &|_| {},
    );
    assert_eq!(r.failures[0].profiles, ["webgl2"]);

    let mut lib = Library::from_declared_sources(
        &declaration(
            "profile = [\"desktop\", \"webgl2\"]",
            "profile = \"webgpu\"",
        ),
        sources,
    )
    .unwrap();
    assert_eq!(lib.profiles(), [Profile::Desktop, Profile::WebGl2]);
    assert_eq!(
        verdicts(&lib),
        [
            ("Web".to_string(), vec!["webgpu".to_string()], 0),
            (
                "Tree".to_string(),
                vec!["desktop".to_string(), "webgl2".to_string()],
                1
            )
        ]
    );
    lib.set_profile(Profile::Desktop);
    assert_eq!(
        verdicts(&lib),
        [
            ("Web".to_string(), vec!["desktop".to_string()], 0),
            ("Tree".to_string(), vec!["desktop".to_string()], 0)
        ]
    );

    // An unknown name in a list is an error at that name; an empty list is an error.
    let e = Library::from_declared_sources(
        &declaration("profile = [\"webgpu\", \"webgl3\"]", ""),
        sources,
    )
    .unwrap_err();
    assert_eq!(
        e.locations(),
        ["wgsl-variants.toml:2:22"],
        "{}",
        e.render(false)
    );
    let e = Library::from_declared_sources(&declaration("", "profile = []"), sources).unwrap_err();
    assert!(
        e.render(false).contains("names no device"),
        "{}",
        e.render(false)
    );
    let e = Library::from_declared_sources(&declaration("", "profile = 3"), sources).unwrap_err();
    assert!(
        e.render(false).contains("a list of profiles"),
        "{}",
        e.render(false)
    );
}
