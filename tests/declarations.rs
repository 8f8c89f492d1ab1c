//! The declaration file says what an engine's Rust says: an option that sets several defs (and
//! valued defs) at once, keyword blocks that passes share, defs set on one module, and a
//! warning where a `false` def meets `#ifdef`.

use wgsl_variants::Library;
use wgsl_variants::declaration::DefValue;

/// A naga_oil tree: a tonemapping module read by two entries, and a view module only `lit`
/// imports.
const TONE: &str = "#define_import_path app::tone
fn tone(c: vec3<f32>) -> vec3<f32> {
#ifdef TONEMAP_IN_SHADER
#ifdef TONEMAP_METHOD_ACES
    return c / (c + vec3<f32>(0.6));
#else ifdef TONEMAP_METHOD_REINHARD
    return c / (c + vec3<f32>(1.0)) * f32(#{LUT_BINDING});
#else
    return c * 0.5;
#endif
#else
    return c;
#endif
}
";
const VIEW: &str = "#define_import_path app::view
const MAX_LIGHTS: u32 = #{MAX_LIGHTS}u;
";
const LIT: &str = "#import app::tone::tone
#import app::view::MAX_LIGHTS
@fragment fn fs() -> @location(0) vec4<f32> { return vec4<f32>(tone(vec3<f32>(f32(MAX_LIGHTS))), 1.0); }
";
const UNLIT: &str = "#import app::tone::tone
@fragment fn fs() -> @location(0) vec4<f32> { return vec4<f32>(tone(vec3<f32>(1.0)), 1.0); }
";

const DECLARATION: &str = r#"
[options]
ACES = ["TONEMAP_IN_SHADER", "TONEMAP_METHOD_ACES"]
REINHARD = { TONEMAP_IN_SHADER = true, TONEMAP_METHOD_REINHARD = true, LUT_BINDING = { uint = 18 } }
NO_METHOD = ["TONEMAP_IN_SHADER"]

[blocks.tonemapping]
multi_compile = [["_", "NO_METHOD", "ACES", "REINHARD"]]

[modules."view.wgsl".constants]
MAX_LIGHTS = { uint = 10 }

[[shader]]
name = "lit"
entry = "lit.wgsl"
[[shader.pass]]
name = "Forward"
use = ["tonemapping"]

[[shader]]
name = "unlit"
entry = "unlit.wgsl"
[[shader.pass]]
name = "Forward"
use = ["tonemapping"]
"#;

fn tree(declaration: &str) -> Result<Library, wgsl_variants::LoadError> {
    Library::from_declared_sources(
        declaration,
        [
            ("tone.wgsl", TONE),
            ("view.wgsl", VIEW),
            ("lit.wgsl", LIT),
            ("unlit.wgsl", UNLIT),
        ],
    )
}

/// Every problem of a declaration that does not load, rendered.
fn refused(declaration: &str) -> String {
    let Some(e) = tree(declaration).err() else {
        panic!("the declaration loads:\n{declaration}")
    };
    e.render(false)
}

#[test]
fn an_option_sets_several_defs_and_valued_defs() {
    let lib = tree(DECLARATION).unwrap();
    assert!(lib.warnings().is_empty(), "{:?}", lib.warnings());
    let pass = lib.pass("lit", "Forward").unwrap();
    assert_eq!(
        pass.keyword_defs("REINHARD"),
        [
            ("LUT_BINDING", DefValue::UInt(18)),
            ("TONEMAP_IN_SHADER", DefValue::Bool(true)),
            ("TONEMAP_METHOD_REINHARD", DefValue::Bool(true)),
        ]
    );
    let wgsl = |keywords: &[&str]| lib.wgsl(&lib.variant("lit", "Forward", keywords).unwrap());
    assert!(wgsl(&["ACES"]).contains("0.6"), "{}", wgsl(&["ACES"]));
    assert!(
        wgsl(&["REINHARD"]).contains("18"),
        "{}",
        wgsl(&["REINHARD"])
    );
    assert!(
        wgsl(&["NO_METHOD"]).contains("0.5"),
        "{}",
        wgsl(&["NO_METHOD"])
    );
    let none = wgsl(&[]);
    assert!(!none.contains("0.5") && !none.contains("0.6"), "{none}");
    // The audit reads the options' defs: four variants, four programs, told apart by the
    // static walk (without the valued def, which makes every variant count as distinct).
    let lib = tree(&DECLARATION.replace(", LUT_BINDING = { uint = 18 }", "")).unwrap();
    let pass = lib.pass("lit", "Forward").unwrap();
    let audit = wgsl_variants::audit::audit_pass(&lib, pass, &Default::default()).unwrap();
    assert_eq!(audit.distinct_full_space.count, 4u32.into());
    assert!(audit.distinct_full_space.exact);
}

#[test]
fn a_block_is_shared_by_passes_and_a_misspelt_one_is_named() {
    let lib = tree(DECLARATION).unwrap();
    for shader in ["lit", "unlit"] {
        let pass = lib.pass(shader, "Forward").unwrap();
        let keywords: Vec<&str> = pass.keywords().collect();
        assert_eq!(keywords, ["NO_METHOD", "ACES", "REINHARD"], "{shader}");
    }
    let message = refused(&DECLARATION.replace(
        "use = [\"tonemapping\"]\n\n[[shader]]",
        "use = [\"tonemaping\"]\n\n[[shader]]",
    ));
    assert!(
        message.contains("uses block `tonemaping`, which no `[blocks.tonemaping]` table declares; did you mean `tonemapping`?"),
        "{message}"
    );
}

#[test]
fn module_defs_reach_the_passes_that_compose_the_module() {
    let lib = tree(DECLARATION).unwrap();
    let lit = lib.pass("lit", "Forward").unwrap();
    assert!(
        lit.constants
            .iter()
            .any(|c| c.name == "MAX_LIGHTS" && c.value == DefValue::UInt(10))
    );
    let unlit = lib.pass("unlit", "Forward").unwrap();
    assert!(unlit.constants.is_empty(), "{:?}", unlit.constants);
    let v = lib.variant("lit", "Forward", &[] as &[&str]).unwrap();
    assert!(lib.wgsl(&v).contains("10u"), "{}", lib.wgsl(&v));

    let message = refused(&DECLARATION.replace("[modules.\"view.wgsl\"", "[modules.\"veiw.wgsl\""));
    assert!(
        message.contains("`[modules.\"veiw.wgsl\"]` names no module of the tree")
            && message.contains("did you mean `view.wgsl`?"),
        "{message}"
    );
    let message = refused(&format!(
        "[constants]\nMAX_LIGHTS = {{ uint = 4 }}\n{DECLARATION}"
    ));
    assert!(
        message.contains("`MAX_LIGHTS` is 10u on module `view.wgsl` and 4u for `lit/Forward`"),
        "{message}"
    );
    let message =
        refused(&DECLARATION.replace("MAX_LIGHTS = { uint = 10 }", "TONEMAP_IN_SHADER = true"));
    assert!(
        message.contains("`TONEMAP_IN_SHADER` is set on module `view.wgsl` and by keyword `NO_METHOD` of `lit/Forward`"),
        "{message}"
    );
}

#[test]
fn a_module_no_pass_composes_is_a_warning() {
    let declaration = DECLARATION.replace(
        "[[shader]]\nname = \"lit\"",
        "[modules.\"unused.wgsl\".constants]\nX = 1\n\n[[shader]]\nname = \"lit\"",
    );
    let lib = Library::from_declared_sources(
        &declaration,
        [
            ("tone.wgsl", TONE),
            ("view.wgsl", VIEW),
            ("lit.wgsl", LIT),
            ("unlit.wgsl", UNLIT),
            (
                "unused.wgsl",
                "#define_import_path app::unused\nconst X: i32 = 1;\n",
            ),
        ],
    )
    .unwrap();
    let warnings: Vec<String> = lib.warnings().iter().map(|w| w.message.clone()).collect();
    assert_eq!(
        warnings,
        ["no pass composes module `unused.wgsl`: its defs change nothing"]
    );
}

#[test]
fn options_are_checked() {
    for (from, to, expected) in [
        (
            "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
            "NO_METHOD = []",
            "option `NO_METHOD` sets no def",
        ),
        (
            "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
            "NO_METHOD = [\"TONEMAP IN SHADER\"]",
            "`TONEMAP IN SHADER` is not a def name",
        ),
        (
            "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
            "NO_METHOD = \"TONEMAP_IN_SHADER\"",
            "an option is a list of the defs it sets",
        ),
        (
            "[blocks.tonemapping]\n",
            "[blocks.tonemapping]\noptions = { ACES = [\"TONEMAP_METHOD_ACES\"] }\n",
            "option `ACES` is declared twice with different defs (`TONEMAP_IN_SHADER, TONEMAP_METHOD_ACES` and `TONEMAP_METHOD_ACES`)",
        ),
        (
            "[options]\n",
            "[constants]\nTONEMAP_METHOD_ACES = true\n[options]\n",
            "`TONEMAP_METHOD_ACES` is both set by option `ACES` of pass `Forward` and a constant",
        ),
    ] {
        assert!(DECLARATION.contains(from), "{from}");
        let message = refused(&DECLARATION.replacen(from, to, 1));
        assert!(message.contains(expected), "{expected}\n---\n{message}");
    }
    // A def within two edits of a name the modules read and the pass does not set.
    let message = refused(&DECLARATION.replace(", \"REINHARD\"]]", "]]").replace(
        "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
        "NO_METHOD = [\"TONEMAP_IN_SHADER\", \"TONEMAP_METHOD_REINHART\"]",
    ));
    assert!(
        message.contains("def `TONEMAP_METHOD_REINHART` of option `NO_METHOD` of `lit/Forward` is read by none of the modules it composes, which read `TONEMAP_METHOD_REINHARD`: a typo?"),
        "{message}"
    );
}

#[test]
fn an_option_whose_defs_no_module_reads_is_a_warning() {
    // A block keyword one pass reads and another does not (a vertex stage that does not
    // tonemap): no warning.
    let view = format!("{VIEW}#ifdef FOG\nconst FOG_ON: bool = true;\n#endif\n");
    let lib = Library::from_declared_sources(
        &DECLARATION.replace(
            "multi_compile = [[\"_\", \"NO_METHOD\", \"ACES\", \"REINHARD\"]]",
            "multi_compile = [[\"_\", \"NO_METHOD\", \"ACES\", \"REINHARD\"], [\"_\", \"FOG\"]]",
        ),
        [
            ("tone.wgsl", TONE),
            ("view.wgsl", view.as_str()),
            ("lit.wgsl", LIT),
            ("unlit.wgsl", UNLIT),
        ],
    )
    .unwrap();
    assert!(lib.warnings().is_empty(), "{:?}", lib.warnings());
    // One def read: the option changes variants (an engine pushes defs a tree may not read).
    let lib = tree(&DECLARATION.replace(
        "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
        "NO_METHOD = [\"TONEMAP_IN_SHADER\", \"DEBUG_VIEW\"]",
    ))
    .unwrap();
    assert!(lib.warnings().is_empty(), "{:?}", lib.warnings());
    // None read: it changes nothing.
    let lib = tree(&DECLARATION.replace(
        "NO_METHOD = [\"TONEMAP_IN_SHADER\"]",
        "NO_METHOD = [\"DEBUG_VIEW\", \"DEBUG_NORMALS\"]",
    ))
    .unwrap();
    let warnings: Vec<String> = lib.warnings().iter().map(|w| w.message.clone()).collect();
    assert_eq!(
        warnings,
        [
            "1 declared keyword(s) of `lit/Forward`, `unlit/Forward` appear in none of the modules they compose: NO_METHOD (sets DEBUG_VIEW, DEBUG_NORMALS)"
        ]
    );
}

#[test]
fn a_false_def_tested_by_ifdef_is_a_warning() {
    let lib = tree(&format!(
        "[constants]\nTONEMAP_IN_SHADER = false\n{}",
        DECLARATION
            .replace("\"TONEMAP_IN_SHADER\", ", "")
            .replace("TONEMAP_IN_SHADER = true, ", "")
            .replace("NO_METHOD = [\"TONEMAP_IN_SHADER\"]\n", "")
            .replace("\"NO_METHOD\", ", "")
    ))
    .unwrap();
    assert_eq!(lib.warnings().len(), 1, "{:?}", lib.warnings());
    let rendered = lib.warnings()[0].render(lib.files(), false);
    assert!(
        rendered.contains("`TONEMAP_IN_SHADER` is `false` in lit/Forward, unlit/Forward, and `#ifdef` tests whether a def is set, not its value"),
        "{rendered}"
    );
    assert!(rendered.contains("tone.wgsl:3:1"), "{rendered}");
    // WESL's `@if` reads the value: no warning there (wesl trees are not naga_oil's dialect).
}

#[test]
fn options_set_wesl_features() {
    let lib = Library::from_declared_sources(
        "dialect = \"wesl\"\n[options]\nFANCY = [\"A\", \"B\"]\n[[shader]]\nname = \"s\"\nentry = \"main.wesl\"\n[[shader.pass]]\nname = \"P\"\nmulti_compile = [[\"_\", \"FANCY\"]]\n",
        [(
            "main.wesl",
            "@fragment fn fs() -> @location(0) vec4f {\n    var c = 0.25;\n    @if(A && B) { c = 0.5; }\n    @if(A && !B) { c = 0.75; }\n    return vec4f(c);\n}\n",
        )],
    )
    .unwrap();
    assert!(lib.warnings().is_empty(), "{:?}", lib.warnings());
    let wgsl = |keywords: &[&str]| lib.wgsl(&lib.variant("s", "P", keywords).unwrap());
    let fancy = wgsl(&["FANCY"]);
    assert!(
        fancy.contains("c = 0.5;") && !fancy.contains("0.75"),
        "{fancy}"
    );
    let plain = wgsl(&[]);
    assert!(
        !plain.contains("c = 0.5;") && !plain.contains("0.75"),
        "{plain}"
    );
}

/// A line gizmo as Bevy 0.19/0.20 draws it: `PERSPECTIVE` is pushed to the fragment stage
/// only, yet the vertex entry point's helper tests it.
const LINE: &str = "struct Out { @builtin(position) clip: vec4<f32>, @location(0) uv: f32 };
fn clip_depth(p: vec4<f32>) -> vec4<f32> {
#ifdef PERSPECTIVE
    return vec4<f32>(p.xy, p.z * 0.5, p.w);
#else
    return p;
#endif
}
@vertex fn vertex(@location(0) position: vec3<f32>) -> Out {
    var out: Out;
    out.clip = clip_depth(vec4<f32>(position, 1.0));
    out.uv = 0.0;
    return out;
}
@fragment fn fragment(in: Out) -> @location(0) vec4<f32> {
#ifdef PERSPECTIVE
    let a = in.uv / in.clip.w;
#else
    let a = in.uv;
#endif
#ifdef JOINTS
    return vec4<f32>(a, 1.0, 1.0, 1.0);
#else
    return vec4<f32>(a);
#endif
}
";

const STAGES: &str = r#"
[blocks.lines]
multi_compile = [["_", "JOINTS"]]

[[shader]]
name = "line_gizmo"
entry = "line.wgsl"
[[shader.pass]]
name = "Lines"
use = ["lines"]
multi_compile = [["_", "PERSPECTIVE"]]
values = { WIDTH = [1, 2] }
[shader.pass.stages.vertex]
use = ["lines"]
keywords = ["WIDTH"]
[shader.pass.stages.fragment]
"#;

fn gizmo(declaration: &str) -> Result<Library, wgsl_variants::LoadError> {
    Library::from_declared_sources(
        declaration,
        [(
            "line.wgsl",
            LINE.replace("out.uv = 0.0;", "out.uv = f32(#{WIDTH});")
                .as_str(),
        )],
    )
}

#[test]
fn a_pass_split_into_stages_composes_each_with_its_own_defs() {
    use wgsl_variants::PipelineStage;
    let lib = gizmo(STAGES).unwrap();
    let shader = lib.shader("line_gizmo").unwrap();
    let names: Vec<&str> = shader.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["Lines/vertex", "Lines/fragment"]);
    let vertex = lib.pass("line_gizmo", "Lines/vertex").unwrap();
    let fragment = lib.pass("line_gizmo", "Lines/fragment").unwrap();
    assert_eq!(vertex.stage, Some(PipelineStage::Vertex));
    assert_eq!(fragment.stage, Some(PipelineStage::Fragment));
    // The same space in every stage; the defs differ.
    assert_eq!(
        wgsl_variants::Space::full(vertex).count(),
        wgsl_variants::Space::full(fragment).count()
    );
    assert!(vertex.keyword_defs("PERSPECTIVE").is_empty());
    assert_eq!(
        vertex.keyword_defs("JOINTS"),
        [("JOINTS", DefValue::Bool(true))]
    );
    assert_eq!(
        vertex.keyword_defs("WIDTH=2"),
        [("WIDTH", DefValue::Int(2))]
    );
    assert_eq!(
        fragment.keyword_defs("PERSPECTIVE"),
        [("PERSPECTIVE", DefValue::Bool(true))]
    );
    let keys = ["PERSPECTIVE", "WIDTH=1"];
    let v = lib.wgsl(&lib.variant("line_gizmo", "Lines/vertex", &keys).unwrap());
    let f = lib.wgsl(&lib.variant("line_gizmo", "Lines/fragment", &keys).unwrap());
    assert!(!v.contains("p.z * 0.5") && !v.contains("in.clip.w"), "{v}");
    assert!(f.contains("p.z * 0.5") && f.contains("in.clip.w"), "{f}");
    // The vertex stage's helper tests a def only the fragment stage gets: the audit says so,
    // naming the item that would change; the fragment stage has no such finding.
    let audit = wgsl_variants::audit::audit_pass(&lib, vertex, &Default::default()).unwrap();
    assert_eq!(audit.unpushed_defs.len(), 1, "{:?}", audit.unpushed_defs);
    let finding = &audit.unpushed_defs[0];
    assert_eq!(finding.keyword, "PERSPECTIVE");
    assert_eq!(finding.pushed_to, [PipelineStage::Fragment]);
    assert_eq!(finding.changes, ["clip_depth"]);
    // Not pushed here is not dead here.
    assert!(audit.dead_keywords.is_empty(), "{:?}", audit.dead_keywords);
    assert!(audit.sets.iter().any(|s| s.other_stages));
    let audit = wgsl_variants::audit::audit_pass(&lib, fragment, &Default::default()).unwrap();
    assert!(audit.unpushed_defs.is_empty(), "{:?}", audit.unpushed_defs);
    // Pushing PERSPECTIVE to the vertex stage too, as a fixed Bevy would: no finding.
    let lib = gizmo(&STAGES.replace(
        "keywords = [\"WIDTH\"]",
        "keywords = [\"WIDTH\", \"PERSPECTIVE\"]",
    ))
    .unwrap();
    let vertex = lib.pass("line_gizmo", "Lines/vertex").unwrap();
    let audit = wgsl_variants::audit::audit_pass(&lib, vertex, &Default::default()).unwrap();
    assert!(audit.unpushed_defs.is_empty(), "{:?}", audit.unpushed_defs);
}

