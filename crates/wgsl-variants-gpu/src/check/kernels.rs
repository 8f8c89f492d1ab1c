//! Compute kernels over the library's pure functions (`deferred/gbuffer`, `deferred/ldr`,
//! `deferred/probe`), run on seeded random inputs plus edge cases and compared with the
//! reference value by value.
//!
//! The kernels live in `src/gpu/kernels/*.wgsl` and `#import` the library's modules; they are
//! composed by the library's own module system: [`kernel_library`] loads the library's files
//! (the bundled ones for the bundled library) plus the kernel files (under `check/`). Each kernel reads `IN` consecutive `vec4f` per case from
//! an input storage buffer and writes `OUT` per case.
//!
//! Comparisons go through [`wgsl_variants_shaders::reference::tolerance`]: [`f32_within`] for `f32` results,
//! [`unorm_within`] for the 8-bit codes of `pack4x8unorm`. Where a result comes out of `exp2`
//! or `pow`, whose Vulkan precision depends on the argument, the bound is derived for the case
//! as the tolerance module prescribes ([`exp2_ulp`], [`pow_ulp`]) and passed to
//! [`f32_within_ulp`].

use glam::{Vec3, Vec4};

use super::report::{KernelReport, Mismatch};
use super::scene::Rng;
use crate::{CheckError, GpuContext, GpuError, run_compute};
use wgsl_variants::Library;
use wgsl_variants::library::LoadOptions;
use wgsl_variants::source::RawFile;
use wgsl_variants_shaders::reference::gbuffer::{GBuffer, decode_normal, encode_normal};
use wgsl_variants_shaders::reference::ldr::{ldr_accumulate, ldr_decode, ldr_encode};
use wgsl_variants_shaders::reference::probe::{
    Probe, box_project, box_project_grown, falloff, forward_blend, mip_from_smoothness, rgbm_decode,
};
use wgsl_variants_shaders::reference::tolerance::{
    F32_ABS, F32_ULP, f32_within, f32_within_ulp, unorm_within,
};

/// The pseudo-shader name that selects the kernels (`check::KERNELS`), and that their
/// mismatches name as their shader.
pub(crate) const PSEUDO_SHADER: &str = "kernels";

/// The kernel sources, as library files under `check/`.
pub const KERNEL_FILES: [(&str, &str); 4] = [
    ("check/io.wgsl", include_str!("../kernels/io.wgsl")),
    (
        "check/gbuffer.wgsl",
        include_str!("../kernels/gbuffer.wgsl"),
    ),
    ("check/ldr.wgsl", include_str!("../kernels/ldr.wgsl")),
    ("check/probe.wgsl", include_str!("../kernels/probe.wgsl")),
];

/// Seed of the kernels' random inputs.
pub const KERNEL_SEED: u64 = 0xC0FF_EE00_D15C;

/// Random cases per kernel, besides the edge cases.
pub const RANDOM_CASES: usize = 512;

/// One compute kernel of the check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Kernel {
    /// Name in reports and for `--pass`.
    pub name: &'static str,
    /// Shader of the kernel library.
    pub shader: &'static str,
    /// Pass of that shader.
    pub pass: &'static str,
    /// Keywords of the variant run.
    pub keywords: &'static [&'static str],
    /// What it evaluates.
    pub description: &'static str,
}

