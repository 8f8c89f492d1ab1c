//! An example renderer crate. Its `build.rs` bakes the bundled shader library for the
//! materials in `materials.toml` ([`shaders`]: every variant of the build set validated, as
//! WGSL and SPIR-V, with a strict lookup) and writes the typed Rust of every baked pass
//! ([`bindings`]: a key per pass, the structs of its buffers, its layouts as wgpu's types). At
//! run time a variant is picked by a typed key — a combination no material uses does not
//! compile — its buffers are filled through the generated structs, and its pipeline is built
//! from the generated interface alone ([`Pass`], drawn by [`draw`]).
//!
//! `tests/gpu_check.rs` holds the two draws of `src/main.rs` to the GPU check's: for the same
//! inputs, the same texels.

/// The baked variants (written by `build.rs`): `variants()`, `variant(shader, pass, keywords)`.
#[allow(missing_docs)]
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/wgsl_variants.rs"));
}

/// The typed Rust of every baked pass (written by `build.rs`): one module per pass.
#[allow(missing_docs)]
pub mod bindings {
    include!(concat!(env!("OUT_DIR"), "/wgsl_variants_bindings.rs"));
}

pub mod draw;
pub mod inputs;

use bindings::standard_deferred as deferred;
use bindings::universal_lit_universalgbuffer as gbuffer;
use draw::{Bound, Draw, DrawError};

/// The built-in Deferred variant the program draws: every map of a metallic material (the
/// "Painted metal" material), LDR, no reflection buffers. A key the bake does not hold would
/// not compile.
pub const DEFERRED: deferred::Key = deferred::Key::checked(deferred::Keywords {
    metallic_map: true,
    normal_map: true,
    occlusion_map: true,
    emission_map: true,
    ..deferred::Keywords::DEFAULT
});

/// The URP G-buffer variant the program draws ("URP painted metal"): octahedral normals, a
/// lightmap with a shadowmask, and all three optional targets (depth as colour, rendering
/// layers, shadowmask): seven colour targets.
pub const URP_GBUFFER: gbuffer::Key = gbuffer::Key::checked(gbuffer::Keywords {
    normalmap: true,
    emission: true,
    metallicspecglossmap: true,
    occlusionmap: true,
    gbuffer_normals_oct: true,
    render_pass_enabled: true,
    write_rendering_layers: true,
    shadows_shadowmask: true,
    lightmap_on: true,
    ..gbuffer::Keywords::DEFAULT
});

/// The built-in G-buffer's formats (Unity's), by target: RT0 albedo and occlusion, RT1
/// specular and smoothness, RT2 normal (`Rgb10a2Unorm`), RT3 emission and ambient
/// (`Rgba16Float` with `UNITY_HDR_ON`, `Rgb10a2Unorm` without), RT4 the baked occlusion
/// (`SHADOWS_SHADOWMASK`).
pub fn deferred_formats(key: deferred::Key) -> Vec<wgpu::TextureFormat> {
    use wgpu::TextureFormat as F;
    let hdr = key.get().unity_hdr_on;
    let targets = key.interface().color_targets.iter();
    targets
        .map(|t| match t.name {
            "rt2" => F::Rgb10a2Unorm,
            "rt3" if hdr => F::Rgba16Float,
            "rt3" => F::Rgb10a2Unorm,
            _ => F::Rgba8Unorm,
        })
        .collect()
}

/// URP's G-buffer formats, by target: GBuffer0 albedo (sRGB), GBuffer1, GBuffer2 the normal
/// (`Rgba8Unorm` octahedral, `Rgba8Snorm` otherwise), GBuffer3 lighting (`Rg11b10Ufloat`),
/// depth as colour (`R32Float`), rendering layers (`R32Uint`) and the shadowmask.
pub fn urp_gbuffer_formats(key: gbuffer::Key) -> Vec<wgpu::TextureFormat> {
    use wgpu::TextureFormat as F;
    let oct = key.get().gbuffer_normals_oct;
    let targets = key.interface().color_targets.iter();
    targets
        .map(|t| match t.name {
            "gbuffer0" => F::Rgba8UnormSrgb,
            "gbuffer2" if !oct => F::Rgba8Snorm,
            "gbuffer3" => F::Rg11b10Ufloat,
            "depth_as_color" => F::R32Float,
            "rendering_layers" => F::R32Uint,
            _ => F::Rgba8Unorm,
        })
        .collect()
}

