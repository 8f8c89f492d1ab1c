//! Light volumes on the GPU (docs/shading.md §10, "Light volumes"): one light of
//! `deferred_shading/Lighting` drawn the way [`light_draw`](crate::light_volume::light_draw)
//! says — as its volume with the stencil pre-pass of `stencil_write/StencilWrite`, or
//! full-screen — over the G-buffer and the depth buffer of the [`LightRig`], and the comparison of the two ways.
//!
//! The volume draw, as in Unity's built-in deferred path, in two render passes over one
//! `Depth24PlusStencil8` attachment:
//! 1. the scene depth (the rig's `f32` depth buffer, written through `frag_depth` by a
//!    full-screen draw, since depth formats cannot be copied into), stencil cleared to 0; then
//!    the volume's front faces (Cull Back), depth test LessEqual, no depth write, stencil
//!    Always with depth-fail Replace 1: pixels whose geometry lies in front of the volume
//!    are marked;
//! 2. the light over the volume's back faces (Cull Front), depth test GreaterEqual (geometry in
//!    front of the back face), stencil NotEqual 1, blended onto RT3.
//!
//! So the light's fragment stage runs exactly on the pixels whose geometry lies inside the
//! volume. Since the mesh bounds every point the light reaches and the light adds nothing
//! (HDR `+ 0`, LDR `· exp2(−0) = · 1`) where its attenuation is 0, the volume and the
//! full-screen draw must give bit-identical RT3 bytes at every pixel ([`compare_draws`]).

use glam::Vec3;

use super::gbuffer::{GBufferImage, rt3_blend};
use super::lighting::{lighting_resources, render_lighting};
use super::rig::LightRig;
use super::scene::{TestScene, push_mat4};
use super::volume_draw::DEPTH_FILL_WGSL;
use crate::light_volume::{LightDraw, LightVolume};
use crate::render::pipeline;
use crate::{
    BoundResource, CheckError, GpuContext, GpuError, Resource, VertexBuffer,
    encode_texture_readback, finish_readbacks, map_buffers,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightType};

/// The depth-stencil format of the volume draws: always renderable, 8 stencil bits.
const DEPTH_STENCIL: wgpu::TextureFormat = wgpu::TextureFormat::Depth24PlusStencil8;

/// The stencil value marking pixels whose geometry lies in front of the volume.
const STENCIL_MARK: u32 = 1;

/// One light of the volume = full-screen comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeCase {
    /// A short name for messages.
    pub name: &'static str,
    /// The light.
    pub light: Light,
    /// Its keyword in the lighting pass.
    pub light_type: LightType,
}

/// The lights the volume test draws both ways: the rig's point light with and without its
/// cube cookie, its spot light, a point light behind the scene's surface (the surface lies in
/// front of most of its volume, so the stencil pre-pass has pixels to mark), and a point light
/// whose volume contains the camera (so it falls back to the full-screen draw).
pub fn volume_cases(rig: &LightRig) -> Vec<VolumeCase> {
    let around_camera = Light::point(Vec3::new(0.5, -0.3, 3.0), 6.0, Vec3::new(0.7, 0.8, 0.9));
    let behind = Light::point(Vec3::new(0.75, -0.5, -1.0), 1.2, Vec3::new(1.5, 1.2, 1.0));
    vec![
        VolumeCase {
            name: "point behind the surface",
            light: behind,
            light_type: LightType::Point,
        },
        VolumeCase {
            name: "point",
            light: rig.point_light,
            light_type: LightType::Point,
        },
        VolumeCase {
            name: "point with cube cookie",
            light: rig.point_light,
            light_type: LightType::PointCookie,
        },
        VolumeCase {
            name: "spot",
            light: rig.spot_light,
            light_type: LightType::Spot,
        },
        VolumeCase {
            name: "point around the camera",
            light: around_camera,
            light_type: LightType::Point,
        },
    ]
}

/// What one light draw left behind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LightRender {
    /// RT3's bytes.
    pub rt3: Vec<u8>,
    /// For a volume draw, the pixels the stencil pre-pass marked (geometry in front of the
    /// volume: the light skipped them); `None` for a full-screen draw.
    pub stencil_marked: Option<usize>,
}