#[test]
fn stages_are_checked() {
    let refused = |declaration: &str| match gizmo(declaration) {
        Ok(_) => panic!("the declaration loads:\n{declaration}"),
        Err(e) => e.render(false),
    };
    let message = refused(&STAGES.replace("stages.fragment]", "stages.fragmnet]"));
    assert!(
        message.contains("pass `Lines` has a stage `fragmnet`: a pass's stages are `vertex` and `fragment`; did you mean `fragment`?"),
        "{message}"
    );
    let message = refused(&STAGES.replace("keywords = [\"WIDTH\"]", "keywords = [\"WIDHT\"]"));
    assert!(
        message.contains(
            "names keyword `WIDHT`, which the pass does not declare; did you mean `WIDTH`?"
        ),
        "{message}"
    );
    let message =
        refused(&STAGES.replace("use = [\"lines\"]\nkeywords", "use = [\"line\"]\nkeywords"));
    assert!(
        message.contains(
            "uses block `line`, which the pass does not use (its `use` list); did you mean `lines`?"
        ),
        "{message}"
    );
    let message = refused(&STAGES.replace(
        "[shader.pass.stages.fragment]",
        "[shader.pass.stages.fragment]\nentry = \"lines.wgsl\"",
    ));
    assert!(message.contains("lines.wgsl"), "{message}");
}

