//! The program's two draws against the GPU check's: the baked variant of each typed key, its
//! pipeline from the bake's generated interface and the example's own draw, over the GPU
//! check's scene — its buffers filled through the bake's generated structs, its textures and
//! vertices — give the texels the GPU check renders for the same variant, byte for byte.
//!
//! The scene's uniforms are filled by the same code that fills them in the wgpu example
//! (`crates/wgsl-variants-gpu/examples/render_variant`), given the bake's `structs` module.

#[path = "../../../crates/wgsl-variants-gpu/tests/common/mod.rs"]
mod common;

#[allow(dead_code)]
#[macro_use]
#[path = "../../../crates/wgsl-variants-gpu/examples/render_variant/headless.rs"]
mod headless;

#[allow(dead_code)]
#[macro_use]
#[path = "../../../crates/wgsl-variants-gpu/examples/render_variant/deferred.rs"]
mod deferred;

#[allow(dead_code)]
#[macro_use]
#[path = "../../../crates/wgsl-variants-gpu/examples/render_variant/urp_gbuffer.rs"]
mod urp_gbuffer;

use wgsl_variants_baked_example::bindings::standard_deferred::structs as baked_deferred;
use wgsl_variants_baked_example::bindings::universal_lit_universalgbuffer::structs as baked_urp;
use wgsl_variants_baked_example::draw::{self, Bound, Gpu};
use wgsl_variants_baked_example::{
    DEFERRED, Pass, URP_GBUFFER, deferred_formats, deferred_pass, urp_gbuffer_formats,
    urp_gbuffer_pass,
};
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;
use wgsl_variants_gpu::check::urp::{self, UrpScene};
use wgsl_variants_gpu::check::{TestScene, render_gbuffer};
use wgsl_variants_gpu::{BoundResource, GpuContext, GpuResources, VertexBuffer, render};

/// The GPU context, or `None` after the loud SKIPPED line where no adapter is allowed to skip.
fn gpu_context() -> Option<GpuContext> {
    common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "the GPU context",
    )
}

/// Draws `pass` with the example's draw over `resources` (uploaded on `ctx`'s device) and
/// `vertices` (packed by the check, asserted to be the generated vertex layout).
fn draw_on(
    ctx: &GpuContext,
    pass: &Pass,
    resources: &[BoundResource],
    vertices: &VertexBuffer,
    size: (u32, u32),
) -> Vec<Vec<u8>> {
    let attributes = pass.attributes();
    assert_eq!(
        vertices.stride, pass.stride,
        "{}: vertex stride",
        pass.label
    );
    assert_eq!(
        vertices.attributes, attributes,
        "{}: vertex layout",
        pass.label
    );
    let uploaded = GpuResources::upload(ctx, &pass.label, resources).unwrap();
    let bound: Vec<Bound<'_>> = resources
        .iter()
        .map(|r| Bound {
            group: r.group,
            binding: r.binding,
            resource: uploaded.binding_resource((r.group, r.binding)).unwrap(),
        })
        .collect();
    let gpu = Gpu {
        device: ctx.device.clone(),
        queue: ctx.queue.clone(),
        adapter: ctx.adapter_name().to_owned(),
    };
    let d = pass.draw(bound, &vertices.data, &attributes, size.0, size.1);
    draw::draw(&gpu, &d).unwrap()
}

/// Every buffer of `ours` holds the bytes of the same slot of `packed`.
fn assert_same_buffers(ours: &[BoundResource], packed: &[BoundResource]) {
    for u in ours {
        let theirs = packed
            .iter()
            .find(|r| (r.group, r.binding) == (u.group, u.binding));
        assert_eq!(
            Some(&u.resource),
            theirs.map(|r| &r.resource),
            "@group({}) @binding({})",
            u.group,
            u.binding
        );
    }
}

