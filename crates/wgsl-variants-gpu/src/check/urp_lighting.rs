//! URP's lighting passes, `stencil_deferred/{PunctualLit, DirectionalLit}`: every variant drawn
//! full-screen over G-buffers that `universal_lit/UniversalGBuffer` rendered on the same GPU,
//! positions rebuilt from the [`LightRig`]'s depth buffer, blended One/One onto GBuffer3
//! (`Rg11b10Ufloat`), and every texel compared with
//! [`wgsl_variants_shaders::reference::urp::lighting::stencil_deferred_light`] evaluated on the
//! G-buffer texels as read back (so the G-buffer pass's own check stays separate):
//! `GBuffer3 = emission + GI (as stored) + light`, within
//! [`wgsl_variants_shaders::reference::tolerance::rg11b10_within`].
//!
//! Inputs ([`GBUFFER_INPUTS`]): three material keyword sets (metallic with maps, specular setup
//! with maps, the ReceiveShadowsOff and SpecularHighlightsOff flags), each rendered with and
//! without `_GBUFFER_NORMALS_OCT` (a lighting variant reads the G-buffer its keyword matches)
//! and always with `_WRITE_RENDERING_LAYERS` (the mesh's layers for `_LIGHT_LAYERS`). Each
//! variant lights each input twice: with a light whose layer mask shares a layer with the mesh
//! and with one whose mask does not (black under `_LIGHT_LAYERS`).
//!
//! Lights: the rig's point, spot (inner angle [`SPOT_INNER_FRACTION`] of the outer one) and
//! directional lights; `_DEFERRED_MAIN_LIGHT` draws the rig's `DIRECTIONAL` light as the main
//! light (binding 7) and the `DIRECTIONAL_COOKIE` one's direction and colour otherwise (binding
//! 5), with `_MAIN_LIGHT_SHADOWS` over the main light's map of [`super::screen_shadows`], and
//! with `_LIGHT_COOKIES` under `urp_cookies::main_light_cookie`'s cookie; the point and spot
//! lights under `_LIGHT_COOKIES` read their rects of `urp_cookies::additional_light_cookies`'
//! atlas. Under `_SCREEN_SPACE_OCCLUSION` every light reads `urp_occlusion::ScreenOcclusion`'s
//! pattern (the light times the direct occlusion), and a directional light, blended One
//! SrcAlpha as URP's, under `_DEFERRED_FIRST_LIGHT` also scales GBuffer3 by the indirect
//! occlusion's ratio to the surface's (`deferred_indirect_occlusion`).

use std::time::Instant;

use glam::Vec3;

