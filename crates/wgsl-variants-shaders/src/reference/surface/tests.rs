//! Per-keyword and hand-computed tests of the passes.

use super::*;
use crate::reference::gbuffer::{GBufferTexel, encode_normal};
use crate::reference::ldr::ldr_encode;
use crate::reference::lightmap::LightmapTexels;

fn geo() -> Geometry {
    Geometry {
        world_position: Vec3::ZERO,
        normal: Vec3::Z,
        tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
    }
}

/// A scene where every term is non-zero: ambient, a light, two distinct probes with distinct
/// faces, probe 0 weighted 0.6.
fn lit_scene() -> Scene {
    let mut s = Scene {
        camera_position: Vec3::new(0.3, 0.4, 4.0),
        sh_r: Vec4::new(0.1, 0.2, 0.3, 0.5),
        sh_g: Vec4::new(0.0, 0.1, 0.2, 0.4),
        sh_b: Vec4::new(-0.1, 0.0, 0.1, 0.3),
        light_dir: Vec3::new(0.2, 0.5, 1.0).normalize(),
        light_color: Vec3::new(1.0, 0.9, 0.8),
        cubes: [
            CubeFaces::from_fn(|f| Vec4::new(0.1 * (f + 1) as f32, 0.5, 0.2, 1.0)),
            CubeFaces::from_fn(|f| Vec4::new(0.3, 0.05 * (f + 1) as f32, 0.7, 1.0)),
        ],
        ..Scene::default()
    };
    s.probes[0].forward_weight = 0.6;
    s
}

/// Textures that differ from their defaults, so each keyword that reads one changes something.
fn busy_texels() -> Texels {
    Texels {
        main_tex: Vec4::new(0.8, 0.6, 0.4, 0.7),
        metallic_map: Vec4::new(0.9, 0.0, 0.0, 0.3),
        normal_map: Vec4::new(0.7, 0.4, 0.9, 1.0),
        occlusion_map: Vec4::new(0.0, 0.25, 0.0, 1.0),
        emission_map: Vec4::new(0.5, 0.25, 1.0, 1.0),
        detail_mask: Vec4::new(0.0, 0.0, 0.0, 0.5),
        detail_albedo: Vec4::new(0.2, 0.9, 0.6, 1.0),
        detail_normal: Vec4::new(0.3, 0.65, 0.9, 1.0),
        lightmap: LightmapTexels {
            baked: Vec4::new(0.6, 0.4, 0.2, 0.3),
            baked_dir: Vec4::new(0.8, 0.3, 0.6, 0.7),
            realtime: Vec4::new(0.3, 0.5, 0.7, 0.4),
            realtime_dir: Vec4::new(0.2, 0.7, 0.4, 0.9),
        },
    }
}

fn busy_material() -> Material {
    Material {
        tint: Vec4::new(0.9, 0.8, 0.7, 0.9),
        emission: Vec3::new(0.2, 0.1, 0.05),
        metallic: 0.3,
        smoothness: 0.6,
        cutoff: 0.7, // above the busy alpha 0.63: _RENDERING_CUTOUT discards
        occlusion_strength: 0.8,
        bump_scale: 1.5,
        detail_bump_scale: 0.7,
    }
}

fn deferred(kw: &Keywords) -> Option<GBuffer> {
    shade_deferred(kw, &busy_material(), &busy_texels(), &geo(), &lit_scene())
}

fn forward(kw: &Keywords) -> Option<Vec4> {
    shade_forward(kw, &busy_material(), &busy_texels(), &geo(), &lit_scene())
}

