//! Looks up baked variants the way a renderer does at run time — no shader compiler, no file
//! system — then draws two of them headless with wgpu through the generated code alone: the
//! built-in Deferred pass and URP's UniversalGBuffer, picked by typed keys, every buffer filled
//! through the generated structs, every layout from the generated interface. Writes the first
//! G-buffer target of each as a PNG into the folder given (default `.`).
//!
//! ```sh
//! cargo run --release -p wgsl-variants-baked-example -- target
//! ```

use std::error::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use glam::{Mat4, Vec3, Vec4};
use wgsl_variants_baked_example::bindings::standard_deferred as deferred;
use wgsl_variants_baked_example::bindings::universal_lit_universalgbuffer as gbuffer;
use wgsl_variants_baked_example::draw::{self, Gpu};
use wgsl_variants_baked_example::inputs::{self, Textures, Uniform};
use wgsl_variants_baked_example::shaders::{self, LookupError, Stage};
use wgsl_variants_baked_example::{
    DEFERRED, Pass, URP_GBUFFER, deferred_formats, deferred_pass, urp_gbuffer_formats,
    urp_gbuffer_pass,
};

/// Picture size.
const SIZE: u32 = 256;

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<(), Box<dyn Error>> {
    lookups()?;
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let gpu = Gpu::new()?;
    println!("adapter: {}", gpu.adapter);
    let camera = Camera::new();

    let pass = deferred_pass(DEFERRED, &deferred_formats(DEFERRED))?;
    let uniforms = deferred_uniforms(&gpu, &camera);
    draw_and_save(&gpu, &pass, &uniforms, &out.join("baked-deferred.png"))?;

    let pass = urp_gbuffer_pass(URP_GBUFFER, &urp_gbuffer_formats(URP_GBUFFER))?;
    let uniforms = urp_uniforms(&gpu, &camera);
    draw_and_save(&gpu, &pass, &uniforms, &out.join("baked-urp-gbuffer.png"))?;
    Ok(())
}

