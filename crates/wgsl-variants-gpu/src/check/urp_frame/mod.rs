//! URP's frame end to end (docs/urp.md §12): one scene ([`UrpFrame`]: the built-in frame's
//! camera and opaque objects with URP Lit materials, a main light with its soft shadow and
//! three additional lights on rendering layers, two of them casting shadows; the main light,
//! the cool point light and the spot with cookies, [`UrpFrameCookies`]) drawn both ways
//! URP draws it, into the HDR camera target (`Rg11b10Ufloat`), after the shadows
//! ([`render_urp_shadows`]: the main light's map or cascades, the additional lights' atlas):
//!
//! - **forward** ([`render_urp_forward`]): `universal_lit/UniversalForward` per object, every
//!   light per pixel (`_ADDITIONAL_LIGHTS`, `_LIGHT_LAYERS`); with screen-space shadows after
//!   URP's depth prepass (`universal_lit/DepthOnly` per object) and the screen-space pass over
//!   its depth;
//! - **deferred** ([`render_urp_deferred`]): `universal_lit/UniversalGBuffer` per object
//!   (octahedral normals, rendering layers; each object stamps the Lit material type into the
//!   stencil), then `stencil_deferred`'s `DirectionalLit` for the main light, full screen,
//!   passing only where the stencil holds the Lit material type, and `PunctualLit` per
//!   additional light over its volume after URP's stencil volume pass (full screen where the
//!   volume crosses the near plane), blended One/One onto GBuffer3.
//!
//! [`compare`] holds every pixel both ways: forward against
//! [`wgsl_variants_shaders::reference::urp::forward::shade_forward`] over the pixel's
//! sub-pixel window; the G-buffer's texels against
//! [`wgsl_variants_shaders::reference::urp::gbuffer::shade_gbuffer`]; GBuffer3 after the
//! lights against [`stencil_deferred_light`] on the G-buffer as read back (the chain of stores
//! through [`rg11b10_store_range`]); and forward against deferred within what the G-buffer's
//! quantization changes in the reference's light ([`UrpFrameReport`]).

mod scene;
mod shadow;

use std::fmt;
use std::sync::Arc;

use glam::Vec3;

pub use scene::{
    DEFAULT_LAYER, EVERY_LAYER, SHELTERED_LAYERS, UrpFrame, UrpFrameCookies, UrpFrameLight,
    UrpFrameObject,
};
pub use shadow::{
    ADDITIONAL_SLICE_SIZE, MAIN_SHADOW_MAP_SIZE, UrpAdditionalShadowSpec, UrpFrameShadow,
    UrpFrameShadows, UrpShadowMaps, UrpShadowSpec, render_urp_shadows,
};

use super::camera::deferred_camera;
use super::scene::{push_mat4, texture};
use super::screen_masks::render_mask;
use super::urp::urp_targets;
use super::urp_additional_shadows::AdditionalAtlas;
use super::urp_lighting::{
    STENCIL_LIGHT, STENCIL_LIT, STENCIL_MATERIAL_MASK, STENCIL_UNLIT, add_blend, light_blend,
};
use super::volume_draw::{depth_fill_draw, over_volume, stencil_fill_draw};
use crate::light_volume::{LightDraw, light_draw};
use crate::{
    BoundResource, CheckError, ColorTarget, DEPTH_STENCIL_FORMAT, DepthTest, Draw, DrawPass,
    GpuContext, GpuError, Resource, StencilTest, TargetFormat, VertexBuffer, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::world_from_depth;
use wgsl_variants_shaders::reference::surface::Geometry;
use wgsl_variants_shaders::reference::tolerance::{
    rg11b10_store_range, urp_texel_within_window, window_offsets, window_range,
};
use wgsl_variants_shaders::reference::urp::ambient_occlusion::{
    AmbientOcclusionFactor, deferred_indirect_occlusion,
};
use wgsl_variants_shaders::reference::urp::forward::{
    CookieTints, ForwardInputs, MainLightShadow, UrpForwardKeywords, UrpForwardLights,
    shade_forward,
};
use wgsl_variants_shaders::reference::urp::gbuffer::{
    UrpGBufferOutput, UrpTexel, shade_gbuffer, urp_surface,
};
use wgsl_variants_shaders::reference::urp::lighting::{
    UrpGBufferTexel, UrpLightKind, UrpLightParams, stencil_deferred_light,
};
use wgsl_variants_shaders::reference::urp::ufloat::unpack_rg11b10;

/// The forward pass's own keywords in the frame: every additional light per pixel, the
/// lights' rendering layers honoured.
pub const FORWARD_KEYWORDS: [&str; 2] = ["_ADDITIONAL_LIGHTS", "_LIGHT_LAYERS"];

/// The G-buffer pass's own keywords in the frame: octahedral normals and the rendering-layers
/// target the lighting passes read for `_LIGHT_LAYERS`.
pub const GBUFFER_KEYWORDS: [&str; 2] = ["_GBUFFER_NORMALS_OCT", "_WRITE_RENDERING_LAYERS"];

/// The camera target's format in both paths (URP's default HDR colour format; GBuffer3).
const TARGET: TargetFormat = TargetFormat::Rg11b10Ufloat;

/// The forward path's image: the camera target's bytes, the depth prepass's depths and the
/// draws that made it.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpForwardImage {
    /// The `Rg11b10Ufloat` camera target, row by row.
    pub bytes: Vec<u8>,
    /// The `DepthOnly` prepass's depths, one `f32` per pixel, with screen-space shadows (what
    /// the screen-space pass rebuilt its positions from).
    pub depth: Option<Vec<f32>>,
    /// Draws made.
    pub draws: usize,
}

