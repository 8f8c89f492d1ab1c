//! A whole frame of the built-in path, end to end (docs/shading.md §12): the objects of
//! [`FrameScene`] rendered
//!
//! - **forward**: `standard/ForwardBase` per object (ambient, probes, emission and the main
//!   directional light), then `standard/ForwardAdd` per object and per-pixel light, blended
//!   One / One with `ZTest LEqual` and no depth writes;
//! - **deferred**: `standard/Deferred` per object into RT0–RT3 and the depth buffer, then
//!   `deferred_shading/Lighting` once per light (the main light first, `DIRECTIONAL`; point
//!   and spot lights as their volumes after a stencil pre-pass) from the G-buffer and the
//!   depth, blended onto RT3, then (LDR) `deferred_final/Final`;
//!
//! with each light's culling mask ([`culling`]: skipped draws forward, stencil bits deferred)
//!
//! in HDR (`Rgba16Float`, `UNITY_HDR_ON`) and LDR (`Rgba8Unorm` forward, the 10-bit `exp2(−c)`
//! RT3 and the final pass deferred), and compares every pixel of both with a CPU reference
//! computed from the formulas ([`wgsl_variants_shaders::reference`]) and with each other: the
//! documents' claim that the shader "produces the same results in both forward and deferred
//! mode". The tolerances are those of [`wgsl_variants_shaders::reference::tolerance`] (the frame's
//! row): the rounding of every draw, the G-buffer's quantization of each deferred light, and
//! the reference's change over the rasterizer's sub-pixel window. Pixels whose window sees two
//! objects (silhouettes) are left out and counted; the background is compared (nothing drawn).
//!
//! These paths read every pass back, as a per-pixel proof needs; [`timed`] draws the same
//! frame with its targets kept on the GPU between passes, each pass timed (the frame bench).
//!
//! ```no_run
//! use wgsl_variants_gpu::GpuContext;
//! use wgsl_variants_gpu::check::frame::{FrameScene, check_frame};
//! let ctx = GpuContext::new(None).unwrap();
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let report = check_frame(&ctx, &lib, &FrameScene::new(), true).unwrap();
//! assert!(report.passed(), "{report}");
//! ```

pub mod culling;
pub mod scene;
pub mod shadow;
pub mod timed;

use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;

use glam::{Vec3, Vec4};

pub use culling::{LayerStencil, MAX_CULLED_LAYERS, VOLUME_STENCIL_BIT};
pub use scene::{
    FRAME_HEIGHT, FRAME_WIDTH, FrameLight, FrameObject, FrameScene, Hit, LAYER_GLASS,
    LAYER_SHELTERED,
};
pub use shadow::{FrameShadow, FrameShadows, ShadowSpec, render_shadows};
pub use timed::{FrameTime, LightingTraffic, ResidentFrame};

use super::compare::pixel;
use super::deferred::final_pass;
use super::gbuffer::rt3_blend;
use super::rig::shadowed;
use super::scene::{brdf_lut_resource, push_mat4, texture};
use super::skybox::{sky_draw, stored_range, view_direction};
use super::volume_draw::{depth_fill_draw, over_volume, stencil_fill_draw};
use crate::light_volume::{LightDraw, LightVolume, light_draw};
use crate::{
    BoundResource, CheckError, ColorTarget, DEPTH_STENCIL_FORMAT, DepthTest, Draw, DrawPass,
    GpuContext, GpuError, Resource, StencilTest, TargetFormat, VertexBuffer, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::brdf::{Dots, diffuse_and_specular_from_metallic};
use wgsl_variants_shaders::reference::cube::CubeFaces;
use wgsl_variants_shaders::reference::light::{Cookie2d, Cookies, LightParams, LightType};
use wgsl_variants_shaders::reference::surface::{
    Geometry, Keywords, RenderingMode, Scene, Texels, shade_deferred, shade_forward,
    shade_forward_add, surface, view_and_reflection,
};
use wgsl_variants_shaders::reference::tolerance::{
    f16_store_error, gbuffer_light_bound, ldr_chain_range, unorm_store_error, window_offsets,
    window_range,
};

/// The rendered frame of one path: its final colour (`Rgba16Float` in HDR, `Rgba8Unorm` in
/// LDR) and how many draws made it.
#[derive(Clone, Debug, PartialEq)]
pub struct PathImage {
    /// Tightly packed pixels of [`PathImage::format`].
    pub bytes: Vec<u8>,
    /// `Rgba16Float` (HDR) or `Rgba8Unorm` (LDR).
    pub format: TargetFormat,
    /// Draw calls, full-screen passes included.
    pub draws: usize,
    /// Lights drawn as their volume (the deferred path's point and spot lights that
    /// [`light_draw`] does not send full screen); 0 forward.
    pub volumes: usize,
}

impl PathImage {
    /// Pixel `i`'s rgb as values (f16 decoded, or unorm `code / 255`).
    pub fn rgb(&self, i: usize) -> Vec3 {
        let v = pixel(self.format, &self.bytes, i).1;
        Vec3::new(v[0], v[1], v[2])
    }
}

/// The keyword names of `object`'s variant of `pass` (`ForwardBase`, `ForwardAdd` with
/// `light`, or `Deferred`, with `UNITY_HDR_ON` when `hdr`).
fn object_keywords(
    object: &FrameObject,
    pass: &str,
    light: Option<LightType>,
    hdr: bool,
) -> Vec<&'static str> {
    let deferred = pass == "Deferred";
    let mut names = Keywords {
        hdr: deferred && hdr,
        reflection_buffers: false,
        occlusion_map: object.keywords.occlusion_map && pass != "ForwardAdd",
        emission_map: object.keywords.emission_map && pass != "ForwardAdd",
        // ForwardAdd adds one light's direct term: no lightmap keywords.
        lightmap: object.keywords.lightmap && pass != "ForwardAdd",
        dirlightmap: object.keywords.dirlightmap && pass != "ForwardAdd",
        dynamic_lightmap: object.keywords.dynamic_lightmap && pass != "ForwardAdd",
        ..object.keywords
    }
    .names();
    names.extend(light.map(LightType::keyword));
    names
}

/// A `standard` or lighting variant by pass and keyword names.
type VariantKey = (&'static str, Vec<&'static str>);

/// A variant's label and composed text.
type VariantText = (String, Arc<str>);

/// The variants a path draws, composed once each (a frame draws the same variant for many
/// lights), and each object's resources, shared by its draws.
struct Drawer<'a> {
    lib: &'a Library,
    frame: &'a FrameScene,
    hdr: bool,
    texts: HashMap<VariantKey, VariantText>,
    /// The resources of the opaque objects, then of the transparent ones.
    objects: Vec<Arc<[BoundResource]>>,
}

