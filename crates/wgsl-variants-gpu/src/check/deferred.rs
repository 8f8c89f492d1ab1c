//! The deferred passes after the G-buffer: `deferred_reflections/Reflections` (one full-screen
//! draw per probe, blended into the `Rgba16Float` reflection buffer), `deferred_reflections/Add`
//! (the buffer onto RT3, HDR and LDR) and `deferred_final/Final` (the LDR decode).
//!
//! The inputs are real: G-buffers rendered by `standard/Deferred` on the same GPU, read back;
//! the reference reads the very same stored texels, so each pass is checked on its own. The
//! reflection buffer is checked after every probe's draw (each draw starts from the previous
//! draw's read-back buffer), so the comparison holds to 1 f16 ULP however many probes overlap.

use std::time::Instant;

use glam::Vec3;

use super::camera::{LightingCamera, depth_camera_resources};
use super::compare::{compare_texel, format_name, pixel};
use super::coverage::keyword_coverage;
use super::gbuffer::{CHAIN_INPUTS, GBufferImage, render_gbuffer, rt3_blend};
use super::pass_check::{PassCheck, Setup};
use super::report::{Mismatch, PassReport};
use super::scene::{MIN_FACE_MARGIN, TestScene, cube_resource, push_probe, texture};
use super::volume_draw::{depth_fill_draw, over_volume};
use crate::light_volume::{LightDraw, probe_draw};
use crate::{
    BoundResource, CheckError, ColorTarget, Draw, DrawPass, GpuContext, GpuError, RenderJob,
    Resource, TargetFormat, render, render_pass,
};
use wgsl_variants::Library;
use wgsl_variants::variants::Choice;
use wgsl_variants_shaders::reference::brdf::Brdf;
use wgsl_variants_shaders::reference::cube::face_margin;
use wgsl_variants_shaders::reference::gbuffer::{GBufferTexel, decode_normal};
use wgsl_variants_shaders::reference::probe::{box_project_grown, composite, draw_order, falloff};
use wgsl_variants_shaders::reference::quantize::unorm_to_f32;
use wgsl_variants_shaders::reference::surface::{
    Keywords, final_ldr, reflection_probe_pixel, reflections_add, view_and_reflection,
};
use wgsl_variants_shaders::reference::tolerance::{f16_blend_error, f16_store_error};

/// Side of the synthetic RT3 the final pass decodes: 32 × 32 texels cover every 10-bit value.
pub const FINAL_RAMP_SIZE: u32 = 32;

/// The composed text of a pass with no keywords (or `keywords`), checked to exist.
fn pass_wgsl(
    lib: &Library,
    shader: &str,
    pass: &str,
    keywords: &[&str],
) -> Result<(String, String), GpuError> {
    let variant = lib
        .variant(shader, pass, keywords)
        .map_err(|e| CheckError::lookup(format!("{shader}/{pass}"), e))?;
    Ok((variant.label(), lib.wgsl(&variant)))
}

/// A full-screen job of `size` pixels with one target.
fn fullscreen_job(
    label: &str,
    wgsl: &str,
    width: u32,
    height: u32,
    target: ColorTarget,
) -> RenderJob {
    let mut job = RenderJob::new(label, wgsl, "vs_main", "fs_main");
    job.width = width;
    job.height = height;
    job.targets = vec![target];
    job
}

/// The reflection buffer after the probes' draws, for one G-buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct Reflections {
    /// `Rgba16Float` bytes after the last draw.
    pub last: Vec<u8>,
    /// Probes drawn as their boxes ([`probe_draw`]); the others were drawn full screen.
    pub boxes: usize,
}

/// How the deferred probes are drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProbeDrawing {
    /// As [`probe_draw`] says: the grown box with the depth test, full screen where the box
    /// crosses the near or far plane (what a renderer does).
    Boxes,
    /// Every probe full screen (the reference's point of view: every pixel blended).
    FullScreen,
}