use super::camera::{LightingCamera, depth_camera_resources};
use super::compare::format_name;
use super::coverage::SmallPass;
use super::options::CheckOptions;
use super::pass_check::{Needs, PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::rig::LightRig;
use super::scene::{TestScene, texture};
use super::screen_masks::ScreenShadow;
use super::shadows::within;
use super::urp::{UrpScene, fade_across, main_shadow_resources};
use super::urp_additional_shadows::{AdditionalAtlas, rig_casting};
use super::urp_cookies::{DrawCookie, additional_light_cookies, main_light_cookie};
use super::urp_occlusion::ScreenOcclusion;
use super::volumes::{LightPipelineInput, StencilScheme, render_volume};
use crate::light_volume::{LightDraw, light_draw};
use crate::{
    BoundResource, CheckError, ColorTarget, GpuContext, GpuError, RenderJob, Resource,
    TargetFormat, render,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightType};
use wgsl_variants_shaders::reference::shadow::{ShadowKeywords, ShadowMaps, shadow_factor};
use wgsl_variants_shaders::reference::tolerance::rg11b10_within;
use wgsl_variants_shaders::reference::urp::ambient_occlusion::{
    AmbientOcclusionFactor, deferred_indirect_occlusion,
};
use wgsl_variants_shaders::reference::urp::forward::{MainLightShadows, UrpShadowFade};
use wgsl_variants_shaders::reference::urp::lighting::{
    UrpGBufferTexel, UrpLight, UrpLightKind, UrpLightParams, stencil_deferred_light,
};
use wgsl_variants_shaders::reference::urp::ufloat::unpack_rg11b10;

/// The material keywords of the G-buffers the lighting variants read (each also rendered
/// with `_GBUFFER_NORMALS_OCT`, and always with `_WRITE_RENDERING_LAYERS`).
pub const GBUFFER_INPUTS: [&[&str]; 3] = [
    &["_NORMALMAP", "_METALLICSPECGLOSSMAP", "_OCCLUSIONMAP"],
    &["_NORMALMAP", "_SPECULAR_SETUP", "_METALLICSPECGLOSSMAP"],
    &["_RECEIVE_SHADOWS_OFF", "_SPECULARHIGHLIGHTS_OFF"],
];

/// The spot's inner angle as a fraction of its outer angle.
pub const SPOT_INNER_FRACTION: f32 = 0.6;

/// The inner angle (URP's `innerSpotAngle`, degrees) the checks give the rig's spot light:
/// [`SPOT_INNER_FRACTION`] of its outer angle.
pub(crate) fn spot_inner_degrees(rig: &LightRig) -> f32 {
    match rig.spot_light.shape {
        wgsl_variants_shaders::reference::light::LightShape::Spot { angle_degrees, .. } => {
            angle_degrees * SPOT_INNER_FRACTION
        }
        _ => 0.0,
    }
}

/// A light mask sharing layer 8 with the mesh's [`super::urp::RENDERING_LAYERS`].
pub const MATCHING_LAYERS: u32 = 1 << 8;

/// A light mask sharing no layer with the mesh.
pub const OTHER_LAYERS: u32 = 1 << 1;

/// One rendered G-buffer: its keywords and the read-back targets (GBuffer0-3, then the
/// optional ones its keywords turn on).
pub(crate) struct UrpGBuffer {
    pub(crate) keywords: Vec<String>,
    pub(crate) oct: bool,
    pub(crate) targets: Vec<Vec<u8>>,
}

impl UrpGBuffer {
    /// The rendering-layers target (`_WRITE_RENDERING_LAYERS`), after the depth-as-colour one
    /// when `_RENDER_PASS_ENABLED` is on too.
    pub(crate) fn rendering_layers(&self) -> Option<&[u8]> {
        let on = |k: &str| self.keywords.iter().any(|x| x == k);
        on("_WRITE_RENDERING_LAYERS")
            .then(|| &self.targets[4 + usize::from(on("_RENDER_PASS_ENABLED"))][..])
    }
}

/// Renders `UniversalGBuffer` with `keywords` over the URP scene.
pub(crate) fn render_urp_gbuffer(
    ctx: &GpuContext,
    lib: &Library,
    urp: &UrpScene,
    keywords: &[&str],
) -> Result<UrpGBuffer, GpuError> {
    let variant = lib
        .variant("universal_lit", "UniversalGBuffer", keywords)
        .map_err(|e| CheckError::lookup("universal_lit/UniversalGBuffer", e))?;
    // The variant's own keyword list (lookup accepts them in any order).
    let keywords = variant.keywords();
    let mut job = urp.job(&variant.label(), &lib.wgsl(&variant), &keywords);
    job.resources = urp.resources();
    let targets = render(ctx, &job)?;
    Ok(UrpGBuffer {
        oct: keywords.contains(&"_GBUFFER_NORMALS_OCT"),
        keywords: keywords.iter().map(|k| (*k).to_owned()).collect(),
        targets,
    })
}

/// The lights of the check, as URP's passes read them.
struct UrpLights {
    point: Light,
    spot: Light,
    main: Light,
    additional: Light,
    spot_inner: f32,
}

impl UrpLights {
    fn new(rig: &LightRig) -> UrpLights {
        UrpLights {
            point: rig.point_light,
            spot: rig.spot_light,
            main: rig.directional_light,
            additional: rig.directional_cookie_light,
            spot_inner: spot_inner_degrees(rig),
        }
    }

    /// The light a variant draws with `layer_mask`.
    fn params(
        &self,
        kind: UrpLightKind,
        main: bool,
        layer_mask: u32,
    ) -> Result<UrpLightParams, GpuError> {
        let light = match (kind, main) {
            (UrpLightKind::Point, _) => self.point,
            (UrpLightKind::Spot, _) => self.spot,
            (UrpLightKind::Directional, true) => self.main,
            (UrpLightKind::Directional, false) => self.additional,
        };
        UrpLight::new(light, self.spot_inner, layer_mask)
            .params()
            .map_err(|e| {
                GpuError::from(CheckError::UnknownToReference {
                    variant: "stencil_deferred".to_owned(),
                    message: e.to_string(),
                })
            })
    }
}

/// What a lighting variant's keywords say.
#[derive(Clone, Copy, Debug)]
struct LightingKeywords {
    kind: UrpLightKind,
    main: bool,
    shadows: MainLightShadows,
    soft: bool,
    additional_shadows: bool,
    oct: bool,
    layers: bool,
    cookies: bool,
    occlusion: bool,
    first_light: bool,
}

impl LightingKeywords {
    fn parse(names: &[&str]) -> Result<LightingKeywords, String> {
        let has = |k: &str| names.contains(&k);
        let kind = if has("_DIRECTIONAL") {
            UrpLightKind::Directional
        } else if has("_SPOT") {
            UrpLightKind::Spot
        } else if has("_POINT") {
            UrpLightKind::Point
        } else {
            return Err(format!("no light keyword in {names:?}"));
        };
        let known = [
            "_DIRECTIONAL",
            "_SPOT",
            "_POINT",
            "_DEFERRED_MAIN_LIGHT",
            "_MAIN_LIGHT_SHADOWS",
            "_MAIN_LIGHT_SHADOWS_CASCADE",
            "_MAIN_LIGHT_SHADOWS_SCREEN",
            "_SHADOWS_SOFT",
            "_ADDITIONAL_LIGHT_SHADOWS",
            "_GBUFFER_NORMALS_OCT",
            "_LIGHT_LAYERS",
            "_LIGHT_COOKIES",
            "_SCREEN_SPACE_OCCLUSION",
            "_DEFERRED_FIRST_LIGHT",
        ];
        if let Some(unknown) = names.iter().find(|n| !known.contains(n)) {
            return Err(format!("keyword {unknown} is unknown to the reference"));
        }
        Ok(LightingKeywords {
            kind,
            main: has("_DEFERRED_MAIN_LIGHT"),
            shadows: MainLightShadows::of(names),
            soft: has("_SHADOWS_SOFT"),
            additional_shadows: has("_ADDITIONAL_LIGHT_SHADOWS"),
            oct: has("_GBUFFER_NORMALS_OCT"),
            layers: has("_LIGHT_LAYERS"),
            cookies: has("_LIGHT_COOKIES"),
            occlusion: has("_SCREEN_SPACE_OCCLUSION"),
            first_light: has("_DEFERRED_FIRST_LIGHT"),
        })
    }
}

/// Checks every variant of `stencil_deferred`'s `pass` (`PunctualLit` or `DirectionalLit`), or
/// the covering set `options` ask for ([`CheckOptions::cover_for`]). `rig` must have its
/// screen shadows rendered ([`LightRig::render_screen_shadows`]): the main light's map is the
/// `DIRECTIONAL` light's.
pub fn check_stencil_deferred(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    pass_name: &str,
    options: &CheckOptions,
) -> Result<PassReport, GpuError> {
    let start = Instant::now();
    let small = SmallPass::new(lib, "stencil_deferred", pass_name, options)?;
    let (pass, choices) = (small.pass, small.choices.as_slice());
    let main_shadow = main_light_shadow(rig, "stencil_deferred")?;
    let fade = lighting_fade(rig, scene, main_shadow);
    let additional = additional_shadows(ctx, lib, scene, rig)?;
    let positions: Vec<Vec3> = scene
        .pixels()
        .map(|(x, y)| rig.deferred_position(scene, x, y))
        .collect();
    let cookie = main_light_cookie(
        &rig.directional_light,
        &positions,
        "stencil_deferred/DirectionalLit",
    )?;
    // The rig's point light is URP's light index 0, its spot 1.
    let atlas = additional_light_cookies(
        &[Some(&rig.point_light), Some(&rig.spot_light)],
        "stencil_deferred/PunctualLit",
    )?;
    let occlusion = ScreenOcclusion::new(scene.width, scene.height);
    let urp = UrpScene::new(scene, super::urp::DEFAULT_SEED);
    let mut gbuffers = Vec::new();
    for material in GBUFFER_INPUTS {
        for oct in [false, true] {
            let mut keywords = material.to_vec();
            keywords.push("_WRITE_RENDERING_LAYERS");
            if oct {
                keywords.push("_GBUFFER_NORMALS_OCT");
            }
            gbuffers.push(render_urp_gbuffer(ctx, lib, &urp, &keywords)?);
        }
    }
    let lights = UrpLights::new(rig);
    let camera = rig.camera(scene);
    let mut report = PassReport::new("stencil_deferred", pass_name);
    let mut outputs: Vec<Vec<Vec<u8>>> = Vec::new();
    // Comparisons in each light's shadow, and those with an outcome within a hair of flipping.
    let (mut shadowed, mut uncertain) = (0usize, 0usize);
    let (mut additional_shadowed, mut additional_uncertain) = (0usize, 0usize);
    // Comparisons under a cookie, and those on a texel's edge: the main light's, then the
    // point and spot lights'.
    let mut cookied = [(0usize, 0usize); 2];
    // Comparisons under the screen-space occlusion, and those where the first light scales
    // GBuffer3 by less than 1.
    let (mut occluded, mut rescaled) = (0usize, 0usize);
    for choice in choices {
        let variant = wgsl_variants::Variant {
            pass,
            choice: choice.clone(),
        };
        let label = variant.label();
        let names = variant.keywords();
        let k = LightingKeywords::parse(&names).map_err(|message| {
            GpuError::from(CheckError::UnknownToReference {
                variant: label.clone(),
                message,
            })
        })?;
        let wgsl = lib.wgsl(&variant);
        // The light's record in the additional lights' shadows and cookies: the rig's point
        // light, then its spot (URP's _ShadowLightIndex and _CookieLightIndex).
        let light_index = match k.kind {
            UrpLightKind::Point => Some(0),
            UrpLightKind::Spot => Some(1),
            UrpLightKind::Directional => None,
        };
        let draw_cookie = match (k.cookies, light_index) {
            (false, _) => None,
            (true, None) => k.main.then_some(DrawCookie::Main(&cookie)),
            (true, Some(index)) => Some(DrawCookie::Additional(&atlas, index)),
        };
        let mut per_draw = Vec::new();
        for gbuffer in gbuffers.iter().filter(|g| g.oct == k.oct) {
            for mask in [MATCHING_LAYERS, OTHER_LAYERS] {
                let light = lights.params(k.kind, k.main, mask)?;
                let extras = LightExtras {
                    additional: light_index.map(|i| (&additional, i)),
                    cookie: draw_cookie,
                    occlusion: k.occlusion.then_some(&occlusion),
                };
                let out = draw_light(
                    ctx,
                    (&label, &wgsl),
                    scene,
                    &camera,
                    gbuffer,
                    (&light, k.main),
                    (main_shadow, &fade),
                    extras,
                    gbuffer.targets[3].clone(),
                )?;
                report.draws += 1;
                let input = format!(
                    "{label} with layer mask {mask:#x} over the G-buffer of universal_lit/UniversalGBuffer {{{}}}",
                    gbuffer.keywords.join(", ")
                );
                for (i, (x, y)) in scene.pixels().enumerate() {
                    let texel_bytes = |t: usize| -> [u8; 4] {
                        let b = &gbuffer.targets[t][i * 4..i * 4 + 4];
                        [b[0], b[1], b[2], b[3]]
                    };
                    let texel = UrpGBufferTexel::decode(
                        texel_bytes(0),
                        texel_bytes(1),
                        texel_bytes(2),
                        gbuffer.oct,
                    )
                    .map_err(|e| CheckError::UnknownToReference {
                        variant: input.clone(),
                        message: format!("G-buffer texel ({x}, {y}): {e}"),
                    })?;
                    let layers = k.layers.then(|| {
                        let t = gbuffer.rendering_layers().unwrap_or_default();
                        u32::from_le_bytes([t[i * 4], t[i * 4 + 1], t[i * 4 + 2], t[i * 4 + 3]])
                    });
                    let stored = unpack_rg11b10(u32::from_le_bytes(texel_bytes(3)));
                    let p = rig.deferred_position(scene, x, y);
                    let (lo, hi) = main_shadow.urp_factor(k.shadows, k.soft, p, (x, y));
                    // URP's MainLightShadow fades the realtime shadow with the distance.
                    let f = if k.shadows != MainLightShadows::Off {
                        fade.at(p, scene.scene.camera_position)
                    } else {
                        0.0
                    };
                    let (lo, hi) = (lo * (1.0 - f) + f, hi * (1.0 - f) + f);
                    let receives = !texel.flags.receive_shadows_off;
                    shadowed += usize::from(hi < 1.0 && receives);
                    uncertain += usize::from(lo != hi && receives);
                    // A punctual light's own shadow (URP's AdditionalLightShadow, faded).
                    let (lo, hi) = match light_index {
                        Some(index) if k.additional_shadows => {
                            let (to_light, _) = light.sample(p);
                            let (a, b) = additional.shadows.attenuation(
                                index as usize,
                                k.soft,
                                p,
                                to_light,
                                scene.scene.camera_position,
                            );
                            additional_shadowed += usize::from(b < 1.0 && receives);
                            additional_uncertain += usize::from(a != b && receives);
                            (lo * a, hi * b)
                        }
                        _ => (lo, hi),
                    };
                    // GetStencilLight: the light's colour times its cookie. The light is linear
                    // in its colour and its attenuation, so the least and greatest cookie and
                    // shadow bound it.
                    let (tint_lo, tint_hi) = match draw_cookie {
                        Some(c) => {
                            let (a, b) = c.color(p);
                            let count = &mut cookied[usize::from(light_index.is_some())];
                            count.0 += 1;
                            count.1 += usize::from(a != b);
                            (a, b)
                        }
                        None => (Vec3::ONE, Vec3::ONE),
                    };
                    // The screen-space occlusion: the light times its direct part; URP returns
                    // before it where the layers keep the light off, so GBuffer3 is kept whole
                    // there.
                    let culled = layers.is_some_and(|l| !light.lights_layers(l));
                    let ao = if k.occlusion {
                        occluded += 1;
                        occlusion.factor(x, y)
                    } else {
                        AmbientOcclusionFactor::NONE
                    };
                    let keep = if k.first_light && k.occlusion && !culled {
                        let surface = f32::from(texel_bytes(1)[3]) / 255.0;
                        deferred_indirect_occlusion(ao.indirect, surface)
                    } else {
                        1.0
                    };
                    rescaled += usize::from(keep < 1.0);
                    let [want_lo, want_hi] =
                        [(lo, tint_lo), (hi, tint_hi)].map(|(shadow, tint)| {
                            let tinted = UrpLightParams {
                                color: light.color * tint * ao.direct,
                                ..light
                            };
                            stored * keep
                                + stencil_deferred_light(
                                    &texel,
                                    p,
                                    scene.scene.camera_position,
                                    &tinted,
                                    shadow,
                                    layers,
                                )
                        });
                    let px = &out[i * 4..i * 4 + 4];
                    let got = TargetFormat::Rg11b10Ufloat.decode_pixel_f32(px);
                    let want = within(got, want_lo.extend(0.0), want_hi.extend(0.0)).truncate();
                    let word = u32::from_le_bytes([px[0], px[1], px[2], px[3]]);
                    report.record(rg11b10_within(word, want), || Mismatch {
                        shader: "stencil_deferred".to_owned(),
                        pass: pass_name.to_owned(),
                        keywords: input.clone(),
                        target: format!("GBuffer3 {}", format_name(TargetFormat::Rg11b10Ufloat)),
                        pixel: [x, y],
                        expected: want.to_array().to_vec(),
                        got: got[..3].to_vec(),
                        got_raw: TargetFormat::Rg11b10Ufloat.decode_pixel(px).to_vec(),
                    });
                }
                per_draw.push(out);
            }
        }
        outputs.push(per_draw);
    }
    small.judge(&mut report, &outputs);
    if shadowed > 0 {
        report.notes.push(format!(
            "{shadowed} pixel comparisons in the main light's shadow, {uncertain} of them with a tap within a hair of flipping (compared within the interval of its outcomes)"
        ));
    }
    if additional_shadowed > 0 {
        report.notes.push(format!(
            "{additional_shadowed} pixel comparisons in a point or spot light's own shadow (the additional lights' atlas: the point light hard over six cube-face slices, the spot light soft under _SHADOWS_SOFT), {additional_uncertain} with a tap or a cube face within a hair of flipping (compared within the interval of the outcomes)"
        ));
    }
    if cookied[0].0 > 0 {
        report.notes.push(format!(
            "{} pixel comparisons under the main light's cookie (a {}×{} RGB cookie read nearest with repeat), {} with a coordinate within 1/64 texel of an edge (compared within the range of the texels)",
            cookied[0].0, cookie.texture.size.0, cookie.texture.size.1, cookied[0].1
        ));
    }
    if occluded > 0 {
        report.notes.push(format!(
            "{occluded} pixel comparisons under the screen-space occlusion (an R8Unorm pattern of 16 levels, direct lighting strength {}){}",
            super::urp_occlusion::DIRECT_STRENGTH,
            if rescaled > 0 {
                format!("; in {rescaled} the first directional light scales GBuffer3 by the indirect occlusion's ratio to the surface's (blended One SrcAlpha)")
            } else {
                String::new()
            }
        ));
    }
    if cookied[1].0 > 0 {
        report.notes.push(format!(
            "{} pixel comparisons under a point or spot light's cookie (their 8×8 rects of a {}×{} atlas read in alpha, nearest, clamped; the spot through its perspective, the point light through the octahedral map), {} with a coordinate within 1/64 texel of an edge (compared within the range of the texels)",
            cookied[1].0, atlas.atlas.size.0, atlas.atlas.size.1, cookied[1].1
        ));
    }
    report.notes.push(format!(
        "full-screen draws over {} UniversalGBuffer G-buffers, each with a light sharing a layer with the mesh and one that does not; onto GBuffer3 Rg11b10Ufloat blended as URP's (a punctual light One One, a directional one One SrcAlpha); positions rebuilt from the depth of a perspective camera",
        GBUFFER_INPUTS.len() * 2
    ));
    report.seconds = start.elapsed().as_secs_f64();
    Ok(report)
}

/// GBuffer3 of `gbuffer` after URP's lighting of the check's lights: the main light (with its
/// soft shadow), then the point and the spot light, each drawn by the lighting variant that
/// matches the G-buffer's normal encoding and rendering layers (the `render` command's
/// `lighting` picture). `rig` must have its screen shadows rendered.
pub(crate) fn light_gbuffer(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    gbuffer: &UrpGBuffer,
) -> Result<Vec<u8>, GpuError> {
    let main_shadow = main_light_shadow(rig, "stencil_deferred")?;
    let fade = lighting_fade(rig, scene, main_shadow);
    let camera = rig.camera(scene);
    let lights = UrpLights::new(rig);
    let mut common = Vec::new();
    if gbuffer.oct {
        common.push("_GBUFFER_NORMALS_OCT");
    }
    if gbuffer.rendering_layers().is_some() {
        common.push("_LIGHT_LAYERS");
    }
    let draws = [
        (
            "DirectionalLit",
            vec![
                "_DIRECTIONAL",
                "_DEFERRED_MAIN_LIGHT",
                "_MAIN_LIGHT_SHADOWS",
                "_SHADOWS_SOFT",
            ],
            UrpLightKind::Directional,
        ),
        ("PunctualLit", vec!["_POINT"], UrpLightKind::Point),
        ("PunctualLit", vec!["_SPOT"], UrpLightKind::Spot),
    ];
    let mut gbuffer3 = gbuffer.targets[3].clone();
    for (pass, mut keywords, kind) in draws {
        keywords.extend(&common);
        let variant = lib
            .variant("stencil_deferred", pass, &keywords)
            .map_err(|e| CheckError::lookup(format!("stencil_deferred/{pass}"), e))?;
        let main = kind == UrpLightKind::Directional;
        let light = lights.params(kind, main, MATCHING_LAYERS)?;
        gbuffer3 = draw_light(
            ctx,
            (&variant.label(), &lib.wgsl(&variant)),
            scene,
            &camera,
            gbuffer,
            (&light, main),
            (main_shadow, &fade),
            LightExtras::default(),
            gbuffer3,
        )?;
    }
    Ok(gbuffer3)
}

/// What a lighting draw binds beyond the G-buffer, the light and the main light's shadow.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct LightExtras<'a> {
    /// For a punctual light: the additional lights' shadows and its index in them (URP's
    /// `_ShadowLightIndex`).
    pub(crate) additional: Option<(&'a AdditionalAtlas, u32)>,
    /// The light's cookie.
    pub(crate) cookie: Option<DrawCookie<'a>>,
    /// The screen-space occlusion (`_SCREEN_SPACE_OCCLUSION`).
    pub(crate) occlusion: Option<&'a ScreenOcclusion>,
}

/// Draws one lighting variant (`label`, `wgsl`) full-screen over `gbuffer` with `light` (the
/// main light's binding when `main`), the main light's shadow map and the `extras`, onto
/// `gbuffer3` (the GBuffer3 contents to start from) with URP's blend for the light's kind
/// ([`light_blend`]); returns GBuffer3 after the draw.
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_light(
    ctx: &GpuContext,
    (label, wgsl): (&str, &str),
    scene: &TestScene,
    camera: &LightingCamera<'_>,
    gbuffer: &UrpGBuffer,
    (light, main): (&UrpLightParams, bool),
    main_shadow: (&ScreenShadow, &UrpShadowFade),
    extras: LightExtras<'_>,
    gbuffer3: Vec<u8>,
) -> Result<Vec<u8>, GpuError> {
    let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
    job.width = scene.width;
    job.height = scene.height;
    job.targets = vec![
        ColorTarget::new(TargetFormat::Rg11b10Ufloat)
            .with_blend(light_blend(light.kind))
            .with_initial(gbuffer3),
    ];
    job.resources = resources(scene, camera, gbuffer, light, main);
    job.resources
        .extend(main_shadow_resources(main_shadow.0, main_shadow.1));
    if let Some((atlas, index)) = extras.additional {
        job.resources.extend(atlas.resources());
        job.resources
            .push(AdditionalAtlas::shadow_light_index(index));
    }
    if let Some(cookie) = extras.cookie {
        job.resources.extend(cookie.resources());
    }
    if let Some(occlusion) = extras.occlusion {
        job.resources.extend(occlusion.resources());
    }
    Ok(render(ctx, &job)?.remove(0))
}

/// The rig's point and spot lights' shadows ([`rig_casting`]) for the lighting checks, their
/// fade ramped across the positions the pass rebuilds from the rig's depth that they shadow.
pub(crate) fn additional_shadows(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
) -> Result<AdditionalAtlas, GpuError> {
    let casting = rig_casting(rig);
    let atlas = AdditionalAtlas::render(
        ctx,
        lib,
        "stencil_deferred/PunctualLit",
        &casting,
        UrpShadowFade::NONE,
    )?;
    let positions: Vec<Vec3> = scene
        .pixels()
        .map(|(x, y)| rig.deferred_position(scene, x, y))
        .collect();
    let in_shadow: Vec<Vec3> = casting
        .iter()
        .enumerate()
        .flat_map(|(i, _)| atlas.shadowed(i, &positions))
        .collect();
    Ok(atlas.faded(fade_across(&in_shadow, scene.scene.camera_position)))
}

/// The main light's shadow fade of the lighting checks: [`fade_across`] the positions the
/// lighting pass rebuilds from the rig's depth where `shadow`'s map darkens the main light.
pub(crate) fn lighting_fade(
    rig: &LightRig,
    scene: &TestScene,
    shadow: &ScreenShadow,
) -> UrpShadowFade {
    let positions: Vec<Vec3> = scene
        .pixels()
        .map(|(x, y)| rig.deferred_position(scene, x, y))
        .collect();
    fade_across(&shadowed(shadow, &positions), scene.scene.camera_position)
}

/// The positions among `positions` where `shadow`'s map (one tap) darkens the main light.
pub(crate) fn shadowed(shadow: &ScreenShadow, positions: &[Vec3]) -> Vec<Vec3> {
    let keywords = ShadowKeywords {
        depth: true,
        ..ShadowKeywords::default()
    };
    let maps = ShadowMaps {
        map: Some(&shadow.map),
        cube: None,
    };
    positions
        .iter()
        .copied()
        .filter(|&p| shadow_factor(&shadow.params, keywords, maps, p).1 < 1.0)
        .collect()
}

/// The main light's map: the rig's `DIRECTIONAL` light's of [`super::screen_shadows`].
pub(crate) fn main_light_shadow<'r>(
    rig: &'r LightRig,
    what: &str,
) -> Result<&'r ScreenShadow, GpuError> {
    rig.screen_shadows
        .as_ref()
        .and_then(|s| s.light(LightType::Directional))
        .ok_or_else(|| {
            GpuError::from(CheckError::UnknownToReference {
                variant: what.to_owned(),
                message: "the main light's shadow map was not rendered".to_owned(),
            })
        })
}

