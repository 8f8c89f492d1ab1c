//! Modules in WESL's dialect, so WESL users (Bevy's main branch among them) can import the
//! bundled library and pick variants with WESL features.
//!
//! Each module `dir/name` becomes the WESL module `package::dir::name` (file `dir/name.wesl`):
//!
//! - one `import package::dir::other::{a, b};` per module that declares names this module
//!   uses (found as for the naga_oil export: our `#import` is textual and transitive, WESL's
//!   imports name items);
//! - every `#if` becomes `@if(…)` attributes. WESL conditions decorate syntax nodes —
//!   declarations, struct members and statements — where ours wrap lines, so each branch's
//!   lines are cut into those nodes and each node gets the branch's condition (with the
//!   negations of the branches before it, and the conditions of the enclosing `#if`s at the
//!   same level). A branch that is not a run of whole nodes — a function header that differs
//!   between branches, say — is resolved by writing the smallest enclosing node once per
//!   branch, each copy under its own `@if`.
//! - conditions: `defined(X)` and `X` are the feature `X` (a keyword that is on is an enabled
//!   feature); `!`, `&&`, `||` map as they are. WESL features are booleans, so a comparison
//!   with a number fails with [`ExportError::Inexpressible`], as do `#define` / `#undef`
//!   inside a module. Shader files (`#shader`) are not modules and are refused; a pass's
//!   `#define`s become features the user sets too (`FORWARD_BASE_PASS`, …).
//!
//! A pass's program is its module with entry points compiled as the root, with the pass's
//! keywords and `#define`s as features: `tests/export.rs` compiles the export with the `wesl`
//! crate for the covering set of every bundled pass and compares what naga sees with our text.
//!
//! ```
//! let lib = wgsl_variants_shaders::library().unwrap();
//! let modules = wgsl_variants::emit::wesl::export(&lib, "deferred/gbuffer").unwrap();
//! assert_eq!(modules[0].module_path, "package::deferred::ldr"); // imports first
//! let gbuffer = &modules[1].source;
//! assert!(gbuffer.contains("import package::deferred::ldr::{ldr_encode};"));
//! assert!(gbuffer.contains("@if(UNITY_HDR_ON)"));
//! ```

use std::fmt::Write as _;

use crate::library::Library;
use crate::preprocess::expr::{BinOp, Expr};
use crate::preprocess::tree::Node;

use super::export::{ExportError, dependency_order, import_closure, library_order, module_index};
use super::naga_oil::import_path;
use super::scan::{Scan, scan_library, scan_nodes};
use crate::keywords::ConstraintKind;
use crate::keywords::SetKind;
use crate::preprocess::lines::comment_step;
use crate::shader::Pass;

/// One module in WESL's dialect (serialized as `module`, `module_path` and `source`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct WeslModule {
    /// Our module path (`deferred/gbuffer`); the WESL file is this path with `.wesl`.
    #[serde(rename = "module")]
    pub path: String,
    /// Its WESL module path (`package::deferred::gbuffer`).
    pub module_path: String,
    /// The source.
    pub source: String,
}

/// The WESL module path of a module path (`package::` and the path with `/` as `::`).
pub(crate) fn module_path(path: &str) -> Result<String, ExportError> {
    import_path(path, Some("package"))
}

/// Exports a module and every module it imports (imports first, the module last).
pub fn export(lib: &Library, path: &str) -> Result<Vec<WeslModule>, ExportError> {
    let index = module_index(lib, path)?;
    let scans = scan_library(lib);
    let mut order = Vec::new();
    dependency_order(lib, index, &mut order);
    order
        .into_iter()
        .map(|m| export_one(lib, m, &scans))
        .collect()
}

/// Exports every module of the library (shader files excluded), each after its imports.
pub fn export_all(lib: &Library) -> Result<Vec<WeslModule>, ExportError> {
    let scans = scan_library(lib);
    library_order(lib)
        .into_iter()
        .map(|m| export_one(lib, m, &scans))
        .collect()
}

fn export_one(lib: &Library, module: usize, scans: &[Scan]) -> Result<WeslModule, ExportError> {
    let graph = lib.module_graph();
    let path = lib.module_paths()[module].clone();
    let parsed = &graph.modules[module];
    let closure = import_closure(lib, module);
    let source = translate(
        lib,
        &path,
        &scans[module],
        &closure[1..],
        scans,
        &parsed.body,
        graph.files.text(parsed.file),
        &parsed.lines,
    )?;
    Ok(WeslModule {
        module_path: module_path(&path)?,
        path,
        source,
    })
}

