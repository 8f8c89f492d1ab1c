//! The GPU proof of URP's `universal_lit/UniversalGBuffer`: the default selection (a t = 3
//! covering set plus one partner per keyword) rendered on the URP test scene, every texel of
//! every target compared with `reference::urp::gbuffer`, and every keyword shown to change a
//! texel (`check::run`). The full space (49,152 variants) is the ignored test
//! `every_universal_gbuffer_variant_matches_the_reference`
//! (`cargo test --release -p wgsl-variants-gpu --test gpu_urp_gbuffer -- --ignored`).
//!
//! Needs a wgpu adapter (lavapipe is enough); see `gpu_passes.rs` for the skip rules.

mod common;

use wgsl_variants::variants::Space;
use wgsl_variants_gpu::check::urp::{UrpScene, compare_variant, urp_targets};
use wgsl_variants_gpu::check::{self, CheckOptions, CheckReport, PassReport, TestScene};
use wgsl_variants_gpu::{GpuContext, render};
use wgsl_variants_shaders::reference::urp::gbuffer::{UrpKeywords, UrpTexel};
use wgsl_variants_shaders::reference::urp::srgb::srgb8;
use wgsl_variants_shaders::reference::urp::ufloat::UFloat;

fn run(full: bool) -> Option<CheckReport> {
    let mut options = CheckOptions::default();
    options.shader = Some("universal_lit".into());
    options.pass = Some("UniversalGBuffer".into());
    options.adapter = common::gpu::adapter_filter();
    options.full = full;
    common::gpu::or_skip(
        check::run(&wgsl_variants_shaders::library().unwrap(), &options),
        "the GPU check",
    )
}

fn assert_passes(report: &CheckReport, at_least: usize) {
    let p = &report.passes[0];
    println!("{report}");
    assert_eq!(
        (p.shader.as_str(), p.pass.as_str()),
        ("universal_lit", "UniversalGBuffer")
    );
    assert!(p.variants_run >= at_least, "{} variants", p.variants_run);
    assert_eq!(p.mismatches, 0, "{report}");
    assert!(p.discarded_compared > 0, "the alpha test discarded nothing");
    assert_eq!(p.keywords.len(), 16);
    assert!(p.untested_keywords.is_empty(), "{:?}", p.untested_keywords);
    assert!(
        p.keywords.iter().all(|k| k.pairs_changed > 0),
        "{:?}",
        p.keywords
    );
    assert!(report.passed());
}

#[test]
fn covering_set_of_universal_gbuffer_matches_the_reference() {
    let Some(report) = run(false) else { return };
    // The 3-wise covering set plus at most one partner per keyword.
    let lib = wgsl_variants_shaders::library().unwrap();
    let pass = lib.pass("universal_lit", "UniversalGBuffer").unwrap();
    let cover = Space::full(pass).covering(3).unwrap().len();
    assert_passes(&report, cover);
    assert!(report.passes[0].variants_run <= cover + 16);
}

#[test]
#[ignore = "49,152 variants: run with --ignored (the README gives the time)"]
fn every_universal_gbuffer_variant_matches_the_reference() {
    let Some(report) = run(true) else { return };
    assert_passes(&report, 49_152);
}