/// RT3 after drawing `case`'s light as `draw` over `gbuffer` (LDR or HDR as the G-buffer),
/// with the rig's camera and depth buffer.
///
/// # Errors
/// [`GpuError`] from the draws; a light whose parameters are undefined is a
/// [`CheckError::UnknownToReference`].
pub fn render_light(
    ctx: &GpuContext,
    lib: &Library,
    scene: &TestScene,
    rig: &LightRig,
    gbuffer: &GBufferImage,
    case: &VolumeCase,
    draw: &LightDraw,
) -> Result<LightRender, GpuError> {
    let params = case.light.params().map_err(|e| {
        GpuError::from(CheckError::UnknownToReference {
            variant: case.name.to_owned(),
            message: e.to_string(),
        })
    })?;
    let mut keywords = vec![case.light_type.keyword()];
    if gbuffer.hdr {
        keywords.push("UNITY_HDR_ON");
    }
    let variant = lib
        .variant("deferred_shading", "Lighting", &keywords)
        .map_err(|e| CheckError::lookup("deferred_shading/Lighting", e))?;
    let (label, wgsl) = (variant.label(), lib.wgsl(&variant));
    let camera = rig.camera(scene);
    let rt3 = gbuffer.targets[3].clone();
    let volume = match draw {
        LightDraw::FullScreen(_) => {
            let rt3 = render_lighting(
                ctx, scene, rig, gbuffer, &label, &wgsl, &params, &camera, rt3,
            )?;
            return Ok(LightRender {
                rt3,
                stencil_marked: None,
            });
        }
        LightDraw::Volume(volume) => volume,
    };
    let stencil = lib
        .variant("stencil_write", "StencilWrite", &[] as &[&str])
        .map_err(|e| CheckError::lookup("stencil_write/StencilWrite", e))?;
    let light = LightPipelineInput {
        label: &label,
        wgsl: &wgsl,
        resources: lighting_resources(scene, rig, gbuffer, &params, &camera),
        format: gbuffer.rt3_format().wgpu_format(),
        blend: rt3_blend(gbuffer.hdr),
        rt3,
    };
    let (rt3, stencil) = render_volume(
        ctx,
        scene,
        rig,
        &lib.wgsl(&stencil),
        light,
        volume,
        &StencilScheme::built_in(),
    )?;
    Ok(LightRender {
        rt3,
        stencil_marked: Some(stencil.iter().filter(|&&s| s == STENCIL_MARK as u8).count()),
    })
}

/// How a volume draw uses the stencil: what the scene-depth draw stamps, the marking pass over
/// the volume, and the light's test.
pub(crate) struct StencilScheme {
    /// Stencil values the scene-depth draw writes (through `stamp_mask`) into column ranges:
    /// the material-type bits a G-buffer pass writes. Empty: the stencil stays cleared to 0.
    pub(crate) stamps: Vec<(std::ops::Range<u32>, u32)>,
    /// The write mask of the stamps.
    pub(crate) stamp_mask: u32,
    /// Faces the marking pass culls.
    pub(crate) mark_cull: Option<wgpu::Face>,
    /// The marking pass's stencil state and reference.
    pub(crate) mark: (wgpu::StencilState, u32),
    /// The light pass's stencil state and reference.
    pub(crate) light: (wgpu::StencilState, u32),
}

impl StencilScheme {
    /// Unity's built-in path (`stencil_write/StencilWrite`): front faces with depth-fail Replace
    /// mark the pixels whose geometry lies in front of the volume; the light skips them.
    fn built_in() -> StencilScheme {
        let keep = wgpu::StencilOperation::Keep;
        StencilScheme {
            stamps: Vec::new(),
            stamp_mask: 0,
            mark_cull: Some(wgpu::Face::Back),
            mark: (
                stencil(
                    wgpu::CompareFunction::Always,
                    wgpu::StencilOperation::Replace,
                    0xff,
                ),
                STENCIL_MARK,
            ),
            light: (
                stencil(wgpu::CompareFunction::NotEqual, keep, 0),
                STENCIL_MARK,
            ),
        }
    }
}

/// The lighting draw's shader, bindings and target.
pub(crate) struct LightPipelineInput<'a> {
    pub(crate) label: &'a str,
    pub(crate) wgsl: &'a str,
    pub(crate) resources: Vec<BoundResource>,
    pub(crate) format: wgpu::TextureFormat,
    pub(crate) blend: wgpu::BlendState,
    pub(crate) rt3: Vec<u8>,
}

/// Stencil state that replaces the value where `compare` passes (and the depth test too),
/// on both faces, through an all-ones write mask.
fn stencil_replace(compare: wgpu::CompareFunction) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: wgpu::StencilOperation::Keep,
        pass_op: wgpu::StencilOperation::Replace,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: 0xff,
    }
}