/// Every kernel.
pub const KERNELS: [Kernel; 12] = [
    Kernel {
        name: "gbuffer_encode_normal",
        shader: "check_gbuffer",
        pass: "EncodeNormal",
        keywords: &[],
        description: "normalize(n)·0.5+0.5: unit, unnormalized, tiny, huge, zero, NaN/inf normals",
    },
    Kernel {
        name: "gbuffer_decode_normal",
        shader: "check_gbuffer",
        pass: "DecodeNormal",
        keywords: &[],
        description: "normalize(rgb·2−1) over random colours and every-axis 10-bit codes",
    },
    Kernel {
        name: "gbuffer_pack",
        shader: "check_gbuffer",
        pass: "Pack",
        keywords: &[],
        description: "the four G-buffer outputs with RT3 = exp2(−c), and RT0/RT1 quantized by pack4x8unorm",
    },
    Kernel {
        name: "gbuffer_pack_hdr",
        shader: "check_gbuffer",
        pass: "Pack",
        keywords: &["UNITY_HDR_ON"],
        description: "the four G-buffer outputs with RT3 = c (UNITY_HDR_ON)",
    },
    Kernel {
        name: "ldr_encode",
        shader: "check_ldr",
        pass: "Encode",
        keywords: &[],
        description: "exp2(−max(c, 0)), incl. negative, 0, huge, ±inf, NaN",
    },
    Kernel {
        name: "ldr_decode",
        shader: "check_ldr",
        pass: "Decode",
        keywords: &[],
        description: "max(−log2(s), 0), incl. s = 0 (+inf), s ≥ 1, negative, NaN, tiny",
    },
    Kernel {
        name: "ldr_accumulate",
        shader: "check_ldr",
        pass: "Accumulate",
        keywords: &[],
        description: "stored · exp2(−max(light, 0))",
    },
    Kernel {
        name: "probe_box_project",
        shader: "check_probe",
        pass: "BoxProject",
        keywords: &[],
        description: "box projection (plain and grown by b), incl. axis and near-axis rays, points on faces, projection off",
    },
    Kernel {
        name: "probe_mip",
        shader: "check_probe",
        pass: "Mip",
        keywords: &[],
        description: "mip from smoothness, incl. 0, 1, > 1, < 0",
    },
    Kernel {
        name: "probe_rgbm_decode",
        shader: "check_probe",
        pass: "RgbmDecode",
        keywords: &[],
        description: "rgb · x · α^y, α = w(a − 1) + 1, incl. y = 0, α = 0, identity decode",
    },
    Kernel {
        name: "probe_forward_blend",
        shader: "check_probe",
        pass: "ForwardBlend",
        keywords: &[],
        description: "t·e0 + (1 − t)·e1, e0 alone from t ≥ 0.99999 (even with e1 = NaN)",
    },
    Kernel {
        name: "probe_falloff",
        shader: "check_probe",
        pass: "Falloff",
        keywords: &[],
        description: "saturate(1 − |dist|/b), incl. b = 0 inside, on and outside the box",
    },
];

/// The kernel library: the files of `lib` (for [`wgsl_variants_shaders::library`], the bundled
/// files) plus the kernel files, so the kernels run the very modules the passes were checked
/// with.
pub fn kernel_library(lib: &Library) -> Result<Library, GpuError> {
    let files = lib.files();
    let mut raw: Vec<RawFile> = (0..files.len())
        .map(|id| RawFile {
            path: files.path(id).to_owned(),
            bytes: files.text(id).as_bytes().to_vec(),
        })
        .collect();
    raw.extend(KERNEL_FILES.iter().map(|(path, text)| RawFile {
        path: (*path).to_owned(),
        bytes: text.as_bytes().to_vec(),
    }));
    Library::from_raw(raw, &LoadOptions::default())
        .map_err(|e| GpuError::from(CheckError::KernelLibrary(Box::new(e))))
}

/// Vulkan's precision of `exp2(x)`: `3 + 2·|x|` ULP (at least [`F32_ULP`]), plus `extra`
/// correctly rounded operations after it.
pub fn exp2_ulp(x: f32, extra: u32) -> u32 {
    let x = if x.is_finite() {
        x.abs().min(1.0e6)
    } else {
        0.0
    };
    (3 + 2 * x.ceil() as u32).max(F32_ULP) + extra
}

/// The precision of `pow(a, y)` as Vulkan derives it from `exp2(y · log2(a))`: `log2` is off by
/// at most 2^-21 absolute on [0.5, 2] (3 ULP elsewhere, which is smaller there), so `y · log2(a)`
/// is off by `|y|·2^-21`, which `exp2` turns into a relative error of `ln 2 · |y| · 2^-21`, at
/// most `6·|y|` ULP; then `exp2`'s own [`exp2_ulp`], and `extra` correctly rounded operations.
pub fn pow_ulp(a: f32, y: f32, extra: u32) -> u32 {
    let e = if a > 0.0 { y * a.log2() } else { 0.0 };
    let y = if y.is_finite() {
        y.abs().min(1.0e6)
    } else {
        0.0
    };
    exp2_ulp(e, 0) + (6.0 * y).ceil() as u32 + extra
}

/// One expected output value and how it is compared.
#[derive(Clone, Copy, Debug)]
enum Want {
    /// [`f32_within`].
    F32(f32),
    /// [`f32_within_ulp`] with a bound derived for the case.
    F32Ulp(f32, u32, f32),
    /// An 8-bit code for [`unorm_within`], found in the low (`false`) or high (`true`) byte of
    /// a 16-bit half carried as an exact `f32`.
    Unorm8(f32, bool),
}

