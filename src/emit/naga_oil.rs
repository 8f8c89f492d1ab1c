//! Modules in naga_oil's dialect, so Bevy users can register them with
//! `Composer::add_composable_module`.
//!
//! Each module becomes one naga_oil module:
//!
//! - `#define_import_path ROOT::dir::name` (the module path with `/` as `::`, under an
//!   optional root);
//! - one `#import ROOT::dir::other::{a, b}` per module that declares names this module uses.
//!   Our `#import` is textual and transitive; naga_oil's imports name items and are not, so
//!   the items are found by scanning the module for identifiers that some module of its import
//!   closure declares at top level (in any `#if` branch);
//! - conditions become `#ifdef` / `#ifndef` / `#if NAME op VALUE` / `#else` / `#endif`.
//!   naga_oil has no `&&`, `||`, `!` or `#elif` on arbitrary expressions, so conditions are
//!   translated to nested directives, duplicating a branch's text where needed (`A || B`:
//!   `#ifdef A` … `#else` `#ifdef B` … ). `defined(X)` and a bare `X` become `#ifdef X`
//!   (pass the keywords that are on as shader defs; a keyword that is off is left out), and
//!   `X op N` becomes `#if X op N`. naga_oil fails on an unknown def in `#if X op N` (even
//!   inside an inactive block), so a valued define must always be given, as
//!   `ShaderDefValue::Int`/`UInt` — `0` where our dialect would leave it undefined.
//!
//! - naga_oil requires a composable module to come back unchanged from naga's WGSL writer,
//!   struct member names included, and naga renames members that end in a digit or are
//!   reserved words (`rt0` becomes `rt0_`). Such members are renamed the same way in every
//!   exported module — declarations, member accesses and any other use of the identifier —
//!   so the G-buffer output's members are `rt0_` … `rt3_` in the naga_oil export.
//!
//! What naga_oil cannot express fails with [`ExportError::Inexpressible`]: `#define` /
//! `#undef` inside a module (naga_oil allows them only at the top of a top-level shader),
//! comparisons between two names or with arithmetic, and module paths that are not
//! `::`-paths of identifiers. Shader files (`#shader`) are not modules and are refused.
//!
//! ```
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let modules = wgsl_variants::emit::naga_oil::export(&lib, "deferred/gbuffer", Some("wv")).unwrap();
//! assert_eq!(modules[0].import_path, "wv::deferred::ldr"); // imports first
//! let gbuffer = &modules[1].source;
//! assert!(gbuffer.contains("#define_import_path wv::deferred::gbuffer"));
//! assert!(gbuffer.contains("#import wv::deferred::ldr::{ldr_encode}"));
//! assert!(gbuffer.contains("#ifdef UNITY_HDR_ON"));
//! ```

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use crate::library::Library;
use crate::preprocess::expr::{BinOp, Expr};
use crate::preprocess::tree::{Conditional, Node};

use super::export::{ExportError, dependency_order, import_closure, library_order, module_index};
use super::scan::{Scan, scan_library};

/// One module in naga_oil's dialect (serialized as `module`, `import_path` and `source`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct NagaOilModule {
    /// Our module path (`deferred/gbuffer`).
    #[serde(rename = "module")]
    pub path: String,
    /// Its naga_oil import path (`ROOT::deferred::gbuffer`).
    pub import_path: String,
    /// The source, starting with `#define_import_path`.
    pub source: String,
}

