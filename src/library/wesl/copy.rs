//! Copies of a module's syntax tree for one compile.
//!
//! `wgsl-parse`'s identifiers are shared handles (`Ident`: a name behind a shared lock), and a
//! parse shares none between two places. `wesl` relies on that sharing: `retarget_idents`
//! points each use of a declaration at the declaration's identifier; the output's
//! declarations are named by renaming the module-scope declarations' identifiers, in place;
//! and its check takes a name used in a type or an expression whose identifier is shared with
//! nothing for an undeclared one. So a compile cannot use a kept tree itself (its renames would
//! reach every other compile, on every thread): it needs a copy with identifiers of its own.
//!
//! - [`fresh_copy`]: a copy as a new parse would be, before `retarget_idents`.
//! - [`Retargeted`]: a tree after `retarget_idents`, kept; [`Retargeted::copy`] gives each
//!   compile a copy with the same sharing between its places but new identifiers, so
//!   `retarget_idents` (scope scans, the largest part of loading a module) runs once per
//!   module and feature values instead of once per compile. `wesl`'s built-in names (one
//!   shared identifier per name for the whole process) stay shared, as `retarget_idents`
//!   leaves them.

// `Ident` hashes and compares by the address of its shared name, which mutating the name
// (interior mutability) does not change: a valid map key.
#![allow(clippy::mutable_key_type)]

use std::collections::{HashMap, HashSet};

use wesl::pass::{self, Visit};
use wgsl_parse::syntax::{
    Expression, ExpressionNode, GlobalDeclaration, GlobalDeclarationNode, Ident, ImportContent,
    Statement, StatementNode, TranslationUnit, TypeExpression,
};

/// A copy of `unit` as `wesl` would get from a new parse of the same text, as far as `wesl`
/// can tell: a new identifier for each module-scope declaration (never renamed in the
/// original) and for each name used in a type or an expression (alone, as after parsing); the
/// other identifiers (members, parameters, local declarations, imports) are neither renamed
/// nor counted by `wesl`, and stay shared.
pub(super) fn fresh_copy(unit: &TranslationUnit) -> TranslationUnit {
    fn new(ident: &mut Ident) {
        let name = ident.name().clone();
        *ident = Ident::new(name);
    }
    fn fresh_ty(ty: &mut TypeExpression) {
        new(&mut ty.ident);
        Visit::<TypeExpression>::visit_rec_mut(ty, &mut |t: &mut TypeExpression| new(&mut t.ident));
    }
    fn fresh_expr(expr: &mut ExpressionNode) {
        match expr.node_mut() {
            Expression::TypeOrIdentifier(ty) => fresh_ty(ty),
            Expression::FunctionCall(call) => fresh_ty(&mut call.ty),
            _ => {}
        }
        for e in Visit::<ExpressionNode>::visit_mut(expr.node_mut()) {
            fresh_expr(e);
        }
    }
    fn fresh_decls(decls: &mut [GlobalDeclarationNode]) {
        for decl in decls {
            match decl.node_mut() {
                GlobalDeclaration::Declaration(d) => new(&mut d.ident),
                GlobalDeclaration::TypeAlias(d) => new(&mut d.ident),
                GlobalDeclaration::Struct(d) => new(&mut d.ident),
                GlobalDeclaration::Function(d) => new(&mut d.ident),
                GlobalDeclaration::Compound(c) => fresh_decls(&mut c.body),
                GlobalDeclaration::Void | GlobalDeclaration::ConstAssert(_) => {}
            }
        }
    }
    let mut copy = unit.clone();
    fresh_decls(&mut copy.global_declarations);
    Visit::<TypeExpression>::visit_rec_mut(&mut copy, &mut |t: &mut TypeExpression| {
        new(&mut t.ident)
    });
    for e in Visit::<ExpressionNode>::visit_mut(&mut copy) {
        fresh_expr(e);
    }
    copy
}

/// Calls `f` on every identifier `wesl` points uses at or renames, declarations first: the
/// imported names, the module-scope declarations, the functions' parameters and local
/// declarations, then every name used in a type or an expression (attributes, template
/// arguments and call targets included). Members, member accesses and directives are left
/// out: `wesl` neither renames them nor points anything at them.
fn each_ident(unit: &mut TranslationUnit, f: &mut impl FnMut(&mut Ident)) {
    fn import(content: &mut ImportContent, f: &mut impl FnMut(&mut Ident)) {
        match content {
            ImportContent::Item(item) => {
                f(&mut item.ident);
                if let Some(rename) = &mut item.rename {
                    f(rename);
                }
            }
            ImportContent::Collection(items) => {
                for i in items {
                    import(&mut i.content, f);
                }
            }
        }
    }
    fn globals(decls: &mut [GlobalDeclarationNode], f: &mut impl FnMut(&mut Ident)) {
        for decl in decls {
            match decl.node_mut() {
                GlobalDeclaration::Declaration(d) => f(&mut d.ident),
                GlobalDeclaration::TypeAlias(d) => f(&mut d.ident),
                GlobalDeclaration::Struct(d) => f(&mut d.ident),
                GlobalDeclaration::Function(d) => {
                    f(&mut d.ident);
                    for p in &mut d.parameters {
                        f(&mut p.ident);
                    }
                }
                GlobalDeclaration::Compound(c) => globals(&mut c.body, f),
                GlobalDeclaration::Void | GlobalDeclaration::ConstAssert(_) => {}
            }
        }
    }
    for i in &mut unit.imports {
        import(&mut i.content, f);
    }
    fn locals(stmt: &mut StatementNode, f: &mut impl FnMut(&mut Ident)) {
        if let Statement::Declaration(d) = stmt.node_mut() {
            f(&mut d.ident);
        }
        for s in Visit::<StatementNode>::visit_mut(stmt.node_mut()) {
            locals(s, f);
        }
    }
    globals(&mut unit.global_declarations, f);
    for s in Visit::<StatementNode>::visit_mut(unit) {
        locals(s, f);
    }
    Visit::<TypeExpression>::visit_rec_mut(unit, &mut |t: &mut TypeExpression| f(&mut t.ident));
}

