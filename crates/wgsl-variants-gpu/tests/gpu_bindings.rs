//! The GPU round trip of generated buffer structs (`wgsl_variants::bindings`): the host fills
//! `bindings_padding/padding.wgsl`'s `Data` — a `vec3` then an `f32`, an array of `vec3`, nested
//! structs, a `mat3x3`, an array of structs with trailing padding, a runtime-sized array of
//! `vec3` — through the committed generated module, a compute kernel writes back every scalar
//! it reads bit-cast to `u32`, and the bits must equal those the host put in the Rust fields.
//! Both variants run: `Params` (without `WIDE`) and `Params2` (with it) are two layouts.
//!
//! The modules are generated with the wgpu option: their bind group layout entries are those
//! the GPU crate derives from reflection, and the render pass `Draw` gets a pipeline from its
//! generated layouts, vertex buffer layout and colour targets alone.
//!
//! The `render_variant` example draws a `standard/Deferred` G-buffer and a URP
//! `universal_lit/UniversalGBuffer` one through generated code alone
//! (`examples/render_variant/deferred.rs` and `urp_gbuffer.rs`, compiled here too): their
//! uniform buffers are byte for byte the scenes', and their texels are the GPU check's for the
//! same variants.
//!
//! Without a wgpu adapter the GPU test prints a loud SKIPPED line and passes, unless `CI=true`
//! or `WGSL_VARIANTS_REQUIRE_GPU=1`. `WGSL_VARIANTS_ADAPTER=<substring>` selects an adapter.

mod common;

use wgsl_variants::Library;
use wgsl_variants::bindings::Options;
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;
use wgsl_variants_gpu::check::urp::{self, UrpScene};
use wgsl_variants_gpu::check::{TestScene, render_gbuffer};
use wgsl_variants_gpu::{
    BoundResource, GpuContext, Resource, compile_scoped, layout_entries, render, run_compute,
};

#[allow(dead_code)]
mod padding {
    include!("bindings_padding/padding_roundtrip.rs");
}

#[allow(dead_code)]
mod draw {
    include!("bindings_padding/padding_draw.rs");
}

#[macro_use]
#[path = "../examples/render_variant/headless.rs"]
mod headless;

#[path = "../examples/render_variant/deferred.rs"]
mod deferred;

#[path = "../examples/render_variant/urp_gbuffer.rs"]
mod urp_gbuffer;

use padding::structs::{Data, Data2, Data2Element, DataElement, Inner, Vec3F32Stride16};

const WGSL: &str = include_str!("bindings_padding/padding.wgsl");
/// Each pass, and its committed module.
const GENERATED: [(&str, &str, &str); 2] = [
    (
        "RoundTrip",
        "padding_roundtrip.rs",
        include_str!("bindings_padding/padding_roundtrip.rs"),
    ),
    (
        "Draw",
        "padding_draw.rs",
        include_str!("bindings_padding/padding_draw.rs"),
    ),
];

/// The GPU context, or `None` (after the loud SKIPPED line) where no adapter is allowed to skip.
fn gpu_context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "the GPU context",
    )
}

fn library() -> Library {
    Library::from_sources([("padding.wgsl", WGSL)]).unwrap()
}

/// The committed modules are what the generator writes today (snapshots: the tests below
/// prove the generator only through them).
#[test]
fn committed_modules_are_current() {
    let lib = library();
    for (pass, file, committed) in GENERATED {
        let pass_def = lib.pass("padding", pass).unwrap();
        let options = Options::default().wgpu(true);
        let code = wgsl_variants::bindings::generate_with(&lib, pass_def, 100, &options)
            .unwrap()
            .code;
        if code != committed {
            let line = code
                .lines()
                .zip(committed.lines())
                .position(|(a, b)| a != b)
                .unwrap_or_else(|| code.lines().count().min(committed.lines().count()));
            panic!(
                "tests/bindings_padding/{file} differs from the generator's output (first at \
                 line {}); regenerate with\n  cargo run --release --ignore-rust-version -p \
                 wgsl-variants-cli -- --root crates/wgsl-variants-gpu/tests/bindings_padding \
                 bindings padding {pass} --wgpu --out \
                 crates/wgsl-variants-gpu/tests/bindings_padding/{file}",
                line + 1
            );
        }
    }
}