#[test]
fn keyword_names_round_trip() {
    for name in KEYWORD_NAMES {
        let k = Keywords::from_names(&[name]).unwrap();
        assert_eq!(k.names(), vec![name]);
        assert_ne!(k, Keywords::default(), "{name}");
    }
    let all: Vec<&str> = KEYWORD_NAMES
        .iter()
        .copied()
        .filter(|n| {
            !matches!(
                *n,
                "_RENDERING_FADE"
                    | "_RENDERING_TRANSPARENT"
                    | "_SMOOTHNESS_ALBEDO"
                    | "UNITY_PBS_USE_BRDF2"
            )
        })
        .collect();
    let k = Keywords::from_names(&all).unwrap();
    assert_eq!(k.names(), all);
    assert_eq!(
        Keywords::from_names(&["_", "__", "___"]).unwrap(),
        Keywords::default()
    );
    assert_eq!(
        Keywords::from_names(&["_NORMAL_MAP", "_NORMAL_MAP"]).unwrap(),
        Keywords::from_names(&["_NORMAL_MAP"]).unwrap()
    );
    assert!(Keywords::from_names(&["_SMOOTHNESS_ALBEDO", "_SMOOTHNESS_METALLIC"]).is_err());
    assert!(Keywords::from_names(&["_RENDERING_CUTOUT", "_RENDERING_TRANSPARENT"]).is_err());
    assert!(Keywords::from_names(&["UNITY_PBS_USE_BRDF2", "UNITY_PBS_USE_BRDF3"]).is_err());
    assert!(Keywords::from_names(&[""]).is_err());
    assert!(Keywords::from_names(&["unity_hdr_on"]).is_err());
    assert!(Keywords::from_names(&["DEFERRED_PASS"]).is_err());
}

/// Every deferred keyword changes the G-buffer for the busy inputs.
#[test]
fn each_deferred_keyword_changes_the_gbuffer() {
    let base = deferred(&Keywords::default()).unwrap();
    for name in KEYWORD_NAMES {
        if matches!(
            name,
            "_RENDERING_FADE"
                | "_RENDERING_TRANSPARENT"
                | "_SMOOTHNESS_METALLIC"
                | "_DETAIL_MASK"
                | "DIRLIGHTMAP_COMBINED"
        ) {
            continue; // no deferred variant / only acts with another keyword (tested below)
        }
        let kw = Keywords::from_names(&[name]).unwrap();
        let g = deferred(&kw);
        assert_ne!(g, Some(base), "{name} changed nothing");
    }
    // _SMOOTHNESS_METALLIC only acts with _METALLIC_MAP.
    let alone = deferred(&Keywords::from_names(&["_SMOOTHNESS_METALLIC"]).unwrap()).unwrap();
    assert_eq!(alone, base);
    let with_map = deferred(&Keywords::from_names(&["_METALLIC_MAP"]).unwrap()).unwrap();
    let both = deferred(&Keywords::from_names(&["_METALLIC_MAP", "_SMOOTHNESS_METALLIC"]).unwrap())
        .unwrap();
    assert_ne!(both, with_map);
    assert!((both.rt1.w - 0.6 * 0.3).abs() < 1e-7);
    // _DETAIL_MASK only acts with a detail map.
    let mask = |names: &[&str]| deferred(&Keywords::from_names(names).unwrap()).unwrap();
    assert_eq!(mask(&["_DETAIL_MASK"]), base);
    assert_ne!(
        mask(&["_DETAIL_MASK", "_DETAIL_ALBEDO_MAP"]),
        mask(&["_DETAIL_ALBEDO_MAP"])
    );
    assert_ne!(
        mask(&["_DETAIL_MASK", "_DETAIL_NORMAL_MAP"]),
        mask(&["_DETAIL_NORMAL_MAP"])
    );
    // DIRLIGHTMAP_COMBINED only acts with a lightmap (each one's directional map).
    assert_eq!(mask(&["DIRLIGHTMAP_COMBINED"]), base);
    for lightmap in ["LIGHTMAP_ON", "DYNAMICLIGHTMAP_ON"] {
        assert_ne!(
            mask(&[lightmap, "DIRLIGHTMAP_COMBINED"]),
            mask(&[lightmap]),
            "{lightmap}"
        );
    }
    // Fade / Transparent have no deferred variant: same as opaque.
    for name in ["_RENDERING_FADE", "_RENDERING_TRANSPARENT"] {
        assert_eq!(
            deferred(&Keywords::from_names(&[name]).unwrap()),
            Some(base)
        );
    }
}

