//! Binding reflection: snapshots of a few variants' JSON, the stable-numbering rule of the
//! bundled library over the tests' selection (the full space: an ignored test), keywords
//! removing bindings, the command line, and
//! (feature `gpu`) wgpu accepting pipelines whose layouts are built from the reflection.

use std::collections::{BTreeMap, HashMap};

use rayon::prelude::*;

use wgsl_variants::reflect::{BindingKind, Reflection, SampleType};
use wgsl_variants::{Library, Space, Variant};

/// A snapshot: name, shader, pass, keywords.
type SnapshotVariant = (
    &'static str,
    &'static str,
    &'static str,
    &'static [&'static str],
);

/// The variants whose reflection JSON is snapshot (`snapshots/reflect.*.snap`).
pub const SNAPSHOTS: [SnapshotVariant; 5] = [
    (
        "reflect.standard.Deferred.all-off",
        "standard",
        "Deferred",
        &[],
    ),
    (
        "reflect.standard.Deferred.maps-hdr-reflection-buffers",
        "standard",
        "Deferred",
        &[
            "_METALLIC_MAP",
            "_NORMAL_MAP",
            "_DETAIL_ALBEDO_MAP",
            "UNITY_HDR_ON",
            "UNITY_ENABLE_REFLECTION_BUFFERS",
        ],
    ),
    (
        "reflect.standard.ForwardBase.emission-occlusion",
        "standard",
        "ForwardBase",
        &["_RENDERING_FADE", "_OCCLUSION_MAP", "_EMISSION_MAP"],
    ),
    (
        "reflect.deferred_reflections.Reflections",
        "deferred_reflections",
        "Reflections",
        &[],
    ),
    (
        "reflect.deferred_final.Final",
        "deferred_final",
        "Final",
        &[],
    ),
];

#[test]
fn reflection_json_snapshots() {
    let lib = wgsl_variants_shaders::library().unwrap();
    for (name, shader, pass, keywords) in SNAPSHOTS {
        let v = lib.variant(shader, pass, keywords).unwrap();
        let json = serde_json::to_string_pretty(&lib.reflect(&v).unwrap()).unwrap();
        insta::with_settings!({ snapshot_path => "../snapshots", prepend_module_to_snapshot => false, omit_expression => true }, {
            insta::assert_snapshot!(name, json);
        });
    }
}

/// The reflection of the tests' selection of the bundled library (`test_support::selection`:
/// every variant of a pass of up to 8192 variants, a 3-wise covering set of a larger one),
/// computed once for the tests that read it. Slots and keyword bindings follow from single
/// keywords and their pairs, which the covering sets hold; the full space is
/// [`full_space_binding_rules`] (ignored: minutes).
fn reflect_selection() -> &'static [Reflection] {
    static SELECTION: std::sync::OnceLock<Vec<Reflection>> = std::sync::OnceLock::new();
    SELECTION.get_or_init(|| {
        let lib = wgsl_variants_shaders::library().unwrap();
        let variants: Vec<Variant> = test_support::selection::plan_of(&lib)
            .into_iter()
            .flat_map(|(pass, choices)| {
                choices
                    .into_iter()
                    .map(move |choice| Variant { pass, choice })
            })
            .collect();
        reflect_each(&lib, &variants)
    })
}

/// The reflection of each of `variants`, in order.
fn reflect_each(lib: &Library, variants: &[Variant]) -> Vec<Reflection> {
    // A reflection depends on the variant's text only (comments and blank lines aside, which
    // `wgsl` leaves out): each distinct text is validated and reflected once, then every
    // variant gets its text's with its own names.
    let texts: Vec<String> = variants.par_iter().map(|v| lib.wgsl(v)).collect();
    let mut first: HashMap<&str, usize> = HashMap::new();
    for (i, text) in texts.iter().enumerate() {
        first.entry(text.as_str()).or_insert(i);
    }
    let distinct: Vec<usize> = first.values().copied().collect();
    let reflected: HashMap<usize, Reflection> = distinct
        .par_iter()
        .map(|&i| (i, lib.reflect(&variants[i]).unwrap()))
        .collect();
    variants
        .iter()
        .zip(&texts)
        .map(|(v, text)| {
            let mut r = reflected[&first[text.as_str()]].clone();
            r.shader = v.pass.shader.clone();
            r.pass = v.pass.name.clone();
            r.keywords = v.keywords().into_iter().map(str::to_string).collect();
            r
        })
        .collect()
}

