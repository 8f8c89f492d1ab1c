//! The frame as a renderer draws it, for timing: the same draws as
//! [`render_forward`](super::render_forward) and [`render_deferred`](super::render_deferred),
//! but every target stays on the GPU between passes (the G-buffer and the light buffer are
//! read where they were written, the depth buffer is the light volumes' read-only depth
//! attachment), prepared once (pipelines compiled, resources uploaded) and recorded into one
//! submission per frame, each pass timed with timestamp queries where the adapter has them
//! ([`crate::PassSpan`]).
//!
//! - forward: `forward base` (ForwardBase per object), `forward add` (ForwardAdd per light and
//!   object, blended One / One, the depth buffer read-only), `forward part`;
//! - deferred: `G-buffer` (Deferred per object into RT0–RT3 and depth), `lighting` (one
//!   Lighting draw per light, RT0–RT2 and depth bound as textures), in LDR `final`, and
//!   `forward part`;
//!
//! where `forward part` is what both paths share after their opaque objects: the sky, then
//! each semi-transparent object's ForwardBase and ForwardAdd draws, blended over the lit
//! image, the opaque depth read-only (absent from a scene without a sky or semi-transparent
//! objects).
//!
//! Nothing is read back while a frame runs; [`ResidentFrame::image`] copies the final target
//! back afterwards, which is how the tests hold this frame to the read-back one.
//! [`ResidentFrame::lighting_traffic`] counts the Lighting pass's fragments with a separate,
//! untimed pass and gives the bytes it moves.
//!
//! Scenes whose directional lights need screen-space shadow masks are refused: the masks are
//! made from a depth read-back ([`FrameShadows::with_masks`]), which this frame avoids. The
//! bench's scenes ([`FrameScene::with_point_lights`]) have none.
//!
//! ```no_run
//! use wgsl_variants_gpu::GpuContext;
//! use wgsl_variants_gpu::check::frame::{FrameScene, ResidentFrame, render_shadows};
//! let ctx = GpuContext::new(None).unwrap();
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let frame = FrameScene::sized(1920, 1080).with_point_lights(16);
//! let shadows = render_shadows(&ctx, &lib, &frame).unwrap();
//! let deferred = ResidentFrame::deferred(&ctx, &lib, &frame, &shadows, true).unwrap();
//! let time = deferred.run(&ctx).unwrap();
//! for (name, span) in deferred.pass_names().iter().zip(time.passes.iter().flatten()) {
//!     println!("{name}: {:.3} ms", span.ms());
//! }
//! ```

use std::sync::Arc;
use std::time::{Duration, Instant};

use super::{
    ADD, Drawer, FrameScene, FrameShadows, LayerStencil, PathImage, forward_draws, forward_part,
    gbuffer_draws, gbuffer_targets, lighting_draws, rt3_format,
};
use crate::check::gbuffer::rt3_blend;
use crate::render::resident::{
    DepthUse, GpuTexture, PreparedPass, ResidentColor, ResidentPass, prepare,
};
use crate::render::timing::PassTimer;
use crate::{
    BoundResource, DEPTH_FORMAT, DEPTH_STENCIL_FORMAT, Draw, GpuContext, GpuError, PassSpan,
    Resource, TargetFormat,
};
use wgsl_variants::Library;

/// One run of a [`ResidentFrame`].
#[derive(Clone, Debug, PartialEq)]
pub struct FrameTime {
    /// Wall-clock time from the start of recording to the GPU's completion (the CPU's clock:
    /// recording, submission and the wait included).
    pub wall: Duration,
    /// Each pass's span on the GPU's clock, in [`ResidentFrame::pass_names`] order; `None`
    /// when the adapter has no timestamp queries.
    pub passes: Option<Vec<PassSpan>>,
}

impl FrameTime {
    /// GPU time of the whole frame in milliseconds (first pass's start to last pass's end),
    /// if timed.
    pub fn gpu_ms(&self) -> Option<f64> {
        let passes = self.passes.as_ref()?;
        Some((passes.last()?.end_ns - passes.first()?.start_ns) * 1e-6)
    }
}