/// Every forward keyword (the ones the forward pass has) changes the colour.
#[test]
fn each_forward_keyword_changes_the_colour() {
    let base = forward(&Keywords::default()).unwrap();
    for name in KEYWORD_NAMES {
        if matches!(
            name,
            "UNITY_HDR_ON"
                | "UNITY_ENABLE_REFLECTION_BUFFERS"
                | "_SMOOTHNESS_METALLIC"
                | "_DETAIL_MASK"
                | "DIRLIGHTMAP_COMBINED"
        ) {
            continue;
        }
        let kw = Keywords::from_names(&[name]).unwrap();
        assert_ne!(forward(&kw), Some(base), "{name} changed nothing");
    }
    for name in [
        "UNITY_HDR_ON",
        "UNITY_ENABLE_REFLECTION_BUFFERS",
        "_SMOOTHNESS_METALLIC",
        "_DETAIL_MASK",
    ] {
        assert_eq!(
            forward(&Keywords::from_names(&[name]).unwrap()),
            Some(base),
            "{name}"
        );
    }
    let f = |names: &[&str]| forward(&Keywords::from_names(names).unwrap()).unwrap();
    assert_ne!(
        f(&["_METALLIC_MAP", "_SMOOTHNESS_METALLIC"]),
        f(&["_METALLIC_MAP"])
    );
    assert_ne!(
        f(&["_DETAIL_MASK", "_DETAIL_ALBEDO_MAP"]),
        f(&["_DETAIL_ALBEDO_MAP"])
    );
}

#[test]
fn surface_inputs_hand_computed() {
    let m = busy_material();
    let t = busy_texels();
    let g = geo();
    let s = surface(&Keywords::default(), &m, &t, &g);
    assert_eq!(s.albedo, Vec3::new(0.8 * 0.9, 0.6 * 0.8, 0.4 * 0.7));
    assert_eq!(s.alpha, 0.9 * 0.7);
    assert_eq!((s.metallic, s.smoothness, s.occlusion), (0.3, 0.6, 1.0));
    assert_eq!(s.emission, m.emission);
    assert_eq!(s.normal, Vec3::Z);

    // Detail albedo with the detail mask: m = 0.5, albedo · mix(1, 2·detail, 0.5).
    let k = Keywords::from_names(&["_DETAIL_ALBEDO_MAP", "_DETAIL_MASK"]).unwrap();
    let s = surface(&k, &m, &t, &g);
    let a = Vec3::new(0.72, 0.48, 0.28);
    let want = a * 0.5 + a * Vec3::new(0.4, 1.8, 1.2) * 0.5;
    assert!(
        (s.albedo - want).abs().max_element() < 1e-6,
        "{} vs {want}",
        s.albedo
    );

    // Metallic map and occlusion: mix(1, 0.25, 0.8) = 0.4.
    let k = Keywords::from_names(&["_METALLIC_MAP", "_OCCLUSION_MAP"]).unwrap();
    let s = surface(&k, &m, &t, &g);
    assert_eq!(s.metallic, 0.9);
    assert!((s.occlusion - 0.4).abs() < 1e-7);
    assert_eq!(s.smoothness, 0.6);

    // Emission map multiplies.
    let s = surface(
        &Keywords::from_names(&["_EMISSION_MAP"]).unwrap(),
        &m,
        &t,
        &g,
    );
    assert_eq!(s.emission, Vec3::new(0.1, 0.025, 0.05));

    // Smoothness from albedo alpha; alpha then ignores main_tex.a.
    let s = surface(
        &Keywords::from_names(&["_SMOOTHNESS_ALBEDO"]).unwrap(),
        &m,
        &t,
        &g,
    );
    assert!((s.smoothness - 0.42).abs() < 1e-7);
    assert_eq!(s.alpha, 0.9);
}

