//! Shadow maps for the GPU check: `standard/ShadowCaster` renders a small occluder scene made
//! here (two cut-out quads between the lights and the test scene's floor) into a 2D
//! `Depth16Unorm` map for the spot light (`SHADOWS_DEPTH`) and a `Rgba16Float` cube of
//! distances for the point light (`SHADOWS_CUBE`, one draw per face, each with a depth buffer).
//! The maps are read back: the GPU binds them to the shadowed variants of `Lighting` and
//! `ForwardAdd`, and the CPU reference ([`wgsl_variants_shaders::reference::shadow`]) runs its own
//! comparison and filter over the same texels. So the reference tests the receivers' math
//! exactly; [`analytic_occlusion`] then checks that the caster's map puts the shadow where the
//! geometry says (a ray from the floor to the light through the quads and their cut-out
//! holes).

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::scene::{MapTexture, push_mat4, push_vec4};
use crate::render::pipeline;
use crate::{
    BoundResource, CheckError, GpuContext, GpuError, Resource, VertexBuffer, read_texture,
};
use wgsl_variants::Library;
use wgsl_variants_shaders::reference::light::{Light, LightType};
use wgsl_variants_shaders::reference::quantize::f16_bits_to_f32;
#[cfg(doc)]
use wgsl_variants_shaders::reference::shadow::atlas_tile;
use wgsl_variants_shaders::reference::shadow::{
    ShadowCube, ShadowError, ShadowKeywords, ShadowMap2d, ShadowMaps, ShadowParams,
    cube_face_view_proj, shadow_factor,
};

/// Edge length of the spot light's 2D map in texels.
pub const MAP_SIZE: u32 = 64;
/// Edge length of the point light's cube faces in texels.
pub const CUBE_SIZE: u32 = 16;
/// The spot shadow's strength.
pub const SPOT_STRENGTH: f32 = 0.8;
/// The point shadow's strength.
pub const POINT_STRENGTH: f32 = 0.9;
/// The spot shadow's receiver depth bias (depth-buffer units).
pub const SPOT_BIAS: f32 = 0.0005;
/// The occluders' cutoff: `main_tex.a` alternates 1 and 0.2 on a 2 × 2 checker (4 × 4 texels).
pub const CUTOFF: f32 = 0.5;

/// The occluder quads: `(min corner, max corner)` in x and y, at height `z`.
pub const OCCLUDERS: [(Vec2, Vec2, f32); 2] = [
    // Under the point light (0.5625, −0.5, 1).
    (Vec2::new(-0.1, -0.9), Vec2::new(0.9, 0.1), 0.55),
    // Half-way along the spot light's axis.
    (Vec2::new(-0.4, -0.35), Vec2::new(0.4, 0.45), 1.1),
];

/// The caster variant the rig renders with: cut-out, so holes in the occluders are holes in
/// the shadow.
const CASTER_KEYWORDS: [&str; 1] = ["_RENDERING_CUTOUT"];

/// The occluders' `main_tex`: 4 × 4 texels, a 2 × 2 checker of alpha 1 and 0.2 (white), so
/// each quad has two holes.
pub fn occluder_texture() -> MapTexture {
    MapTexture {
        width: 4,
        height: 4,
        texels: (0..16)
            .map(|i| {
                let a = if (i % 4 / 2 + i / 8) % 2 == 0 {
                    255
                } else {
                    51
                };
                [255, 255, 255, a]
            })
            .collect(),
    }
}

/// Whether the occluder texture keeps the fragment at uv (the caster's `_RENDERING_CUTOUT`).
fn occluder_kept(uv: Vec2) -> bool {
    let x = ((uv.x * 2.0).floor() as i32).clamp(0, 1);
    let y = ((uv.y * 2.0).floor() as i32).clamp(0, 1);
    (x + y) % 2 == 0
}

/// Position (location 0) and uv (location 3) of the occluders' triangles.
fn occluder_mesh() -> VertexBuffer {
    let mut vertices: Vec<[f32; 5]> = Vec::new();
    for (lo, hi, z) in OCCLUDERS {
        let v = |u: f32, t: f32| [lo.x + (hi.x - lo.x) * u, lo.y + (hi.y - lo.y) * t, z, u, t];
        vertices.extend([
            v(0.0, 0.0),
            v(1.0, 0.0),
            v(1.0, 1.0),
            v(0.0, 0.0),
            v(1.0, 1.0),
            v(0.0, 1.0),
        ]);
    }
    VertexBuffer::from_f32(&[(0, 3), (3, 2)], &vertices)
}