impl<'a> Drawer<'a> {
    fn new(lib: &'a Library, frame: &'a FrameScene, hdr: bool) -> Self {
        let objects = frame
            .objects
            .iter()
            .chain(&frame.transparent)
            .map(|o| Arc::from(frame.object_resources(o)))
            .collect();
        Drawer {
            lib,
            frame,
            hdr,
            texts: HashMap::new(),
            objects,
        }
    }

    /// A variant's label and composed text.
    fn text(
        &mut self,
        shader: &'static str,
        pass: &'static str,
        names: Vec<&'static str>,
    ) -> Result<VariantText, GpuError> {
        if let Some(known) = self.texts.get(&(pass, names.clone())) {
            return Ok(known.clone());
        }
        let variant = self
            .lib
            .variant(shader, pass, &names)
            .map_err(|e| CheckError::lookup(format!("{shader}/{pass} {names:?}"), e))?;
        let text = (variant.label(), Arc::from(self.lib.wgsl(&variant)));
        self.texts.insert((pass, names), text.clone());
        Ok(text)
    }

    /// Every object's draw of `pass` (ForwardBase, with the main light's `shadow`; Deferred)
    /// with the opaque depth test.
    fn opaque(
        &mut self,
        pass: &'static str,
        shadow: Option<&FrameShadow>,
    ) -> Result<Vec<Draw>, GpuError> {
        (0..self.frame.objects.len())
            .map(|o| {
                Ok(self
                    .object(o, pass, None, shadow)?
                    .with_depth(DepthTest::OPAQUE))
            })
            .collect()
    }

    /// Object `o`'s draw of a `standard` pass, with the bindings of `light` (ForwardAdd) and
    /// of `shadow` (ForwardAdd's light's, or ForwardBase's main light's). `o` counts the
    /// opaque objects, then the transparent ones.
    fn object(
        &mut self,
        o: usize,
        pass: &'static str,
        light: Option<&FrameLight>,
        shadow: Option<&FrameShadow>,
    ) -> Result<Draw, GpuError> {
        let opaque = self.frame.objects.len();
        let object = match o.checked_sub(opaque) {
            Some(t) => &self.frame.transparent[t],
            None => &self.frame.objects[o],
        };
        let mut names = object_keywords(object, pass, light.map(|l| l.light_type), self.hdr);
        names.extend(shadow.map(FrameShadow::names).unwrap_or_default());
        let (label, wgsl) = self.text("standard", pass, names)?;
        let mut resources = light.map_or_else(Vec::new, |l| self.frame.light_resources(&l.params));
        resources.extend(shadow.map(|s| s.resources.clone()).unwrap_or_default());
        Ok(Draw::fullscreen(
            &format!("{} {label}", object.name),
            &wgsl,
            "vs_main",
            "fs_main",
        )
        .with_mesh(object.mesh())
        .with_shared(&self.objects[o])
        .with_resources(resources))
    }
}

/// One-One additive blending (ForwardAdd on opaque and cutout surfaces).
const ADD: wgpu::BlendState = wgpu::BlendState {
    color: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
    alpha: wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    },
};

/// The blend state of a semi-transparent object's ForwardBase draw (`add` false) or
/// ForwardAdd draw, as Unity's Standard shader sets them for its rendering modes
/// (`StandardShaderGUI.cs`: `_SrcBlend` SrcAlpha for Fade, One for Transparent — the shader
/// premultiplies — with `_DstBlend` OneMinusSrcAlpha; the ForwardAdd pass blends
/// `[_SrcBlend] One`).
fn transparent_blend(mode: RenderingMode, add: bool) -> wgpu::BlendState {
    let src = match mode {
        RenderingMode::Fade => wgpu::BlendFactor::SrcAlpha,
        _ => wgpu::BlendFactor::One,
    };
    let dst = if add {
        wgpu::BlendFactor::One
    } else {
        wgpu::BlendFactor::OneMinusSrcAlpha
    };
    let component = wgpu::BlendComponent {
        src_factor: src,
        dst_factor: dst,
        operation: wgpu::BlendOperation::Add,
    };
    wgpu::BlendState {
        color: component,
        alpha: component,
    }
}

/// The forward part of either path: the sky where no surface was drawn, then each
/// semi-transparent object in [`FrameScene::transparent_order`], its ForwardBase draw then one
/// ForwardAdd draw per light that lights it, blended ([`transparent_blend`]), back faces culled, depth tested
/// against the opaque objects' without writing, and without shadow keywords (the transparent
/// queue receives no shadows).
fn forward_part(drawer: &mut Drawer<'_>, frame: &FrameScene) -> Result<Vec<Draw>, GpuError> {
    let mut draws = Vec::new();
    if let Some(sky) = &frame.sky {
        let camera = frame.scene.camera_position;
        draws.push(
            sky_draw(drawer.lib, sky, frame.view_proj, camera)?.with_depth(DepthTest::BACKGROUND),
        );
    }
    for t in frame.transparent_order() {
        let o = frame.objects.len() + t;
        let mode = frame.transparent[t].keywords.rendering;
        let blended = |draw: Draw, add: bool| {
            draw.with_blend(transparent_blend(mode, add))
                .with_depth(DepthTest::TRANSPARENT)
                .with_cull(wgpu::Face::Back)
        };
        draws.push(blended(drawer.object(o, "ForwardBase", None, None)?, false));
        for light in frame
            .lights
            .iter()
            .filter(|l| l.lights(&frame.transparent[t]))
        {
            draws.push(blended(
                drawer.object(o, "ForwardAdd", Some(light), None)?,
                true,
            ));
        }
    }
    Ok(draws)
}

/// The forward path's draws: ForwardBase per object (with the main light's shadow), then
/// ForwardAdd per light and object it lights (blended One / One onto the same surface; a
/// light's culling mask leaves the other objects' draws out).
fn forward_draws(
    drawer: &mut Drawer<'_>,
    frame: &FrameScene,
    shadows: &FrameShadows,
) -> Result<(Vec<Draw>, Vec<Draw>), GpuError> {
    let base = drawer.opaque("ForwardBase", shadows.main.as_ref())?;
    let mut add = Vec::with_capacity(frame.lights.len() * frame.objects.len());
    for (light, shadow) in frame.lights.iter().zip(&shadows.lights) {
        for o in (0..frame.objects.len()).filter(|&o| light.lights(&frame.objects[o])) {
            add.push(
                drawer
                    .object(o, "ForwardAdd", Some(light), shadow.as_ref())?
                    .with_blend(ADD)
                    .with_depth(DepthTest::SAME_SURFACE),
            );
        }
    }
    Ok((base, add))
}