/// One expected output: `(flat output index, output name, want)`.
type Expected = (usize, &'static str, Want);

/// A kernel's inputs and expected outputs.
struct Cases {
    /// `IN` vec4f per case.
    per_case_in: usize,
    /// `OUT` vec4f per case.
    per_case_out: usize,
    /// Inputs, flat.
    inputs: Vec<Vec4>,
    /// Per case: a description and the expected outputs.
    expected: Vec<(String, Vec<Expected>)>,
}

impl Cases {
    fn new(per_case_in: usize, per_case_out: usize) -> Cases {
        Cases {
            per_case_in,
            per_case_out,
            inputs: Vec::new(),
            expected: Vec::new(),
        }
    }

    /// Adds a case; `want` lists `(output vec4 index within the case, component, name, want)`.
    fn push(
        &mut self,
        inputs: &[Vec4],
        description: String,
        want: Vec<(usize, usize, &'static str, Want)>,
    ) {
        debug_assert_eq!(inputs.len(), self.per_case_in);
        let case = self.expected.len();
        self.inputs.extend_from_slice(inputs);
        let base = case * self.per_case_out * 4;
        self.expected.push((
            description,
            want.into_iter()
                .map(|(v, c, name, w)| (base + v * 4 + c, name, w))
                .collect(),
        ));
    }
}

/// `[x, y, z]` for descriptions.
fn v3(v: Vec3) -> String {
    format!("({:e}, {:e}, {:e})", v.x, v.y, v.z)
}

/// The three components of `v` at output vec4 `out`, compared with [`f32_within`].
fn want3(out: usize, name: &'static str, v: Vec3) -> Vec<(usize, usize, &'static str, Want)> {
    (0..3).map(|c| (out, c, name, Want::F32(v[c]))).collect()
}

/// The three components with a derived ULP bound and absolute floor.
fn want3_ulp(
    out: usize,
    name: &'static str,
    v: Vec3,
    ulp: [u32; 3],
    floor: f32,
) -> Vec<(usize, usize, &'static str, Want)> {
    (0..3)
        .map(|c| (out, c, name, Want::F32Ulp(v[c], ulp[c], floor)))
        .collect()
}

/// A probe as its five vec4f (`Probe` of `deferred/probe.wgsl`).
fn probe_vec4s(p: &Probe) -> [Vec4; 5] {
    [
        p.position.extend(0.0),
        p.box_min.extend(p.forward_weight),
        p.box_max.extend(0.0),
        Vec4::new(p.hdr.x, p.hdr.y, 0.0, p.hdr.z),
        Vec4::new(
            if p.box_projection { 1.0 } else { 0.0 },
            p.blend_distance,
            p.importance as f32,
            0.0,
        ),
    ]
}

/// A random direction-ish vector with components in `[-1, 1]`, not all tiny.
fn random_vec(rng: &mut Rng) -> Vec3 {
    loop {
        let v = Vec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if v.length() > 0.05 {
            return v;
        }
    }
}

fn encode_normal_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(1, 1);
    let mut normals = vec![
        Vec3::ZERO,
        Vec3::new(-0.0, 0.0, -0.0),
        Vec3::X,
        Vec3::NEG_X,
        Vec3::Y,
        Vec3::NEG_Y,
        Vec3::Z,
        Vec3::NEG_Z,
        Vec3::new(3.0, 0.0, 4.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-2.0, 5.0, -7.0),
        Vec3::new(1.0e-18, 2.0e-18, -1.0e-18), // tiny: the squared length underflows
        Vec3::new(3.0e-19, 0.0, 0.0),
        Vec3::new(1.0e18, -2.0e18, 3.0e18),
        Vec3::new(1.0e30, 1.0e30, -1.0e30), // huge: the squared length overflows
        Vec3::new(f32::MAX, 0.0, f32::MAX),
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(f32::INFINITY, 0.0, 0.0),
        Vec3::new(0.0, f32::NEG_INFINITY, 1.0),
    ];
    for _ in 0..RANDOM_CASES {
        let scale = 10f32.powf(rng.range(-3.0, 3.0));
        normals.push(random_vec(rng) * scale);
    }
    for n in normals {
        cases.push(
            &[n.extend(0.0)],
            format!("n = {}", v3(n)),
            want3(0, "encoded", encode_normal(n)),
        );
    }
    cases
}

fn decode_normal_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(1, 1);
    let mut colours = vec![
        Vec3::ZERO,
        Vec3::ONE,
        Vec3::new(1.0, 0.5, 0.5),
        Vec3::new(0.0, 0.5, 0.5),
        Vec3::new(0.5, 1.0, 0.5),
        Vec3::new(0.5, 0.5, 0.0),
        Vec3::new(0.5, 0.5, 1.0),
    ];
    // 10-bit codes next to the axes.
    for q in [0u32, 1, 511, 512, 513, 1022, 1023] {
        let c = q as f32 / 1023.0;
        colours.push(Vec3::new(c, 512.0 / 1023.0, 511.0 / 1023.0));
        colours.push(Vec3::new(511.0 / 1023.0, c, 1.0 - c));
    }
    for _ in 0..RANDOM_CASES {
        let c = Vec3::new(
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        );
        if (c * 2.0 - 1.0).length() > 1.0e-3 {
            colours.push(c);
        }
    }
    for c in colours {
        cases.push(
            &[c.extend(0.0)],
            format!("rgb = {}", v3(c)),
            want3(0, "normal", decode_normal(c)),
        );
    }
    cases
}

