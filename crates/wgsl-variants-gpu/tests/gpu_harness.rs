//! GPU harness tests. They need a wgpu adapter (Mesa lavapipe is enough:
//! `apt-get install mesa-vulkan-drivers`). Without one they print a loud SKIPPED line and
//! pass, unless `CI=true` or `WGSL_VARIANTS_REQUIRE_GPU=1`, in which case they fail.
//! `WGSL_VARIANTS_ADAPTER=<substring>` selects an adapter by name.

mod common;

use wgsl_variants_gpu::{
    BoundResource, ColorTarget, GpuContext, GpuError, GpuResources, RenderJob, Resource,
    TargetFormat, read_texture, render, run_compute,
};

/// Creates a context, or returns `None` (after a loud message) when no adapter exists and a
/// GPU is not required.
fn context() -> Option<GpuContext> {
    let ctx = common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "GPU context creation",
    )?;
    eprintln!("using adapter: {}", ctx.adapter_name());
    Some(ctx)
}

/// Held by the two tests that destroy a device or leave a long dispatch running: run at the
/// same time in one process, they hung NVIDIA's 580 driver (H200) for over two minutes, while
/// each alone takes a second there (and both together a second on lavapipe).
static DEVICE_ABUSE: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Full-screen triangle vertex shader shared by the render tests.
const FULLSCREEN_VS: &str = r#"
@vertex
fn vs(@builtin(vertex_index) i: u32) -> @builtin(position) vec4<f32> {
    let p = vec2<f32>(f32((i << 1u) & 2u), f32(i & 2u));
    return vec4<f32>(p * 2.0 - 1.0, 0.0, 1.0);
}
"#;

fn assert_all_pixels(
    format: TargetFormat,
    bytes: &[u8],
    pixels: usize,
    check: impl Fn([u32; 4]) -> bool,
) {
    assert_eq!(
        bytes.len(),
        pixels * format.bytes_per_pixel(),
        "{format:?} byte count"
    );
    for (i, px) in format.decode_image(bytes).into_iter().enumerate() {
        assert!(check(px), "{format:?} pixel {i} = {px:?}");
    }
}

#[test]
fn compute_doubles_floats() {
    let Some(ctx) = context() else { return };
    let wgsl = r#"
@group(0) @binding(0) var<storage, read> input: array<f32>;
@group(0) @binding(1) var<storage, read_write> output: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i < arrayLength(&input) {
        output[i] = input[i] * 2.0;
    }
}
"#;
    let input: Vec<f32> = (0..100).map(|i| i as f32 * 0.5 - 7.0).collect();
    let out = run_compute(
        &ctx,
        "double",
        wgsl,
        "main",
        bytemuck::cast_slice(&input),
        400,
        2,
    )
    .expect("compute");
    let out: Vec<f32> = bytemuck::pod_collect_to_vec(&out);
    let expected: Vec<f32> = input.iter().map(|v| v * 2.0).collect();
    assert_eq!(out, expected);
    assert!(ctx.take_error().is_none());
}

