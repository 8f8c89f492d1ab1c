//! The items that no variant of a pass reaches, found without composing any variant.
//!
//! Every module the pass can import is split into items with **every** `#if` branch read (each
//! branch from the state before the `#if`, as the all-branches scan of the exports does), and
//! an item's references are the union over the branches that declare it. Any one variant's
//! reference graph is then part of this union graph, so an item the union graph does not reach
//! from the roots is reached by no variant. The converse need not hold (branches that never
//! occur together are still joined), so the list can only be shorter than the truth.

use std::collections::{BTreeMap, HashMap};

use crate::library::Library;
use crate::preprocess::tree::Node;
use crate::shader::Pass;

use crate::reach::items::{Item, Splitter, State};

/// Top-level items of one module that no variant of a pass reaches.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Unreached {
    /// The module's path (relative, without extension).
    pub module: String,
    /// The names of its unreached items, in the order they are declared.
    pub names: Vec<String>,
}

/// The items of the modules `pass` composes that none of its variants reaches, per module in
/// the order the modules are first imported (empty for a tree in another dialect, which its
/// own composer prunes).
///
/// ```
/// let lib = wgsl_variants_shaders::library().unwrap();
/// let pass = lib.pass("deferred_final", "Final").unwrap();
/// for u in wgsl_variants::analysis::unreached(&lib, pass) {
///     println!("{}: {}", u.module, u.names.join(", "));
/// }
/// ```
pub fn unreached(lib: &Library, pass: &Pass) -> Vec<Unreached> {
    if lib.dialect() != crate::preprocess::Dialect::WgslVariants {
        return Vec::new();
    }
    let graph = lib.module_graph();
    let Scan {
        splitter,
        module_of,
        joined,
        ..
    } = Scan::pass(&graph, pass);
    let items = splitter.items;
    // Without an entry point a variant is validated whole: nothing is left out.
    if !items.iter().any(|i| i.entry) {
        return Vec::new();
    }

    let (by_name, mut reached, mut stack) = start(&items);
    let reach = |i: usize, reached: &mut Vec<bool>, stack: &mut Vec<usize>| {
        if !reached[i] {
            reached[i] = true;
            stack.push(i);
        }
    };
    while let Some(i) = stack.pop() {
        let item: &Item<'_> = &items[i];
        // Everything declared under the same name, in any branch, and items joined to it.
        let same = item.name.and_then(|n| by_name.get(n)).into_iter().flatten();
        let refs = item.refs.iter().filter_map(|r| by_name.get(r)).flatten();
        let partners = joined
            .iter()
            .filter_map(|&(a, b)| (a == i).then_some(b).or_else(|| (b == i).then_some(a)));
        let next: Vec<usize> = same.chain(refs).copied().chain(partners).collect();
        for j in next {
            reach(j, &mut reached, &mut stack);
        }
    }

    let mut per_module: BTreeMap<usize, Vec<String>> = BTreeMap::new();
    let mut order: Vec<usize> = Vec::new();
    for (i, item) in items.iter().enumerate() {
        let Some(name) = item.name else { continue };
        if reached[i] {
            continue;
        }
        let module = module_of[i];
        let names = per_module.entry(module).or_insert_with(|| {
            order.push(module);
            Vec::new()
        });
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
    }
    order
        .into_iter()
        .map(|m| Unreached {
            module: lib.module_paths()[m].clone(),
            names: per_module.remove(&m).unwrap_or_default(),
        })
        .collect()
}