fn pack_cases(rng: &mut Rng, hdr: bool) -> Cases {
    let mut cases = Cases::new(4, 5);
    let mut inputs: Vec<(Vec3, f32, Vec3, f32, Vec3, Vec3)> = vec![
        (Vec3::ZERO, 1.0, Vec3::splat(0.04), 0.5, Vec3::Z, Vec3::ZERO),
        (
            Vec3::ONE,
            0.0,
            Vec3::ONE,
            1.0,
            Vec3::NEG_Y,
            Vec3::new(1.0, 2.0, 0.5),
        ),
        (
            Vec3::new(1.5, -0.25, 0.5),
            2.0,
            Vec3::new(-1.0, 0.3, 7.0),
            -0.5,
            Vec3::ZERO,
            Vec3::new(-3.0, 11.0, 200.0),
        ),
        (
            Vec3::splat(0.5),
            0.5,
            Vec3::splat(0.5),
            0.5,
            Vec3::new(2.0, -2.0, 1.0),
            Vec3::new(f32::INFINITY, 10.0, 1.0e-7),
        ),
    ];
    if !hdr {
        // NaN light is treated as 0 by the LDR encoding.
        inputs.push((
            Vec3::splat(0.25),
            1.0,
            Vec3::splat(0.1),
            0.9,
            Vec3::X,
            Vec3::new(f32::NAN, 0.0, 1.0),
        ));
    }
    for _ in 0..RANDOM_CASES {
        let unit3 = |rng: &mut Rng| {
            Vec3::new(
                rng.range(0.0, 1.0),
                rng.range(0.0, 1.0),
                rng.range(0.0, 1.0),
            )
        };
        let diffuse = unit3(rng);
        let spec = unit3(rng);
        let c = Vec3::new(
            rng.range(-1.0, 12.0),
            rng.range(-1.0, 12.0),
            rng.range(-1.0, 12.0),
        );
        inputs.push((
            diffuse,
            rng.range(0.0, 1.0),
            spec,
            rng.range(0.0, 1.0),
            random_vec(rng),
            c,
        ));
    }
    for (diffuse, occlusion, spec, smoothness, normal, c) in inputs {
        let g = GBuffer::pack(diffuse, occlusion, spec, smoothness, normal, c, hdr);
        let mut want = Vec::new();
        for (out, name, v) in [(0, "rt0", g.rt0), (1, "rt1", g.rt1), (2, "rt2", g.rt2)] {
            for comp in 0..4 {
                want.push((out, comp, name, Want::F32(v[comp])));
            }
        }
        for comp in 0..4 {
            let w = if hdr || comp == 3 {
                Want::F32(g.rt3[comp])
            } else {
                // exp2(−max(c, 0)): exp2's precision depends on its argument.
                Want::F32Ulp(g.rt3[comp], exp2_ulp(c[comp].clamp(0.0, 200.0), 0), F32_ABS)
            };
            want.push((3, comp, "rt3", w));
        }
        // pack4x8unorm codes: lo/hi 16 bits of each packed word.
        for (target, v) in [(0usize, g.rt0), (1, g.rt1)] {
            for comp in 0..4 {
                let name = if target == 0 {
                    "pack4x8unorm(rt0)"
                } else {
                    "pack4x8unorm(rt1)"
                };
                want.push((
                    4,
                    target * 2 + comp / 2,
                    name,
                    Want::Unorm8(v[comp], comp % 2 == 1),
                ));
            }
        }
        cases.push(
            &[
                diffuse.extend(occlusion),
                spec.extend(smoothness),
                normal.extend(0.0),
                c.extend(0.0),
            ],
            format!(
                "diffuse {} occlusion {occlusion:e} spec {} smoothness {smoothness:e} n {} c {}",
                v3(diffuse),
                v3(spec),
                v3(normal),
                v3(c)
            ),
            want,
        );
    }
    cases
}

/// Values for the LDR kernels: random plus edge cases.
fn ldr_values(rng: &mut Rng, lo: f32, hi: f32, edges: &[f32]) -> Vec<Vec4> {
    let mut values: Vec<f32> = edges.to_vec();
    for _ in 0..RANDOM_CASES * 4 {
        values.push(rng.range(lo, hi));
    }
    while !values.len().is_multiple_of(4) {
        values.push(0.5);
    }
    values.chunks(4).map(Vec4::from_slice).collect()
}

