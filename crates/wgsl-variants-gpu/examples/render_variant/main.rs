//! Renders a G-buffer variant of the bundled standard shader's `Deferred` pass and one of
//! URP's `universal_lit/UniversalGBuffer` headless with wgpu through generated code alone —
//! `standard_deferred.rs` and `universal_gbuffer.rs`, written by `wgsl-variants bindings
//! SHADER PASS --wgpu`: a typed key instead of keyword strings, the uniform buffers filled
//! through the generated structs, and the bind group layouts, the vertex buffer layout and the
//! colour targets from the generated interface (`deferred.rs`, `urp_gbuffer.rs`; the draw
//! both share is `headless.rs`). Writes the first target of each as a PNG: `OUT.png` and
//! `OUT-urp.png`.
//!
//! ```sh
//! cargo run --release -p wgsl-variants-gpu --example render_variant -- out.png
//! ```
//!
//! Any adapter works, including Mesa's lavapipe (`apt-get install mesa-vulkan-drivers`).
//! `tests/gpu_bindings.rs` checks that these texels are the GPU check's for the same variants.

#[macro_use]
mod headless;
mod deferred;
mod urp_gbuffer;

use std::error::Error;
use std::path::{Path, PathBuf};

use wgsl_variants_gpu::GpuContext;
use wgsl_variants_gpu::check::TestScene;
use wgsl_variants_gpu::check::scene::DEFAULT_SEED;
use wgsl_variants_gpu::check::urp::{self, UrpScene};

/// Output size.
const SIZE: u32 = 256;

fn main() -> Result<(), Box<dyn Error>> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "render_variant.png".into()),
    );
    let lib = wgsl_variants_shaders::library()?;
    let ctx = GpuContext::new(std::env::var("WGSL_VARIANTS_ADAPTER").ok().as_deref())?;
    println!("adapter: {}", ctx.adapter_name());
    let mut scene = TestScene::new(DEFAULT_SEED);
    // The quad fills the view at any size: a bigger picture than the check's.
    (scene.width, scene.height) = (SIZE, SIZE);

    let key = deferred::KEY;
    println!("standard/Deferred {:?}", key.keywords());
    let targets = deferred::render(&ctx, &lib, &scene)?;
    save(&out, &targets, "RT0")?;

    let key = urp_gbuffer::KEY;
    println!("universal_lit/UniversalGBuffer {:?}", key.keywords());
    let urp = UrpScene::new(&scene, urp::DEFAULT_SEED);
    let targets = urp_gbuffer::render(&ctx, &lib, &urp)?;
    let stem = out.file_stem().unwrap_or_default().to_string_lossy();
    save(
        &out.with_file_name(format!("{stem}-urp.png")),
        &targets,
        "GBuffer0",
    )?;
    Ok(())
}

/// Writes the colour of the first of `targets` (RGBA, 8 bits a channel) to `path`, and checks
/// that the draw covered at least half of it.
fn save(path: &Path, targets: &[Vec<u8>], name: &str) -> Result<(), Box<dyn Error>> {
    let first = &targets[0];
    let covered = first
        .chunks_exact(4)
        .filter(|p| p[..3] != [0, 0, 0])
        .count();
    // The G-buffer's alpha is data (occlusion, material flags), not coverage: drop it.
    let rgb: Vec<u8> = first
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    image::save_buffer(path, &rgb, SIZE, SIZE, image::ExtendedColorType::Rgb8)?;
    println!(
        "  {} targets at {SIZE}x{SIZE}: {covered} of {} pixels lit in {name}; wrote {}",
        targets.len(),
        SIZE * SIZE,
        path.display()
    );
    if covered < (SIZE * SIZE / 2) as usize {
        return Err(format!("only {covered} pixels were drawn").into());
    }
    Ok(())
}