/// Draws the deferred probes of `scene` over `gbuffer` (`deferred_reflections/Reflections`,
/// in [`draw_order`]) as `drawing` says, and returns the reflection buffer: the
/// probe-box = full-screen comparison of the `gpu_volumes` test.
pub fn reflection_buffer(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    gbuffer: &GBufferImage,
    drawing: ProbeDrawing,
) -> Result<Reflections, GpuError> {
    run_reflections(ctx, lib, scene, gbuffer, None, drawing, Brdf::Brdf1)
}

/// Draws the deferred probes over `gbuffer` one by one with the Reflections variant of tier
/// `brdf`, comparing after each draw when `report` is given; returns the final reflection
/// buffer.
fn run_reflections(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    gbuffer: &GBufferImage,
    mut report: Option<&mut PassReport>,
    drawing: ProbeDrawing,
    brdf: Brdf,
) -> Result<Reflections, GpuError> {
    let tier: Vec<&str> = brdf.keyword().into_iter().collect();
    let (label, wgsl) = pass_wgsl(lib, "deferred_reflections", "Reflections", &tier)?;
    let (w, h) = (scene.width, scene.height);
    let probes: Vec<_> = scene.deferred_probes.iter().map(|(p, _)| *p).collect();
    let order = draw_order(&probes);
    let input = format!(
        "{{{}}} over the G-buffer of standard/Deferred {{{}}}",
        tier.join(", "),
        gbuffer.keywords.join(", ")
    );
    let blend = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::SrcAlpha,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    };
    let stored: Vec<GBufferTexel> = (0..(w * h) as usize).map(|i| gbuffer.texel(i)).collect();
    // The pass rebuilds each pixel's position from the depth of the scene's own camera.
    let depth = scene.depth_buffer();
    let camera = LightingCamera {
        view_proj: scene.view_proj,
        position: scene.scene.camera_position,
        depth: &depth,
    };
    let wgsl: std::sync::Arc<str> = std::sync::Arc::from(wgsl);
    let depth_texture = Resource::Texture2d {
        format: wgpu::TextureFormat::R32Float,
        width: w,
        height: h,
        data: depth.iter().flat_map(|d| d.to_le_bytes()).collect(),
    };
    let mut boxes = 0;
    let mut previous: Option<Vec<u8>> = None;
    for (step, &p) in order.iter().enumerate() {
        let (probe, cube) = &scene.deferred_probes[p];
        let mut target = ColorTarget::new(TargetFormat::Rgba16Float).with_blend(wgpu::BlendState {
            color: blend,
            alpha: blend,
        });
        if let Some(bytes) = &previous {
            target = target.with_initial(bytes.clone());
        }
        let probe_label = format!("{label} probe {p}");
        let mut resources = vec![
            BoundResource::new(
                0,
                0,
                texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[0]),
            ),
            BoundResource::new(
                0,
                1,
                texture(TargetFormat::Rgba8Unorm, w, h, &gbuffer.targets[1]),
            ),
            BoundResource::new(
                0,
                2,
                texture(TargetFormat::Rgb10a2Unorm, w, h, &gbuffer.targets[2]),
            ),
            BoundResource::new(0, 5, cube_resource(cube)),
            BoundResource::new(0, 6, Resource::Sampler { nearest: true }),
            BoundResource::new(0, 7, Resource::Uniform(probe_uniform(probe))),
        ];
        resources.extend(depth_camera_resources((scene.width, scene.height), &camera));
        let draw =
            Draw::fullscreen(&probe_label, &wgsl, "vs_main", "fs_main").with_resources(resources);
        let volume = match drawing {
            ProbeDrawing::FullScreen => None,
            ProbeDrawing::Boxes => match probe_draw(probe, scene.view_proj) {
                Ok(LightDraw::Volume(v)) => Some(v),
                Ok(LightDraw::FullScreen(_)) => None,
                Err(e) => {
                    return Err(GpuError::Validation {
                        label: probe_label,
                        message: e.to_string(),
                    });
                }
            },
        };
        let mut pass = DrawPass::new(&probe_label, w, h, vec![target]);
        if let Some(v) = volume {
            boxes += 1;
            // The scene's depth into the pass's depth buffer, then the box's back faces where
            // the scene lies in front of them.
            pass.depth = true;
            pass.draws.push(depth_fill_draw(depth_texture.clone()));
            pass.draws.push(over_volume(draw, "vs_box", &v));
        } else {
            pass.draws.push(draw);
        }
        let out = render_pass(ctx, &pass)?.targets.remove(0);
        if let Some(report) = report.as_deref_mut() {
            report.draws += 1;
            let target = format!(
                "reflection buffer Rgba16Float after probe {p} (draw {})",
                step + 1
            );
            for (i, (x, y)) in scene.pixels().enumerate() {
                let g = stored[i].to_gbuffer();
                let pos = scene.world_position(x, y);
                // The scene keeps every lookup of a correct G-buffer MIN_FACE_MARGIN away from a
                // cube-face edge; a G-buffer that comes out wrong may not be, and a mismatch there
                // says so (the comparison is made all the same).
                let mut edge_note = String::new();
                if falloff(pos, probe) > 0.0 {
                    let n = decode_normal(g.rt2.truncate());
                    let (_, r) = view_and_reflection(scene.scene.camera_position, pos, n);
                    let margin = face_margin(box_project_grown(r, pos, probe));
                    if margin < MIN_FACE_MARGIN * 0.5 {
                        edge_note = format!(
                            " (this G-buffer's normal reflects {margin:.4} from a cube-face edge)"
                        );
                    }
                }
                let prev = match &previous {
                    Some(bytes) => {
                        Vec3::from_slice(&pixel(TargetFormat::Rgba16Float, bytes, i).1[..3])
                    }
                    None => Vec3::ZERO,
                };
                let sample =
                    reflection_probe_pixel(brdf, &g, pos, scene.scene.camera_position, probe, cube);
                let (src, a) = (sample.truncate(), sample.w);
                let want = composite(prev, &[(src, a)]);
                let (raw, got) = pixel(TargetFormat::Rgba16Float, &out, i);
                let ok = (0..3).all(|c| {
                    let allowed = f16_store_error(want[c]) + f16_blend_error(src[c], a, prev[c]);
                    (got[c] - want[c]).abs() <= allowed
                });
                let (shader, pass) = (report.shader.clone(), report.pass.clone());
                report.record(ok, || Mismatch {
                    shader,
                    pass,
                    keywords: input.clone(),
                    target: format!("{target}{edge_note}"),
                    pixel: [x, y],
                    expected: want.to_array().to_vec(),
                    got: got.to_vec(),
                    got_raw: raw.to_vec(),
                });
            }
        }
        previous = Some(out);
    }
    if let Some(report) = report {
        report.variants_run = 1;
        report.distinct_shaders = 1;
    }
    Ok(Reflections {
        last: previous.unwrap_or_else(|| vec![0; (w * h * 8) as usize]),
        boxes,
    })
}