/// The bake's generated structs hold the bytes the GPU check packs by hand for the scene.
#[test]
fn baked_structs_hold_the_checks_bytes() {
    let scene = TestScene::new(DEFAULT_SEED);
    let ours: Vec<BoundResource> = deferred_uniforms!(baked_deferred, &scene);
    assert_eq!(ours.len(), 5);
    assert_same_buffers(&ours, &scene.standard_resources());
    let urp = UrpScene::new(&scene, urp::DEFAULT_SEED);
    let ours: Vec<BoundResource> = urp_uniforms!(baked_urp, &urp);
    assert_eq!(ours.len(), 4);
    assert_same_buffers(&ours, &urp.resources());
}

/// `standard/Deferred`: the program's key, the bake's text and interface, the example's draw
/// give the GPU check's G-buffer.
#[test]
fn baked_deferred_gbuffer_is_the_gpu_checks() {
    let Some(ctx) = gpu_context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let scene = TestScene::new(DEFAULT_SEED);
    let pass = deferred_pass(DEFERRED, &deferred_formats(DEFERRED)).unwrap();
    let resources = headless::with_scene_textures(
        deferred_uniforms!(baked_deferred, &scene),
        scene.standard_resources(),
    );
    let vertices = headless::interleave(&[scene.quad()]);
    let ours = draw_on(
        &ctx,
        &pass,
        &resources,
        &vertices,
        (scene.width, scene.height),
    );
    let keywords = DEFERRED.keywords();
    let check = render_gbuffer(&ctx, &lib, &scene, &keywords).unwrap();
    common::assert_same_targets(&pass.label, &ours, &check.targets);
    eprintln!(
        "{} on {}: {} targets of {}x{} equal the GPU check's",
        pass.label,
        ctx.adapter_name(),
        ours.len(),
        scene.width,
        scene.height
    );
}

/// `universal_lit/UniversalGBuffer`, seven targets: the same. (The check clears its targets to
/// values the scene never writes, the example to black: the variant discards no pixel.)
#[test]
fn baked_urp_gbuffer_is_the_gpu_checks() {
    let Some(ctx) = gpu_context() else { return };
    let lib = wgsl_variants_shaders::library().unwrap();
    let urp = UrpScene::new(&TestScene::new(DEFAULT_SEED), urp::DEFAULT_SEED);
    let pass = urp_gbuffer_pass(URP_GBUFFER, &urp_gbuffer_formats(URP_GBUFFER)).unwrap();
    let resources = headless::with_scene_textures(urp_uniforms!(baked_urp, &urp), urp.resources());
    let vertices = headless::interleave(&[urp.scene.quad(), urp.lightmap_uvs()]);
    let size = (urp.scene.width, urp.scene.height);
    let ours = draw_on(&ctx, &pass, &resources, &vertices, size);
    let keywords = URP_GBUFFER.keywords();
    let variant = lib
        .variant("universal_lit", "UniversalGBuffer", &keywords)
        .unwrap();
    let mut job = urp.job(&variant.label(), &lib.wgsl(&variant), &keywords);
    job.resources = urp.resources();
    let check = render(&ctx, &job).unwrap();
    common::assert_same_targets(&pass.label, &ours, &check);
    eprintln!(
        "{} on {}: {} targets of {}x{} equal the GPU check's",
        pass.label,
        ctx.adapter_name(),
        ours.len(),
        size.0,
        size.1
    );
}

/// The formats the program gives its targets are the GPU check's for the same variants.
#[test]
fn target_formats_are_the_checks() {
    assert_eq!(
        urp_gbuffer_formats(URP_GBUFFER),
        wgsl_variants_gpu::urp_gbuffer_formats(&URP_GBUFFER.keywords())
    );
    assert_eq!(
        deferred_formats(DEFERRED),
        deferred::gbuffer_formats(&deferred::KEY.get())
    );
    assert_eq!(DEFERRED.keywords(), deferred::KEY.keywords());
    assert_eq!(URP_GBUFFER.keywords(), urp_gbuffer::KEY.keywords());
}
