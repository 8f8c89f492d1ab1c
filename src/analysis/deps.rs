//! The static walk: which keyword sets can change which part of a pass's composed text.
//!
//! The walk visits a pass's composition tree in compose order (pass body, each imported module
//! where it would first be emitted), once, following every branch that some variant can take.
//! It keeps, for every name, either its value when that is the same in every variant, or the
//! keyword sets it depends on. A union-find over keyword sets joins:
//!
//! - the sets read by an `#if`/`#elif` (through names and the sets those names depend on)
//!   with the sets of its enclosing conditions;
//! - a `#define`/`#undef` under conditions makes its name depend on those conditions' sets;
//! - a module imported under conditions, or at several sites, is walked at each site that may
//!   emit it, with the sets of the earlier sites joined in (where it lands depends on them).
//!
//! Conditions whose value is the same in every variant are decided during the walk. What is
//! left is a sequence of *slots*: constant runs of lines (the same in every variant) and
//! *regions* (an `#if` or an `#import` at top level whose output depends on one class of sets).
//! A region's output depends only on the sets of its class.

use std::collections::HashMap;

use crate::preprocess::compose::ModuleGraph;
use crate::preprocess::expr::{BinOp, Expr};
use crate::preprocess::tree::Node;
use crate::shader::Pass;
use crate::variants::Space;

use super::bits::{Bits, UnionFind};
use super::compose::{LineIds, node_key};

/// Most nodes the walk visits before giving up (modules imported at many conditional sites
/// can be walked once per site).
const MAX_VISITS: usize = 4_000_000;

/// One slot of the composed text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Slot {
    /// Lines emitted by every variant.
    Const(Vec<u32>),
    /// A region: its output depends on the class of this set.
    Region(usize),
}

/// What the static walk found.
#[derive(Clone, Debug)]
pub(crate) struct Template {
    /// The slots, in output order.
    pub slots: Vec<Slot>,
    /// Region root nodes (by node key) and their slot.
    pub regions: HashMap<usize, usize>,
    /// Classes of keyword sets that must be enumerated together.
    pub uf: UnionFind,
}

/// The walk gave up (too many visits).
#[derive(Clone, Copy, Debug)]
pub(crate) struct TooComplex;

#[derive(Clone, Debug)]
enum Val {
    /// The same in every variant (`None`: undefined).
    Known(Option<i64>),
    /// Depends on these sets.
    Unknown(Bits),
}

enum Abs {
    Known(i64),
    Unknown(Bits),
}

#[derive(Clone, Debug)]
enum Included {
    No,
    Maybe(Bits),
    Yes,
}

/// Runs the static walk of `pass` over the variants of `space`.
pub(crate) fn analyze(
    graph: &ModuleGraph<'_>,
    ids: &LineIds,
    pass: &Pass,
    space: &Space<'_>,
) -> Result<Template, TooComplex> {
    // Constants (declaration files) are known; a keyword's def is its name (or, for a valued
    // set's `NAME=VALUE`, NAME), known when the space leaves its set one option.
    let mut vals: HashMap<Box<str>, Val> = pass
        .defs([])
        .into_iter()
        .map(|(name, value)| (Box::from(name), Val::Known(Some(value.as_i64()))))
        .collect();
    // A def several sets' options set (an option's defs) depends on all of them.
    let mut setters: HashMap<&str, Bits> = HashMap::new();
    for (s, set) in pass.sets.iter().enumerate() {
        match space.options(s).as_slice() {
            // The same option in every variant.
            [only] => {
                if let Some(k) = &set.options[*only as usize] {
                    for (name, value) in pass.keyword_defs(k) {
                        if !setters.contains_key(name) {
                            vals.insert(Box::from(name), Val::Known(Some(value.as_i64())));
                        }
                    }
                }
            }
            _ => {
                for k in set.keywords() {
                    for (name, _) in pass.keyword_defs(k) {
                        let bits = setters.entry(name).or_insert_with(|| Bits::single(s));
                        bits.insert(s);
                        vals.insert(Box::from(name), Val::Unknown(bits.clone()));
                    }
                }
            }
        }
    }
    let mut a = Analyzer {
        graph,
        ids,
        vals,
        included: vec![Included::No; graph.modules.len()],
        template: Template {
            slots: Vec::new(),
            regions: HashMap::new(),
            uf: UnionFind::new(pass.sets.len()),
        },
        visits: 0,
    };
    a.walk(pass.module, &pass.body, None)?;
    Ok(a.template)
}