/// The rule the README documents: within a pass, a (group, binding) slot always holds the
/// same resource — same name, same kind — in every variant that has it.
#[test]
fn binding_numbers_are_stable_across_the_selection() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let planned: usize = test_support::selection::plan_of(&lib)
        .iter()
        .map(|(_, choices)| choices.len())
        .sum();
    let all = reflect_selection();
    assert_eq!(all.len(), planned);
    assert_stable_slots(all);
}

/// The stable-slot rule over every variant of every bundled pass (1020582), and the keyword
/// bindings of every variant of the standard shader (184,328). About 4.5 minutes on 2 cores
/// (the fresh-clone CI run of 2026-11-29, when this was CI's form):
/// `cargo test --release --ignore-rust-version --test reflect -- --ignored`.
#[test]
#[ignore = "the full space (1020582 variants): cargo test --release --test reflect -- --ignored"]
fn full_space_binding_rules() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let variants: Vec<Variant> = lib
        .passes()
        .flat_map(|pass| {
            Space::full(pass)
                .enumerate(1_000_000)
                .unwrap()
                .into_iter()
                .map(move |choice| Variant { pass, choice })
        })
        .collect();
    let all = reflect_each(&lib, &variants);
    assert_eq!(all.len(), 1_020_582);
    assert_stable_slots(&all);
    assert_eq!(assert_keyword_bindings(&all), 55_296 + 18432 + 110_592 + 8);
}

/// Within each pass of `all`, a slot holds one resource, and a resource one slot.
fn assert_stable_slots(all: &[Reflection]) {
    // (shader, pass, group, binding) -> (name, kind)
    type Slot = (String, String, u32, u32);
    let mut seen: BTreeMap<Slot, (String, BindingKind)> = BTreeMap::new();
    for r in all {
        for b in &r.bindings {
            let key = (r.shader.clone(), r.pass.clone(), b.group, b.binding);
            let value = (b.name.clone(), b.kind.clone());
            let first = seen.entry(key.clone()).or_insert_with(|| value.clone());
            assert_eq!(
                *first, value,
                "{key:?} changes in {}/{} {:?}",
                r.shader, r.pass, r.keywords
            );
        }
    }
    // Two names never share a slot, and one name never moves between slots.
    let mut by_name: BTreeMap<(String, String, String), (u32, u32)> = BTreeMap::new();
    for ((shader, pass, group, binding), (name, _)) in &seen {
        let old = by_name.insert(
            (shader.clone(), pass.clone(), name.clone()),
            (*group, *binding),
        );
        assert!(old.is_none(), "{shader}/{pass} {name} has two slots");
    }
    // The standard passes use three groups: frame (0), material (1), object (2: the object,
    // its baked occlusion with SHADOWS_SHADOWMASK, and its lightmaps: the record, four maps
    // and their sampler).
    let standard: Vec<_> = seen
        .keys()
        .filter(|k| k.0 == "standard" && k.1 == "Deferred")
        .collect();
    assert_eq!(standard.len(), 6 + 10 + 8);
}

/// A keyword that is off removes its texture; one that is on brings it (with the same slot).
#[test]
fn keywords_add_and_remove_bindings() {
    let all = reflect_selection();
    let standard = all.iter().filter(|r| r.shader == "standard").count();
    assert_eq!(assert_keyword_bindings(all), standard);
    // The covering sets of the three lit passes and the whole ShadowCaster pass.
    assert!(standard > 8 + 3 * 30, "{standard}");
}

