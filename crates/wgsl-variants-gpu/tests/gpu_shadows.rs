//! The GPU proof of `standard/ShadowCaster` and of where shadows land: every caster variant
//! rendered over the occluder scene of `check::shadows` (two cut-out quads), each keyword
//! changing the map where it should and nowhere else; and the shadow the receivers compute
//! from the read-back maps (`reference::shadow`, the same comparison the GPU check holds the
//! Lighting and ForwardAdd variants to) lies where the geometry puts it — a ray from each floor
//! pixel to the light, through the quads and their holes.
//!
//! Adapter policy as in `gpu_passes.rs` (`tests/common/gpu.rs`).

mod common;

use glam::{Mat4, Vec3};
use wgsl_variants::Library;
use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::shadows::{
    CUBE_SIZE, MAP_SIZE, ShadowRig, analytic_occlusion, render_caster,
};
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport, LightRig, TestScene};
use wgsl_variants_shaders::reference::light::LightType;
use wgsl_variants_shaders::reference::shadow::{ShadowKeywords, ShadowParams, cube_face_view_proj};

fn check_pass(lib: &Library, shader: &str, pass: &str) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some(shader.to_owned());
    options.pass = Some(pass.to_owned());
    options.adapter = common::gpu::adapter_filter();
    common::gpu::or_skip(check::run(lib, &options), "the GPU check")
}

fn check_caster(lib: &Library) -> Option<CheckReport> {
    check_pass(lib, "standard", "ShadowCaster")
}

/// `SHADOWS_SCREEN`: all 8 `screen_space_shadows/Collect` variants' masks of both directional
/// lights with 1, 2 and 4 cascades match the reference over the read-back atlases, with
/// shadowed pixels, pixels in every cascade and in none, and every keyword changing some; and
/// planted faults are caught: a mask that mixes with half the strength, cascades selected from
/// their far splits, overlapping split spheres not made exclusive, and cascade 1 read through
/// cascade 0's view.
#[test]
fn screen_space_shadows_match_the_reference() {
    let Some(report) = check_pass(
        &wgsl_variants_shaders::library().unwrap(),
        "screen_space_shadows",
        "Collect",
    ) else {
        return;
    };
    eprintln!("{report}");
    assert!(report.passed(), "{report}");
    let p = &report.passes[0];
    assert_eq!((p.variants_run, p.draws), (8, 8 * 2 * 3 * 2));
    assert_eq!(p.keywords.len(), 3, "{:?}", p.keywords);
    let note = &p.notes[0];
    let count_before = |word: &str| -> usize {
        note.split(word)
            .next()
            .and_then(|s| s.rsplit(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap()
    };
    let shadowed = count_before(" shadowed");
    assert!(
        shadowed > 100,
        "the occluders shadow part of the view: {shadowed}"
    );
    // Pixels per cascade 0-3, none and several of the 4 cascades, as the check counted them
    // (the list after `label` in `text`).
    let counts = |text: &str, label: &str| -> Vec<usize> {
        let list = text.split(label).nth(1).unwrap();
        list[1..list.find(']').unwrap()]
            .split(", ")
            .map(|n| n.parse().unwrap())
            .collect()
    };
    // The camera's view: every cascade holds pixels by view depth, some lie beyond, none in
    // two. The deep view along the floor: so do the split spheres.
    let deep = note.split("deep view by view depth ").nth(1).unwrap();
    let by_depth = counts(note, "camera view by view depth ");
    assert!(
        by_depth[..5].iter().all(|&n| n > 0) && by_depth[5] == 0,
        "{note}"
    );
    let spheres = counts(deep, "by split spheres ");
    assert!(
        spheres[..4].iter().all(|&n| n > 0) && spheres[5] == 0,
        "{note}"
    );

    for (from, to) in [
        (
            "shadow_mix(cascades.params.x, visibility)",
            "shadow_mix(cascades.params.x * 0.5, visibility)",
        ),
        ("vec4f(z) >= c.splits_near", "vec4f(z) >= c.splits_far"),
        ("saturate(inside.yzw - inside.xyz)", "inside.yzw"),
        (
            "shadow_coords(c.world_to_shadow[1], p) * w.y",
            "shadow_coords(c.world_to_shadow[0], p) * w.y",
        ),
    ] {
        let file = if from.starts_with("shadow_mix") {
            "internal/screen_space_shadows.wgsl"
        } else {
            "lighting/cascades.wgsl"
        };
        let lib = common::mutate::bundled_with(file, from, to);
        let Some(report) = check_pass(&lib, "screen_space_shadows", "Collect") else {
            return;
        };
        let p = &report.passes[0];
        eprintln!("planted {to:?}: {} mismatches", p.mismatches);
        assert!(p.mismatches > 0 && !report.passed(), "{to:?} not caught");
    }
}

/// `check-gpu`'s ShadowCaster part: all 8 variants, every texel of the spot map and of the
/// six cube faces against the nearest kept occluder point, each keyword changing a texel.
#[test]
fn check_gpu_covers_every_caster_variant_per_texel() {
    let Some(report) = check_caster(&wgsl_variants_shaders::library().unwrap()) else {
        return;
    };
    let p = &report.passes[0];
    eprintln!("{report}");
    assert!(report.passed(), "{report}");
    assert_eq!(p.variants_run, 8);
    // 4 spot maps of 64x64 and 4 x 6 cube faces of 16x16, less the edge texels.
    let all = 4 * 64 * 64 + 4 * 6 * 16 * 16;
    assert!(p.pixels_compared > all * 3 / 4 && p.pixels_compared < all);
    assert!(p.discarded_compared > 0 && p.discarded_compared < p.pixels_compared);
    assert_eq!(p.keywords.len(), 3, "{:?}", p.keywords);
}

/// The caster check is not vacuous: a cube distance 1 % long, and a cutout that never
/// discards, are both caught (in the variants they touch only).
#[test]
fn a_wrong_caster_fails_the_check() {
    let lib = common::mutate::bundled_with(
        "standard/shadow_caster.wgsl",
        "* camera.position.w;",
        "* camera.position.w * 1.01;",
    );
    let Some(report) = check_caster(&lib) else {
        return;
    };
    let p = &report.passes[0];
    assert!(p.mismatches > 0 && !report.passed());
    assert!(
        common::mutate::caught_in(&report)
            .iter()
            .all(|k| k.contains("SHADOWS_CUBE"))
    );
    let lib = common::mutate::bundled_with(
        "standard/surface.wgsl",
        "    if alpha < material.params.z {",
        "    if alpha < -1.0 {",
    );
    let Some(report) = check_caster(&lib) else {
        return;
    };
    let p = &report.passes[0];
    assert!(p.mismatches > 0);
    assert!(
        common::mutate::caught_in(&report)
            .iter()
            .all(|k| k.contains("_RENDERING_CUTOUT") && !k.contains("_SMOOTHNESS_ALBEDO")),
        "{report}"
    );
}

fn context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "creating the GPU context",
    )
}