/// The deferred path's images: the G-buffer pass's targets and depth, and GBuffer3 after the
/// lights.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpDeferredImage {
    /// GBuffer0–3 and the rendering layers, as the G-buffer pass left them.
    pub gbuffer: Vec<Vec<u8>>,
    /// The G-buffer pass's depth, one `f32` per pixel.
    pub depth: Vec<f32>,
    /// GBuffer3 after every light (`Rg11b10Ufloat`): the frame.
    pub lit: Vec<u8>,
    /// Draws made (the harness's depth and stencil hand-over not counted).
    pub draws: usize,
    /// Additional lights drawn as their volumes (each after its stencil volume pass).
    pub volumes: usize,
}

/// A variant's label and composed text.
fn text(
    lib: &Library,
    shader: &str,
    pass: &str,
    names: &[&str],
) -> Result<(String, Arc<str>), GpuError> {
    let variant = lib
        .variant(shader, pass, names)
        .map_err(|e| CheckError::lookup(format!("{shader}/{pass} {names:?}"), e))?;
    Ok((variant.label(), Arc::from(lib.wgsl(&variant))))
}

/// The lights' shadows and cookies and the screen-space occlusion as a receiver takes them:
/// their keywords and bindings.
#[derive(Clone, Debug, Default)]
struct Receiver {
    keywords: Vec<&'static str>,
    resources: Vec<BoundResource>,
}

/// Object `o`'s draw of a `universal_lit` pass: the object's material keywords the pass
/// declares (as Unity applies a material's keywords to each pass), the pass's own keywords
/// `extra`, and the lights' shadows, cookies and occlusion as `receiver` takes them.
fn object_draw(
    lib: &Library,
    frame: &UrpFrame,
    o: usize,
    pass: &str,
    extra: &[&str],
    receiver: &Receiver,
) -> Result<Draw, GpuError> {
    let object = &frame.geometry.objects[o];
    let declared = lib
        .pass("universal_lit", pass)
        .map_err(|e| CheckError::lookup(format!("universal_lit/{pass}"), e))?;
    let mut names: Vec<&str> = frame.objects[o]
        .keywords
        .iter()
        .copied()
        .filter(|k| declared.keyword(k).is_some())
        .collect();
    names.extend(extra);
    names.extend(&receiver.keywords);
    let mut resources = frame.object_resources(o)?;
    resources.extend(receiver.resources.iter().cloned());
    let (label, wgsl) = text(lib, "universal_lit", pass, &names)?;
    Ok(Draw::fullscreen(
        &format!("{} {label}", object.name),
        &wgsl,
        "vs_main",
        "fs_main",
    )
    .with_mesh(object.mesh())
    .with_resources(resources)
    .with_depth(DepthTest::OPAQUE))
}

/// Every object's [`object_draw`] of a `universal_lit` pass, in the frame's order.
fn object_draws(
    lib: &Library,
    frame: &UrpFrame,
    pass: &str,
    extra: &[&str],
    receiver: &Receiver,
) -> Result<Vec<Draw>, GpuError> {
    (0..frame.geometry.objects.len())
        .map(|o| object_draw(lib, frame, o, pass, extra, receiver))
        .collect()
}

/// Renders the forward path: `UniversalForward` per object into the camera target, reading
/// the `shadows` ([`render_urp_shadows`]); with screen-space shadows, after URP's depth
/// prepass (`DepthOnly` per object) and the screen-space pass over its depth.
pub fn render_urp_forward(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
    shadows: &UrpFrameShadows,
) -> Result<UrpForwardImage, GpuError> {
    let g = &frame.geometry;
    let (mut receiver, mut draws, mut depth) = (Receiver::default(), 0, None);
    receiver.keywords = shadows.forward_keywords();
    receiver.keywords.extend(frame.cookie_keywords());
    receiver.keywords.extend(frame.occlusion_keywords());
    receiver.resources = frame.cookie_resources();
    receiver.resources.extend(frame.occlusion_resources());
    if let Some(a) = &shadows.additional {
        receiver.resources.extend(a.resources());
    }
    if let Some(s) = &shadows.main {
        receiver.resources.extend(s.resources());
        if s.screen {
            let prepass = render_depth_prepass(ctx, lib, frame)?;
            let inputs = [
                BoundResource::new(0, 3, depth_texture(g.width, g.height, &prepass)),
                BoundResource::new(
                    0,
                    4,
                    Resource::Uniform(deferred_camera(g.view_proj, g.scene.camera_position)),
                ),
            ];
            receiver
                .resources
                .push(render_screen_shadow(ctx, lib, frame, s, &inputs)?);
            draws += g.objects.len() + 1;
            depth = Some(prepass);
        }
    }
    let mut pass = DrawPass::new(
        "URP frame: forward",
        g.width,
        g.height,
        vec![ColorTarget::new(TARGET)],
    );
    pass.depth = true;
    pass.draws = object_draws(lib, frame, "UniversalForward", &FORWARD_KEYWORDS, &receiver)?;
    draws += pass.draws.len();
    Ok(UrpForwardImage {
        bytes: render_pass(ctx, &pass)?.targets.remove(0),
        depth,
        draws,
    })
}