/// URP's blend of a lighting draw: a directional light's [`keep_blend`], a punctual light's
/// [`add_blend`].
pub(crate) fn light_blend(kind: UrpLightKind) -> wgpu::BlendState {
    match kind {
        UrpLightKind::Directional => keep_blend(),
        UrpLightKind::Point | UrpLightKind::Spot => add_blend(),
    }
}

/// URP's blend of the directional lights and the SSAOOnly pass: `One SrcAlpha` on colour
/// (GBuffer3 = light + GBuffer3 · alpha, the alpha what GBuffer3 keeps), `Zero One` on alpha.
pub(crate) fn keep_blend() -> wgpu::BlendState {
    wgpu::BlendState {
        color: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::SrcAlpha,
            operation: wgpu::BlendOperation::Add,
        },
        ..add_blend()
    }
}

/// URP's punctual lighting blend: `One One` on colour (GBuffer3 += light), `Zero One` on alpha.
pub(crate) fn add_blend() -> wgpu::BlendState {
    wgpu::BlendState {
        color: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        },
        alpha: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        },
    }
}

/// Bindings 0-7 of a lighting draw: GBuffer0-2 (GBuffer0 as `Rgba8UnormSrgb`, so loads decode
/// the albedo), the depth and camera, the light (binding 7 for the main light, else 5) and the
/// rendering layers (`R32Uint`).
fn resources(
    scene: &TestScene,
    camera: &LightingCamera<'_>,
    gbuffer: &UrpGBuffer,
    light: &UrpLightParams,
    main: bool,
) -> Vec<BoundResource> {
    let (w, h) = (scene.width, scene.height);
    let normal_format = if gbuffer.oct {
        TargetFormat::Rgba8Unorm
    } else {
        TargetFormat::Rgba8Snorm
    };
    let mut out = vec![
        BoundResource::new(
            0,
            0,
            texture(TargetFormat::Rgba8UnormSrgb, w, h, &gbuffer.targets[0]),
        ),
        BoundResource::new(
            0,
            1,
            texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[1]),
        ),
        BoundResource::new(0, 2, texture(normal_format, w, h, &gbuffer.targets[2])),
        BoundResource::new(
            0,
            if main { 7 } else { 5 },
            Resource::Uniform(light.uniform()),
        ),
    ];
    if let Some(layers) = gbuffer.rendering_layers() {
        out.push(BoundResource::new(
            0,
            6,
            texture(TargetFormat::R32Uint, w, h, layers),
        ));
    }
    out.extend(depth_camera_resources((scene.width, scene.height), camera));
    out
}