/// What the deferred Lighting pass reads and writes, per fragment and in all.
///
/// Per fragment a Lighting draw shades, the shader loads one texel of RT0, RT1, RT2 and the
/// depth buffer, and the blend reads and writes RT3's texel:
///
/// `bytes_read = bpp(RT0) + bpp(RT1) + bpp(RT2) + bpp(depth) + bpp(RT3)`,
/// `bytes_written = bpp(RT3)`,
///
/// each `bpp` the texel size of the format actually bound (the depth aspect for the depth
/// buffer): 4 + 4 + 4 + 4 + 8 = 24 read and 8 written in HDR (`Rgba16Float` RT3), 20 and 4 in
/// LDR (`Rgb10a2Unorm` RT3). The light volumes' depth test reads the same depth texel the
/// shader loads and is not counted twice; the light's uniform is one cached read per draw.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightingTraffic {
    /// Fragments the Lighting pass shades: every pixel for a full-screen light, the pixels
    /// whose surface lies inside a volume for the others (counted on the GPU).
    pub fragments: u64,
    /// Bytes read per fragment (the formula above).
    pub bytes_read_per_fragment: u64,
    /// Bytes written per fragment.
    pub bytes_written_per_fragment: u64,
}

impl LightingTraffic {
    /// Bytes the pass moves to and from memory at least: fragments × (read + written).
    pub fn bytes_moved(&self) -> u64 {
        self.fragments * (self.bytes_read_per_fragment + self.bytes_written_per_fragment)
    }

    /// The memory-bandwidth floor of the pass in milliseconds at `gb_per_s` (10⁹ bytes per
    /// second): no GPU with that bandwidth moves these bytes faster.
    pub fn floor_ms(&self, gb_per_s: f64) -> f64 {
        self.bytes_moved() as f64 / (gb_per_s * 1e9) * 1e3
    }
}

/// Counts fragments: the light's volume (or full screen) with the Lighting draw's pipeline
/// state, adding 1 per fragment to an `Rgba16Float` target (exact up to 2048 per pixel).
const COUNT_WGSL: &str = "
struct DeferredCamera {
    inv_view_proj: mat4x4f,
    position: vec4f,
    view_proj: mat4x4f,
}
@group(0) @binding(4) var<uniform> deferred_camera: DeferredCamera;