#[test]
fn normal_mapping_hand_computed() {
    let m = busy_material();
    let t = busy_texels();
    // A tangent frame rotated about Z by 90°: T = +Y, N = +Z, B = cross(N, T) = −X; w = −1 flips B to +X.
    let g = Geometry {
        world_position: Vec3::ZERO,
        normal: Vec3::new(0.0, 0.0, 3.0),
        tangent: Vec4::new(0.0, 2.0, 0.0, -1.0),
    };
    let k = Keywords::from_names(&["_NORMAL_MAP"]).unwrap();
    // unpack: ((0.4)·1.5, (−0.2)·1.5, 0.8) = (0.6, −0.3, 0.8).
    let ts = tangent_space_normal(&k, &m, &t, 1.0);
    assert!((ts - Vec3::new(0.6, -0.3, 0.8)).abs().max_element() < 1e-6);
    let s = surface(&k, &m, &t, &g);
    let want = (0.6 * Vec3::Y + -0.3 * Vec3::X + 0.8 * Vec3::Z).normalize();
    assert!((s.normal - want).length() < 1e-6, "{} vs {want}", s.normal);

    // Detail normal, masked by 0.5: d = mix((0,0,1), ((−0.4)·0.7, 0.3·0.7, 0.8), 0.5)
    //   = (−0.14, 0.105, 0.9); blended with t: normalize((0.46, −0.195, 0.72)).
    let k = Keywords::from_names(&["_NORMAL_MAP", "_DETAIL_NORMAL_MAP", "_DETAIL_MASK"]).unwrap();
    let ts = tangent_space_normal(&k, &m, &t, 0.5);
    let want = Vec3::new(0.46, -0.195, 0.72).normalize();
    assert!((ts - want).length() < 1e-6, "{ts} vs {want}");
    let s = surface(&k, &m, &t, &g);
    let world = (want.x * Vec3::Y + want.y * Vec3::X + want.z * Vec3::Z).normalize();
    assert!((s.normal - world).length() < 1e-6);

    // Detail normal alone, unmasked: t starts at (0, 0, 1).
    let k = Keywords::from_names(&["_DETAIL_NORMAL_MAP"]).unwrap();
    let ts = tangent_space_normal(&k, &m, &t, 1.0);
    assert!((ts - Vec3::new(-0.28, 0.21, 0.8).normalize()).length() < 1e-6);

    // Flat normal maps leave the vertex normal.
    let flat = Texels::default();
    let k = Keywords::from_names(&["_NORMAL_MAP", "_DETAIL_NORMAL_MAP"]).unwrap();
    assert!((surface(&k, &m, &flat, &g).normal - Vec3::Z).length() < 1e-7);
}

#[test]
fn cutout_discards_below_cutoff_only() {
    let kw = Keywords::from_names(&["_RENDERING_CUTOUT"]).unwrap();
    let mut m = busy_material();
    let t = busy_texels(); // alpha = 0.9 · 0.7 = 0.63
    m.cutoff = 0.64;
    assert!(shade_deferred(&kw, &m, &t, &geo(), &lit_scene()).is_none());
    assert!(shade_forward(&kw, &m, &t, &geo(), &lit_scene()).is_none());
    m.cutoff = 0.9 * 0.7; // equal: kept
    assert!(shade_deferred(&kw, &m, &t, &geo(), &lit_scene()).is_some());
    assert!(shade_forward(&kw, &m, &t, &geo(), &lit_scene()).is_some());
    // Without the keyword nothing is discarded.
    m.cutoff = 1.0;
    assert!(shade_deferred(&Keywords::default(), &m, &t, &geo(), &lit_scene()).is_some());
    // Fade does not alpha-test.
    let fade = Keywords::from_names(&["_RENDERING_FADE"]).unwrap();
    assert!(shade_forward(&fade, &m, &t, &geo(), &lit_scene()).is_some());
}

