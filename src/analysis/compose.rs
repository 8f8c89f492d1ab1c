//! Composing a variant as a sequence of line ids, recording where each audited region went.
//!
//! The walk is the preprocessor's ([`crate::preprocess::compose::walk`]) with another sink:
//! every output line is an id (equal ids ⟺ equal line text, so equal id sequences ⟺ equal
//! composed text), and the output range of each region found by the static analysis is
//! recorded.

use std::collections::HashMap;
use std::ops::Range;

use crate::preprocess::compose::{ModuleGraph, Sink, walk};
use crate::preprocess::tree::Node;
use crate::shader::Pass;

/// Every line of every module, interned: two lines have the same id iff their text is equal.
pub(crate) struct LineIds {
    /// For each module, the id of each of its lines.
    pub per_module: Vec<Vec<u32>>,
}

impl LineIds {
    /// Interns every line of the library.
    pub fn new(graph: &ModuleGraph<'_>) -> LineIds {
        let mut index: HashMap<&str, u32> = HashMap::new();
        let per_module = graph
            .modules
            .iter()
            .map(|m| {
                let text = graph.files.text(m.file);
                m.lines
                    .iter()
                    .zip(&m.comment_only)
                    .map(|(r, &comment_only)| {
                        // Blank and comment-only lines are no code: they never tell variants apart.
                        if comment_only {
                            return NO_CODE;
                        }
                        let line = &text[r.start as usize..r.end as usize];
                        let next = index.len() as u32;
                        *index.entry(line).or_insert(next)
                    })
                    .collect()
            })
            .collect();
        LineIds { per_module }
    }
}

/// The id of a blank or comment-only line, which composition leaves out (as the lean text of
/// [`crate::Library::wgsl`] does).
pub(crate) const NO_CODE: u32 = u32::MAX;

/// The identity of a parsed node (its address; nodes do not move while a library lives).
pub(crate) fn node_key(node: &Node) -> usize {
    node as *const Node as usize
}

/// Composes variants of one pass into line ids.
pub(crate) struct IdComposer<'a> {
    /// The library's modules.
    pub graph: &'a ModuleGraph<'a>,
    /// Interned lines.
    pub ids: &'a LineIds,
    /// Region root nodes (by [`node_key`]) and their slot index.
    pub regions: &'a HashMap<usize, usize>,
    /// Number of slots (regions and constant runs).
    pub slots: usize,
}

/// One composed variant: its lines and, per region slot, its output range.
#[derive(Clone, Debug, Default)]
pub(crate) struct IdText {
    /// The composed lines.
    pub lines: Vec<u32>,
    /// `(start, end)` in `lines` for each region slot; unused for constant slots.
    pub spans: Vec<(u32, u32)>,
}

impl IdComposer<'_> {
    /// Composes `pass` with `choice` (one option per set).
    pub fn compose(&self, pass: &Pass, choice: &[u16]) -> IdText {
        let keywords = choice
            .iter()
            .zip(&pass.sets)
            .filter_map(|(&o, s)| s.options[o as usize].as_deref());
        let defines: HashMap<Box<str>, i64> = pass
            .defs(keywords)
            .into_iter()
            .map(|(name, value)| (Box::from(name), value.as_i64()))
            .collect();
        let mut sink = IdSink {
            c: self,
            out: IdText {
                lines: Vec::with_capacity(1024),
                spans: vec![(0, 0); self.slots],
            },
        };
        walk(self.graph, pass.module, &pass.body, defines, &mut sink);
        sink.out
    }
}

/// Appends line ids and records the output range of each region.
struct IdSink<'c, 'a> {
    c: &'c IdComposer<'a>,
    out: IdText,
}

impl Sink for IdSink<'_, '_> {
    fn text(&mut self, module: usize, run: &Range<u32>) {
        let ids = &self.c.ids.per_module[module];
        self.out.lines.extend(
            ids[run.start as usize..run.end as usize]
                .iter()
                .copied()
                .filter(|&id| id != NO_CODE),
        );
    }

    fn begin(&mut self, node: &Node) -> Option<usize> {
        let slot = *self.c.regions.get(&node_key(node))?;
        let here = self.out.lines.len() as u32;
        self.out.spans[slot] = (here, here);
        Some(slot)
    }

    fn end(&mut self, slot: usize) {
        self.out.spans[slot].1 = self.out.lines.len() as u32;
    }
}
