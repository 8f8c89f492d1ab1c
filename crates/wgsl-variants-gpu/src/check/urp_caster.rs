//! `universal_lit/ShadowCaster` per texel: every variant renders the URP scene's quad into a
//! 64 × 64 `Depth16Unorm` map — the variants without `_CASTING_PUNCTUAL_LIGHT_SHADOW` for the
//! rig's directional light (an orthographic box, [`directional_shadow_view_proj`]), those with
//! it for the rig's spot light (its perspective, [`spot_shadow_view_proj`]) — and each texel is
//! compared with the reference: the quad's two triangles with their vertices placed by
//! [`caster_clip`] (bias, pancaking), rasterized at texel centres (depth affine in screen
//! space, uv perspective-correct), the alpha test against the base map's texel at that uv.
//! Depth within 1 LSB of 16 bits ([`unorm_within`]); texels not covered or discarded hold
//! the clear value 1. Texels within a hair of a triangle edge or of a base-map texel edge are
//! left to the rasterizer and counted.

use std::time::Instant;

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::coverage::SmallPass;
use super::options::CheckOptions;
use super::pass_check::{PassCheck, Setup};
use super::quad_raster::{AlphaTest, Expected, rasterize_quad};
use super::report::{Mismatch, PassReport};
use super::scene::{TestScene, push_mat4, push_vec4};
use super::screen_masks::REGION_RADIUS;
use super::shadows::{MAP_SIZE, render_depth};
use super::urp::{DEFAULT_SEED, UrpScene};
use crate::{BoundResource, CheckError, GpuContext, GpuError, Resource};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::LightShape;
use wgsl_variants_shaders::reference::shadow::{
    directional_shadow_view_proj, spot_shadow_view_proj,
};
use wgsl_variants_shaders::reference::tolerance::unorm_within;
use wgsl_variants_shaders::reference::urp::shadow::{CasterLight, apply_shadow_bias, caster_clip};

/// URP's `_ShadowBias` of the directional light's map: (depth, normal) in world units.
pub const DIRECTIONAL_BIAS: Vec2 = Vec2::new(-0.05, -0.08);

/// URP's `_ShadowBias` of the spot light's map.
pub const SPOT_BIAS: Vec2 = Vec2::new(-0.03, -0.05);

/// The radius of the tight directional box: smaller than the quad, so its near plane cuts it
/// (pancaking) and its far plane clips it.
pub const TIGHT_RADIUS: f32 = 0.25;

/// One light's map: view-projection, caster light and bias.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CasterView {
    /// The light's view-projection.
    pub(crate) view_proj: Mat4,
    light: CasterLight,
    bias: Vec2,
}

/// The views of the check from the rig's lights: directional, directional in a box tighter than
/// the quad, spot.
pub(crate) fn views(
    rig: &super::rig::LightRig,
    scene: &TestScene,
) -> Result<[CasterView; 3], GpuError> {
    let refused = |message: &str| {
        GpuError::from(CheckError::UnknownToReference {
            variant: "universal_lit/ShadowCaster".to_owned(),
            message: message.to_owned(),
        })
    };
    let LightShape::Directional { direction, .. } = rig.directional_light.shape else {
        return Err(refused("the rig's directional light is not directional"));
    };
    let LightShape::Spot {
        position,
        direction: axis,
        angle_degrees,
        range,
    } = rig.spot_light.shape
    else {
        return Err(refused("the rig's spot light is not a spot"));
    };
    let forward = direction.normalize();
    let directional = |radius: f32| CasterView {
        view_proj: directional_shadow_view_proj(forward, scene.centre.extend(0.0), radius),
        light: CasterLight::Directional { to_light: -forward },
        bias: DIRECTIONAL_BIAS,
    };
    Ok([
        directional(REGION_RADIUS),
        directional(TIGHT_RADIUS),
        CasterView {
            view_proj: spot_shadow_view_proj(position, axis, angle_degrees, range),
            light: CasterLight::Punctual { position },
            bias: SPOT_BIAS,
        },
    ])
}

/// The caster's bindings: the URP scene's material, sampler, base map and object, the light's
/// view-projection as the camera, and the `UrpShadowCaster` uniform.
fn resources(urp: &UrpScene, view: &CasterView) -> Vec<BoundResource> {
    let mut out: Vec<BoundResource> = urp
        .resources()
        .into_iter()
        .filter(|r| (r.group, r.binding) != (0, 0))
        .collect();
    let mut camera = Vec::new();
    push_mat4(&mut camera, view.view_proj);
    push_vec4(&mut camera, Vec4::ZERO);
    let (direction, position) = match view.light {
        CasterLight::Directional { to_light } => (to_light, Vec3::ZERO),
        CasterLight::Punctual { position } => (Vec3::ZERO, position),
    };
    let mut caster = Vec::new();
    push_vec4(&mut caster, direction.extend(0.0));
    push_vec4(&mut caster, position.extend(1.0));
    push_vec4(&mut caster, view.bias.extend(0.0).extend(0.0));
    out.push(BoundResource::new(0, 0, Resource::Uniform(camera)));
    out.push(BoundResource::new(0, 4, Resource::Uniform(caster)));
    out
}

