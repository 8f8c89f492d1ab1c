//! WESL modules: `@if` / `@elif` / `@else` attributes read into the same tree as `#if`
//! blocks, so the import graph, the depth limits and the audit's static walk are shared.
//!
//! The module is parsed by `wgsl-parse` (the parser of the `wesl` crate that composes WESL
//! variants). Facts of WESL's conditional translation this follows (the WESL specification
//! and `wesl` 0.6's `condcomp`): a condition decorates one syntax node of a list — an
//! import, a directive, a global declaration (a block of declarations too, `@if(A) { … }`), a struct member, a function parameter, a
//! statement, a switch clause, a `continuing` block or a `break if` — at most one condition
//! per node; `@elif` and `@else` continue the chain of the node just before them; conditions
//! are feature names, `true`, `false`, `!`, `&&`, `||` and parentheses, a feature being on
//! or off.
//!
//! Each decorated node becomes one branch of a [`Conditional`] over its bytes, together with
//! the `@elif` / `@else` nodes that follow it (the blanks and comments between two nodes of a
//! chain go with the earlier one). The tree's "lines" are those byte segments, not lines: the
//! audit interns segments as it interns lines, so a variant's text is the segments it keeps.

use std::ops::Range;

use wgsl_parse::SyntaxNode;
use wgsl_parse::syntax as syn;

use crate::diagnostic::{FileId, Span};
use crate::preprocess::error::ParseError;
use crate::preprocess::expr::{BinOp, Expr};
use crate::preprocess::parse::ParseLimits;
use crate::preprocess::tree::{Conditional, ImportRef, Node, ParsedModule};

/// A condition attribute, read.
enum Cond {
    If(Expr),
    Elif(Expr),
    Else,
}

/// One node of a chain: its condition, its bytes, and the conditional pieces inside it.
struct Member {
    cond: Cond,
    start: usize,
    end: usize,
    nested: Vec<Piece>,
}

/// What the tree is cut at: a chain of conditional nodes, or an import statement (which
/// becomes an import node after its text).
enum Piece {
    Chain(Vec<Member>),
    Import {
        start: usize,
        end: usize,
        paths: Vec<String>,
    },
}

/// Parses a WESL module. Returns every problem found.
pub(super) fn parse(
    file: FileId,
    text: &str,
    limits: ParseLimits,
) -> Result<ParsedModule, Vec<ParseError>> {
    // Deep nesting overflows the stack of the recursive tree wgsl-parse builds (an abort, not a
    // panic): refused before the parser sees it, as this crate's own dialect refuses it.
    if let Some(at) = crate::preprocess::lines::nesting_past(text, limits.expr_depth) {
        return Err(vec![ParseError::TooDeep {
            what: "brackets and prefix operators",
            limit: limits.expr_depth,
            span: Span::new(file, at..at + 1),
        }]);
    }
    // A parser panic on input it does not expect is this file's error, not the tool's crash.
    let parsed = std::panic::catch_unwind(|| text.parse::<syn::TranslationUnit>());
    let unit = match parsed {
        Ok(Ok(unit)) => unit,
        Ok(Err(e)) => {
            let r = e.span.range();
            let start = r.start.min(text.len());
            return Err(vec![ParseError::Syntax {
                message: e.error.to_string(),
                span: Span::new(file, start..r.end.clamp(start, text.len())),
            }]);
        }
        Err(_) => {
            return Err(vec![ParseError::Syntax {
                message: "the WESL parser (wgsl-parse 0.6) panicked on this file".into(),
                span: Span::new(file, 0..0),
            }]);
        }
    };
    let mut w = Walker {
        file,
        text,
        limits,
        errors: Vec::new(),
    };
    let pieces = w.unit(&unit);
    if !w.errors.is_empty() {
        return Err(w.errors);
    }
    let mut b = Builder {
        file,
        text,
        lines: Vec::new(),
        comment_only: Vec::new(),
        imports: Vec::new(),
    };
    let body = b.build(0, text.len(), pieces);
    Ok(ParsedModule {
        file,
        lines: b.lines,
        comment_only: b.comment_only,
        body,
        imports: b.imports,
        shader: None,
        import_name: None,
    })
}

