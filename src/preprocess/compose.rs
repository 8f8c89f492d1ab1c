//! Composing one variant: walking the parsed tree with a keyword set's defines.

use std::collections::HashMap;
use std::ops::Range;

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
    let mut sink = TextSink {
        graph,
        with_map,
        out: Composed::default(),
    };
    sink.out.text.reserve(16 * 1024);
    walk(graph, module, body, defines, &mut sink);
    sink.out
}

/// What a composition walk does with what it takes: the composer copies text, the audit
/// records line ids. [`walk`] is generic over it, so each sink gets its own monomorphized
/// walk with no dynamic dispatch per line.
pub(crate) trait Sink {
    /// Lines `run` (indices into [`ParsedModule::lines`]) of module `module` are emitted.
    fn text(&mut self, module: usize, run: &Range<u32>);

    /// `node`, an `#if` or an `#import`, is about to be walked. A sink that returns `Some(key)`
    /// is called back with [`Sink::end`] once everything the node emits has been emitted.
    fn begin(&mut self, _node: &Node) -> Option<usize> {
        None
    }

    /// The output of the node that [`Sink::begin`] returned `key` for is complete.
    fn end(&mut self, _key: usize) {}
}

enum Frame<'n> {
    /// Nodes left to walk in a module.
    Nodes(usize, &'n [Node]),
    /// The end of the output of a node a sink asked about.
    End(usize),
}

/// The composition walk: `body` (nodes of module `module`) with `defines` in effect at the
/// start, in output order. Each module is emitted once, at its first import; later imports of
/// it are no-ops. Directive lines produce no output.
///
/// Walks with an explicit stack: nesting depth (`#if` inside imports inside `#if` …) is
/// bounded by limits, but not by the thread's stack size.
pub(crate) fn walk<S: Sink>(
    graph: &ModuleGraph<'_>,
    module: usize,
    body: &[Node],
    mut defines: HashMap<Box<str>, i64>,
    sink: &mut S,
) {
    let mut included = vec![false; graph.modules.len()];
    let mut stack = vec![Frame::Nodes(module, body)];
    while let Some(frame) = stack.pop() {
        let (module, nodes) = match frame {
            Frame::End(key) => {
                sink.end(key);
                continue;
            }
            Frame::Nodes(module, nodes) => (module, nodes),
        };
        let Some((node, rest)) = nodes.split_first() else {
            continue;
        };
        stack.push(Frame::Nodes(module, rest));
        if matches!(node, Node::If(_) | Node::Import(_))
            && let Some(key) = sink.begin(node)
        {
            stack.push(Frame::End(key));
        }
        match node {
            Node::Text(run) => sink.text(module, run),
            Node::If(cond) => {
                let lookup = |n: &str| defines.get(n).copied();
                let taken = cond
                    .branches
                    .iter()
                    .find(|(e, _)| e.eval(&lookup) != 0)
                    .map(|(_, b)| b);
                stack.push(Frame::Nodes(module, taken.unwrap_or(&cond.otherwise)));
            }
            Node::Define { name, value } => {
                defines.insert(name.clone(), *value);
            }
            Node::Undef { name } => {
                defines.remove(name);
            }
            Node::Import(index) => {
                let target = graph.resolved[module][*index];
                if !included[target] {
                    included[target] = true;
                    stack.push(Frame::Nodes(target, &graph.modules[target].body));
                }
            }
        }
    }
}

/// The composer's sink: copies the lines, keeping the line map unless lean.
struct TextSink<'g, 'a> {
    graph: &'g ModuleGraph<'a>,
    with_map: bool,
    out: Composed,
}

impl Sink for TextSink<'_, '_> {
    fn text(&mut self, module: usize, run: &Range<u32>) {
        let parsed = &self.graph.modules[module];
        let text = self.graph.files.text(parsed.file);
        let range = run.start as usize..run.end as usize;
        for (line, &comment_only) in parsed.lines[range.clone()]
            .iter()
            .zip(&parsed.comment_only[range])
        {
            if !self.with_map && comment_only {
                continue;
            }
            if self.with_map {
                self.out
                    .map
                    .push(self.out.text.len(), parsed.file, line.start as usize);
            }
            self.out
                .text
                .push_str(&text[line.start as usize..line.end as usize]);
            self.out.text.push('\n');
        }
    }
}
