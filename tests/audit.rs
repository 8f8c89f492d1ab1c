//! The variant-explosion audit: counts checked against hand-computed numbers (bundled library,
//! a fixture made to have dead and coupled keywords, synthetic 40- and 64-keyword shaders),
//! and the analytic distinct count cross-checked against enumeration on random libraries.

use num_bigint::BigUint;
use std::collections::{BTreeSet, HashMap, HashSet};
use std::path::{Path, PathBuf};
use test_support::shaders as synthetic;
use wgsl_variants::audit::{self, AuditOptions, Method, PassAudit};
use wgsl_variants::materials::{self, Material};
use wgsl_variants::{Choice, Library, Pass, Space};

fn big(n: u64) -> BigUint {
    BigUint::from(n)
}

fn pow2(k: u32) -> BigUint {
    BigUint::from(1u8) << k
}

fn audit_of(lib: &Library, shader: &str, pass: &str, options: &AuditOptions) -> PassAudit {
    let p = lib.pass(shader, pass).expect("pass");
    audit::audit_pass(lib, p, options).expect("audit")
}

// ---------------------------------------------------------------------------------------------
// The bundled library.
#[test]
fn bundled_library_counts_match_the_hand_computed_ones() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let o = AuditOptions::default();
    // Deferred: _RENDERING_CUTOUT 2 · _METALLIC_MAP 2 · smoothness 3 · six maps 2^6 ·
    // UNITY_HDR_ON 2 · UNITY_ENABLE_REFLECTION_BUFFERS 2 · SHADOWS_SHADOWMASK 2 · the BRDF
    // tier 3 · the lightmap keywords 6 (8 less DIRLIGHTMAP_COMBINED without LIGHTMAP_ON) =
    // 110592, and every keyword guards code of its own (bindings, surface functions, G-buffer
    // packing, reflection probes, RT4, the tier's indirect specular, the lightmaps), so every
    // variant's composed text is distinct.
    let d = audit_of(&lib, "standard", "Deferred", &o);
    assert_eq!(d.full_space, big(110_592));
    assert_eq!(d.after_filtering, big(110_592));
    assert_eq!(d.build_set, big(110_592));
    assert_eq!(d.distinct.count, big(110_592));
    assert!(d.distinct.exact);
    assert_eq!(d.distinct.method, Method::Components);
    assert!(d.dead_keywords.is_empty(), "{:?}", d.dead_keywords);
    assert!(d.together.is_empty(), "{:?}", d.together);
    assert!(d.identical_code.is_empty());
    // Coupled sets: _METALLIC_MAP with the smoothness set (surface_smoothness reads the
    // metallic map only with _SMOOTHNESS_METALLIC), _NORMAL_MAP with _DETAIL_NORMAL_MAP
    // (`#if defined(_NORMAL_MAP) || defined(_DETAIL_NORMAL_MAP)`); the rest are independent.
    let row = |name: &str| d.sets.iter().find(|s| s.name == name).expect(name);
    assert_eq!(
        row("_METALLIC_MAP").coupled_with,
        vec!["_SMOOTHNESS_ALBEDO _SMOOTHNESS_METALLIC"]
    );
    assert_eq!(row("_METALLIC_MAP").group, Some((big(6), 6)));
    assert_eq!(row("_NORMAL_MAP").group, Some((big(4), 4)));
    for independent in [
        "_RENDERING_CUTOUT",
        "_OCCLUSION_MAP",
        "_EMISSION_MAP",
        "UNITY_HDR_ON",
    ] {
        assert_eq!(row(independent).distinct_factor, Some(2), "{independent}");
    }
    // ForwardBase: rendering mode 4 · 2 · 3 · 2^6 · 2 (SHADOWS_SCREEN) · 3 (tier) · 6
    // (lightmaps) = 55296, all
    // distinct (_RENDERING_CUTOUT clips, _RENDERING_FADE and _RENDERING_TRANSPARENT change the
    // output alpha, TRANSPARENT also premultiplies, SHADOWS_SCREEN reads the mask).
    let f = audit_of(&lib, "standard", "ForwardBase", &o);
    assert_eq!(f.full_space, big(55_296));
    assert_eq!(f.distinct.count, big(55_296));
    assert!(f.distinct.exact && f.dead_keywords.is_empty());
    // The internal shaders: Final and Reflections have no keywords; Add has UNITY_HDR_ON.
    assert_eq!(
        audit_of(&lib, "deferred_final", "Final", &o).distinct.count,
        big(1)
    );
    let add = audit_of(&lib, "deferred_reflections", "Add", &o);
    assert_eq!(
        (add.full_space.clone(), add.distinct.count.clone()),
        (big(2), big(2))
    );
    // And the analytic counts agree with composing every variant.
    for pass in lib.passes() {
        let a = audit::audit_pass(&lib, pass, &o).unwrap();
        assert_eq!(
            a.distinct.count,
            big(enumerated_distinct(&lib, pass, &Space::full(pass)) as u64)
        );
    }
}