/// URP's stencil bit 4, StencilLight: set by a light's stencil-volume pass (URP's `StencilUsage`).
pub const STENCIL_LIGHT: u32 = 0x10;
/// URP's stencil bits 5-6: the material type the G-buffer pass writes.
pub const STENCIL_MATERIAL_MASK: u32 = 0x60;
/// Material type Lit (`0b01 << 5`).
pub const STENCIL_LIT: u32 = 0x20;
/// Material type Unlit (`0b00 << 5`).
pub const STENCIL_UNLIT: u32 = 0x00;

/// URP's stencil use for a point or spot light (`StencilDeferred.shader`, docs/urp.md §9), over
/// a stencil whose left half the G-buffer pass stamped Lit and right half Unlit:
/// - the stencil volume (both faces, depth test LessEqual) tests `NotEqual` Unlit through the
///   material mask and inverts StencilLight where the depth test fails: the pixels whose
///   geometry lies inside the volume end up marked (one face behind the geometry), those in
///   front (two) or behind (none) do not;
/// - the Lit lighting pass (back faces, GreaterEqual) tests `Equal` StencilLight | Lit through
///   StencilLight | the material mask and zeroes StencilLight where it passes.
pub(crate) fn urp_stencil_scheme(width: u32) -> StencilScheme {
    let face = |compare, pass_op, depth_fail_op| wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op,
        pass_op,
    };
    let both = |f: wgpu::StencilFaceState, read_mask, write_mask| wgpu::StencilState {
        front: f,
        back: f,
        read_mask,
        write_mask,
    };
    let keep = wgpu::StencilOperation::Keep;
    StencilScheme {
        stamps: vec![
            (0..width / 2, STENCIL_LIT),
            (width / 2..width, STENCIL_UNLIT),
        ],
        stamp_mask: STENCIL_MATERIAL_MASK,
        mark_cull: None,
        mark: (
            both(
                face(
                    wgpu::CompareFunction::NotEqual,
                    keep,
                    wgpu::StencilOperation::Invert,
                ),
                STENCIL_MATERIAL_MASK,
                STENCIL_LIGHT,
            ),
            STENCIL_UNLIT,
        ),
        light: (
            both(
                face(
                    wgpu::CompareFunction::Equal,
                    wgpu::StencilOperation::Zero,
                    keep,
                ),
                STENCIL_LIGHT | STENCIL_MATERIAL_MASK,
                STENCIL_LIGHT,
            ),
            STENCIL_LIGHT | STENCIL_LIT,
        ),
    }
}