/// Adds `refl` onto the G-buffer's RT3 with the Add pass of its HDR mode; compares when
/// `report` is given. Returns RT3 after the draw.
fn run_add(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    gbuffer: &GBufferImage,
    refl: &[u8],
    report: Option<&mut PassReport>,
) -> Result<Vec<u8>, GpuError> {
    let keywords: &[&str] = if gbuffer.hdr { &["UNITY_HDR_ON"] } else { &[] };
    let (label, wgsl) = pass_wgsl(lib, "deferred_reflections", "Add", keywords)?;
    let (w, h) = (scene.width, scene.height);
    let format = gbuffer.rt3_format();
    let target = ColorTarget::new(format)
        .with_blend(rt3_blend(gbuffer.hdr))
        .with_initial(gbuffer.targets[3].clone());
    let mut job = fullscreen_job(&label, &wgsl, w, h, target);
    job.resources = vec![BoundResource::new(
        0,
        0,
        texture(TargetFormat::Rgba16Float, w, h, refl),
    )];
    let out = render(ctx, &job)?.remove(0);
    if let Some(report) = report {
        report.draws += 1;
        let input = format!(
            "{{{}}} over the G-buffer of standard/Deferred {{{}}}",
            keywords.join(", "),
            gbuffer.keywords.join(", ")
        );
        let target = format!("RT3 {}", format_name(format));
        for i in 0..(w * h) as usize {
            let rt3 = gbuffer.texel(i).rt3.to_vec4();
            let refl = Vec3::from_slice(&pixel(TargetFormat::Rgba16Float, refl, i).1[..3]);
            let want = reflections_add(rt3.truncate(), refl, gbuffer.hdr).extend(rt3.w);
            compare_texel(report, &input, &target, format, &out, i, w, want);
        }
    }
    Ok(out)
}