#[test]
fn bundled_materials_strip_shader_features() {
    let lib = wgsl_variants_shaders::library().unwrap();
    let m = materials::parse(
        r#"
[[material]]
name = "Bricks"
shader = "standard"
keywords = ["_NORMAL_MAP", "_METALLIC_MAP"]
[[material]]
name = "Plain"
shader = "standard"
keywords = []
"#,
        true,
        "m.toml",
    )
    .unwrap();
    let mut o = AuditOptions::default();
    o.materials = Some(m);
    let d = audit_of(&lib, "standard", "Deferred", &o);
    // Two shader_feature combinations × the multi_compile sets (2 · 2 · 2 · 3 · 6).
    assert_eq!(d.build_set, big(288));
    assert_eq!(d.after_stripping, big(288));
    assert_eq!(d.distinct.count, big(288));
    assert_eq!(d.distinct_full_space.count, big(110_592));
    // No material uses the internal shaders: they build nothing.
    assert_eq!(
        audit_of(&lib, "deferred_reflections", "Add", &o).build_set,
        big(0)
    );
    let hdr = d.sets.iter().find(|s| s.name == "UNITY_HDR_ON").unwrap();
    assert!(
        hdr.suggestions.iter().any(|s| s.contains("shader_feature")),
        "{:?}",
        hdr.suggestions
    );
}

// ---------------------------------------------------------------------------------------------
// Enumeration helpers (the reference the analysis is checked against).
fn enumerated_distinct(lib: &Library, pass: &Pass, space: &Space<'_>) -> usize {
    let texts: HashSet<String> = space
        .enumerate(1 << 20)
        .expect("small space")
        .into_iter()
        // The audit counts composed texts, before reachability leaves anything out.
        .map(|c| lib.compose_unpruned(&variant(pass, c), false).text)
        .collect();
    texts.len()
}

fn variant(pass: &Pass, choice: Choice) -> wgsl_variants::Variant<'_> {
    wgsl_variants::Variant { pass, choice }
}

/// Keywords that change code, but not when turned on alone from the all-base variant.
fn enumerated_together(lib: &Library, pass: &Pass, dead: &BTreeSet<String>) -> BTreeSet<String> {
    let base: Vec<u16> = pass
        .sets
        .iter()
        .map(|s| s.none_index().unwrap_or(0) as u16)
        .collect();
    let text = |c: &[u16]| lib.wgsl(&variant(pass, Choice(c.to_vec().into_boxed_slice())));
    let off = text(&base);
    let mut together = BTreeSet::new();
    for (s, set) in pass.sets.iter().enumerate() {
        for (o, name) in set.options.iter().enumerate() {
            let Some(name) = name else { continue };
            if o as u16 == base[s] || dead.contains(name) {
                continue;
            }
            let mut c = base.clone();
            c[s] = o as u16;
            if text(&c) == off {
                together.insert(name.clone());
            }
        }
    }
    together
}