/// The whole deferred pass for a simple dielectric, computed by hand.
#[test]
fn deferred_hand_computed() {
    let scene = Scene {
        camera_position: Vec3::new(0.0, 0.0, 2.0), // v = n = +Z: nv = 1
        sh_r: Vec4::new(0.0, 0.0, 0.5, 0.25),      // sh(+Z) = 0.75
        sh_g: Vec4::new(0.0, 0.0, 0.0, 0.5),
        sh_b: Vec4::new(0.0, 0.0, -1.0, 0.5), // −0.5 → 0
        cubes: [
            CubeFaces::uniform(Vec4::new(1.0, 2.0, 3.0, 1.0)),
            CubeFaces::uniform(Vec4::ZERO),
        ],
        ..Scene::default()
    };
    let mat = Material {
        tint: Vec4::new(0.5, 0.5, 0.5, 1.0),
        emission: Vec3::new(0.1, 0.0, 0.0),
        metallic: 0.0,
        smoothness: 0.5,
        ..Material::default()
    };
    let g = shade_deferred(
        &Keywords::default(),
        &mat,
        &Texels::default(),
        &geo(),
        &scene,
    )
    .unwrap();
    // diffuse = 0.5 · 0.96 = 0.48, spec 0.04, omr 0.96.
    // indirect specular: r = 0.25, reduction 16/17, nv = 1 → fresnel = spec = 0.04; env = (1,2,3).
    let ispec = Vec3::new(1.0, 2.0, 3.0) * 0.04 * 16.0 / 17.0;
    let c = Vec3::new(0.1, 0.0, 0.0) + 0.48 * Vec3::new(0.75, 0.5, 0.0) + ispec;
    assert!(
        (g.rt0 - Vec4::new(0.48, 0.48, 0.48, 1.0))
            .abs()
            .max_element()
            < 1e-7
    );
    assert!(
        (g.rt1 - Vec4::new(0.04, 0.04, 0.04, 0.5))
            .abs()
            .max_element()
            < 1e-7
    );
    assert_eq!(g.rt2, Vec4::new(0.5, 0.5, 1.0, 1.0));
    let want = ldr_encode(c).extend(1.0);
    assert!(
        (g.rt3 - want).abs().max_element() < 1e-6,
        "{} vs {want}",
        g.rt3
    );

    // HDR stores c; reflection buffers remove the indirect specular.
    let hdr = Keywords::from_names(&["UNITY_HDR_ON"]).unwrap();
    let g = shade_deferred(&hdr, &mat, &Texels::default(), &geo(), &scene).unwrap();
    assert!((g.rt3.truncate() - c).abs().max_element() < 1e-6);
    let rb = Keywords::from_names(&["UNITY_HDR_ON", "UNITY_ENABLE_REFLECTION_BUFFERS"]).unwrap();
    let g = shade_deferred(&rb, &mat, &Texels::default(), &geo(), &scene).unwrap();
    assert!((g.rt3.truncate() - (c - ispec)).abs().max_element() < 1e-6);
    assert!(
        (g.rt1 - Vec4::new(0.04, 0.04, 0.04, 0.5))
            .abs()
            .max_element()
            < 1e-7
    ); // still written
}

