//! Bakes the bundled library's build set for `materials.toml`: WGSL, SPIR-V and the typed Rust
//! of every baked pass (keys, structs, layouts, with wgpu's types). A shader that does not
//! validate fails this build with naga's diagnostics, pointing at the `.wgsl` file.

use wgsl_variants::bake::BakeTarget;
use wgsl_variants::bindings::Options;

fn main() {
    let baked = wgsl_variants_shaders::bake()
        .materials("materials.toml")
        .target(BakeTarget::Wgsl)
        .target(BakeTarget::SpirV)
        .bindings_with(Options::default().wgpu(true))
        .run();
    println!(
        "cargo:warning=baked {} variants ({} distinct outputs) into {}",
        baked.variants,
        baked.outputs,
        baked.file.display()
    );
}
