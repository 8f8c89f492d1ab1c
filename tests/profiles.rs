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