/// Dead keywords by brute force: options that compose like the set's base option everywhere.
fn enumerated_dead(lib: &Library, pass: &Pass) -> BTreeSet<String> {
    let all = Space::full(pass).enumerate(1 << 20).unwrap();
    let text: HashMap<Choice, String> = all
        .iter()
        .map(|c| (c.clone(), lib.wgsl(&variant(pass, c.clone()))))
        .collect();
    let mut dead = BTreeSet::new();
    for (s, set) in pass.sets.iter().enumerate() {
        if set.len() < 2 {
            continue;
        }
        let base = set.none_index().unwrap_or(0) as u16;
        let whole_set_dead = all.iter().all(|c| {
            (0..set.len() as u16).all(|o| {
                let mut d = c.0.clone();
                d[s] = o;
                text[&Choice(d)] == text[c]
            })
        });
        for (o, name) in set.options.iter().enumerate() {
            let Some(name) = name else { continue };
            let same = all.iter().filter(|c| c.0[s] == base).all(|c| {
                let mut d = c.0.clone();
                d[s] = o as u16;
                text[&Choice(d)] == text[c]
            });
            if (o as u16 != base && same) || whole_set_dead {
                dead.insert(name.clone());
            }
        }
    }
    dead
}

// ---------------------------------------------------------------------------------------------
// Random libraries: the analytic count equals the enumerated one.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }
}

struct Gen {
    rng: Rng,
    keywords: Vec<String>,
    modules: usize,
    unique: usize,
}

impl Gen {
    fn name(&mut self) -> String {
        let r = self.rng.below(10);
        if r < 7 && !self.keywords.is_empty() {
            let k = self.rng.below(self.keywords.len());
            self.keywords[k].clone()
        } else {
            format!("X{}", self.rng.below(2))
        }
    }

    fn expr(&mut self, depth: usize) -> String {
        match self.rng.below(if depth == 0 { 3 } else { 8 }) {
            0 => format!("defined({})", self.name()),
            1 => self.name(),
            2 => format!("!defined {}", self.name()),
            3 => format!("{} && {}", self.expr(depth - 1), self.expr(depth - 1)),
            4 => format!("({} || {})", self.expr(depth - 1), self.expr(depth - 1)),
            5 => format!("!({})", self.expr(depth - 1)),
            6 => format!("{} == {}", self.name(), self.rng.below(3)),
            _ => format!("{} >= 1", self.name()),
        }
    }

    fn text(&mut self) -> String {
        // A few shared lines make collisions and ambiguous concatenations likely.
        match self.rng.below(6) {
            0 => "}".into(),
            1 => "a".into(),
            2 => "b".into(),
            3 => String::new(),
            _ => {
                self.unique += 1;
                format!("line{}", self.unique)
            }
        }
    }

    fn body(&mut self, module: usize, depth: usize, out: &mut String) {
        for _ in 0..1 + self.rng.below(4) {
            match self.rng.below(10) {
                0..=3 => {
                    let t = self.text();
                    out.push_str(&t);
                    out.push('\n');
                }
                4..=6 if depth > 0 => {
                    let e = self.expr(2);
                    out.push_str(&format!("#if {e}\n"));
                    self.body(module, depth - 1, out);
                    if self.rng.chance(30) {
                        let e = self.expr(1);
                        out.push_str(&format!("#elif {e}\n"));
                        self.body(module, depth - 1, out);
                    }
                    if self.rng.chance(50) {
                        out.push_str("#else\n");
                        self.body(module, depth - 1, out);
                    }
                    out.push_str("#endif\n");
                }
                7 => {
                    let x = self.rng.below(2);
                    if self.rng.chance(25) {
                        out.push_str(&format!("#undef X{x}\n"));
                    } else {
                        out.push_str(&format!("#define X{x} {}\n", 1 + self.rng.below(2)));
                    }
                }
                8 if module + 1 < self.modules => {
                    let m = module + 1 + self.rng.below(self.modules - module - 1);
                    out.push_str(&format!("#import m{m}\n"));
                }
                _ => {
                    let t = self.text();
                    out.push_str(&t);
                    out.push('\n');
                }
            }
        }
    }
}