/// Every ShadowCaster variant: the depth map (SHADOWS_DEPTH) or the +Z face's distances and
/// depth (SHADOWS_CUBE). Cutout opens the checker holes; `_SMOOTHNESS_ALBEDO` takes the alpha
/// from the tint (1), closing them again, and without cutout changes nothing.
#[test]
fn every_caster_variant_and_its_keywords() {
    let Some(ctx) = context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let rig = LightRig::new(&scene);
    let spot = ShadowParams::for_light(&rig.spot_light, 0.8, 0.0).unwrap();
    let point = ShadowParams::for_light(&rig.point_light, 0.9, 0.0).unwrap();
    let render = |extra: &[&str], cube: bool| {
        let mut kw: Vec<&str> = extra.to_vec();
        kw.push(if cube {
            "SHADOWS_CUBE"
        } else {
            "SHADOWS_DEPTH"
        });
        let (view_proj, params, size): (Mat4, &ShadowParams, u32) = if cube {
            // The −Z face looks down from the point light at the occluder under it.
            (
                cube_face_view_proj(point.light_position, 5, 1.0 / point.inv_range),
                &point,
                CUBE_SIZE,
            )
        } else {
            (spot.world_to_shadow, &spot, MAP_SIZE)
        };
        let image = render_caster(
            &ctx,
            &lib,
            &kw,
            view_proj,
            params.light_position.extend(params.inv_range),
            size,
        )
        .unwrap();
        (image.depth, image.color)
    };
    for cube in [false, true] {
        let plain = render(&[], cube);
        let cutout = render(&["_RENDERING_CUTOUT"], cube);
        let albedo = render(&["_SMOOTHNESS_ALBEDO"], cube);
        let both = render(&["_RENDERING_CUTOUT", "_SMOOTHNESS_ALBEDO"], cube);
        let covered = plain.0.iter().filter(|&&d| d < u16::MAX).count();
        let holes = plain
            .0
            .iter()
            .zip(&cutout.0)
            .filter(|(a, b)| a != b)
            .count();
        eprintln!(
            "ShadowCaster {}: {covered} texels covered, {holes} opened by cutout",
            if cube {
                "SHADOWS_CUBE (-Z face)"
            } else {
                "SHADOWS_DEPTH"
            }
        );
        assert!(covered > 20, "the occluders cover part of the map");
        assert!(
            holes > 5 && holes < covered,
            "cutout opens some texels, not all"
        );
        // Holes only open: cutout never brings a caster nearer (through a hole in the upper
        // quad the map sees the lower one, or nothing).
        assert!(plain.0.iter().zip(&cutout.0).all(|(a, b)| b >= a));
        assert_eq!(albedo, plain, "_SMOOTHNESS_ALBEDO alone changes nothing");
        assert_eq!(
            both, plain,
            "_SMOOTHNESS_ALBEDO closes the holes (alpha = tint.a)"
        );
        if cube {
            // The colour target holds |p - light| / range where covered, the clear 1 elsewhere.
            let color = plain.1.expect("SHADOWS_CUBE writes colour");
            let r: Vec<f32> = color
                .chunks_exact(8)
                .map(|t| {
                    wgsl_variants_shaders::reference::quantize::f16_bits_to_f32(u16::from_le_bytes(
                        [t[0], t[1]],
                    ))
                })
                .collect();
            for (d, v) in plain.0.iter().zip(&r) {
                if *d == u16::MAX {
                    assert_eq!(*v, 1.0);
                } else {
                    // The occluder is 0.45 below the light; its corners at most ~0.9 away.
                    assert!((0.45 / 2.6..0.95 / 2.6).contains(v), "{v}");
                }
            }
        } else {
            assert!(plain.1.is_none());
        }
    }
}