fn ldr_encode_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(1, 1);
    let edges = [
        0.0,
        -0.0,
        1.0,
        0.5,
        2.0,
        8.0,
        10.0,
        11.0,
        24.0,
        200.0,
        1.0e30,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -1.0,
        -1.0e30,
        1.0e-30,
        1.0e-7,
        126.0,
        149.0,
        150.0,
    ];
    for c in ldr_values(rng, -2.0, 16.0, &edges) {
        let e = ldr_encode(c.truncate());
        let ew = ldr_encode(Vec3::splat(c.w)).x;
        let want = (0..4)
            .map(|i| {
                let x = c[i];
                let value = if i < 3 { e[i] } else { ew };
                let arg = if x > 0.0 { x.min(200.0) } else { 0.0 };
                (
                    0,
                    i,
                    "ldr_encode",
                    Want::F32Ulp(value, exp2_ulp(arg, 0), F32_ABS),
                )
            })
            .collect();
        cases.push(&[c], format!("c = {:?}", c.to_array()), want);
    }
    cases
}

fn ldr_decode_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(1, 1);
    let edges = [
        0.0,
        -0.0,
        1.0,
        1.5,
        f32::INFINITY,
        -1.0,
        f32::NAN,
        1.0e-30,
        1.0 / 1024.0,
        1.0 / 1023.0,
        0.5,
        1.0 - 1.0 / 16_777_216.0,
        0.25,
        1.0e-3,
        2.0,
        f32::NEG_INFINITY,
        1.2e-38,
    ];
    for s in ldr_values(rng, 0.0, 1.0, &edges) {
        let d = ldr_decode(s.truncate());
        let dw = ldr_decode(Vec3::splat(s.w)).x;
        let want = (0..4)
            .map(|i| (0, i, "ldr_decode", Want::F32(if i < 3 { d[i] } else { dw })))
            .collect();
        cases.push(&[s], format!("s = {:?}", s.to_array()), want);
    }
    cases
}

fn ldr_accumulate_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(2, 1);
    let mut pairs = vec![
        (Vec3::ONE, Vec3::ZERO),
        (Vec3::new(0.5, 0.25, 0.0), Vec3::new(1.0, -3.0, 5.0)),
        (
            Vec3::new(1.0, 0.5, 1.0),
            Vec3::new(f32::INFINITY, f32::NAN, 30.0),
        ),
        (Vec3::splat(0.125), Vec3::new(0.0, -0.0, 1.0e-30)),
    ];
    for _ in 0..RANDOM_CASES {
        let stored = Vec3::new(
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        );
        let light = Vec3::new(
            rng.range(-1.0, 12.0),
            rng.range(-1.0, 12.0),
            rng.range(-1.0, 12.0),
        );
        pairs.push((stored, light));
    }
    for (stored, light) in pairs {
        let r = ldr_accumulate(stored, light);
        let ulp = std::array::from_fn(|i| {
            let arg = if light[i] > 0.0 {
                light[i].min(200.0)
            } else {
                0.0
            };
            exp2_ulp(arg, 1)
        });
        cases.push(
            &[stored.extend(0.0), light.extend(0.0)],
            format!("stored {} light {}", v3(stored), v3(light)),
            want3_ulp(0, "ldr_accumulate", r, ulp, F32_ABS),
        );
    }
    cases
}

/// A random probe around the origin.
fn random_probe(rng: &mut Rng) -> Probe {
    let box_min = Vec3::new(
        rng.range(-5.0, -0.5),
        rng.range(-5.0, -0.5),
        rng.range(-5.0, -0.5),
    );
    let box_max = Vec3::new(
        rng.range(0.5, 5.0),
        rng.range(0.5, 5.0),
        rng.range(0.5, 5.0),
    );
    let position = box_min
        + (box_max - box_min)
            * Vec3::new(
                rng.range(0.0, 1.0),
                rng.range(0.0, 1.0),
                rng.range(0.0, 1.0),
            );
    Probe {
        position,
        box_min,
        box_max,
        hdr: Vec3::new(1.0, 1.0, 0.0),
        box_projection: true,
        blend_distance: rng.pick(&[0.0, 0.25, 0.5, 1.0, 2.0]),
        importance: 1,
        forward_weight: 1.0,
    }
}

/// The absolute floor for results built from operands of magnitude up to that of `values`.
fn scaled_floor(values: &[Vec3]) -> f32 {
    let scale = values
        .iter()
        .map(|v| v.abs().max_element())
        .fold(1.0f32, f32::max);
    F32_ABS * scale
}

