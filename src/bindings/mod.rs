//! Typed Rust for a pass, generated from its whole variant space: a variant key checked
//! against the pass's constraints, every struct a buffer binding uses as `#[repr(C)]` Rust
//! with explicit padding and `bytemuck::Pod`, and each variant's bindings, vertex inputs and
//! colour targets as plain data.
//!
//! ```
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let pass = lib.pass("deferred_reflections", "Add").unwrap();
//! let out = wgsl_variants::bindings::generate(&lib, pass, 1_000_000).unwrap();
//! assert!(out.code.contains("pub struct Key(Keywords);"));
//! assert_eq!(out.variants, 2);
//! ```
//!
//! What the module holds (the guide's `bindings.md` shows one):
//!
//! - `SHADER`, `PASS`; `Keywords`, one public field per keyword set (`bool` for `_ X`, an enum
//!   of `keywords` for a set of options); `Key::new(Keywords) -> Result<Key, KeyError>`, a
//!   `const fn` that checks `require`, `exclude` and `skip_variants` (`Key::checked` for
//!   constants: an impossible combination does not compile); `Key::choice`, `Key::index`,
//!   `Key::keywords` (the strings bake's lookup takes) and `Key::interface`.
//! - `Interface` per distinct interface of the variants: `BindingEntry`s (the facts
//!   [`reflect`](crate::reflect) lists), `VertexAttribute`s packed in one buffer, and
//!   `ColorTarget`s; `VARIANT_INTERFACE[key.index()]` picks a variant's.
//! - `structs`: one Rust struct per distinct layout of a WGSL struct across the variants (a
//!   struct whose layout differs between variants is `Name`, `Name2`, …; its doc says which
//!   variants use it), with compile-time assertions of size, alignment and every offset from
//!   naga's [`Layouter`](naga::proc::Layouter). Generated code needs `bytemuck` with the
//!   `derive` and `min_const_generics` features (padding arrays of any length are `Pod`).
//!
//! - With [`Options::wgpu`] ([`generate_with`]), the interfaces as wgpu's types too:
//!   `Interface::bind_group_layout_entries`, `Interface::vertex_buffer_layout`,
//!   `Interface::color_target_states` (checked against each output's component type) and
//!   `to_wgpu` on the plain types. The module then needs `wgpu` 30; this library does not.
//!
//! Every variant of the pass's space after `skip_variants` is composed and validated by naga,
//! once per distinct text, in parallel. Output is byte-identical across runs.

mod key;
mod layouts;
mod names;
mod structs;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::Write as _;

use rayon::prelude::*;

use crate::error::VariantError;
use crate::library::{Library, Variant};
use crate::reflect::{Binding, BindingKind};
use crate::shader::Pass;
use crate::variants::{BudgetError, Choice, Space};

pub(crate) use key::combination_index;
pub use structs::{Member, Scalar, StructDef, Ty};

/// Why a pass's bindings could not be generated.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BindingsError {
    /// No such shader or pass.
    #[error(transparent)]
    Lookup(#[from] crate::lookup::LookupError),
    /// The pass has more variants than the budget.
    #[error("{0}")]
    Budget(#[from] BudgetError),
    /// A variant does not build: generated code would describe a shader that does not exist.
    #[error("variant {} does not build", .0.variant)]
    Variant(Box<VariantError>),
    /// A buffer binding's type (or a vertex input) has no Rust equivalent here.
    #[error("`{ty}`: {reason}")]
    UnsupportedType {
        /// The WGSL type or input.
        ty: String,
        /// Why.
        reason: String,
    },
    /// naga's layouter refused a type.
    #[error("layout of variant {variant}: {error}")]
    Layout {
        /// `shader/pass {KEYWORDS}`.
        variant: String,
        /// naga's error.
        error: naga::proc::LayoutError,
    },
    /// The product of the keyword sets' sizes is too large for the table of interfaces.
    #[error("{combinations} option combinations: past the {limit} the interface table holds")]
    TooManyCombinations {
        /// The product of the sets' sizes.
        combinations: u128,
        /// The limit.
        limit: u128,
    },
}

/// The generated module and what went into it.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Generated {
    /// The Rust module (a file to `include!` inside a `mod`).
    pub code: String,
    /// Variants read (the space after `skip_variants`).
    pub variants: usize,
    /// Distinct composed texts among them (each validated once).
    pub distinct_texts: usize,
    /// Distinct struct layouts written.
    pub structs: usize,
    /// Distinct interfaces (bindings, vertex inputs, colour targets) written.
    pub interfaces: usize,
}

