//! Looks up baked variants strictly, the way a renderer would at run time: no shader
//! compiler, no file system, no dependency.

mod shaders {
    include!(concat!(env!("OUT_DIR"), "/wgsl_variants.rs"));
}

use shaders::{LookupError, Stage};

fn main() -> Result<(), LookupError> {
    // Keywords in any order.
    let v = shaders::variant(
        "standard",
        "Deferred",
        &["UNITY_HDR_ON", "_NORMAL_MAP", "_OCCLUSION_MAP"],
    )?;
    let wgsl = v.wgsl.expect("WGSL was baked");
    let spirv = v.spirv.expect("SPIR-V was baked");
    println!(
        "{}/{} {{{}}}: {} bytes of WGSL, {} SPIR-V words ({} bytes), entry points {}",
        v.shader,
        v.pass,
        v.keywords.join(", "),
        wgsl.len(),
        spirv.len(),
        spirv.len() * 4,
        v.entry_points
            .iter()
            .map(|e| format!("{} ({:?})", e.name, e.stage))
            .collect::<Vec<_>>()
            .join(", ")
    );
    assert_eq!(spirv[0], 0x0723_0203, "SPIR-V magic number");
    assert!(v.entry_points.iter().any(|e| e.stage == Stage::Fragment));
    assert!(wgsl.contains("@fragment"));

    // Strict: a combination no material uses was not baked, and typos are named.
    assert!(matches!(
        shaders::variant("standard", "Deferred", &["_EMISSION_MAP"]),
        Err(LookupError::NotBaked { .. })
    ));
    assert!(matches!(
        shaders::variant("standard", "Deferred", &["_NORMAL_MAPP"]),
        Err(LookupError::UnknownKeyword { .. })
    ));
    println!(
        "not baked: {}",
        shaders::variant("standard", "Deferred", &["_EMISSION_MAP"]).unwrap_err()
    );

    for pass in shaders::passes() {
        let (count, bytes) = pass.variants().fold((0, 0), |(n, b), v| {
            (
                n + 1,
                b + v.wgsl.map_or(0, str::len) + v.spirv.map_or(0, |s| s.len() * 4),
            )
        });
        println!(
            "{}/{}: {count} variants, {bytes} bytes baked",
            pass.shader, pass.pass
        );
    }
    println!("{} variants in all", shaders::variants().len());
    Ok(())
}
