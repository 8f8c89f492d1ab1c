//! Bakes the bundled library's build set for `materials.toml`: WGSL and SPIR-V. A shader that
//! does not validate fails this build with naga's diagnostics, pointing at the `.wgsl` file.

use wgsl_variants::bake::{Bake, BakeTarget};

fn main() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../wgsl");
    let baked = Bake::new(root)
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