#[test]
fn carets_are_sized_and_placed_in_the_source_not_the_substituted_text() {
    let lib = Library::from_declared_sources(
        "dialect = \"naga-oil\"\n[constants]\nCOUNT = { uint = 10 }\n[[shader]]\nname = \"s\"\nentry = \"m.wgsl\"\n[[shader.pass]]\nname = \"P\"\n",
        [(
            "m.wgsl",
            "@fragment fn fs() -> @location(0) vec4<f32> {\n    let n = #{COUNT}; let c = missing_name;\n    return vec4<f32>(f32(n));\n}\n",
        )],
    )
    .unwrap();
    let composed = lib.compose(&lib.variant("s", "P", &[] as &[&str]).unwrap());
    let e = composed.failure.expect("an unknown identifier");
    let (span, _) = &e.labels[0];
    let text = lib.files().text(span.file);
    // naga_oil's text reads `let n = 10u; let c = missing_name;`: the column moved by five.
    assert_eq!(&text[span.range()], "missing_name", "{e:?}");
    assert_eq!(e.location(lib.files()).unwrap().column, 31);
}

#[test]
fn blocks_and_options_are_shared_across_trees_by_an_included_file() {
    // One file of blocks and options, included by two trees' declarations.
    let shared = "[options]\nACES = [\"TONEMAP_IN_SHADER\", \"TONEMAP_METHOD_ACES\"]\n\
                  [blocks.tonemapping]\nmulti_compile = [[\"_\", \"ACES\"]]\n";
    let declaration = "include = [\"shared/tonemapping.toml\"]\n[[shader]]\nname = \"lit\"\n\
                       entry = \"lit.wgsl\"\n[[shader.pass]]\nname = \"Forward\"\nuse = [\"tonemapping\"]\n";
    let load = |shared: &str| {
        Library::from_declared_sources(
            declaration,
            [
                ("shared/tonemapping.toml", shared),
                ("tone.wgsl", TONE),
                ("view.wgsl", VIEW),
                ("lit.wgsl", LIT),
            ],
        )
    };
    let lib = load(shared).unwrap();
    let pass = lib.pass("lit", "Forward").unwrap();
    assert_eq!(pass.keywords().collect::<Vec<_>>(), ["ACES"]);
    assert_eq!(
        pass.keyword_defs("ACES"),
        [
            ("TONEMAP_IN_SHADER", DefValue::Bool(true)),
            ("TONEMAP_METHOD_ACES", DefValue::Bool(true))
        ]
    );
    // Problems in the included file are located in it.
    let Err(e) = load(&shared.replace("[\"_\", \"ACES\"]", "[\"_\", \"ACE S\"]")) else {
        panic!("a bad keyword in the included file loads")
    };
    let rendered = e.render(false);
    assert!(
        rendered.contains("`ACE S` is not a keyword")
            && rendered.contains("shared/tonemapping.toml:4:"),
        "{rendered}"
    );
    let Err(e) = load(&format!("{shared}[constants]\nX = 1\n")) else {
        panic!("an included file with constants loads")
    };
    assert!(
        e.render(false).contains("unknown field `constants`"),
        "{}",
        e.render(false)
    );
    // A missing included file, and a block declared in both files.
    let Err(e) = Library::from_declared_sources(declaration, [("lit.wgsl", LIT)]) else {
        panic!("a missing include loads")
    };
    assert!(
        e.render(false)
            .contains("include `shared/tonemapping.toml`: no such file"),
        "{}",
        e.render(false)
    );
    let twice = format!("{declaration}[blocks.tonemapping]\nmulti_compile = [[\"_\", \"X\"]]\n");
    let Err(e) = Library::from_declared_sources(
        &twice,
        [
            ("shared/tonemapping.toml", shared),
            ("lit.wgsl", LIT),
            ("tone.wgsl", TONE),
            ("view.wgsl", VIEW),
        ],
    ) else {
        panic!("a block declared twice loads")
    };
    assert!(
        e.render(false)
            .contains("block `tonemapping` is declared twice"),
        "{}",
        e.render(false)
    );
}