/// Renders the forward path: ForwardBase per object, then ForwardAdd per light and object
/// (with the light's shadow keywords and `shadows`' maps). Where a directional light has a
/// shadow, first a depth pre-pass (every object's `ShadowCaster` with the camera's view) and
/// its screen-space masks ([`FrameShadows::with_masks`]).
pub fn render_forward(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
    shadows: &FrameShadows,
    hdr: bool,
) -> Result<PathImage, GpuError> {
    let format = if hdr {
        TargetFormat::Rgba16Float
    } else {
        TargetFormat::Rgba8Unorm
    };
    let mut pass = DrawPass::new(
        "frame: forward",
        frame.width,
        frame.height,
        vec![ColorTarget::new(format)],
    );
    pass.depth = true;
    let mut drawer = Drawer::new(lib, frame, hdr);
    let mut draws = 0;
    let masked;
    let shadows = if shadows.needs_masks() {
        let mut prepass = DrawPass::new("frame: depth pre-pass", frame.width, frame.height, vec![]);
        prepass.depth = true;
        let camera = frame.scene.camera_position.extend(0.0);
        prepass.draws =
            shadow::caster_draws(&mut drawer, "SHADOWS_DEPTH", frame.view_proj, camera)?;
        draws += prepass.draws.len();
        let depth = render_pass(ctx, &prepass)?.depth.unwrap_or_default();
        let collects;
        (masked, collects) = shadows.with_masks(ctx, lib, frame, &depth)?;
        draws += collects;
        &masked
    } else {
        shadows
    };
    let (base, add) = forward_draws(&mut drawer, frame, shadows)?;
    pass.draws = base;
    pass.draws.extend(add);
    pass.draws.extend(forward_part(&mut drawer, frame)?);
    draws += pass.draws.len();
    let bytes = render_pass(ctx, &pass)?.targets.remove(0);
    Ok(PathImage {
        bytes,
        format,
        draws,
        volumes: 0,
    })
}

/// What the deferred path leaves before the final pass: RT0–RT3 and the depth buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct GBufferFrame {
    /// RT0 (`Rgba8Unorm`), RT1 (`Rgba8Unorm`), RT2 (`Rgb10a2Unorm`), RT3.
    pub targets: Vec<Vec<u8>>,
    /// The depth buffer, one `f32` per pixel.
    pub depth: Vec<f32>,
}

/// RT3's format: `Rgba16Float` in HDR, the `exp2(−c)` `Rgb10a2Unorm` in LDR.
fn rt3_format(hdr: bool) -> TargetFormat {
    if hdr {
        TargetFormat::Rgba16Float
    } else {
        TargetFormat::Rgb10a2Unorm
    }
}

/// The G-buffer pass's targets: RT0 and RT1 (`Rgba8Unorm`), RT2 (`Rgb10a2Unorm`) and RT3
/// cleared to no light (0 in HDR, `exp2(−0)` = 1 in LDR).
fn gbuffer_targets(hdr: bool) -> Vec<ColorTarget> {
    let empty = if hdr { 0.0 } else { 1.0 };
    vec![
        ColorTarget::new(TargetFormat::Rgba8Unorm),
        ColorTarget::new(TargetFormat::Rgba8Unorm),
        ColorTarget::new(TargetFormat::Rgb10a2Unorm),
        ColorTarget::new(rt3_format(hdr)).with_clear([empty, empty, empty, 1.0]),
    ]
}

/// The G-buffer pass's draws, one per opaque object, each marking its pixels' stencil with
/// its layer's bit ([`LayerStencil::object_bits`], 0 included, so a nearer object's marks
/// replace a farther one's) when some light leaves a layer out.
fn gbuffer_draws(drawer: &mut Drawer<'_>, stencil: &LayerStencil) -> Result<Vec<Draw>, GpuError> {
    let draws = drawer.opaque("Deferred", None)?;
    if !stencil.any() {
        return Ok(draws);
    }
    Ok(draws
        .into_iter()
        .zip(&drawer.frame.objects)
        .map(|(d, o)| d.with_stencil(StencilTest::mark(stencil.object_bits(o))))
        .collect())
}

/// The stencil pre-pass of a light drawn as `volume` (`stencil_write/StencilWrite`, Unity's
/// `Internal-StencilWrite`): its front faces, depth test LessEqual without writes, setting
/// [`VOLUME_STENCIL_BIT`] where the depth test fails — where the surface lies in front of the
/// volume.
fn stencil_pre_pass(
    drawer: &mut Drawer<'_>,
    frame: &FrameScene,
    volume: &LightVolume,
) -> Result<Draw, GpuError> {
    let (label, wgsl) = drawer.text("stencil_write", "StencilWrite", Vec::new())?;
    let mut camera = Vec::new();
    push_mat4(&mut camera, frame.view_proj);
    Ok(Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
        .depth_only()
        .with_mesh(VertexBuffer::from_f32(&[(0, 3)], &volume.positions))
        .with_resources(vec![BoundResource::new(0, 0, Resource::Uniform(camera))])
        .with_cull(wgpu::Face::Back)
        .with_depth(DepthTest {
            compare: wgpu::CompareFunction::LessEqual,
            write: false,
        })
        .with_stencil(StencilTest::set_where_depth_fails(VOLUME_STENCIL_BIT)))
}

/// The Lighting pass's draws, one per light (the main light first, full screen; the others
/// as their volumes, each after its stencil pre-pass, where [`light_draw`] allows, else full screen; with the light's shadow
/// keywords and `shadows`' maps; passing only where the stencil holds none of the bits of the
/// layers the light leaves out), each with `shared` (the G-buffer's bindings and the camera,
/// however the caller binds them), and how many are volumes.
fn lighting_draws(
    drawer: &mut Drawer<'_>,
    frame: &FrameScene,
    shadows: &FrameShadows,
    hdr: bool,
    shared: &Arc<[BoundResource]>,
    stencil: &LayerStencil,
) -> Result<(Vec<Draw>, usize), GpuError> {
    let mut volumes = 0;
    let mut draws = Vec::with_capacity(1 + frame.lights.len());
    let main = (
        LightType::Directional,
        frame.main_light,
        None,
        shadows.main.as_ref(),
        stencil.mask_bits(frame.main_culling_mask),
    );
    let lights = frame.lights.iter().zip(&shadows.lights).map(|(l, s)| {
        let bits = stencil.light_bits(l);
        (l.light_type, l.params, Some(&l.light), s.as_ref(), bits)
    });
    for (light_type, params, light, shadow, bits) in std::iter::once(main).chain(lights) {
        let mut names = vec![light_type.keyword()];
        names.extend(shadow.map(FrameShadow::names).unwrap_or_default());
        if hdr {
            names.push("UNITY_HDR_ON");
        }
        names.extend(frame.brdf.keyword());
        let (label, wgsl) = drawer.text("deferred_shading", "Lighting", names)?;
        let mut resources = frame.light_resources(&params);
        resources.push(brdf_lut_resource());
        resources.extend(shadow.map(|s| s.resources.clone()).unwrap_or_default());
        let volume = match light.map(|l| light_draw(l, frame.view_proj)) {
            Some(Ok(LightDraw::Volume(v))) => Some(v),
            Some(Err(e)) => {
                return Err(GpuError::Validation {
                    label: label.clone(),
                    message: e.to_string(),
                });
            }
            _ => None,
        };
        let draw = Draw::fullscreen(&label, &wgsl, "vs_main", "fs_main")
            .with_shared(shared)
            .with_resources(resources);
        volumes += usize::from(volume.is_some());
        match volume {
            Some(v) => {
                // Unity's stencil pre-pass: the volume's front faces mark the pixels whose
                // surface lies in front of the volume; the light skips them and clears them.
                draws.push(stencil_pre_pass(drawer, frame, &v)?);
                let test = StencilTest::none_of(bits | VOLUME_STENCIL_BIT);
                draws.push(
                    over_volume(draw, "vs_volume", &v)
                        .with_stencil(test.clearing(VOLUME_STENCIL_BIT)),
                );
            }
            None if bits != 0 => draws.push(draw.with_stencil(StencilTest::none_of(bits))),
            None => draws.push(draw),
        }
    }
    Ok((draws, volumes))
}