/// A random library: one shader with one pass, a few keyword sets, a few modules.
fn random_library(seed: u64) -> (Vec<(String, String)>, Vec<String>) {
    let mut g = Gen {
        rng: Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1),
        keywords: Vec::new(),
        modules: 0,
        unique: 0,
    };
    let mut pragmas = String::new();
    let sets = 1 + g.rng.below(5);
    for s in 0..sets {
        let kind = if g.rng.chance(50) {
            "multi_compile"
        } else {
            "shader_feature"
        };
        match g.rng.below(4) {
            0 => {
                pragmas.push_str(&format!("#pragma {kind} _ A{s} B{s}\n"));
                g.keywords.extend([format!("A{s}"), format!("B{s}")]);
            }
            1 if kind == "multi_compile" => {
                pragmas.push_str(&format!("#pragma {kind} A{s} B{s}\n"));
                g.keywords.extend([format!("A{s}"), format!("B{s}")]);
            }
            _ => {
                pragmas.push_str(&format!("#pragma {kind} _ K{s}\n"));
                g.keywords.push(format!("K{s}"));
            }
        }
    }
    if g.rng.chance(25) {
        let k = g.keywords[g.rng.below(g.keywords.len())].clone();
        pragmas.push_str(&format!("#pragma skip_variants {k}\n"));
    }
    g.modules = g.rng.below(4);
    let mut files = Vec::new();
    for m in 0..g.modules {
        let mut body = String::new();
        g.body(m, 2, &mut body);
        files.push((format!("m{m}.wgsl"), body));
    }
    let mut pass = String::new();
    for _ in 0..1 + g.rng.below(3) {
        if g.modules > 0 && g.rng.chance(40) {
            let m = g.rng.below(g.modules);
            if g.rng.chance(50) {
                let e = g.expr(1);
                pass.push_str(&format!("#if {e}\n#import m{m}\n#endif\n"));
            } else {
                pass.push_str(&format!("#import m{m}\n"));
            }
        } else {
            g.body(usize::MAX - 1, 3, &mut pass);
        }
    }
    // `module + 1 < modules` is false for usize::MAX - 1: the pass body imports explicitly.
    files.push((
        "main.wgsl".into(),
        format!("#shader s\n#pass P\n{pragmas}{pass}#endpass\n"),
    ));
    (files, g.keywords.clone())
}

fn random_materials(rng: &mut Rng, keywords: &[String], pass: &Pass) -> Vec<Material> {
    (0..rng.below(4))
        .map(|i| {
            let mut on: Vec<String> = Vec::new();
            // A keyword skip_variants strips is refused in a material (materials::Skipped).
            for k in keywords.iter().filter(|k| !pass.skip_variants.contains(k)) {
                let (set, _) = pass.keyword(k).unwrap();
                if rng.chance(40) && !on.iter().any(|o| pass.keyword(o).unwrap().0 == set) {
                    on.push(k.clone());
                }
            }
            Material {
                name: format!("m{i}"),
                shader: "s".into(),
                keywords: on,
            }
        })
        .collect()
}