fn box_project_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(7, 2);
    let unit = Probe {
        position: Vec3::new(0.25, -0.5, 0.0),
        box_min: Vec3::new(-1.0, -2.0, -3.0),
        box_max: Vec3::new(1.0, 2.0, 3.0),
        hdr: Vec3::new(1.0, 1.0, 0.0),
        box_projection: true,
        blend_distance: 1.0,
        importance: 1,
        forward_weight: 1.0,
    };
    let mut inputs: Vec<(Vec3, Vec3, Probe)> = vec![
        // Axis rays (ignored axes) and −0 components.
        (Vec3::X, Vec3::ZERO, unit),
        (Vec3::NEG_Y, Vec3::ZERO, unit),
        (Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.5, 0.5, 0.5), unit),
        (Vec3::new(-0.0, 3.0, -0.0), Vec3::ZERO, unit),
        // Near-axis rays.
        (Vec3::new(1.0, 1.0e-7, -1.0e-7), Vec3::ZERO, unit),
        (
            Vec3::new(-1.0e-6, 1.0, 2.0e-6),
            Vec3::new(0.3, 0.0, -0.2),
            unit,
        ),
        (Vec3::new(1.0e-30, 1.0e-30, -1.0), Vec3::ZERO, unit),
        // Points on a face, leaving through it and through the opposite one.
        (Vec3::new(1.0, 0.5, 0.25), Vec3::new(1.0, 0.0, 0.0), unit),
        (Vec3::new(-1.0, 0.5, 0.25), Vec3::new(1.0, 0.0, 0.0), unit),
        (Vec3::new(0.2, 0.3, -1.0), Vec3::new(0.0, 0.0, -3.0), unit),
        // A corner.
        (Vec3::ONE, Vec3::new(1.0, 2.0, 3.0), unit),
        // Box projection off: r unchanged, not even normalized.
        (
            Vec3::new(-3.0, 0.5, 2.0),
            Vec3::ZERO,
            Probe {
                box_projection: false,
                ..unit
            },
        ),
        // Blend distance 0: the grown box is the box.
        (
            Vec3::new(0.3, -0.4, 0.5),
            Vec3::new(0.1, 0.2, 0.3),
            Probe {
                blend_distance: 0.0,
                ..unit
            },
        ),
    ];
    for _ in 0..RANDOM_CASES {
        let probe = random_probe(rng);
        let t = Vec3::new(
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        );
        let p = probe.box_min + (probe.box_max - probe.box_min) * t;
        inputs.push((random_vec(rng), p, probe));
    }
    for (r, p, probe) in inputs {
        let floor = scaled_floor(&[
            r,
            p,
            probe.position,
            probe.box_min,
            probe.box_max,
            probe.grown().box_min,
            probe.grown().box_max,
        ]);
        let plain = box_project(r, p, &probe);
        let grown = box_project_grown(r, p, &probe);
        let mut want = want3_ulp(0, "box_project", plain, [F32_ULP; 3], floor);
        want.extend(want3_ulp(
            1,
            "box_project_grown",
            grown,
            [F32_ULP; 3],
            floor,
        ));
        let mut input = vec![r.extend(0.0), p.extend(0.0)];
        input.extend(probe_vec4s(&probe));
        cases.push(
            &input,
            format!(
                "r {} p {} o {} box {}..{} b {} projection {}",
                v3(r),
                v3(p),
                v3(probe.position),
                v3(probe.box_min),
                v3(probe.box_max),
                probe.blend_distance,
                probe.box_projection
            ),
            want,
        );
    }
    cases
}

fn mip_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(1, 1);
    let edges = [
        0.0, 1.0, 0.5, 1.5, -0.5, 2.0, -1.0, 0.999_999, 1.0e-7, 0.25, 0.75, 0.1,
    ];
    for s in ldr_values(rng, 0.0, 1.0, &edges) {
        let want = (0..4)
            .map(|i| (0, i, "mip", Want::F32(mip_from_smoothness(s[i]))))
            .collect();
        cases.push(&[s], format!("smoothness {:?}", s.to_array()), want);
    }
    cases
}