/// One URP light drawn as its volume with URP's stencil scheme and full-screen, compared.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UrpVolumeComparison {
    /// Pixels (row-major) where the volume draw differs from what URP's scheme must give: the
    /// full-screen result on the Lit half, GBuffer3 untouched on the Unlit half.
    pub differing: Vec<usize>,
    /// Lit-half pixels the light changed.
    pub lit: usize,
    /// Unlit-half pixels the full-screen draw changed (so the material test matters).
    pub unlit_reached: usize,
    /// Pixels whose StencilLight bit is still set after the light (URP's pass zeroes it).
    pub stencil_light_left: usize,
}

/// Draws the check's `kind` light (point or spot) of `PunctualLit` over a URP G-buffer as its
/// volume (`crate::light_volume`) with URP's stencil scheme (`urp_stencil_scheme`, docs/urp.md §9),
/// and full-screen, and compares.
///
/// # Errors
/// [`GpuError`] from the draws; a light that would be drawn full-screen (crossing the near
/// plane) or that the reference refuses is a [`CheckError::UnknownToReference`].
pub fn compare_urp_volume(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    kind: UrpLightKind,
) -> Result<UrpVolumeComparison, GpuError> {
    let what = format!("stencil_deferred/PunctualLit {kind:?} volume");
    let refused = |message: String| {
        GpuError::from(CheckError::UnknownToReference {
            variant: what.clone(),
            message,
        })
    };
    let urp = UrpScene::new(scene, super::urp::DEFAULT_SEED);
    let gbuffer = render_urp_gbuffer(ctx, lib, &urp, &["_NORMALMAP", "_GBUFFER_NORMALS_OCT"])?;
    let lights = UrpLights::new(rig);
    let light = lights.params(kind, false, MATCHING_LAYERS)?;
    let shape = match kind {
        UrpLightKind::Point => lights.point,
        UrpLightKind::Spot => lights.spot,
        UrpLightKind::Directional => {
            return Err(refused("directional lights have no volume".into()));
        }
    };
    let volume = match light_draw(&shape, rig.view_proj).map_err(|e| refused(e.to_string()))? {
        LightDraw::Volume(volume) => volume,
        LightDraw::FullScreen(reason) => {
            return Err(refused(format!("drawn full-screen: {reason:?}")));
        }
    };
    let variant = lib
        .variant(
            "stencil_deferred",
            "PunctualLit",
            &[kind.keyword(), "_GBUFFER_NORMALS_OCT"],
        )
        .map_err(|e| CheckError::lookup("stencil_deferred/PunctualLit", e))?;
    let (label, wgsl) = (variant.label(), lib.wgsl(&variant));
    let stencil_pass = lib
        .variant("stencil_write", "StencilWrite", &[] as &[&str])
        .map_err(|e| CheckError::lookup("stencil_write/StencilWrite", e))?;
    let camera = rig.camera(scene);
    let main_shadow = main_light_shadow(rig, &what)?;
    let fade = lighting_fade(rig, scene, main_shadow);
    let initial = gbuffer.targets[3].clone();
    let full = draw_light(
        ctx,
        (&label, &wgsl),
        scene,
        &camera,
        &gbuffer,
        (&light, false),
        (main_shadow, &fade),
        LightExtras::default(),
        initial.clone(),
    )?;
    let input = LightPipelineInput {
        label: &label,
        wgsl: &wgsl,
        resources: resources(scene, &camera, &gbuffer, &light, false),
        format: wgpu::TextureFormat::Rg11b10Ufloat,
        blend: add_blend(),
        rt3: initial.clone(),
    };
    let (volume_rt3, stencil) = render_volume(
        ctx,
        scene,
        rig,
        &lib.wgsl(&stencil_pass),
        input,
        &volume,
        &urp_stencil_scheme(scene.width),
    )?;
    let px = |b: &[u8], i: usize| b[i * 4..i * 4 + 4].to_vec();
    let half = scene.width / 2;
    let (mut differing, mut lit, mut unlit_reached) = (Vec::new(), 0, 0);
    for (i, (x, _)) in scene.pixels().enumerate() {
        let changed = px(&full, i) != px(&initial, i);
        let want = if x < half {
            lit += usize::from(changed);
            px(&full, i)
        } else {
            unlit_reached += usize::from(changed);
            px(&initial, i)
        };
        if px(&volume_rt3, i) != want {
            differing.push(i);
        }
    }
    Ok(UrpVolumeComparison {
        differing,
        lit,
        unlit_reached,
        stencil_light_left: stencil
            .iter()
            .filter(|&&s| u32::from(s) & STENCIL_LIGHT != 0)
            .count(),
    })
}

