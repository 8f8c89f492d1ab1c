//! The GPU round trip of generated buffer structs (`wgsl_variants::bindings`): the host fills
//! `bindings_padding/padding.wgsl`'s `Data` — a `vec3` then an `f32`, an array of `vec3`, nested
//! structs, a `mat3x3`, an array of structs with trailing padding, a runtime-sized array of
//! `vec3` — through the committed generated module, a compute kernel writes back every scalar
//! it reads bit-cast to `u32`, and the bits must equal those the host put in the Rust fields.
//! Both variants run: `Params` (without `WIDE`) and `Params2` (with it) are two layouts.
//!
//! Without a wgpu adapter the GPU test prints a loud SKIPPED line and passes, unless `CI=true`
//! or `WGSL_VARIANTS_REQUIRE_GPU=1`. `WGSL_VARIANTS_ADAPTER=<substring>` selects an adapter.

mod common;

use wgsl_variants::Library;
use wgsl_variants_gpu::{GpuContext, run_compute};

#[allow(dead_code)]
mod padding {
    include!("bindings_padding/padding_roundtrip.rs");
}

use padding::structs::{Data, Data2, Data2Element, DataElement, Inner, Vec3F32Stride16};

const WGSL: &str = include_str!("bindings_padding/padding.wgsl");
const GENERATED: &str = include_str!("bindings_padding/padding_roundtrip.rs");
const REGENERATE: &str = "cargo run --release --ignore-rust-version -p wgsl-variants-cli -- \
     --root crates/wgsl-variants-gpu/tests/bindings_padding bindings padding RoundTrip \
     --out crates/wgsl-variants-gpu/tests/bindings_padding/padding_roundtrip.rs";

fn library() -> Library {
    Library::from_sources([("padding.wgsl", WGSL)]).unwrap()
}

/// The committed module is what the generator writes today (a snapshot: the GPU test below
/// proves the generator only through it).
#[test]
fn committed_module_is_current() {
    let code = library()
        .bindings(padding::SHADER, padding::PASS, 100)
        .unwrap()
        .code;
    if code != GENERATED {
        let line = code
            .lines()
            .zip(GENERATED.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| code.lines().count().min(GENERATED.lines().count()));
        panic!(
            "tests/bindings_padding/padding_roundtrip.rs differs from the generator's output \
             (first at line {}); regenerate with\n  {REGENERATE}",
            line + 1
        );
    }
}

/// Distinct values for every scalar, and the bits the kernel must write back for each.
#[derive(Default)]
struct Values {
    next: u32,
    expected: Vec<u32>,
}

impl Values {
    /// A fresh `f32` (never one of the padding's bits), recorded as expected.
    fn f(&mut self) -> f32 {
        self.next += 1;
        let x = self.next as f32 * 1.25 - 20.0;
        self.expected.push(x.to_bits());
        x
    }

    fn v2(&mut self) -> [f32; 2] {
        [self.f(), self.f()]
    }

    fn v3(&mut self) -> [f32; 3] {
        [self.f(), self.f(), self.f()]
    }

    fn u(&mut self) -> u32 {
        self.next += 1;
        let x = 1000 + self.next;
        self.expected.push(x);
        x
    }

    fn i(&mut self) -> i32 {
        self.next += 1;
        let x = -1000 - self.next as i32;
        self.expected.push(x as u32);
        x
    }

    fn inner(&mut self) -> Inner {
        let mut x: Inner = garbage();
        x.a = self.v2();
        x.b = self.f();
        x
    }

    fn vec3_stride16(&mut self) -> Vec3F32Stride16 {
        let mut x: Vec3F32Stride16 = garbage();
        x.value = self.v3();
        x
    }
}

/// Padding bytes the GPU must skip: a value that no field holds.
const PAD: u8 = 0xA5;

