//! `universal_lit/DepthOnly` per texel: every variant renders the URP scene's quad through
//! three views — the rig's perspective camera (the view the screen-space passes read), the
//! directional light's box around the scene and one tighter than the quad (its near plane
//! clips the quad: the depth prepass does not pancake) — into an `R32Float` target over a
//! `Depth32Float` buffer, both cleared to 1 (the far plane). The reference is
//! [`rasterize_quad`] with the vertices placed by the camera alone (URP's
//! `TransformObjectToHClip`): the target's texel is the reference depth within
//! [`depth_within`] (the `f32` bound from the nearest depth over the sub-pixel window), and
//! the depth buffer's the same bits (the fragment writes the depth the buffer gets); texels not
//! covered, clipped or discarded by the alpha test keep 1 in both.

use std::time::Instant;

use glam::{Mat4, Vec3, Vec4};

use super::coverage::SmallPass;
use super::pass_check::{PassCheck, Setup};
use super::quad_raster::{AlphaTest, Expected, rasterize_quad};
use super::report::{Mismatch, PassReport};
use super::scene::{push_mat4, push_vec4};
use super::shadows::MAP_SIZE;
use super::urp::{DEFAULT_SEED, UrpScene};
use super::urp_caster::views;
use crate::{
    BoundResource, ColorTarget, DepthTest, Draw, DrawPass, GpuError, Resource, TargetFormat,
    render_pass,
};
use wgsl_variants_shaders::reference::tolerance::depth_within;

/// The shader and pass.
const PASS: (&str, &str) = ("universal_lit", "DepthOnly");

/// One view of the check: its name, view-projection and target size.
struct DepthView {
    name: &'static str,
    view_proj: Mat4,
    size: (u32, u32),
}

/// The pass's bindings: the URP scene's material, sampler, base map and object, and
/// `view_proj` as the camera.
fn resources(urp: &UrpScene, view_proj: Mat4) -> Vec<BoundResource> {
    let mut out: Vec<BoundResource> = urp
        .resources()
        .into_iter()
        .filter(|r| (r.group, r.binding) != (0, 0))
        .collect();
    let mut camera = Vec::new();
    push_mat4(&mut camera, view_proj);
    push_vec4(&mut camera, Vec4::ZERO);
    out.push(BoundResource::new(0, 0, Resource::Uniform(camera)));
    out
}

/// Checks every variant of `universal_lit/DepthOnly` against the reference (module docs).
///
/// # Errors
/// A GPU failure, a variant that does not compile, or a rig without its directional light.
pub(crate) fn check_urp_depth_only(setup: &Setup<'_>) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let (scene, rig) = (setup.scene, setup.rig);
    let small = SmallPass::new(setup.lib, PASS.0, PASS.1, setup.options)?;
    let (pass, choices) = (small.pass, small.choices.as_slice());
    let urp = UrpScene::new(scene, DEFAULT_SEED);
    let [directional, tight, _] = views(rig, scene)?;
    let views = [
        DepthView {
            name: "camera",
            view_proj: rig.view_proj,
            size: (scene.width, scene.height),
        },
        DepthView {
            name: "light box",
            view_proj: directional.view_proj,
            size: (MAP_SIZE, MAP_SIZE),
        },
        DepthView {
            name: "tight light box",
            view_proj: tight.view_proj,
            size: (MAP_SIZE, MAP_SIZE),
        },
    ];
    let mesh = scene.quad();
    let mut report = PassReport::new(PASS.0, PASS.1);
    let (mut edges, mut clear, mut discarded, mut depths) = (0usize, 0usize, 0usize, 0usize);
    let mut outputs = Vec::new();
    for choice in choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let names = variant.keywords();
        let on = |k: &str| names.contains(&k);
        let label = variant.label();
        let wgsl: std::sync::Arc<str> = std::sync::Arc::from(setup.lib.wgsl(&variant));
        let mut per_view = Vec::new();
        for view in &views {
            let (w, h) = view.size;
            let mut draw_pass = DrawPass::new(
                &label,
                w,
                h,
                vec![ColorTarget::new(TargetFormat::R32Float).with_clear([1.0, 0.0, 0.0, 0.0])],
            );
            draw_pass.depth = true;
            draw_pass.draws.push(
                Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
                    .with_mesh(mesh.clone())
                    .with_resources(resources(&urp, view.view_proj))
                    .with_depth(DepthTest::OPAQUE),
            );
            let mut out = render_pass(setup.ctx, &draw_pass)?;
            report.draws += 1;
            let color = out.targets.remove(0);
            let depth = out.depth.unwrap_or_default();
            let place = |p: Vec3, _n: Vec3| (view.view_proj * p.extend(1.0), false);
            let alpha = AlphaTest::of(
                &urp,
                on("_ALPHATEST_ON"),
                on("_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A"),
            );
            let (expected, _) = rasterize_quad(&urp, place, view.size, alpha, true);
            let plain = AlphaTest::of(&urp, false, false);
            let (unclipped, _) = rasterize_quad(&urp, place, view.size, plain, true);
            for (i, want) in expected.iter().enumerate() {
                let got = f32::from_le_bytes([
                    color[i * 4],
                    color[i * 4 + 1],
                    color[i * 4 + 2],
                    color[i * 4 + 3],
                ]);
                let buffer = depth[i];
                let want = match *want {
                    Expected::Edge => {
                        edges += 1;
                        continue;
                    }
                    Expected::Clear => {
                        clear += 1;
                        discarded += usize::from(matches!(unclipped[i], Expected::Depth { .. }));
                        (1.0, 0.0)
                    }
                    Expected::Depth { depth, window } => {
                        depths += 1;
                        (depth, window)
                    }
                };
                let ok = depth_within(got, want) && got.to_bits() == buffer.to_bits();
                report.record(ok, || Mismatch {
                    shader: PASS.0.to_owned(),
                    pass: PASS.1.to_owned(),
                    keywords: format!("{label}, {} view", view.name),
                    target: "depth R32Float (then the Depth32Float buffer)".to_owned(),
                    pixel: [i as u32 % w, i as u32 / w],
                    expected: vec![want.0 - want.1, want.0 + want.1],
                    got: vec![got, buffer],
                    got_raw: vec![got.to_bits(), buffer.to_bits()],
                });
            }
            per_view.push(color);
        }
        outputs.push(per_view);
    }
    small.judge(&mut report, &outputs);
    report.notes.push(format!(
        "the URP scene's quad through the rig's {}x{} perspective camera and the directional light's {MAP_SIZE}x{MAP_SIZE} boxes (the tight one clips the quad at its near plane); {depths} depth and {clear} clear texel comparisons ({discarded} discarded by the alpha test), {edges} edge texels left to the rasterizer",
        scene.width, scene.height
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `universal_lit/DepthOnly` in the check's registry.
pub(crate) struct UrpDepthOnly;

/// The entry of `universal_lit/DepthOnly`.
pub(crate) static URP_DEPTH_ONLY: UrpDepthOnly = UrpDepthOnly;

impl PassCheck for UrpDepthOnly {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[PASS]
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_urp_depth_only(setup)?])
    }
}