/// The WESL text of `body`: a header comment, one `import` per module of `closure` that
/// declares names the body uses (the first such module, in closure order), the body.
#[allow(clippy::too_many_arguments)]
fn translate(
    lib: &Library,
    path: &str,
    own: &Scan,
    closure: &[usize],
    scans: &[Scan],
    body: &[Node],
    text: &str,
    lines: &[std::ops::Range<u32>],
) -> Result<String, ExportError> {
    let fail = |message: String| ExportError::Inexpressible {
        module: path.to_string(),
        message,
    };
    let mut imports: Vec<(usize, Vec<&str>)> = Vec::new();
    for name in own.used.difference(&own.declared) {
        if let Some(&m) = closure.iter().find(|&&m| scans[m].declared.contains(name)) {
            match imports.iter_mut().find(|(i, _)| *i == m) {
                Some((_, names)) => names.push(name),
                None => imports.push((m, vec![name])),
            }
        }
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "// {path}, exported by wgsl-variants {} in WESL's dialect.",
        env!("CARGO_PKG_VERSION")
    );
    // In closure order, so the output does not depend on module ids.
    for m in closure {
        if let Some((_, names)) = imports.iter().find(|(i, _)| i == m) {
            let _ = writeln!(
                out,
                "import {}::{{{}}};",
                module_path(&lib.module_paths()[*m])?,
                names.join(", ")
            );
        }
    }
    let pieces = pieces(body, text, lines).map_err(fail)?;
    emit_seq(&pieces, Kind::Declarations, None, &mut out).map_err(fail)?;
    Ok(out)
}

/// A pass as a WESL program: the root module to compile (it holds the entry points), the
/// features the pass's `#define`s set, and the modules the root imports.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct WeslPass {
    /// The root: the one module the pass's body imports when the body is only `#define`s and
    /// that `#import` (`standard/my_lighting`), else the body itself as the module
    /// `SHADER_FILE/PASS` (`internal/deferred_shading/Lighting`).
    pub root: WeslModule,
    /// Features to enable besides the variant's keywords: the pass's `#define`s.
    pub features: Vec<String>,
    /// Every module the root imports, directly or not, each after its imports.
    pub modules: Vec<WeslModule>,
}

/// Exports one pass (see [`WeslPass`]): compile `root` with its `features` and the variant's
/// keywords enabled.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let pass = lib.pass("standard", "Deferred").unwrap();
/// let p = wgsl_variants::emit::wesl::export_pass(&lib, pass).unwrap();
/// assert_eq!(p.root.module_path, "package::standard::my_lighting");
/// assert_eq!(p.features, ["DEFERRED_PASS"]);
/// ```
pub fn export_pass(lib: &Library, pass: &Pass) -> Result<WeslPass, ExportError> {
    let graph = lib.module_graph();
    let shader_file = &graph.modules[pass.module];
    let text = graph.files.text(shader_file.file);
    let label = format!("{}/{}", pass.shader, pass.name);
    let fail = |message: String| ExportError::Inexpressible {
        module: label.clone(),
        message,
    };
    let mut features = Vec::new();
    let mut imported = Vec::new();
    let mut own_text = false;
    let mut body = Vec::new();
    for node in &pass.body {
        match node {
            Node::Define { name, value } => {
                if *value != 0 {
                    features.push(name.to_string());
                }
            }
            Node::Undef { name } => {
                return Err(fail(format!("`#undef {name}`: WESL has no `#undef`")));
            }
            Node::Import(import) => {
                let m = module_index(lib, &shader_file.imports[*import].path)?;
                imported.push(m);
                body.push(node.clone());
            }
            Node::Text(run) => {
                own_text |= shader_file.lines[run.start as usize..run.end as usize]
                    .iter()
                    .any(|l| {
                        let line = text[l.start as usize..l.end as usize].trim();
                        !line.is_empty() && !line.starts_with("//")
                    });
                body.push(node.clone());
            }
            Node::If(_) => {
                own_text = true;
                body.push(node.clone());
            }
        }
    }
    let scans = scan_library(lib);
    let mut order = Vec::new();
    if let ([root], false) = (imported.as_slice(), own_text) {
        dependency_order(lib, *root, &mut order);
        let mut modules: Vec<WeslModule> = order
            .into_iter()
            .map(|m| export_one(lib, m, &scans))
            .collect::<Result<_, _>>()?;
        let root = modules.pop().ok_or_else(|| fail("no module".into()))?;
        return Ok(WeslPass {
            root,
            features,
            modules,
        });
    }
    let mut closure: Vec<usize> = Vec::new();
    for &m in &imported {
        dependency_order(lib, m, &mut order);
        for c in import_closure(lib, m) {
            if !closure.contains(&c) {
                closure.push(c);
            }
        }
    }
    let file_path = &lib.module_paths()[pass.module];
    let path = format!("{file_path}/{}", pass.name);
    let own = scan_nodes(&body, text, &shader_file.lines);
    let source = translate(
        lib,
        &path,
        &own,
        &closure,
        &scans,
        &body,
        text,
        &shader_file.lines,
    )?;
    Ok(WeslPass {
        root: WeslModule {
            module_path: module_path(&path)?,
            path,
            source,
        },
        features,
        modules: order
            .into_iter()
            .map(|m| export_one(lib, m, &scans))
            .collect::<Result<_, _>>()?,
    })
}