/// What the generator writes besides the plain-data module.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Options {
    /// Also write the interfaces as wgpu's types: `Interface::bind_group_layout_entries`,
    /// `Interface::vertex_buffer_layout`, `Interface::color_target_states` and `to_wgpu` on
    /// the plain types. The module then needs the `wgpu` crate (version 30, whose API it is
    /// written for); the library itself never depends on wgpu.
    pub wgpu: bool,
}

impl Options {
    /// The options with the wgpu types on or off.
    pub fn wgpu(mut self, on: bool) -> Options {
        self.wgpu = on;
        self
    }
}

/// WGSL storage texel formats wgpu has a `TextureFormat` for (the wgpu prelude's table).
const WGPU_STORAGE_FORMATS: &[&str] = &[
    "r8unorm",
    "r8snorm",
    "r8uint",
    "r8sint",
    "r16uint",
    "r16sint",
    "r16float",
    "rg8unorm",
    "rg8snorm",
    "rg8uint",
    "rg8sint",
    "r32uint",
    "r32sint",
    "r32float",
    "rg16uint",
    "rg16sint",
    "rg16float",
    "rgba8unorm",
    "rgba8snorm",
    "rgba8uint",
    "rgba8sint",
    "bgra8unorm",
    "rgb10a2uint",
    "rgb10a2unorm",
    "rg11b10ufloat",
    "r64uint",
    "rg32uint",
    "rg32sint",
    "rg32float",
    "rgba16uint",
    "rgba16sint",
    "rgba16float",
    "rgba32uint",
    "rgba32sint",
    "rgba32float",
    "r16unorm",
    "r16snorm",
    "rg16unorm",
    "rg16snorm",
    "rgba16unorm",
    "rgba16snorm",
];

/// Most option combinations the interface table holds (one `u16`/`u32` each).
pub(crate) const MAX_COMBINATIONS: u128 = 1 << 22;

/// What one distinct text yields.
struct Shape {
    bindings: Vec<Binding>,
    /// The type of each buffer binding, in binding order.
    buffers: Vec<Ty>,
    vertex: Vec<layouts::VertexInput>,
    targets: Vec<layouts::FragmentOutput>,
}

fn shape(lib: &Library, variant: &Variant<'_>) -> Result<Shape, BindingsError> {
    let composed = lib.compose_text(variant);
    let (module, info) =
        crate::validator::validate_for(&composed, &variant.label(), lib.pass_profile(variant.pass))
            .map_err(|_| {
                // Composed again with its line map, so the error names the original file and line.
                match lib.naga_module(variant) {
                    Err(e) => BindingsError::Variant(Box::new(e)),
                    Ok(_) => BindingsError::UnsupportedType {
                        ty: variant.label(),
                        reason: "its lean composition does not validate".into(),
                    },
                }
            })?;
    let mut layouter = naga::proc::Layouter::default();
    layouter
        .update(module.to_ctx())
        .map_err(|error| BindingsError::Layout {
            variant: variant.label(),
            error,
        })?;
    let bindings = crate::reflect::bindings(&module, &info);
    let mut buffers = Vec::new();
    for b in &bindings {
        if !matches!(
            b.kind,
            BindingKind::UniformBuffer { .. } | BindingKind::StorageBuffer { .. }
        ) {
            continue;
        }
        let var = module.global_variables.iter().map(|(_, v)| v).find(|v| {
            v.binding
                .as_ref()
                .is_some_and(|r| (r.group, r.binding) == (b.group, b.binding))
        });
        let Some(var) = var else { continue };
        let ty = match &module.types[var.ty].inner {
            naga::TypeInner::BindingArray { base, .. } => *base,
            _ => var.ty,
        };
        buffers.push(Ty::from_naga(&module, &layouter, ty)?);
    }
    Ok(Shape {
        bindings,
        buffers,
        vertex: layouts::vertex_inputs(&module)?,
        targets: layouts::fragment_outputs(&module),
    })
}

