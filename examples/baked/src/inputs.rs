//! What a draw binds, made the way a renderer makes it: uniform buffers from the generated
//! structs' bytes, textures and samplers for the bindings the interface lists, and vertices
//! packed as the generated vertex layout says. The textures are small procedural stand-ins
//! (a renderer binds its assets there), chosen by the binding's name.

use glam::{Vec2, Vec3, Vec4};

use crate::Pass;
use crate::draw::{Bound, Gpu};

/// A uniform buffer at `@group(group) @binding(binding)` holding a generated struct's bytes.
pub struct Uniform {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The buffer.
    pub buffer: wgpu::Buffer,
}

impl Uniform {
    /// A buffer holding `value` (a generated struct: `bytemuck::Pod`, laid out as WGSL's).
    pub fn new<T: bytemuck::Pod>(gpu: &Gpu, group: u32, binding: u32, value: &T) -> Uniform {
        let buffer = wgpu::util::DeviceExt::create_buffer_init(
            &gpu.device,
            &wgpu::util::BufferInitDescriptor {
                label: Some("uniform"),
                contents: bytemuck::bytes_of(value),
                usage: wgpu::BufferUsages::UNIFORM,
            },
        );
        Uniform {
            group,
            binding,
            buffer,
        }
    }

    /// The buffer as a draw's resource.
    pub fn bound(&self) -> Bound<'_> {
        Bound {
            group: self.group,
            binding: self.binding,
            resource: self.buffer.as_entire_binding(),
        }
    }
}

/// A texture or sampler for every texture and sampler binding of a [`Pass`].
pub struct Textures {
    views: Vec<(u32, u32, wgpu::TextureView)>,
    samplers: Vec<(u32, u32, wgpu::Sampler)>,
}

/// Texels per side of the stand-in textures.
const SIZE: u32 = 64;

impl Textures {
    /// Stand-ins for `pass`'s textures (2D or cube, by the layout) and samplers (linear,
    /// repeating), the content by the binding's name: a checkerboard for albedo, bumps for a
    /// normal map, stripes for metallic and smoothness, a sky for probes, mid-grey otherwise.
    pub fn for_pass(gpu: &Gpu, pass: &Pass) -> Textures {
        let mut views = Vec::new();
        let mut samplers = Vec::new();
        for (group, entries) in (0u32..).zip(&pass.groups) {
            for e in entries {
                let name = pass
                    .names
                    .iter()
                    .find(|n| (n.0, n.1) == (group, e.binding))
                    .map_or("", |n| n.2);
                match e.ty {
                    wgpu::BindingType::Texture {
                        view_dimension,
                        sample_type,
                        ..
                    } => {
                        let view = texture(gpu, name, view_dimension, sample_type);
                        views.push((group, e.binding, view));
                    }
                    wgpu::BindingType::Sampler(kind) => {
                        let compare = (kind == wgpu::SamplerBindingType::Comparison)
                            .then_some(wgpu::CompareFunction::LessEqual);
                        let linear = kind == wgpu::SamplerBindingType::Filtering;
                        let filter = if linear {
                            wgpu::FilterMode::Linear
                        } else {
                            wgpu::FilterMode::Nearest
                        };
                        let sampler = gpu.device.create_sampler(&wgpu::SamplerDescriptor {
                            label: Some(name),
                            address_mode_u: wgpu::AddressMode::Repeat,
                            address_mode_v: wgpu::AddressMode::Repeat,
                            mag_filter: filter,
                            min_filter: filter,
                            compare,
                            ..Default::default()
                        });
                        samplers.push((group, e.binding, sampler));
                    }
                    _ => {}
                }
            }
        }
        Textures { views, samplers }
    }

    /// Every texture and sampler as a draw's resource.
    pub fn bound(&self) -> Vec<Bound<'_>> {
        let views = self.views.iter().map(|(group, binding, view)| Bound {
            group: *group,
            binding: *binding,
            resource: wgpu::BindingResource::TextureView(view),
        });
        let samplers = self.samplers.iter().map(|(group, binding, sampler)| Bound {
            group: *group,
            binding: *binding,
            resource: wgpu::BindingResource::Sampler(sampler),
        });
        views.chain(samplers).collect()
    }
}

