//! Bakes the bundled library's build set for `materials.toml`: WGSL and SPIR-V. A shader that
//! does not validate fails this build with naga's diagnostics, pointing at the `.wgsl` file.

use wgsl_variants::bake::BakeTarget;

fn main() {
    let baked = wgsl_variants_shaders::bake()
        .materials("materials.toml")
        .target(BakeTarget::Wgsl)
        .target(BakeTarget::SpirV)
        .run();
    println!(
        "cargo:warning=baked {} variants ({} distinct outputs) into {}",
        baked.variants,
        baked.outputs,
        baked.file.display()
    );
}
