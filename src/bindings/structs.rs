//! Host-shareable WGSL types as Rust: the layout of a buffer binding's type, read from naga's
//! IR and [`naga::proc::Layouter`], and the `#[repr(C)]` Rust that reproduces it byte for byte
//! (explicit padding fields, `bytemuck::Pod`, compile-time assertions of size, alignment and
//! every field's offset).
//!
//! Rust's `repr(C)` and WGSL's layout agree on field order but not on alignment: a `vec3<f32>`
//! is 12 bytes aligned to 16 in WGSL, `[f32; 3]` is aligned to 4 in Rust. So every gap naga's
//! offsets leave becomes a named `_padN: [u8; N]` field, an array whose stride exceeds its
//! element becomes an array of a padded wrapper, a `matCx3` column takes four scalars, and
//! each struct carries naga's alignment in `repr(C, align(N))`. With no implicit padding left,
//! `bytemuck` can derive `Pod`.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use naga::proc::Layouter;

use super::BindingsError;

/// A host-shareable type as laid out by naga (sizes and alignments in bytes).
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Ty {
    /// `f32`, `i32`, `u32`, `f16` (as `u16` bits), `f64`, …; atomics are their scalar.
    Scalar(Scalar),
    /// `vecN<S>`.
    Vector {
        /// The component.
        scalar: Scalar,
        /// N.
        size: u32,
    },
    /// `matCxR<S>`: C columns, each a `vecR<S>` at `column_stride` bytes.
    Matrix {
        /// The component.
        scalar: Scalar,
        /// C.
        columns: u32,
        /// R.
        rows: u32,
        /// Bytes from one column to the next (16 for `vec3<f32>` columns).
        column_stride: u32,
    },
    /// `array<E, N>` (`len: Some(N)`) or a runtime-sized `array<E>` (`len: None`).
    Array {
        /// The element.
        element: Box<Ty>,
        /// N, or `None` for a runtime-sized array.
        len: Option<u32>,
        /// Bytes from one element to the next.
        stride: u32,
    },
    /// A struct.
    Struct(Box<StructDef>),
}

/// A scalar of a host-shareable type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Scalar {
    /// The Rust type holding its bits: `f32`, `i32`, `u32`, `u16` (for `f16`), `f64`, ….
    pub rust: &'static str,
    /// Its size in bytes.
    pub width: u32,
}

/// A WGSL struct with naga's layout.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct StructDef {
    /// The WGSL name.
    pub name: String,
    /// Size in bytes (for a struct ending in a runtime-sized array: the offset of that array).
    pub size: u32,
    /// Alignment in bytes.
    pub align: u32,
    /// Members in declaration order.
    pub members: Vec<Member>,
}

/// A member of a [`StructDef`].
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Member {
    /// The WGSL name.
    pub name: String,
    /// Offset from the start of the struct, from naga's IR.
    pub offset: u32,
    /// Its type.
    pub ty: Ty,
}