/// Renders the deferred path: the G-buffer pass over every object, the screen-space masks of
/// the directional lights' shadows over its depth ([`FrameShadows::with_masks`]), one
/// Lighting draw per light (the main light first, full screen; the others as their volumes
/// where [`light_draw`] allows, else full screen; with the light's shadow keywords and
/// `shadows`' maps), and in LDR the final pass.
pub fn render_deferred(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
    shadows: &FrameShadows,
    hdr: bool,
) -> Result<PathImage, GpuError> {
    let (w, h) = (frame.width, frame.height);
    let rt3_format = rt3_format(hdr);
    let stencil = LayerStencil::new(frame)?;
    let mut gbuffer = DrawPass::new("frame: G-buffer", w, h, gbuffer_targets(hdr));
    gbuffer.depth = true;
    gbuffer.depth_format = DEPTH_STENCIL_FORMAT;
    let mut drawer = Drawer::new(lib, frame, hdr);
    gbuffer.draws = gbuffer_draws(&mut drawer, &stencil)?;
    let out = render_pass(ctx, &gbuffer)?;
    let marks = out.stencil.unwrap_or_default();
    let g = GBufferFrame {
        depth: out.depth.unwrap_or_default(),
        targets: out.targets,
    };
    let (shadows, collects) = shadows.with_masks(ctx, lib, frame, &g.depth)?;

    // The lighting pass tests the G-buffer's depth: a first draw writes it into the pass's
    // depth buffer (no colour), then each light draws its volume's back faces where the scene
    // lies in front of them (depth GreaterEqual), or full screen (light_volume::light_draw).
    // The G-buffer's stencil marks come back the same way: one draw per culled layer's bit.
    let mut lighting = DrawPass::new(
        "frame: lighting",
        w,
        h,
        vec![
            ColorTarget::new(rt3_format)
                .with_blend(rt3_blend(hdr))
                .with_initial(g.targets[3].clone()),
        ],
    );
    lighting.depth = true;
    lighting.depth_format = gbuffer.depth_format;
    let depth_texture = Resource::Texture2d {
        format: wgpu::TextureFormat::R32Float,
        width: w,
        height: h,
        data: g.depth.iter().flat_map(|d| d.to_le_bytes()).collect(),
    };
    lighting.draws.push(depth_fill_draw(depth_texture.clone()));
    let fills = stencil.layers().len();
    if stencil.any() {
        let marks = Resource::Texture2d {
            format: wgpu::TextureFormat::R8Uint,
            width: w,
            height: h,
            data: marks,
        };
        lighting
            .draws
            .extend((0..fills).map(|bit| stencil_fill_draw(marks.clone(), 1 << bit)));
    }
    let shared: Arc<[BoundResource]> = Arc::from(vec![
        BoundResource::new(0, 0, texture(TargetFormat::Rgba8Unorm, w, h, &g.targets[0])),
        BoundResource::new(0, 1, texture(TargetFormat::Rgba8Unorm, w, h, &g.targets[1])),
        BoundResource::new(
            0,
            2,
            texture(TargetFormat::Rgb10a2Unorm, w, h, &g.targets[2]),
        ),
        BoundResource::new(0, 3, depth_texture.clone()),
        BoundResource::new(0, 4, Resource::Uniform(frame.deferred_camera())),
    ]);
    let (draws, volumes) = lighting_draws(&mut drawer, frame, &shadows, hdr, &shared, &stencil)?;
    lighting.draws.extend(draws);
    // The depth and stencil fills are this harness's way to hand the G-buffer's depth and
    // marks to the next pass.
    let mut draws = gbuffer.draws.len() + collects + lighting.draws.len() - 1 - fills;
    let rt3 = render_pass(ctx, &lighting)?.targets.remove(0);
    let (lit, format) = if hdr {
        (rt3, rt3_format)
    } else {
        draws += 1;
        (final_pass(ctx, lib, &rt3, w, h)?, TargetFormat::Rgba8Unorm)
    };
    // The forward part: the sky and the semi-transparent objects over the lit image (RT3 in
    // HDR, the final pass's output in LDR), tested against the G-buffer pass's depth.
    let part = forward_part(&mut drawer, frame)?;
    if part.is_empty() {
        return Ok(PathImage {
            bytes: lit,
            format,
            draws,
            volumes,
        });
    }
    draws += part.len();
    let mut forward = DrawPass::new(
        "frame: forward part",
        w,
        h,
        vec![ColorTarget::new(format).with_initial(lit)],
    );
    forward.depth = true;
    forward.draws.push(depth_fill_draw(depth_texture));
    forward.draws.extend(part);
    Ok(PathImage {
        bytes: render_pass(ctx, &forward)?.targets.remove(0),
        format,
        draws,
        volumes,
    })
}

/// The reference at one point of a surface: the forward terms and what the deferred path's
/// tolerance needs.
#[derive(Clone, Debug)]
struct Terms {
    /// ForwardBase's rgb: ambient, probes, emission and the main light (with its shadow
    /// factor's upper end).
    base: Vec3,
    /// The same with the main light's shadow factor's lower end.
    base_lo: Vec3,
    /// The indices in [`FrameScene::lights`] of the lights that light the object (their
    /// culling masks hold its layer): one ForwardAdd draw, one Lighting store, each.
    lights: Vec<usize>,
    /// The light each of their ForwardAdd draws adds (with the shadow factor's upper end).
    adds: Vec<Vec3>,
    /// The same with the shadow factor's lower end (an uncertain shadow tap may go either
    /// way; equal to `adds` where no tap is uncertain).
    adds_lo: Vec<Vec3>,
    /// What the G-buffer pass writes to RT3 (ambient, probes, emission).
    c0: Vec3,
    /// The main light's direct term.
    main: Vec3,
    /// Whether the main light lights the object (its culling mask holds the object's layer):
    /// one Lighting store more.
    main_lit: bool,
    /// [`gbuffer_light_bound`] of the main light and each per-pixel light in `lights`.
    bounds: Vec<Vec3>,
}