/// A value whose every byte is [`PAD`]; the test then sets each field, so only padding keeps it.
fn garbage<T: bytemuck::Pod>() -> T {
    bytemuck::pod_read_unaligned(&vec![PAD; size_of::<T>()])
}

/// Fills the fields `Params` and `Params2` share, in WGSL declaration order.
macro_rules! fill_params {
    ($p:expr, $values:expr) => {{
        let (p, v) = (&mut $p, &mut *$values);
        p.v = v.v3();
        p.s = v.f();
        p.arr = [v.vec3_stride16(), v.vec3_stride16(), v.vec3_stride16()];
        p.inner = v.inner();
        for column in &mut p.m {
            let [x, y, z] = v.v3();
            column[..3].copy_from_slice(&[x, y, z]);
        }
        p.items = [v.inner(), v.inner()];
        p.u = [v.u(), v.u(), v.u()];
        p.i = v.i();
        p.k = v.u();
    }};
}

/// Runs the kernel of the variant `keywords` on `input` and asserts that it wrote `expected`.
fn round_trip(ctx: &GpuContext, lib: &Library, keywords: &[&str], input: &[u8], expected: &[u32]) {
    let words = expected.len();
    let variant = lib
        .variant(padding::SHADER, padding::PASS, keywords)
        .unwrap();
    let label = variant.label();
    let wgsl = lib.wgsl(&variant);
    let out = run_compute(ctx, &label, &wgsl, "main", input, words * 4, 1)
        .unwrap_or_else(|e| panic!("{label}: {e}"));
    let got: Vec<u32> = bytemuck::cast_slice(&out).to_vec();
    // The first difference says which scalar (in WGSL declaration order) was read elsewhere.
    if let Some(i) = (0..words).find(|&i| got[i] != expected[i]) {
        panic!(
            "{label}: scalar {i} read back as {:#010x}, written as {:#010x} ({} of {words} differ)",
            got[i],
            expected[i],
            (0..words).filter(|&i| got[i] != expected[i]).count()
        );
    }
    eprintln!(
        "{label} on {}: {words} scalars of {} bytes read back",
        ctx.adapter_name(),
        input.len()
    );
}

/// Both layouts of `Data`, written with the generated structs, read back bit for bit.
#[test]
fn padded_structs_round_trip_through_the_gpu() {
    let Some(ctx) = common::gpu::or_skip(
        GpuContext::new(common::gpu::adapter_filter().as_deref()),
        "the GPU context",
    ) else {
        return;
    };
    let lib = library();
    const LIGHTS: usize = 5;

    // Without `WIDE`: `Data` holds `Params`.
    const NARROW: padding::Key = padding::Key::checked(padding::Keywords { wide: false });
    let mut values = Values::default();
    let mut head: Data = garbage();
    fill_params!(head.params, &mut values);
    head.count = values.u();
    values.expected.push(LIGHTS as u32);
    let lights: Vec<DataElement> = (0..LIGHTS).map(|_| values.vec3_stride16()).collect();
    let mut input = bytemuck::bytes_of(&head).to_vec();
    input.extend_from_slice(bytemuck::cast_slice(&lights));
    round_trip(&ctx, &lib, &NARROW.keywords(), &input, &values.expected);

    // With `WIDE`: `Data2` holds `Params2`, 16 bytes longer.
    const WIDE: padding::Key = padding::Key::checked(padding::Keywords { wide: true });
    let mut values = Values::default();
    let mut head: Data2 = garbage();
    fill_params!(head.params, &mut values);
    head.params.w = [values.f(), values.f(), values.f(), values.f()];
    head.count = values.u();
    values.expected.push(LIGHTS as u32);
    let lights: Vec<Data2Element> = (0..LIGHTS).map(|_| values.vec3_stride16()).collect();
    let mut input = bytemuck::bytes_of(&head).to_vec();
    input.extend_from_slice(bytemuck::cast_slice(&lights));
    round_trip(&ctx, &lib, &WIDE.keywords(), &input, &values.expected);
}
