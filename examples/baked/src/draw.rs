//! One headless draw with wgpu: a device, and a pipeline built from a baked variant's text and
//! the generated interface, drawn into fresh colour targets that are read back. What a renderer
//! has already; here so the example runs anywhere (Mesa's lavapipe included).

use std::fmt;

/// A wgpu device and its queue.
pub struct Gpu {
    /// The device.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// The adapter's name (`llvmpipe (…)` for lavapipe).
    pub adapter: String,
}

/// Why a draw failed.
#[derive(Debug)]
pub enum DrawError {
    /// No adapter (install a Vulkan driver, or Mesa's lavapipe: `mesa-vulkan-drivers`).
    NoAdapter,
    /// The adapter refused the device.
    Device(wgpu::RequestDeviceError),
    /// wgpu refused an object (its validation error, naga's diagnostics included).
    Wgpu(String),
    /// The variant needs a resource the caller did not give.
    Missing {
        /// `@group`.
        group: u32,
        /// `@binding`.
        binding: u32,
        /// The variable's name.
        name: &'static str,
    },
    /// A target could not be read back.
    Readback(String),
}

impl fmt::Display for DrawError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DrawError::NoAdapter => write!(
                f,
                "no wgpu adapter: install a Vulkan driver (Mesa's lavapipe: apt-get install \
                 mesa-vulkan-drivers)"
            ),
            DrawError::Device(e) => write!(f, "the adapter refused the device: {e}"),
            DrawError::Wgpu(e) => write!(f, "wgpu: {e}"),
            DrawError::Missing {
                group,
                binding,
                name,
            } => write!(
                f,
                "nothing given for @group({group}) @binding({binding}) `{name}`"
            ),
            DrawError::Readback(e) => write!(f, "read-back: {e}"),
        }
    }
}

impl std::error::Error for DrawError {}

impl Gpu {
    /// The first adapter of the primary back ends (Vulkan, Metal, DX12), with the limits of
    /// the adapter for colour attachment bytes: URP's G-buffer with its optional targets needs
    /// up to 48 bytes per sample (WebGPU's default is 32).
    pub fn new() -> Result<Gpu, DrawError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::from_env().unwrap_or(wgpu::Backends::PRIMARY);
        let instance = wgpu::Instance::new(desc);
        let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
            .map_err(|_| DrawError::NoAdapter)?;
        let mut limits = wgpu::Limits::default().or_worse_values_from(&adapter.limits());
        limits.max_color_attachment_bytes_per_sample = limits
            .max_color_attachment_bytes_per_sample
            .max(adapter.limits().max_color_attachment_bytes_per_sample);
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("wgsl-variants-baked-example"),
            // URP's GBuffer3 is `Rg11b10Ufloat`, renderable only with this feature.
            required_features: adapter.features() & wgpu::Features::RG11B10UFLOAT_RENDERABLE,
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(DrawError::Device)?;
        Ok(Gpu {
            device,
            queue,
            adapter: adapter.get_info().name,
        })
    }

    /// Runs `f` in a validation error scope: the first error wgpu reports becomes
    /// [`DrawError::Wgpu`].
    fn scoped<T>(&self, f: impl FnOnce() -> T) -> Result<T, DrawError> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        match pollster::block_on(scope.pop()) {
            None => Ok(value),
            Some(e) => Err(DrawError::Wgpu(chain(&e))),
        }
    }
}

/// An error with its sources (naga's diagnostics are there).
fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(s) = source {
        // wgpu's messages often hold their sources already.
        let line = s.to_string();
        if !text.contains(&line) {
            text.push_str(&format!("\n  caused by: {line}"));
        }
        source = s.source();
    }
    text
}

/// A resource for one `@group/@binding`.
pub struct Bound<'a> {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// What is bound.
    pub resource: wgpu::BindingResource<'a>,
}

/// Everything one draw takes: the pipeline's parts (from the generated interface), the
/// resources and the vertices.
pub struct Draw<'a> {
    /// Labels every wgpu object.
    pub label: &'a str,
    /// The variant's WGSL, with `vs_main` and `fs_main`.
    pub wgsl: &'a str,
    /// The layout entries of each bind group, `@group(0)` first.
    pub groups: Vec<Vec<wgpu::BindGroupLayoutEntry>>,
    /// The names of the bindings, by `(group, binding)`, for [`DrawError::Missing`].
    pub names: Vec<(u32, u32, &'static str)>,
    /// A resource for every binding of `groups`.
    pub resources: Vec<Bound<'a>>,
    /// The one vertex buffer's layout.
    pub vertex_layout: wgpu::VertexBufferLayout<'a>,
    /// The vertices, packed as `vertex_layout` says: a triangle list.
    pub vertices: &'a [u8],
    /// The colour targets in `@location` order.
    pub targets: Vec<Option<wgpu::ColorTargetState>>,
    /// Target width in pixels.
    pub width: u32,
    /// Target height in pixels.
    pub height: u32,
}