struct Analyzer<'g, 'a> {
    graph: &'g ModuleGraph<'a>,
    ids: &'g LineIds,
    vals: HashMap<Box<str>, Val>,
    included: Vec<Included>,
    template: Template,
    visits: usize,
}

impl Analyzer<'_, '_> {
    fn val(&self, name: &str) -> Val {
        self.vals.get(name).cloned().unwrap_or(Val::Known(None))
    }

    fn eval(&self, e: &Expr) -> Abs {
        match e {
            Expr::Int(v) => Abs::Known(*v),
            Expr::Name(n) => match self.val(n) {
                Val::Known(v) => Abs::Known(v.unwrap_or(0)),
                Val::Unknown(d) => Abs::Unknown(d),
            },
            Expr::Defined(n) => match self.val(n) {
                Val::Known(v) => Abs::Known(v.is_some() as i64),
                Val::Unknown(d) => Abs::Unknown(d),
            },
            Expr::Not(e) => match self.eval(e) {
                Abs::Known(v) => Abs::Known(Expr::logical_not(v)),
                u => u,
            },
            Expr::Neg(e) => match self.eval(e) {
                Abs::Known(v) => Abs::Known(Expr::negate(v)),
                u => u,
            },
            Expr::Binary(op, a, b) => {
                let (a, b) = (self.eval(a), self.eval(b));
                match (op, a, b) {
                    (BinOp::Or, Abs::Known(x), _) | (BinOp::Or, _, Abs::Known(x)) if x != 0 => {
                        Abs::Known(1)
                    }
                    (BinOp::And, Abs::Known(0), _) | (BinOp::And, _, Abs::Known(0)) => {
                        Abs::Known(0)
                    }
                    (op, Abs::Known(x), Abs::Known(y)) => Abs::Known(op.apply(x, y)),
                    // `x || u` with x == 0, `x && u` with x != 0: the value is `u != 0`.
                    (BinOp::Or | BinOp::And, Abs::Known(_), u)
                    | (BinOp::Or | BinOp::And, u, Abs::Known(_)) => u,
                    (_, Abs::Unknown(mut x), Abs::Unknown(y)) => {
                        x.union_with(&y);
                        Abs::Unknown(x)
                    }
                    (_, Abs::Unknown(x), Abs::Known(_)) | (_, Abs::Known(_), Abs::Unknown(x)) => {
                        Abs::Unknown(x)
                    }
                }
            }
        }
    }

    /// Joins `deps` and the context into one class; returns the new context.
    fn join(&mut self, deps: &Bits, ctx: Option<usize>) -> usize {
        let mut all = deps.clone();
        if let Some(c) = ctx {
            all.insert(c);
        }
        self.template
            .uf
            .union_all(&all)
            .expect("a join has at least one set")
    }

    fn region(&mut self, node: &Node, class: usize) {
        let slot = self.template.slots.len();
        self.template.slots.push(Slot::Region(class));
        self.template.regions.insert(node_key(node), slot);
    }

    fn text(&mut self, lines: &[u32]) {
        match self.template.slots.last_mut() {
            Some(Slot::Const(run)) => run.extend_from_slice(lines),
            _ => self.template.slots.push(Slot::Const(lines.to_vec())),
        }
    }