impl Terms {
    fn total(&self) -> Vec3 {
        self.base + self.adds.iter().copied().sum::<Vec3>()
    }

    fn total_lo(&self) -> Vec3 {
        self.base_lo + self.adds_lo.iter().copied().sum::<Vec3>()
    }
}

/// One object as the reference shades it in the frame: its keywords (without the
/// G-buffer's), texels and the frame's cookies, for ForwardBase's and each light's ForwardAdd
/// formula.
struct Shading<'a> {
    frame: &'a FrameScene,
    object: &'a FrameObject,
    kw: Keywords,
    tex: Texels,
    cookie: Cookie2d,
    cube: &'a CubeFaces,
}

impl<'a> Shading<'a> {
    fn new(frame: &'a FrameScene, object: &'a FrameObject) -> Self {
        let (cookie, cube) = frame.cookies();
        Shading {
            frame,
            object,
            kw: Keywords {
                hdr: false,
                reflection_buffers: false,
                ..object.keywords
            },
            tex: object.reference_texels(),
            cookie,
            cube,
        }
    }

    fn cookies(&self) -> Option<Cookies<'_>> {
        Some(Cookies {
            texture: &self.cookie,
            cube: self.cube,
        })
    }

    /// ForwardBase's rgba at `geo`, the main light's shadow factor `factor` (a black main
    /// light where its culling mask leaves the object out).
    fn base(&self, geo: &Geometry, factor: f32) -> Vec4 {
        let scene = self.frame.scene_for(self.object).with_main_shadow(factor);
        self.base_in(geo, &scene)
    }

    /// ForwardBase's rgba at `geo` with `scene`'s lighting.
    fn base_in(&self, geo: &Geometry, scene: &Scene) -> Vec4 {
        shade_forward(&self.kw, &self.object.material, &self.tex, geo, scene).unwrap_or(Vec4::ZERO)
    }

    /// ForwardAdd's rgba at `geo` of `light` as `params` describe it (its own parameters, or
    /// shadowed).
    fn add(&self, geo: &Geometry, light: &FrameLight, params: &LightParams) -> Vec4 {
        shade_forward_add(
            &self.kw,
            &self.object.material,
            &self.tex,
            geo,
            self.frame.scene.camera_position,
            params,
            light.light_type,
            self.cookies(),
        )
        .unwrap_or(Vec4::ZERO)
    }
}

/// The reference terms of `object` at `geo`, the lights shadowed by `shadows`; the lights
/// whose culling mask leaves the object out add nothing, and draw nothing.
fn terms(
    frame: &FrameScene,
    shadows: &FrameShadows,
    object: &FrameObject,
    geo: &Geometry,
) -> Terms {
    let shading = Shading::new(frame, object);
    let (kw, mat, tex) = (&shading.kw, &object.material, &shading.tex);
    let camera = frame.scene.camera_position;
    let p = geo.world_position;
    // The frame's cutout object is kept everywhere (its alpha is above the cutoff).
    let main_factor = shadows.main.as_ref().map_or((1.0, 1.0), |s| s.received(p));
    let base_with = |f: f32| shading.base(geo, f).truncate();
    let (base, base_lo) = (base_with(main_factor.1), base_with(main_factor.0));
    // One factor per light (a light without a shadow, or without a map, keeps all of it).
    let factors: Vec<(f32, f32)> = (0..frame.lights.len())
        .map(|i| {
            shadows
                .lights
                .get(i)
                .and_then(Option::as_ref)
                .map_or((1.0, 1.0), |s| s.received(p))
        })
        .collect();
    let add =
        |l: &FrameLight, factor: f32| shading.add(geo, l, &shadowed(&l.params, factor)).truncate();
    let lights: Vec<usize> = (0..frame.lights.len())
        .filter(|&i| frame.lights[i].lights(object))
        .collect();
    let adds = lights
        .iter()
        .map(|&i| add(&frame.lights[i], factors[i].0.max(factors[i].1)))
        .collect();
    let adds_lo = lights
        .iter()
        .map(|&i| add(&frame.lights[i], factors[i].0.min(factors[i].1)))
        .collect();
    let hdr_kw = Keywords { hdr: true, ..*kw };
    let c0 = shade_deferred(&hdr_kw, mat, tex, geo, &frame.scene)
        .map_or(Vec3::ZERO, |g| g.rt3.truncate());
    let s = surface(kw, mat, tex, geo);
    let (diffuse, spec, _) = diffuse_and_specular_from_metallic(s.albedo, s.metallic);
    let (v, _) = view_and_reflection(camera, p, s.normal);
    let bound = |params: &LightParams, t: LightType| {
        let (l, attenuation) = params.sample(t, p, shading.cookies());
        gbuffer_light_bound(
            kw.brdf,
            diffuse,
            spec,
            s.smoothness,
            &Dots::new(s.normal, v, l),
            params.color * attenuation,
        )
    };
    let main_lit = frame.main_lights(object);
    let mut bounds = Vec::with_capacity(1 + lights.len());
    if main_lit {
        bounds.push(bound(
            &shadowed(&frame.main_light, main_factor.1),
            LightType::Directional,
        ));
    }
    bounds.extend(lights.iter().map(|&i| {
        let (l, f) = (&frame.lights[i], factors[i]);
        bound(&shadowed(&l.params, f.0.max(f.1)), l.light_type)
    }));
    Terms {
        main: base - c0,
        main_lit,
        base,
        base_lo,
        lights,
        adds,
        adds_lo,
        c0,
        bounds,
    }
}

/// Whether a light whose culling mask leaves `object` out (the main light included) would
/// add more than 1 % of `total` at `geo` (unshadowed): the pixel shows that the mask is
/// honoured.
fn culled_light_matters(
    frame: &FrameScene,
    object: &FrameObject,
    geo: &Geometry,
    total: Vec3,
) -> bool {
    let shading = Shading::new(frame, object);
    let matters = |add: Vec3| add.max_element() > 0.01 * total.max_element().max(1e-3);
    let main = || {
        let dark = frame.scene.with_main_shadow(0.0);
        (shading.base_in(geo, &frame.scene) - shading.base_in(geo, &dark)).truncate()
    };
    (!frame.main_lights(object) && matters(main()))
        || frame
            .lights
            .iter()
            .filter(|l| !l.lights(object))
            .any(|l| matters(shading.add(geo, l, &l.params).truncate()))
}