#[test]
fn analytic_distinct_equals_enumeration_on_random_libraries() {
    let mut by_method: HashMap<&'static str, usize> = HashMap::new();
    let mut fused = 0;
    let seeds: u64 = std::env::var("AUDIT_SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(600);
    for seed in 1..=seeds {
        let (files, keywords) = random_library(seed);
        let lib = Library::from_sources(files.clone())
            .unwrap_or_else(|e| panic!("seed {seed}: {e}\n{files:#?}"));
        let pass = lib.pass("s", "P").unwrap();
        let mut rng = Rng(seed | 1);
        let mats = random_materials(&mut rng, &keywords, pass);
        // Small component limits sometimes, to exercise the fallbacks.
        let component_limit = if seed % 5 == 0 { 2 } else { 1 << 16 };
        let mut o = AuditOptions::default();
        o.materials = Some(mats.clone());
        o.component_limit = component_limit;
        let a = audit::audit_pass(&lib, pass, &o).unwrap();
        let ctx = || {
            format!(
                "seed {seed}\n{}",
                files
                    .iter()
                    .map(|f| format!("== {}\n{}", f.0, f.1))
                    .collect::<String>()
            )
        };
        assert!(a.distinct.exact, "{}", ctx());
        let full = enumerated_distinct(&lib, pass, &Space::full(pass));
        let after = enumerated_distinct(&lib, pass, &Space::after_skip(pass));
        let build = enumerated_distinct(&lib, pass, &lib.build_set(pass, Some(&mats)).unwrap());
        assert_eq!(
            a.distinct_full_space.count,
            big(full as u64),
            "full space, {}",
            ctx()
        );
        assert_eq!(
            a.distinct_after_filtering.count,
            big(after as u64),
            "after skip, {}",
            ctx()
        );
        assert_eq!(a.distinct.count, big(build as u64), "build set, {}", ctx());
        assert_eq!(a.full_space, Space::full(pass).count());
        assert_eq!(a.after_filtering, Space::after_skip(pass).count());
        assert_eq!(
            a.build_set,
            lib.build_set(pass, Some(&mats)).unwrap().count()
        );
        let dead: BTreeSet<String> = a.dead_keywords.iter().cloned().collect();
        assert_eq!(
            dead,
            enumerated_dead(&lib, pass),
            "dead keywords, {}",
            ctx()
        );
        let together: BTreeSet<String> = a.together.iter().map(|t| t.keyword.clone()).collect();
        assert_eq!(
            together,
            enumerated_together(&lib, pass, &dead),
            "together, {}",
            ctx()
        );
        *by_method
            .entry(match a.distinct_full_space.method {
                Method::Components => "components",
                Method::Enumeration => "enumeration",
                Method::Bound => "bound",
            })
            .or_default() += 1;
        if a.sets.iter().any(|s| s.group.is_some()) {
            fused += 1;
        }
        // With no room to enumerate, the count is a bound and says so.
        let mut tight_options = AuditOptions::default();
        tight_options.component_limit = 1;
        tight_options.enumeration_limit = 1;
        let tight = audit::audit_pass(&lib, pass, &tight_options).unwrap();
        if !tight.distinct_full_space.exact {
            assert_eq!(tight.distinct_full_space.method, Method::Bound);
            assert!(
                tight.distinct_full_space.count >= big(full as u64),
                "{}",
                ctx()
            );
        }
    }
    println!("random libraries by method: {by_method:?}; with coupled sets: {fused}");
    assert!(by_method.get("components").copied().unwrap_or(0) > 300);
    assert!(by_method.get("enumeration").copied().unwrap_or(0) > 0);
}

// ---------------------------------------------------------------------------------------------
// The fixture: dead keywords, keywords that matter only together, identical code.
fn fixture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/audit")
}

fn fixture_materials() -> Vec<Material> {
    materials::load(&fixture().join("materials.toml")).unwrap()
}

