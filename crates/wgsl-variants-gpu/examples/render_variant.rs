//! Loads one variant of the bundled standard shader through the Rust API, builds its bind group
//! layouts from the variant's reflection (no hand-written layout), renders the GPU check's test
//! scene headless with wgpu and writes a PNG.
//!
//! ```sh
//! cargo run --release -p wgsl-variants-gpu --example render_variant -- out.png                # default keywords
//! cargo run --release -p wgsl-variants-gpu --example render_variant -- out.png _NORMAL_MAP    # exactly these
//! ```
//!
//! Any adapter works, including Mesa's lavapipe (`apt-get install mesa-vulkan-drivers`).

use std::error::Error;

use wgsl_variants_gpu::check::TestScene;
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;
use wgsl_variants_gpu::{
    GpuContext, GpuResources, compile_scoped, create_bind_group_layouts, create_pipeline_layout,
    read_texture,
};

/// Output size: the test scene's quad fills the view at any resolution.
const SIZE: u32 = 256;

fn main() -> Result<(), Box<dyn Error>> {
    let mut args = std::env::args().skip(1);
    let out = args.next().unwrap_or_else(|| "render_variant.png".into());
    let mut keywords: Vec<String> = args.collect();
    if keywords.is_empty() {
        keywords = [
            "_NORMAL_MAP",
            "_METALLIC_MAP",
            "_OCCLUSION_MAP",
            "_EMISSION_MAP",
        ]
        .map(String::from)
        .to_vec();
    }

    // 1. The variant, strictly looked up, and its reflection.
    let lib = wgsl_variants_shaders::library()?;
    let variant = lib.variant("standard", "ForwardBase", &keywords)?;
    let label = variant.label();
    let wgsl = lib.wgsl(&variant);
    let reflection = lib.reflect(&variant)?;
    print!("{}", reflection.to_text());

    // 2. The device, and the test scene's resources (every binding of the standard shader;
    //    the variant binds the ones its reflection lists).
    let ctx = GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref())?;
    println!("adapter: {}", ctx.adapter_name());
    let scene = TestScene::new(DEFAULT_SEED);
    let resources = GpuResources::upload(&ctx, &label, &scene.standard_resources())?;
    let quad = scene.quad();

    // 3. Layouts from reflection, bind groups, pipeline: all explicit.
    let format = wgpu::TextureFormat::Rgba8Unorm;
    let (layouts, bind_groups, pipeline) = compile_scoped(&ctx, &label, || {
        let layouts = create_bind_group_layouts(&ctx.device, &reflection, &label)?;
        let mut bind_groups = Vec::new();
        for (group, bindings) in reflection.groups().iter().enumerate() {
            let entries = bindings
                .iter()
                .map(|b| {
                    let resource = resources
                        .binding_resource((b.group, b.binding))
                        .ok_or_else(|| format!("the scene has nothing for {}", b.name))?;
                    Ok(wgpu::BindGroupEntry {
                        binding: b.binding,
                        resource,
                    })
                })
                .collect::<Result<Vec<_>, String>>()?;
            bind_groups.push(ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&label),
                layout: &layouts[group],
                entries: &entries,
            }));
        }
        let pipeline_layout = create_pipeline_layout(&ctx.device, &layouts, &label);
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&label),
                source: wgpu::ShaderSource::Wgsl(wgsl.as_str().into()),
            });
        let vertex_layout = [Some(wgpu::VertexBufferLayout {
            array_stride: quad.stride,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &quad.attributes,
        })];
        let pipeline = ctx
            .device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&label),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs_main"),
                    compilation_options: Default::default(),
                    buffers: &vertex_layout,
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs_main"),
                    compilation_options: Default::default(),
                    targets: &[Some(format.into())],
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            });
        Ok::<_, Box<dyn Error>>((layouts, bind_groups, pipeline))
    })??;
    let _ = layouts;

    // 4. Draw the quad into an offscreen target and read it back.
    let target = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some(&label),
        size: wgpu::Extent3d {
            width: SIZE,
            height: SIZE,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let vertices = wgpu::util::DeviceExt::create_buffer_init(
        &ctx.device,
        &wgpu::util::BufferInitDescriptor {
            label: Some(&label),
            contents: &quad.data,
            usage: wgpu::BufferUsages::VERTEX,
        },
    );
    let vertex_count = (quad.data.len() as u64 / quad.stride) as u32;
    ctx.scoped(&label, || {
        let view = target.create_view(&Default::default());
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some(&label),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: None,
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_pipeline(&pipeline);
            for (group, bind_group) in bind_groups.iter().enumerate() {
                pass.set_bind_group(group as u32, bind_group, &[]);
            }
            pass.set_vertex_buffer(0, vertices.slice(..));
            pass.draw(0..vertex_count, 0..1);
        }
        ctx.queue.submit([encoder.finish()]);
    })?;
    let pixels = read_texture(&ctx, &label, &target)?;

    // 5. A picture, and a sanity check that the draw covered the target.
    let covered = pixels
        .chunks_exact(4)
        .filter(|p| p[..3] != [0, 0, 0])
        .count();
    image::save_buffer(&out, &pixels, SIZE, SIZE, image::ExtendedColorType::Rgba8)?;
    println!(
        "rendered {label} at {SIZE}x{SIZE}: {covered} of {} pixels lit; wrote {out}",
        SIZE * SIZE
    );
    if covered < (SIZE * SIZE / 2) as usize {
        return Err(format!("only {covered} pixels were drawn").into());
    }
    Ok(())
}