fn is_ident(s: &str) -> bool {
    !s.is_empty()
        && !s.starts_with(|c: char| c.is_ascii_digit())
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The naga_oil import path of a module path under `root`.
pub(crate) fn import_path(path: &str, root: Option<&str>) -> Result<String, ExportError> {
    let mut segments: Vec<&str> = Vec::new();
    if let Some(r) = root {
        segments.extend(r.split("::"));
    }
    segments.extend(path.split('/'));
    if let Some(bad) = segments.iter().find(|s| !is_ident(s)) {
        return Err(ExportError::Inexpressible {
            module: path.to_string(),
            message: format!(
                "`{bad}` cannot be a segment of a naga_oil import path (identifiers only)"
            ),
        });
    }
    Ok(segments.join("::"))
}

/// Exports a module and every module it imports (imports first, the module last).
pub fn export(
    lib: &Library,
    path: &str,
    root: Option<&str>,
) -> Result<Vec<NagaOilModule>, ExportError> {
    let index = module_index(lib, path)?;
    let scans = scan_library(lib);
    let renames = member_renames(lib, &scans)?;
    let mut order = Vec::new();
    dependency_order(lib, index, &mut order);
    order
        .into_iter()
        .map(|m| export_one(lib, m, root, &scans, &renames))
        .collect()
}

/// Exports every module of the library (shader files excluded), each after its imports.
pub fn export_all(lib: &Library, root: Option<&str>) -> Result<Vec<NagaOilModule>, ExportError> {
    let scans = scan_library(lib);
    let renames = member_renames(lib, &scans)?;
    library_order(lib)
        .into_iter()
        .map(|m| export_one(lib, m, root, &scans, &renames))
        .collect()
}

/// The name naga's WGSL writer gives a struct member (its `Namer` in a struct's namespace:
/// a trailing digit or a reserved word gets a `_`), or `None` for names it would rewrite in
/// ways not mirrored here.
fn naga_member_name(name: &str) -> Option<String> {
    let base = name.trim_end_matches('_');
    if base.is_empty()
        || base.contains("__")
        || base.starts_with("_naga")
        || !base.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    {
        return None;
    }
    let mut out = base.to_string();
    if base.ends_with(|c: char| c.is_ascii_digit())
        || naga::keywords::wgsl::RESERVED.contains(&base)
    {
        out.push('_');
    }
    Some(out)
}

/// naga_oil requires composable modules to survive naga's WGSL write-back unchanged, struct
/// member names included; members that naga renames (`rt0` becomes `rt0_`) are renamed the
/// same way here, everywhere in the library (declarations, member accesses and any other use
/// of the identifier), so the exported modules keep their meaning.
fn member_renames(lib: &Library, scans: &[Scan]) -> Result<BTreeMap<String, String>, ExportError> {
    let mut everything: BTreeSet<&str> = BTreeSet::new();
    for scan in scans {
        everything.extend(scan.used.iter().map(String::as_str));
        everything.extend(scan.declared.iter().map(String::as_str));
        everything.extend(scan.members.iter().map(String::as_str));
    }
    let mut renames = BTreeMap::new();
    for (index, scan) in scans.iter().enumerate() {
        for member in &scan.members {
            let fail = |message: String| ExportError::Inexpressible {
                module: lib.module_paths()[index].clone(),
                message,
            };
            let Some(new) = naga_member_name(member) else {
                return Err(fail(format!(
                    "struct member `{member}` would be renamed by naga's WGSL writer, which naga_oil rejects"
                )));
            };
            if new == *member {
                continue;
            }
            if everything.contains(new.as_str()) {
                return Err(fail(format!(
                    "struct member `{member}` must be renamed to `{new}` for naga_oil (naga's WGSL writer renames it), but `{new}` is already used"
                )));
            }
            renames.insert(member.clone(), new);
        }
    }
    Ok(renames)
}

fn export_one(
    lib: &Library,
    module: usize,
    root: Option<&str>,
    scans: &[Scan],
    renames: &BTreeMap<String, String>,
) -> Result<NagaOilModule, ExportError> {
    let graph = lib.module_graph();
    let path = lib.module_paths()[module].clone();
    let parsed = &graph.modules[module];
    let own = &scans[module];
    // Which module of the closure declares each used name (the first in import order).
    let mut imports: BTreeMap<usize, BTreeSet<&str>> = BTreeMap::new();
    let closure = import_closure(lib, module);
    for name in own.used.difference(&own.declared) {
        if let Some(&m) = closure[1..]
            .iter()
            .find(|&&m| scans[m].declared.contains(name))
        {
            imports.entry(m).or_default().insert(name);
        }
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// {path}, exported by wgsl-variants {} in naga_oil's dialect.",
        env!("CARGO_PKG_VERSION")
    );
    let _ = writeln!(out, "#define_import_path {}", import_path(&path, root)?);
    // In closure order, so the output does not depend on module ids.
    for m in closure.iter().filter(|m| imports.contains_key(m)) {
        let items: Vec<&str> = imports[m]
            .iter()
            .map(|n| renames.get(*n).map_or(*n, String::as_str))
            .collect();
        let _ = writeln!(
            out,
            "#import {}::{{{}}}",
            import_path(&lib.module_paths()[*m], root)?,
            items.join(", ")
        );
    }
    let text = graph.files.text(parsed.file);
    let body = Translator {
        path: &path,
        text,
        lines: &parsed.lines,
        renames,
        in_block_comment: std::cell::Cell::new(0),
    }
    .nodes(&parsed.body)?;
    out.push_str(&body);
    Ok(NagaOilModule {
        import_path: import_path(&path, root)?,
        path,
        source: out,
    })
}

struct Translator<'a> {
    path: &'a str,
    text: &'a str,
    lines: &'a [std::ops::Range<u32>],
    renames: &'a BTreeMap<String, String>,
    /// Block-comment nesting carried from line to line.
    in_block_comment: std::cell::Cell<u32>,
}