/// The generated wgpu layout entries are those the GPU crate derives from the variant's
/// reflection, group by group, for every variant of both passes.
#[test]
fn generated_layout_entries_are_the_reflected_ones() {
    let lib = library();
    // Each module has its own `Interface` type: compare through its two methods.
    let check = |pass: &str, keywords: &[&str], groups: u32, entries: &dyn Fn(u32) -> Vec<_>| {
        let variant = lib.variant("padding", pass, keywords).unwrap();
        let reflected = layout_entries(&lib.reflect(&variant).unwrap()).unwrap();
        assert_eq!(groups as usize, reflected.len(), "{}", variant.label());
        for (group, expected) in reflected.iter().enumerate() {
            assert_eq!(
                &entries(group as u32),
                expected,
                "{} group {group}",
                variant.label()
            );
        }
    };
    for wide in [false, true] {
        let key = padding::Key::checked(padding::Keywords { wide });
        let i = key.interface();
        check("RoundTrip", &key.keywords(), i.group_count(), &|g| {
            i.bind_group_layout_entries(g)
        });
    }
    let i = draw::Key::checked(draw::Keywords::DEFAULT).interface();
    check("Draw", &[], i.group_count(), &|g| {
        i.bind_group_layout_entries(g)
    });
}

/// The vertex buffer layout packs the inputs in location order, and the colour targets take
/// formats of their outputs' component types only, at their locations.
#[test]
fn generated_vertex_layout_and_color_targets() {
    let interface = draw::Key::checked(draw::Keywords::DEFAULT).interface();
    let attributes = interface.wgpu_vertex_attributes();
    let layout = interface.vertex_buffer_layout(&attributes);
    assert_eq!(layout.array_stride, 24);
    assert_eq!(
        layout.attributes,
        wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x2, 2 => Uint32]
    );
    let formats = [
        wgpu::TextureFormat::Rgba8Unorm,
        wgpu::TextureFormat::Rgba8Uint,
    ];
    let states = interface.color_target_states(&formats).unwrap();
    assert_eq!(states.len(), 3);
    assert_eq!(states[0].as_ref().unwrap().format, formats[0]);
    assert_eq!(states[1], None, "no output at @location(1)");
    assert_eq!(states[2].as_ref().unwrap().format, formats[1]);
    assert_eq!(
        interface.color_target_states(&[formats[1], formats[1]]),
        Err(draw::ColorTargetError::Format {
            location: 0,
            kind: draw::ColorKind::Float,
            format: formats[1],
        })
    );
    assert_eq!(
        interface.color_target_states(&formats[..1]),
        Err(draw::ColorTargetError::Count {
            targets: 2,
            formats: 1
        })
    );
}

/// Distinct values for every scalar, and the bits the kernel must write back for each.
#[derive(Default)]
struct Values {
    next: u32,
    expected: Vec<u32>,
}

impl Values {
    /// A fresh `f32` (never one of the padding's bits), recorded as expected.
    fn f(&mut self) -> f32 {
        self.next += 1;
        let x = self.next as f32 * 1.25 - 20.0;
        self.expected.push(x.to_bits());
        x
    }

    fn v2(&mut self) -> [f32; 2] {
        [self.f(), self.f()]
    }

    fn v3(&mut self) -> [f32; 3] {
        [self.f(), self.f(), self.f()]
    }

    fn u(&mut self) -> u32 {
        self.next += 1;
        let x = 1000 + self.next;
        self.expected.push(x);
        x
    }

    fn i(&mut self) -> i32 {
        self.next += 1;
        let x = -1000 - self.next as i32;
        self.expected.push(x as u32);
        x
    }

    fn inner(&mut self) -> Inner {
        let mut x: Inner = garbage();
        x.a = self.v2();
        x.b = self.f();
        x
    }

    fn vec3_stride16(&mut self) -> Vec3F32Stride16 {
        let mut x: Vec3F32Stride16 = garbage();
        x.value = self.v3();
        x
    }
}

/// Padding bytes the GPU must skip: a value that no field holds.
const PAD: u8 = 0xA5;

/// A value whose every byte is [`PAD`]; the test then sets each field, so only padding keeps it.
fn garbage<T: bytemuck::Pod>() -> T {
    bytemuck::pod_read_unaligned(&vec![PAD; size_of::<T>()])
}

/// Fills the fields `Params` and `Params2` share, in WGSL declaration order.
macro_rules! fill_params {
    ($p:expr, $values:expr) => {{
        let (p, v) = (&mut $p, &mut *$values);
        p.v = v.v3();
        p.s = v.f();
        p.arr = [v.vec3_stride16(), v.vec3_stride16(), v.vec3_stride16()];
        p.inner = v.inner();
        for column in &mut p.m {
            let [x, y, z] = v.v3();
            column[..3].copy_from_slice(&[x, y, z]);
        }
        p.items = [v.inner(), v.inner()];
        p.u = [v.u(), v.u(), v.u()];
        p.i = v.i();
        p.k = v.u();
    }};
}