struct Walker<'t> {
    file: FileId,
    text: &'t str,
    limits: ParseLimits,
    errors: Vec<ParseError>,
}

/// How to find where a node without a span of its own ends.
#[derive(Clone, Copy)]
enum Extent {
    /// The node has a span.
    Spanned,
    /// A parameter: up to the `,` or `)` after it.
    Parameter,
    /// A clause or block: through the `}` closing its first block, or a `;`.
    Block,
}

impl Walker<'_> {
    fn unit(&mut self, unit: &syn::TranslationUnit) -> Vec<Piece> {
        let first_decl = unit
            .global_declarations
            .first()
            .map_or(self.text.len(), |d| d.span().range().start);
        let header = header_statements(self.text, first_decl);
        let imports = unit.imports.len();
        if header.len() < imports + unit.global_directives.len() {
            self.errors.push(ParseError::Syntax {
                message: "could not locate every import and directive statement".into(),
                span: Span::new(self.file, 0..0),
            });
            return Vec::new();
        }
        let mut pieces = Vec::new();
        // Imports and directives: their statements, in order, found by `header_statements`.
        let import_ranges = &header[..imports];
        let mut at = 0;
        pieces.extend(self.list(&unit.imports, 0, &mut |_, _| {
            let r = import_ranges[at].clone();
            at += 1;
            r
        }));
        // Each import statement is also a piece of its own (inside its chain when it has a
        // condition), so `build` puts its import node after its text.
        let mut flat = Vec::new();
        for (stmt, r) in unit.imports.iter().zip(import_ranges) {
            flat.push(Piece::Import {
                start: r.start,
                end: r.end,
                paths: import_paths(stmt),
            });
        }
        pieces = attach_imports(pieces, flat);
        let directive_ranges = &header[imports..];
        let mut at = 0;
        pieces.extend(self.list(&unit.global_directives, 0, &mut |_, _| {
            let r = directive_ranges[at].clone();
            at += 1;
            r
        }));
        pieces.extend(self.declarations(&unit.global_declarations, 0));
        pieces
    }

    /// A list of module-scope declarations and the lists inside them; a block of
    /// declarations (`@if(A) { … }`, WESL 0.6) is one node whose list is read the same way.
    fn declarations(&mut self, decls: &[syn::GlobalDeclarationNode], depth: usize) -> Vec<Piece> {
        self.spanned_list(decls, depth, &mut |w, decl, depth| match decl.node() {
            syn::GlobalDeclaration::Struct(s) => {
                w.spanned_list(&s.members, depth, &mut |_, _, _| Vec::new())
            }
            syn::GlobalDeclaration::Function(f) => {
                let mut inner = w.unspanned_list(&f.parameters, depth, Extent::Parameter);
                inner.extend(w.statements(&f.body.statements, depth));
                inner
            }
            syn::GlobalDeclaration::Compound(c) => w.declarations(&c.body, depth),
            _ => Vec::new(),
        })
    }

    /// A list of statements and the lists inside them.
    fn statements(&mut self, stmts: &[syn::StatementNode], depth: usize) -> Vec<Piece> {
        self.spanned_list(stmts, depth, &mut |w, stmt, depth| w.inside(stmt, depth))
    }

    /// The lists inside one statement.
    fn inside(&mut self, stmt: &syn::StatementNode, depth: usize) -> Vec<Piece> {
        match stmt.node() {
            syn::Statement::Compound(c) => self.statements(&c.statements, depth),
            syn::Statement::If(s) => {
                let mut out = self.statements(&s.if_clause.body.statements, depth);
                for clause in &s.else_if_clauses {
                    out.extend(self.statements(&clause.body.statements, depth));
                }
                if let Some(e) = &s.else_clause {
                    out.extend(self.statements(&e.body.statements, depth));
                }
                out
            }
            syn::Statement::Switch(s) => {
                let mut out = self.unspanned_list(&s.clauses, depth, Extent::Block);
                for clause in &s.clauses {
                    out.extend(self.statements(&clause.body.statements, depth));
                }
                sort(out)
            }
            syn::Statement::Loop(s) => {
                let mut out = self.statements(&s.body.statements, depth);
                if let Some(c) = &s.continuing {
                    out.extend(self.unspanned_list(std::slice::from_ref(c), depth, Extent::Block));
                    out.extend(self.statements(&c.body.statements, depth));
                    if let Some(b) = &c.break_if {
                        out.extend(self.unspanned_list(
                            std::slice::from_ref(b),
                            depth,
                            Extent::Block,
                        ));
                    }
                }
                sort(out)
            }
            syn::Statement::For(s) => self.statements(&s.body.statements, depth),
            syn::Statement::While(s) => self.statements(&s.body.statements, depth),
            _ => Vec::new(),
        }
    }

    /// A list of nodes with spans.
    fn spanned_list<T: SyntaxNode>(
        &mut self,
        nodes: &[T],
        depth: usize,
        inner: &mut dyn FnMut(&mut Self, &T, usize) -> Vec<Piece>,
    ) -> Vec<Piece> {
        self.walk(nodes, depth, Extent::Spanned, &mut |_, _| 0..0, inner)
    }

    /// A list of nodes without spans (and without lists inside them that this walk reads
    /// separately).
    fn unspanned_list<T: SyntaxNode>(
        &mut self,
        nodes: &[T],
        depth: usize,
        extent: Extent,
    ) -> Vec<Piece> {
        self.walk(nodes, depth, extent, &mut |_, _| 0..0, &mut |_, _, _| {
            Vec::new()
        })
    }

    /// A list of nodes whose ranges `range` gives.
    fn list<T: SyntaxNode>(
        &mut self,
        nodes: &[T],
        depth: usize,
        range: &mut dyn FnMut(&mut Self, &T) -> Range<usize>,
    ) -> Vec<Piece> {
        self.walk(nodes, depth, Extent::Spanned, range, &mut |_, _, _| {
            Vec::new()
        })
    }

    /// The chains of one list of sibling nodes, with the pieces inside unconditional nodes
    /// hoisted to this level.
    fn walk<T: SyntaxNode>(
        &mut self,
        nodes: &[T],
        depth: usize,
        extent: Extent,
        range: &mut dyn FnMut(&mut Self, &T) -> Range<usize>,
        inner: &mut dyn FnMut(&mut Self, &T, usize) -> Vec<Piece>,
    ) -> Vec<Piece> {
        let mut out = Vec::new();
        let mut chain: Vec<Member> = Vec::new();
        // Whether the previous sibling was `@if` or `@elif` (an `@elif`/`@else` may follow).
        let mut open = false;
        for node in nodes {
            let given = range(self, node);
            let conds: Vec<&syn::AttributeNode> = node
                .attributes()
                .iter()
                .filter(|a| {
                    matches!(
                        a.node(),
                        syn::Attribute::If(_) | syn::Attribute::Elif(_) | syn::Attribute::Else
                    )
                })
                .collect();
            if let Some(second) = conds.get(1) {
                self.errors.push(ParseError::Attribute {
                    attribute: name(second.node()),
                    message: "a node has at most one `@if`, `@elif` or `@else`".into(),
                    span: self.span(second.span().range()),
                });
            }
            let Some(attr) = conds.first() else {
                if !chain.is_empty() {
                    out.push(Piece::Chain(std::mem::take(&mut chain)));
                }
                open = false;
                out.extend(inner(self, node, depth));
                continue;
            };
            let attr_span = self.span(attr.span().range());
            if depth >= self.limits.if_depth {
                self.errors.push(ParseError::TooDeep {
                    what: "`@if`",
                    limit: self.limits.if_depth,
                    span: attr_span,
                });
                return out;
            }
            let cond = match attr.node() {
                syn::Attribute::If(e) => Cond::If(self.expr(e, 0)),
                syn::Attribute::Elif(e) => Cond::Elif(self.expr(e, 0)),
                _ => Cond::Else,
            };
            if matches!(cond, Cond::If(_)) {
                if !chain.is_empty() {
                    out.push(Piece::Chain(std::mem::take(&mut chain)));
                }
            } else if !open {
                self.errors.push(ParseError::Attribute {
                    attribute: name(attr.node()),
                    message: "it must follow a node with `@if` or `@elif` in the same list".into(),
                    span: attr_span,
                });
                continue;
            }
            open = !matches!(cond, Cond::Else);
            let first_attr = node
                .attributes()
                .iter()
                .map(|a| a.span().range().start)
                .min()
                .unwrap_or(0);
            let start = at_sign(self.text, first_attr);
            let (start, end) = match (extent, node.span()) {
                (Extent::Spanned, Some(s)) => (s.range().start.min(start), s.range().end),
                (Extent::Spanned, None) => (given.start.min(start), given.end),
                (kind, _) => (start, node_end(self.text, start, kind)),
            };
            let nested = inner(self, node, depth + 1);
            chain.push(Member {
                cond,
                start,
                end,
                nested,
            });
        }
        if !chain.is_empty() {
            out.push(Piece::Chain(chain));
        }
        out
    }

    /// A condition as an expression of this crate (a feature is a name: 1 when on).
    fn expr(&mut self, e: &syn::ExpressionNode, depth: usize) -> Expr {
        let span = self.span(e.span().range());
        if depth > self.limits.expr_depth {
            self.errors.push(ParseError::TooDeep {
                what: "expression",
                limit: self.limits.expr_depth,
                span,
            });
            return Expr::Int(0);
        }
        match e.node() {
            syn::Expression::Literal(syn::LiteralExpression::Bool(b)) => Expr::Int(*b as i64),
            syn::Expression::Parenthesized(p) => self.expr(&p.expression, depth + 1),
            syn::Expression::Unary(u) if u.operator == syn::UnaryOperator::LogicalNegation => {
                Expr::Not(Box::new(self.expr(&u.operand, depth + 1)))
            }
            syn::Expression::Binary(b)
                if matches!(
                    b.operator,
                    syn::BinaryOperator::ShortCircuitAnd | syn::BinaryOperator::ShortCircuitOr
                ) =>
            {
                let op = if b.operator == syn::BinaryOperator::ShortCircuitAnd {
                    BinOp::And
                } else {
                    BinOp::Or
                };
                Expr::Binary(
                    op,
                    Box::new(self.expr(&b.left, depth + 1)),
                    Box::new(self.expr(&b.right, depth + 1)),
                )
            }
            syn::Expression::TypeOrIdentifier(t)
                if t.template_args.is_none() && t.path.is_none() =>
            {
                Expr::Name(t.ident.name().as_str().into())
            }
            _ => {
                self.errors.push(ParseError::Attribute {
                    attribute: "if",
                    message: "conditions are feature names, `true`, `false`, `!`, `&&`, `||` and parentheses".into(),
                    span,
                });
                Expr::Int(0)
            }
        }
    }

    fn span(&self, r: Range<usize>) -> Span {
        let start = r.start.min(self.text.len());
        Span::new(self.file, start..r.end.clamp(start, self.text.len()))
    }
}

