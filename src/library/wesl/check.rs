//! `wesl`'s check of a linked program (`wesl::pass::validate_wgsl`, 0.6.0), answered in time
//! linear in the program.
//!
//! `validate_wgsl` checks four things: every name used in a type or an expression is shared
//! with a declaration or is a built-in name (an identifier used once is undeclared);
//! module-scope names are unique; no declaration reaches itself through the names its types,
//! expressions and calls use (a cycle); each call names a function, a struct or an alias of
//! one, or a built-in function or constructor, with as many arguments as the function has
//! parameters (a struct: its members, or none). It looks each name up by scanning the
//! declarations, and searches for cycles from every declaration anew, so on Bevy's programs
//! (over a thousand declarations) it took about a third of a variant's compile.
//!
//! [`validate_wgsl`] answers the same question with hash lookups and one depth-first search.
//! It only decides *whether* the program passes: where it finds a fault it calls `wesl`'s own
//! check, whose verdict and diagnostic are the ones reported. So the verdict is always
//! `wesl`'s as long as this check passes only programs `wesl`'s passes — it checks all that
//! `wesl`'s does, the same way; `tests` compare the two on programs with each fault.

// `Ident` hashes and compares by the address of its shared name, which mutating the name
// (interior mutability) does not change: a valid map key.
#![allow(clippy::mutable_key_type)]

use std::collections::{HashMap, HashSet};
use std::sync::LazyLock;

use wesl::pass::{self, Visit};
use wgsl_parse::SyntaxNode;
use wgsl_parse::syntax::{
    Expression, ExpressionNode, FunctionCall, GlobalDeclaration, Ident, TranslationUnit,
    TypeExpression,
};

/// The built-in names `wesl` knows (`wgsl-types`' list, as `wesl`'s own table is built).
static BUILTIN_NAMES: LazyLock<HashSet<&'static str>> =
    LazyLock::new(|| wgsl_types::idents::iter_builtin_idents().collect());

/// `wesl::pass::validate_wgsl`'s verdict on `module`, and its diagnostic where it fails.
pub(super) fn validate_wgsl(module: &TranslationUnit) -> Result<(), wesl::Error> {
    if passes(module) {
        Ok(())
    } else {
        pass::validate_wgsl(module).map_err(wesl::Error::from)
    }
}

/// Whether `module` passes all four checks. Looks identifiers up by reference: cloning one
/// would change the use counts the first check reads.
fn passes(module: &TranslationUnit) -> bool {
    let decls = &module.global_declarations;
    // Each name to its first declaration (what `wesl`'s scans find).
    let mut by_ident: HashMap<&Ident, usize> = HashMap::new();
    for (i, decl) in decls.iter().enumerate() {
        if let Some(id) = ident(decl.node()) {
            by_ident.entry(id).or_insert(i);
        }
    }
    defined_symbols(module) && unique_names(module) && acyclic(module, &by_ident) && {
        let calls_ok = |decl: &GlobalDeclaration| {
            Visit::<ExpressionNode>::visit(decl).all(|expr| match expr.node() {
                Expression::FunctionCall(call) => callable(call, &call.ty.ident, module, &by_ident),
                _ => true,
            })
        };
        decls.iter().all(|d| calls_ok(d.node()))
    }
}

/// A module-scope declaration's name, borrowed.
fn ident(decl: &GlobalDeclaration) -> Option<&Ident> {
    match decl {
        GlobalDeclaration::Declaration(d) => Some(&d.ident),
        GlobalDeclaration::TypeAlias(d) => Some(&d.ident),
        GlobalDeclaration::Struct(d) => Some(&d.ident),
        GlobalDeclaration::Function(d) => Some(&d.ident),
        GlobalDeclaration::Void
        | GlobalDeclaration::ConstAssert(_)
        | GlobalDeclaration::Compound(_) => None,
    }
}