#[test]
fn render_four_targets_with_constant_outputs() {
    let Some(ctx) = context() else { return };
    let wgsl = format!(
        "{FULLSCREEN_VS}{}",
        r#"
struct Out {
    @location(0) a: vec4<f32>,
    @location(1) b: vec4<f32>,
    @location(2) c: vec4<f32>,
    @location(3) d: vec4<f32>,
}

@fragment
fn fs() -> Out {
    var o: Out;
    o.a = vec4<f32>(0.5, 0.25, 1.0, 0.0);
    o.b = vec4<f32>(0.25, 0.5, 1.0, 1.0);
    o.c = vec4<f32>(1.5, -2.0, 0.125, 65504.0);
    o.d = vec4<f32>(0.0, 1.0, 0.0, 1.0);
    return o;
}
"#
    );
    let mut job = RenderJob::new("mrt", &wgsl, "vs", "fs");
    job.width = 16;
    job.height = 8;
    job.targets = vec![
        ColorTarget::new(TargetFormat::Rgba8Unorm),
        ColorTarget::new(TargetFormat::Rgb10a2Unorm),
        ColorTarget::new(TargetFormat::Rgba16Float),
        ColorTarget::new(TargetFormat::Rgba8Unorm),
    ];
    let out = render(&ctx, &job).expect("render");
    assert_eq!(out.len(), 4);
    let n = 16 * 8;
    assert_all_pixels(TargetFormat::Rgba8Unorm, &out[0], n, |p| {
        matches!(p[0], 127 | 128) && matches!(p[1], 63 | 64) && p[2] == 255 && p[3] == 0
    });
    assert_all_pixels(TargetFormat::Rgb10a2Unorm, &out[1], n, |p| {
        matches!(p[0], 255 | 256) && matches!(p[1], 511 | 512) && p[2] == 1023 && p[3] == 3
    });
    for px in TargetFormat::Rgba16Float.decode_image_f32(&out[2]) {
        assert_eq!(px, [1.5, -2.0, 0.125, 65504.0]);
    }
    assert_all_pixels(TargetFormat::Rgba8Unorm, &out[3], n, |p| {
        p == [0, 255, 0, 255]
    });
    assert!(ctx.take_error().is_none());
}

#[test]
fn render_clear_blend_and_float32() {
    let Some(ctx) = context() else { return };
    let wgsl = format!(
        "{FULLSCREEN_VS}{}",
        r#"
@fragment
fn fs() -> @location(0) vec4<f32> {
    return vec4<f32>(0.25, 0.5, 0.75, 1.0);
}
"#
    );
    // Additive blending over the clear colour (Rgba16Float is blendable without features).
    let mut job = RenderJob::new("blend", &wgsl, "vs", "fs");
    job.targets = vec![
        ColorTarget::new(TargetFormat::Rgba16Float)
            .with_clear([1.0, 2.0, 3.0, 4.0])
            .with_blend(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent::REPLACE,
            }),
    ];
    let out = render(&ctx, &job).expect("render");
    for px in TargetFormat::Rgba16Float.decode_image_f32(&out[0]) {
        assert_eq!(px, [1.25, 2.5, 3.75, 1.0]);
    }

    // Rgba32Float: drawn values, and the clear colour when nothing is drawn.
    job.targets =
        vec![ColorTarget::new(TargetFormat::Rgba32Float).with_clear([1.0, -2.0, 3.5, 4.0])];
    let out = render(&ctx, &job).expect("render");
    for px in TargetFormat::Rgba32Float.decode_image_f32(&out[0]) {
        assert_eq!(px, [0.25, 0.5, 0.75, 1.0]);
    }
    job.vertex_count = 0;
    let out = render(&ctx, &job).expect("render");
    assert_eq!(out[0].len(), 16 * 16 * 16);
    for px in TargetFormat::Rgba32Float.decode_image_f32(&out[0]) {
        assert_eq!(px, [1.0, -2.0, 3.5, 4.0]);
    }

    // Float32 blending is allowed only where the device can blend Rgba32Float (the harness
    // takes the adapter's format features, for URP's targets): elsewhere a pipeline error.
    job.targets = vec![
        ColorTarget::new(TargetFormat::Rgba32Float).with_blend(wgpu::BlendState::ALPHA_BLENDING),
    ];
    let blendable = ctx
        .device
        .features()
        .contains(wgpu::Features::FLOAT32_BLENDABLE)
        || (ctx
            .device
            .features()
            .contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES)
            && ctx
                .adapter
                .get_texture_format_features(wgpu::TextureFormat::Rgba32Float)
                .flags
                .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE));
    let result = render(&ctx, &job);
    if blendable {
        assert!(result.is_ok(), "{result:?}");
    } else {
        assert!(
            matches!(result, Err(GpuError::PipelineCompile { .. })),
            "{result:?}"
        );
    }
}

