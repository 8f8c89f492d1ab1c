//! Composing one variant: walking the parsed tree with a keyword set's defines.

use std::collections::HashMap;
use std::ops::Range;

use crate::diagnostic::SourceFiles;

use super::line_map::LineMap;
use super::tree::{Node, ParsedModule};

/// The modules of a library with their imports resolved, ready to compose from.
pub(crate) struct ModuleGraph<'a> {
    /// Parsed modules, indexed by module id.
    pub modules: &'a [ParsedModule],
    /// For each module, the module id of each of its imports (same order as `imports`).
    pub resolved: &'a [Vec<usize>],
    /// The source texts.
    pub files: &'a SourceFiles,
}

impl ModuleGraph<'_> {
    /// The modules `root` reaches through its imports under any conditions, `root` first
    /// (unresolved imports skipped).
    pub fn reach(&self, root: usize) -> Vec<usize> {
        reach(self.resolved, root)
    }

    /// Whether `name` appears as a whole word in one of `modules` (in a directive, a
    /// condition, a substitution or code).
    pub fn mentions(&self, modules: &[usize], name: &str) -> bool {
        modules.iter().any(|&m| {
            let text = self.files.text(self.modules[m].file);
            text.match_indices(name).any(|(i, _)| {
                let word = |c: Option<char>| c.is_some_and(|c| c.is_alphanumeric() || c == '_');
                !word(text[..i].chars().next_back()) && !word(text[i + name.len()..].chars().next())
            })
        })
    }
}

/// The modules `root` reaches in an import graph, `root` first.
pub(crate) fn reach(resolved: &[Vec<usize>], root: usize) -> Vec<usize> {
    let mut reached = vec![root];
    let mut at = 0;
    while let Some(&m) = reached.get(at) {
        at += 1;
        for &t in resolved.get(m).map_or(&[][..], Vec::as_slice) {
            if t != usize::MAX && !reached.contains(&t) {
                reached.push(t);
            }
        }
    }
    reached
}

/// The WGSL text of one variant and the map back to its sources.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Composed {
    /// Final WGSL.
    pub text: String,
    /// Where each output line came from (empty for a program composed by naga_oil, which
    /// writes it anew).
    pub map: LineMap,
    /// For a tree in another dialect: the composer's error, when it could not compose the
    /// variant (`text` then describes the error, so different errors hash differently).
    /// Validating the composition reports it; this crate's own composition never fails.
    pub failure: Option<Box<crate::error::VariantError>>,
    /// For a tree whose composer validates what it composes (WESL): the profile naga already
    /// found `text` valid for (nothing that profile refuses either), so that the validation
    /// stage does not parse and validate it again for that profile. `None` otherwise (and in
    /// what other code builds: it is only a shortcut).
    pub validated: Option<crate::validator::Profile>,
}

