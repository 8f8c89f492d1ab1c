/// What a variant's pipeline needs from the host: its bindings, vertex inputs and colour
/// targets (plain data, the same facts `wgsl-variants reflect` lists).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Interface {
    /// The bindings the entry points use, sorted by (group, binding).
    pub bindings: &'static [BindingEntry],
    /// The vertex entry point's inputs by location, packed in one buffer in that order.
    pub vertex_attributes: &'static [VertexAttribute],
    /// Bytes per vertex of that buffer (0 without vertex inputs).
    pub vertex_stride: u64,
    /// The fragment entry point's outputs by location: one colour target each.
    pub color_targets: &'static [ColorTarget],
}

/// One `@group/@binding` resource a variant uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BindingEntry {
    /// `@group`.
    pub group: u32,
    /// `@binding`.
    pub binding: u32,
    /// The variable's name.
    pub name: &'static str,
    /// What is bound.
    pub kind: BindingKind,
    /// The stages whose entry points use it.
    pub visibility: &'static [Stage],
    /// `binding_array<…, N>`: `Some(N)`; an unbounded binding array: `Some(0)`.
    pub count: Option<u32>,
}

/// A shader stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// `@vertex`.
    Vertex,
    /// `@fragment`.
    Fragment,
    /// `@compute`.
    Compute,
    /// A task shader.
    Task,
    /// A mesh shader.
    Mesh,
    /// A ray-tracing stage.
    RayTracing,
}

/// What is bound at a slot (WebGPU's binding layout types).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BindingKind {
    /// `var<uniform>`.
    UniformBuffer {
        /// Minimum binding size in bytes.
        size: u64,
        /// The Rust type of its contents, in `structs` (or a plain array).
        rust_type: &'static str,
    },
    /// `var<storage, …>`.
    StorageBuffer {
        /// Minimum binding size in bytes (a runtime-sized array: one element).
        size: u64,
        /// `var<storage, read>`.
        read_only: bool,
        /// The Rust type of its contents, in `structs` (or a plain array).
        rust_type: &'static str,
    },
    /// A sampled texture.
    Texture {
        /// Sample type.
        sample_type: SampleType,
        /// View dimension.
        dimension: Dimension,
        /// `texture_multisampled_*`.
        multisampled: bool,
    },
    /// A storage texture.
    StorageTexture {
        /// Texel format, as WGSL spells it (`rgba8unorm`).
        format: &'static str,
        /// Access mode.
        access: TextureAccess,
        /// View dimension.
        dimension: Dimension,
    },
    /// A sampler.
    Sampler {
        /// `sampler_comparison`.
        comparison: bool,
    },
    /// `texture_external`.
    ExternalTexture,
    /// A ray-tracing acceleration structure.
    AccelerationStructure,
}

/// The sample type of a sampled texture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SampleType {
    /// `texture_*<f32>` sampled with a sampler: a filterable format.
    Float,
    /// `texture_*<f32>` that is only loaded: any float format.
    UnfilterableFloat,
    /// `texture_depth_*`.
    Depth,
    /// `texture_*<i32>`.
    Sint,
    /// `texture_*<u32>`.
    Uint,
}

/// A texture view dimension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Dimension {
    /// 1D.
    D1,
    /// 2D.
    D2,
    /// 2D array.
    D2Array,
    /// 3D.
    D3,
    /// Cube.
    Cube,
    /// Cube array.
    CubeArray,
}

/// How a storage texture may be accessed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TextureAccess {
    /// `read`.
    Read,
    /// `write`.
    Write,
    /// `read_write`.
    ReadWrite,
    /// Atomic access.
    Atomic,
}

/// One vertex input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VertexAttribute {
    /// `@location`.
    pub location: u32,
    /// The argument's or member's name.
    pub name: &'static str,
    /// Its format (wgpu's names).
    pub format: VertexFormat,
    /// Its offset in the packed vertex.
    pub offset: u64,
}

/// A vertex attribute's format, named as wgpu names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)]
pub enum VertexFormat {
    Float16x2,
    Float16x4,
    Float32,
    Float32x2,
    Float32x3,
    Float32x4,
    Float64,
    Float64x2,
    Float64x3,
    Float64x4,
    Sint32,
    Sint32x2,
    Sint32x3,
    Sint32x4,
    Uint32,
    Uint32x2,
    Uint32x3,
    Uint32x4,
}

/// One fragment output: the colour target at `location`. The shader fixes the component type
/// and count, not the texture format (an `f32` output fits `Rgba8Unorm` or `Rgba16Float`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ColorTarget {
    /// `@location`.
    pub location: u32,
    /// The output's name (the result struct's member; `""` for a bare result).
    pub name: &'static str,
    /// Components written (1 to 4).
    pub components: u32,
    /// The component type: the target format's sample type must match.
    pub kind: ColorKind,
}

/// A colour target's component type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ColorKind {
    /// `f32` (`f16`): a float, unorm or snorm format.
    Float,
    /// `i32`: a sint format.
    Sint,
    /// `u32`: a uint format.
    Uint,
}