#[test]
fn render_binds_only_used_resources() {
    let Some(ctx) = context() else { return };
    let wgsl = format!(
        "{FULLSCREEN_VS}{}",
        r#"
struct Params { color: vec4<f32> }
@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> extra: array<f32>;
@group(1) @binding(0) var tex: texture_2d<f32>;
@group(1) @binding(1) var samp: sampler;
@group(1) @binding(2) var cube: texture_cube<f32>;
@group(2) @binding(0) var unused_tex: texture_2d<f32>;

@fragment
fn fs() -> @location(0) vec4<f32> {
    let t = textureSampleLevel(tex, samp, vec2<f32>(0.25, 0.25), 0.0);
    let c = textureSampleLevel(cube, samp, vec3<f32>(1.0, 0.0, 0.0), 0.0);
    return params.color * 0.5 + t * 0.25 + c * 0.25 + vec4<f32>(extra[0]);
}
"#
    );
    let uniform: Vec<u8> = bytemuck::cast_slice(&[1.0f32, 0.0, 0.0, 1.0]).to_vec();
    let extra: Vec<u8> = bytemuck::cast_slice(&[0.0f32]).to_vec();
    let face = |rgba: [u8; 4]| rgba.repeat(4 * 4);
    let mut job = RenderJob::new("resources", &wgsl, "vs", "fs");
    job.width = 4;
    job.height = 4;
    job.resources = vec![
        BoundResource::new(0, 0, Resource::Uniform(uniform)),
        BoundResource::new(0, 1, Resource::Storage(extra)),
        BoundResource::new(
            1,
            0,
            Resource::Texture2d {
                format: wgpu::TextureFormat::Rgba8Unorm,
                width: 2,
                height: 2,
                data: [0u8, 255, 0, 0].repeat(4),
            },
        ),
        BoundResource::new(1, 1, Resource::Sampler { nearest: true }),
        BoundResource::new(
            1,
            2,
            Resource::TextureCube {
                format: wgpu::TextureFormat::Rgba8Unorm,
                size: 4,
                levels: vec![[
                    face([0, 0, 255, 0]),
                    face([0; 4]),
                    face([0; 4]),
                    face([0; 4]),
                    face([0; 4]),
                    face([0; 4]),
                ]],
            },
        ),
        // Declared by the shader but unused by the entry points: must be skipped.
        BoundResource::new(
            2,
            0,
            Resource::Texture2d {
                format: wgpu::TextureFormat::Rgba8Unorm,
                width: 1,
                height: 1,
                data: vec![0; 4],
            },
        ),
        // Not declared at all: must be skipped.
        BoundResource::new(3, 7, Resource::Sampler { nearest: false }),
    ];
    let out = render(&ctx, &job).expect("render");
    // 0.5 * (1,0,0,1) + 0.25 * (0,1,0,0) + 0.25 * (0,0,1,0)
    assert_all_pixels(TargetFormat::Rgba8Unorm, &out[0], 16, |p| {
        matches!(p[0], 127 | 128)
            && matches!(p[1], 63 | 64)
            && matches!(p[2], 63 | 64)
            && matches!(p[3], 127 | 128)
    });

    // A used slot without a resource is reported, not a panic.
    let mut missing = job.clone();
    missing.resources.retain(|r| (r.group, r.binding) != (0, 1));
    match render(&ctx, &missing) {
        Err(GpuError::Validation { message, .. }) => {
            assert!(message.contains("@group(0) @binding(1)"), "{message}")
        }
        other => panic!("expected a validation error, got {other:?}"),
    }

    // A resource of the wrong kind is a captured wgpu validation error.
    let mut wrong = job.clone();
    wrong.resources[2] = BoundResource::new(1, 0, Resource::Sampler { nearest: true });
    assert!(matches!(
        render(&ctx, &wrong),
        Err(GpuError::Validation { .. })
    ));
    assert!(ctx.take_error().is_none(), "{:?}", ctx.take_error());
}