/// A module's tree after `wesl`'s `retarget_idents`, kept to be copied for each compile.
#[derive(Debug)]
pub(super) struct Retargeted {
    unit: TranslationUnit,
    /// `wesl`'s built-in identifiers the tree points at (shared by the whole process).
    builtins: HashSet<Ident>,
}

impl Retargeted {
    /// `unit` after `retarget_idents`, on a [`fresh_copy`] of it.
    pub(super) fn new(unit: &TranslationUnit) -> Retargeted {
        let mut unit = fresh_copy(unit);
        let mut own = HashSet::new();
        each_ident(&mut unit, &mut |id| {
            own.insert(id.clone());
        });
        pass::retarget_idents(&mut unit);
        // `retarget_idents` points a use at a declaration of the tree or at a built-in name.
        let mut builtins = HashSet::new();
        each_ident(&mut unit, &mut |id| {
            if !own.contains(id) {
                builtins.insert(id.clone());
            }
        });
        Retargeted { unit, builtins }
    }

    /// A copy for one compile: each identifier of the tree (built-in names aside) replaced by
    /// a new one, the same new one wherever the tree shares it, so the copy is what
    /// `retarget_idents` makes of a [`fresh_copy`] (`tests` compare the two).
    pub(super) fn copy(&self) -> TranslationUnit {
        let mut copy = self.unit.clone();
        let mut new: HashMap<Ident, Ident> = HashMap::new();
        each_ident(&mut copy, &mut |id| {
            if self.builtins.contains(id) {
                return;
            }
            let mapped = new
                .entry(id.clone())
                .or_insert_with(|| Ident::new(id.name().clone()));
            *id = mapped.clone();
        });
        copy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each identifier `each_ident` visits, as the index of the first place that holds it:
    /// two trees with equal lists share identifiers between the same places.
    fn sharing(unit: &mut TranslationUnit) -> Vec<(String, usize)> {
        let mut first: HashMap<Ident, usize> = HashMap::new();
        let mut out = Vec::new();
        each_ident(unit, &mut |id| {
            let n = first.len();
            let at = *first.entry(id.clone()).or_insert(n);
            out.push((id.name().clone(), at));
        });
        out
    }

    const MODULE: &str = "import package::a::{b, c as d};
        import package::e::f;
        struct S { x: vec3<f32>, y: array<f32, 4> }
        alias T = S;
        const N = 4u;
        var<private> g: array<T, N>;
        fn h(p: f32, q: S) -> f32 {
            var x = p;
            let y = q.x.x + b(x) + d;
            for (var i = 0u; i < N; i++) { let x = f32(i); g[i].y[0] = x + y; }
            { let p = 2.0; x += p; }
            return max(x, undeclared);
        }
        @fragment fn main(@builtin(position) pos: vec4<f32>) -> @location(0) vec4<f32> {
            let s = S(pos.xyz, array<f32, 4>(1.0, 2.0, 3.0, 4.0));
            return vec4(h(pos.x, s), f::k, 0.0, 1.0);
        }";

    #[test]
    fn a_copy_shares_as_retargeting_a_fresh_copy_does() {
        let unit: TranslationUnit = MODULE.parse().unwrap();
        let kept = Retargeted::new(&unit);
        let mut expected = fresh_copy(&unit);
        pass::retarget_idents(&mut expected);
        let mut copy = kept.copy();
        assert_eq!(sharing(&mut copy), sharing(&mut expected));
        assert_eq!(copy.to_string(), expected.to_string());
        // Shadowing made distinct identifiers of one name (`x`, `p`), and uses were pointed
        // at declarations: the sharing is not trivial.
        let list = sharing(&mut copy);
        let xs: HashSet<usize> = list.iter().filter(|(n, _)| n == "x").map(|p| p.1).collect();
        assert!(xs.len() >= 2, "{list:?}");
        assert!(list.iter().enumerate().any(|(i, (_, at))| *at != i));
    }

    #[test]
    fn copies_share_nothing_but_built_in_names() {
        let unit: TranslationUnit = MODULE.parse().unwrap();
        let kept = Retargeted::new(&unit);
        assert!(!kept.builtins.is_empty());
        let (mut one, mut two) = (kept.copy(), kept.copy());
        let mut ids_one = Vec::new();
        each_ident(&mut one, &mut |id| ids_one.push(id.clone()));
        let mut ids_two = Vec::new();
        each_ident(&mut two, &mut |id| ids_two.push(id.clone()));
        for (a, b) in ids_one.iter().zip(&ids_two) {
            assert_eq!(a == b, kept.builtins.contains(a), "{a}");
        }
        // A rename in one copy (as mangling does) reaches neither the other nor the kept tree.
        let GlobalDeclaration::Function(h) = one.global_declarations[4].node_mut() else {
            panic!("h is the fifth declaration");
        };
        h.ident.rename("renamed".into());
        assert!(one.to_string().contains("renamed(pos.x, s)"));
        assert!(!two.to_string().contains("renamed"));
        assert!(!kept.copy().to_string().contains("renamed"));
    }
}