/// Draws `draw` into targets cleared to black and reads every target back: tightly packed
/// rows each, in `@location` order.
pub fn draw(gpu: &Gpu, draw: &Draw<'_>) -> Result<Vec<Vec<u8>>, DrawError> {
    let device = &gpu.device;
    let label = Some(draw.label);
    let (bind_groups, pipeline) = gpu.scoped(|| {
        let mut layouts = Vec::new();
        let mut bind_groups = Vec::new();
        for (group, entries) in (0u32..).zip(&draw.groups) {
            let layout = device
                .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label, entries });
            let entries = entries
                .iter()
                .map(|e| {
                    let bound = draw
                        .resources
                        .iter()
                        .find(|r| (r.group, r.binding) == (group, e.binding));
                    let name = || {
                        let (.., name) = draw
                            .names
                            .iter()
                            .find(|n| (n.0, n.1) == (group, e.binding))
                            .copied()
                            .unwrap_or((group, e.binding, "?"));
                        name
                    };
                    let bound = bound.ok_or_else(|| DrawError::Missing {
                        group,
                        binding: e.binding,
                        name: name(),
                    })?;
                    Ok(wgpu::BindGroupEntry {
                        binding: e.binding,
                        resource: bound.resource.clone(),
                    })
                })
                .collect::<Result<Vec<_>, DrawError>>()?;
            bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label,
                layout: &layout,
                entries: &entries,
            }));
            layouts.push(layout);
        }
        let layouts: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label,
            bind_group_layouts: &layouts,
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label,
            source: wgpu::ShaderSource::Wgsl(draw.wgsl.into()),
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label,
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vs_main"),
                compilation_options: Default::default(),
                buffers: &[Some(draw.vertex_layout.clone())],
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("fs_main"),
                compilation_options: Default::default(),
                targets: &draw.targets,
            }),
            primitive: Default::default(),
            depth_stencil: None,
            multisample: Default::default(),
            multiview_mask: None,
            cache: None,
        });
        Ok::<_, DrawError>((bind_groups, pipeline))
    })??;

    let size = wgpu::Extent3d {
        width: draw.width,
        height: draw.height,
        depth_or_array_layers: 1,
    };
    let textures: Vec<Option<wgpu::Texture>> = draw
        .targets
        .iter()
        .map(|t| {
            t.as_ref().map(|t| {
                device.create_texture(&wgpu::TextureDescriptor {
                    label,
                    size,
                    mip_level_count: 1,
                    sample_count: 1,
                    dimension: wgpu::TextureDimension::D2,
                    format: t.format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
                    view_formats: &[],
                })
            })
        })
        .collect();
    let vertices = wgpu::util::DeviceExt::create_buffer_init(
        device,
        &wgpu::util::BufferInitDescriptor {
            label,
            contents: draw.vertices,
            usage: wgpu::BufferUsages::VERTEX,
        },
    );
    let count = (draw.vertices.len() as u64 / draw.vertex_layout.array_stride) as u32;

    // Draw, then copy each target into a buffer with rows padded as copies require.
    let copies = gpu.scoped(|| {
        let views: Vec<Option<wgpu::TextureView>> = textures
            .iter()
            .map(|t| t.as_ref().map(|t| t.create_view(&Default::default())))
            .collect();
        let attachments: Vec<Option<wgpu::RenderPassColorAttachment>> = views
            .iter()
            .map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view: view.as_ref()?,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })
            })
            .collect();
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label,
                color_attachments: &attachments,
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            for (group, bind_group) in (0u32..).zip(&bind_groups) {
                pass.set_bind_group(group, bind_group, &[]);
            }
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..count, 0..1);
        }
        let mut copies = Vec::new();
        for texture in textures.iter().flatten() {
            let texel = u64::from(texture.format().block_copy_size(None).unwrap_or(4));
            let row = u64::from(draw.width) * texel;
            let padded = row.next_multiple_of(u64::from(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT));
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label,
                size: padded * u64::from(draw.height),
                usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                mapped_at_creation: false,
            });
            encoder.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &buffer,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: 0,
                        bytes_per_row: Some(padded as u32),
                        rows_per_image: None,
                    },
                },
                size,
            );
            copies.push((buffer, row as usize, padded as usize));
        }
        gpu.queue.submit([encoder.finish()]);
        copies
    })?;

    let mut out = Vec::new();
    for (buffer, row, padded) in copies {
        let slice = buffer.slice(..);
        let (sent, mapped) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |result| {
            // The receiver waits below; a failed send only means it gave up.
            let _ = sent.send(result);
        });
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| DrawError::Readback(e.to_string()))?;
        mapped
            .recv()
            .map_err(|e| DrawError::Readback(e.to_string()))?
            .map_err(|e| DrawError::Readback(e.to_string()))?;
        let data = slice
            .get_mapped_range()
            .map_err(|e| DrawError::Readback(e.to_string()))?;
        let mut texels = Vec::with_capacity(row * draw.height as usize);
        for r in data.chunks(padded) {
            texels.extend_from_slice(&r[..row]);
        }
        drop(data);
        buffer.unmap();
        out.push(texels);
    }
    Ok(out)
}