/// A planted bug: one texel of a real rendering changed by one code beyond each tolerance
/// (the sRGB albedo, the octahedral normal's code, the `Rg11b10Ufloat` light, the rendering
/// layers) is reported, with its pixel and target, and the untouched rendering is not.
#[test]
fn the_comparison_catches_a_wrong_texel() {
    let Some(ctx) = common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context",
    ) else {
        return;
    };
    let lib = wgsl_variants_shaders::library().unwrap();
    let pass = lib.pass("universal_lit", "UniversalGBuffer").unwrap();
    let names = [
        "_GBUFFER_NORMALS_OCT",
        "_WRITE_RENDERING_LAYERS",
        "_EMISSION",
    ];
    let variant = lib
        .variant("universal_lit", "UniversalGBuffer", &names)
        .unwrap();
    let urp = UrpScene::new(&TestScene::default(), check::urp::DEFAULT_SEED);
    let mut job = urp.job(&variant.label(), &lib.wgsl(&variant), &names);
    job.resources = urp.resources();
    let bytes = render(&ctx, &job).unwrap();
    let k = UrpKeywords::from_names(&names).unwrap();
    let expected: Vec<Option<Vec<UrpTexel>>> = urp
        .scene
        .pixels()
        .map(|(x, y)| urp.reference(&k, x, y).map(|o| o.texels(&k)))
        .collect();
    let targets = urp_targets(&names);
    assert_eq!(targets.len(), 5);
    let compare = |bytes: &[Vec<u8>]| {
        let mut report = PassReport::new(&pass.shader, &pass.name);
        compare_variant(
            &mut report,
            &urp.scene,
            pass,
            "{planted}",
            &targets,
            &expected,
            bytes,
        );
        report
    };
    assert_eq!(compare(&bytes).mismatches, 0);

    let pixel = 37; // (5, 2), kept by this variant
    let at = pixel * 4;
    let want = expected[pixel].clone().unwrap();
    let away = |correct: u32, max: u32| {
        if correct + 2 <= max {
            correct + 2
        } else {
            correct - 2
        }
    };
    let one_wrong = |target: usize, texel: [u8; 4]| {
        let mut wrong = bytes.clone();
        wrong[target][at..at + 4].copy_from_slice(&texel);
        let report = compare(&wrong);
        assert_eq!(report.mismatches, 1, "target {target}");
        let m = &report.first_mismatches[0];
        assert_eq!(
            (m.pixel, m.target.as_str()),
            ([5, 2], targets[target].0.as_str())
        );
    };
    let texel = |t: usize| -> [u8; 4] { bytes[t][at..at + 4].try_into().unwrap() };
    // GBuffer0: the red byte 2 steps from the exact sRGB encoding's rounding (1 is tolerated).
    let UrpTexel::Srgb8(albedo) = want[0] else {
        panic!("{:?}", want[0])
    };
    let mut t = texel(0);
    t[0] = away(u32::from(srgb8(albedo.x)), 255) as u8;
    one_wrong(0, t);
    // GBuffer2: the x code of the octahedral normal 2 codes away, repacked into its bytes.
    let UrpTexel::OctNormal { bytes: oct, .. } = want[2] else {
        panic!("{:?}", want[2])
    };
    let x = away(u32::from(oct[0]) | (u32::from(oct[2] & 15) << 8), 4095);
    let mut t = texel(2);
    t[0] = (x & 255) as u8;
    t[2] = (oct[2] & 0xF0) | (x >> 8) as u8;
    t[1] = oct[1];
    one_wrong(2, t);
    // GBuffer3: the g channel 2 steps of its 11-bit format away.
    let UrpTexel::Ufloat(light) = want[3] else {
        panic!("{:?}", want[3])
    };
    let word = u32::from_le_bytes(texel(3));
    let g = away(u32::from(UFloat::F11.encode(light.y)), 0x7BF);
    one_wrong(3, ((word & !(0x7FF << 11)) | (g << 11)).to_le_bytes());
    // Rendering layers: one bit.
    let mut t = texel(4);
    t[3] ^= 0x40;
    one_wrong(4, t);
}

/// The scene exercises what the keywords change: the environment lookups stay off cube-face
/// edges, the alpha test keeps some pixels and discards others, lightmap texels are read away
/// from their edges, and the default selection is the covering set the tests build.
#[test]
fn urp_scene_is_well_posed() {
    let urp = UrpScene::new(&TestScene::default(), check::urp::DEFAULT_SEED);
    for names in [&[][..], &["_NORMALMAP"][..]] {
        let k = UrpKeywords::from_names(names).unwrap();
        for (x, y) in urp.scene.pixels() {
            let out = urp.reference(&k, x, y).unwrap();
            let p = urp.pixel(x, y).geometry.world_position;
            let v = (urp.lighting.camera_position - p).normalize();
            let r = wgsl_variants_shaders::reference::surface::reflect(-v, out.normal);
            let margin = wgsl_variants_shaders::reference::cube::face_margin(r);
            assert!(
                margin >= check::scene::MIN_FACE_MARGIN,
                "({x}, {y}) {margin}"
            );
        }
    }
    let k = UrpKeywords::from_names(&["_ALPHATEST_ON"]).unwrap();
    let kept = urp
        .scene
        .pixels()
        .filter(|&(x, y)| urp.reference(&k, x, y).is_some())
        .count();
    assert!(kept > 0 && kept < 256, "{kept}");
    // uv · ½ + ¼ lands a quarter texel inside: pixels 0 and 1 share lightmap texel 4.
    assert_eq!(urp.lightmap_texel(0, 1), (4, 4));
    assert_eq!(urp.lightmap_texel(15, 14), (11, 11));
    assert!(urp.texels(0, 0).lightmap.max_element() > 0.0);
    assert_eq!(urp.pixel(3, 3).depth, 0.5);
    let lib = wgsl_variants_shaders::library().unwrap();
    let pass = lib.pass("universal_lit", "UniversalGBuffer").unwrap();
    let cover = Space::full(pass).covering(check::DEFAULT_COVER_T).unwrap();
    // 16 keyword sets, two of them one three-valued factor (their exclusion): far below the
    // 49,152 variants, and every variant in the space.
    assert_eq!(cover.len(), 30);
    assert!(cover.iter().all(|c| Space::full(pass).contains(c)));
}