/// The attribute's name as written after `@`.
fn name(a: &syn::Attribute) -> &'static str {
    match a {
        syn::Attribute::If(_) => "if",
        syn::Attribute::Elif(_) => "elif",
        _ => "else",
    }
}

/// Pieces in source order.
fn sort(mut pieces: Vec<Piece>) -> Vec<Piece> {
    pieces.sort_by_key(|p| match p {
        Piece::Chain(m) => m[0].start,
        Piece::Import { start, .. } => *start,
    });
    pieces
}

/// Puts each import piece where its statement is: inside the chain member that covers it,
/// or at the top level.
fn attach_imports(chains: Vec<Piece>, imports: Vec<Piece>) -> Vec<Piece> {
    let mut top = Vec::new();
    let mut chains = chains;
    for import in imports {
        let Piece::Import { start, .. } = &import else {
            continue;
        };
        let member = chains.iter_mut().find_map(|p| match p {
            Piece::Chain(members) => members
                .iter_mut()
                .find(|m| m.start <= *start && *start < m.end),
            Piece::Import { .. } => None,
        });
        match member {
            Some(m) => m.nested.push(import),
            None => top.push(import),
        }
    }
    chains.extend(top);
    sort(chains)
}

/// The full paths an import statement names (`package::a::b::{c, d}` names `package::a::b::c`
/// and `package::a::b::d`); `self::` and `super::` stay relative (the loader knows the
/// module's path).
/// The virtual `constants` package (numbers set by the host) is no module of the tree.
fn import_paths(stmt: &syn::ImportStatement) -> Vec<String> {
    let mut prefix = Vec::new();
    if let Some(p) = &stmt.path {
        match &p.origin {
            syn::PathOrigin::Absolute => prefix.push("package".to_string()),
            syn::PathOrigin::Relative(0) => prefix.push("self".to_string()),
            syn::PathOrigin::Relative(n) => prefix.extend((0..*n).map(|_| "super".to_string())),
            syn::PathOrigin::Package(name) => prefix.push(name.clone()),
        }
        prefix.extend(p.components.iter().cloned());
    }
    let mut out = Vec::new();
    flatten(&mut prefix, &stmt.content, &mut out);
    out.retain(|p| p != "constants" && !p.starts_with("constants::"));
    out
}