@vertex
fn vs_main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {
    let uv = vec2f(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4f(uv * 2.0 - 1.0, 0.0, 1.0);
}

@vertex
fn vs_volume(@location(0) world_position: vec3f) -> @builtin(position) vec4f {
    return deferred_camera.view_proj * vec4f(world_position, 1.0);
}

@fragment
fn fs_main() -> @location(0) vec4f {
    return vec4f(1.0, 0.0, 0.0, 0.0);
}
";

/// The deferred frame's fragment count pass and the bytes per fragment of its Lighting pass.
#[derive(Debug)]
struct Counter {
    pass: PreparedPass,
    target: GpuTexture,
    bytes_read: u64,
    bytes_written: u64,
}

/// One path of the frame, prepared on the GPU: run it as often as needed.
#[derive(Debug)]
pub struct ResidentFrame {
    label: &'static str,
    passes: Vec<PreparedPass>,
    timer: Option<PassTimer>,
    output: GpuTexture,
    format: TargetFormat,
    volumes: usize,
    counter: Option<Counter>,
}

/// The `forward part` pass over `color` with the opaque `depth` read-only, or none without
/// draws.
fn forward_part_pass(
    ctx: &GpuContext,
    color: &GpuTexture,
    depth: &GpuTexture,
    draws: &[Draw],
) -> Result<Option<PreparedPass>, GpuError> {
    if draws.is_empty() {
        return Ok(None);
    }
    prepare(
        ctx,
        &ResidentPass {
            label: "forward part",
            colors: vec![ResidentColor {
                texture: color,
                clear: None,
                blend: None,
            }],
            depth: Some((depth, DepthUse::ReadOnly)),
            inputs: Vec::new(),
            copy_depth_to: None,
            draws,
        },
    )
    .map(Some)
}

/// Refuses shadows that need a depth read-back (see the module's documentation).
fn resident_shadows(label: &str, shadows: &FrameShadows) -> Result<(), GpuError> {
    if shadows.needs_masks() {
        return Err(GpuError::Validation {
            label: label.to_owned(),
            message: String::from(
                "screen-space shadow masks are made from a depth read-back; the GPU-resident \
                 frame draws scenes without them",
            ),
        });
    }
    Ok(())
}

impl ResidentFrame {
    /// The forward path: `forward base`, then `forward add`.
    ///
    /// # Errors
    /// A scene that needs screen-space shadow masks, and every error of preparing the draws
    /// (as [`render_pass`](crate::render_pass)).
    pub fn forward(
        ctx: &GpuContext,
        lib: &Library,
        frame: &FrameScene,
        shadows: &FrameShadows,
        hdr: bool,
    ) -> Result<ResidentFrame, GpuError> {
        let label = "frame (GPU-resident): forward";
        resident_shadows(label, shadows)?;
        let (w, h) = (frame.width, frame.height);
        let format = if hdr {
            TargetFormat::Rgba16Float
        } else {
            TargetFormat::Rgba8Unorm
        };
        let color = GpuTexture::new(ctx, label, w, h, format.wgpu_format())?;
        let depth = GpuTexture::new(ctx, label, w, h, DEPTH_FORMAT)?;
        let mut drawer = Drawer::new(lib, frame, hdr);
        let (base, add) = forward_draws(&mut drawer, frame, shadows)?;
        let part = forward_part(&mut drawer, frame)?;
        let base = prepare(
            ctx,
            &ResidentPass {
                label: "forward base",
                colors: vec![ResidentColor {
                    texture: &color,
                    clear: Some([0.0; 4]),
                    blend: None,
                }],
                depth: Some((&depth, DepthUse::Clear)),
                inputs: Vec::new(),
                copy_depth_to: None,
                draws: &base,
            },
        )?;
        let add = prepare(
            ctx,
            &ResidentPass {
                label: "forward add",
                colors: vec![ResidentColor {
                    texture: &color,
                    clear: None,
                    blend: None,
                }],
                depth: Some((&depth, DepthUse::ReadOnly)),
                inputs: Vec::new(),
                copy_depth_to: None,
                draws: &add,
            },
        )?;
        let mut passes = vec![base, add];
        passes.extend(forward_part_pass(ctx, &color, &depth, &part)?);
        Ok(ResidentFrame::new(
            ctx, label, passes, color, format, 0, None,
        ))
    }

    /// The deferred path: `G-buffer`, `lighting`, and in LDR `final`.
    ///
    /// # Errors
    /// As [`ResidentFrame::forward`].
    pub fn deferred(
        ctx: &GpuContext,
        lib: &Library,
        frame: &FrameScene,
        shadows: &FrameShadows,
        hdr: bool,
    ) -> Result<ResidentFrame, GpuError> {
        let label = "frame (GPU-resident): deferred";
        resident_shadows(label, shadows)?;
        let (w, h) = (frame.width, frame.height);
        let targets = gbuffer_targets(hdr);
        let rts = targets
            .iter()
            .map(|t| GpuTexture::new(ctx, label, w, h, t.format.wgpu_format()))
            .collect::<Result<Vec<_>, _>>()?;
        let stencil = LayerStencil::new(frame)?;
        // The G-buffer pass's stencil marks stay in the attachment the Lighting pass tests and
        // its volumes' pre-passes write; the lights sample a copy of its depth.
        let depth = GpuTexture::new(ctx, label, w, h, DEPTH_STENCIL_FORMAT)?;
        let depth_copy = GpuTexture::new(ctx, label, w, h, wgpu::TextureFormat::R32Float)?;
        let mut drawer = Drawer::new(lib, frame, hdr);
        let gbuffer_draws = gbuffer_draws(&mut drawer, &stencil)?;
        let gbuffer = prepare(
            ctx,
            &ResidentPass {
                label: "G-buffer",
                colors: rts
                    .iter()
                    .zip(&targets)
                    .map(|(texture, t)| ResidentColor {
                        texture,
                        clear: Some(t.clear),
                        blend: None,
                    })
                    .collect(),
                depth: Some((&depth, DepthUse::Clear)),
                inputs: Vec::new(),
                copy_depth_to: Some(&depth_copy),
                draws: &gbuffer_draws,
            },
        )?;
        // The camera is the one resource every light shares; the G-buffer is bound where it
        // was rendered (inputs), not uploaded.
        let shared: Arc<[BoundResource]> = Arc::from(vec![BoundResource::new(
            0,
            4,
            Resource::Uniform(frame.deferred_camera()),
        )]);
        let (lights, volumes) =
            lighting_draws(&mut drawer, frame, shadows, hdr, &shared, &stencil)?;
        let inputs = vec![
            ((0, 0), &rts[0]),
            ((0, 1), &rts[1]),
            ((0, 2), &rts[2]),
            ((0, 3), &depth_copy),
        ];
        let lighting = prepare(
            ctx,
            &ResidentPass {
                label: "lighting",
                colors: vec![ResidentColor {
                    texture: &rts[3],
                    clear: None,
                    blend: Some(rt3_blend(hdr)),
                }],
                depth: Some((&depth, DepthUse::ReadDepthWriteStencil)),
                inputs,
                copy_depth_to: None,
                draws: &lights,
            },
        )?;
        let counter = Counter::new(ctx, &lights, (&depth, &depth_copy), &rts)?;
        let mut passes = vec![gbuffer, lighting];
        let mut rts = rts;
        let (output, format) = if hdr {
            (rts.remove(3), rt3_format(hdr))
        } else {
            let out = GpuTexture::new(ctx, label, w, h, TargetFormat::Rgba8Unorm.wgpu_format())?;
            let (final_label, wgsl) = drawer.text("deferred_final", "Final", Vec::new())?;
            let draw = [Draw::fullscreen(&final_label, &wgsl, "vs_main", "fs_main")];
            passes.push(prepare(
                ctx,
                &ResidentPass {
                    label: "final",
                    colors: vec![ResidentColor {
                        texture: &out,
                        clear: Some([0.5, 0.25, 0.75, 0.0]),
                        blend: None,
                    }],
                    depth: None,
                    inputs: vec![((0, 0), &rts[3])],
                    copy_depth_to: None,
                    draws: &draw,
                },
            )?);
            (out, TargetFormat::Rgba8Unorm)
        };
        let part = forward_part(&mut drawer, frame)?;
        passes.extend(forward_part_pass(ctx, &output, &depth, &part)?);
        Ok(ResidentFrame::new(
            ctx,
            label,
            passes,
            output,
            format,
            volumes,
            Some(counter),
        ))
    }

    fn new(
        ctx: &GpuContext,
        label: &'static str,
        passes: Vec<PreparedPass>,
        output: GpuTexture,
        format: TargetFormat,
        volumes: usize,
        counter: Option<Counter>,
    ) -> ResidentFrame {
        ResidentFrame {
            label,
            timer: PassTimer::new(ctx, label, passes.len()),
            passes,
            output,
            format,
            volumes,
            counter,
        }
    }

    /// The same frame timed by the wall clock only (as on an adapter without timestamp
    /// queries): to check that fallback on an adapter that has them.
    pub fn without_timestamps(mut self) -> ResidentFrame {
        self.timer = None;
        self
    }

    /// Whether [`ResidentFrame::run`] times each pass on the GPU.
    pub fn timed(&self) -> bool {
        self.timer.is_some()
    }

    /// The passes' names, in order (`forward base`, `forward add`; `G-buffer`, `lighting`,
    /// `final`).
    pub fn pass_names(&self) -> Vec<&str> {
        self.passes.iter().map(PreparedPass::label).collect()
    }

    /// Draw calls of a frame.
    pub fn draws(&self) -> usize {
        self.passes.iter().map(PreparedPass::draws).sum()
    }

    /// Lights the deferred path draws as their volume (0 forward).
    pub fn volumes(&self) -> usize {
        self.volumes
    }

    /// Renders the frame once: every pass recorded into one command buffer (with timestamp
    /// writes when timed), submitted, and waited for; then the timestamps (16 bytes a pass)
    /// are read. Nothing else is read back.
    ///
    /// # Errors
    /// A wgpu error while recording ([`GpuError::Validation`]), a timeout or a lost device.
    pub fn run(&self, ctx: &GpuContext) -> Result<FrameTime, GpuError> {
        let start = Instant::now();
        ctx.scoped(self.label, || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some(self.label),
                });
            for (i, pass) in self.passes.iter().enumerate() {
                pass.encode(&mut encoder, self.timer.as_ref().map(|t| t.writes(i)));
            }
            if let Some(timer) = &self.timer {
                timer.resolve(&mut encoder);
            }
            ctx.queue.submit([encoder.finish()]);
        })?;
        ctx.wait(self.label)?;
        let wall = start.elapsed();
        let passes = match &self.timer {
            Some(timer) => Some(timer.read(ctx, self.label)?),
            None => None,
        };
        Ok(FrameTime { wall, passes })
    }

    /// The final target after the last [`ResidentFrame::run`], copied back.
    ///
    /// # Errors
    /// As [`crate::read_texture`].
    pub fn image(&self, ctx: &GpuContext) -> Result<PathImage, GpuError> {
        Ok(PathImage {
            bytes: self.output.read(ctx, self.label)?,
            format: self.format,
            draws: self.draws(),
            volumes: self.volumes,
        })
    }

    /// The deferred Lighting pass's fragments and bytes (`None` for the forward path): one
    /// untimed pass over the light volumes after the last [`ResidentFrame::run`], whose count
    /// target is read back.
    ///
    /// # Errors
    /// As [`ResidentFrame::run`] and [`crate::read_texture`].
    pub fn lighting_traffic(&self, ctx: &GpuContext) -> Result<Option<LightingTraffic>, GpuError> {
        let Some(counter) = &self.counter else {
            return Ok(None);
        };
        let label = "lighting fragments";
        ctx.scoped(label, || {
            let mut encoder = ctx
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
            counter.pass.encode(&mut encoder, None);
            ctx.queue.submit([encoder.finish()]);
        })?;
        ctx.wait(label)?;
        let counts = counter.target.read(ctx, label)?;
        let fragments = counts
            .chunks_exact(8)
            .map(|p| TargetFormat::Rgba16Float.decode_pixel_f32(p)[0] as u64)
            .sum();
        Ok(Some(LightingTraffic {
            fragments,
            bytes_read_per_fragment: counter.bytes_read,
            bytes_written_per_fragment: counter.bytes_written,
        }))
    }
}