/// Distinct constants of the interface table: `PREFIX_N` per distinct literal.
#[derive(Default)]
struct Parts {
    index: HashMap<String, String>,
    counts: BTreeMap<&'static str, usize>,
    code: String,
}

impl Parts {
    /// The constant holding `literal` (`TYPE = VALUE` for slices, a `BindingEntry` literal
    /// otherwise), declared at its first use.
    fn add(&mut self, prefix: &'static str, literal: String) -> String {
        if let Some(name) = self.index.get(&literal) {
            return name.clone();
        }
        let n = self.counts.entry(prefix).or_insert(0);
        let name = format!("{prefix}_{n}");
        *n += 1;
        let decl = if prefix == "BINDING" {
            format!("BindingEntry = {literal}")
        } else {
            literal.clone()
        };
        let _ = writeln!(self.code, "    const {name}: {decl};");
        self.index.insert(literal, name.clone());
        name
    }
}

/// Which variants use a struct layout: how many, and the options each set takes among them.
struct Usage {
    variants: usize,
    options: Vec<BTreeSet<u16>>,
    bindings: BTreeSet<String>,
}

/// Generates the typed module of `pass` (see the [module docs](self)) as plain data;
/// `budget` bounds the variants read.
pub fn generate(lib: &Library, pass: &Pass, budget: u64) -> Result<Generated, BindingsError> {
    generate_with(lib, pass, budget, &Options::default())
}

/// [`generate`] with [`Options`]: with `wgpu`, the module also converts its interfaces to
/// wgpu's types.
pub fn generate_with(
    lib: &Library,
    pass: &Pass,
    budget: u64,
    options: &Options,
) -> Result<Generated, BindingsError> {
    generate_baked(lib, pass, budget, options, None)
}

/// What a `Bake::bindings` module knows of its bake: the position in the bake's `variants()`
/// of each [`Key::index`](key) (`u32::MAX`: left out), and how many variants the bake has.
pub(crate) struct BakedTable {
    /// One entry per combination of the pass.
    pub(crate) index: Vec<u32>,
    /// The length of the bake's `variants()`.
    pub(crate) variants: usize,
}