/// URP's depth prepass of the forward path: `universal_lit/DepthOnly` per object, depth
/// tested, into an `R32Float` target cleared to the far plane: its depths, row by row.
fn render_depth_prepass(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<Vec<f32>, GpuError> {
    let g = &frame.geometry;
    let mut pass = DrawPass::new(
        "URP frame: depth prepass",
        g.width,
        g.height,
        vec![ColorTarget::new(TargetFormat::R32Float).with_clear([1.0, 0.0, 0.0, 0.0])],
    );
    pass.depth = true;
    pass.draws = object_draws(lib, frame, "DepthOnly", &[], &Receiver::default())?;
    let bytes = render_pass(ctx, &pass)?.targets.remove(0);
    Ok(bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect())
}

/// A camera's depths as the `R32Float` texture the full-screen passes read (binding 3).
fn depth_texture(width: u32, height: u32, depth: &[f32]) -> Resource {
    Resource::Texture2d {
        format: wgpu::TextureFormat::R32Float,
        width,
        height,
        data: depth.iter().flat_map(|d| d.to_le_bytes()).collect(),
    }
}

/// URP's stencil volume pass (`StencilDeferred.shader`, "Stencil Volume"; docs/urp.md §9): a
/// punctual light's volume, both faces, depth test LessEqual without writes; where the
/// material type is not Unlit, each face whose depth test fails inverts StencilLight, so the
/// pixels whose surface lies inside the volume end up marked.
const VOLUME_MARK: StencilTest = StencilTest {
    compare: wgpu::CompareFunction::NotEqual,
    fail_op: wgpu::StencilOperation::Keep,
    depth_fail_op: wgpu::StencilOperation::Invert,
    pass_op: wgpu::StencilOperation::Keep,
    read_mask: STENCIL_MATERIAL_MASK,
    write_mask: STENCIL_LIGHT,
    reference: STENCIL_UNLIT,
};

/// The punctual Lit pass over its volume: passes where StencilLight and the Lit material type
/// are set, and zeroes StencilLight there.
const VOLUME_LIGHT: StencilTest = StencilTest {
    compare: wgpu::CompareFunction::Equal,
    fail_op: wgpu::StencilOperation::Keep,
    depth_fail_op: wgpu::StencilOperation::Keep,
    pass_op: wgpu::StencilOperation::Zero,
    read_mask: STENCIL_LIGHT | STENCIL_MATERIAL_MASK,
    write_mask: STENCIL_LIGHT,
    reference: STENCIL_LIGHT | STENCIL_LIT,
};

/// The draws of the lighting pass after the depth and stencil hand-over, and how many lights
/// were drawn as volumes: the main light (`DirectionalLit`, `_DEFERRED_MAIN_LIGHT`) full
/// screen where the stencil holds the Lit material type; each additional light
/// (`PunctualLit`) as its volume after URP's stencil volume pass, or full screen like the main
/// light where its volume crosses the near plane ([`light_draw`]).
fn light_draws(
    lib: &Library,
    frame: &UrpFrame,
    shadows: &UrpFrameShadows,
    screen: Option<BoundResource>,
    shared: &Arc<[BoundResource]>,
) -> Result<(Vec<Draw>, usize), GpuError> {
    let lit = StencilTest::equal(STENCIL_LIT, STENCIL_MATERIAL_MASK);
    let common = ["_GBUFFER_NORMALS_OCT", "_LIGHT_LAYERS"];
    let light_resource = |binding, light: &UrpLightParams| {
        vec![BoundResource::new(
            0,
            binding,
            Resource::Uniform(light.uniform()),
        )]
    };
    let cookies = frame.draw_cookies();
    let occlusion = frame.occlusion_keywords();
    // What every light draw receives: its cookie (`_LIGHT_COOKIES` and its bindings) where the
    // light has one, and the screen-space occlusion.
    let receive = |k: usize, names: &mut Vec<&'static str>, resources: &mut Vec<BoundResource>| {
        if let Some(c) = cookies[k] {
            names.push("_LIGHT_COOKIES");
            resources.extend(c.resources());
        }
        names.extend(&occlusion);
        resources.extend(frame.occlusion_resources());
    };
    let mut names = vec!["_DIRECTIONAL", "_DEFERRED_MAIN_LIGHT"];
    names.extend(common);
    let mut main_resources = light_resource(7, &frame.main_light);
    if let Some(s) = &shadows.main {
        names.extend(s.receiver_keywords());
        main_resources.extend(s.resources());
    }
    receive(0, &mut names, &mut main_resources);
    // The main light is the first directional light: with the screen-space occlusion it also
    // scales GBuffer3 by the indirect part (blended One SrcAlpha).
    if frame.occlusion.is_some() {
        names.push("_DEFERRED_FIRST_LIGHT");
    }
    main_resources.extend(screen);
    let (label, wgsl) = text(lib, "stencil_deferred", "DirectionalLit", &names)?;
    let mut main_draw = Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
        .with_shared(shared)
        .with_resources(main_resources)
        .with_stencil(lit);
    main_draw.blend = Some(light_blend(UrpLightKind::Directional));
    let mut draws = vec![main_draw];
    let (mark_label, mark_wgsl) = text(lib, "stencil_write", "StencilWrite", &[])?;
    let mut camera = Vec::new();
    push_mat4(&mut camera, frame.geometry.view_proj);
    let mut volumes = 0;
    for (k, l) in frame.lights.iter().enumerate() {
        let mut names = vec![match l.params.kind {
            UrpLightKind::Spot => "_SPOT",
            _ => "_POINT",
        }];
        names.extend(common);
        names.extend(shadows.additional_keywords());
        let mut resources = light_resource(5, &l.params);
        if let Some(a) = &shadows.additional {
            resources.push(AdditionalAtlas::shadow_light_index(k as u32));
            resources.extend(a.resources());
        }
        receive(k + 1, &mut names, &mut resources);
        let (label, wgsl) = text(lib, "stencil_deferred", "PunctualLit", &names)?;
        let draw = Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
            .with_shared(shared)
            .with_resources(resources);
        let volume =
            light_draw(&l.light, frame.geometry.view_proj).map_err(|e| GpuError::Validation {
                label: label.clone(),
                message: e.to_string(),
            })?;
        match volume {
            LightDraw::Volume(v) => {
                volumes += 1;
                draws.push(
                    Draw::fullscreen(&mark_label, &mark_wgsl, "vs_main", "fs_main")
                        .depth_only()
                        .with_mesh(VertexBuffer::from_f32(&[(0, 3)], &v.positions))
                        .with_resources(vec![BoundResource::new(
                            0,
                            0,
                            Resource::Uniform(camera.clone()),
                        )])
                        .with_depth(DepthTest {
                            compare: wgpu::CompareFunction::LessEqual,
                            write: false,
                        })
                        .with_stencil(VOLUME_MARK),
                );
                draws.push(over_volume(draw, "vs_volume", &v).with_stencil(VOLUME_LIGHT));
            }
            LightDraw::FullScreen(_) => draws.push(draw.with_stencil(lit)),
        }
    }
    Ok((draws, volumes))
}