/// A module's body: lines (each with its `\n`) and conditionals, whose branches carry the
/// whole condition under which they are taken (`#elif` and `#else` with the negations of the
/// branches before them).
#[derive(Clone, Debug)]
enum Piece {
    Text(String),
    If(Conditional),
}

/// A conditional's branches with their whole conditions; `exhaustive` when it has an
/// `#else` (some branch is always taken).
#[derive(Clone, Debug)]
struct Conditional {
    branches: Vec<(Expr, Vec<Piece>)>,
    exhaustive: bool,
}

fn pieces(
    nodes: &[Node],
    text: &str,
    lines: &[std::ops::Range<u32>],
) -> Result<Vec<Piece>, String> {
    let mut out = Vec::new();
    for node in nodes {
        match node {
            Node::Text(run) => {
                for line in &lines[run.start as usize..run.end as usize] {
                    out.push(Piece::Text(format!(
                        "{}\n",
                        &text[line.start as usize..line.end as usize]
                    )));
                }
            }
            Node::Import(_) => {}
            Node::Define { name, .. } => {
                return Err(format!(
                    "`#define {name}` inside a module: WESL features are set by the user, not by a module"
                ));
            }
            Node::Undef { name } => return Err(format!("`#undef {name}`: WESL has no `#undef`")),
            Node::If(cond) => {
                let mut branches = Vec::new();
                let mut before: Option<Expr> = None;
                let with_before = |e: Expr, before: &Option<Expr>| match before {
                    None => e,
                    Some(b) => Expr::Binary(BinOp::And, Box::new(b.clone()), Box::new(e)),
                };
                for (expr, body) in &cond.branches {
                    branches.push((
                        with_before(expr.clone(), &before),
                        pieces(body, text, lines)?,
                    ));
                    let not = Expr::Not(Box::new(expr.clone()));
                    before = Some(with_before(not, &before));
                }
                let otherwise = pieces(&cond.otherwise, text, lines)?;
                let exhaustive = !otherwise.is_empty();
                if exhaustive {
                    branches.push((before.unwrap_or(Expr::Int(1)), otherwise));
                }
                out.push(Piece::If(Conditional {
                    branches,
                    exhaustive,
                }));
            }
        }
    }
    Ok(out)
}

/// A condition in WESL's syntax (fully parenthesized below the top).
fn condition(e: &Expr) -> Result<String, String> {
    let atom = |e: &Expr| -> Result<String, String> {
        let s = condition(e)?;
        Ok(if matches!(e, Expr::Binary(..)) {
            format!("({s})")
        } else {
            s
        })
    };
    match e {
        Expr::Int(v) => Ok(if *v != 0 { "true" } else { "false" }.to_string()),
        Expr::Name(n) | Expr::Defined(n) => Ok(n.to_string()),
        Expr::Not(inner) => Ok(format!("!{}", atom(inner)?)),
        Expr::Binary(BinOp::And, a, b) => Ok(format!("{} && {}", atom(a)?, atom(b)?)),
        Expr::Binary(BinOp::Or, a, b) => Ok(format!("{} || {}", atom(a)?, atom(b)?)),
        Expr::Binary(op @ (BinOp::Eq | BinOp::Ne), a, b) => match (&**a, &**b) {
            (e, Expr::Int(v @ (0 | 1))) | (Expr::Int(v @ (0 | 1)), e) if is_boolean(e) => {
                if (*op == BinOp::Eq) == (*v == 1) {
                    condition(e)
                } else {
                    Ok(format!("!{}", atom(e)?))
                }
            }
            _ => Err(comparison(op)),
        },
        Expr::Binary(op, ..) => Err(comparison(op)),
        Expr::Neg(_) => Err("unary `-` in a condition: WESL features are booleans".to_string()),
    }
}