impl Ty {
    /// Reads a host-shareable type from naga's IR; `layouter` must be updated for `module`.
    pub fn from_naga(
        module: &naga::Module,
        layouter: &Layouter,
        ty: naga::Handle<naga::Type>,
    ) -> Result<Ty, BindingsError> {
        let unsupported = |what: &str| BindingsError::UnsupportedType {
            ty: module.types[ty]
                .name
                .clone()
                .unwrap_or_else(|| what.to_string()),
            reason: format!("{what} has no host-shareable layout"),
        };
        Ok(match &module.types[ty].inner {
            naga::TypeInner::Scalar(s) | naga::TypeInner::Atomic(s) => {
                Ty::Scalar(scalar(*s).ok_or_else(|| unsupported("bool"))?)
            }
            naga::TypeInner::Vector { size, scalar: s } => Ty::Vector {
                scalar: scalar(*s).ok_or_else(|| unsupported("a vector of bool"))?,
                size: *size as u32,
            },
            naga::TypeInner::Matrix {
                columns,
                rows,
                scalar: s,
            } => {
                let s = scalar(*s).ok_or_else(|| unsupported("a matrix of bool"))?;
                // A column is aligned like `vecR`: 2 components → 2, 3 or 4 → 4.
                let lanes = if *rows as u32 == 2 { 2 } else { 4 };
                Ty::Matrix {
                    scalar: s,
                    columns: *columns as u32,
                    rows: *rows as u32,
                    column_stride: lanes * s.width,
                }
            }
            naga::TypeInner::Array { base, size, stride } => Ty::Array {
                element: Box::new(Ty::from_naga(module, layouter, *base)?),
                len: match size {
                    naga::ArraySize::Constant(n) => Some(n.get()),
                    naga::ArraySize::Dynamic => None,
                    naga::ArraySize::Pending(_) => {
                        return Err(unsupported("an array sized by an override"));
                    }
                },
                stride: *stride,
            },
            naga::TypeInner::Struct { members, span } => {
                let layout = layouter[ty];
                let mut out = Vec::with_capacity(members.len());
                for m in members {
                    out.push(Member {
                        name: m.name.clone().unwrap_or_default(),
                        offset: m.offset,
                        ty: Ty::from_naga(module, layouter, m.ty)?,
                    });
                }
                // A struct ending in a runtime-sized array is its head: the array is a tail.
                let size = match out.last() {
                    Some(Member {
                        ty: Ty::Array { len: None, .. },
                        offset,
                        ..
                    }) => *offset,
                    _ => *span,
                };
                Ty::Struct(Box::new(StructDef {
                    name: module.types[ty].name.clone().unwrap_or_default(),
                    size,
                    align: layout.alignment.round_up(1),
                    members: out,
                }))
            }
            _ => return Err(unsupported("this type")),
        })
    }

    /// Size in bytes, as naga lays it out (a runtime-sized array: one stride).
    pub fn size(&self) -> u32 {
        match self {
            Ty::Scalar(s) => s.width,
            Ty::Vector { scalar, size } => scalar.width * size,
            Ty::Matrix {
                columns,
                column_stride,
                ..
            } => columns * column_stride,
            Ty::Array { len, stride, .. } => len.unwrap_or(1) * stride,
            Ty::Struct(s) => s.size,
        }
    }

    /// Alignment in bytes, as naga lays it out.
    pub fn align(&self) -> u32 {
        match self {
            Ty::Scalar(s) => s.width,
            Ty::Vector { scalar, size } => scalar.width * if *size == 2 { 2 } else { 4 },
            Ty::Matrix { column_stride, .. } => *column_stride,
            Ty::Array { element, .. } => element.align(),
            Ty::Struct(s) => s.align,
        }
    }

    /// Calls `f` on every struct this type holds, inner ones first.
    pub fn visit_structs<'t>(&'t self, f: &mut impl FnMut(&'t StructDef)) {
        match self {
            Ty::Array { element, .. } => element.visit_structs(f),
            Ty::Struct(s) => {
                for m in &s.members {
                    m.ty.visit_structs(f);
                }
                f(s);
            }
            _ => {}
        }
    }
}

fn scalar(s: naga::Scalar) -> Option<Scalar> {
    let rust = match (s.kind, s.width) {
        (naga::ScalarKind::Float, 2) => "u16",
        (naga::ScalarKind::Float, 4) => "f32",
        (naga::ScalarKind::Float, 8) => "f64",
        (naga::ScalarKind::Sint, 4) => "i32",
        (naga::ScalarKind::Sint, 8) => "i64",
        (naga::ScalarKind::Uint, 4) => "u32",
        (naga::ScalarKind::Uint, 8) => "u64",
        _ => return None,
    };
    Some(Scalar {
        rust,
        width: u32::from(s.width),
    })
}

/// Rust names of the distinct structs of a pass: the WGSL name for the first layout of that
/// name met, `Name2`, `Name3`, … for the next ones.
#[derive(Debug, Default)]
pub struct Names {
    names: BTreeMap<StructDef, String>,
    per_wgsl_name: BTreeMap<String, usize>,
}

impl Names {
    /// Names `def` if it has no name yet; returns its name.
    pub fn add(&mut self, def: &StructDef) -> String {
        if let Some(name) = self.names.get(def) {
            return name.clone();
        }
        let base = super::names::camel(&def.name);
        let n = self.per_wgsl_name.entry(base.clone()).or_insert(0);
        *n += 1;
        let name = if *n == 1 { base } else { format!("{base}{n}") };
        self.names.insert(def.clone(), name.clone());
        name
    }