/// The caster's bindings: the light's camera (view_proj, position with w = 1 / range), the
/// occluders' material (tint white, cutoff [`CUTOFF`]), sampler and texture, the identity
/// object.
fn caster_resources(view_proj: Mat4, position: Vec4) -> Vec<BoundResource> {
    let mut camera = Vec::new();
    push_mat4(&mut camera, view_proj);
    push_vec4(&mut camera, position);
    let mut material = Vec::new();
    for v in [
        Vec4::ONE,
        Vec4::ZERO,
        Vec4::new(0.0, 0.5, CUTOFF, 1.0),
        Vec4::new(1.0, 1.0, 0.0, 0.0),
        Vec4::new(1.0, 1.0, 0.0, 0.0),
    ] {
        push_vec4(&mut material, v);
    }
    let mut object = Vec::new();
    push_mat4(&mut object, Mat4::IDENTITY);
    push_mat4(&mut object, Mat4::IDENTITY);
    vec![
        BoundResource::new(0, 0, Resource::Uniform(camera)),
        BoundResource::new(1, 0, Resource::Uniform(material)),
        BoundResource::new(1, 1, Resource::Sampler { nearest: true }),
        BoundResource::new(1, 2, occluder_texture().resource()),
        BoundResource::new(2, 0, Resource::Uniform(object)),
    ]
}

/// The depth format of the shadow maps: renderable, and copyable both ways.
pub(crate) const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth16Unorm;
/// The colour format of the cube's faces.
pub(crate) const CUBE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

/// What one caster draw leaves: the depth buffer (16-bit) and, for `SHADOWS_CUBE`, the
/// colour target's bytes.
pub struct CasterImage {
    /// Depth per texel, row-major.
    pub depth: Vec<u16>,
    /// The `Rgba16Float` target's bytes (`SHADOWS_CUBE`).
    pub color: Option<Vec<u8>>,
}

/// Renders the occluders with `standard/ShadowCaster` `{keywords}` into a `size × size` depth
/// buffer (cleared to 1, test `Less`) and, for `SHADOWS_CUBE`, a colour target cleared to 1.
pub fn render_caster(
    ctx: &GpuContext,
    lib: &Library,
    keywords: &[&str],
    view_proj: Mat4,
    position: Vec4,
    size: u32,
) -> Result<CasterImage, GpuError> {
    let variant = lib
        .variant("standard", "ShadowCaster", keywords)
        .map_err(|e| CheckError::lookup(format!("standard/ShadowCaster {keywords:?}"), e))?;
    render_depth(
        ctx,
        (&variant.label(), &lib.wgsl(&variant)),
        &occluder_mesh(),
        &caster_resources(view_proj, position),
        size,
        keywords.contains(&"SHADOWS_CUBE"),
    )
}

/// Lays `tile × tile` maps (each row by row, in tile order) into an atlas of `cols × rows`
/// tiles, row-major (the layout of [`atlas_tile`]); tiles without a map stay clear (the far
/// plane). Returns the atlas's texels and size. Stops at the first map that failed.
pub(crate) fn lay_tiles(
    (cols, rows): (u32, u32),
    tile: u32,
    maps: impl IntoIterator<Item = Result<Vec<u16>, GpuError>>,
) -> Result<(Vec<u16>, (u32, u32)), GpuError> {
    let (w, h) = (cols * tile, rows * tile);
    let mut atlas = vec![u16::MAX; (w * h) as usize];
    for (i, texels) in maps.into_iter().enumerate() {
        let texels = texels?;
        let (x0, y0) = ((i as u32 % cols) * tile, (i as u32 / cols) * tile);
        for (row, texels) in texels.chunks(tile as usize).enumerate() {
            let at = ((y0 + row as u32) * w + x0) as usize;
            atlas[at..at + tile as usize].copy_from_slice(texels);
        }
    }
    Ok((atlas, (w, h)))
}