/// The forward pass for a simple dielectric, computed by hand, in each rendering mode.
#[test]
fn forward_hand_computed() {
    let scene = Scene {
        camera_position: Vec3::new(0.0, 0.0, 2.0),
        sh_r: Vec4::new(0.0, 0.0, 0.0, 0.5),
        sh_g: Vec4::new(0.0, 0.0, 0.0, 0.5),
        sh_b: Vec4::new(0.0, 0.0, 0.0, 0.5),
        light_dir: Vec3::Z, // h = n: nh = nl = lh = 1
        light_color: Vec3::new(1.0, 0.5, 0.25),
        ..Scene::default()
    };
    let mat = Material {
        tint: Vec4::new(0.5, 0.5, 0.5, 0.5),
        smoothness: 0.0, // pr = r = 1: reduction 1/2
        ..Material::default()
    };
    let kw = Keywords::default();
    let c = shade_forward(&kw, &mat, &Texels::default(), &geo(), &scene).unwrap();
    // BRDF1 with n = v = l: Disney diffuse 1, Fresnel = spec colour, V = 0.5 / (2 + 1e-5),
    // d = 1 (so D·π = 1 / (1 + 1e-7)).
    let spec = 0.5 / (2.0 + 1e-5) / (1.0 + 1e-7);
    let direct = (Vec3::splat(0.48) + Vec3::splat(0.04 * spec)) * scene.light_color;
    let want = Vec3::splat(0.48 * 0.5) + direct; // black probes
    assert!(
        (c.truncate() - want).abs().max_element() < 1e-6,
        "{c} vs {want}"
    );
    assert_eq!(c.w, 1.0);

    let fade = Keywords::from_names(&["_RENDERING_FADE"]).unwrap();
    let f = shade_forward(&fade, &mat, &Texels::default(), &geo(), &scene).unwrap();
    assert_eq!(f, c.truncate().extend(0.5));

    // Transparent: diffuse · 0.5 = 0.24; alpha = 1 − 0.96 + 0.5 · 0.96 = 0.52.
    let tr = Keywords::from_names(&["_RENDERING_TRANSPARENT"]).unwrap();
    let t = shade_forward(&tr, &mat, &Texels::default(), &geo(), &scene).unwrap();
    let direct = (Vec3::splat(0.24) + Vec3::splat(0.04 * spec)) * scene.light_color;
    let want = Vec3::splat(0.24 * 0.5) + direct;
    assert!(
        (t.truncate() - want).abs().max_element() < 1e-6,
        "{t} vs {want}"
    );
    assert!((t.w - 0.52).abs() < 1e-7);
}

#[test]
fn forward_environment_uses_box_projection_and_weight() {
    let mut scene = Scene {
        cubes: [
            CubeFaces::from_fn(|f| Vec4::splat(f as f32)),
            CubeFaces::from_fn(|f| Vec4::splat(10.0 + f as f32)),
        ],
        ..Scene::default()
    };
    // From p = (0.9, 0, 0) looking along (−1, 0, 0.5): without box projection the sample is −X
    // (face 1); projected onto the unit box around o = (0, 0, 0.5)… hits x = −1 at z = 0.95,
    // which seen from o is (−1, 0, 0.45): still −X. Move o to (0, 0, −1): (−1, 0, 1.95) → +Z.
    let p = Vec3::new(0.9, 0.0, 0.0);
    let r = Vec3::new(-1.0, 0.0, 0.5);
    assert_eq!(forward_environment(&scene, p, r, 0.5), Vec3::splat(1.0));
    scene.probes[0].box_projection = true;
    scene.probes[0].position = Vec3::new(0.0, 0.0, -1.0);
    assert_eq!(forward_environment(&scene, p, r, 0.5), Vec3::splat(4.0));
    // Blend with probe 1 (not projected: −X, 11).
    scene.probes[0].forward_weight = 0.25;
    assert_eq!(
        forward_environment(&scene, p, r, 0.5),
        Vec3::splat(0.25 * 4.0 + 0.75 * 11.0)
    );
    // RGBM decode of probe 1.
    scene.probes[0].forward_weight = 0.0;
    scene.probes[1].hdr = Vec3::new(0.5, 1.0, 0.0);
    assert_eq!(forward_environment(&scene, p, r, 0.5), Vec3::splat(5.5));
}