impl Translator<'_> {
    fn fail(&self, message: String) -> ExportError {
        ExportError::Inexpressible {
            module: self.path.to_string(),
            message,
        }
    }

    fn nodes(&self, nodes: &[Node]) -> Result<String, ExportError> {
        let mut out = String::new();
        for node in nodes {
            match node {
                Node::Text(run) => {
                    for line in &self.lines[run.start as usize..run.end as usize] {
                        self.rewrite(&self.text[line.start as usize..line.end as usize], &mut out);
                        out.push('\n');
                    }
                }
                Node::Import(_) => {}
                Node::Define { name, .. } => {
                    return Err(self.fail(format!(
                        "`#define {name}` inside a module: naga_oil allows `#define` only at the top of a top-level shader"
                    )));
                }
                Node::Undef { name } => {
                    return Err(self.fail(format!("`#undef {name}`: naga_oil has no `#undef`")));
                }
                Node::If(cond) => out.push_str(&self.conditional(cond, 0)?),
            }
        }
        Ok(out)
    }

    /// Copies a line, renaming identifiers (outside comments) per `renames`.
    fn rewrite(&self, line: &str, out: &mut String) {
        let mut depth = self.in_block_comment.get();
        let mut i = 0;
        while i < line.len() {
            let rest = &line[i..];
            if depth > 0 {
                let step = if rest.starts_with("*/") {
                    depth -= 1;
                    2
                } else if rest.starts_with("/*") {
                    depth += 1;
                    2
                } else {
                    rest.chars().next().map_or(1, char::len_utf8)
                };
                out.push_str(&rest[..step]);
                i += step;
                continue;
            }
            if rest.starts_with("//") {
                out.push_str(rest);
                break;
            }
            if rest.starts_with("/*") {
                depth += 1;
                out.push_str("/*");
                i += 2;
                continue;
            }
            let c = rest.chars().next().unwrap_or(' ');
            if c.is_ascii_alphanumeric() || c == '_' {
                let len = rest
                    .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                    .unwrap_or(rest.len());
                let word = &rest[..len];
                match self.renames.get(word) {
                    Some(new) if !c.is_ascii_digit() => out.push_str(new),
                    _ => out.push_str(word),
                }
                i += len;
                continue;
            }
            out.push(c);
            i += c.len_utf8();
        }
        self.in_block_comment.set(depth);
    }

    /// `#if` branch `i` onwards, as nested naga_oil conditionals.
    fn conditional(&self, cond: &Conditional, i: usize) -> Result<String, ExportError> {
        match cond.branches.get(i) {
            None => self.nodes(&cond.otherwise),
            Some((expr, body)) => {
                let then = self.nodes(body)?;
                let otherwise = self.conditional(cond, i + 1)?;
                self.emit(expr, then, otherwise)
            }
        }
    }

    fn emit(&self, expr: &Expr, then: String, otherwise: String) -> Result<String, ExportError> {
        if then == otherwise {
            return Ok(then);
        }
        match expr {
            Expr::Int(v) => Ok(if *v != 0 { then } else { otherwise }),
            Expr::Name(n) | Expr::Defined(n) => Ok(ifdef(n, &then, &otherwise)),
            Expr::Not(e) => self.emit(e, otherwise, then),
            Expr::Neg(e) => match constant(e) {
                Some(v) => self.emit(&Expr::Int(Expr::negate(v)), then, otherwise),
                None => Err(self
                    .fail("unary `-` on a name cannot be expressed in naga_oil's dialect".into())),
            },
            Expr::Binary(BinOp::And, a, b) => {
                let inner = self.emit(b, then, otherwise.clone())?;
                self.emit(a, inner, otherwise)
            }
            Expr::Binary(BinOp::Or, a, b) => {
                let inner = self.emit(b, then.clone(), otherwise)?;
                self.emit(a, then, inner)
            }
            Expr::Binary(op, a, b) => {
                if let (Some(x), Some(y)) = (constant(a), constant(b)) {
                    return Ok(if op.apply(x, y) != 0 { then } else { otherwise });
                }
                match (&**a, &**b) {
                    (Expr::Name(n), other) if constant(other).is_some() => {
                        Ok(if_compare(n, *op, constant(other).unwrap_or(0), &then, &otherwise))
                    }
                    (other, Expr::Name(n)) if constant(other).is_some() => Ok(if_compare(
                        n,
                        flip(*op),
                        constant(other).unwrap_or(0),
                        &then,
                        &otherwise,
                    )),
                    // A 0/1-valued expression compared with 0 or 1.
                    (e, other) | (other, e)
                        if is_boolean(e)
                            && matches!(op, BinOp::Eq | BinOp::Ne)
                            && matches!(constant(other), Some(0 | 1)) =>
                    {
                        let truth = (*op == BinOp::Eq) == (constant(other) == Some(1));
                        if truth {
                            self.emit(e, then, otherwise)
                        } else {
                            self.emit(e, otherwise, then)
                        }
                    }
                    _ => Err(self.fail(
                        "a comparison other than NAME op INTEGER cannot be expressed in naga_oil's dialect".into(),
                    )),
                }
            }
        }
    }
}