#[test]
fn broken_shaders_return_pipeline_compile_errors() {
    let Some(ctx) = context() else { return };
    // Syntax error in the module.
    let job = RenderJob::new(
        "syntax",
        "@fragment fn fs( -> @location(0) vec4<f32> {",
        "vs",
        "fs",
    );
    match render(&ctx, &job) {
        Err(GpuError::PipelineCompile { label, message }) => {
            assert_eq!(label, "syntax");
            assert!(!message.is_empty());
        }
        other => panic!("expected PipelineCompile, got {other:?}"),
    }
    // Type error (validates in the parser, fails naga validation).
    let bad_type =
        format!("{FULLSCREEN_VS}@fragment fn fs() -> @location(0) vec4<f32> {{ return 1u; }}");
    let job = RenderJob::new("type-error", &bad_type, "vs", "fs");
    assert!(matches!(
        render(&ctx, &job),
        Err(GpuError::PipelineCompile { .. })
    ));
    // Valid module, but the pipeline does not validate: integer output into a unorm target.
    let int_out = format!(
        "{FULLSCREEN_VS}@fragment fn fs() -> @location(0) vec4<u32> {{ return vec4<u32>(1u); }}"
    );
    let job = RenderJob::new("int-into-unorm", &int_out, "vs", "fs");
    match render(&ctx, &job) {
        Err(GpuError::PipelineCompile { label, .. }) => assert_eq!(label, "int-into-unorm"),
        other => panic!("expected PipelineCompile, got {other:?}"),
    }
    // Missing entry point.
    let ok = format!(
        "{FULLSCREEN_VS}@fragment fn fs() -> @location(0) vec4<f32> {{ return vec4<f32>(1.0); }}"
    );
    let job = RenderJob::new("no-entry", &ok, "vs", "nope");
    assert!(matches!(
        render(&ctx, &job),
        Err(GpuError::PipelineCompile { .. })
    ));
    // Broken compute shader.
    let err = run_compute(
        &ctx,
        "compute-syntax",
        "@compute fn main( {",
        "main",
        &[],
        4,
        1,
    );
    assert!(
        matches!(err, Err(GpuError::PipelineCompile { .. })),
        "{err:?}"
    );
    // The device is still usable afterwards and nothing escaped the scopes.
    assert!(render(&ctx, &RenderJob::new("ok", &ok, "vs", "fs")).is_ok());
    assert!(ctx.take_error().is_none(), "{:?}", ctx.take_error());
}