/// Every name used in a type or an expression is declared or built in (`wesl`: its
/// identifier is shared, or its name is a built-in one, or it is `_`).
fn defined_symbols(module: &TranslationUnit) -> bool {
    fn ty_ok(ty: &TypeExpression) -> bool {
        if ty.path.is_none()
            && ty.ident.use_count() == 1
            && !BUILTIN_NAMES.contains(ty.ident.name().as_str())
            && *ty.ident.name() != "_"
        {
            return false;
        }
        ty.template_args
            .iter()
            .flatten()
            .all(|arg| expr_ok(&arg.expression))
    }
    fn expr_ok(expr: &ExpressionNode) -> bool {
        match expr.node() {
            Expression::TypeOrIdentifier(ty) => ty_ok(ty),
            Expression::FunctionCall(call) => ty_ok(&call.ty) && call.arguments.iter().all(expr_ok),
            other => Visit::<ExpressionNode>::visit(other).all(expr_ok),
        }
    }
    module.global_declarations.iter().all(|decl| {
        let decl = decl.node();
        let types_ok = match decl {
            GlobalDeclaration::Declaration(d) => d.ty.iter().all(ty_ok),
            GlobalDeclaration::TypeAlias(d) => ty_ok(&d.ty),
            GlobalDeclaration::Struct(d) => d.members.iter().all(|m| ty_ok(&m.ty)),
            GlobalDeclaration::Function(d) => {
                d.parameters.iter().all(|p| ty_ok(&p.ty)) && d.return_type.iter().all(ty_ok)
            }
            _ => true,
        };
        Visit::<ExpressionNode>::visit(decl).all(expr_ok) && types_ok
    })
}

/// No two module-scope names (imports and declarations without a condition) are equal.
fn unique_names(module: &TranslationUnit) -> bool {
    let conditional = |attrs: &[wgsl_parse::syntax::AttributeNode]| {
        attrs
            .iter()
            .any(|a| a.is_if() || a.is_elif() || a.is_else())
    };
    let mut seen = HashSet::new();
    // Imports are gone from a linked program; one left over is checked as `wesl` would.
    for import in &module.imports {
        if conditional(import.attributes()) {
            continue;
        }
        let mut names = Vec::new();
        import_names(&import.content, &mut names);
        if !names.into_iter().all(|n| seen.insert(n)) {
            return false;
        }
    }
    module.global_declarations.iter().all(|decl| {
        conditional(decl.attributes())
            || ident(decl.node()).is_none_or(|id| seen.insert(id.to_string()))
    })
}

/// The names an import brings in.
fn import_names(content: &wgsl_parse::syntax::ImportContent, out: &mut Vec<String>) {
    match content {
        wgsl_parse::syntax::ImportContent::Item(item) => {
            out.push(item.rename.as_ref().unwrap_or(&item.ident).to_string())
        }
        wgsl_parse::syntax::ImportContent::Collection(items) => {
            for item in items {
                import_names(&item.content, out);
            }
        }
    }
}

/// No declaration reaches itself: the graph whose edges go from a declaration to the first
/// declaration of each name its types (calls included) use has no cycle (`wesl` searches
/// from every named declaration for its own name; a cycle is found from any declaration on
/// it). Iterative colouring, so deep chains cannot overflow the stack.
fn acyclic(module: &TranslationUnit, by_ident: &HashMap<&Ident, usize>) -> bool {
    let decls = &module.global_declarations;
    let edges: Vec<Vec<usize>> = decls
        .iter()
        .map(|decl| {
            let mut out = Vec::new();
            Visit::<TypeExpression>::visit_rec(decl.node(), &mut |ty: &TypeExpression| {
                if let Some(&to) = by_ident.get(&ty.ident) {
                    out.push(to);
                }
            });
            out
        })
        .collect();
    // 0: not seen, 1: on the current path, 2: done.
    let mut state = vec![0u8; decls.len()];
    for start in 0..decls.len() {
        if state[start] != 0 || ident(decls[start].node()).is_none() {
            continue;
        }
        let mut stack = vec![(start, 0usize)];
        state[start] = 1;
        while let Some((node, next)) = stack.pop() {
            match edges[node].get(next) {
                Some(&to) => {
                    stack.push((node, next + 1));
                    match state[to] {
                        1 => return false,
                        0 => {
                            state[to] = 1;
                            stack.push((to, 0));
                        }
                        _ => {}
                    }
                }
                None => state[node] = 2,
            }
        }
    }
    true
}