/// Stencil state with the same test and operations on both faces.
pub(crate) fn stencil(
    compare: wgpu::CompareFunction,
    depth_fail: wgpu::StencilOperation,
    write: u32,
) -> wgpu::StencilState {
    let face = wgpu::StencilFaceState {
        compare,
        fail_op: wgpu::StencilOperation::Keep,
        depth_fail_op: depth_fail,
        pass_op: wgpu::StencilOperation::Keep,
    };
    wgpu::StencilState {
        front: face,
        back: face,
        read_mask: 0xff,
        write_mask: write,
    }
}

fn depth_stencil(
    write: bool,
    compare: wgpu::CompareFunction,
    stencil: wgpu::StencilState,
) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_STENCIL,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil,
        bias: wgpu::DepthBiasState::default(),
    }
}

/// The scene depth (and `scheme`'s stamps), the stencil pass and the light over `volume`;
/// returns RT3 and the stencil afterwards (one byte per pixel, row by row).
pub(crate) fn render_volume(
    ctx: &GpuContext,
    scene: &TestScene,
    rig: &LightRig,
    stencil_wgsl: &str,
    light: LightPipelineInput<'_>,
    volume: &LightVolume,
    scheme: &StencilScheme,
) -> Result<(Vec<u8>, Vec<u8>), GpuError> {
    let label = light.label;
    let (w, h) = (scene.width, scene.height);
    let mesh = VertexBuffer::from_f32(&[(0, 3)], &volume.positions);
    let layout = [Some(wgpu::VertexBufferLayout {
        array_stride: mesh.stride,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &mesh.attributes,
    })];
    let depth: Vec<u8> = rig.depth.iter().flat_map(|d| d.to_le_bytes()).collect();
    let (fill, fill_groups) = pipeline(
        ctx,
        "light volume: scene depth",
        DEPTH_FILL_WGSL,
        ("vs_main", Some("fs_main")),
        &[],
        None,
        depth_stencil(
            true,
            wgpu::CompareFunction::Always,
            wgpu::StencilState {
                write_mask: scheme.stamp_mask,
                ..stencil_replace(wgpu::CompareFunction::Always)
            },
        ),
        &[],
        &[BoundResource::new(
            0,
            0,
            Resource::Texture2d {
                format: wgpu::TextureFormat::R32Float,
                width: w,
                height: h,
                data: depth,
            },
        )],
    )?;
    let mut camera = Vec::new();
    push_mat4(&mut camera, rig.view_proj);
    let (mark, mark_groups) = pipeline(
        ctx,
        "stencil_write/StencilWrite",
        stencil_wgsl,
        ("vs_main", None),
        &layout,
        scheme.mark_cull,
        depth_stencil(
            false,
            wgpu::CompareFunction::LessEqual,
            scheme.mark.0.clone(),
        ),
        &[],
        &[BoundResource::new(0, 0, Resource::Uniform(camera))],
    )?;
    let target = [Some(wgpu::ColorTargetState {
        format: light.format,
        blend: Some(light.blend),
        write_mask: wgpu::ColorWrites::ALL,
    })];
    let (lit, lit_groups) = pipeline(
        ctx,
        label,
        light.wgsl,
        ("vs_volume", Some("fs_main")),
        &layout,
        Some(wgpu::Face::Front),
        depth_stencil(
            false,
            wgpu::CompareFunction::GreaterEqual,
            scheme.light.0.clone(),
        ),
        &target,
        &light.resources,
    )?;

    let pending = ctx.scoped(label, || {
        let size = wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        };
        let texture = |format, usage| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let rt3 = texture(
            light.format,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
        );
        ctx.queue.write_texture(
            rt3.as_image_copy(),
            &light.rt3,
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some((light.rt3.len() as u32) / h),
                rows_per_image: Some(h),
            },
            size,
        );
        let ds = texture(
            DEPTH_STENCIL,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        );
        let ds_view = ds.create_view(&wgpu::TextureViewDescriptor::default());
        let rt3_view = rt3.create_view(&wgpu::TextureViewDescriptor::default());
        let vertices = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: mesh.data.len() as u64,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&vertices, 0, &mesh.data);
        let count = volume.positions.len() as u32;
        let attachment = |depth_load, stencil_load| wgpu::RenderPassDepthStencilAttachment {
            view: &ds_view,
            depth_ops: Some(wgpu::Operations {
                load: depth_load,
                store: wgpu::StoreOp::Store,
            }),
            stencil_ops: Some(wgpu::Operations {
                load: stencil_load,
                store: wgpu::StoreOp::Store,
            }),
        };
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("light volume: depth and stencil"),
                color_attachments: &[],
                depth_stencil_attachment: Some(attachment(
                    wgpu::LoadOp::Clear(1.0),
                    wgpu::LoadOp::Clear(0),
                )),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&fill);
            for (group, bind_group) in &fill_groups {
                pass.set_bind_group(*group, bind_group, &[]);
            }
            pass.draw(0..3, 0..1);
            // The stamps: the depth again (unchanged) with each column range's stencil value.
            for (columns, value) in &scheme.stamps {
                pass.set_scissor_rect(columns.start, 0, columns.end - columns.start, h);
                pass.set_stencil_reference(*value);
                pass.draw(0..3, 0..1);
            }
            pass.set_scissor_rect(0, 0, w, h);
            pass.set_pipeline(&mark);
            for (group, bind_group) in &mark_groups {
                pass.set_bind_group(*group, bind_group, &[]);
            }
            pass.set_stencil_reference(scheme.mark.1);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..count, 0..1);
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(label),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &rt3_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(attachment(wgpu::LoadOp::Load, wgpu::LoadOp::Load)),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&lit);
            for (group, bind_group) in &lit_groups {
                pass.set_bind_group(*group, bind_group, &[]);
            }
            pass.set_stencil_reference(scheme.light.1);
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..count, 0..1);
        }
        let stencil = encode_stencil_readback(ctx, &mut encoder, &ds, label);
        let pending = encode_texture_readback(ctx, &mut encoder, &rt3, label);
        if pending.is_ok() {
            ctx.queue.submit([encoder.finish()]);
        }
        pending.map(|p| (p, stencil))
    })??;
    let (pending, stencil) = pending;
    let rt3 = finish_readbacks(ctx, label, vec![pending])?.remove(0);
    let rows = map_buffers(ctx, label, &[&stencil])?.remove(0);
    let stencil = rows
        .chunks(STENCIL_ROW as usize)
        .take(h as usize)
        .flat_map(|row| &row[..w as usize])
        .copied()
        .collect();
    Ok((rt3, stencil))
}

