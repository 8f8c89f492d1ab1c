//! URP's G-buffer encoders in WGSL (`wgsl/universal/gbuffer.wgsl`) against the CPU reference
//! (`wgsl_variants_shaders::reference::urp`), run as a compute kernel on the GPU: the octahedral
//! normal packed 8:8:8 over a Fibonacci sphere plus edge cases, and the flags byte.

mod common;

use common::gpu::{adapter_filter, or_skip};
use glam::{Vec3, Vec4};
use wgsl_variants::Library;
use wgsl_variants::library::LoadOptions;
use wgsl_variants::source::RawFile;
use wgsl_variants_gpu::{GpuContext, run_compute};
use wgsl_variants_shaders::reference::tolerance::f32_within;
use wgsl_variants_shaders::reference::urp::accuracy::fibonacci_sphere;
use wgsl_variants_shaders::reference::urp::flags::{MaterialFlags, unpack_flags_byte};
use wgsl_variants_shaders::reference::urp::normal::{encode_normal_oct, oct_encode};

/// One case: in = (n.xyz, flags byte); out = (urp_pack_normal(n), urp_pack_flags(flags)),
/// (urp_oct_encode(n), 0, 0).
const KERNEL: &str = r#"#shader check_urp
#pass PackNormalOct
#define _GBUFFER_NORMALS_OCT
#import universal/gbuffer

@group(0) @binding(0) var<storage, read> input: array<vec4f>;
@group(0) @binding(1) var<storage, read_write> output: array<vec4f>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3u) {
    let i = id.x;
    if i >= arrayLength(&input) {
        return;
    }
    let c = input[i];
    output[2u * i] = vec4f(urp_pack_normal(c.xyz), urp_pack_flags(u32(c.w)));
    output[2u * i + 1u] = vec4f(urp_oct_encode(c.xyz), 0.0, 0.0);
}
#endpass
"#;

fn library() -> Library {
    let bundled = wgsl_variants_shaders::library().unwrap();
    let files = bundled.files();
    let mut raw: Vec<RawFile> = (0..files.len())
        .map(|id| RawFile {
            path: files.path(id).to_owned(),
            bytes: files.text(id).as_bytes().to_vec(),
        })
        .collect();
    raw.push(RawFile {
        path: "check/urp.wgsl".into(),
        bytes: KERNEL.as_bytes().to_vec(),
    });
    Library::from_raw(raw, &LoadOptions::default()).unwrap()
}

/// The two 12-bit codes of three packed bytes.
fn codes(b: [u8; 3]) -> (i32, i32) {
    (
        i32::from(b[0]) | (i32::from(b[2] & 15) << 8),
        i32::from(b[1]) | (i32::from(b[2] >> 4) << 8),
    )
}

#[test]
fn octahedral_packing_and_flags_match_the_reference() {
    let Some(ctx) = or_skip(GpuContext::new(adapter_filter().as_deref()), "GPU context") else {
        return;
    };
    let lib = library();
    let variant = lib
        .variant("check_urp", "PackNormalOct", &[] as &[&str])
        .unwrap();
    let wgsl = lib.wgsl(&variant);

    let mut normals = fibonacci_sphere(4096);
    normals.extend([
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
        Vec3::ZERO,
        Vec3::new(3.0, -4.0, 0.0),
        Vec3::new(1e-3, 1e-3, -1.0),
    ]);
    let input: Vec<Vec4> = normals
        .iter()
        .enumerate()
        .map(|(i, n)| n.extend((i % 16) as f32))
        .collect();
    let raw: Vec<[f32; 4]> = input.iter().map(|v| v.to_array()).collect();
    let out = run_compute(
        &ctx,
        "urp pack",
        &wgsl,
        "main",
        bytemuck::cast_slice(&raw),
        input.len() * 32,
        input.len().div_ceil(64) as u32,
    )
    .unwrap();
    let out: Vec<[f32; 4]> = bytemuck::pod_collect_to_vec(&out);
    let out: Vec<Vec4> = out.into_iter().map(Vec4::from_array).collect();

    let mut exact = 0;
    for (i, c) in input.iter().enumerate() {
        let n = c.truncate();
        let (packed, oct) = (out[2 * i], out[2 * i + 1]);
        // The octahedral coordinates: within the f32 tolerance of the reference.
        let want = oct_encode(n);
        assert!(
            f32_within(oct.x, want.x) && f32_within(oct.y, want.y),
            "{n}: oct {oct} vs {want}"
        );
        // Each channel is a whole byte / 255, and the two 12-bit codes are the reference's, or
        // one code away where the GPU's f32 division put f · 4095.5 on the other side of an
        // integer (truncation has no tolerance band of its own).
        let bytes = [packed.x, packed.y, packed.z].map(|v| {
            let b = (v * 255.0).round();
            assert!(f32_within(v, b / 255.0), "{n}: {v} is not a byte / 255");
            b as u8
        });
        let (gx, gy) = codes(bytes);
        let (wx, wy) = codes(encode_normal_oct(n));
        assert!(
            (gx - wx).abs() <= 1 && (gy - wy).abs() <= 1,
            "{n}: codes ({gx}, {gy}) vs ({wx}, {wy})"
        );
        if (gx, gy) == (wx, wy) {
            exact += 1;
        }
        // The flags byte survives byte / 255 and the shader-side read.
        let flags = MaterialFlags::from_byte(c.w as u8).unwrap();
        assert!(
            f32_within(packed.w, flags.pack()),
            "{n}: flags {}",
            packed.w
        );
        assert_eq!(unpack_flags_byte(packed.w), flags.to_byte());
    }
    println!("{exact} of {} packed normals bit-exact", input.len());
    // Off-by-one codes are rare boundary cases, not the rule.
    assert!(
        exact * 100 >= input.len() * 99,
        "{exact} of {}",
        input.len()
    );
}