fn constant(e: &Expr) -> Option<i64> {
    match e {
        Expr::Int(v) => Some(*v),
        Expr::Neg(inner) => constant(inner).map(Expr::negate),
        _ => None,
    }
}

fn is_boolean(e: &Expr) -> bool {
    matches!(
        e,
        Expr::Defined(_)
            | Expr::Not(_)
            | Expr::Binary(
                BinOp::And
                    | BinOp::Or
                    | BinOp::Eq
                    | BinOp::Ne
                    | BinOp::Lt
                    | BinOp::Le
                    | BinOp::Gt
                    | BinOp::Ge,
                _,
                _
            )
    )
}

/// `v op n` ⇔ `n flip(op) v`.
fn flip(op: BinOp) -> BinOp {
    match op {
        BinOp::Lt => BinOp::Gt,
        BinOp::Le => BinOp::Ge,
        BinOp::Gt => BinOp::Lt,
        BinOp::Ge => BinOp::Le,
        other => other,
    }
}

fn ifdef(name: &str, then: &str, otherwise: &str) -> String {
    match (then.is_empty(), otherwise.is_empty()) {
        (true, true) => String::new(),
        (false, true) => format!("#ifdef {name}\n{then}#endif\n"),
        (true, false) => format!("#ifndef {name}\n{otherwise}#endif\n"),
        (false, false) => format!("#ifdef {name}\n{then}#else\n{otherwise}#endif\n"),
    }
}

fn if_compare(name: &str, op: BinOp, value: i64, then: &str, otherwise: &str) -> String {
    // naga_oil evaluates `#if NAME op N` even in inactive blocks and fails when NAME is not a
    // def, so it cannot be guarded by `#ifdef NAME`: valued defines must always be given.
    if otherwise.is_empty() {
        format!("#if {name} {} {value}\n{then}#endif\n", op.symbol())
    } else {
        format!(
            "#if {name} {} {value}\n{then}#else\n{otherwise}#endif\n",
            op.symbol()
        )
    }
}
