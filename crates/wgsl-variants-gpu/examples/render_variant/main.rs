//! Renders a variant of the bundled standard shader's `Deferred` pass (its G-buffer) headless
//! with wgpu through generated code alone — `standard_deferred.rs`, written by
//! `wgsl-variants bindings standard Deferred --wgpu`: a typed key instead of keyword strings,
//! the uniform buffers filled through the generated structs, and the bind group layouts, the
//! vertex buffer layout and the colour targets from the generated interface (`deferred.rs`).
//! Writes RT0 (albedo and occlusion) as a PNG.
//!
//! ```sh
//! cargo run --release -p wgsl-variants-gpu --example render_variant -- out.png
//! ```
//!
//! Any adapter works, including Mesa's lavapipe (`apt-get install mesa-vulkan-drivers`).
//! `tests/gpu_bindings.rs` checks that these texels are the GPU check's for the same variant.

mod deferred;

use std::error::Error;

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::TestScene;
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;

/// Output size.
const SIZE: u32 = 256;

fn main() -> Result<(), Box<dyn Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "render_variant.png".into());
    let lib = wgsl_variants_shaders::library()?;
    let ctx = GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref())?;
    println!("adapter: {}", ctx.adapter_name());
    let mut scene = TestScene::new(DEFAULT_SEED);
    // The quad fills the view at any size: a bigger picture than the check's.
    (scene.width, scene.height) = (SIZE, SIZE);
    let key = deferred::KEY;
    let bindings: Vec<&str> = key.interface().bindings.iter().map(|b| b.name).collect();
    println!(
        "{}/{} {:?}: bindings {bindings:?}",
        deferred::standard_deferred::SHADER,
        deferred::standard_deferred::PASS,
        key.keywords(),
    );
    let targets = deferred::render(&ctx, &lib, &scene)?;

    // A picture of RT0, and a sanity check that the draw covered the target.
    let rt0 = &targets[0];
    let covered = rt0.chunks_exact(4).filter(|p| p[..3] != [0, 0, 0]).count();
    let (width, height) = (scene.width, scene.height);
    image::save_buffer(&out, rt0, width, height, image::ExtendedColorType::Rgba8)?;
    println!(
        "rendered RT0..RT{} at {width}x{height}: {covered} of {} pixels lit in RT0; wrote {out}",
        targets.len() - 1,
        width * height
    );
    if covered < (width * height / 2) as usize {
        return Err(format!("only {covered} pixels were drawn").into());
    }
    Ok(())
}