#[test]
fn reflection_pass_hand_computed() {
    // Dielectric-like spec colour (0.04, 0.2, 0.1): omr = 1 − 0.2 = 0.8.
    let spec = Vec3::new(0.04, 0.2, 0.1);
    let g = GBuffer::pack(Vec3::ZERO, 0.5, spec, 0.5, Vec3::Z, Vec3::ZERO, true);
    let mut probe = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
    probe.box_projection = true;
    probe.blend_distance = 2.0;
    let cube = CubeFaces::from_fn(|f| {
        if f == 0 {
            Vec4::new(1.0, 1.0, 1.0, 1.0)
        } else {
            Vec4::new(5.0, 5.0, 5.0, 1.0)
        }
    });
    // p = (0, 0, 2) (outside by 1 in z: falloff 1 − 1/2), camera on +Z axis: v = n, r = +Z.
    // Grown box [−3, 3]: hits z = 3 → (0, 0, 3) → +Z face (5).
    let p = Vec3::new(0.0, 0.0, 2.0);
    let out = reflection_probe_pixel(Brdf::Brdf1, &g, p, Vec3::new(0.0, 0.0, 7.0), &probe, &cube);
    // env = 5 · 0.5; reduction 16/17; nv = 1 → fresnel = spec.
    let want = 2.5 * 16.0 / 17.0 * spec;
    assert!(
        (out.truncate() - want).abs().max_element() < 1e-6,
        "{out} vs {want}"
    );
    assert_eq!(out.w, 0.5);
    // At grazing view the fresnel goes to grazing = saturate(0.5 + 1 − 0.8) = 0.7.
    let out = reflection_probe_pixel(
        Brdf::Brdf1,
        &g,
        p,
        p + Vec3::new(5.0, 0.0, 0.0),
        &probe,
        &cube,
    );
    // v = +X, r = reflect(−X, Z) = −X… from (0,0,2) to x = −3 → (−3, 0, 2) → −X face (5).
    assert!(
        (out.truncate() - Vec3::splat(2.5 * 16.0 / 17.0 * 0.7))
            .abs()
            .max_element()
            < 1e-6
    );
}

#[test]
fn deferred_reflections_match_forward_for_a_single_full_probe() {
    // With a pure white albedo (max channel 1) the recovered one_minus_reflectivity equals the
    // forward one, so the reflection pass over the G-buffer's float values reproduces the
    // forward indirect specular term exactly in form.
    let kw = Keywords::from_names(&["UNITY_HDR_ON", "UNITY_ENABLE_REFLECTION_BUFFERS"]).unwrap();
    let mat = Material {
        metallic: 0.4,
        smoothness: 0.7,
        ..Material::default()
    };
    let mut scene = lit_scene();
    scene.probes[0].forward_weight = 1.0;
    scene.probes[0].box_projection = false;
    let geo = Geometry {
        world_position: Vec3::new(0.2, -0.1, 0.0),
        ..geo()
    };
    let g = shade_deferred(&kw, &mat, &Texels::default(), &geo, &scene).unwrap();
    let mut probe = scene.probes[0];
    probe.blend_distance = 1.0;
    let refl = reflection_buffer(
        Brdf::Brdf1,
        &g,
        geo.world_position,
        scene.camera_position,
        &[(probe, scene.cubes[0])],
    );

    let s = surface(&kw, &mat, &Texels::default(), &geo);
    let (_, spec, omr) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
    let (v, r) = view_and_reflection(scene.camera_position, geo.world_position, s.normal);
    let env = forward_environment(&scene, geo.world_position, r, s.smoothness) * s.occlusion;
    let want = indirect_specular(Brdf::Brdf1, env, spec, s.smoothness, omr, s.normal, v);
    assert!((refl - want).abs().max_element() < 2e-3, "{refl} vs {want}"); // f16 buffer
    // Adding it to RT3 gives the no-reflection-buffer G-buffer's light.
    let plain = Keywords::from_names(&["UNITY_HDR_ON"]).unwrap();
    let g2 = shade_deferred(&plain, &mat, &Texels::default(), &geo, &scene).unwrap();
    let added = reflections_add(g.rt3.truncate(), refl, true);
    assert!((added - g2.rt3.truncate()).abs().max_element() < 2e-3);
}