/// A `stencil_deferred` pass in the check's registry.
pub(crate) struct StencilDeferred {
    passes: &'static [(&'static str, &'static str)],
}

/// The entry of `stencil_deferred/PunctualLit`.
pub(crate) static PUNCTUAL_LIT: StencilDeferred = StencilDeferred {
    passes: &[("stencil_deferred", "PunctualLit")],
};

/// The entry of `stencil_deferred/DirectionalLit`.
pub(crate) static DIRECTIONAL_LIT: StencilDeferred = StencilDeferred {
    passes: &[("stencil_deferred", "DirectionalLit")],
};

impl PassCheck for StencilDeferred {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        self.passes
    }

    /// The main light's map is the rig's `DIRECTIONAL` light's.
    fn needs(&self) -> Needs {
        Needs {
            screen_masks: true,
            ..Needs::NOTHING
        }
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        _selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        Ok(vec![check_stencil_deferred(
            setup.ctx,
            setup.lib,
            setup.scene,
            setup.rig,
            self.passes[0].1,
            setup.options,
        )?])
    }
}

#[cfg(test)]
mod tests {
    use super::super::urp::RENDERING_LAYERS;
    use super::*;

    #[test]
    fn layer_masks_match_and_miss_the_mesh() {
        assert_ne!(RENDERING_LAYERS & MATCHING_LAYERS, 0);
        assert_eq!(RENDERING_LAYERS & OTHER_LAYERS, 0);
    }

    #[test]
    fn every_light_of_the_check_is_accepted_and_reaches_the_scene() {
        let scene = TestScene::default();
        let rig = LightRig::new(&scene);
        let lights = UrpLights::new(&rig);
        for (kind, main) in [
            (UrpLightKind::Point, false),
            (UrpLightKind::Spot, false),
            (UrpLightKind::Directional, false),
            (UrpLightKind::Directional, true),
        ] {
            let light = lights.params(kind, main, MATCHING_LAYERS).unwrap();
            let lit = scene
                .pixels()
                .filter(|&(x, y)| light.sample(rig.deferred_position(&scene, x, y)).1 > 0.0)
                .count();
            assert!(lit > 20, "{kind:?} lights {lit} pixels");
        }
    }
}