impl Composed {
    /// A variant that has no program (its composer refused it). Its text is the error itself,
    /// so that variants failing alike (same stage, message and places) share one text and are
    /// one failure with many keyword sets, as variants with one program are.
    pub fn failed(error: crate::error::VariantError) -> Composed {
        Composed {
            text: format!(
                "// {:?} {} {:?}\n",
                error.stage, error.message, error.labels
            ),
            failure: Some(Box::new(error)),
            ..Composed::default()
        }
    }
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
pub(crate) fn compose(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::preprocess::parse::{ParseLimits, parse_module};

    /// A hand-built library: `(path, text, module ids of its imports)`, module id = index.
    struct Fixture {
        files: SourceFiles,
        modules: Vec<ParsedModule>,
        resolved: Vec<Vec<usize>>,
    }

    impl Fixture {
        fn new(sources: &[(&str, &str, &[usize])]) -> Fixture {
            let mut files = SourceFiles::new();
            let mut modules = Vec::new();
            let mut resolved = Vec::new();
            for (path, text, imports) in sources {
                let file = files.add(path.to_string(), text.to_string());
                let parsed = parse_module(file, text, ParseLimits::default()).unwrap();
                assert_eq!(parsed.imports.len(), imports.len());
                modules.push(parsed);
                resolved.push(imports.to_vec());
            }
            Fixture {
                files,
                modules,
                resolved,
            }
        }

        /// Composes the body of module `module` with `defines` on.
        fn compose(&self, module: usize, defines: &[&str], with_map: bool) -> Composed {
            let graph = ModuleGraph {
                modules: &self.modules,
                resolved: &self.resolved,
                files: &self.files,
            };
            let defines = defines.iter().map(|d| (Box::from(*d), 1)).collect();
            compose(
                &graph,
                module,
                &self.modules[module].body,
                defines,
                with_map,
            )
        }
    }

    /// The branch taken is the one whose condition the starting defines make true; directive
    /// lines produce no output.
    #[test]
    fn branch_taken_by_define() {
        let f = Fixture::new(&[(
            "m.wgsl",
            "a\n#ifdef RED\nred\n#elif GREEN\ngreen\n#else\nblue\n#endif\nz",
            &[],
        )]);
        assert_eq!(f.compose(0, &["RED"], true).text, "a\nred\nz\n");
        assert_eq!(f.compose(0, &["RED", "GREEN"], true).text, "a\nred\nz\n");
        assert_eq!(f.compose(0, &["GREEN"], true).text, "a\ngreen\nz\n");
        assert_eq!(f.compose(0, &[], true).text, "a\nblue\nz\n");
    }

    /// Defines flow through an import in text order: the imported module sees what was
    /// defined before the `#import`, the importer sees what the module defines, and an
    /// `#undef` after the import takes effect from there on.
    #[test]
    fn define_undef_order_across_import() {
        let f = Fixture::new(&[
            (
                "m.wgsl",
                "#ifdef X\nm_x\n#else\nm_no_x\n#endif\n#define Y",
                &[],
            ),
            (
                "main.wgsl",
                "#define X\n#import m\n#undef X\n#ifdef X\nmain_x\n#endif\n#ifdef Y\nmain_y\n#endif",
                &[0],
            ),
            (
                "late.wgsl",
                "#import m\n#define X\n#ifdef X\nlate_x\n#endif",
                &[0],
            ),
        ]);
        assert_eq!(f.compose(1, &[], true).text, "m_x\nmain_y\n");
        // Defined after the import: the module does not see it.
        assert_eq!(f.compose(2, &[], true).text, "m_no_x\nlate_x\n");
        // A starting define removed by `#undef` is off afterwards.
        assert_eq!(f.compose(1, &["X"], true).text, "m_x\nmain_y\n");
    }

    /// A module imported by two others (a diamond) is emitted once, at its first import.
    #[test]
    fn diamond_included_once() {
        let f = Fixture::new(&[
            ("common.wgsl", "common", &[]),
            ("a.wgsl", "#import common\na", &[0]),
            ("b.wgsl", "#import common\nb", &[0]),
            (
                "main.wgsl",
                "#import a\n#import b\n#import common\nmain",
                &[1, 2, 0],
            ),
        ]);
        let out = f.compose(3, &[], true).text;
        assert_eq!(out, "common\na\nb\nmain\n");
        assert_eq!(out.matches("common").count(), 1);
    }

    /// A module imported only inside a branch that is not taken is not emitted, and a later
    /// import still emits it.
    #[test]
    fn import_in_untaken_branch() {
        let f = Fixture::new(&[
            ("m.wgsl", "m", &[]),
            (
                "main.wgsl",
                "#ifdef X\n#import m\n#endif\nx\n#import m",
                &[0, 0],
            ),
        ]);
        assert_eq!(f.compose(1, &[], true).text, "x\nm\n");
        assert_eq!(f.compose(1, &["X"], true).text, "m\nx\n");
    }

    /// The lean text drops blank and comment-only lines and keeps no map; the code lines are
    /// the same, in the same order, as in the full text.
    #[test]
    fn lean_versus_full() {
        let text = "// header\nfn a() {}\n\n   // indented\nfn b() {} // trailing\n\t\nfn c() {}";
        let f = Fixture::new(&[("m.wgsl", text, &[])]);
        let full = f.compose(0, &[], true);
        let lean = f.compose(0, &[], false);
        assert_eq!(full.text, format!("{text}\n"));
        assert_eq!(full.map.len(), 7);
        assert_eq!(lean.text, "fn a() {}\nfn b() {} // trailing\nfn c() {}\n");
        assert!(lean.map.is_empty());
        let code: Vec<&str> = full
            .text
            .lines()
            .filter(|l| {
                let t = l.trim();
                !t.is_empty() && !t.starts_with("//")
            })
            .collect();
        assert_eq!(code, lean.text.lines().collect::<Vec<_>>());
    }

    /// Every offset of every output line maps back to the same byte of the source file and
    /// line it was copied from, across imports.
    #[test]
    fn line_map_points_back() {
        let f = Fixture::new(&[
            (
                "lib.wgsl",
                "// lib\nfn helper() -> f32 { return 1.0; }",
                &[],
            ),
            (
                "main.wgsl",
                "#ifdef X\nfn x() {}\n#endif\n#import lib\nfn main() { helper(); }",
                &[0],
            ),
        ]);
        let out = f.compose(1, &["X"], true);
        assert_eq!(
            out.text,
            "fn x() {}\n// lib\nfn helper() -> f32 { return 1.0; }\nfn main() { helper(); }\n"
        );
        assert_eq!(out.map.len(), 4);
        let mut start = 0;
        for line in out.text.split_inclusive('\n') {
            let content = line.trim_end_matches('\n');
            for col in 0..content.len() {
                let span = out
                    .map
                    .to_original(start + col, start + col + 1, &out.text)
                    .unwrap();
                let source = f.files.text(span.file);
                assert_eq!(
                    &source[span.start as usize..span.end as usize],
                    &content[col..col + 1],
                    "output offset {}",
                    start + col
                );
            }
            start += line.len();
        }
        // `helper` in `fn main() { helper(); }` points into main.wgsl.
        let at = out.text.rfind("helper").unwrap();
        let span = out.map.to_original(at, at + 6, &out.text).unwrap();
        assert_eq!(span.file, f.modules[1].file);
        assert_eq!(
            span.start as usize,
            "#ifdef X\nfn x() {}\n#endif\n#import lib\nfn main() { ".len()
        );
        assert_eq!(span.end - span.start, 6);
    }
}