/// [`generate_with`], with the table of the bake the module is written for.
pub(crate) fn generate_baked(
    lib: &Library,
    pass: &Pass,
    budget: u64,
    options: &Options,
    baked: Option<&BakedTable>,
) -> Result<Generated, BindingsError> {
    let combinations: u128 = pass.sets.iter().map(|s| s.len() as u128).product();
    if combinations > MAX_COMBINATIONS {
        return Err(BindingsError::TooManyCombinations {
            combinations,
            limit: MAX_COMBINATIONS,
        });
    }
    let mut choices = Space::after_skip(pass).enumerate(budget)?;
    // A bake's module describes what the bake holds: `Key::new` refuses the rest, so their
    // interfaces would never be read (and building them cost minutes in a build script).
    if let Some(baked) = baked {
        choices.retain(|c| {
            let at = key::combination_index(pass, c);
            baked.index.get(at).is_some_and(|&n| n != u32::MAX)
        });
    }
    let variant = |choice: &Choice| Variant {
        pass,
        choice: choice.clone(),
    };
    // Variants often compose to the same text: hash them all, build each text once.
    let hashes: Vec<[u8; 32]> = choices
        .par_iter()
        .map(|c| *blake3::hash(lib.compose_text(&variant(c)).text.as_bytes()).as_bytes())
        .collect();
    let mut first: HashMap<[u8; 32], usize> = HashMap::new();
    let mut distinct: Vec<usize> = Vec::new();
    let text_of: Vec<usize> = hashes
        .iter()
        .enumerate()
        .map(|(i, h)| {
            *first.entry(*h).or_insert_with(|| {
                distinct.push(i);
                distinct.len() - 1
            })
        })
        .collect();
    let shapes: Vec<Shape> = distinct
        .par_iter()
        .map(|&i| shape(lib, &variant(&choices[i])))
        .collect::<Result<_, _>>()?;
    if options.wgpu {
        for b in shapes.iter().flat_map(|s| &s.bindings) {
            if let BindingKind::StorageTexture { format, .. } = &b.kind
                && !WGPU_STORAGE_FORMATS.contains(&format.as_str())
            {
                return Err(BindingsError::UnsupportedType {
                    ty: format!("texture_storage_*<{format}, …>"),
                    reason: "wgpu has no TextureFormat for it".into(),
                });
            }
        }
    }

    // Names in order of first use, inner structs before the structs that hold them.
    let mut names = structs::Names::default();
    let mut defs: Vec<StructDef> = Vec::new();
    let mut structs_of: Vec<Vec<String>> = Vec::with_capacity(shapes.len());
    for s in &shapes {
        let mut here = Vec::new();
        for ty in &s.buffers {
            ty.visit_structs(&mut |d| {
                let name = names.add(d);
                if !defs.contains(d) {
                    defs.push(d.clone());
                }
                if !here.contains(&name) {
                    here.push(name);
                }
            });
        }
        structs_of.push(here);
    }

    // Who uses each struct: the options of every set among its variants, and its bindings.
    let mut usage: BTreeMap<String, Usage> = BTreeMap::new();
    for (i, choice) in choices.iter().enumerate() {
        for name in &structs_of[text_of[i]] {
            let u = usage.entry(name.clone()).or_insert_with(|| Usage {
                variants: 0,
                options: vec![BTreeSet::new(); pass.sets.len()],
                bindings: BTreeSet::new(),
            });
            u.variants += 1;
            for (set, o) in choice.0.iter().enumerate() {
                u.options[set].insert(*o);
            }
        }
    }
    let mut wrappers = BTreeMap::new();
    for s in &shapes {
        let mut types = s.buffers.iter();
        for b in &s.bindings {
            if !matches!(
                b.kind,
                BindingKind::UniformBuffer { .. } | BindingKind::StorageBuffer { .. }
            ) {
                continue;
            }
            if let Some(Ty::Struct(d)) = types.next()
                && let Some(u) = usage.get_mut(names.get(d))
            {
                u.bindings.insert(format!(
                    "@group({}) @binding({}) `{}`",
                    b.group, b.binding, b.name
                ));
            }
        }
    }
    let all_options: Vec<BTreeSet<u16>> = (0..pass.sets.len())
        .map(|set| choices.iter().map(|c| c.0[set]).collect())
        .collect();

    // The interfaces, deduplicated by their literal, built of deduplicated parts.
    let mut parts = Parts::default();
    let mut interface_index: HashMap<String, usize> = HashMap::new();
    let mut interfaces: Vec<String> = Vec::new();
    let mut interface_of_text = Vec::with_capacity(shapes.len());
    for s in &shapes {
        let mut types = s.buffers.iter();
        let bindings: Vec<String> = s
            .bindings
            .iter()
            .map(|b| {
                let rust_type = match b.kind {
                    BindingKind::UniformBuffer { .. } | BindingKind::StorageBuffer { .. } => types
                        .next()
                        .map(|t| structs::rust_type(t, &names, &mut wrappers))
                        .unwrap_or_default(),
                    _ => String::new(),
                };
                let literal = layouts::binding_literal(b, &rust_type);
                parts.add("BINDING", literal)
            })
            .collect();
        let (vertex, stride) = layouts::vertex_literal(&s.vertex);
        let vertex = parts.add("VERTEX", format!("&[VertexAttribute] = {vertex}"));
        let targets = layouts::targets_literal(&s.targets);
        let targets = parts.add("TARGETS", format!("&[ColorTarget] = {targets}"));
        let literal = format!(
            "    Interface {{ bindings: &[{}], vertex_attributes: {vertex}, vertex_stride: {stride}, color_targets: {targets} }},\n",
            bindings.join(", ")
        );
        let n = interfaces.len();
        let index = *interface_index.entry(literal.clone()).or_insert(n);
        if index == n {
            interfaces.push(literal);
        }
        interface_of_text.push(index);
    }
    let mut table = vec![u32::MAX; combinations as usize];
    for (i, choice) in choices.iter().enumerate() {
        let index = key::combination_index(pass, choice);
        table[index] = interface_of_text[text_of[i]] as u32;
    }

    // The module.
    let fields = key::fields(pass);
    let label = format!("{}/{}", pass.shader, pass.name);
    let mut code = String::new();
    let _ = writeln!(
        code,
        "// @generated by wgsl-variants {} (wgsl_variants::bindings): typed Rust for `{label}`,",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(
        code,
        "// from its {} {}variants ({} distinct texts). Do not edit. Include it in a module:",
        choices.len(),
        if baked.is_some() { "baked " } else { "" },
        shapes.len()
    );
    let _ = writeln!(
        code,
        "//     #[allow(dead_code)] mod deferred {{ include!(\"deferred.rs\"); }}"
    );
    if options.wgpu {
        let _ = writeln!(
            code,
            "// It needs `bytemuck` with the `derive` and `min_const_generics` features, and `wgpu` 30."
        );
    } else {
        let _ = writeln!(
            code,
            "// It needs `bytemuck` with the `derive` and `min_const_generics` features."
        );
    }
    let _ = writeln!(code);
    let _ = writeln!(code, "/// The shader.");
    let _ = writeln!(code, "pub const SHADER: &str = {:?};", pass.shader);
    let _ = writeln!(code, "/// The pass.");
    let _ = writeln!(code, "pub const PASS: &str = {:?};", pass.name);
    let _ = writeln!(code);
    key::write(&mut code, pass, &fields, baked.is_some());
    let _ = writeln!(code);
    code.push_str(PRELUDE);
    let _ = writeln!(code);
    if options.wgpu {
        code.push_str(PRELUDE_WGPU);
        let _ = writeln!(code);
    }
    let wide = interfaces.len() >= usize::from(u16::MAX);
    let (int, none) = if wide {
        ("u32", u32::MAX)
    } else {
        ("u16", u32::from(u16::MAX))
    };
    let _ = writeln!(code, "pub use tables::{{INTERFACES, VARIANT_INTERFACE}};");
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "/// The data behind [`Key::interface`], one line per distinct binding, vertex layout, list"
    );
    let _ = writeln!(code, "/// of colour targets and interface.");
    let _ = writeln!(code, "#[rustfmt::skip]");
    let _ = writeln!(code, "mod tables {{");
    let _ = writeln!(code, "    use super::*;");
    let _ = writeln!(code);
    code.push_str(&parts.code);
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "    /// The distinct interfaces of the pass's variants; [`Key::interface`] picks one."
    );
    let _ = writeln!(
        code,
        "    pub static INTERFACES: [Interface; {}] = [",
        interfaces.len()
    );
    for i in &interfaces {
        let _ = write!(code, "    {i}");
    }
    let _ = writeln!(code, "    ];");
    let _ = writeln!(code);
    let _ = writeln!(
        code,
        "    /// The index in [`INTERFACES`] of each [`Key::index`] (`{int}::MAX`: no variant)."
    );
    let _ = writeln!(
        code,
        "    pub static VARIANT_INTERFACE: [{int}; {}] = [",
        table.len()
    );
    for row in table.chunks(24) {
        let row: Vec<String> = row
            .iter()
            .map(|&v| if v == u32::MAX { none } else { v }.to_string())
            .collect();
        let _ = writeln!(code, "        {},", row.join(", "));
    }
    let _ = writeln!(code, "    ];");
    if let Some(baked) = baked {
        let _ = writeln!(code);
        let _ = writeln!(
            code,
            "    /// The length of the bake's `variants()`, which [`BAKED`] indexes."
        );
        let _ = writeln!(
            code,
            "    pub const BAKED_VARIANTS: usize = {};",
            baked.variants
        );
        let _ = writeln!(
            code,
            "    /// The position in the bake's `variants()` of each [`Key::index`] (`u32::MAX`: not baked)."
        );
        // A `const`, not a `static`: `Key::new` is a `const fn` and reads it (so clippy's
        // advice to make a large array a `static` cannot be followed).
        let _ = writeln!(code, "    #[allow(clippy::large_const_arrays)]");
        let _ = writeln!(
            code,
            "    pub const BAKED: [u32; {}] = [",
            baked.index.len()
        );
        for row in baked.index.chunks(16) {
            let row: Vec<String> = row.iter().map(u32::to_string).collect();
            let _ = writeln!(code, "        {},", row.join(", "));
        }
        let _ = writeln!(code, "    ];");
    }
    let _ = writeln!(code, "}}");
    let _ = writeln!(code);

    // The structs, inner ones first.
    let mut body = String::new();
    for d in &defs {
        let name = names.get(d);
        let u = &usage[name];
        let mut doc = String::new();
        let _ = writeln!(
            doc,
            "/// WGSL `{}`: {} bytes, aligned to {}.",
            d.name, d.size, d.align
        );
        let _ = writeln!(
            doc,
            "///\n/// Used by {} of {} variants{}.",
            u.variants,
            choices.len(),
            describe(pass, &u.options, &all_options)
        );
        if !u.bindings.is_empty() {
            let list: Vec<&str> = u.bindings.iter().map(String::as_str).collect();
            let _ = writeln!(doc, "/// Bound at {}.", list.join(", "));
        }
        body.push_str(&structs::write_struct(d, &doc, &names, &mut wrappers));
        body.push('\n');
    }
    for w in wrappers.values() {
        body.push_str(w);
        body.push('\n');
    }
    let _ = writeln!(
        code,
        "/// The types of the pass's buffers, one per distinct layout, with WGSL's padding."
    );
    if body.is_empty() {
        let _ = writeln!(code, "pub mod structs {{}}");
    } else {
        let _ = writeln!(code, "pub mod structs {{");
        for line in body.trim_end().lines() {
            if line.is_empty() {
                code.push('\n');
            } else {
                let _ = writeln!(code, "    {line}");
            }
        }
        let _ = writeln!(code, "}}");
    }
    Ok(Generated {
        code,
        variants: choices.len(),
        distinct_texts: shapes.len(),
        structs: defs.len(),
        interfaces: interfaces.len(),
    })
}

