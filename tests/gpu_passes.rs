use std::time::Instant;
use wgsl_variants::gpu::*;
use wgsl_variants::{Library, variants::Space};

#[test]
fn timing() {
    let ctx = GpuContext::new(None).unwrap();
    eprintln!("adapter {}", ctx.adapter_name());
    let lib = Library::bundled().unwrap();
    let pass = lib.pass("standard", "Deferred").unwrap();
    let all = Space::full(pass).enumerate(10000).unwrap();
    let t0 = Instant::now();
    let mut texts = std::collections::HashSet::new();
    for c in &all {
        let v = wgsl_variants::Variant {
            pass,
            choice: c.clone(),
        };
        texts.insert(lib.wgsl(&v));
    }
    eprintln!(
        "compose {} distinct {} in {:?}",
        all.len(),
        texts.len(),
        t0.elapsed()
    );
    let t0 = Instant::now();
    for (i, text) in texts.iter().take(20).enumerate() {
        let p = compile_scoped(&ctx, "x", || {
            let m = wgsl_module(&ctx, "x", text);
            let vl = [Some(wgpu::VertexBufferLayout {
                array_stride: 48,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x4, 3 => Float32x2],
            })];
            let targets = [
                Some(wgpu::ColorTargetState {
                    format: wgpu::TextureFormat::Rgba8Unorm,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                }),
                Some(wgpu::ColorTargetState {
                    format: wgpu::TextureFormat::Rgba8Unorm,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                }),
                Some(wgpu::ColorTargetState {
                    format: wgpu::TextureFormat::Rgb10a2Unorm,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                }),
                Some(wgpu::ColorTargetState {
                    format: wgpu::TextureFormat::Rgb10a2Unorm,
                    blend: None,
                    write_mask: wgpu::ColorWrites::ALL,
                }),
            ];
            ctx.device
                .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                    label: None,
                    layout: None,
                    vertex: wgpu::VertexState {
                        module: &m,
                        entry_point: Some("vs_main"),
                        compilation_options: Default::default(),
                        buffers: &vl,
                    },
                    primitive: Default::default(),
                    depth_stencil: None,
                    multisample: Default::default(),
                    fragment: Some(wgpu::FragmentState {
                        module: &m,
                        entry_point: Some("fs_main"),
                        compilation_options: Default::default(),
                        targets: &targets,
                    }),
                    multiview_mask: None,
                    cache: None,
                })
        });
        if let Err(e) = p {
            eprintln!("{e}");
        }
        if i == 0 {
            eprintln!("first {:?}", t0.elapsed());
        }
    }
    eprintln!("20 pipelines {:?}", t0.elapsed());
}