/// A baked variant's pipeline, built from its key alone: the baked WGSL, and the bind group
/// layouts, vertex layout and colour targets of the generated interface.
pub struct Pass {
    /// `shader/pass {keywords}`.
    pub label: String,
    /// The baked WGSL.
    pub wgsl: &'static str,
    /// The layout entries of each bind group, `@group(0)` first.
    pub groups: Vec<Vec<wgpu::BindGroupLayoutEntry>>,
    /// Every binding: `(group, binding, name)`.
    pub names: Vec<(u32, u32, &'static str)>,
    /// The vertex inputs of the one vertex buffer: `(name, attribute)`.
    pub vertex: Vec<(&'static str, wgpu::VertexAttribute)>,
    /// Bytes per vertex.
    pub stride: u64,
    /// The colour targets in `@location` order.
    pub targets: Vec<Option<wgpu::ColorTargetState>>,
}

/// Defines `pub fn $name(key, formats) -> Result<Pass, DrawError>` for the generated module
/// `$m`: each generated module has its own `Key` and `Interface` types.
macro_rules! pass_fn {
    ($name:ident, $m:ident) => {
        /// The pipeline of `key`'s baked variant, with `formats` for its colour targets.
        pub fn $name(key: $m::Key, formats: &[wgpu::TextureFormat]) -> Result<Pass, DrawError> {
            let variant = key.baked(shaders::variants());
            let i = key.interface();
            let attributes = i.wgpu_vertex_attributes();
            Ok(Pass {
                label: format!("{}/{} {:?}", $m::SHADER, $m::PASS, key.keywords()),
                wgsl: variant
                    .wgsl
                    .ok_or_else(|| DrawError::Wgpu("the bake holds no WGSL".into()))?,
                groups: (0..i.group_count())
                    .map(|g| i.bind_group_layout_entries(g))
                    .collect(),
                names: i
                    .bindings
                    .iter()
                    .map(|b| (b.group, b.binding, b.name))
                    .collect(),
                vertex: i
                    .vertex_attributes
                    .iter()
                    .map(|a| a.name)
                    .zip(attributes)
                    .collect(),
                stride: i.vertex_stride,
                targets: i
                    .color_target_states(formats)
                    .map_err(|e| DrawError::Wgpu(e.to_string()))?,
            })
        }
    };
}

pass_fn!(deferred_pass, deferred);
pass_fn!(urp_gbuffer_pass, gbuffer);

impl Pass {
    /// The draw of this pipeline over `resources` and `vertices` (packed as [`Pass::vertex`]
    /// says) into `width` × `height` targets.
    pub fn draw<'a>(
        &'a self,
        resources: Vec<Bound<'a>>,
        vertices: &'a [u8],
        attributes: &'a [wgpu::VertexAttribute],
        width: u32,
        height: u32,
    ) -> Draw<'a> {
        Draw {
            label: &self.label,
            wgsl: self.wgsl,
            groups: self.groups.clone(),
            names: self.names.clone(),
            resources,
            vertex_layout: wgpu::VertexBufferLayout {
                array_stride: self.stride,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes,
            },
            vertices,
            targets: self.targets.clone(),
            width,
            height,
        }
    }

    /// The vertex attributes, for [`Pass::draw`].
    pub fn attributes(&self) -> Vec<wgpu::VertexAttribute> {
        self.vertex.iter().map(|(_, a)| *a).collect()
    }
}
