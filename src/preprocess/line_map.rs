//! Mapping byte offsets of composed WGSL back to the original module files.

use crate::diagnostic::{FileId, Span};

/// For each line of composed output: where it starts in the output and where it came from.
///
/// Lines are copied verbatim, so an offset inside an output line maps to the same column of
/// the original line.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LineMap {
    /// (output byte offset, source file, source byte offset) per output line, ascending.
    entries: Vec<(u32, FileId, u32)>,
}

impl LineMap {
    /// Records that the output line starting at `out` is a copy of `file` from byte `src`.
    pub fn push(&mut self, out: usize, file: FileId, src: usize) {
        self.entries.push((out as u32, file, src as u32));
    }

    /// Number of mapped lines.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Where output line `line` came from: its file and the byte its copy starts at.
    pub(crate) fn line_source(&self, line: usize) -> Option<(FileId, usize)> {
        self.entries
            .get(line)
            .map(|&(_, file, src)| (file, src as usize))
    }

    /// Whether no line is mapped.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The original location of output bytes `start..end` (clipped to the start's line).
    pub fn to_original(&self, start: usize, end: usize, output: &str) -> Option<Span> {
        let i = self
            .entries
            .partition_point(|e| e.0 as usize <= start)
            .checked_sub(1)?;
        let (out, file, src) = self.entries[i];
        let line_end = output[out as usize..]
            .find('\n')
            .map_or(output.len(), |n| out as usize + n);
        // Past the line's `\n` (only at the end of the output): the end of the original
        // line, not into its line break (which may be CR LF or a multi-byte NEL/LS/PS).
        let delta = (start - out as usize).min(line_end - out as usize);
        let len = end.clamp(start, line_end.max(start + 1)) - start;
        let begin = src as usize + delta;
        Some(Span::new(file, begin..begin + len.max(1)))
    }
}