/// Renders the deferred path: the G-buffer pass (each object stamping the Lit material type
/// into the stencil, as URP's G-buffer pass does), then the lighting pass over GBuffer3, the
/// lights reading the `shadows` ([`render_urp_shadows`]).
pub fn render_urp_deferred(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
    shadows: &UrpFrameShadows,
) -> Result<UrpDeferredImage, GpuError> {
    let g = &frame.geometry;
    let (w, h) = (g.width, g.height);
    let targets = urp_targets(&GBUFFER_KEYWORDS)
        .into_iter()
        .map(|(_, t)| t.with_clear([0.0; 4]))
        .collect();
    let mut gbuffer = DrawPass::new("URP frame: G-buffer", w, h, targets);
    gbuffer.depth = true;
    gbuffer.depth_format = DEPTH_STENCIL_FORMAT;
    // URP's G-buffer pass: `Ref` the material type, `WriteMask` the material bits, `Pass
    // Replace`.
    let stamp = StencilTest {
        write_mask: STENCIL_MATERIAL_MASK,
        ..StencilTest::set(STENCIL_LIT)
    };
    gbuffer.draws = object_draws(
        lib,
        frame,
        "UniversalGBuffer",
        &GBUFFER_KEYWORDS,
        &Receiver::default(),
    )?
    .into_iter()
    .map(|d| d.with_stencil(stamp))
    .collect();
    let out = render_pass(ctx, &gbuffer)?;
    let depth = out.depth.unwrap_or_default();
    let marks = out.stencil.unwrap_or_default();
    let targets = out.targets;

    // The lighting pass gets the G-buffer's depth and stencil marks through fill draws (this
    // harness reads each pass back), then draws each light.
    let mut lighting = DrawPass::new(
        "URP frame: lighting",
        w,
        h,
        vec![
            ColorTarget::new(TARGET)
                .with_blend(add_blend())
                .with_initial(targets[3].clone()),
        ],
    );
    lighting.depth = true;
    lighting.depth_format = DEPTH_STENCIL_FORMAT;
    let depth_texture = depth_texture(w, h, &depth);
    lighting.draws.push(depth_fill_draw(depth_texture.clone()));
    lighting.draws.push(stencil_fill_draw(
        Resource::Texture2d {
            format: wgpu::TextureFormat::R8Uint,
            width: w,
            height: h,
            data: marks,
        },
        STENCIL_LIT,
    ));
    let shared: Arc<[BoundResource]> = Arc::from(vec![
        BoundResource::new(
            0,
            0,
            texture(TargetFormat::Rgba8UnormSrgb, w, h, &targets[0]),
        ),
        BoundResource::new(0, 1, texture(TargetFormat::Rgba8Unorm, w, h, &targets[1])),
        BoundResource::new(0, 2, texture(TargetFormat::Rgba8Unorm, w, h, &targets[2])),
        BoundResource::new(0, 3, depth_texture),
        BoundResource::new(
            0,
            4,
            Resource::Uniform(deferred_camera(g.view_proj, g.scene.camera_position)),
        ),
        BoundResource::new(0, 6, texture(TargetFormat::R32Uint, w, h, &targets[4])),
    ]);
    let screen = match shadows.main.as_ref().filter(|s| s.screen) {
        Some(s) => Some(render_screen_shadow(ctx, lib, frame, s, &shared)?),
        None => None,
    };
    let screen_draws = usize::from(screen.is_some());
    let (light_draws, volumes) = light_draws(lib, frame, shadows, screen, &shared)?;
    lighting.draws.extend(light_draws);
    let draws = gbuffer.draws.len() + screen_draws + lighting.draws.len() - 2;
    let lit = render_pass(ctx, &lighting)?.targets.remove(0);
    Ok(UrpDeferredImage {
        gbuffer: targets,
        depth,
        lit,
        draws,
        volumes,
    })
}

/// URP's `ScreenSpaceShadows` pass over the camera's depth (in `inputs`, binding 3, with the
/// camera at 4: the G-buffer pass's or the depth prepass's): the main light's map or cascades
/// as `shadow` holds them, with their keywords, into a camera-sized `Rgba8Unorm` target; the
/// target as the receivers' binding 16.
fn render_screen_shadow(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
    shadow: &UrpFrameShadow,
    inputs: &[BoundResource],
) -> Result<BoundResource, GpuError> {
    let g = &frame.geometry;
    let (w, h) = (g.width, g.height);
    let (label, wgsl) = text(
        lib,
        "universal_screen_space_shadows",
        "ScreenSpaceShadows",
        &shadow.map_keywords(),
    )?;
    let mut resources = inputs.to_vec();
    resources.extend(shadow.resources());
    let texels = render_mask(ctx, &label, &wgsl, (w, h), resources)?;
    Ok(BoundResource::new(
        0,
        16,
        texture(TargetFormat::Rgba8Unorm, w, h, &texels),
    ))
}

/// Which of the four judgements a pixel failed.
pub const JUDGEMENTS: [&str; 4] = [
    "forward vs reference",
    "G-buffer vs reference",
    "deferred lighting vs reference",
    "forward vs deferred",
];