/// The reference colour of pixel `(x, y)` (before a target clamps it): what the ray through its
/// centre sees, lit by the forward formulas and shadowed by `shadows`, with the
/// semi-transparent surfaces in front blended over it (on the background, the sky); `None` on
/// an empty background.
pub fn reference_rgb(frame: &FrameScene, shadows: &FrameShadows, x: u32, y: u32) -> Option<Vec3> {
    let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
    let (hit, layers) = frame.cast_through(cx, cy);
    if hit.is_none() && layers.is_empty() && frame.sky.is_none() {
        return None;
    }
    let opaque = match hit {
        Some(h) => terms(frame, shadows, &frame.objects[h.object], &h.geometry).total(),
        None => frame.sky.as_ref().map_or(Vec3::ZERO, |sky| {
            let dir = view_direction(frame.view_proj, (frame.width, frame.height), cx, cy);
            let (lo, hi) = sky.range(&sky.skybox, &[dir]);
            (lo + hi) * 0.5
        }),
    };
    Some(layers.iter().fold(opaque, |under, h| {
        let l = layer(frame, &frame.transparent[h.object], &[h.geometry]);
        l.base.0 + under * (1.0 - l.alpha) + l.adds.iter().map(|a| a.0).sum::<Vec3>()
    }))
}

/// One compared pixel whose forward or deferred value (or their pair) is out of tolerance.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameMismatch {
    /// Pixel `(x, y)`.
    pub pixel: [u32; 2],
    /// The object the pixel sees (`background` for none).
    pub object: &'static str,
    /// The reference rgb (before the target clamps it).
    pub reference: Vec3,
    /// The forward path's rgb.
    pub forward: Vec3,
    /// The deferred path's rgb.
    pub deferred: Vec3,
    /// Which comparisons failed: forward, deferred, forward vs deferred.
    pub failed: [bool; 3],
}

/// The result of [`check_frame`].
#[derive(Clone, Debug, PartialEq)]
pub struct FrameReport {
    /// HDR or LDR.
    pub hdr: bool,
    /// Draw calls of the forward path.
    pub forward_draws: usize,
    /// Draw calls of the deferred path.
    pub deferred_draws: usize,
    /// Lights the deferred path drew as their volume.
    pub volumes: usize,
    /// Pixels on a surface, compared.
    pub compared: usize,
    /// Background pixels, compared (both paths must leave them empty).
    pub background: usize,
    /// Silhouette pixels left out (their sub-pixel window sees two objects or the background).
    pub edges: usize,
    /// Pixels out of tolerance: forward vs reference, deferred vs reference, forward vs
    /// deferred.
    pub failures: [usize; 3],
    /// The largest ratio of a difference to its allowance (forward, deferred, pair): below 1
    /// when everything passes, and how much room the tolerance left.
    pub worst: [f32; 3],
    /// Where each of `worst` was found.
    pub worst_pixel: [[u32; 2]; 3],
    /// Pixels each light changes by more than 1 % of its value (every light must reach some).
    pub lit_by: Vec<(&'static str, usize)>,
    /// Compared pixels in some light's shadow (factor below 1 at the centre).
    pub shadowed: usize,
    /// Compared pixels where a shadow tap is too close to call (the reference allows both).
    pub uncertain: usize,
    /// Compared pixels seen through semi-transparent objects (background included).
    pub through_transparent: usize,
    /// Compared pixels of opaque objects some light's culling mask leaves out, where that
    /// light would add more than 1 % of the value: the pixels the deferred path's stencil
    /// keeps it off.
    pub culled: usize,
    /// The first mismatches (at most 20).
    pub mismatches: Vec<FrameMismatch>,
}

impl FrameReport {
    /// Whether every compared pixel agrees and every light lights something.
    pub fn passed(&self) -> bool {
        self.failures == [0; 3] && self.lit_by.iter().all(|&(_, n)| n > 0)
    }
}

impl fmt::Display for FrameReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "frame {}: {} pixels compared, {} background, {} silhouette pixels left out; forward {} draws, deferred {} draws ({} light volumes)",
            if self.hdr { "HDR" } else { "LDR" },
            self.compared,
            self.background,
            self.edges,
            self.forward_draws,
            self.deferred_draws,
            self.volumes,
        )?;
        writeln!(
            f,
            "  mismatches: forward {} (worst {:.2} of the allowance, at {:?}), deferred {} (worst {:.2}, at {:?}), forward vs deferred {} (worst {:.2}, at {:?})",
            self.failures[0],
            self.worst[0],
            self.worst_pixel[0],
            self.failures[1],
            self.worst[1],
            self.worst_pixel[1],
            self.failures[2],
            self.worst[2],
            self.worst_pixel[2],
        )?;
        for (name, n) in &self.lit_by {
            writeln!(f, "  {name}: lights {n} pixels")?;
        }
        writeln!(
            f,
            "  {} pixels in a shadow, {} with a shadow tap too close to call, {} seen through semi-transparent objects, {} a light's culling mask keeps it off",
            self.shadowed, self.uncertain, self.through_transparent, self.culled
        )?;
        for m in &self.mismatches {
            writeln!(
                f,
                "  ({}, {}) {}: reference {:.5} forward {:.5} deferred {:.5} failed [forward, deferred, pair] {:?}",
                m.pixel[0], m.pixel[1], m.object, m.reference, m.forward, m.deferred, m.failed
            )?;
        }
        Ok(())
    }
}

/// The allowed interval of a path's value, per channel.
#[derive(Clone, Copy, Debug)]
struct Interval {
    lo: Vec3,
    hi: Vec3,
}

impl Interval {
    /// How far outside `got` is, relative to the interval's half width (≤ 1 inside).
    fn ratio(&self, got: Vec3) -> f32 {
        let mid = (self.lo + self.hi) * 0.5;
        let half = ((self.hi - self.lo) * 0.5).max(Vec3::splat(f32::MIN_POSITIVE));
        ((got - mid).abs() / half).max_element()
    }

    fn contains(&self, got: Vec3) -> bool {
        got.cmpge(self.lo).all() && got.cmple(self.hi).all()
    }

    /// The interval clamped to [0, 1] and widened by `e` (an LDR target's last store).
    fn saturated(&self, e: f32) -> Interval {
        Interval {
            lo: self.lo.clamp(Vec3::ZERO, Vec3::ONE) - Vec3::splat(e),
            hi: self.hi.clamp(Vec3::ZERO, Vec3::ONE) + Vec3::splat(e),
        }
    }
}

/// Sum of [`f16_store_error`] over the partial sums `start, start + a₁, …`.
fn f16_chain(start: Vec3, steps: &[Vec3]) -> Vec3 {
    let mut sum = start;
    let mut err = sum.to_array().map(f16_store_error);
    for s in steps {
        sum += *s;
        let e = sum.to_array().map(f16_store_error);
        for k in 0..3 {
            err[k] += e[k];
        }
    }
    Vec3::from_array(err)
}