/// Runs the kernel of the variant `keywords` on `input` and asserts that it wrote `expected`.
fn round_trip(ctx: &GpuContext, lib: &Library, keywords: &[&str], input: &[u8], expected: &[u32]) {
    let words = expected.len();
    let variant = lib
        .variant(padding::SHADER, padding::PASS, keywords)
        .unwrap();
    let label = variant.label();
    let wgsl = lib.wgsl(&variant);
    let out = run_compute(ctx, &label, &wgsl, "main", input, words * 4, 1)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let got: Vec<u32> = bytemuck::cast_slice(&out).to_vec();
    // The first difference says which scalar (in WGSL declaration order) was read elsewhere.
    if let Some(i) = (0..words).find(|&i| got[i] != expected[i]) {
        panic!(
            "{label}: scalar {i} read back as {:#010x}, written as {:#010x} ({} of {words} differ)",
            got[i],
            expected[i],
            (0..words).filter(|&i| got[i] != expected[i]).count()
        );
    }
    eprintln!(
        "{label} on {}: {words} scalars of {} bytes read back",
        ctx.adapter_name(),
        input.len()
    );
}

/// wgpu accepts a render pipeline built from the generated layouts alone (its validation
/// checks them against the shader: bindings, vertex formats, colour target types).
#[test]
fn draw_pipeline_from_generated_layouts() {
    let Some(ctx) = gpu_context() else { return };
    let lib = library();
    let key = draw::Key::checked(draw::Keywords::DEFAULT);
    let interface = key.interface();
    let variant = lib
        .variant(draw::SHADER, draw::PASS, &key.keywords())
        .unwrap();
    let label = variant.label();
    let wgsl = lib.wgsl(&variant);
    let attributes = interface.wgpu_vertex_attributes();
    let targets = interface
        .color_target_states(&[
            wgpu::TextureFormat::Rgba8Unorm,
            wgpu::TextureFormat::Rgba8Uint,
        ])
        .unwrap();
    compile_scoped(&ctx, &label, || {
        let groups: Vec<wgpu::BindGroupLayout> = (0..interface.group_count())
            .map(|group| {
                ctx.device
                    .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                        label: Some(&label),
                        entries: &interface.bind_group_layout_entries(group),
                    })
            })
            .collect();
        let groups: Vec<Option<&wgpu::BindGroupLayout>> = groups.iter().map(Some).collect();
        let layout = ctx
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(&label),
                bind_group_layouts: &groups,
                immediate_size: 0,
            });
        let module = ctx
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(&label),
                source: wgpu::ShaderSource::Wgsl(wgsl.as_str().into()),
            });
        ctx.device
            .create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(&label),
                layout: Some(&layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("vs"),
                    compilation_options: Default::default(),
                    buffers: &[Some(interface.vertex_buffer_layout(&attributes))],
                },
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some("fs"),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                primitive: Default::default(),
                depth_stencil: None,
                multisample: Default::default(),
                multiview_mask: None,
                cache: None,
            })
    })
    .unwrap_or_else(|e| panic!("{label}: {e}"));
    eprintln!(
        "{label} on {}: pipeline from generated layouts",
        ctx.adapter_name()
    );
}

/// Both layouts of `Data`, written with the generated structs, read back bit for bit.
#[test]
fn padded_structs_round_trip_through_the_gpu() {
    let Some(ctx) = gpu_context() else { return };
    let lib = library();
    const LIGHTS: usize = 5;

    // Without `WIDE`: `Data` holds `Params`.
    const NARROW: padding::Key = padding::Key::checked(padding::Keywords { wide: false });
    let mut values = Values::default();
    let mut head: Data = garbage();
    fill_params!(head.params, &mut values);
    head.count = values.u();
    values.expected.push(LIGHTS as u32);
    let lights: Vec<DataElement> = (0..LIGHTS).map(|_| values.vec3_stride16()).collect();
    let mut input = bytemuck::bytes_of(&head).to_vec();
    input.extend_from_slice(bytemuck::cast_slice(&lights));
    round_trip(&ctx, &lib, &NARROW.keywords(), &input, &values.expected);

    // With `WIDE`: `Data2` holds `Params2`, 16 bytes longer.
    const WIDE: padding::Key = padding::Key::checked(padding::Keywords { wide: true });
    let mut values = Values::default();
    let mut head: Data2 = garbage();
    fill_params!(head.params, &mut values);
    head.params.w = [values.f(), values.f(), values.f(), values.f()];
    head.count = values.u();
    values.expected.push(LIGHTS as u32);
    let lights: Vec<Data2Element> = (0..LIGHTS).map(|_| values.vec3_stride16()).collect();
    let mut input = bytemuck::bytes_of(&head).to_vec();
    input.extend_from_slice(bytemuck::cast_slice(&lights));
    round_trip(&ctx, &lib, &WIDE.keywords(), &input, &values.expected);
}