/// Whether pruning leaves every variant of `pass` as composed: each item the pass can compose
/// is a root or is mentioned, outside any `#if` of the mentioning item, by an item that is
/// itself kept whenever it is composed. The audit's proof that every variant has its own text
/// ([`super::proves_all_distinct`]) holds for the pruned texts only then. `false` is
/// always safe (validation then keeps an index of the texts it has seen).
pub fn prunes_nothing(lib: &Library, pass: &Pass) -> bool {
    if lib.dialect() != crate::preprocess::Dialect::WgslVariants {
        return false;
    }
    let graph = lib.module_graph();
    let items = Scan::pass(&graph, pass).splitter.items;
    // Without an entry point a variant is validated whole.
    if !items.iter().any(|i| i.entry) {
        return true;
    }
    let (by_name, mut kept, mut stack) = start(&items);
    while let Some(i) = stack.pop() {
        let item = &items[i];
        let mut conditional = item.cond_refs.clone();
        for r in &item.refs {
            // Each conditional mention is also in `refs`: skip it once.
            if let Some(at) = conditional.iter().position(|c| c == r) {
                conditional.swap_remove(at);
                continue;
            }
            for &j in by_name.get(r).into_iter().flatten() {
                if !kept[j] {
                    kept[j] = true;
                    stack.push(j);
                }
            }
        }
    }
    kept.iter().all(|&k| k)
}

/// Where a walk of the reference graph starts: the items of each name, a mark per item (the
/// roots marked) and the roots to visit.
fn start<'t>(items: &[Item<'t>]) -> (HashMap<&'t str, Vec<usize>>, Vec<bool>, Vec<usize>) {
    let mut by_name: HashMap<&str, Vec<usize>> = HashMap::new();
    for (i, item) in items.iter().enumerate() {
        if let Some(name) = item.name {
            by_name.entry(name).or_default().push(i);
        }
    }
    let stack: Vec<usize> = (0..items.len()).filter(|&i| items[i].is_root()).collect();
    let mut marked = vec![false; items.len()];
    for &i in &stack {
        marked[i] = true;
    }
    (by_name, marked, stack)
}

/// The all-branches walk: feeds every line of every branch to one splitter.
struct Scan<'t> {
    splitter: Splitter<'t>,
    /// The module of each item.
    module_of: Vec<usize>,
    /// Items that different branches left open and the text after the `#if` continues: each
    /// reaches the other (the continuation's references were given to one of them only).
    joined: Vec<(usize, usize)>,
    visited: Vec<bool>,
    line: u32,
}

impl<'t> Scan<'t> {
    /// Scans every module `pass` can compose, every branch read.
    fn pass(graph: &crate::preprocess::compose::ModuleGraph<'t>, pass: &'t Pass) -> Scan<'t> {
        let mut scan = Scan {
            splitter: Splitter::default(),
            module_of: Vec::new(),
            joined: Vec::new(),
            visited: vec![false; graph.modules.len()],
            line: 0,
        };
        scan.visited[pass.module] = true;
        scan.nodes(graph, pass.module, &pass.body);
        scan
    }

    fn nodes(
        &mut self,
        graph: &crate::preprocess::compose::ModuleGraph<'t>,
        module: usize,
        nodes: &'t [Node],
    ) {
        let parsed = &graph.modules[module];
        let text = graph.files.text(parsed.file);
        for node in nodes {
            match node {
                Node::Text(run) => {
                    for line in &parsed.lines[run.start as usize..run.end as usize] {
                        self.splitter
                            .line(self.line, &text[line.start as usize..line.end as usize]);
                        self.line += 1;
                    }
                    self.module_of.resize(self.splitter.items.len(), module);
                }
                Node::If(cond) => {
                    let start: State = self.splitter.state.clone();
                    self.splitter.level += 1;
                    let mut ends: Vec<State> = Vec::new();
                    for body in cond
                        .branches
                        .iter()
                        .map(|(_, b)| b)
                        .chain(std::iter::once(&cond.otherwise))
                    {
                        self.splitter.state = start.clone();
                        self.nodes(graph, module, body);
                        ends.push(self.splitter.state.clone());
                    }
                    self.splitter.level -= 1;
                    let first = ends.swap_remove(0);
                    if let Some(a) = first.open() {
                        for b in ends.iter().filter_map(State::open) {
                            if a != b {
                                self.joined.push((a, b));
                            }
                        }
                    }
                    self.splitter.state = first;
                }
                Node::Import(index) => {
                    let target = graph.resolved[module][*index];
                    if target != usize::MAX && !self.visited[target] {
                        self.visited[target] = true;
                        self.nodes(graph, target, &graph.modules[target].body);
                    }
                }
                Node::Define { .. } | Node::Undef { .. } => {}
            }
        }
    }
}