/// The forward value's allowed interval: the reference's range over the sub-pixel window
/// `[lo, hi]`, widened by the rounding of each of the `stores` draws (partial sums in f16, or
/// one unorm step each in LDR, saturated).
fn forward_interval(t: &Terms, lo: Vec3, hi: Vec3, hdr: bool, stores: usize) -> Interval {
    let e = if hdr {
        f16_chain(t.base, &t.adds)
    } else {
        Vec3::splat(stores as f32 * unorm_store_error(8))
    };
    let out = Interval {
        lo: lo - e,
        hi: hi + e,
    };
    if hdr { out } else { out.saturated(0.0) }
}

/// The deferred value's allowed interval when the exact light lies in `[lo, hi]`: the
/// G-buffer bound of every light, then the rounding of RT3 after the G-buffer pass and each
/// of the `lights` Lighting draws (f16 partial sums in HDR; the 10-bit `exp2(−c)` chain and
/// the final pass's 8-bit store in LDR).
fn deferred_interval(t: &Terms, lo: Vec3, hi: Vec3, hdr: bool, lights: usize) -> Interval {
    let bounds: Vec3 = t.bounds.iter().copied().sum::<Vec3>();
    if hdr {
        let mut steps: Vec<Vec3> = t.main_lit.then_some(t.main).into_iter().collect();
        steps.extend(t.adds.iter().copied());
        let e = f16_chain(t.c0, &steps) + bounds;
        Interval {
            lo: lo - e,
            hi: hi + e,
        }
    } else {
        let (lo, hi) = (lo - bounds, hi + bounds);
        let stores = 1 + lights as u32;
        let mut out = Interval { lo, hi };
        for k in 0..3 {
            (out.lo[k], out.hi[k]) = ldr_chain_range(lo[k], hi[k], stores);
        }
        out.saturated(unorm_store_error(8))
    }
}

/// A semi-transparent surface over a pixel's sub-pixel window: the range of what its
/// ForwardBase draw adds (`rgb` times its source factor), its alpha (the destination keeps
/// `1 − alpha`), and the range of what each ForwardAdd draw adds (one per light that lights
/// the object).
#[derive(Clone, Debug)]
struct Layer {
    base: (Vec3, Vec3),
    alpha: f32,
    adds: Vec<(Vec3, Vec3)>,
}

/// The reference of transparent object `object` at the window's points `geos` (the centre
/// first): the forward formulas without shadows, scaled by the blend's source factors
/// ([`transparent_blend`]).
fn layer(frame: &FrameScene, object: &FrameObject, geos: &[Geometry]) -> Layer {
    let shading = Shading::new(frame, object);
    // Fade scales the source by its alpha; Transparent's shader premultiplied it.
    let scaled = |c: Vec4| match shading.kw.rendering {
        RenderingMode::Fade => c.truncate() * c.w,
        _ => c.truncate(),
    };
    let base: Vec<Vec4> = geos.iter().map(|g| shading.base(g, 1.0)).collect();
    let adds = frame
        .lights
        .iter()
        .filter(|l| l.lights(object))
        .map(|l| {
            let values: Vec<Vec3> = geos
                .iter()
                .map(|g| scaled(shading.add(g, l, &l.params)))
                .collect();
            window_range(&values)
        })
        .collect();
    Layer {
        base: window_range(&base.iter().map(|c| scaled(*c)).collect::<Vec<_>>()),
        alpha: base[0].w,
        adds,
    }
}

/// `under`, the allowed interval of a pixel before its semi-transparent surfaces, after
/// `layers` draw over it in order: each draw blends (`src + (1 − alpha) · dst`, then `+ add`
/// per light; monotone in every input, so the interval's ends map to the result's) and
/// stores (one f16 rounding, or an 8-bit target's clamp and rounding).
fn through_layers(under: Interval, layers: &[Layer], hdr: bool) -> Interval {
    let store = |i: Interval| {
        if hdr {
            let e = Vec3::from_array(i.lo.abs().max(i.hi.abs()).to_array().map(f16_store_error));
            Interval {
                lo: i.lo - e,
                hi: i.hi + e,
            }
        } else {
            i.saturated(unorm_store_error(8))
        }
    };
    layers.iter().fold(under, |dst, l| {
        let keep = 1.0 - l.alpha;
        let mut out = store(Interval {
            lo: l.base.0 + dst.lo * keep,
            hi: l.base.1 + dst.hi * keep,
        });
        for (lo, hi) in &l.adds {
            out = store(Interval {
                lo: out.lo + *lo,
                hi: out.hi + *hi,
            });
        }
        out
    })
}

/// What both paths may hold at background pixel `(cx, cy)` (its centre) before the
/// semi-transparent objects: the sky's range over the pixel's sub-pixel window, stored in the
/// output's format (`Rgba16Float` in HDR, `Rgba8Unorm` in LDR), or 0 without a sky.
fn background(frame: &FrameScene, cx: f64, cy: f64, hdr: bool) -> Interval {
    let Some(sky) = &frame.sky else {
        return Interval {
            lo: Vec3::ZERO,
            hi: Vec3::ZERO,
        };
    };
    let size = (frame.width, frame.height);
    let dirs: Vec<Vec3> = window_offsets()
        .iter()
        .map(|&(dx, dy)| {
            view_direction(
                frame.view_proj,
                size,
                cx + f64::from(dx),
                cy + f64::from(dy),
            )
        })
        .collect();
    let (lo, hi) = sky.range(&sky.skybox, &dirs);
    let format = if hdr {
        TargetFormat::Rgba16Float
    } else {
        TargetFormat::Rgba8Unorm
    };
    let (lo, hi) = stored_range(format, lo, hi);
    Interval { lo, hi }
}

/// Renders the frame both ways in HDR or LDR and compares every pixel with the reference and
/// the two paths with each other.
pub fn check_frame(
    ctx: &GpuContext,
    lib: &Library,
    frame: &FrameScene,
    hdr: bool,
) -> Result<FrameReport, GpuError> {
    let shadows = render_shadows(ctx, lib, frame)?;
    let forward = render_forward(ctx, lib, frame, &shadows, hdr)?;
    let deferred = render_deferred(ctx, lib, frame, &shadows, hdr)?;
    Ok(compare(frame, &shadows, &forward, &deferred, hdr))
}