/// Draws `mesh` with a caster program (`vs_main`, `fs_main`) into a `size × size`
/// `Depth16Unorm` buffer (cleared to 1, test `Less`) and, with `cube`, an `Rgba16Float`
/// colour target cleared to 1; both read back.
pub(crate) fn render_depth(
    ctx: &GpuContext,
    (label, wgsl): (&str, &str),
    mesh: &VertexBuffer,
    resources: &[BoundResource],
    size: u32,
    cube: bool,
) -> Result<CasterImage, GpuError> {
    let label = label.to_owned();
    let layout = [Some(wgpu::VertexBufferLayout {
        array_stride: mesh.stride,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &mesh.attributes,
    })];
    let targets = [Some(wgpu::ColorTargetState {
        format: CUBE_FORMAT,
        blend: None,
        write_mask: wgpu::ColorWrites::ALL,
    })];
    let (pipe, groups) = pipeline(
        ctx,
        &label,
        wgsl,
        ("vs_main", Some("fs_main")),
        &layout,
        None,
        wgpu::DepthStencilState {
            format: DEPTH,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        },
        if cube { &targets } else { &[] },
        resources,
    )?;
    let (depth_tex, color_tex) = ctx.scoped(&label, || {
        let texture = |format| {
            ctx.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(&label),
                size: wgpu::Extent3d {
                    width: size,
                    height: size,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                view_formats: &[],
            })
        };
        let depth_tex = texture(DEPTH);
        let color_tex = cube.then(|| texture(CUBE_FORMAT));
        let vertices = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&label),
            size: mesh.data.len() as u64,
            usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        ctx.queue.write_buffer(&vertices, 0, &mesh.data);
        let depth_view = depth_tex.create_view(&wgpu::TextureViewDescriptor::default());
        let color_view = color_tex
            .as_ref()
            .map(|t| t.create_view(&wgpu::TextureViewDescriptor::default()));
        let color_attachments: Vec<Option<wgpu::RenderPassColorAttachment<'_>>> = color_view
            .iter()
            .map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let mut encoder = ctx
            .device
            .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                label: Some(&label),
            });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(&label),
                color_attachments: &color_attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipe);
            for (group, bind_group) in &groups {
                pass.set_bind_group(*group, bind_group, &[]);
            }
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..(mesh.data.len() / mesh.stride as usize) as u32, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
        (depth_tex, color_tex)
    })?;
    let depth = read_texture(ctx, &label, &depth_tex)?
        .chunks_exact(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect();
    let color = match color_tex {
        Some(t) => Some(read_texture(ctx, &label, &t)?),
        None => None,
    };
    Ok(CasterImage { depth, color })
}

/// The r channel of `Rgba16Float` bytes, one value per texel.
pub(crate) fn red_f16(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(8)
        .map(|t| f16_bits_to_f32(u16::from_le_bytes([t[0], t[1]])))
        .collect()
}

/// What the reference refusing a shadow means to the check: an error naming `variant`.
pub(crate) fn refused(variant: &str) -> impl Fn(ShadowError) -> GpuError + '_ {
    move |e| {
        GpuError::from(CheckError::UnknownToReference {
            variant: variant.to_owned(),
            message: e.to_string(),
        })
    }
}

/// The shadows of the check's spot light ([`SPOT_STRENGTH`], [`SPOT_BIAS`]) and point light
/// ([`POINT_STRENGTH`]), as the maps are rendered with.
pub(crate) fn rig_params(
    spot_light: &Light,
    point_light: &Light,
) -> Result<(ShadowParams, ShadowParams), GpuError> {
    let refused = refused("standard/ShadowCaster");
    Ok((
        ShadowParams::for_light(spot_light, SPOT_STRENGTH, SPOT_BIAS).map_err(&refused)?,
        ShadowParams::for_light(point_light, POINT_STRENGTH, 0.0).map_err(&refused)?,
    ))
}

/// The shadow maps of the check's spot and point lights, as rendered by the GPU and read back.
#[derive(Clone, Debug)]
pub struct ShadowRig {
    /// The spot light's shadow (`SHADOWS_DEPTH`).
    pub spot: ShadowParams,
    /// The point light's shadow (`SHADOWS_CUBE`).
    pub point: ShadowParams,
    /// The spot's map.
    pub map: ShadowMap2d,
    /// The spot's map as rendered (`Depth16Unorm`).
    pub map_texels: Vec<u16>,
    /// The point's cube.
    pub cube: ShadowCube,
    /// The cube's faces as rendered (`Rgba16Float` bytes, wgpu layer order).
    pub cube_faces: [Vec<u8>; 6],
}

impl ShadowRig {
    /// Renders the maps of `spot_light` and `point_light` with the cut-out caster.
    ///
    /// # Errors
    /// A GPU failure, or a map the reference refuses ([`CheckError::UnknownToReference`]).
    pub fn render(
        ctx: &GpuContext,
        lib: &Library,
        spot_light: &Light,
        point_light: &Light,
    ) -> Result<ShadowRig, GpuError> {
        let refused = refused("standard/ShadowCaster");
        let (spot, point) = rig_params(spot_light, point_light)?;
        let mut kw: Vec<&str> = CASTER_KEYWORDS.to_vec();
        kw.push("SHADOWS_DEPTH");
        let image = render_caster(
            ctx,
            lib,
            &kw,
            spot.world_to_shadow,
            spot.light_position.extend(spot.inv_range),
            MAP_SIZE,
        )?;
        let map = ShadowMap2d::from_depth16(MAP_SIZE, MAP_SIZE, &image.depth).map_err(&refused)?;
        kw.pop();
        kw.push("SHADOWS_CUBE");
        let range = 1.0 / point.inv_range;
        let mut faces: [Vec<u8>; 6] = Default::default();
        for (face, bytes) in faces.iter_mut().enumerate() {
            let image = render_caster(
                ctx,
                lib,
                &kw,
                cube_face_view_proj(point.light_position, face, range),
                point.light_position.extend(point.inv_range),
                CUBE_SIZE,
            )?;
            *bytes = image.color.unwrap_or_default();
        }
        let cube = ShadowCube::new(CUBE_SIZE, faces.iter().flat_map(|f| red_f16(f)).collect())
            .map_err(&refused)?;
        Ok(ShadowRig {
            spot,
            point,
            map,
            map_texels: image.depth,
            cube,
            cube_faces: faces,
        })
    }