/// The reference map of one variant (`alpha_test`, `albedo_alpha_smoothness` as its keywords)
/// and how many of its depth texels lie on a triangle with a pancaked vertex.
fn reference_map(
    urp: &UrpScene,
    view: &CasterView,
    alpha_test: bool,
    albedo_alpha_smoothness: bool,
) -> (Vec<Expected>, usize) {
    let place = |p: Vec3, n: Vec3| {
        let clip = caster_clip(view.view_proj, p, n, view.light, view.bias);
        let unclamped = view.view_proj
            * apply_shadow_bias(p, n, view.light.direction(p), view.bias).extend(1.0);
        (clip, unclamped.z < 0.0)
    };
    let alpha = AlphaTest::of(urp, alpha_test, albedo_alpha_smoothness);
    rasterize_quad(urp, place, (MAP_SIZE, MAP_SIZE), alpha, false)
}

/// Checks every variant of `universal_lit/ShadowCaster` (or the covering set `options` ask
/// for: [`CheckOptions::cover_for`]) against the reference map (module docs).
pub fn check_urp_shadow_caster(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &super::rig::LightRig,
    options: &CheckOptions,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let small = SmallPass::new(lib, "universal_lit", "ShadowCaster", options)?;
    let (pass, choices) = (small.pass, small.choices.as_slice());
    let urp = UrpScene::new(scene, DEFAULT_SEED);
    let [directional, tight, spot] = views(rig, scene)?;
    let mesh = scene.quad();
    let mut report = PassReport::new("universal_lit", "ShadowCaster");
    let (mut edges, mut clear, mut discarded, mut pancaked) = (0usize, 0usize, 0usize, 0usize);
    let mut outputs = Vec::new();
    for choice in choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let names = variant.keywords();
        let on = |k: &str| names.contains(&k);
        let views = if on("_CASTING_PUNCTUAL_LIGHT_SHADOW") {
            vec![spot]
        } else {
            vec![directional, tight]
        };
        let label = variant.label();
        let wgsl = lib.wgsl(&variant);
        let mut per_view = Vec::new();
        for view in views {
            let image = render_depth(
                ctx,
                (&label, &wgsl),
                &mesh,
                &resources(&urp, &view),
                MAP_SIZE,
                false,
            )?;
            report.draws += 1;
            let alpha_test = on("_ALPHATEST_ON");
            let (expected, on_pancaked) = reference_map(
                &urp,
                &view,
                alpha_test,
                on("_SMOOTHNESS_TEXTURE_ALBEDO_CHANNEL_A"),
            );
            pancaked += on_pancaked;
            let (plain, _) = reference_map(&urp, &view, false, false);
            for (i, want) in expected.iter().enumerate() {
                let got = image.depth[i];
                let (x, y) = (i as u32 % MAP_SIZE, i as u32 / MAP_SIZE);
                let ok = match *want {
                    Expected::Edge => {
                        edges += 1;
                        continue;
                    }
                    Expected::Clear => {
                        clear += 1;
                        discarded += usize::from(matches!(plain[i], Expected::Depth { .. }));
                        got == u16::MAX
                    }
                    Expected::Depth { depth, .. } => unorm_within(u32::from(got), depth, 16),
                };
                report.record(ok, || Mismatch {
                    shader: "universal_lit".to_owned(),
                    pass: "ShadowCaster".to_owned(),
                    keywords: label.clone(),
                    target: "shadow map Depth16Unorm".to_owned(),
                    pixel: [x, y],
                    expected: match *want {
                        Expected::Depth { depth, .. } => vec![depth],
                        _ => vec![1.0],
                    },
                    got: vec![f32::from(got) / 65535.0],
                    got_raw: vec![u32::from(got)],
                });
            }
            per_view.push(image.depth);
        }
        outputs.push(per_view);
    }
    small.judge(&mut report, &outputs);
    report.notes.push(format!(
        "{MAP_SIZE}x{MAP_SIZE} Depth16Unorm maps of the URP scene's quad: directional light (orthographic boxes of radius {REGION_RADIUS} and {TIGHT_RADIUS}, bias {DIRECTIONAL_BIAS}; {pancaked} texels on a triangle with a vertex pancaked onto the near plane) without _CASTING_PUNCTUAL_LIGHT_SHADOW, spot light (perspective, bias {SPOT_BIAS}) with it; {clear} clear texel comparisons ({discarded} discarded by the alpha test), {edges} edge texels left to the rasterizer"
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// `universal_lit/ShadowCaster` in the check's registry.
pub(crate) struct UrpShadowCaster;

/// The entry of `universal_lit/ShadowCaster`.
pub(crate) static URP_SHADOW_CASTER: UrpShadowCaster = UrpShadowCaster;

impl PassCheck for UrpShadowCaster {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[("universal_lit", "ShadowCaster")]
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_urp_shadow_caster(
            setup.ctx,
            setup.lib,
            setup.scene,
            setup.rig,
            setup.options,
        )?])
    }
}