/// Bytes per row of the stencil readback: one byte per pixel, padded to wgpu's copy alignment
/// (the check's targets are at most 256 pixels wide).
const STENCIL_ROW: u32 = wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;

/// Records a copy of the stencil aspect of `ds` (at most [`STENCIL_ROW`] pixels wide) into a
/// mappable buffer.
fn encode_stencil_readback(
    ctx: &GpuContext,
    encoder: &mut wgpu::CommandEncoder,
    ds: &wgpu::Texture,
    label: &str,
) -> wgpu::Buffer {
    let buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: u64::from(STENCIL_ROW) * u64::from(ds.height()),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture: ds,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::StencilOnly,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(STENCIL_ROW),
                rows_per_image: Some(ds.height()),
            },
        },
        ds.size(),
    );
    buffer
}

/// How a volume draw compares with the full-screen draw of the same light.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DrawComparison {
    /// Pixels (row-major indices) whose bytes differ between the two draws.
    pub differing: Vec<usize>,
    /// Pixels the full-screen draw changed (the light reaches their geometry).
    pub lit: usize,
}

impl DrawComparison {
    /// Whether the two draws are bit-identical at every pixel.
    pub fn identical(&self) -> bool {
        self.differing.is_empty()
    }
}

/// Compares RT3 after a full-screen draw and after a volume draw of one light, both from
/// `initial`, pixel by pixel (`bytes_per_pixel` bytes each): the draws must agree bit for bit.
///
/// ```
/// use wgsl_variants_gpu::check::volumes::compare_draws;
/// let initial = [0u8, 0, 0, 0];
/// // The full-screen draw lit pixels 1 and 2; a volume missing pixel 2 is caught.
/// let c = compare_draws(&initial, &[0, 5, 7, 0], &[0, 5, 0, 0], 1);
/// assert_eq!((c.differing, c.lit), (vec![2], 2));
/// ```
pub fn compare_draws(
    initial: &[u8],
    full_screen: &[u8],
    volume: &[u8],
    bytes_per_pixel: usize,
) -> DrawComparison {
    let px = |b: &[u8]| -> Vec<Vec<u8>> {
        b.chunks(bytes_per_pixel.max(1))
            .map(<[u8]>::to_vec)
            .collect()
    };
    let (start, full, vol) = (px(initial), px(full_screen), px(volume));
    let n = full.len().max(vol.len());
    DrawComparison {
        differing: (0..n).filter(|&i| full.get(i) != vol.get(i)).collect(),
        lit: (0..full.len())
            .filter(|&i| start.get(i) != full.get(i))
            .count(),
    }
}