fn comparison(op: &BinOp) -> String {
    format!(
        "a comparison with `{}`: WESL features are booleans, with no values to compare",
        op.symbol()
    )
}

fn is_boolean(e: &Expr) -> bool {
    matches!(
        e,
        Expr::Defined(_) | Expr::Not(_) | Expr::Binary(BinOp::And | BinOp::Or, ..)
    )
}

/// `a && b` (either may be absent: no condition).
fn and(a: Option<&str>, b: &str) -> String {
    let wrap = |s: &str| {
        if s.contains(' ') {
            format!("({s})")
        } else {
            s.to_string()
        }
    };
    match a {
        None => b.to_string(),
        Some(a) => format!("{} && {}", wrap(a), wrap(b)),
    }
}

/// What a sequence holds, and so where its nodes end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Module scope: a declaration ends at `;` or at the `}` that closes its body.
    Declarations,
    /// A struct body: a member ends at `,`.
    Members,
    /// A function or block body: a statement ends at `;`, or at the `}` that closes it unless
    /// `else` follows.
    Statements,
}

/// Where the cutter is in a sequence.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct State {
    /// Bracket depth within the sequence.
    depth: i32,
    /// `<…>` depth in a struct member's type (`array<f32, 4>` holds a comma).
    angle: i32,
    /// Inside a node.
    in_node: bool,
    /// A statement's closing `}` was seen: the next token ends it unless it is `else`.
    after_block: bool,
    /// Block-comment nesting.
    comment: u32,
    /// The previous significant character was an identifier's.
    after_ident: bool,
}

/// What the cutter reports at a byte offset of a text.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Event {
    /// A node starts here.
    Start,
    /// A node ends here (exclusive).
    End,
}

impl State {
    /// Advances over `text`, reporting node boundaries.
    fn feed(
        &mut self,
        kind: Kind,
        text: &str,
        mut on: impl FnMut(Event, usize),
    ) -> Result<(), String> {
        let bytes = text.as_bytes();
        let mut i = 0;
        while i < bytes.len() {
            let rest = &text[i..];
            if let Some(skip) = comment_step(rest, &mut self.comment) {
                i += skip;
                continue;
            }
            let c = bytes[i];
            if c.is_ascii_whitespace() {
                i += 1;
                continue;
            }
            let word_len = if c.is_ascii_alphanumeric() || c == b'_' {
                rest.find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_'))
                    .unwrap_or(rest.len())
            } else {
                rest.chars().next().map_or(1, char::len_utf8)
            };
            if self.after_block {
                self.after_block = false;
                if &rest[..word_len] != "else" {
                    self.in_node = false;
                    on(Event::End, i);
                }
            }
            if !self.in_node {
                self.in_node = true;
                on(Event::Start, i);
            }
            let ident = c.is_ascii_alphanumeric() || c == b'_';
            match c {
                b'{' | b'(' | b'[' => self.depth += 1,
                b'}' | b')' | b']' => {
                    self.depth -= 1;
                    if self.depth < 0 {
                        return Err("a closing bracket without its opening one in the same conditional block".to_string());
                    }
                    if c == b'}' && self.depth == 0 {
                        match kind {
                            Kind::Declarations => {
                                self.in_node = false;
                                on(Event::End, i + 1);
                            }
                            Kind::Statements => self.after_block = true,
                            Kind::Members => {}
                        }
                    }
                }
                b'<' if kind == Kind::Members && self.after_ident => self.angle += 1,
                b'>' if kind == Kind::Members && self.angle > 0 => self.angle -= 1,
                b';' if self.depth == 0 && kind != Kind::Members => {
                    self.in_node = false;
                    on(Event::End, i + 1);
                }
                b',' if self.depth == 0 && self.angle == 0 && kind == Kind::Members => {
                    self.in_node = false;
                    on(Event::End, i + 1);
                }
                _ => {}
            }
            self.after_ident = ident;
            i += word_len;
        }
        Ok(())
    }