/// One compared pixel out of tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpFrameMismatch {
    /// Pixel `(x, y)`.
    pub pixel: [u32; 2],
    /// The object the pixel sees (`background` for none).
    pub object: &'static str,
    /// Index into [`JUDGEMENTS`].
    pub judgement: usize,
    /// The allowed interval (or, for a G-buffer texel, the reference's texels at the centre).
    pub expected: String,
    /// What the GPU wrote.
    pub got: String,
}

/// The result of comparing the two paths' images with the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct UrpFrameReport {
    /// Draws of the forward path.
    pub forward_draws: usize,
    /// Draws of the deferred path.
    pub deferred_draws: usize,
    /// Additional lights the deferred path drew as their volumes.
    pub volumes: usize,
    /// Pixels whose whole sub-pixel window sees one object, compared.
    pub compared: usize,
    /// Pixels seeing no object (both paths must leave them black).
    pub background: usize,
    /// Pixels left out: their window crosses a silhouette.
    pub edges: usize,
    /// Failures per judgement ([`JUDGEMENTS`]).
    pub failures: [usize; 4],
    /// Per additional light: pixels where it adds more than 1 % of the light.
    pub lit_by: Vec<(&'static str, usize)>,
    /// Pixels where a light that the rendering layers keep off would add more than 1 %.
    pub layer_culled: usize,
    /// Compared pixels in the main light's shadow (some of its light blocked).
    pub shadowed: usize,
    /// Of those, pixels with a shadow tap within a hair of flipping (compared within the
    /// interval of both outcomes).
    pub uncertain: usize,
    /// Per additional light: pixels it lights where its own shadow blocks some of its light
    /// (`_ADDITIONAL_LIGHT_SHADOWS`).
    pub additional_shadowed: Vec<usize>,
    /// With `_MAIN_LIGHT_SHADOWS_CASCADE`, compared pixels per cascade URP's split spheres
    /// pick (0 to 3), in none, and in several (which URP's cascade index cannot handle; the
    /// frame must have none): all of them, and those in the shadow. Zeros with one map.
    pub cascades: [[usize; 6]; 2],
    /// With `_LIGHT_COOKIES`, the main light's cookie texels (their colours) seen at the
    /// compared pixels' centres clear of an edge (0 without cookies).
    pub main_cookie_texels: usize,
    /// Per light (the main light first, then each additional light): compared pixels whose
    /// centre lies within 1/64 texel of an edge of the light's cookie (compared within the
    /// range of the texels).
    pub cookie_edges: Vec<usize>,
    /// With `_SCREEN_SPACE_OCCLUSION`, compared pixels where the main light (the first
    /// directional light) scales GBuffer3 by less than 1.
    pub occluded: usize,
    /// The first mismatches, in pixel order (at most 20).
    pub mismatches: Vec<UrpFrameMismatch>,
}

impl UrpFrameReport {
    /// Whether every judgement held at every pixel.
    pub fn passed(&self) -> bool {
        self.failures.iter().all(|&f| f == 0)
    }

    fn fail(
        &mut self,
        pixel: [u32; 2],
        object: &'static str,
        judgement: usize,
        expected: String,
        got: String,
    ) {
        self.failures[judgement] += 1;
        if self.mismatches.len() < 20 {
            self.mismatches.push(UrpFrameMismatch {
                pixel,
                object,
                judgement,
                expected,
                got,
            });
        }
    }
}

impl fmt::Display for UrpFrameReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "URP frame: {} pixels compared, {} background, {} silhouette pixels left out; forward {} draws, deferred {} draws ({} light volumes)",
            self.compared,
            self.background,
            self.edges,
            self.forward_draws,
            self.deferred_draws,
            self.volumes
        )?;
        for (name, failures) in JUDGEMENTS.iter().zip(self.failures) {
            writeln!(f, "  {name}: {failures} failures")?;
        }
        let lit: Vec<String> = self
            .lit_by
            .iter()
            .map(|(name, n)| format!("{name} {n}"))
            .collect();
        writeln!(
            f,
            "  pixels lit by: {}; {} pixels a light's rendering layers keep it off; {} in the main light's shadow ({} with a tap too close to call)",
            lit.join(", "),
            self.layer_culled,
            self.shadowed,
            self.uncertain
        )?;
        if self.additional_shadowed.iter().any(|&n| n > 0) {
            let shadowed: Vec<String> = self
                .lit_by
                .iter()
                .zip(&self.additional_shadowed)
                .map(|((name, _), n)| format!("{name} {n}"))
                .collect();
            writeln!(
                f,
                "  pixels in an additional light's own shadow: {}",
                shadowed.join(", ")
            )?;
        }
        if self.main_cookie_texels > 0 {
            writeln!(
                f,
                "  cookies: {} texels of the main light's seen; pixels on a cookie's texel edge (main light, then each additional light): {:?}",
                self.main_cookie_texels, self.cookie_edges
            )?;
        }
        if self.occluded > 0 {
            writeln!(
                f,
                "  screen-space occlusion: the main light scales GBuffer3 by less than 1 in {} pixels",
                self.occluded
            )?;
        }
        if self.cascades[0].iter().any(|&n| n > 0) {
            writeln!(
                f,
                "  cascades 0-3, none, several: {:?} pixels, {:?} of them in the shadow",
                self.cascades[0], self.cascades[1]
            )?;
        }
        for m in &self.mismatches {
            writeln!(
                f,
                "  ({}, {}) {}: {}: expected {}, got {}",
                m.pixel[0], m.pixel[1], m.object, JUDGEMENTS[m.judgement], m.expected, m.got
            )?;
        }
        Ok(())
    }
}