    fn depend(&mut self, name: &str, ctx: usize, same: impl Fn(&Val) -> bool) {
        let prev = self.val(name);
        if same(&prev) {
            return;
        }
        let mut deps = match prev {
            Val::Unknown(d) => d,
            Val::Known(_) => Bits::default(),
        };
        deps.insert(ctx);
        self.vals.insert(Box::from(name), Val::Unknown(deps));
    }

    /// Walks with an explicit stack: nesting is bounded by the load limits, not by the
    /// thread's stack. Bodies are walked in compose order.
    fn walk(
        &mut self,
        module: usize,
        nodes: &[Node],
        ctx: Option<usize>,
    ) -> Result<(), TooComplex> {
        let graph = self.graph;
        let mut stack: Vec<(usize, &[Node], Option<usize>)> = vec![(module, nodes, ctx)];
        while let Some((module, nodes, ctx)) = stack.pop() {
            let Some((node, rest)) = nodes.split_first() else {
                continue;
            };
            stack.push((module, rest, ctx));
            self.visits += 1;
            if self.visits > MAX_VISITS {
                return Err(TooComplex);
            }
            match node {
                Node::Text(run) => {
                    if ctx.is_none() {
                        let ids: Vec<u32> = self.ids.per_module[module]
                            [run.start as usize..run.end as usize]
                            .iter()
                            .copied()
                            .filter(|&id| id != super::compose::NO_CODE)
                            .collect();
                        self.text(&ids);
                    }
                }
                Node::If(cond) => {
                    let mut deps = Bits::default();
                    let mut bodies = Vec::new();
                    let mut decided = false;
                    for (e, body) in &cond.branches {
                        match self.eval(e) {
                            Abs::Known(0) => {}
                            Abs::Known(_) => {
                                bodies.push(body.as_slice());
                                decided = true;
                                break;
                            }
                            Abs::Unknown(d) => {
                                deps.union_with(&d);
                                bodies.push(body.as_slice());
                            }
                        }
                    }
                    if !decided {
                        bodies.push(cond.otherwise.as_slice());
                    }
                    if deps.is_empty() {
                        // The same branch in every variant.
                        stack.push((module, bodies[0], ctx));
                    } else {
                        let class = self.join(&deps, ctx);
                        if ctx.is_none() {
                            self.region(node, class);
                        }
                        for body in bodies.into_iter().rev() {
                            stack.push((module, body, Some(class)));
                        }
                    }
                }
                Node::Define { name, value } => match ctx {
                    None => {
                        self.vals.insert(name.clone(), Val::Known(Some(*value)));
                    }
                    Some(c) => {
                        self.depend(name, c, |v| matches!(v, Val::Known(Some(x)) if x == value))
                    }
                },
                Node::Undef { name } => match ctx {
                    None => {
                        self.vals.insert(name.clone(), Val::Known(None));
                    }
                    Some(c) => self.depend(name, c, |v| matches!(v, Val::Known(None))),
                },
                Node::Import(index) => {
                    let target = graph.resolved[module][*index];
                    let body = graph.modules[target].body.as_slice();
                    match (self.included[target].clone(), ctx) {
                        (Included::Yes, _) => {}
                        (Included::No, None) => {
                            self.included[target] = Included::Yes;
                            stack.push((target, body, None));
                        }
                        (Included::No, Some(c)) => {
                            self.included[target] = Included::Maybe(Bits::single(c));
                            stack.push((target, body, Some(c)));
                        }
                        (Included::Maybe(d), None) => {
                            // Emitted here exactly when no earlier site emitted it.
                            let class = self.join(&d, None);
                            self.region(node, class);
                            self.included[target] = Included::Yes;
                            stack.push((target, body, Some(class)));
                        }
                        (Included::Maybe(d), Some(c)) => {
                            let class = self.join(&d, Some(c));
                            self.included[target] = Included::Maybe(Bits::single(class));
                            stack.push((target, body, Some(class)));
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