#[test]
fn oversized_or_misused_resources_return_errors() {
    let Some(ctx) = context() else { return };
    let wgsl = r#"
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
@compute @workgroup_size(1)
fn main() { output[0] = 1u; }
"#;
    // Output larger than any storage binding.
    let err = run_compute(&ctx, "huge", wgsl, "main", &[], 1 << 40, 1);
    assert!(matches!(err, Err(GpuError::Validation { .. })), "{err:?}");
    // Only binding 1 used: binding 0 is skipped by the auto layout.
    let out = run_compute(&ctx, "only-output", wgsl, "main", &[], 4, 1).expect("compute");
    assert_eq!(out, 1u32.to_le_bytes());
    // Too many workgroups: captured validation error at dispatch.
    let err = run_compute(&ctx, "too-many-groups", wgsl, "main", &[], 4, u32::MAX);
    assert!(err.is_err(), "{err:?}");

    // Reading back a texture without COPY_SRC.
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("no-copy-src"),
        size: wgpu::Extent3d {
            width: 4,
            height: 4,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: wgpu::TextureFormat::Rgba8Unorm,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    assert!(matches!(
        read_texture(&ctx, "no-copy-src", &texture),
        Err(GpuError::Readback { .. })
    ));

    // Render target larger than the device allows, and texture data that is too short.
    let ok = format!(
        "{FULLSCREEN_VS}@fragment fn fs() -> @location(0) vec4<f32> {{ return vec4<f32>(1.0); }}"
    );
    let mut job = RenderJob::new("too-big", &ok, "vs", "fs");
    job.width = ctx.device.limits().max_texture_dimension_2d + 1;
    assert!(matches!(
        render(&ctx, &job),
        Err(GpuError::Validation { .. })
    ));
    let short = [BoundResource::new(
        0,
        0,
        Resource::Texture2d {
            format: wgpu::TextureFormat::Rgba8Unorm,
            width: 8,
            height: 8,
            data: vec![0; 10],
        },
    )];
    assert!(matches!(
        GpuResources::upload(&ctx, "short", &short),
        Err(GpuError::Validation { .. })
    ));
    assert!(ctx.take_error().is_none(), "{:?}", ctx.take_error());
}

#[test]
fn uncaptured_errors_and_device_loss_are_recorded() {
    let _serial = DEVICE_ABUSE.lock().unwrap_or_else(|e| e.into_inner());
    let Some(ctx) = context() else { return };
    // An invalid buffer created outside any harness scope goes to the recording handler.
    let _buffer = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("map-read-storage"),
        size: 16,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::STORAGE,
        mapped_at_creation: false,
    });
    match ctx.take_error() {
        Some(GpuError::Validation { label, message }) => {
            assert_eq!(label, "uncaptured");
            assert!(!message.is_empty());
        }
        other => panic!("expected a recorded validation error, got {other:?}"),
    }
    assert!(ctx.take_error().is_none());

    // A destroyed device is reported as lost, and later work fails cleanly.
    ctx.device.destroy();
    assert!(ctx.wait("after-destroy").is_err());
    assert!(matches!(ctx.take_error(), Some(GpuError::DeviceLost(_))));
    let ok = format!(
        "{FULLSCREEN_VS}@fragment fn fs() -> @location(0) vec4<f32> {{ return vec4<f32>(1.0); }}"
    );
    assert!(matches!(
        render(&ctx, &RenderJob::new("after-destroy", &ok, "vs", "fs")),
        Err(GpuError::DeviceLost(_))
    ));
}

#[test]
fn waits_are_bounded() {
    let _serial = DEVICE_ABUSE.lock().unwrap_or_else(|e| e.into_inner());
    let Some(mut ctx) = context() else { return };
    // Enough work to take far longer than the 1 ms timeout on any adapter.
    let wgsl = r#"
@group(0) @binding(0) var<storage, read> input: array<u32>;
@group(0) @binding(1) var<storage, read_write> output: array<u32>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    var x = input[0] + id.x;
    for (var i = 0u; i < input[1]; i++) {
        x = x * 1664525u + 1013904223u;
    }
    output[id.x] = x;
}
"#;
    let input: Vec<u8> = bytemuck::cast_slice(&[1u32, 100_000_000]).to_vec();
    ctx.timeout = std::time::Duration::from_millis(1);
    let result = run_compute(&ctx, "slow", wgsl, "main", &input, 4 * 256, 4);
    match result {
        Err(GpuError::Timeout { label, seconds }) => {
            assert_eq!(label, "slow");
            assert!(seconds < 0.01);
        }
        other => panic!("expected a timeout, got {other:?}"),
    }
    // Let the work drain before the device is dropped.
    ctx.timeout = std::time::Duration::from_secs(120);
    ctx.wait("drain").expect("drain");
}

#[test]
fn an_adapter_that_is_not_there_is_a_clear_error() {
    match GpuContext::new(Some("no-such-adapter-anywhere")) {
        Err(e @ GpuError::NoAdapter { .. }) => {
            let message = e.to_string();
            assert!(message.contains("no-such-adapter-anywhere"), "{message}");
        }
        Err(other) => panic!("expected NoAdapter, got {other}"),
        Ok(ctx) => panic!("matched adapter {}", ctx.adapter_name()),
    }
}