#[test]
fn reflection_buffer_orders_and_blends_probes() {
    let g = GBuffer::pack(Vec3::ZERO, 1.0, Vec3::ONE, 1.0, Vec3::Z, Vec3::ZERO, true);
    let red = CubeFaces::uniform(Vec4::new(1.0, 0.0, 0.0, 1.0));
    let green = CubeFaces::uniform(Vec4::new(0.0, 1.0, 0.0, 1.0));
    let big = Probe::new(Vec3::ZERO, Vec3::splat(-4.0), Vec3::splat(4.0));
    let small = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
    let p = Vec3::ZERO;
    let cam = Vec3::Z;
    // Inside both: the smaller draws last and wins, whatever the given order.
    assert_eq!(
        reflection_buffer(Brdf::Brdf1, &g, p, cam, &[(small, green), (big, red)]),
        Vec3::Y
    );
    assert_eq!(
        reflection_buffer(Brdf::Brdf1, &g, p, cam, &[(big, red), (small, green)]),
        Vec3::Y
    );
    // Importance overrides volume.
    let important_big = Probe {
        importance: 2,
        ..big
    };
    assert_eq!(
        reflection_buffer(
            Brdf::Brdf1,
            &g,
            p,
            cam,
            &[(small, green), (important_big, red)]
        ),
        Vec3::X
    );
    // Outside every probe's blend range: the cleared buffer.
    assert_eq!(
        reflection_buffer(
            Brdf::Brdf1,
            &g,
            Vec3::new(9.0, 0.0, 0.0),
            Vec3::new(9.0, 0.0, 1.0),
            &[(big, red)]
        ),
        Vec3::ZERO
    );
    assert_eq!(reflection_buffer(Brdf::Brdf1, &g, p, cam, &[]), Vec3::ZERO);
}

#[test]
fn reflections_add_and_final_decode() {
    // LDR: c = 1 stored as 0.5; adding 2 gives 0.125 → decodes to 3.
    let rt3 = ldr_encode(Vec3::ONE);
    let after = reflections_add(rt3, Vec3::splat(2.0), false);
    assert_eq!(after, Vec3::splat(0.125));
    assert_eq!(final_ldr(after), Vec3::splat(3.0));
    // Negative reflections add nothing in LDR; in HDR they add as is.
    assert_eq!(reflections_add(rt3, Vec3::splat(-1.0), false), rt3);
    assert_eq!(
        reflections_add(Vec3::ONE, Vec3::splat(-0.5), true),
        Vec3::splat(0.5)
    );
}

#[test]
fn gbuffer_round_trip_through_the_targets() {
    for hdr in [false, true] {
        let mut kw = Keywords::from_names(&[
            "_NORMAL_MAP",
            "_METALLIC_MAP",
            "_OCCLUSION_MAP",
            "_EMISSION_MAP",
        ])
        .unwrap();
        kw.hdr = hdr;
        let g = deferred(&kw).unwrap();
        let s = surface(&kw, &busy_material(), &busy_texels(), &geo());
        let decoded = GBufferTexel::quantize(&g, hdr).decode();
        let (diffuse, spec, _) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
        let step = 0.5 / 255.0 + 1e-6;
        assert!((decoded.diffuse - diffuse).abs().max_element() <= step);
        assert!((decoded.specular - spec).abs().max_element() <= step);
        assert!((decoded.occlusion - s.occlusion).abs() <= step);
        assert!((decoded.smoothness - s.smoothness).abs() <= step);
        assert!((decoded.normal - s.normal).length() < 2e-3);
        assert!((g.rt2.truncate() - encode_normal(s.normal)).length() < 1e-7);
        let c = if hdr {
            g.rt3.truncate()
        } else {
            crate::reference::ldr::ldr_decode(g.rt3.truncate())
        };
        assert!(
            (decoded.c - c).abs().max_element() < 5e-3,
            "{} vs {c}",
            decoded.c
        );
    }
}