    /// The shadow of the light `t` (spot or point; directional lights have none).
    pub fn params(&self, t: LightType) -> Option<&ShadowParams> {
        match t {
            LightType::Spot => Some(&self.spot),
            LightType::Point | LightType::PointCookie => Some(&self.point),
            _ => None,
        }
    }

    /// The shadow bindings (group 0, 10–14 of `wgsl/lighting/light_bindings.wgsl`) with the
    /// `Shadow` uniform of `params`.
    pub fn resources(&self, params: &ShadowParams) -> Vec<BoundResource> {
        shadow_bindings(
            params,
            Some((&self.map_texels, MAP_SIZE)),
            Some((&self.cube_faces, CUBE_SIZE)),
        )
    }

    /// The reference shadow factor interval at `p` for light `t` under `keywords`.
    pub fn factor(&self, t: LightType, keywords: ShadowKeywords, p: Vec3) -> (f32, f32) {
        match self.params(t) {
            Some(params) if keywords.any() => shadow_factor(
                params,
                keywords,
                ShadowMaps {
                    map: Some(&self.map),
                    cube: Some(&self.cube),
                },
                p,
            ),
            _ => (1.0, 1.0),
        }
    }
}

/// The receivers' shadow bindings (group 0, 10–14 of `wgsl/lighting/light_bindings.wgsl`): the
/// `Shadow` uniform of `params`, the 2D map (`Depth16Unorm` codes, `size × size`) with its
/// LessEqual comparison sampler, and the cube of distances (six `Rgba16Float` faces of
/// `size × size`, wgpu's layer order) with a nearest sampler — each map only where given.
pub(crate) fn shadow_bindings(
    params: &ShadowParams,
    map: Option<(&[u16], u32)>,
    cube: Option<(&[Vec<u8>; 6], u32)>,
) -> Vec<BoundResource> {
    let uniform: Vec<u8> = params
        .uniform()
        .into_iter()
        .flat_map(f32::to_le_bytes)
        .collect();
    let mut out = vec![BoundResource::new(0, 10, Resource::Uniform(uniform))];
    if let Some((texels, size)) = map {
        out.push(BoundResource::new(
            0,
            11,
            Resource::Texture2d {
                format: DEPTH,
                width: size,
                height: size,
                data: texels.iter().flat_map(|d| d.to_le_bytes()).collect(),
            },
        ));
        out.push(BoundResource::new(
            0,
            12,
            Resource::ComparisonSampler {
                compare: wgpu::CompareFunction::LessEqual,
                nearest: true,
            },
        ));
    }
    if let Some((faces, size)) = cube {
        out.push(BoundResource::new(
            0,
            13,
            Resource::TextureCube {
                format: CUBE_FORMAT,
                size,
                levels: vec![faces.clone()],
            },
        ));
        out.push(BoundResource::new(
            0,
            14,
            Resource::Sampler { nearest: true },
        ));
    }
    out
}

/// Whether the segment from `p` to `light` crosses an occluder where its texture keeps the
/// fragment (the geometry's answer to "is `p` in shadow").
pub fn analytic_occlusion(p: Vec3, light: Vec3) -> bool {
    OCCLUDERS.iter().any(|&(lo, hi, z)| {
        let t = (z - p.z) / (light.z - p.z);
        if !(t > 0.0 && t < 1.0) {
            return false;
        }
        let q = p + (light - p) * t;
        let uv = (Vec2::new(q.x, q.y) - lo) / (hi - lo);
        (0.0..=1.0).contains(&uv.x) && (0.0..=1.0).contains(&uv.y) && occluder_kept(uv)
    })
}

/// The GPU value where the reference allows an interval `[a, b]` (per channel, either order):
/// `got` clamped into it, so a texel is compared exactly where the interval is a point and
/// within the interval's bounds where an uncertain shadow tap could go either way.
pub fn within(got: [f32; 4], a: Vec4, b: Vec4) -> Vec4 {
    Vec4::from_array(got).clamp(a.min(b), a.max(b))
}