/// The strict string lookup (tools, logs), and what the bake holds.
fn lookups() -> Result<(), LookupError> {
    // Keywords in any order.
    let v = shaders::variant(
        "standard",
        "Deferred",
        &["UNITY_HDR_ON", "_NORMAL_MAP", "_OCCLUSION_MAP"],
    )?;
    let wgsl = v.wgsl.expect("WGSL was baked");
    let spirv = v.spirv.expect("SPIR-V was baked");
    println!(
        "{}/{} {{{}}}: {} bytes of WGSL, {} SPIR-V words, entry points {}",
        v.shader,
        v.pass,
        v.keywords.join(", "),
        wgsl.len(),
        spirv.len(),
        v.entry_points
            .iter()
            .map(|e| format!("{} ({:?})", e.name, e.stage))
            .collect::<Vec<_>>()
            .join(", ")
    );
    assert_eq!(spirv[0], 0x0723_0203, "SPIR-V magic number");
    assert!(v.entry_points.iter().any(|e| e.stage == Stage::Fragment));

    // Strict: a combination no material uses was not baked, and typos are named.
    assert!(matches!(
        shaders::variant("standard", "Deferred", &["_EMISSION_MAP"]),
        Err(LookupError::NotBaked { .. })
    ));
    assert!(matches!(
        shaders::variant("standard", "Deferred", &["_NORMAL_MAPP"]),
        Err(LookupError::UnknownKeyword { .. })
    ));
    // The typed keys find the same variants without strings; one no material uses is refused
    // (and would not compile as a constant).
    let typed = DEFERRED.baked(shaders::variants());
    let by_name = shaders::variant("standard", "Deferred", &DEFERRED.keywords())?;
    assert!(std::ptr::eq(typed, by_name));
    let stripped = deferred::Keywords {
        emission_map: true,
        ..deferred::Keywords::DEFAULT
    };
    assert!(matches!(
        deferred::Key::new(stripped),
        Err(deferred::KeyError::NotBaked)
    ));

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

/// A camera 2.4 units in front of the quad, which is turned a little so its shading varies.
struct Camera {
    view_proj: Mat4,
    position: Vec3,
    model: Mat4,
}

impl Camera {
    fn new() -> Camera {
        let position = Vec3::new(0.0, 0.0, 2.4);
        // Right-handed, looking down −Z; depth 0 at the near plane, 1 at the far (WebGPU's).
        let view = Mat4::from_translation(-position);
        let (near, far) = (0.1, 100.0);
        let f = 1.0 / (25f32.to_radians()).tan();
        let projection = Mat4::from_cols(
            Vec4::new(f, 0.0, 0.0, 0.0),
            Vec4::new(0.0, f, 0.0, 0.0),
            Vec4::new(0.0, 0.0, far / (near - far), -1.0),
            Vec4::new(0.0, 0.0, near * far / (near - far), 0.0),
        );
        Camera {
            view_proj: projection * view,
            position,
            model: Mat4::from_rotation_y(0.35) * Mat4::from_rotation_x(-0.25),
        }
    }

    fn normal_matrix(&self) -> [[f32; 4]; 4] {
        self.model.inverse().transpose().to_cols_array_2d()
    }
}

/// Second-order spherical harmonics of a soft sky (Unity's `unity_SHAr/g/b`: the linear
/// terms, then the constant).
const SH: [[f32; 4]; 3] = [
    [0.0, 0.05, 0.02, 0.25],
    [0.0, 0.07, 0.02, 0.28],
    [0.0, 0.12, 0.02, 0.35],
];

/// `standard/Deferred`'s uniform buffers, each filled through its generated struct.
fn deferred_uniforms(gpu: &Gpu, camera: &Camera) -> Vec<Uniform> {
    use deferred::structs;
    let probe = |x: f32| structs::Probe {
        position: [x, 0.0, 1.0, 0.0],
        box_min: [x - 5.0, -5.0, -5.0, 0.0],
        box_max: [x + 5.0, 5.0, 5.0, 0.0],
        // Unity's HDR decode values: multiplier, exponent.
        hdr: [1.0, 1.0, 0.0, 0.0],
        // Box projection off, blend distance, importance.
        params: [0.0, 1.0, 1.0, 0.0],
    };
    vec![
        Uniform::new(
            gpu,
            0,
            0,
            &structs::Camera {
                view_proj: camera.view_proj.to_cols_array_2d(),
                position: camera.position.extend(1.0).to_array(),
            },
        ),
        Uniform::new(
            gpu,
            0,
            1,
            &structs::Lighting {
                sh_r: SH[0],
                sh_g: SH[1],
                sh_b: SH[2],
                light_dir: Vec4::new(-0.4, 0.6, 0.7, 0.0).normalize().to_array(),
                light_color: [1.0, 0.95, 0.9, 1.0],
            },
        ),
        Uniform::new(
            gpu,
            0,
            2,
            &structs::Probes {
                probe0: probe(-2.0),
                probe1: probe(2.0),
            },
        ),
        Uniform::new(
            gpu,
            1,
            0,
            &structs::Material {
                tint: [1.0, 1.0, 1.0, 1.0],
                emission: [1.0, 1.0, 1.0, 0.0],
                // Metallic, smoothness, alpha cutoff, occlusion strength.
                params: [1.0, 0.8, 0.5, 1.0],
                // Bump scale, detail bump scale.
                bump: [1.0, 1.0, 0.0, 0.0],
                detail_st: [1.0, 1.0, 0.0, 0.0],
            },
        ),
        Uniform::new(
            gpu,
            2,
            0,
            &structs::Object {
                model: camera.model.to_cols_array_2d(),
                normal_matrix: camera.normal_matrix(),
            },
        ),
    ]
}

/// `universal_lit/UniversalGBuffer`'s uniform buffers, each filled through its generated
/// struct.
fn urp_uniforms(gpu: &Gpu, camera: &Camera) -> Vec<Uniform> {
    use gbuffer::structs;
    vec![
        Uniform::new(
            gpu,
            0,
            0,
            &structs::Camera {
                view_proj: camera.view_proj.to_cols_array_2d(),
                position: camera.position.extend(1.0).to_array(),
            },
        ),
        Uniform::new(
            gpu,
            0,
            1,
            &structs::Lighting {
                sh_r: SH[0],
                sh_g: SH[1],
                sh_b: SH[2],
                main_light_dir: Vec4::new(-0.4, 0.6, 0.7, 0.0).normalize().to_array(),
                main_light_color: [1.0, 0.95, 0.9, 1.0],
                // Shadow attenuation, shadow strength.
                main_light_shadow: [1.0, 1.0, 0.0, 0.0],
                subtractive_shadow_color: [0.2, 0.2, 0.3, 0.0],
                glossy_environment_color: [0.3, 0.35, 0.4, 0.0],
                probes_occlusion: [1.0; 4],
                ambient_occlusion_params: [0.0; 4],
            },
        ),
        Uniform::new(
            gpu,
            1,
            0,
            &structs::Material {
                base_color: [1.0, 1.0, 1.0, 1.0],
                spec_color: [0.2, 0.2, 0.2, 0.0],
                emission_color: [1.0, 1.0, 1.0, 0.0],
                // Metallic, smoothness, alpha cutoff, bump scale.
                params: [1.0, 0.8, 0.5, 1.0],
                // Occlusion strength.
                extra: [1.0, 0.0, 0.0, 0.0],
            },
        ),
        Uniform::new(
            gpu,
            2,
            0,
            &structs::Object {
                model: camera.model.to_cols_array_2d(),
                normal_matrix: camera.normal_matrix(),
                lightmap_st: [1.0, 1.0, 0.0, 0.0],
                rendering_layers: [1, 0, 0, 0],
            },
        ),
    ]
}

/// Draws `pass` over the quad with stand-in textures and `uniforms`, and writes its first
/// target's colour to `path`.
fn draw_and_save(
    gpu: &Gpu,
    pass: &Pass,
    uniforms: &[Uniform],
    path: &Path,
) -> Result<(), Box<dyn Error>> {
    let textures = Textures::for_pass(gpu, pass);
    let mut resources = textures.bound();
    resources.extend(uniforms.iter().map(Uniform::bound));
    let vertices = inputs::pack(pass, &inputs::quad())?;
    let attributes = pass.attributes();
    let targets = draw::draw(
        gpu,
        &pass.draw(resources, &vertices, &attributes, SIZE, SIZE),
    )?;
    // The first target is RGBA8 in both G-buffers; its alpha is data (occlusion), not coverage.
    let rgb: Vec<u8> = targets[0]
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    let covered = targets[0]
        .chunks_exact(4)
        .filter(|p| p[..3] != [0, 0, 0])
        .count();
    if covered < (SIZE * SIZE / 4) as usize {
        return Err(format!("{}: only {covered} pixels drawn", pass.label).into());
    }
    image::save_buffer(path, &rgb, SIZE, SIZE, image::ExtendedColorType::Rgb8)?;
    println!(
        "{}: {} targets at {SIZE}x{SIZE}, {covered} pixels drawn; wrote {}",
        pass.label,
        targets.len(),
        path.display()
    );
    Ok(())
}