/// The receivers' shadow from the read-back maps against the geometry: at every floor pixel of
/// the test scene, the hard shadow of the spot and of the point light is where a ray to the
/// light crosses an occluder (not through a hole), except at pixels whose lookup is within a
/// texel of a shadow edge, which the map's resolution decides.
#[test]
fn shadows_land_where_the_geometry_puts_them() {
    let Some(ctx) = context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::default();
    let rig = LightRig::new(&scene);
    let shadows = ShadowRig::render(&ctx, &lib, &rig.spot_light, &rig.point_light).unwrap();
    let hard_depth = ShadowKeywords {
        depth: true,
        ..Default::default()
    };
    let hard_cube = ShadowKeywords {
        cube: true,
        ..Default::default()
    };
    for (light, kw, position) in [
        (LightType::Spot, hard_depth, shadows.spot.light_position),
        (LightType::Point, hard_cube, shadows.point.light_position),
    ] {
        let (mut agree, mut edge, mut shadowed, mut through_hole, mut unlit) = (0, 0, 0, 0, 0);
        for (x, y) in scene.pixels() {
            let p = scene.world_position(x, y);
            // Out of the light's reach the shadow does not matter (beyond the range the cube's
            // clear value 1 is below the receiver's distance: "shadowed", and unlit anyway).
            if rig.params(light).sample(light, p, None).1 == 0.0 {
                unlit += 1;
                continue;
            }
            let (lo, hi) = shadows.factor(light, kw, p);
            let in_shadow = hi < 1.0;
            let geometry = analytic_occlusion(p, position);
            // A shadow edge nearby: the geometry's answer changes within a map texel's
            // footprint on the floor (at most 0.13 world units here: a 64-texel map over the
            // spot's 70°, 16-texel cube faces 1 above the floor).
            let near_edge = [
                Vec3::new(0.13, 0.0, 0.0),
                Vec3::new(-0.13, 0.0, 0.0),
                Vec3::new(0.0, 0.13, 0.0),
                Vec3::new(0.0, -0.13, 0.0),
            ]
            .iter()
            .any(|&o| analytic_occlusion(p + o, position) != geometry);
            if near_edge || lo != hi {
                edge += 1;
                continue;
            }
            assert_eq!(
                in_shadow, geometry,
                "{light:?} pixel ({x}, {y}) at {p}: map says {in_shadow}, geometry {geometry}"
            );
            agree += 1;
            shadowed += usize::from(geometry);
            // Lit, though within 0.3 of a shadowed point: through a hole, or beside a caster.
            through_hole += usize::from(
                !geometry
                    && [0.3f32, -0.3]
                        .iter()
                        .any(|&o| analytic_occlusion(p + Vec3::new(o, 0.0, 0.0), position)),
            );
        }
        eprintln!(
            "{light:?}: {agree} floor pixels agree with the geometry ({shadowed} in shadow, {through_hole} lit within 0.3 of a shadow), {edge} at shadow edges, {unlit} out of reach"
        );
        assert!(shadowed >= 3, "{light:?}: the occluder shadows the floor");
        assert!(agree > 2 * edge, "{light:?}: most pixels are decided");
    }
}