/// Decodes an LDR RT3 (`Rgb10a2Unorm` bytes of `width × height`) with the final pass and
/// compares with [`final_ldr`] when `report` is given. Returns the `Rgba8Unorm` frame.
fn run_final(
    ctx: &GpuContext,
    lib: &Library,
    rt3: &[u8],
    width: u32,
    height: u32,
    input: &str,
    report: Option<&mut PassReport>,
) -> Result<Vec<u8>, GpuError> {
    let (label, wgsl) = pass_wgsl(lib, "deferred_final", "Final", &[])?;
    let clear = [0.5, 0.25, 0.75, 0.0];
    let target = ColorTarget::new(TargetFormat::Rgba8Unorm).with_clear(clear);
    let mut job = fullscreen_job(&label, &wgsl, width, height, target);
    job.resources = vec![BoundResource::new(
        0,
        0,
        texture(TargetFormat::Rgb10a2Unorm, width, height, rt3),
    )];
    let out = render(ctx, &job)?.remove(0);
    if let Some(report) = report {
        report.draws += 1;
        for i in 0..(width * height) as usize {
            let (raw, _) = pixel(TargetFormat::Rgb10a2Unorm, rt3, i);
            let stored = Vec3::new(
                unorm_to_f32(raw[0], 10),
                unorm_to_f32(raw[1], 10),
                unorm_to_f32(raw[2], 10),
            );
            let want = final_ldr(stored).extend(1.0);
            compare_texel(
                report,
                input,
                "out Rgba8Unorm",
                TargetFormat::Rgba8Unorm,
                &out,
                i,
                width,
                want,
            );
        }
    }
    Ok(out)
}

/// Decodes an LDR RT3 (`Rgb10a2Unorm` bytes of `width × height`) with `deferred_final/Final`
/// into an `Rgba8Unorm` frame, without comparing.
pub fn final_pass(
    ctx: &GpuContext,
    lib: &Library,
    rt3: &[u8],
    width: u32,
    height: u32,
) -> Result<Vec<u8>, GpuError> {
    run_final(ctx, lib, rt3, width, height, "", None)
}

/// An `Rgb10a2Unorm` image of `FINAL_RAMP_SIZE²` texels in which every channel value
/// 0 ..= 1023 occurs in each of r, g and b (in different orders), a = 3.
pub fn ldr_ramp() -> Vec<u8> {
    let n = FINAL_RAMP_SIZE * FINAL_RAMP_SIZE;
    (0..n)
        .flat_map(|i| {
            let r = i;
            let g = 1023 - i;
            let b = (i * 389) % 1024;
            wgsl_variants_shaders::reference::quantize::pack_rgb10a2([r, g, b, 3]).to_le_bytes()
        })
        .collect()
}

/// The results of the deferred chain for pictures: per chain input, the reflection buffer,
/// RT3 after Add, and (LDR) the final frame.
#[derive(Clone, Debug)]
pub struct ChainImages {
    /// The reflection buffer (`Rgba16Float`).
    pub reflections: Vec<u8>,
    /// RT3 after adding the reflections.
    pub rt3: Vec<u8>,
    /// The final `Rgba8Unorm` frame (LDR only).
    pub frame: Option<Vec<u8>>,
}

/// Runs reflections, add and (LDR) final over a G-buffer without comparing (for pictures).
pub fn render_chain(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    gbuffer: &GBufferImage,
) -> Result<ChainImages, GpuError> {
    let refl = run_reflections(
        ctx,
        lib,
        scene,
        gbuffer,
        None,
        ProbeDrawing::Boxes,
        Brdf::Brdf1,
    )?
    .last;
    let rt3 = run_add(ctx, lib, scene, gbuffer, &refl, None)?;
    let frame = if gbuffer.hdr {
        None
    } else {
        Some(run_final(
            ctx,
            lib,
            &rt3,
            scene.width,
            scene.height,
            "",
            None,
        )?)
    };
    Ok(ChainImages {
        reflections: refl,
        rt3,
        frame,
    })
}