/// Renders the frame both ways and compares every pixel.
pub fn check_urp_frame(
    ctx: &GpuContext,
    lib: &Library,
    frame: &UrpFrame,
) -> Result<UrpFrameReport, GpuError> {
    let shadows = render_urp_shadows(ctx, lib, frame)?;
    let forward = render_urp_forward(ctx, lib, frame, &shadows)?;
    let deferred = render_urp_deferred(ctx, lib, frame, &shadows)?;
    compare(frame, &shadows, &forward, &deferred)
}

/// One point the forward reference shades: what varies between the candidates of a pixel.
struct ForwardSample<'a> {
    /// The object hit.
    object: usize,
    /// Where it is hit.
    geometry: &'a Geometry,
    /// The main light's shadow there (`None`: the frame has no main-light shadows).
    shadow: Option<MainLightShadow>,
    /// The additional lights' shadows and which end (0 the lower, 1 the upper) of each light's
    /// shadow interval.
    additional: (&'a UrpFrameShadows, usize),
    /// The cookies' tints ([`UrpFrame::cookie_tints`]).
    tints: CookieTints,
    /// The screen-space occlusion at the pixel.
    occlusion: AmbientOcclusionFactor,
}

/// What `UniversalForward` writes at `at` (black where it discards).
fn forward_reference(frame: &UrpFrame, lights: &UrpForwardLights, at: ForwardSample) -> Vec3 {
    let ForwardSample {
        object: o,
        geometry: geo,
        shadow,
        additional: (shadows, end),
        tints,
        occlusion,
    } = at;
    let mut names = frame.objects[o].keywords.to_vec();
    names.extend(FORWARD_KEYWORDS);
    names.extend(frame.cookie_keywords());
    names.extend(frame.occlusion_keywords());
    if shadow.is_some() {
        names.push("_MAIN_LIGHT_SHADOWS");
    }
    names.extend(shadows.additional_keywords());
    let k = UrpForwardKeywords::from_names(&names)
        .expect("the URP frame's keywords are UniversalForward's");
    let p = geo.world_position;
    let camera = frame.lighting.camera_position;
    let additional: Vec<f32> = lights
        .additional()
        .iter()
        .enumerate()
        .map(|(i, l)| shadows.additional_at(i, p, l.sample(p).0, camera)[end])
        .collect();
    let inputs = ForwardInputs {
        shadow: shadow.unwrap_or(MainLightShadow::NONE),
        additional_shadows: additional,
        tints,
        occlusion,
        ..ForwardInputs::NONE
    };
    shade_forward(
        &k,
        &frame.objects[o].material,
        &frame.texels(o),
        &frame.pixel(o, *geo),
        &frame.lighting,
        frame.environment(),
        lights,
        &inputs,
    )
    .unwrap_or(Vec3::ZERO)
}

/// The reference colour of pixel `(x, y)`: what the ray through its centre sees, lit by URP's
/// forward formulas and shadowed by `shadows` (the upper end of an uncertain tap, the first
/// cookie texel on an edge); `None` on the background.
///
/// # Errors
/// As [`UrpFrame::forward_lights`].
pub fn reference_rgb(
    frame: &UrpFrame,
    shadows: &UrpFrameShadows,
    x: u32,
    y: u32,
) -> Result<Option<Vec3>, GpuError> {
    let lights = frame.forward_lights()?;
    let hit = frame.geometry.cast(f64::from(x) + 0.5, f64::from(y) + 0.5);
    Ok(hit.map(|h| {
        let s = shadows
            .main
            .as_ref()
            .map(|s| s.at(h.geometry.world_position)[1]);
        let p = h.geometry.world_position;
        let tints = frame.cookie_tints(p, 1).swap_remove(0);
        let at = ForwardSample {
            object: h.object,
            geometry: &h.geometry,
            shadow: s,
            additional: (shadows, 1),
            tints,
            occlusion: frame.occlusion_at(x, y),
        };
        forward_reference(frame, &lights, at)
    }))
}

/// The texel `i` of a target of four-byte pixels.
fn word(bytes: &[u8], i: usize) -> [u8; 4] {
    [
        bytes[i * 4],
        bytes[i * 4 + 1],
        bytes[i * 4 + 2],
        bytes[i * 4 + 3],
    ]
}

/// `[lo, hi]` as text.
fn interval(lo: Vec3, hi: Vec3) -> String {
    format!("[{lo:.4}, {hi:.4}]")
}

/// Whether `v` lies in `[lo, hi]` on every channel.
fn inside(v: Vec3, lo: Vec3, hi: Vec3) -> bool {
    v.cmpge(lo).all() && v.cmple(hi).all()
}

/// The G-buffer texel the lighting pass would read if the G-buffer held the reference's exact
/// values.
fn exact_texel(
    out: &UrpGBufferOutput,
    flags: wgsl_variants_shaders::reference::urp::flags::MaterialFlags,
) -> UrpGBufferTexel {
    UrpGBufferTexel {
        albedo: out.gbuffer0.truncate(),
        flags,
        specular: out.gbuffer1.truncate(),
        normal: out.normal,
        smoothness: out.smoothness,
    }
}