    /// The name of a struct added before.
    pub fn get(&self, def: &StructDef) -> &str {
        &self.names[def]
    }
}

/// The Rust spelling of a type, and the padded wrappers that spelling needs (name → code),
/// collected into `wrappers`.
pub fn rust_type(ty: &Ty, names: &Names, wrappers: &mut BTreeMap<String, String>) -> String {
    match ty {
        Ty::Scalar(s) => s.rust.to_string(),
        Ty::Vector { scalar, size } => format!("[{}; {size}]", scalar.rust),
        Ty::Matrix {
            scalar,
            columns,
            column_stride,
            ..
        } => format!(
            "[[{}; {}]; {columns}]",
            scalar.rust,
            column_stride / scalar.width
        ),
        Ty::Array {
            element,
            len,
            stride,
        } => {
            let element = element_type(element, *stride, names, wrappers);
            match len {
                Some(n) => format!("[{element}; {n}]"),
                // Only reached for a runtime-sized array used as a binding's whole type: its
                // element is what the host writes, one after another.
                None => element,
            }
        }
        Ty::Struct(s) => names.get(s).to_string(),
    }
}

/// Bytes a type's Rust spelling takes (its WGSL size, except a vector's or an element's
/// trailing padding, which the wrapper or the next field holds).
fn rust_size(ty: &Ty) -> u32 {
    ty.size()
}

/// The Rust element type of an array with `stride`: the element itself when it fills the
/// stride, else a wrapper `XStrideN` that adds the padding.
pub fn element_type(
    element: &Ty,
    stride: u32,
    names: &Names,
    wrappers: &mut BTreeMap<String, String>,
) -> String {
    let inner = rust_type(element, names, wrappers);
    let size = rust_size(element);
    if size == stride {
        return inner;
    }
    let name = format!("{}Stride{stride}", type_ident(element, names));
    if !wrappers.contains_key(&name) {
        let mut code = String::new();
        let align = element.align();
        let pad = stride - size;
        let _ = writeln!(
            code,
            "/// One element of an array of `{}` with a stride of {stride} bytes: the value and",
            wgsl_name(element)
        );
        let _ = writeln!(code, "/// {pad} bytes of padding.");
        let _ = writeln!(code, "#[repr(C, align({align}))]");
        let _ = writeln!(
            code,
            "#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]"
        );
        let _ = writeln!(code, "pub struct {name} {{");
        let _ = writeln!(code, "    /// The element.");
        let _ = writeln!(code, "    pub value: {inner},");
        let _ = writeln!(code, "    /// Padding up to the array's stride.");
        let _ = writeln!(code, "    pub _pad: [u8; {pad}],");
        let _ = writeln!(code, "}}");
        let _ = writeln!(code);
        assertions(
            &mut code,
            &name,
            stride,
            align,
            &[("value", 0), ("_pad", size)],
        );
        wrappers.insert(name.clone(), code);
    }
    name
}

/// A Rust identifier fragment for a type: `F32`, `Vec3F32`, `Mat3x3F32`, a struct's name.
fn type_ident(ty: &Ty, names: &Names) -> String {
    let scalar = |s: &Scalar| {
        let mut c = s.rust.chars();
        c.next()
            .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
            .unwrap_or_default()
    };
    match ty {
        Ty::Scalar(s) => scalar(s),
        Ty::Vector { scalar: s, size } => format!("Vec{size}{}", scalar(s)),
        Ty::Matrix {
            scalar: s,
            columns,
            rows,
            ..
        } => format!("Mat{columns}x{rows}{}", scalar(s)),
        Ty::Array { element, len, .. } => {
            format!("Array{}{}", len.unwrap_or(0), type_ident(element, names))
        }
        Ty::Struct(s) => names.get(s).to_string(),
    }
}

/// The WGSL spelling of a type, for doc comments.
pub fn wgsl_name(ty: &Ty) -> String {
    let scalar = |s: &Scalar| match s.rust {
        "u16" => "f16",
        other => other,
    };
    match ty {
        Ty::Scalar(s) => scalar(s).to_string(),
        Ty::Vector { scalar: s, size } => format!("vec{size}<{}>", scalar(s)),
        Ty::Matrix {
            scalar: s,
            columns,
            rows,
            ..
        } => format!("mat{columns}x{rows}<{}>", scalar(s)),
        Ty::Array { element, len, .. } => match len {
            Some(n) => format!("array<{}, {n}>", wgsl_name(element)),
            None => format!("array<{}>", wgsl_name(element)),
        },
        Ty::Struct(s) => s.name.clone(),
    }
}