/// `wesl`'s check of one call (the outermost expressions of a declaration): a function with
/// as many parameters as arguments, a struct with as many members (or no arguments), an
/// alias of one without template arguments (followed), an alias with them, or a built-in
/// function or constructor.
fn callable(
    call: &FunctionCall,
    name: &Ident,
    module: &TranslationUnit,
    by_ident: &HashMap<&Ident, usize>,
) -> bool {
    let mut name = name;
    // An alias chain longer than the declarations is a cycle; `acyclic` refused it already.
    for _ in 0..=module.global_declarations.len() {
        match by_ident
            .get(name)
            .map(|&i| module.global_declarations[i].node())
        {
            Some(GlobalDeclaration::Function(f)) => {
                return call.arguments.len() == f.parameters.len();
            }
            Some(GlobalDeclaration::Struct(s)) => {
                return call.arguments.is_empty() || call.arguments.len() == s.members.len();
            }
            Some(GlobalDeclaration::TypeAlias(alias)) => {
                if alias.ty.template_args.is_some() {
                    return true;
                }
                name = &alias.ty.ident;
            }
            Some(_) => return false,
            None => {
                let n = name.name();
                return wgsl_types::idents::BUILTIN_FUNCTION_NAMES.contains(&n.as_str())
                    || wgsl_types::idents::BUILTIN_CONSTRUCTOR_NAMES.contains(&n.as_str());
            }
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A program as `wesl` links one: parsed, names pointed at their declarations.
    fn linked(text: &str) -> TranslationUnit {
        let mut unit: TranslationUnit = text.parse().expect("parses");
        pass::retarget_idents(&mut unit);
        unit
    }

    /// This check's verdict is `wesl`'s.
    fn agrees(text: &str) -> bool {
        let unit = linked(text);
        let ours = passes(&unit);
        let theirs = pass::validate_wgsl(&unit).is_ok();
        assert_eq!(ours, theirs, "verdicts differ on:\n{text}");
        ours
    }

    #[test]
    fn valid_programs_pass() {
        assert!(agrees(
            "struct S { a: vec3f, b: f32 }
             alias T = S;
             const N = 4u;
             var<private> xs: array<S, N>;
             fn f(s: S) -> f32 { return s.b + g(1.0); }
             fn g(x: f32) -> f32 { let t = T(vec3f(x), x); return max(x, t.b); }
             @fragment fn main() -> @location(0) vec4f { return vec4f(f(xs[0]), 0.0, 0.0, 1.0); }"
        ));
    }

    #[test]
    fn each_fault_is_found_as_wesl_finds_it() {
        // An undeclared name.
        assert!(!agrees("fn f() -> f32 { return missing(1.0); }"));
        assert!(!agrees("var<private> v: Missing;"));
        // A name declared twice.
        assert!(!agrees("fn f() {} fn f() {}"));
        // Recursion, direct and through another function; a struct containing itself.
        assert!(!agrees("fn f() { f(); }"));
        assert!(!agrees("fn f() { g(); } fn g() { f(); }"));
        assert!(!agrees("struct S { s: array<S, 2> }"));
        // Calls: wrong arity, a constant called, a struct with too few members.
        assert!(!agrees(
            "fn f(x: f32) -> f32 { return x; } fn g() { let a = f(); }"
        ));
        assert!(!agrees("const C = 1; fn g() { let a = C(); }"));
        assert!(!agrees(
            "struct S { a: f32, b: f32 } fn g() { let s = S(1.0); }"
        ));
        // An alias of a function-like struct, called with the wrong count.
        assert!(!agrees(
            "struct S { a: f32 } alias T = S; fn g() { let s = T(1.0, 2.0); }"
        ));
    }

    #[test]
    fn what_wesl_leaves_unchecked_passes_here_too() {
        // `wesl` checks the outermost call of an expression only.
        assert!(agrees(
            "fn f(x: f32) -> f32 { return x; } fn g() { let a = 1.0 + f(); }"
        ));
        // A call statement is not an expression.
        assert!(agrees("fn f(x: f32) {} fn g() { f(); }"));
        // A struct built from no arguments.
        assert!(agrees("struct S { a: f32 } fn g() { let s = S(); }"));
    }
}
