//! The parsed form of a module: WGSL line runs and directives as a tree.
//!
//! Modules are parsed once when a library loads; composing a variant only walks this tree,
//! so the per-variant cost is a tree walk plus copying text.

use std::ops::Range;

use crate::diagnostic::{FileId, Span};
use crate::keywords::SetKind;

use super::expr::Expr;

/// A node of a module body.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Node {
    /// A run of consecutive WGSL lines, as indices into [`ParsedModule::lines`].
    Text(Range<u32>),
    /// `#if` … `#endif`.
    If(Box<Conditional>),
    /// `#define NAME VALUE`.
    Define {
        /// The name.
        name: Box<str>,
        /// The value (1 when none is written).
        value: i64,
    },
    /// `#undef NAME`.
    Undef {
        /// The name.
        name: Box<str>,
    },
    /// `#import path`: index into [`ParsedModule::imports`].
    Import(usize),
}

/// The branches of one `#if`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Conditional {
    /// `#if` and `#elif` conditions, each with its body, in order.
    pub branches: Vec<(Expr, Vec<Node>)>,
    /// The `#else` body (empty without `#else`).
    pub otherwise: Vec<Node>,
}

/// One `#import` of a module.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ImportRef {
    /// Path as written, without extension (naga_oil: the item's or module's full `a::b::c`
    /// path, with `{…}` groups expanded).
    pub path: String,
    /// Where the path is written.
    pub span: Span,
}

/// A `#pragma` of a pass, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Pragma {
    /// `multi_compile[_local]` or `shader_feature[_local]`.
    Keywords {
        /// The pragma kind.
        kind: SetKind,
        /// Whether the `_local` form was used.
        local: bool,
        /// The names, with where each is written.
        names: Vec<(Box<str>, Span)>,
        /// The whole directive.
        span: Span,
    },
    /// `skip_variants`.
    SkipVariants(Vec<(Box<str>, Span)>),
    /// `exclude_renderers`.
    ExcludeRenderers(Vec<Box<str>>),
    /// `require A B…` (A on needs each of B… on) or `exclude A B…` (at most one on).
    Constraint {
        /// `require` or `exclude`.
        kind: crate::keywords::ConstraintKind,
        /// The keywords, with where each is written (at least two).
        names: Vec<(Box<str>, Span)>,
        /// The whole directive.
        span: Span,
    },
}

/// A `#pass … #endpass` block.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct PassDecl {
    /// Pass name.
    pub name: String,
    /// Where the name is written.
    pub span: Span,
    /// `#tag` pairs in order.
    pub tags: Vec<(String, String)>,
    /// Pragmas in order.
    pub pragmas: Vec<Pragma>,
    /// The body.
    pub body: Vec<Node>,
    /// Shader defs with a fixed value (declaration files' `constants`).
    pub constants: Vec<crate::keywords::Constant>,
    /// Keywords that set several defs (declaration files' `options`): each keyword with the
    /// defs it sets, in place of the def of its own name.
    pub options: std::collections::BTreeMap<String, Vec<crate::keywords::Constant>>,
    /// The pass's own entry module, where a declaration file names one (its path as written
    /// and where); otherwise the pass composes its shader's.
    pub entry: Option<(String, Span)>,
    /// The module id of `entry`, once the loader has found it.
    pub module: Option<usize>,
    /// The devices the pass is validated for, where a declaration file names them for the
    /// pass (`profile`); empty: the tree's.
    pub profiles: Vec<crate::validator::Profile>,
    /// The pipeline stage the pass composes, when a declaration file splits its pass into
    /// stages (`stages`); `None`: the whole pipeline from one module.
    pub stage: Option<crate::stage::PipelineStage>,
}

/// A shader file's `#shader` declaration and passes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ShaderDecl {
    /// Shader name.
    pub name: String,
    /// Where the name is written.
    pub span: Span,
    /// Passes in file order.
    pub passes: Vec<PassDecl>,
}

/// A parsed module file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct ParsedModule {
    /// The file.
    pub file: FileId,
    /// Byte range of each line.
    pub lines: Vec<Range<u32>>,
    /// Whether each line is blank or only a `//` comment (left out of lean compositions).
    pub comment_only: Vec<bool>,
    /// Body of a plain module (empty for a shader file).
    pub body: Vec<Node>,
    /// Every `#import` in the file, in order.
    pub imports: Vec<ImportRef>,
    /// The shader declared by this file, if it is a shader file.
    pub shader: Option<ShaderDecl>,
    /// The name other modules import this one by (naga_oil's `#define_import_path`), with
    /// where it is written; `None`: imported by its path.
    pub import_name: Option<(String, Span)>,
}

/// Adds every name the conditions of `nodes` read (`#ifdef X`, `#if X > 1`, `@if(X)`), in
/// every branch.
pub(crate) fn names_read(nodes: &[Node], out: &mut std::collections::BTreeSet<String>) {
    for node in nodes {
        if let Node::If(cond) = node {
            for (expr, body) in &cond.branches {
                expr.visit_names(&mut |n| {
                    out.insert(n.to_string());
                });
                names_read(body, out);
            }
            names_read(&cond.otherwise, out);
        }
    }
}