/// The stand-in for the texture `name`: RGBA8 (a float binding), RGBA32 integers (an integer
/// binding) or depth, with six layers for a cube.
fn texture(
    gpu: &Gpu,
    name: &str,
    dimension: wgpu::TextureViewDimension,
    sample_type: wgpu::TextureSampleType,
) -> wgpu::TextureView {
    let layers = match dimension {
        wgpu::TextureViewDimension::Cube => 6,
        _ => 1,
    };
    let (format, texel): (wgpu::TextureFormat, Box<dyn Fn(u32, Vec2) -> Vec4>) = match sample_type {
        wgpu::TextureSampleType::Float { .. } => (wgpu::TextureFormat::Rgba8Unorm, content(name)),
        wgpu::TextureSampleType::Uint => {
            (wgpu::TextureFormat::Rgba32Uint, Box::new(|_, _| Vec4::ONE))
        }
        wgpu::TextureSampleType::Sint => {
            (wgpu::TextureFormat::Rgba32Sint, Box::new(|_, _| Vec4::ONE))
        }
        wgpu::TextureSampleType::Depth => (
            wgpu::TextureFormat::Depth32Float,
            Box::new(|_, _| Vec4::ONE),
        ),
    };
    let mut data = Vec::new();
    for layer in 0..layers {
        for y in 0..SIZE {
            for x in 0..SIZE {
                let uv = (Vec2::new(x as f32, y as f32) + 0.5) / SIZE as f32;
                let v = texel(layer, uv);
                match format {
                    wgpu::TextureFormat::Rgba8Unorm => {
                        data.extend(
                            (v.clamp(Vec4::ZERO, Vec4::ONE) * 255.0)
                                .round()
                                .to_array()
                                .map(|c| c as u8),
                        );
                    }
                    wgpu::TextureFormat::Depth32Float => data.extend(v.x.to_le_bytes()),
                    _ => data.extend(
                        v.to_array()
                            .into_iter()
                            .flat_map(|c| (c as u32).to_le_bytes()),
                    ),
                }
            }
        }
    }
    let texture = wgpu::util::DeviceExt::create_texture_with_data(
        &gpu.device,
        &gpu.queue,
        &wgpu::TextureDescriptor {
            label: Some(name),
            size: wgpu::Extent3d {
                width: SIZE,
                height: SIZE,
                depth_or_array_layers: layers,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        &data,
    );
    texture.create_view(&wgpu::TextureViewDescriptor {
        dimension: Some(dimension),
        ..Default::default()
    })
}

/// The content of a float texture by its binding's name, per layer and UV.
fn content(name: &str) -> Box<dyn Fn(u32, Vec2) -> Vec4> {
    let has = |part: &str| name.contains(part);
    if has("normal") || has("bump") {
        // Tangent-space bumps, stored as n · 0.5 + 0.5.
        Box::new(|_, uv| {
            let s = (uv * std::f32::consts::TAU * 4.0).to_array().map(f32::sin);
            let n = Vec3::new(0.35 * s[0], 0.35 * s[1], 1.0).normalize();
            (n * 0.5 + 0.5).extend(1.0)
        })
    } else if has("probe") || has("environment") {
        // A sky: blue up (+Y, layer 2), warm below (−Y, layer 3), a horizon between.
        Box::new(|layer, uv| match layer {
            2 => Vec4::new(0.35, 0.55, 0.9, 1.0),
            3 => Vec4::new(0.3, 0.25, 0.2, 1.0),
            _ => Vec3::new(0.35, 0.55, 0.9)
                .lerp(Vec3::new(0.8, 0.75, 0.65), uv.y)
                .extend(1.0),
        })
    } else if has("metallic") {
        // Metallic stripes in R, smoothness in A.
        Box::new(|_, uv| {
            let metal = if ((uv.x * 8.0).floor() as u32).is_multiple_of(2) {
                1.0
            } else {
                0.0
            };
            Vec4::new(metal, 0.0, 0.0, 0.35 + 0.5 * uv.y)
        })
    } else if has("occlusion") {
        Box::new(|_, uv| Vec4::splat(0.6 + 0.4 * uv.y))
    } else if has("emission") {
        // Dark, with one glowing spot.
        Box::new(|_, uv| {
            let glow = (1.0 - uv.distance(Vec2::splat(0.7)) * 8.0).max(0.0);
            Vec4::new(glow, 0.6 * glow, 0.2 * glow, 1.0)
        })
    } else if has("main_tex") || has("base_map") || has("albedo") && !has("detail") {
        // An 8 × 8 checkerboard of two paints.
        Box::new(|_, uv| {
            let odd = ((uv.x * 8.0).floor() + (uv.y * 8.0).floor()) as u32 % 2 == 1;
            if odd {
                Vec4::new(0.75, 0.2, 0.15, 1.0)
            } else {
                Vec4::new(0.85, 0.8, 0.7, 1.0)
            }
        })
    } else if has("lightmap") {
        Box::new(|_, uv| Vec4::new(0.6 + 0.3 * uv.x, 0.55, 0.45, 1.0))
    } else {
        // Detail maps (Unity's detail albedo is ×2: grey is neutral), masks and the rest.
        Box::new(|_, _| Vec4::splat(0.5))
    }
}

/// One vertex, by the names the bundled library gives its vertex inputs.
#[derive(Clone, Copy, Debug)]
pub struct Vertex {
    /// `position`.
    pub position: Vec3,
    /// `normal`.
    pub normal: Vec3,
    /// `tangent`: xyz, and the bitangent's sign in w.
    pub tangent: Vec4,
    /// `uv`.
    pub uv: Vec2,
    /// `lightmap_uv` (URP's second UV set).
    pub lightmap_uv: Vec2,
}

/// A square of side 2 in the XY plane facing +Z, as two triangles.
pub fn quad() -> Vec<Vertex> {
    let corner = |x: f32, y: f32| Vertex {
        position: Vec3::new(x, y, 0.0),
        normal: Vec3::Z,
        tangent: Vec4::new(1.0, 0.0, 0.0, 1.0),
        uv: Vec2::new(x * 0.5 + 0.5, 0.5 - y * 0.5),
        lightmap_uv: Vec2::new(x * 0.5 + 0.5, y * 0.5 + 0.5),
    };
    [
        (-1., -1.),
        (1., -1.),
        (1., 1.),
        (-1., -1.),
        (1., 1.),
        (-1., 1.),
    ]
    .map(|(x, y)| corner(x, y))
    .to_vec()
}

/// `vertices` packed as `pass`'s vertex layout says: each input by its name, as many
/// components as its format has (`f32`s).
pub fn pack(pass: &Pass, vertices: &[Vertex]) -> Result<Vec<u8>, String> {
    let mut data = vec![0u8; vertices.len() * pass.stride as usize];
    for (v, out) in vertices.iter().zip(data.chunks_mut(pass.stride as usize)) {
        for (name, attribute) in &pass.vertex {
            let value: &[f32] = match *name {
                "position" => &v.position.to_array(),
                "normal" => &v.normal.to_array(),
                "tangent" => &v.tangent.to_array(),
                "uv" => &v.uv.to_array(),
                "lightmap_uv" => &v.lightmap_uv.to_array(),
                other => return Err(format!("no vertex data for the input `{other}`")),
            };
            use wgpu::VertexFormat as F;
            let components = match attribute.format {
                F::Float32 => 1,
                F::Float32x2 => 2,
                F::Float32x3 => 3,
                F::Float32x4 => 4,
                other => return Err(format!("`{name}` is {other:?}: only f32 inputs are packed")),
            };
            let at = attribute.offset as usize;
            let bytes: Vec<u8> = value
                .iter()
                .chain(std::iter::repeat(&1.0))
                .take(components)
                .flat_map(|c| c.to_le_bytes())
                .collect();
            out[at..at + bytes.len()].copy_from_slice(&bytes);
        }
    }
    Ok(data)
}