impl Counter {
    /// The count pass over `lights` (the Lighting draws, their shader swapped for
    /// [`COUNT_WGSL`]; the volumes' stencil pre-passes as they are) against the depth-stencil
    /// attachment `depth`, and the formula's bytes from the formats of `rts` (RT0–RT3) and of
    /// the depth the lights sample (`sampled`).
    fn new(
        ctx: &GpuContext,
        lights: &[Draw],
        (depth, sampled): (&GpuTexture, &GpuTexture),
        rts: &[GpuTexture],
    ) -> Result<Counter, GpuError> {
        let label = "lighting fragments";
        let wgsl: Arc<str> = Arc::from(COUNT_WGSL);
        let draws: Vec<Draw> = lights
            .iter()
            .map(|d| {
                if d.color_writes.is_empty() {
                    return d.clone();
                }
                Draw {
                    label: format!("count {}", d.label),
                    wgsl: Arc::clone(&wgsl),
                    ..d.clone()
                }
            })
            .collect();
        let size = depth.size();
        let target = GpuTexture::new(
            ctx,
            label,
            size.0,
            size.1,
            TargetFormat::Rgba16Float.wgpu_format(),
        )?;
        let pass = prepare(
            ctx,
            &ResidentPass {
                label,
                colors: vec![ResidentColor {
                    texture: &target,
                    clear: Some([0.0; 4]),
                    blend: Some(ADD),
                }],
                depth: Some((depth, DepthUse::ReadDepthWriteStencil)),
                inputs: Vec::new(),
                copy_depth_to: None,
                draws: &draws,
            },
        )?;
        let rt3 = rts[3].texel_bytes();
        let bytes_read =
            rts[..3].iter().map(GpuTexture::texel_bytes).sum::<u64>() + sampled.texel_bytes() + rt3;
        Ok(Counter {
            pass,
            target,
            bytes_read,
            bytes_written: rt3,
        })
    }
}