/// Every buffer in `ours` holds the bytes of the one at its slot in `packed` (the GPU check's,
/// packed by hand), and `ours` has one per buffer binding of the variant (`entries`: its
/// generated layout entries).
fn assert_same_buffers(
    ours: &[BoundResource],
    packed: &[BoundResource],
    entries: &[wgpu::BindGroupLayoutEntry],
) {
    let buffers = entries
        .iter()
        .filter(|e| matches!(e.ty, wgpu::BindingType::Buffer { .. }))
        .count();
    assert_eq!(ours.len(), buffers, "every buffer of the variant");
    for u in ours {
        let theirs = packed
            .iter()
            .find(|r| (r.group, r.binding) == (u.group, u.binding))
            .unwrap();
        let (Resource::Uniform(a), Resource::Uniform(b)) = (&u.resource, &theirs.resource) else {
            panic!("@group({}) @binding({}) is no uniform", u.group, u.binding);
        };
        assert_eq!(a, b, "@group({}) @binding({})", u.group, u.binding);
    }
}

/// Same inputs: every uniform buffer the example fills through the generated structs holds the
/// bytes the GPU check packs for the scene by hand.
#[test]
fn example_uniforms_are_the_scenes() {
    let scene = TestScene::new(DEFAULT_SEED);
    let i = deferred::KEY.interface();
    let entries: Vec<_> = (0..i.group_count())
        .flat_map(|g| i.bind_group_layout_entries(g))
        .collect();
    assert_same_buffers(
        &deferred::uniforms(&scene),
        &scene.standard_resources(),
        &entries,
    );
}

/// The same for the URP variant: its buffers are the URP scene's.
#[test]
fn example_urp_uniforms_are_the_scenes() {
    let urp = UrpScene::new(&TestScene::new(DEFAULT_SEED), urp::DEFAULT_SEED);
    let i = urp_gbuffer::KEY.interface();
    let entries: Vec<_> = (0..i.group_count())
        .flat_map(|g| i.bind_group_layout_entries(g))
        .collect();
    assert_same_buffers(&urp_gbuffer::uniforms(&urp), &urp.resources(), &entries);
}

/// The example's G-buffer, drawn through generated code alone, is the GPU check's for the
/// same variant and scene, texel for texel.
#[test]
fn example_gbuffer_is_the_gpu_checks() {
    let Some(ctx) = gpu_context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::new(DEFAULT_SEED);
    let ours = deferred::render(&ctx, &lib, &scene).unwrap();
    let keywords = deferred::KEY.keywords();
    let check = render_gbuffer(&ctx, &lib, &scene, &keywords).unwrap();
    common::assert_same_targets("standard/Deferred", &ours, &check.targets);
    eprintln!(
        "standard/Deferred {keywords:?} on {}: {} targets of {}x{} equal the GPU check's",
        ctx.adapter_name(),
        ours.len(),
        scene.width,
        scene.height
    );
}

/// The example's URP G-buffer (seven targets), drawn through generated code alone, is what the
/// GPU check renders for the same variant over the URP scene, texel for texel. (The check
/// clears its targets to values the scene never writes, the example to black: the variant
/// discards no pixel, so no cleared texel is left to differ.)
#[test]
fn example_urp_gbuffer_is_the_gpu_checks() {
    let Some(ctx) = gpu_context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let urp = UrpScene::new(&TestScene::new(DEFAULT_SEED), urp::DEFAULT_SEED);
    let ours = urp_gbuffer::render(&ctx, &lib, &urp).unwrap();
    let keywords = urp_gbuffer::KEY.keywords();
    let variant = lib
        .variant("universal_lit", "UniversalGBuffer", &keywords)
        .unwrap();
    let mut job = urp.job(&variant.label(), &lib.wgsl(&variant), &keywords);
    job.resources = urp.resources();
    let check = render(&ctx, &job).unwrap();
    common::assert_same_targets("universal_lit/UniversalGBuffer", &ours, &check);
    eprintln!(
        "universal_lit/UniversalGBuffer {keywords:?} on {}: {} targets of {}x{} equal the GPU \
         check's",
        ctx.adapter_name(),
        ours.len(),
        urp.scene.width,
        urp.scene.height
    );
}