fn strings(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

#[test]
fn fixture_counts_match_the_hand_computed_ones() {
    let lib = Library::from_dir(fixture().join("lib")).unwrap();
    let a = audit_of(&lib, "fx", "Main", &AuditOptions::default());
    // Sets: fog 3 (_ FOG_LINEAR FOG_EXP) · UNUSED_DEBUG 2 · NOOP_FLAG 2 · RIM 2 · RIM_SOFT 2 ·
    // quality 3 · SHADOWS 2 = 288; skip_variants FOG_EXP leaves fog 2: 192.
    assert_eq!(a.full_space, big(288));
    assert_eq!(a.after_filtering, big(192));
    assert_eq!(a.build_set, big(192));
    // Distinct: fog 3 (no fog, linear, exp) · UNUSED_DEBUG 1 (never read) · NOOP_FLAG 1
    // (an empty #ifdef) · {RIM, RIM_SOFT} 2 (only `RIM && RIM_SOFT` is code) · quality 2
    // (only QUALITY_HIGH is read) · SHADOWS 2 (through #define RECEIVE_SHADOWS) = 24;
    // after skip_variants fog gives 2: 16.
    assert_eq!(a.distinct_full_space.count, big(24));
    assert_eq!(a.distinct_after_filtering.count, big(16));
    assert_eq!(a.distinct.count, big(16));
    assert!(a.distinct.exact && a.findings_exact);
    assert_eq!(
        a.dead_keywords,
        strings(&["UNUSED_DEBUG", "NOOP_FLAG", "QUALITY_MED"])
    );
    let together: Vec<(String, Vec<Vec<String>>)> = a
        .together
        .iter()
        .map(|t| (t.keyword.clone(), t.with.clone()))
        .collect();
    assert_eq!(
        together,
        vec![
            ("RIM".to_string(), vec![strings(&["RIM_SOFT"])]),
            ("RIM_SOFT".to_string(), vec![strings(&["RIM"])]),
        ]
    );
    let row = |name: &str| a.sets.iter().find(|s| s.name == name).expect(name);
    assert_eq!(row("FOG_LINEAR FOG_EXP").distinct_factor, Some(3));
    assert_eq!(row("FOG_LINEAR FOG_EXP").after_filtering, 2);
    assert!(row("UNUSED_DEBUG").dead && row("NOOP_FLAG").dead);
    assert!(row("UNUSED_DEBUG").suggestions[0].starts_with("strip it"));
    assert_eq!(row("RIM").coupled_with, strings(&["RIM_SOFT"]));
    assert_eq!(row("RIM").group, Some((big(4), 2)));
    let quality = row("QUALITY_LOW QUALITY_MED QUALITY_HIGH");
    assert_eq!(quality.distinct_factor, Some(2));
    assert_eq!(
        quality.identical_options,
        vec![strings(&["QUALITY_LOW", "QUALITY_MED"])]
    );
    assert!(quality.suggestions[0].contains("drop `QUALITY_MED`"));
    assert_eq!(row("SHADOWS").distinct_factor, Some(2));
    // Identical code in the build set: the rim group and the dead and merged options.
    let rim = a
        .identical_code
        .iter()
        .find(|g| g.keywords == strings(&["RIM", "RIM_SOFT"]))
        .expect("rim group");
    assert_eq!((rim.variants.clone(), rim.distinct), (big(4), 2));
    assert_eq!(
        rim.shared,
        vec![vec![
            strings(&[]),
            strings(&["RIM_SOFT"]),
            strings(&["RIM"])
        ]]
    );
    // Outline: OUTLINE_THICK || OUTLINE_DEBUG imports one module: 4 variants, 2 codes; neither
    // keyword is dead and neither needs the other.
    let o = audit_of(&lib, "fx", "Outline", &AuditOptions::default());
    assert_eq!(
        (o.full_space.clone(), o.distinct.count.clone()),
        (big(4), big(2))
    );
    assert!(o.dead_keywords.is_empty() && o.together.is_empty());
    assert_eq!(
        o.identical_code[0].shared,
        vec![vec![
            strings(&["OUTLINE_DEBUG"]),
            strings(&["OUTLINE_THICK"]),
            strings(&["OUTLINE_THICK", "OUTLINE_DEBUG"])
        ]]
    );
    // Every count agrees with composing every variant, and so do the dead keywords.
    for pass in lib.passes() {
        let a = audit::audit_pass(&lib, pass, &AuditOptions::default()).unwrap();
        assert_eq!(
            a.distinct_full_space.count,
            big(enumerated_distinct(&lib, pass, &Space::full(pass)) as u64)
        );
        let dead: BTreeSet<String> = a.dead_keywords.iter().cloned().collect();
        assert_eq!(dead, enumerated_dead(&lib, pass));
    }
}

#[test]
fn fixture_materials_strip_and_share_code() {
    let lib = Library::from_dir(fixture().join("lib")).unwrap();
    let mut o = AuditOptions::default();
    o.materials = Some(fixture_materials());
    let a = audit_of(&lib, "fx", "Main", &o);
    // Four material combinations (Plain, Rimmed, RimOnly, Shadowed) × fog 2 (after skip) ×
    // UNUSED_DEBUG 2 × quality 3 = 48.
    assert_eq!(a.after_stripping, big(48));
    assert_eq!(a.build_set, big(48));
    // Codes: the materials give 3 (RimOnly = Plain), fog 2, UNUSED_DEBUG 1, quality 2: 12.
    assert_eq!(a.distinct.count, big(12));
    let pass = lib.pass("fx", "Main").unwrap();
    let space = lib.build_set(pass, Some(&fixture_materials())).unwrap();
    assert_eq!(
        a.distinct.count,
        big(enumerated_distinct(&lib, pass, &space) as u64)
    );
    let fog = a
        .sets
        .iter()
        .find(|s| s.name == "FOG_LINEAR FOG_EXP")
        .unwrap();
    assert_eq!(fog.used_by_materials, Some(Vec::new()));
    assert!(
        fog.suggestions
            .iter()
            .any(|s| s.contains("declare it shader_feature"))
    );
    let rim = a.sets.iter().find(|s| s.name == "RIM").unwrap();
    assert_eq!(rim.used_by_materials, Some(strings(&["RIM"])));
    assert_eq!(rim.build_set, 2);
    let shared = a
        .identical_code
        .iter()
        .find(|g| g.keywords.contains(&"RIM".to_string()))
        .expect("materials group");
    // The joint factor of the four shader_feature sets: Plain and RimOnly share code.
    assert_eq!((shared.variants.clone(), shared.distinct), (big(4), 3));
    assert_eq!(shared.shared, vec![vec![strings(&[]), strings(&["RIM"])]]);
}

// ---------------------------------------------------------------------------------------------
// Synthetic 40- and 64-keyword shaders: exact without enumeration.
#[test]
fn forty_independent_keywords_are_audited_exactly() {
    let lib = Library::from_sources(synthetic::keyword_shader(40, false)).unwrap();
    let a = audit_of(&lib, "synth", "P", &AuditOptions::default());
    assert_eq!(a.full_space, pow2(40));
    assert_eq!(a.distinct.count, pow2(40));
    assert!(a.distinct.exact && a.distinct.method == Method::Components);
    assert!(a.dead_keywords.is_empty() && a.together.is_empty());
    assert!(a.sets.iter().all(|s| s.distinct_factor == Some(2)));
}

#[test]
fn sixty_four_keywords_with_dead_and_coupled_ones_are_audited_exactly() {
    let lib = Library::from_sources(synthetic::keyword_shader(64, true)).unwrap();
    let a = audit_of(&lib, "synth", "P", &AuditOptions::default());
    assert_eq!(a.full_space, pow2(64));
    assert_eq!(a.full_space.to_string(), "18446744073709551616");
    // Per group of four: K4g ×2, {K4g+1, K4g+2} 2 codes of 4, K4g+3 ×1: 4 = 2^2 per group,
    // 16 groups: 2^32.
    assert_eq!(a.distinct.count, pow2(32));
    assert!(a.distinct.exact);
    let dead: Vec<String> = (0..16).map(|g| format!("K{}", 4 * g + 3)).collect();
    assert_eq!(a.dead_keywords, dead);
    assert_eq!(a.together.len(), 32);
    assert_eq!(a.together[0].keyword, "K1");
    assert_eq!(a.together[0].with, vec![strings(&["K2"])]);
    // 40 keywords, grouped: 10 groups of 4 → 2^20 distinct of 2^40.
    let lib = Library::from_sources(synthetic::keyword_shader(40, true)).unwrap();
    let a = audit_of(&lib, "synth", "P", &AuditOptions::default());
    assert_eq!(
        (a.full_space.clone(), a.distinct.count.clone()),
        (pow2(40), pow2(20))
    );
    assert_eq!(a.dead_keywords.len(), 10);
}

#[test]
fn an_oversized_group_is_enumerated_or_reported_as_a_bound() {
    // 17 keywords read by one condition: one group of 2^17 assignments, past the 2^16 limit.
    let n = 17;
    let mut text = String::from("#shader big\n#pass P\n");
    for i in 0..n {
        text.push_str(&format!("#pragma multi_compile _ K{i}\n"));
    }
    let any: Vec<String> = (0..n).map(|i| format!("defined(K{i})")).collect();
    text.push_str(&format!(
        "#if {}\nfn any_on() {{}}\n#endif\n#endpass\n",
        any.join(" || ")
    ));
    let lib = Library::from_sources([("big.wgsl", text)]).unwrap();
    // The whole space (2^17) fits the default enumeration limit: exact, by enumeration.
    let a = audit_of(&lib, "big", "P", &AuditOptions::default());
    assert_eq!(a.full_space, pow2(17));
    assert_eq!(a.distinct.count, big(2));
    assert!(a.distinct.exact && a.distinct.method == Method::Enumeration);
    // Without room to enumerate, the group's size is reported, as a bound.
    let mut small = AuditOptions::default();
    small.enumeration_limit = 1000;
    let b = audit_of(&lib, "big", "P", &small);
    assert_eq!(b.distinct.count, pow2(17));
    assert!(!b.distinct.exact && b.distinct.method == Method::Bound);
    assert!(!b.findings_exact);
    // A larger group limit makes it exact again, by components.
    let mut wide = AuditOptions::default();
    wide.component_limit = 1 << 17;
    wide.enumeration_limit = 1000;
    let c = audit_of(&lib, "big", "P", &wide);
    assert_eq!(c.distinct.count, big(2));
    assert!(c.distinct.exact && c.distinct.method == Method::Components);
    assert_eq!(c.together.len(), 0, "each keyword alone turns the code on");
}

// ---------------------------------------------------------------------------------------------
// Constraints: the audit's counts honour `#pragma require` / `#pragma exclude`.
#[test]
fn constraints_are_honoured_and_reported() {
    let lib = Library::from_sources([
        (
            "s.wgsl",
            "#shader s\n#pass P\n#pragma shader_feature _ _NORMAL_MAP\n\
             #pragma shader_feature _ _DETAIL_NORMAL_MAP\n#pragma multi_compile _ FOG_A FOG_B\n\
             #pragma multi_compile _ SHADOWS\n#pragma require _DETAIL_NORMAL_MAP _NORMAL_MAP\n\
             #pragma exclude FOG_B SHADOWS\n#import lib\n#endpass\n",
        ),
        (
            "lib.wgsl",
            "#if defined(_NORMAL_MAP)\nfn n() {}\n#endif\n#if defined(_DETAIL_NORMAL_MAP)\nfn d() {}\n#endif\n\
             #if defined(FOG_A)\nfn a() {}\n#endif\n#if defined(FOG_B)\nfn b() {}\n#endif\n\
             #if defined(SHADOWS)\nfn s() {}\n#endif\n",
        ),
    ])
    .unwrap();
    let pass = lib.pass("s", "P").unwrap();
    let a = audit_of(&lib, "s", "P", &AuditOptions::default());
    // 2·2·3·2 = 24 without constraints; 3 normal-map combinations × 5 fog/shadow ones.
    assert_eq!(a.full_space, big(15));
    assert_eq!(a.build_set, big(15));
    assert_eq!(
        a.distinct.count,
        big(enumerated_distinct(&lib, pass, &Space::full(pass)) as u64)
    );
    assert_eq!(a.distinct.count, big(15));
    assert_eq!(
        a.constraints,
        [
            "require _DETAIL_NORMAL_MAP _NORMAL_MAP",
            "exclude FOG_B SHADOWS"
        ]
    );
}