/// `: those with `A` and without `B`` — the options a struct's variants take in each set
/// where they take fewer than the pass's variants do.
fn describe(pass: &Pass, used: &[BTreeSet<u16>], all: &[BTreeSet<u16>]) -> String {
    let mut parts = Vec::new();
    for (set, (u, a)) in used.iter().zip(all).enumerate() {
        if u == a {
            continue;
        }
        let options = &pass.sets[set].options;
        let names: Vec<String> = u
            .iter()
            .map(|&o| match &options[o as usize] {
                Some(k) => format!("with `{k}`"),
                None => {
                    let keywords: Vec<&str> = pass.sets[set].keywords().collect();
                    format!("without `{}`", keywords.join("`/`"))
                }
            })
            .collect();
        parts.push(names.join(" or "));
    }
    if parts.is_empty() {
        String::new()
    } else {
        format!(": those {}", parts.join(" and "))
    }
}

const PRELUDE: &str = include_str!("prelude.rs");
const PRELUDE_WGPU: &str = include_str!("prelude_wgpu.rs");

impl Library {
    /// The typed Rust module of `shader/pass` ([`bindings`](crate::bindings)): variant key,
    /// buffer structs and interfaces, from every variant after `skip_variants` (at most
    /// `budget`).
    pub fn bindings(
        &self,
        shader: &str,
        pass: &str,
        budget: u64,
    ) -> Result<Generated, BindingsError> {
        generate(self, self.pass(shader, pass)?, budget)
    }
}
