//! Composing one variant: walking the parsed tree with a keyword set's defines.

use std::collections::HashMap;

use crate::diagnostic::SourceFiles;

use super::line_map::LineMap;
use super::tree::{Node, ParsedModule};

/// The modules of a library with their imports resolved, ready to compose from.
pub struct ModuleGraph<'a> {
    /// Parsed modules, indexed by module id.
    pub modules: &'a [ParsedModule],
    /// For each module, the module id of each of its imports (same order as `imports`).
    pub resolved: &'a [Vec<usize>],
    /// The source texts.
    pub files: &'a SourceFiles,
}

/// The WGSL text of one variant and the map back to its sources.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Composed {
    /// Final WGSL.
    pub text: String,
    /// Where each output line came from.
    pub map: LineMap,
}

/// Composes `body` (nodes of module `module`) with `defines` in effect at the start.
///
/// Each module is emitted once, at its first import; later imports of it are no-ops.
/// Directive lines produce no output.
///
/// With `with_map` false the composition is *lean*: blank and comment-only lines are left out
/// and no line map is kept. The program is the same (half the bytes for naga to lex in the
/// bundled library): both texts copy the same lines, each ended with `\n`, and a line is left
/// out only when [`super::lines::scan`] found it blank or a `//` comment at block-comment depth
/// 0, with WGSL's own line breaks and blankspace, so removing it cannot join or split tokens or
/// comments. A caller that hashes or validates the lean text composes again, with the map, to
/// locate an error.
pub fn compose(
    graph: &ModuleGraph<'_>,
    module: usize,
    body: &[Node],
    defines: HashMap<Box<str>, i64>,
    with_map: bool,
) -> Composed {
    let mut c = Composer {
        graph,
        defines,
        included: vec![false; graph.modules.len()],
        with_map,
        out: Composed::default(),
    };
    c.out.text.reserve(16 * 1024);
    c.walk(module, body);
    c.out
}

struct Composer<'g, 'a> {
    graph: &'g ModuleGraph<'a>,
    defines: HashMap<Box<str>, i64>,
    included: Vec<bool>,
    with_map: bool,
    out: Composed,
}

impl Composer<'_, '_> {
    /// Walks with an explicit stack: nesting depth (`#if` inside imports inside `#if` …) is
    /// bounded by limits, but not by the thread's stack size.
    fn walk(&mut self, module: usize, nodes: &[Node]) {
        let graph = self.graph;
        let mut stack: Vec<(usize, &[Node])> = vec![(module, nodes)];
        while let Some((module, nodes)) = stack.pop() {
            let Some((node, rest)) = nodes.split_first() else {
                continue;
            };
            stack.push((module, rest));
            let parsed = &graph.modules[module];
            match node {
                Node::Text(run) => {
                    let text = graph.files.text(parsed.file);
                    for (line, &comment_only) in parsed.lines[run.start as usize..run.end as usize]
                        .iter()
                        .zip(&parsed.comment_only[run.start as usize..run.end as usize])
                    {
                        if !self.with_map && comment_only {
                            continue;
                        }
                        if self.with_map {
                            self.out.map.push(
                                self.out.text.len(),
                                parsed.file,
                                line.start as usize,
                            );
                        }
                        self.out
                            .text
                            .push_str(&text[line.start as usize..line.end as usize]);
                        self.out.text.push('\n');
                    }
                }
                Node::If(cond) => {
                    let defines = &self.defines;
                    let lookup = |n: &str| defines.get(n).copied();
                    let taken = cond
                        .branches
                        .iter()
                        .find(|(e, _)| e.eval(&lookup) != 0)
                        .map(|(_, b)| b);
                    stack.push((module, taken.unwrap_or(&cond.otherwise)));
                }
                Node::Define { name, value } => {
                    self.defines.insert(name.clone(), *value);
                }
                Node::Undef { name } => {
                    self.defines.remove(name);
                }
                Node::Import(index) => {
                    let target = graph.resolved[module][*index];
                    if !self.included[target] {
                        self.included[target] = true;
                        stack.push((target, &graph.modules[target].body));
                    }
                }
            }
        }
    }
}