/// Over the standard shader's variants of `all`: each map with its keyword, the probes, the
/// lookup table and the lightmaps where the pass reads them. Returns how many were checked.
fn assert_keyword_bindings(all: &[Reflection]) -> usize {
    let maps = [
        ("_METALLIC_MAP", "metallic_map", (1, 3)),
        ("_NORMAL_MAP", "normal_map", (1, 4)),
        ("_OCCLUSION_MAP", "occlusion_map", (1, 5)),
        ("_EMISSION_MAP", "emission_map", (1, 6)),
        ("_DETAIL_ALBEDO_MAP", "detail_albedo", (1, 8)),
        ("_DETAIL_NORMAL_MAP", "detail_normal", (1, 9)),
    ];
    let mut checked = 0;
    for r in all.iter().filter(|r| r.shader == "standard") {
        let has = |name: &str| {
            r.bindings
                .iter()
                .find(|b| b.name == name)
                .map(|b| (b.group, b.binding))
        };
        let on = |k: &str| r.keywords.iter().any(|x| x == k);
        for (keyword, name, slot) in maps {
            assert_eq!(
                has(name),
                on(keyword).then_some(slot),
                "{keyword} in {:?}",
                r.keywords
            );
        }
        // The detail mask is sampled only to blend a detail map.
        let detail = on("_DETAIL_ALBEDO_MAP") || on("_DETAIL_NORMAL_MAP");
        assert_eq!(has("detail_mask").is_some(), on("_DETAIL_MASK") && detail);
        // Probes are bound where the pass samples them (never in ForwardAdd).
        let probes = r.pass == "ForwardBase"
            || (r.pass == "Deferred" && !on("UNITY_ENABLE_REFLECTION_BUFFERS"));
        for name in ["probes", "probe_cube0", "probe_cube1", "probe_sampler"] {
            assert_eq!(
                has(name).is_some(),
                probes,
                "{name} in {}/{:?}",
                r.pass,
                r.keywords
            );
        }
        // BRDF3's lookup table is bound where the direct term reads it (never in Deferred).
        let lut = (r.pass == "ForwardBase" || r.pass == "ForwardAdd") && on("UNITY_PBS_USE_BRDF3");
        assert_eq!(
            has("brdf_lut"),
            lut.then_some((0, 17)),
            "{}/{:?}",
            r.pass,
            r.keywords
        );
        // The lightmaps (ForwardBase, Deferred): each map with its keywords, the record and
        // the sampler with either lightmap.
        let lightmapped = on("LIGHTMAP_ON") || on("DYNAMICLIGHTMAP_ON");
        let directional = on("DIRLIGHTMAP_COMBINED");
        for (name, bound, slot) in [
            ("lightmap", lightmapped, (2, 2)),
            ("lightmap_tex", on("LIGHTMAP_ON"), (2, 3)),
            ("lightmap_dir", on("LIGHTMAP_ON") && directional, (2, 4)),
            ("dynamic_lightmap", on("DYNAMICLIGHTMAP_ON"), (2, 5)),
            (
                "dynamic_lightmap_dir",
                on("DYNAMICLIGHTMAP_ON") && directional,
                (2, 6),
            ),
            ("lightmap_sampler", lightmapped, (2, 7)),
        ] {
            assert_eq!(
                has(name),
                bound.then_some(slot),
                "{name} in {}/{:?}",
                r.pass,
                r.keywords
            );
        }
        checked += 1;
    }
    checked
}

#[test]
fn texture_sample_types_follow_wgpu_rules() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let v = lib
        .variant("deferred_reflections", "Reflections", &[] as &[&str])
        .unwrap();
    let r = lib.reflect(&v).unwrap();
    let sample_type = |name: &str| match &r.bindings.iter().find(|b| b.name == name).unwrap().kind {
        BindingKind::Texture { sample_type, .. } => *sample_type,
        other => panic!("{name} is {other:?}"),
    };
    // Loaded with textureLoad only: any float format, including the R32Float depth.
    for name in ["rt0", "rt1", "rt2", "depth_tex"] {
        assert_eq!(sample_type(name), SampleType::UnfilterableFloat, "{name}");
    }
    assert_eq!(sample_type("probe_cube"), SampleType::Float);
    let size = |name: &str| &r.bindings.iter().find(|b| b.name == name).unwrap().kind;
    // Probe: 5 × vec4f.
    assert_eq!(size("probe"), &BindingKind::UniformBuffer { size: 80 });
    // DeferredCamera: inverse view-projection, position, view-projection.
    assert_eq!(
        size("deferred_camera"),
        &BindingKind::UniformBuffer { size: 144 }
    );
}