/// Compares the two paths' images of `frame` with the reference (shadowed by `shadows`, the
/// maps both paths were given), pixel by pixel.
pub fn compare(
    frame: &FrameScene,
    shadows: &FrameShadows,
    forward: &PathImage,
    deferred: &PathImage,
    hdr: bool,
) -> FrameReport {
    let mut report = FrameReport {
        hdr,
        forward_draws: forward.draws,
        deferred_draws: deferred.draws,
        volumes: deferred.volumes,
        compared: 0,
        background: 0,
        edges: 0,
        failures: [0; 3],
        worst: [0.0; 3],
        worst_pixel: [[0; 2]; 3],
        lit_by: frame.lights.iter().map(|l| (l.name, 0)).collect(),
        shadowed: 0,
        uncertain: 0,
        through_transparent: 0,
        culled: 0,
        mismatches: Vec::new(),
    };
    for (i, (x, y)) in frame.pixels().enumerate() {
        let (cx, cy) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
        let (centre, centre_layers) = frame.cast_through(cx, cy);
        let window: Vec<(Option<Hit>, Vec<Hit>)> = window_offsets()[1..]
            .iter()
            .map(|&(dx, dy)| frame.cast_through(cx + f64::from(dx), cy + f64::from(dy)))
            .collect();
        // The same opaque object and the same transparent ones over the whole window.
        let key = |(h, layers): &(Option<Hit>, Vec<Hit>)| {
            let objects: Vec<usize> = layers.iter().map(|l| l.object).collect();
            (h.map(|h| h.object), objects)
        };
        let centre_key = key(&(centre, centre_layers.clone()));
        if !window.iter().all(|w| key(w) == centre_key) {
            report.edges += 1;
            continue;
        }
        let (f, d) = (forward.rgb(i), deferred.rgb(i));
        let layers: Vec<Layer> = centre_layers
            .iter()
            .enumerate()
            .map(|(k, l)| {
                let mut geos = vec![l.geometry];
                geos.extend(window.iter().map(|w| w.1[k].geometry));
                layer(frame, &frame.transparent[l.object], &geos)
            })
            .collect();
        report.through_transparent += usize::from(!layers.is_empty());
        let Some(hit) = centre else {
            report.background += 1;
            let under = background(frame, cx, cy, hdr);
            let i = through_layers(under, &layers, hdr);
            // Both paths draw the background the same way onto the same format: equal.
            let same = Interval { lo: f, hi: f };
            let reference = (i.lo + i.hi) * 0.5;
            judge(
                &mut report,
                [x, y],
                "background",
                reference,
                (f, d),
                [i, i, same],
                false,
            );
            continue;
        };
        report.compared += 1;
        let object = &frame.objects[hit.object];
        let t = terms(frame, shadows, object, &hit.geometry);
        let factors: Vec<(f32, f32)> = shadows
            .iter()
            .map(|s| s.factor(hit.geometry.world_position))
            .collect();
        report.shadowed += usize::from(factors.iter().any(|f| f.0.min(f.1) < 1.0));
        report.uncertain += usize::from(factors.iter().any(|f| f.0 != f.1));
        let window_terms: Vec<Terms> = window
            .iter()
            .filter_map(|w| w.0.as_ref())
            .map(|h| terms(frame, shadows, object, &h.geometry))
            .collect();
        let mut values = vec![t.total(), t.total_lo()];
        for w in &window_terms {
            values.extend([w.total(), w.total_lo()]);
        }
        let (lo, hi) = window_range(&values);
        let total = t.total();
        for (&k, add) in t.lights.iter().zip(&t.adds_lo) {
            if add.max_element() > 0.01 * total.max_element().max(1e-3) {
                report.lit_by[k].1 += 1;
            }
        }
        // ForwardBase plus one ForwardAdd per light that lights the object store into the
        // forward target; deferred, the main light (where it lights the object) and those
        // lights store into RT3 (the stencil keeps the others' draws off the object's pixels).
        let forward_stores = 1 + t.lights.len();
        let deferred_lights = usize::from(t.main_lit) + t.lights.len();
        report.culled += usize::from(culled_light_matters(frame, object, &hit.geometry, total));
        let fi = forward_interval(&t, lo, hi, hdr, forward_stores);
        let di = deferred_interval(&t, lo, hi, hdr, deferred_lights);
        // Forward against deferred: the deferred interval around what the forward value says
        // the light is (its own rounding undone; a saturated LDR value says only "≥ 1"),
        // widened by the window's range: forward interpolates the world position with the
        // snapped triangle's weights, deferred rebuilds it on the centre's ray.
        let width = hi - lo;
        let (f_lo, f_hi) = if hdr {
            let e = f16_chain(t.base, &t.adds);
            (f - e, f + e)
        } else {
            let e = Vec3::splat(forward_stores as f32 * unorm_store_error(8));
            let hi = Vec3::select(f.cmpge(Vec3::ONE), Vec3::splat(f32::INFINITY), f + e);
            (f - e, hi)
        };
        let pi = deferred_interval(&t, f_lo - width, f_hi + width, hdr, deferred_lights);
        if layers.is_empty() {
            judge(
                &mut report,
                [x, y],
                object.name,
                total,
                (f, d),
                [fi, di, pi],
                false,
            );
        } else {
            let (fi, di) = (
                through_layers(fi, &layers, hdr),
                through_layers(di, &layers, hdr),
            );
            let name = frame.transparent[centre_layers[0].object].name;
            let reference = (fi.lo + fi.hi) * 0.5;
            judge(
                &mut report,
                [x, y],
                name,
                reference,
                (f, d),
                [fi, di, di],
                true,
            );
        }
    }
    report
}

/// Counts pixel `pixel`'s comparisons: forward `got.0` in `intervals[0]`, deferred `got.1` in
/// `intervals[1]`, and the pair (deferred in `intervals[2]`, the interval the forward value
/// implies) — or, seen `through` semi-transparent surfaces (whose blending the forward value
/// cannot be undone through), both paths in their own intervals.
fn judge(
    report: &mut FrameReport,
    pixel: [u32; 2],
    object: &'static str,
    reference: Vec3,
    (f, d): (Vec3, Vec3),
    intervals: [Interval; 3],
    through: bool,
) {
    let [fi, di, pi] = intervals;
    let mut ratios = [fi.ratio(f), di.ratio(d), pi.ratio(d)];
    let mut failed = [!fi.contains(f), !di.contains(d), !pi.contains(d)];
    if through {
        ratios[2] = ratios[0].max(ratios[1]);
        failed[2] = failed[0] || failed[1];
    }
    for k in 0..3 {
        if ratios[k] > report.worst[k] {
            report.worst[k] = ratios[k];
            report.worst_pixel[k] = pixel;
        }
        report.failures[k] += usize::from(failed[k]);
    }
    if failed.iter().any(|b| *b) {
        push_mismatch(report, pixel, object, reference, f, d, failed);
    }
}

#[allow(clippy::too_many_arguments)]
fn push_mismatch(
    report: &mut FrameReport,
    pixel: [u32; 2],
    object: &'static str,
    reference: Vec3,
    forward: Vec3,
    deferred: Vec3,
    failed: [bool; 3],
) {
    if report.mismatches.len() < 20 {
        report.mismatches.push(FrameMismatch {
            pixel,
            object,
            reference,
            forward,
            deferred,
            failed,
        });
    }
}