/// Compares the two paths' images of `frame` with the reference, pixel by pixel.
///
/// # Errors
/// [`GpuError::Check`] when a G-buffer texel's flags byte has reserved bits set (the lighting
/// reference cannot read it).
pub fn compare(
    frame: &UrpFrame,
    shadows: &UrpFrameShadows,
    forward: &UrpForwardImage,
    deferred: &UrpDeferredImage,
) -> Result<UrpFrameReport, GpuError> {
    let shadow = shadows.main.as_ref();
    let g = &frame.geometry;
    let lights = frame.forward_lights()?;
    let env = frame.environment();
    let camera = frame.lighting.camera_position;
    let inv_view_proj = g.view_proj.inverse();
    let mut report = UrpFrameReport {
        forward_draws: forward.draws,
        deferred_draws: deferred.draws,
        volumes: deferred.volumes,
        compared: 0,
        background: 0,
        edges: 0,
        failures: [0; 4],
        lit_by: frame.lights.iter().map(|l| (l.name, 0)).collect(),
        layer_culled: 0,
        shadowed: 0,
        uncertain: 0,
        additional_shadowed: vec![0; frame.lights.len()],
        cascades: [[0; 6]; 2],
        main_cookie_texels: 0,
        cookie_edges: vec![0; frame.lights.len() + 1],
        occluded: 0,
        mismatches: Vec::new(),
    };
    let mut every_light: Vec<&UrpLightParams> = vec![&frame.main_light];
    every_light.extend(frame.lights.iter().map(|l| &l.params));
    // Each light's cookie, the main light's first; the main cookie's texels seen.
    let cookies = frame.draw_cookies();
    let mut main_cookie_seen = std::collections::BTreeSet::new();
    for (i, (x, y)) in g.pixels().enumerate() {
        let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        let hits: Vec<_> = window_offsets()
            .iter()
            .map(|&(dx, dy)| g.cast(cx + f64::from(dx), cy + f64::from(dy)))
            .collect();
        if !hits
            .iter()
            .all(|h| h.map(|h| h.object) == hits[0].map(|h| h.object))
        {
            report.edges += 1;
            continue;
        }
        let f_got = unpack_rg11b10(u32::from_le_bytes(word(&forward.bytes, i)));
        let d_got = unpack_rg11b10(u32::from_le_bytes(word(&deferred.lit, i)));
        let Some(hit) = hits[0] else {
            report.background += 1;
            // Nothing drawn: both targets keep their clear colour (the stencil keeps the
            // lights off).
            if f_got != Vec3::ZERO {
                report.fail(
                    [x, y],
                    "background",
                    0,
                    "0".to_owned(),
                    format!("{f_got:.4}"),
                );
            }
            if d_got != Vec3::ZERO {
                report.fail(
                    [x, y],
                    "background",
                    2,
                    "0".to_owned(),
                    format!("{d_got:.4}"),
                );
            }
            continue;
        };
        report.compared += 1;
        let o = hit.object;
        let name = g.objects[o].name;
        let geos: Vec<Geometry> = hits.iter().flatten().map(|h| h.geometry).collect();
        let material = &frame.objects[o].material;
        let tex = frame.texels(o);

        // Forward: the reference over the window (both ends of an uncertain shadow tap), stored
        // once; with screen-space shadows, the pass's texel at the position the prepass's depth
        // rebuilds.
        let shadows_at = |p: Vec3| shadow.map(|s| s.at(p));
        let prepass = forward
            .depth
            .as_ref()
            .map(|d| world_from_depth(inv_view_proj, x, y, g.width, g.height, d[i]));
        // Each texel the main light's cookie may read is shaded (the outcome need not grow
        // with it), the additional lights' cookies at the ends of their ranges.
        // The occlusion is the pixel's texel, the same at every window point.
        let ao = frame.occlusion_at(x, y);
        let mut values = Vec::with_capacity(2 * geos.len());
        for geo in &geos {
            let p = geo.world_position;
            let s = shadow.map(|s| s.received(prepass.unwrap_or(p), p));
            for k in [0, 1] {
                for tints in frame.cookie_tints(p, k) {
                    let at = ForwardSample {
                        object: o,
                        geometry: geo,
                        shadow: s.map(|s| s[k]),
                        additional: (shadows, k),
                        tints,
                        occlusion: ao,
                    };
                    values.push(forward_reference(frame, &lights, at));
                }
            }
        }
        let cookie_texels = |p: Vec3| {
            cookies
                .iter()
                .map(|c| c.map_or(1, |c| c.candidates(p).len()))
                .collect::<Vec<_>>()
        };
        for (k, n) in cookie_texels(hit.geometry.world_position)
            .into_iter()
            .enumerate()
        {
            report.cookie_edges[k] += usize::from(n > 1);
        }
        if let Some(c) = cookies[0]
            && let [texel] = c.candidates(hit.geometry.world_position)[..]
        {
            main_cookie_seen.insert(texel.to_array().map(f32::to_bits));
        }
        if let Some([lo, hi]) = shadows_at(hit.geometry.world_position) {
            report.shadowed += usize::from(lo.attenuation < 1.0);
            report.uncertain += usize::from(lo.attenuation != hi.attenuation);
        }
        if let Some(k) = shadow.and_then(|s| s.cascade_at(hit.geometry.world_position)) {
            report.cascades[0][k] += 1;
            if shadows_at(hit.geometry.world_position).is_some_and(|s| s[0].attenuation < 1.0) {
                report.cascades[1][k] += 1;
            }
        }
        let (lo, hi) = window_range(&values);
        let (f_lo, f_hi) = rg11b10_store_range(lo, hi);
        if !inside(f_got, f_lo, f_hi) {
            report.fail([x, y], name, 0, interval(f_lo, f_hi), format!("{f_got:.4}"));
        }

        // The G-buffer: each target's texel against the reference at some window point.
        let gk = frame.surface_keywords(o, &GBUFFER_KEYWORDS);
        let outputs: Vec<UrpGBufferOutput> = geos
            .iter()
            .filter_map(|geo| {
                shade_gbuffer(
                    &gk,
                    material,
                    &tex,
                    &frame.pixel(o, *geo),
                    &frame.lighting,
                    env,
                )
            })
            .collect();
        let expected: Vec<_> = outputs.iter().map(|out| out.texels(&gk)).collect();
        for (t, target) in deferred.gbuffer.iter().enumerate() {
            let got = word(target, i);
            let window: Vec<UrpTexel> = expected.iter().map(|e| e[t]).collect();
            if !urp_texel_within_window(got, &window) {
                let centre = expected.first().map(|e| format!("{:?}", e[t]));
                report.fail(
                    [x, y],
                    name,
                    1,
                    format!(
                        "target {t}: {}",
                        centre.unwrap_or_else(|| "discarded".to_owned())
                    ),
                    format!("{got:?}"),
                );
            }
        }

        // The lighting: GBuffer3 as stored plus each light on the texel as read back, at the
        // position rebuilt from depth, stored after each light.
        let texel = UrpGBufferTexel::decode(
            word(&deferred.gbuffer[0], i),
            word(&deferred.gbuffer[1], i),
            word(&deferred.gbuffer[2], i),
            true,
        )
        .map_err(|e| CheckError::UnknownToReference {
            variant: "the URP frame's G-buffer".to_owned(),
            message: format!("texel ({x}, {y}): {e}"),
        })?;
        let layers = u32::from_le_bytes(word(&deferred.gbuffer[4], i));
        let stored = unpack_rg11b10(u32::from_le_bytes(word(&deferred.gbuffer[3], i)));
        let p = world_from_depth(inv_view_proj, x, y, g.width, g.height, deferred.depth[i]);
        // The main light's shadow at a position: its attenuation's two ends (1 without one).
        let main_shadow =
            |p: Vec3| shadow.map_or([1.0; 2], |s| s.received(p, p).map(|s| s.attenuation));
        // GetStencilLight: the light's colour times its cookie; the light grows with both,
        // so the ends of the cookie's and the shadow's ranges bound it.
        let light_at = |t: &UrpGBufferTexel, p: Vec3, i: usize, end: usize| {
            let shadow = if i == 0 {
                main_shadow(p)[end]
            } else {
                let to_light = every_light[i].sample(p).0;
                shadows.additional_at(i - 1, p, to_light, camera)[end]
            };
            let tint = cookies[i].map_or(Vec3::ONE, |c| {
                let (lo, hi) = c.color(p);
                [lo, hi][end]
            });
            let light = UrpLightParams {
                color: every_light[i].color * tint * ao.direct,
                ..*every_light[i]
            };
            stencil_deferred_light(t, p, camera, &light, shadow, Some(layers))
        };
        // The main light, the first directional light, scales GBuffer3 by the indirect
        // occlusion's ratio to the surface's (1 where its layers keep it off the texel).
        let first = |surface: f32| {
            let lit = frame.main_light.lights_layers(layers);
            if frame.occlusion.is_some() && lit {
                deferred_indirect_occlusion(ao.indirect, surface)
            } else {
                1.0
            }
        };
        let keep = first(f32::from(word(&deferred.gbuffer[1], i)[3]) / 255.0);
        report.occluded += usize::from(keep < 1.0);
        let (mut d_lo, mut d_hi) = (stored * keep, stored * keep);
        let mut decoded_light = Vec3::ZERO;
        for i in 0..every_light.len() {
            let (lo, hi) = (light_at(&texel, p, i, 0), light_at(&texel, p, i, 1));
            decoded_light += hi;
            (d_lo, d_hi) = rg11b10_store_range(d_lo + lo.min(hi), d_hi + lo.max(hi));
        }
        if !inside(d_got, d_lo, d_hi) {
            report.fail([x, y], name, 2, interval(d_lo, d_hi), format!("{d_got:.4}"));
        }

        // Forward against deferred: what the G-buffer's quantization changes in the
        // reference's light (the exact surface at the centre against the texel as read back),
        // plus both intervals' widths.
        let Some(centre) = outputs.first() else {
            continue;
        };
        let exact = exact_texel(centre, gk.flags());
        let q_point = hit.geometry.world_position;
        let exact_light: Vec3 = (0..every_light.len())
            .map(|i| light_at(&exact, q_point, i, 1))
            .sum();
        let exact_keep = first(centre.gbuffer1.w);
        let quantization =
            (centre.gbuffer3 * exact_keep + exact_light - stored * keep - decoded_light).abs();
        let allowance = quantization + (f_hi - f_lo) + (d_hi - d_lo);
        // URP's deferred path scales the whole of GBuffer3 by the occlusion, the emission with
        // the global illumination; the forward path leaves the emission whole.
        let emission = urp_surface(&gk, material, &tex).map_or(Vec3::ZERO, |s| s.emission);
        let expected = f_got + emission * (exact_keep - 1.0);
        if !inside(d_got, expected - allowance, expected + allowance) {
            report.fail(
                [x, y],
                name,
                3,
                interval(expected - allowance, expected + allowance),
                format!("{d_got:.4}"),
            );
        }

        // What the pixel shows: which additional light reaches it, and where a light's layers
        // keep it off.
        let total = values[0].max_element().max(1e-3);
        for (k, l) in frame.lights.iter().enumerate() {
            let tint = cookies[k + 1].map_or(Vec3::ONE, |c| c.color(q_point).1);
            let light = UrpLightParams {
                color: l.params.color * tint,
                ..l.params
            };
            let unmasked = stencil_deferred_light(&exact, q_point, camera, &light, 1.0, None);
            let matters = unmasked.max_element() > 0.01 * total;
            if l.params.lights_layers(frame.objects[o].rendering_layers) {
                report.lit_by[k].1 += usize::from(matters);
                let to_light = l.params.sample(q_point).0;
                let shadowed = shadows.additional_at(k, q_point, to_light, camera)[1] < 1.0;
                report.additional_shadowed[k] +=
                    usize::from(matters && shadowed && !exact.flags.receive_shadows_off);
            } else {
                report.layer_culled += usize::from(matters);
            }
        }
    }
    report.main_cookie_texels = main_cookie_seen.len();
    Ok(report)
}