    /// The state at a conditional's end: a statement whose block just closed has ended (an
    /// `else` after `#endif` would be a branch that is not whole nodes), and what the last
    /// character was does not matter.
    fn settled(self) -> State {
        if self.after_block {
            State {
                after_block: false,
                in_node: false,
                after_ident: false,
                ..self
            }
        } else {
            State {
                after_ident: false,
                ..self
            }
        }
    }

    /// The state after `pieces`; a conditional's branches must all end in the same state.
    fn after(mut self, kind: Kind, pieces: &[Piece]) -> Result<State, String> {
        for piece in pieces {
            match piece {
                Piece::Text(t) => self.feed(kind, t, |_, _| {})?,
                Piece::If(cond) => self = self.after_if(kind, cond)?,
            }
        }
        Ok(self)
    }

    fn after_if(self, kind: Kind, cond: &Conditional) -> Result<State, String> {
        // Without an `#else`, the conditional may also be skipped.
        let mut ends = Vec::new();
        if !cond.exhaustive {
            ends.push(self);
        }
        for (_, body) in &cond.branches {
            ends.push(self.after(kind, body)?);
        }
        let Some(first) = ends.first().map(|s| s.settled()) else {
            return Ok(self);
        };
        if ends.iter().all(|s| s.settled() == first) {
            Ok(first)
        } else {
            Err("an `#if` whose branches leave the code in different places (an unbalanced bracket, or a node ended in one branch only)".to_string())
        }
    }
}

/// A sequence cut into nodes.
enum Chunk {
    /// Whitespace and comments between nodes.
    Raw(String),
    /// A conditional at a node boundary whose every branch is a run of whole nodes.
    Group(Conditional),
    /// One node, possibly with conditionals inside.
    Node(Vec<Piece>),
}

fn cut(pieces: &[Piece], kind: Kind) -> Result<Vec<Chunk>, String> {
    let mut chunks = Vec::new();
    let mut state = State::default();
    let mut node: Vec<Piece> = Vec::new();
    let mut raw = String::new();
    let flush_raw = |raw: &mut String, chunks: &mut Vec<Chunk>| {
        if !raw.is_empty() {
            chunks.push(Chunk::Raw(std::mem::take(raw)));
        }
    };
    for piece in pieces {
        match piece {
            Piece::Text(t) => {
                let mut from = 0;
                let mut events = Vec::new();
                state.feed(kind, t, |e, at| events.push((e, at)))?;
                for (event, at) in events {
                    match event {
                        Event::Start => {
                            raw.push_str(&t[from..at]);
                            flush_raw(&mut raw, &mut chunks);
                        }
                        Event::End => {
                            node.push(Piece::Text(t[from..at].to_string()));
                            chunks.push(Chunk::Node(std::mem::take(&mut node)));
                        }
                    }
                    from = at;
                }
                if state.in_node {
                    node.push(Piece::Text(t[from..].to_string()));
                } else {
                    raw.push_str(&t[from..]);
                }
            }
            Piece::If(cond) => {
                if state.after_block {
                    // The statement before ended with its block.
                    state.after_block = false;
                    state.in_node = false;
                    chunks.push(Chunk::Node(std::mem::take(&mut node)));
                }
                let boundary = State {
                    after_ident: state.after_ident,
                    ..State::default()
                };
                let whole = !state.in_node
                    && cond.branches.iter().all(|(_, body)| {
                        boundary
                            .after(kind, body)
                            .is_ok_and(|end| end.settled() == State::default())
                    });
                if whole {
                    flush_raw(&mut raw, &mut chunks);
                    chunks.push(Chunk::Group(cond.clone()));
                } else {
                    flush_raw(&mut raw, &mut chunks);
                    state.in_node = true;
                    state = state.after_if(kind, cond)?;
                    node.push(piece.clone());
                    if !state.in_node {
                        chunks.push(Chunk::Node(std::mem::take(&mut node)));
                    }
                }
            }
        }
    }
    if !node.is_empty() {
        chunks.push(Chunk::Node(node));
    }
    flush_raw(&mut raw, &mut chunks);
    Ok(chunks)
}

fn emit_seq(
    pieces: &[Piece],
    kind: Kind,
    pending: Option<&str>,
    out: &mut String,
) -> Result<(), String> {
    for chunk in cut(pieces, kind)? {
        match chunk {
            Chunk::Raw(text) => out.push_str(&text),
            Chunk::Group(cond) => {
                for (expr, body) in &cond.branches {
                    let c = and(pending, &condition(expr)?);
                    emit_seq(body, kind, Some(&c), out)?;
                }
            }
            Chunk::Node(node) => emit_node(&node, kind, pending, out)?,
        }
    }
    Ok(())
}