/// Checks the selected passes of the chain (`Reflections`, `Add`, `Final`), running the
/// earlier passes as setup where only later ones are selected.
pub fn check_deferred_chain(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    chain: &[(&str, &str)],
) -> Result<Vec<PassReport>, GpuError> {
    let wants = |pass: &str| chain.iter().any(|(_, p)| *p == pass);
    let mut reflections = PassReport::new("deferred_reflections", "Reflections");
    let mut add = PassReport::new("deferred_reflections", "Add");
    let mut fin = PassReport::new("deferred_final", "Final");
    let (mut t_refl, mut t_add, mut t_final) = (0.0, 0.0, 0.0);
    let mut add_outputs: Vec<(bool, Vec<u8>)> = Vec::new();
    // The reflection buffers of the first LDR input, one per tier (Brdf::ALL order).
    let mut tier_outputs: Vec<Vec<u8>> = Vec::new();

    if wants("Reflections") || wants("Add") || wants("Final") {
        // LDR and HDR G-buffers of each chain input.
        for (n, keywords) in CHAIN_INPUTS.iter().enumerate() {
            for hdr in [false, true] {
                if !wants("Reflections") && !wants("Add") && (hdr || n > 0) {
                    continue; // Final alone needs one LDR RT3
                }
                let mut kw: Vec<&str> = keywords.names();
                if hdr {
                    kw.push("UNITY_HDR_ON");
                }
                debug_assert!(Keywords::from_names(&kw).is_ok());
                let gbuffer = render_gbuffer(ctx, lib, scene, &kw)?;
                let start = Instant::now();
                // Every tier over every input (the G-buffer does not depend on the tier with
                // reflection buffers); BRDF1's buffer goes on to Add.
                let mut refl = None;
                for brdf in Brdf::ALL {
                    if brdf != Brdf::Brdf1 && !wants("Reflections") {
                        continue;
                    }
                    let out = run_reflections(
                        ctx,
                        lib,
                        scene,
                        &gbuffer,
                        wants("Reflections").then_some(&mut reflections),
                        ProbeDrawing::Boxes,
                        brdf,
                    )?;
                    if n == 0 && !hdr {
                        tier_outputs.push(out.last.clone());
                    }
                    if brdf == Brdf::Brdf1 {
                        refl = Some(out);
                    }
                }
                let refl = refl.expect("BRDF1 always runs");
                t_refl += start.elapsed().as_secs_f64();
                let start = Instant::now();
                let rt3 = run_add(
                    ctx,
                    lib,
                    scene,
                    &gbuffer,
                    &refl.last,
                    wants("Add").then_some(&mut add),
                )?;
                t_add += start.elapsed().as_secs_f64();
                if !hdr && wants("Final") {
                    let start = Instant::now();
                    let input = format!(
                        "RT3 after Reflections + Add over standard/Deferred {{{}}}",
                        kw.join(", ")
                    );
                    run_final(
                        ctx,
                        lib,
                        &rt3,
                        scene.width,
                        scene.height,
                        &input,
                        Some(&mut fin),
                    )?;
                    t_final += start.elapsed().as_secs_f64();
                }
                add_outputs.push((hdr, rt3));
            }
        }
    }

    let mut reports = Vec::new();
    if wants("Reflections") {
        let probes: Vec<_> = scene.deferred_probes.iter().map(|(p, _)| *p).collect();
        reflections.notes.push(format!(
            "{} probes drawn in order {:?} over {} G-buffers, in each BRDF tier; compared after every draw",
            probes.len(),
            draw_order(&probes),
            CHAIN_INPUTS.len() * 2
        ));
        // Keyword coverage: the tiers' buffers over the same input differ.
        let pass = lib
            .pass("deferred_reflections", "Reflections")
            .map_err(|e| CheckError::lookup("deferred_reflections/Reflections", e))?;
        let choices: Vec<Choice> = Brdf::ALL
            .iter()
            .map(|b| {
                let tier: Vec<&str> = b.keyword().into_iter().collect();
                pass.resolve(&tier)
                    .map_err(|e| CheckError::lookup("deferred_reflections/Reflections", e))
            })
            .collect::<Result<_, _>>()?;
        reflections.variants_run = choices.len();
        reflections.distinct_shaders = choices.len();
        reflections.keywords =
            keyword_coverage(pass, &choices, |a, b| tier_outputs[a] != tier_outputs[b]);
        reflections.judge_keywords();
        reflections.seconds = t_refl;
        reports.push(reflections);
    }
    if wants("Add") {
        add.variants_run = 2;
        add.distinct_shaders = 2;
        // Keyword coverage: the HDR and LDR results of the same input differ.
        let pass = lib
            .pass("deferred_reflections", "Add")
            .map_err(|e| CheckError::lookup("deferred_reflections/Add", e))?;
        let choices: Vec<Choice> = [&[][..], &["UNITY_HDR_ON"][..]]
            .iter()
            .map(|k| {
                pass.resolve(k)
                    .map_err(|e| CheckError::lookup("deferred_reflections/Add", e))
            })
            .collect::<Result<_, _>>()?;
        let decoded = |hdr: bool| -> Vec<[f32; 4]> {
            add_outputs
                .iter()
                .find(|(h, _)| *h == hdr)
                .map(|(h, bytes)| {
                    let format = if *h {
                        TargetFormat::Rgba16Float
                    } else {
                        TargetFormat::Rgb10a2Unorm
                    };
                    format.decode_image_f32(bytes)
                })
                .unwrap_or_default()
        };
        let (ldr, hdr) = (decoded(false), decoded(true));
        add.keywords = keyword_coverage(pass, &choices, |a, b| {
            let of = |i: usize| {
                if choices[i].0.iter().any(|&o| o != 0) {
                    &hdr
                } else {
                    &ldr
                }
            };
            of(a) != of(b)
        });
        add.judge_keywords();
        add.notes.push(String::from(
            "HDR: One/One onto the Rgba16Float RT3; LDR: DstColor/Zero onto the Rgb10a2Unorm exp2(-c) RT3",
        ));
        add.seconds = t_add;
        reports.push(add);
    }
    if wants("Final") {
        let start = Instant::now();
        let ramp = ldr_ramp();
        run_final(
            ctx,
            lib,
            &ramp,
            FINAL_RAMP_SIZE,
            FINAL_RAMP_SIZE,
            "synthetic RT3: every 10-bit value 0..=1023 in r, g and b",
            Some(&mut fin),
        )?;
        t_final += start.elapsed().as_secs_f64();
        fin.variants_run = 1;
        fin.distinct_shaders = 1;
        fin.notes.push(String::from(
            "RT3 value 0 decodes to +inf, clamped to 255 by the Rgba8Unorm target",
        ));
        fin.seconds = t_final;
        reports.push(fin);
    }
    Ok(reports)
}

/// The deferred chain in the check's registry: `Reflections`, `Add` and `Final` are one entry,
/// since each pass's output is the next one's input.
pub(crate) struct DeferredChain;

/// The entry of the deferred chain.
pub(crate) static CHAIN: DeferredChain = DeferredChain;

impl PassCheck for DeferredChain {
    fn passes(&self) -> &'static [(&'static str, &'static str)] {
        &[
            ("deferred_reflections", "Reflections"),
            ("deferred_reflections", "Add"),
            ("deferred_final", "Final"),
        ]
    }

    fn check(
        &self,
        setup: &Setup<'_>,
        selected: &[(&str, &str)],
    ) -> Result<Vec<PassReport>, GpuError> {
        check_deferred_chain(setup.ctx, setup.lib, setup.scene, selected)
    }
}

/// The `Probe` uniform of the deferred reflection pass (`deferred/probe`'s record).
fn probe_uniform(probe: &wgsl_variants_shaders::reference::probe::Probe) -> Vec<u8> {
    let mut out = Vec::new();
    push_probe(&mut out, probe);
    out
}