fn rgbm_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(2, 1);
    let mut inputs = vec![
        (Vec4::new(0.5, 0.25, 1.0, 0.5), Vec3::new(1.0, 1.0, 0.0)),
        (Vec4::new(0.5, 0.25, 1.0, 0.5), Vec3::new(5.0, 1.0, 1.0)),
        (Vec4::new(1.0, 1.0, 1.0, 0.5), Vec3::new(2.0, 2.2, 1.0)),
        (Vec4::new(0.2, 0.4, 0.6, 0.0), Vec3::new(4.0, 2.2, 1.0)), // α = 0, y > 0
        (Vec4::new(0.2, 0.4, 0.6, 0.0), Vec3::new(4.0, 0.0, 1.0)), // α = 0, y = 0
        (Vec4::new(0.2, 0.4, 0.6, 1.0), Vec3::new(4.0, 2.2, 1.0)), // α = 1
        (Vec4::new(0.0, 1.0, 0.5, 0.25), Vec3::new(8.0, 0.5, 0.5)),
        (Vec4::ONE, Vec3::new(1.0, 1.0, 1.0)),
    ];
    for _ in 0..RANDOM_CASES {
        let texel = Vec4::new(
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
            rng.range(0.0, 1.0),
        );
        let y = rng.pick(&[0.0, 1.0, 2.2, 0.5, -1.0]);
        let y = if y < 0.0 { rng.range(0.0, 3.0) } else { y };
        let w = rng.pick(&[0.0, 1.0, 0.5, -1.0]);
        let w = if w < 0.0 { rng.range(0.0, 1.0) } else { w };
        inputs.push((texel, Vec3::new(rng.range(0.5, 8.0), y, w)));
    }
    for (texel, hdr) in inputs {
        let rgb = rgbm_decode(texel, hdr);
        let alpha = hdr.z * (texel.w - 1.0) + 1.0;
        // α^y, then · x and · rgb.
        let ulp = pow_ulp(alpha, hdr.y, 2);
        cases.push(
            &[texel, Vec4::new(hdr.x, hdr.y, 0.0, hdr.z)],
            format!("texel {:?} hdr {}", texel.to_array(), v3(hdr)),
            want3_ulp(0, "rgbm_decode", rgb, [ulp; 3], F32_ABS),
        );
    }
    cases
}

fn forward_blend_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(3, 1);
    let e0 = Vec3::new(0.25, 1.5, 3.0);
    let e1 = Vec3::new(2.0, 0.0, 0.5);
    let nan = Vec3::splat(f32::NAN);
    let mut inputs = vec![
        (e0, e1, 0.0),
        (e0, e1, 1.0),
        (e0, e1, 0.5),
        (e0, nan, 1.0),
        (e0, nan, 0.99999),
        (e0, nan, 1.5),
        (e0, e1, 0.999_989_9),
        (e0, e1, 0.99999),
        (e0, e1, -0.5),
    ];
    for _ in 0..RANDOM_CASES {
        let a = Vec3::new(
            rng.range(0.0, 4.0),
            rng.range(0.0, 4.0),
            rng.range(0.0, 4.0),
        );
        let b = Vec3::new(
            rng.range(0.0, 4.0),
            rng.range(0.0, 4.0),
            rng.range(0.0, 4.0),
        );
        inputs.push((a, b, rng.range(0.0, 1.0)));
    }
    for (a, b, t) in inputs {
        cases.push(
            &[a.extend(0.0), b.extend(0.0), Vec4::new(t, 0.0, 0.0, 0.0)],
            format!("e0 {} e1 {} t {t:e}", v3(a), v3(b)),
            want3(0, "forward_blend", forward_blend(a, b, t)),
        );
    }
    cases
}

fn falloff_cases(rng: &mut Rng) -> Cases {
    let mut cases = Cases::new(6, 1);
    let unit = Probe::new(Vec3::ZERO, Vec3::splat(-1.0), Vec3::splat(1.0));
    let zero = Probe {
        blend_distance: 0.0,
        ..unit
    };
    let mut inputs = vec![
        (Vec3::ZERO, unit),
        (Vec3::new(1.5, 0.0, 0.0), unit),
        (Vec3::new(1.5, 1.5, 0.0), unit),
        (Vec3::new(2.0, 0.0, 0.0), unit),
        (Vec3::new(-9.0, 0.0, 0.0), unit),
        (Vec3::ONE, unit),
        (Vec3::new(0.0, -1.25, 0.0), unit),
        (Vec3::new(1.0e6, 0.0, 0.0), unit),
        (Vec3::ZERO, zero),
        (Vec3::ONE, zero),
        (Vec3::new(-1.0, 0.5, 1.0), zero),
        (Vec3::new(0.0, 0.0, 1.0 + f32::EPSILON), zero),
        (Vec3::new(1.001, 0.0, 0.0), zero),
        (Vec3::new(5.0, 5.0, 5.0), zero),
        (
            Vec3::new(0.0, 0.0, 2.0),
            Probe {
                blend_distance: 2.0,
                ..unit
            },
        ),
    ];
    for _ in 0..RANDOM_CASES {
        let probe = random_probe(rng);
        let p = Vec3::new(
            rng.range(-7.0, 7.0),
            rng.range(-7.0, 7.0),
            rng.range(-7.0, 7.0),
        );
        inputs.push((p, probe));
    }
    for (p, probe) in inputs {
        let mut input = vec![p.extend(0.0)];
        input.extend(probe_vec4s(&probe));
        cases.push(
            &input,
            format!(
                "p {} box {}..{} b {}",
                v3(p),
                v3(probe.box_min),
                v3(probe.box_max),
                probe.blend_distance
            ),
            vec![(0, 0, "falloff", Want::F32(falloff(p, &probe)))],
        );
    }
    cases
}