fn text_of(pieces: &[Piece]) -> Option<String> {
    let mut s = String::new();
    for p in pieces {
        match p {
            Piece::Text(t) => s.push_str(t),
            Piece::If(_) => return None,
        }
    }
    Some(s)
}

/// `@if(c) ` before a node (not before an empty `;`).
fn prefixed(text: &str, pending: Option<&str>) -> String {
    match pending {
        Some(c) if text.trim() != ";" => format!("@if({c}) {text}"),
        _ => text.to_string(),
    }
}

fn emit_node(
    node: &[Piece],
    kind: Kind,
    pending: Option<&str>,
    out: &mut String,
) -> Result<(), String> {
    if let Some(text) = text_of(node) {
        out.push_str(&prefixed(&text, pending));
        return Ok(());
    }
    if let Some((header, body, footer)) = split_body(node) {
        let first = first_keyword(&header);
        if first != "switch" {
            out.push_str(&prefixed(&header, pending));
            let inner = if first == "struct" {
                Kind::Members
            } else {
                Kind::Statements
            };
            emit_seq(&body, inner, None, out)?;
            out.push_str(&footer);
            return Ok(());
        }
    }
    // Resolve the first conditional by writing the node once per branch.
    let at = node
        .iter()
        .position(|p| matches!(p, Piece::If(_)))
        .unwrap_or_default();
    let Piece::If(cond) = &node[at] else {
        return Ok(());
    };
    let mut taken_any = Vec::new();
    for (i, (expr, body)) in cond.branches.iter().enumerate() {
        let mut copy = node[..at].to_vec();
        copy.extend(body.iter().cloned());
        copy.extend(node[at + 1..].iter().cloned());
        let c = and(pending, &condition(expr)?);
        if i > 0 {
            // The copies of one node, one after the other.
            out.push('\n');
        }
        emit_seq(&copy, kind, Some(&c), out)?;
        taken_any.push(Expr::Not(Box::new(expr.clone())));
    }
    // Without an `#else`, the node without the conditional's text.
    if !cond.exhaustive {
        let mut copy = node[..at].to_vec();
        copy.extend(node[at + 1..].iter().cloned());
        let none = taken_any
            .into_iter()
            .reduce(|a, b| Expr::Binary(BinOp::And, Box::new(a), Box::new(b)))
            .unwrap_or(Expr::Int(1));
        let c = and(pending, &condition(&none)?);
        out.push('\n');
        emit_seq(&copy, kind, Some(&c), out)?;
    }
    Ok(())
}

/// The first word of a node after its attributes (`@fragment fn` → `fn`).
fn first_keyword(header: &str) -> &str {
    let mut rest = header.trim_start();
    while let Some(after) = rest.strip_prefix('@') {
        let name_end = after
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(after.len());
        rest = after[name_end..].trim_start();
        if let Some(args) = rest.strip_prefix('(') {
            let close = args.find(')').map_or(args.len(), |i| i + 1);
            rest = args[close..].trim_start();
        }
    }
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    &rest[..end]
}

/// A node as header (up to its first `{`), body and footer (from the matching `}`), when the
/// header and the footer hold no conditional and every conditional of the body keeps the
/// bracket depth.
fn split_body(node: &[Piece]) -> Option<(String, Vec<Piece>, String)> {
    let mut header = String::new();
    let mut body: Vec<Piece> = Vec::new();
    let mut footer = String::new();
    // 0: header, 1: body, 2: footer.
    let mut phase = 0;
    let mut depth = 0i32;
    let mut comment = 0u32;
    for piece in node {
        match piece {
            Piece::If(cond) => {
                if phase != 1 {
                    return None;
                }
                let start = State {
                    depth: 1,
                    in_node: true,
                    ..State::default()
                };
                let end = start.after_if(Kind::Statements, cond).ok()?;
                if end.depth != 1 {
                    return None;
                }
                body.push(piece.clone());
            }
            Piece::Text(t) => {
                let bytes = t.as_bytes();
                let mut from = 0;
                let mut i = 0;
                while i < bytes.len() {
                    let rest = &t[i..];
                    if let Some(skip) = comment_step(rest, &mut comment) {
                        i += skip;
                        continue;
                    }
                    match bytes[i] {
                        b'{' | b'(' | b'[' => {
                            depth += 1;
                            if phase == 0 && bytes[i] == b'{' && depth == 1 {
                                header.push_str(&t[from..=i]);
                                from = i + 1;
                                phase = 1;
                            }
                        }
                        b'}' | b')' | b']' => {
                            depth -= 1;
                            if phase == 1 && depth == 0 {
                                body.push(Piece::Text(t[from..i].to_string()));
                                from = i;
                                phase = 2;
                            }
                        }
                        _ => {}
                    }
                    i += rest.chars().next().map_or(1, char::len_utf8);
                }
                match phase {
                    0 => header.push_str(&t[from..]),
                    1 => body.push(Piece::Text(t[from..].to_string())),
                    _ => footer.push_str(&t[from..]),
                }
            }
        }
    }
    (phase == 2).then_some((header, body, footer))
}