/// Writes the compile-time assertions of a type's size, alignment and field offsets.
fn assertions(code: &mut String, name: &str, size: u32, align: u32, fields: &[(&str, u32)]) {
    let _ = writeln!(code, "const _: () = {{");
    let _ = writeln!(
        code,
        "    assert!(core::mem::size_of::<{name}>() == {size});"
    );
    let _ = writeln!(
        code,
        "    assert!(core::mem::align_of::<{name}>() == {align});"
    );
    for (field, offset) in fields {
        let _ = writeln!(
            code,
            "    assert!(core::mem::offset_of!({name}, {field}) == {offset});"
        );
    }
    let _ = writeln!(code, "}};");
}

/// The Rust code of one struct: doc comment (`doc`, already `///` lines), definition with
/// explicit padding, and assertions. Nested structs and wrappers are written by the caller.
pub fn write_struct(
    def: &StructDef,
    doc: &str,
    names: &Names,
    wrappers: &mut BTreeMap<String, String>,
) -> String {
    let name = names.get(def);
    let mut fields: Vec<(String, String, String, u32)> = Vec::new(); // name, type, doc, offset
    let mut cursor = 0;
    let mut pads = 0;
    let mut tail = None;
    for m in &def.members {
        if let Ty::Array {
            element,
            len: None,
            stride,
        } = &m.ty
        {
            tail = Some((element, *stride, m));
            break;
        }
        if m.offset > cursor {
            fields.push((
                format!("_pad{pads}"),
                format!("[u8; {}]", m.offset - cursor),
                "Padding (WGSL alignment).".into(),
                cursor,
            ));
            pads += 1;
        }
        let ty = rust_type(&m.ty, names, wrappers);
        let mut field_doc = format!("`{}: {}`", m.name, wgsl_name(&m.ty));
        if let Ty::Matrix {
            rows: 3,
            columns,
            scalar,
            ..
        } = &m.ty
        {
            let _ = write!(
                field_doc,
                ": {columns} columns of 4 `{}`, the 4th of each is padding",
                scalar.rust
            );
        }
        fields.push((super::names::field_name(&m.name), ty, field_doc, m.offset));
        cursor = m.offset + rust_size(&m.ty);
    }
    if def.size > cursor {
        fields.push((
            format!("_pad{pads}"),
            format!("[u8; {}]", def.size - cursor),
            "Padding up to the struct's size (WGSL alignment).".into(),
            cursor,
        ));
    }
    // A head of a runtime-sized array keeps naga's alignment only when its size allows it:
    // `repr(align)` would otherwise add padding Rust does not show and `Pod` refuses.
    let align = if def.size.is_multiple_of(def.align) {
        def.align
    } else {
        1 << def.size.trailing_zeros().min(def.align.trailing_zeros())
    };
    let mut code = String::new();
    code.push_str(doc);
    let _ = writeln!(code, "#[repr(C, align({align}))]");
    let _ = writeln!(
        code,
        "#[derive(Clone, Copy, Debug, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]"
    );
    let _ = writeln!(code, "pub struct {name} {{");
    for (field, ty, doc, _) in &fields {
        let _ = writeln!(code, "    /// {doc}");
        let _ = writeln!(code, "    pub {field}: {ty},");
    }
    let _ = writeln!(code, "}}");
    let _ = writeln!(code);
    let offsets: Vec<(&str, u32)> = fields.iter().map(|(f, _, _, o)| (f.as_str(), *o)).collect();
    if let Some((element, stride, member)) = tail {
        let element_ty = element_type(element, stride, names, wrappers);
        let _ = writeln!(
            code,
            "/// The element of `{name}`'s runtime-sized array `{}`: the buffer holds a `{name}`,",
            member.name
        );
        let _ = writeln!(
            code,
            "/// then any number of these, each {stride} bytes from the last, from byte {}.",
            member.offset
        );
        let _ = writeln!(code, "pub type {name}Element = {element_ty};");
        let _ = writeln!(code);
    }
    assertions(&mut code, name, def.size, align, &offsets);
    code
}