/// The inputs and expected outputs of `kernel`.
fn cases_of(kernel: &Kernel) -> Cases {
    let mut rng = Rng::new(
        KERNEL_SEED
            ^ kernel
                .name
                .bytes()
                .fold(0u64, |h, b| h.rotate_left(5) ^ u64::from(b)),
    );
    match kernel.name {
        "gbuffer_encode_normal" => encode_normal_cases(&mut rng),
        "gbuffer_decode_normal" => decode_normal_cases(&mut rng),
        "gbuffer_pack" => pack_cases(&mut rng, false),
        "gbuffer_pack_hdr" => pack_cases(&mut rng, true),
        "ldr_encode" => ldr_encode_cases(&mut rng),
        "ldr_decode" => ldr_decode_cases(&mut rng),
        "ldr_accumulate" => ldr_accumulate_cases(&mut rng),
        "probe_box_project" => box_project_cases(&mut rng),
        "probe_mip" => mip_cases(&mut rng),
        "probe_rgbm_decode" => rgbm_cases(&mut rng),
        "probe_forward_blend" => forward_blend_cases(&mut rng),
        _ => falloff_cases(&mut rng),
    }
}

/// Runs one kernel and compares its outputs.
pub fn check_kernel(
    ctx: &GpuContext,
    lib: &Library,
    kernel: &Kernel,
) -> Result<KernelReport, GpuError> {
    let variant = lib
        .variant(kernel.shader, kernel.pass, kernel.keywords)
        .map_err(|e| CheckError::lookup(format!("kernel {}", kernel.name), e))?;
    let wgsl = lib.wgsl(&variant);
    let cases = cases_of(kernel);
    let input: Vec<u8> = cases
        .inputs
        .iter()
        .flat_map(|v| v.to_array())
        .flat_map(f32::to_le_bytes)
        .collect();
    let n = cases.expected.len();
    let out_len = n * cases.per_case_out * 16;
    let bytes = run_compute(
        ctx,
        &format!("kernel {} ({})", kernel.name, variant.label()),
        &wgsl,
        "main",
        &input,
        out_len,
        n.div_ceil(64) as u32,
    )?;
    let out: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    let mut report = KernelReport::new(kernel.name, kernel.description);
    report.cases = n;
    debug_assert_eq!(cases.per_case_in * n, cases.inputs.len());
    for (case, (description, wants)) in cases.expected.iter().enumerate() {
        for &(index, name, want) in wants {
            let got = out[index];
            let (ok, expected) = match want {
                Want::F32(w) => (f32_within(got, w), w),
                Want::F32Ulp(w, ulp, floor) => (f32_within_ulp(got, w, ulp, floor), w),
                Want::Unorm8(w, high) => {
                    let half = got as u32;
                    let code = if high { half >> 8 } else { half & 0xff };
                    (unorm_within(code, w, 8), w)
                }
            };
            report.record(ok, || Mismatch {
                shader: PSEUDO_SHADER.to_owned(),
                pass: kernel.name.to_owned(),
                keywords: description.clone(),
                target: name.to_owned(),
                pixel: [case as u32, (index % 4) as u32],
                expected: vec![expected],
                got: vec![got],
                got_raw: vec![got.to_bits()],
            });
        }
    }
    Ok(report)
}

/// Runs `kernels`, composed with [`kernel_library`] of `lib`.
pub fn check_kernels(
    ctx: &GpuContext,
    lib: &Library,
    kernels: &[&Kernel],
) -> Result<Vec<KernelReport>, GpuError> {
    let lib = kernel_library(lib)?;
    kernels.iter().map(|k| check_kernel(ctx, &lib, k)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kernel_library_composes_every_kernel() {
        let lib = kernel_library(&wgsl_variants_shaders::library().unwrap()).unwrap();
        for k in &KERNELS {
            let v = lib.variant(k.shader, k.pass, k.keywords).unwrap();
            let (module, _) = lib.naga_module(&v).unwrap();
            assert!(
                module.entry_points.iter().any(|e| e.name == "main"),
                "{}",
                k.name
            );
        }
    }

    #[test]
    fn derived_bounds() {
        assert_eq!(exp2_ulp(0.0, 0), F32_ULP);
        assert_eq!(exp2_ulp(10.0, 1), 24);
        assert_eq!(pow_ulp(0.5, 1.0, 0), F32_ULP + 6);
    }
}