/// The whole library as a WESL tree, as files (`(relative path, text)`): every module
/// ([`export_all`]), each pass's root module that is not one of them ([`export_pass`]), and
/// the [`declaration`] file, so `wgsl-variants --root DIR` reads it back as a WESL tree.
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let files = wgsl_variants::emit::wesl::export_tree(&lib).unwrap();
/// assert!(files.iter().any(|(p, _)| p == "deferred/ldr.wesl"));
/// assert_eq!(files.last().unwrap().0, "wgsl-variants.toml");
/// ```
pub fn export_tree(lib: &Library) -> Result<Vec<(String, String)>, ExportError> {
    let mut modules = export_all(lib)?;
    for pass in lib.passes() {
        let root = export_pass(lib, pass)?.root;
        if !modules.iter().any(|m| m.path == root.path) {
            modules.push(root);
        }
    }
    let mut files: Vec<(String, String)> = modules
        .into_iter()
        .map(|m| (format!("{}.wesl", m.path), m.source))
        .collect();
    files.push((crate::declaration::FILE_NAME.to_string(), declaration(lib)?));
    Ok(files)
}

/// The declaration file (`wgsl-variants.toml`) of the WESL export of every pass: the passes'
/// keyword sets, constraints, `skip_variants` and tags as they are, each pass composing its
/// root module ([`export_pass`]) with its `#define`s as `Bool` constants (features). Written
/// next to the modules, it makes the export a WESL tree this crate loads again, with the same
/// variants (`tests/export.rs` validates it).
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let toml = wgsl_variants::emit::wesl::declaration(&lib).unwrap();
/// assert!(toml.starts_with("# The keywords of"));
/// assert!(toml.contains("entry = \"standard/my_lighting.wesl\""));
/// assert!(toml.contains("constants = { DEFERRED_PASS = true }"));
/// ```
pub fn declaration(lib: &Library) -> Result<String, ExportError> {
    use std::fmt::Write;
    let quote = |s: &str| toml::Value::String(s.to_string()).to_string();
    let names = |names: &[Option<String>]| -> String {
        let items: Vec<String> = names
            .iter()
            .map(|n| quote(n.as_deref().unwrap_or("_")))
            .collect();
        format!("[{}]", items.join(", "))
    };
    let mut out = String::from(
        "# The keywords of this WESL tree, exported from wgsl-variants' library: each pass composes\n# its root module with its keywords as WESL features (`wgsl-variants --root DIR validate`).\ndialect = \"wesl\"\n",
    );
    for shader in lib.shaders() {
        let mut passes = Vec::new();
        for pass in &shader.passes {
            passes.push((pass, export_pass(lib, pass)?));
        }
        let Some((_, first)) = passes.first() else {
            continue;
        };
        let _ = write!(
            out,
            "\n[[shader]]\nname = {}\nentry = {}\n",
            quote(&shader.name),
            quote(&format!("{}.wesl", first.root.path))
        );
        for (pass, exported) in &passes {
            let _ = write!(
                out,
                "\n[[shader.pass]]\nname = {}\nentry = {}\n",
                quote(&pass.name),
                quote(&format!("{}.wesl", exported.root.path))
            );
            if !pass.tags.is_empty() {
                let tags: Vec<String> = pass
                    .tags
                    .iter()
                    .map(|(k, v)| format!("{} = {}", quote(k), quote(v)))
                    .collect();
                let _ = writeln!(out, "tags = {{ {} }}", tags.join(", "));
            }
            for (kind, local, key) in [
                (SetKind::MultiCompile, false, "multi_compile"),
                (SetKind::MultiCompile, true, "multi_compile_local"),
                (SetKind::ShaderFeature, false, "shader_feature"),
                (SetKind::ShaderFeature, true, "shader_feature_local"),
            ] {
                let sets: Vec<String> = pass
                    .sets
                    .iter()
                    .filter(|s| s.kind == kind && s.local == local)
                    .map(|s| names(&s.options))
                    .collect();
                if !sets.is_empty() {
                    let _ = writeln!(out, "{key} = [{}]", sets.join(", "));
                }
            }
            for (kind, key) in [
                (ConstraintKind::Require, "require"),
                (ConstraintKind::Exclude, "exclude"),
            ] {
                let pairs: Vec<String> = pass
                    .constraints
                    .iter()
                    .filter(|c| c.kind == kind)
                    .map(|c| names(&c.keywords.iter().cloned().map(Some).collect::<Vec<_>>()))
                    .collect();
                if !pairs.is_empty() {
                    let _ = writeln!(out, "{key} = [{}]", pairs.join(", "));
                }
            }
            if !pass.skip_variants.is_empty() {
                let skips: Vec<String> = pass.skip_variants.iter().map(|k| quote(k)).collect();
                let _ = writeln!(out, "skip_variants = [{}]", skips.join(", "));
            }
            if !exported.features.is_empty() {
                let features: Vec<String> = exported
                    .features
                    .iter()
                    .map(|f| format!("{f} = true"))
                    .collect();
                let _ = writeln!(out, "constants = {{ {} }}", features.join(", "));
            }
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn export_text(files: &[(&str, &str)], module: &str) -> String {
        let raw = files
            .iter()
            .map(|(p, t)| crate::source::RawFile {
                path: p.to_string(),
                bytes: t.as_bytes().to_vec(),
            })
            .collect();
        let lib = Library::from_raw(raw, &Default::default()).unwrap();
        export(&lib, module).unwrap().pop().unwrap().source
    }

    #[test]
    fn declarations_members_and_statements() {
        let src = "\
struct S {
    a: f32,
#if defined(B)
    b: array<f32, 4>,
#endif
}
#if defined(B) && !defined(C)
fn g() -> f32 { return 1.0; }
#else
fn g() -> f32 { return 2.0; }
#endif
fn f() -> f32 {
    var x = 1.0;
#if defined(C)
    x = 2.0;
    if x > 1.0 {
        x = 3.0;
    } else {
        x = 4.0;
    }
#endif
    return x;
}
";
        let out = export_text(&[("m.wgsl", src)], "m");
        assert!(out.contains("@if(B) b: array<f32, 4>,"), "{out}");
        assert!(out.contains("@if(B && !C) fn g()"), "{out}");
        assert!(out.contains("@if(!(B && !C)) fn g()"), "{out}");
        assert!(out.contains("@if(C) x = 2.0;"), "{out}");
        assert!(out.contains("@if(C) if x > 1.0 {"), "{out}");
        assert!(out.contains("} else {"), "{out}");
    }

    #[test]
    fn a_header_that_differs_is_written_once_per_branch() {
        let src = "\
@fragment
#if defined(A)
fn fs() -> @location(0) vec4f {
#else
fn fs() -> @location(0) vec2f {
#endif
#if defined(B)
    let y = 1.0;
#endif
    return vec4f(1.0);
}
";
        let out = export_text(&[("m.wgsl", src)], "m");
        assert!(
            out.contains("@if(A) @fragment\nfn fs() -> @location(0) vec4f {"),
            "{out}"
        );
        assert!(
            out.contains("@if(!A) @fragment\nfn fs() -> @location(0) vec2f {"),
            "{out}"
        );
        assert_eq!(out.matches("@if(B) let y = 1.0;").count(), 2, "{out}");
    }

    #[test]
    fn comments_with_any_characters_are_skipped() {
        let src = "\
/* a block comment · with − non-ASCII { and a brace */
#if defined(A)
// a line comment · {
const a: f32 = 1.0; /* trailing · */
#endif
";
        let out = export_text(&[("m.wgsl", src)], "m");
        assert!(out.contains("@if(A) const a: f32 = 1.0;"), "{out}");
    }

    #[test]
    fn comparisons_are_inexpressible() {
        let raw = vec![crate::source::RawFile {
            path: "m.wgsl".into(),
            bytes: b"#if N > 2\nconst a = 1;\n#endif\n".to_vec(),
        }];
        let lib = Library::from_raw(raw, &Default::default()).unwrap();
        let err = export(&lib, "m").unwrap_err();
        assert!(
            err.to_string().contains("WESL features are booleans"),
            "{err}"
        );
    }
}