fn flatten(prefix: &mut Vec<String>, content: &syn::ImportContent, out: &mut Vec<String>) {
    match content {
        syn::ImportContent::Item(item) => {
            prefix.push(item.ident.name().to_string());
            out.push(prefix.join("::"));
            prefix.pop();
        }
        syn::ImportContent::Collection(imports) => {
            for i in imports {
                let n = prefix.len();
                prefix.extend(i.path.iter().cloned());
                flatten(prefix, &i.content, out);
                prefix.truncate(n);
            }
        }
    }
}

/// Where an attribute starts: its `@` (at or before `at`, across blanks).
fn at_sign(text: &str, at: usize) -> usize {
    let at = at.min(text.len());
    if text[at..].starts_with('@') {
        return at;
    }
    let before = text[..at].trim_end();
    if before.ends_with('@') {
        before.len() - 1
    } else {
        at
    }
}

/// The byte ranges of the `;`-terminated statements before `end` (imports, then
/// directives: the only statements allowed before the first declaration), comments skipped.
fn header_statements(text: &str, end: usize) -> Vec<Range<usize>> {
    let b = text.as_bytes();
    let end = end.min(b.len());
    let mut out = Vec::new();
    let mut i = 0;
    let mut start = None;
    let mut depth = 0i32;
    while i < end {
        if let Some(next) = skip_comment(b, i) {
            i = next;
            continue;
        }
        let c = b[i];
        if start.is_none() && !c.is_ascii_whitespace() {
            start = Some(i);
        }
        match c {
            b'(' | b'{' | b'[' => depth += 1,
            b')' | b'}' | b']' => depth -= 1,
            b';' if depth <= 0 => {
                if let Some(s) = start.take() {
                    out.push(s..i + 1);
                }
                depth = 0;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The index after a comment starting at `i`, if one does.
fn skip_comment(b: &[u8], i: usize) -> Option<usize> {
    if b[i] != b'/' {
        return None;
    }
    match b.get(i + 1) {
        Some(b'/') => Some(
            b[i..]
                .iter()
                .position(|&c| c == b'\n')
                .map_or(b.len(), |p| i + p + 1),
        ),
        Some(b'*') => Some(
            b[i + 2..]
                .windows(2)
                .position(|w| w == b"*/")
                .map_or(b.len(), |p| i + 2 + p + 2),
        ),
        _ => None,
    }
}

/// The end of a node without a span, written from `start` (its first attribute): a
/// parameter ends before the `,` or `)` after it; a clause after the `}` closing its first
/// block or after a `;`.
fn node_end(text: &str, start: usize, kind: Extent) -> usize {
    let b = text.as_bytes();
    let param = matches!(kind, Extent::Parameter);
    let mut i = start;
    let mut depth = 0i32;
    // Template brackets (`array<f32, 4>`) only matter in a parameter's type.
    let mut angle = 0i32;
    while i < b.len() {
        if let Some(next) = skip_comment(b, i) {
            i = next;
            continue;
        }
        match b[i] {
            b'(' | b'[' | b'{' => depth += 1,
            b')' | b']' => {
                if depth == 0 {
                    return i;
                }
                depth -= 1;
            }
            b'}' => {
                if depth == 0 {
                    return i;
                }
                depth -= 1;
                if depth == 0 && !param {
                    return i + 1;
                }
            }
            b';' if depth == 0 => return i + 1,
            b',' if depth == 0 && angle == 0 && param => return i,
            b'<' if param && i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_') => {
                angle += 1
            }
            b'>' if param && angle > 0 => angle -= 1,
            _ => {}
        }
        i += 1;
    }
    b.len()
}

/// Whether a piece of WGSL is only blanks and comments.
fn blank(text: &str) -> bool {
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        if let Some(next) = skip_comment(b, i) {
            i = next;
            continue;
        }
        if !b[i].is_ascii_whitespace() {
            return false;
        }
        i += 1;
    }
    true
}

/// Builds the tree from the pieces, cutting the text into segments.
struct Builder<'t> {
    file: FileId,
    text: &'t str,
    lines: Vec<Range<u32>>,
    comment_only: Vec<bool>,
    imports: Vec<ImportRef>,
}

impl Builder<'_> {
    fn build(&mut self, a: usize, b: usize, pieces: Vec<Piece>) -> Vec<Node> {
        let mut nodes = Vec::new();
        let mut at = a;
        for piece in pieces {
            match piece {
                Piece::Import { start, end, paths } => {
                    let end = end.clamp(at, b);
                    self.text(&mut nodes, at, end);
                    let keyword = self.text[start.min(end)..end]
                        .find("import")
                        .map_or(start, |i| start + i);
                    for path in paths {
                        nodes.push(Node::Import(self.imports.len()));
                        self.imports.push(ImportRef {
                            path,
                            span: Span::new(self.file, keyword.min(end)..end),
                        });
                    }
                    at = end;
                }
                Piece::Chain(members) => {
                    let starts: Vec<usize> = members.iter().map(|m| m.start).collect();
                    let first = starts[0].clamp(at, b);
                    self.text(&mut nodes, at, first);
                    at = first;
                    let last = members.len() - 1;
                    let mut branches = Vec::new();
                    let mut otherwise = Vec::new();
                    for (i, m) in members.into_iter().enumerate() {
                        let end = if i < last { starts[i + 1] } else { m.end };
                        let end = end.clamp(at, b);
                        let body = self.build(at, end, m.nested);
                        at = end;
                        match m.cond {
                            Cond::If(e) | Cond::Elif(e) => branches.push((e, body)),
                            Cond::Else => otherwise = body,
                        }
                    }
                    nodes.push(Node::If(Box::new(Conditional {
                        branches,
                        otherwise,
                    })));
                }
            }
        }
        self.text(&mut nodes, at, b.max(at));
        nodes
    }

    /// Appends bytes `a..b` as a segment (joined to a text node just before it).
    fn text(&mut self, nodes: &mut Vec<Node>, a: usize, b: usize) {
        if a >= b {
            return;
        }
        let index = self.lines.len() as u32;
        self.lines.push(a as u32..b as u32);
        self.comment_only.push(blank(&self.text[a..b]));
        match nodes.last_mut() {
            Some(Node::Text(run)) if run.end == index => run.end = index + 1,
            _ => nodes.push(Node::Text(index..index + 1)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(m: &ParsedModule, text: &str, nodes: &[Node], out: &mut Vec<String>) {
        for n in nodes {
            match n {
                Node::Text(r) => {
                    for l in r.clone() {
                        let s = &m.lines[l as usize];
                        out.push(text[s.start as usize..s.end as usize].trim().to_string());
                    }
                }
                Node::If(c) => {
                    for (e, b) in &c.branches {
                        out.push(format!("if {e:?} {{"));
                        texts(m, text, b, out);
                        out.push("}".into());
                    }
                    out.push("else {".into());
                    texts(m, text, &c.otherwise, out);
                    out.push("}".into());
                }
                Node::Import(i) => out.push(format!("import {}", m.imports[*i].path)),
                _ => {}
            }
        }
    }

    fn tree(text: &str) -> Vec<String> {
        let m = parse(0, text, ParseLimits::default()).unwrap_or_else(|e| panic!("{e:?}"));
        let mut out = Vec::new();
        texts(&m, text, &m.body, &mut out);
        out.retain(|s| !s.is_empty());
        out
    }

    #[test]
    fn declarations_with_a_chain_become_one_conditional() {
        let t = tree(
            "import package::a::{b, c};\n@if(A) import super::d;\n@if(A && !B) fn f() -> f32 { return 1.0; }\n@elif(B) fn f() -> f32 { return 2.0; }\n@else fn f() -> f32 { return 3.0; }\nfn g() {}\n",
        );
        assert_eq!(t[0], "import package::a::{b, c};");
        assert_eq!(t[1], "import package::a::b");
        assert_eq!(t[2], "import package::a::c");
        assert!(t[3].starts_with("if Name(\"A\")"), "{t:#?}");
        assert_eq!(t[4], "@if(A) import super::d;");
        assert_eq!(t[5], "import super::d");
        assert_eq!(t.last().unwrap(), "fn g() {}");
        let joined = t.join("\n");
        assert!(joined.contains("if Binary(And, Name(\"A\"), Not(Name(\"B\"))) {\n@if(A && !B) fn f() -> f32 { return 1.0; }\n}"), "{joined}");
        assert!(
            joined.contains("else {\n@else fn f() -> f32 { return 3.0; }\n}"),
            "{joined}"
        );
    }

    #[test]
    fn statements_members_and_parameters_are_cut_at_their_bytes() {
        let t = tree(
            "struct S {\n    a: f32,\n    @if(A) b: f32,\n}\nfn f(x: f32, @if(A) y: array<f32, 4>) -> f32 {\n    var r = x;\n    @if(B) {\n        r += 1.0;\n    }\n    return r;\n}\n",
        );
        let joined = t.join("\n");
        assert!(
            joined.contains("if Name(\"A\") {\n@if(A) b: f32\n}"),
            "{joined}"
        );
        assert!(
            joined.contains("if Name(\"A\") {\n@if(A) y: array<f32, 4>\n}"),
            "{joined}"
        );
        assert!(
            joined.contains("if Name(\"B\") {\n@if(B) {\n        r += 1.0;\n    }\n}"),
            "{joined}"
        );
    }

    #[test]
    fn module_scope_blocks_are_one_conditional_with_their_declarations_inside() {
        let t = tree(
            "@if(A) {\n    var<private> x: f32;\n    @if(B) fn f() {}\n}\n@else {\n    fn g() {}\n}\nfn h() {}\n",
        );
        let joined = t.join("\n");
        assert!(
            joined.contains("if Name(\"A\") {\n@if(A) {\n    var<private> x: f32;\nif Name(\"B\") {\n@if(B) fn f() {}\n}\nelse {\n}\n}\n}"),
            "{joined}"
        );
        assert!(
            joined.contains("else {\n@else {\n    fn g() {}\n}\n}"),
            "{joined}"
        );
        assert_eq!(t.last().unwrap(), "fn h() {}");
    }

    #[test]
    fn malformed_conditions_are_located() {
        let text = "@else fn f() {}\n@if(A) @if(B) fn g() {}\n@if(A + 1) fn h() {}\n";
        let errors = parse(0, text, ParseLimits::default()).unwrap_err();
        let shown: Vec<String> = errors
            .iter()
            .map(|e| format!("{e} @{}", e.span().start))
            .collect();
        assert_eq!(errors.len(), 3, "{shown:?}");
        assert!(
            shown[0].starts_with("malformed `@else`") && shown[0].ends_with("@0"),
            "{shown:?}"
        );
        assert!(shown[1].contains("at most one"), "{shown:?}");
        assert!(shown[2].contains("feature names"), "{shown:?}");
        let syntax = parse(0, "fn f( {", ParseLimits::default()).unwrap_err();
        assert!(matches!(syntax[0], ParseError::Syntax { .. }));
    }
}
